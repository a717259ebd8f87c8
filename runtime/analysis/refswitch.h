/*
 * refswitch: the switches of the reference solution (reference.c) in
 * extended precision: the modes at the start, each crossing of a switch
 * function located inside an accepted step, the flips, and their record.
 * The modes are the twin's u[nu + k] (eomc_model.h), which the caller
 * owns and hands over; the motion is the caller's too (RefSwMotion): this
 * knows no step and no model function.  Not installed.
 */
#ifndef EOMC_REFSWITCH_H
#define EOMC_REFSWITCH_H

#include "eomc_model.h"
#include "step/stepevents.h" /* (when a switch chatters) */

typedef struct RefSwMotion {
    void *ctx;
    /* the state at t of the step in hand, which starts at t0, by a step
     * of its own from there (reference.c's side step); 0, or -1 when it
     * cannot be made */
    int (*state)(void *ctx, eomc_ext t0, eomc_ext t, eomc_ext *x);
    /* x' at (t, x) in the modes as they are; 0 or -1 */
    int (*rate)(void *ctx, eomc_ext t, const eomc_ext *x, eomc_ext *f);
    /* the switch functions s [nmode] at (t, x) in the modes as they are */
    void (*functions)(void *ctx, eomc_ext t, const eomc_ext *x, eomc_ext *s);
    /* Dry friction (NULL members: none).  held: whether mode k is a stick
     * switch, which no sign sets; settle: the items' modes at a state
     * (t, x) alone, after the signs (0, or -1 where none follow the
     * motion); flip: mode k's flip to on at (t, x) in a solution, x's
     * speed set to 0 where an item sticks (the modes it sets with it are
     * the caller's to find); 0 or -1.  friction: whether mode k is a
     * slip or stick switch (flipped at an instant after the contacts'). */
    int (*held)(void *ctx, int k);
    int (*friction)(void *ctx, int k);
    int (*settle)(void *ctx, eomc_ext t, const eomc_ext *x);
    int (*flip)(void *ctx, int k, int on, eomc_ext t, eomc_ext *x);
} RefSwMotion;

typedef struct RefSwitches RefSwitches;

/* For nmode switches of a state of N components, modes mode [nmode]
 * (1 or 0), over the time span [t0, t_end]; NULL when memory runs out. */
RefSwitches *refsw_alloc(int nmode, int N, eomc_ext *mode, RefSwMotion mo, eomc_ext t0,
                         eomc_ext t_end);
void refsw_free(RefSwitches *w);

/* The modes of the state (t, x) alone, from the signs of its switch
 * functions (0: mode 0), as the doubles take them outside a run; dry
 * friction's by motion.settle.  0, or -1 where friction's cannot be
 * decided. */
int refsw_signs(RefSwitches *w, eomc_ext t, const eomc_ext *x);

/* The modes at the start (t0, x0), as a run sets them: the sign of each
 * s, where it is 0 the side the motion leaves to; the record emptied.
 * 0; -1 where the motion cannot be computed; -2 where neither mode leaves
 * a kink the start is on (the run stops there too), switch *bad. */
int refsw_start(RefSwitches *w, const eomc_ext *x0, int *bad);

/* After an accepted step from (t0, x0) with rate f0 to (t1, x1), f1 (in
 * the modes held; motion.state steps from (t0, x0)): 1 when a switch
 * function crossed 0 in (t0, t1], the earliest crossing into *t_hit (to
 * a few units of rounding of t), its state there into x_hit; 0 when
 * none did; -1 when the motion cannot be computed. */
int refsw_check(RefSwitches *w, eomc_ext t0, const eomc_ext *x0, const eomc_ext *f0,
                eomc_ext t1, const eomc_ext *x1, const eomc_ext *f1, eomc_ext *t_hit,
                eomc_ext *x_hit);

/* The flips at t_hit, the state x there (refsw_check's): every switch
 * located there, and every other whose s is past 0 there (kinks at one
 * instant), each recorded with the sensitivity of its time to the state
 * (sc [N] the components' scales for the differences); an item of dry
 * friction that sticks there (motion.flip) has its speed in x set to 0
 * and its stick switch recorded with its slip's sensitivities.  0; -1
 * when the motion cannot be computed; -2 when a switch chatters
 * (STEPEV_CHATTER_FLIPS quick flips in a row, as the run stops), switch *bad. */
int refsw_flip(RefSwitches *w, eomc_ext t_hit, eomc_ext *x, const eomc_ext *sc, int *bad);
/* After a jump of the inputs at t (a sampled controller's sample), the
 * state x there: the switches whose functions the jump moved past 0 flip
 * at t, recorded as refsw_flip records them, in the order the runs flip
 * them (stepevents.c's settle).  Its returns. */
int refsw_jump(RefSwitches *w, eomc_ext t, eomc_ext *x, const eomc_ext *sc, int *bad);

/* The record since refsw_start: n flips, each's time, switch and [N]
 * sensitivities |ds/dx_i| / |ds/dt| (how far the crossing moves in time
 * per unit error of component i; INFINITY where s is tangent), ... */
long refsw_count(const RefSwitches *w);
const double *refsw_times(const RefSwitches *w);
const int *refsw_which(const RefSwitches *w);
const double *refsw_sens(const RefSwitches *w);
/* ... and [N] the state as its instant arrived, and its rate there in
 * the modes before it (the same for flips at one instant). */
const double *refsw_states(const RefSwitches *w);
const double *refsw_rates(const RefSwitches *w);

#endif
