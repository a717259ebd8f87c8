/*
 * evolve.h: the step layer (evolve.c), for the driver above it
 * (integrate.c): one accepted step at a time, as GSL's evolve takes them,
 * with the checks after each and the scene's events.  The steps' state is
 * evolve.c's alone (struct eomc_evolve, the same as eomc_sim_step's): the
 * driver sees what each step covered and keeps its own rows.  Not
 * installed, and nothing of it leaves the library (runtime/meson.build).
 */
#ifndef EOMC_EVOLVE_H
#define EOMC_EVOLVE_H

#include "eomc.h"

/* evolve_step's and evolve_stop's status when a callback's nonzero status
 * stopped the run (evolve_stopped).  Every status from it down to -1099 is the step
 * layer's own; evolve_error says what the others mean. */
enum { EVOLVE_STOPPED = -1000 };
/* A continuous controller failed in a right-hand side (sim_control_failed):
 * no smaller step can help; evolve_error returns its status. */
enum { EVOLVE_CONTROL = -1006 };
/* A side step (a state computed by a step of its own) is split in at
 * most this many pieces. */
enum { EVOLVE_SIDE_PIECES = 64 };

enum { EVOLVE_NONE, EVOLVE_STOP, EVOLVE_SET };

/* What evolve_step did, also when it failed after the step was accepted
 * (the steps collapsed or ground): that step's end stands. */
typedef struct EvolveStep {
    int taken;                    /* a step was accepted: t0 .. t1 */
    double t0, t1;
    const double *x0, *f0;        /* the state and x' at t0 and t1 */
    const double *x1, *f1;
    int restarted;                /* a pending reset (or a controller's sample) was
                                   * applied first: the step started from the state
                                   * it set (with the inputs it set) */
    int sampled;                  /* the step ended at a controller's sample: the
                                   * next starts afresh, with the inputs it sets */
    int ev, fired;                /* EVOLVE_... and the event that ended the step */
    double reached;               /* no step taken, but the motion is known up to
                                   * this time (the failure is past it), or NAN */
    const double *xr, *fr;        /* ... the state and x' there */
    const struct Taylor *series;  /* Taylor's method (set for every step, taken or
                                   * not): the step's series, valid on t0 .. t1
                                   * until the next step (taylor.h: taylor_eval),
                                   * its dense output; else NULL */
} EvolveStep;

/* The steps of s from x [2nq] at o->t0, into *e (eomc_evolve_free it
 * either way): the options checked, st zeroed and started, x the state
 * the steps advance in place; o, x and st are kept, not copied.  EOMC_OK
 * or a status with its message. */
int evolve_open(eomc_evolve **e, eomc_sim *s, const eomc_run_opts *o, double *x,
                eomc_stats *st);
/* The equations at t0 (with the derivative when steps follow): EOMC_OK or
 * a status with its message. */
int evolve_start(eomc_evolve *e, int derivative);
/* After the state at t0 was written: what the watches start from. */
int evolve_watch(eomc_evolve *e);
/* Before the first step: the fixed steps of the span (st->h_used). */
void evolve_begin(eomc_evolve *e);
/* Whether a step is left to take: before t_end, or a reset to apply. */
int evolve_more(const eomc_evolve *e);
/* One accepted step into *tk: GSL_SUCCESS, or a status for evolve_error
 * (EVOLVE_STOPPED, evolve_stopped). */
int evolve_step(eomc_evolve *e, EvolveStep *tk);
/* The time reached, and x' at the state there. */
double evolve_time(const eomc_evolve *e);
/* Taylor's method: the series the next step will ask for starts at
 * (evolve_time, *x) unless a reset or a sample comes first, or the step
 * is a side step's; its Taylor (taylor.h, for taylor_lanes_fill), NULL
 * for another method or where a reset or a sample comes first. */
struct Taylor *evolve_taylor(eomc_evolve *e, const double **x);
const double *evolve_rate(const eomc_evolve *e);
/* The state at t into x by a step of its own from (tk, xk, fk): 1, 2, 4,
 * ... pieces until each passes the step control; GSL_SUCCESS or a
 * failure status, without a message. */
int evolve_side(eomc_evolve *e, double tk, const double *xk, const double *fk, double t,
                double *x);
/* A callback of the driver's (a row's) returned status at (t, x): the run
 * stops there, as when on_event stops it, with x the state the caller gets
 * back (kept, not copied).  Returns EVOLVE_STOPPED. */
int evolve_stop(eomc_evolve *e, int status, double t, const double *x);
/* After EVOLVE_STOPPED: the callback's status, the time and the state it
 * was called with (valid until the next step, or as long as the caller
 * keeps the state it gave evolve_stop). */
int evolve_stopped(const eomc_evolve *e, double *t, const double **x);
/* The message of a stepping status other than success; returns the
 * EOMC_ status. */
int evolve_error(eomc_evolve *e, int status);

#endif
