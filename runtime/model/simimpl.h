/*
 * simimpl.h: the simulator's internal API, for the layers above sim.c
 * (the steps evolve.c and stepevents.c, reference.c, linearize.c,
 * rows.c).  Not installed, and nothing of it leaves the library (built
 * with -fvisibility=hidden, runtime/meson.build).  struct eomc_sim is sim.c's
 * alone: the layers above see it through eomc.h and these functions, and
 * keep their own work arrays.
 */
#ifndef EOMC_SIMIMPL_H
#define EOMC_SIMIMPL_H

#include "eomc.h"

#include <stddef.h>

/* A zeroed array of n doubles (at least one), or NULL. */
double *sim_zeros(size_t n);
/* Whether every x[i] is finite. */
int sim_all_finite(const double *x, int n);
/* Seconds of the process's CPU time (cpu), or of a monotonic wall clock. */
double sim_seconds(int cpu);
/* "t = T: CAUSE; state: q1 = .., q1' = .." (each speed by its name);
 * returns EOMC_ENUMERIC. */
int sim_numeric_error(eomc_sim *s, double t, const double *q, const double *v,
                      const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* q' = W(q) v into qd [nq] (v itself when the speeds are the rates). */
void sim_qdot(const eomc_sim *s, const double *q, const double *v, double *qd);
/* q'' = dq'/dq q' + dq'/dv v' into qdd [nq] at x [nx] with x' = f [nx]
 * (qdot_jacobian); 0, or -1 when the model has no qdot_jacobian.  For a
 * model whose speeds are not the rates (dense output). */
int sim_qddot(eomc_sim *s, const double *x, const double *f, double *qdd);
/* The speeds v [nv] whose q' = W(q) v is nearest qd [nq] (least squares:
 * W^T W v = W^T qd, W from qdot_jacobian); 0, or -1 without
 * qdot_jacobian or where W^T W is not positive definite.  For a model
 * whose speeds are not the rates (dense output). */
int sim_speeds_of(eomc_sim *s, const double *q, const double *qd, double *v);
/* dense 1: every constrained solve forms M and solves the KKT system (or
 * eliminates), unit loads or not (kkt_set_dense); 0: the cheapest again.
 * For the analyses, which read exact zeros in q'' (linearize.c). */
void sim_set_dense(eomc_sim *s, int dense);
/* The message of a usage error; returns EOMC_EUSAGE. */
int sim_usage_error(eomc_sim *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* The usage error of `what` (a method, --linearize) on a model built
 * without its Jacobian; returns EOMC_EUSAGE. */
int sim_no_jacobian(eomc_sim *s, const char *what);
/* The inputs u at (t, q, v) [nu] (held ones constant, a controller's
 * its outputs: a sampled one's of its last sample, a continuous one's of
 * its call here; without a state, q NULL, the inputs' own values), valid
 * until the next call that evaluates the model. */
const double *sim_inputs_at(eomc_sim *s, double t, const double *q, const double *v);
/* The controller's period (eomc_sim_set_controller: 0 continuous), or -1
 * without one. */
double sim_control_period(const eomc_sim *s);
/* A sampled controller's samples are t0 + k period before t_end; one
 * within this share of the period of t_end is t_end's, where none is taken
 * (as an output time that close is t_end: eomc_run_rows). */
#define SIM_SAMPLE_AT_END_REL 1e-9
/* The inputs the controller sets [nu] (1: set). */
const unsigned char *sim_control_drives(const eomc_sim *s);
/* The controller's call at (t, x) [nx], u [nu] the inputs' own values in,
 * with those it sets out, the simulator's state untouched (the
 * reference's samples): EOMC_OK, its status, or EOMC_ENUMERIC for a value
 * that is not finite (the message set either way). */
int sim_control_call(eomc_sim *s, double t, const double *x, double *u);
/* A run's start: no sample taken yet, no failure. */
void sim_control_start(eomc_sim *s);
/* The sampled controller's call at (t, x) [nx], its outputs held from
 * here: EOMC_OK, the controller's nonzero status, or EOMC_ENUMERIC where
 * it set an input to a value that is not finite (the message says which,
 * and when). */
int sim_sample(eomc_sim *s, double t, const double *x);
/* A continuous controller's failure in an evaluation of the model (its
 * status, the message set; the evaluation failed, and every next one
 * fails until sim_control_start), or EOMC_OK. */
int sim_control_failed(const eomc_sim *s);
/* The switch functions s [nmode] at (t, q, v) in the modes as they are
 * (eomc_model.h's switches). */
void sim_switches(eomc_sim *s, double t, const double *q, const double *v, double *sw);
/* Mode k: 1 (its switch function > 0) or 0; set to on. */
int sim_mode(const eomc_sim *s, int k);
void sim_set_mode(eomc_sim *s, int k, int on);
/* Every mode from the sign of its switch function at (t, q, v): 1 where
 * it is > 0, else 0 (exactly 0: 0 here; a run's start then looks at the
 * side the motion leaves to, evolve.c's start_modes).  Dry friction's
 * items at rest are stuck where they can be (friction.h's settle).
 * EOMC_OK, or the error where friction's modes cannot be decided. */
int sim_set_modes(eomc_sim *s, double t, const double *q, const double *v);
/* Whether mode k is dry friction's stick switch, which no switch
 * function of the model drives (sim_switches gives F - |phi| for it). */
int sim_mode_held(const eomc_sim *s, int k);
/* Mode k's flip to on at (t, x) in a run, its switch located there: set,
 * or dry friction's (friction.h's flip: an item whose speed crosses 0
 * sticks where it can, its speed in x set to 0; the modes it sets with
 * it, a group's, the caller finds by comparing).  EOMC_OK or the error. */
int sim_flip(eomc_sim *s, int k, int on, double t, double *x);
/* The run's span, for dry friction's look ahead (friction.h). */
void sim_span(eomc_sim *s, double span);
/* on = 1: a run keeps the modes (set at its start, flipped at its
 * switches) until on = 0; otherwise eomc_sim_accel, _energy, _outputs and
 * _invariant take the modes of the state they are given. */
void sim_modes_run(eomc_sim *s, int on);
/* The parameter array the generated functions take: eomc_sim_params'
 * [np] values, then the [nd] the model derives from them. */
const double *sim_p(const eomc_sim *s);
/* EOMC_STABILIZE_... as eomc_sim_stabilize set it. */
int sim_stabilize_method(const eomc_sim *s);
/* B = dx'/du [nx x nu] at (t, x), row-major, right after
 * eomc_sim_jacobian at the same (t, x) (M as it factored it); 0, or -1
 * when the constrained solve fails. */
int sim_input_jacobian(eomc_sim *s, double t, const double *x, double *B);
/* A constrained model's Newton start for a nonlinear constraint (kkt.h's
 * kkt_save_start): saved at a step's start, restored before each attempt;
 * no-ops without constraints. */
void sim_save_start(eomc_sim *s);
void sim_restore_start(eomc_sim *s);
/* After a failed eomc_sim_accel: the constraint whose row vanished and its
 * largest entry's fraction (kkt_vanished), or -1 (and without
 * constraints). */
int sim_vanished(const eomc_sim *s, double *fraction);
/* Baumgarte's weights of constraint c as the stabilization set them (0
 * when off): its f gets *wv vel + *wp pos (kkt.c). */
void sim_baumgarte(const eomc_sim *s, int c, double *wv, double *wp);
/* Whether the model has a holonomic or first-order constraint. */
int sim_has_levels(const eomc_sim *s);
/* The rows of B = df/dq'' at (t, x) into B [nc*nv]; -1 when x is not
 * finite or the accelerations (needed when f is not affine) fail. */
int sim_constraint_rows(eomc_sim *s, double t, const double *x, double *B);
/* The constraint rows the solves use (model/depend.c): chosen where the
 * model is first solved or projected, or here at (t, q, v) if that has
 * not happened yet (again after the parameters changed); EOMC_OK, or the
 * error (an eliminating model whose rows are dependent there). */
int sim_choose_rows(eomc_sim *s, double t, const double *q, const double *v);
/* The same, chosen again at (t, q, v) whatever was chosen before: where a
 * run starts (eomc_sim_integrate), so that each run's are its own start's. */
int sim_start_rows(eomc_sim *s, double t, const double *q, const double *v);
/* The rows left out of the solves as dependent on the others, drop [nc]
 * (1: left out, its multiplier 0), or NULL when none are (or they are not
 * chosen yet). */
const unsigned char *sim_dropped_rows(const eomc_sim *s);
/* Those rows and the ones they depend on, "loop_z, dependent on loop_x,
 * loop_y"; "" when none are left out. */
const char *sim_dropped_note(const eomc_sim *s);
/* After a step: EOMC_OK while every row left out follows the kept ones
 * (depend_watch), else EOMC_ENUMERIC with the message naming it. */
int sim_dropped_watch(eomc_sim *s, double t, const double *q, const double *v);
/* The largest |g|, |g'| or |phi| at (t, q, v), 0 without such
 * constraints. */
double sim_level_residual(eomc_sim *s, double t, const double *q, const double *v);
/* EOMC_OK when (q, v) is on its holonomic and velocity-level constraints
 * (eomc_sim_inconsistency at most EOMC_INCONSISTENT), else EOMC_ENUMERIC
 * with the message "t = T: WHAT: the state is off 2 constraints, worst
 * first: c1 (velocities: its residual is 1 of the size of its terms), c2
 * (positions: 0.3); state: ...", every one it violates. */
int sim_off_constraints(eomc_sim *s, double t, const double *q, const double *v,
                        const char *what);
/* The condition number of the linear system whose solution is q'' at
 * (t, q, v): the mass matrix balanced by its diagonal (which makes it free
 * of the coordinates' units), or the scaled KKT or elimination matrix;
 * NAN when it cannot be had (the solve failed). */
double sim_condition(eomc_sim *s, double t, const double *q, const double *v);
/* What the nearly singular direction of the system sim_condition last
 * factored mixes: "the mass matrix (coordinates th1, th2)"; valid until
 * the next call. */
const char *sim_condition_what(eomc_sim *s);
/* The smallest pivot of the solves for q'' since the last call, balanced
 * as sim_condition balances (1 when none): its inverse is about a lower
 * bound on their condition, had for free from their factorizations. */
double sim_take_pivot(eomc_sim *s);
/* The largest condition of the stuck friction rows' system where an item
 * let go since the last call (friction.h's fric_condition; 0 when none),
 * its time into t and what into what (valid until the next let-go).  A let
 * go that rounding placed (rows parting by little more than it) shows
 * here, after the modes that had it are gone. */
double sim_take_flip_condition(eomc_sim *s, double *t, const char **what);

#endif
