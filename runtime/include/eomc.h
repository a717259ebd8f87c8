/*
 * eomc.h: the runtime library (libeomcrt) that generated models link.
 *
 * An eomc_sim holds one model, its parameter values and inputs, and every
 * work array the right-hand side needs: after eomc_sim_alloc, evaluating
 * accelerations, Jacobians or a whole integration allocates nothing per
 * step.  The API follows GSL's object_verb style: alloc, use, free; every
 * function that can fail returns an EOMC_ status and leaves a message in
 * eomc_sim_error().
 *
 *     eomc_sim *sim = eomc_sim_alloc(&pendulum_model);
 *     eomc_sim_set(sim, "l", 2.0);
 *     double q[1] = {0.5}, v[1] = {0}, a[1];
 *     if (eomc_sim_accel(sim, 0.0, q, v, a) != EOMC_OK)
 *         fprintf(stderr, "%s\n", eomc_sim_error(sim));
 *     eomc_sim_free(sim);
 *
 * The first-order state is x = (q, v) of length nx = nq + nv, the
 * coordinates and then the speeds (eomc_nv, eomc_nx below); its derivative
 * is x' = (q', v'): q' = v and v' = q'' for a model whose speeds are its
 * coordinates' rates (model->nv = 0), q' = W(q) v (model->qdot) and v' the
 * speeds' rates otherwise (a free or ball joint's angular velocity).  Below,
 * "q''" and "the accelerations" are v' [nv], the mass matrix is nv x nv,
 * and a "velocity" is a speed.
 *
 * GSL's error handler is the program's: libeomcrt never sets it, and checks
 * every status where it arises.  Its own solves never reach the handler
 * (M is factored by GSL's pivoted Cholesky, which only computes; every
 * other matrix is tested for singularity before it is solved with).  Two
 * GSL routines it calls can reach it on bad data: the iteration matrix
 * solve of the implicit methods (bsimp, rk1imp, rk2imp, rk4imp, msbdf),
 * when I - h J is exactly singular, and the QR iteration of
 * eomc_sim_eigenvalues, when it does not converge.  Under GSL's default
 * handler these abort the program, as GSL does everywhere; a program that
 * wants eomc's status and message instead calls gsl_set_error_handler_off()
 * first, as eomc_main does for the time it runs.
 */
#ifndef EOMC_H
#define EOMC_H

#include <stdio.h>

#include "eomc_model.h"

/* What this header declares is the library's whole interface: libeomcrt is
 * built with -fvisibility=hidden and keeps its other symbols local
 * (runtime/meson.build), so a program's own la_dot or sim_zeros cannot
 * clash with its internals. */
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

enum {
    EOMC_OK = 0,
    EOMC_EUSAGE = 2,   /* bad name or value from the user: exit status 2 */
    EOMC_ENUMERIC = 3, /* numerical failure at run time: exit status 3 */
};

typedef struct eomc_sim eomc_sim;

/* The number of speeds, nv: the model's nv, or nq when its speeds are its
 * coordinates' rates (model->nv = 0); and the state's size nq + nv. */
static inline int
eomc_nv(const eomc_model *m)
{
    return m->nv > 0 ? m->nv : m->nq;
}
static inline int
eomc_nx(const eomc_model *m)
{
    return m->nq + eomc_nv(m);
}

/* NULL if the model's ABI does not match this runtime or memory runs out. */
eomc_sim *eomc_sim_alloc(const eomc_model *m);
void eomc_sim_free(eomc_sim *s);
const eomc_model *eomc_sim_model(const eomc_sim *s);

/* A model's sizes and names by kind, for a caller that does not read
 * eomc_model's layout (the Python package, through ctypes): kind "q"
 * (coordinates), "v" (the speeds' names: model->nv of them, none when the
 * speeds are the coordinates' rates, which are named q'), "p"
 * (parameters), "u" (inputs), "c" (constraints), "out" (the scene's
 * outputs), "event" or "place" (eomc_sim_place's).  The count, or -1 for another kind;
 * the k-th name, or NULL out of range.  eomc_model_text: "name", "spec",
 * "form", "scene", "method" or "invariant" (NULL: none, or another). */
int eomc_model_count(const eomc_model *m, const char *kind);
const char *eomc_model_name(const eomc_model *m, const char *kind, int k);
const char *eomc_model_text(const eomc_model *m, const char *what);

/* Set a parameter, or an input, by name.  An input set here is held at
 * this constant value from then on.  EOMC_EUSAGE for an unknown name. */
int eomc_sim_set(eomc_sim *s, const char *name, double value);
/* Whether the parameters make the model physical (model->check: no
 * negative mass, inertias positive definite and of some distribution of
 * mass): EOMC_OK, or EOMC_EUSAGE with a message naming the body or
 * particle and the parameters with their values.  eomc_run_check calls
 * it. */
int eomc_sim_check(eomc_sim *s);
/* Current parameter values [np]. */
const double *eomc_sim_params(const eomc_sim *s);
/* Input values at t [nu] (constants or the model's signals; a sampled
 * controller's held outputs, not a continuous one's, which need a state). */
void eomc_sim_inputs(eomc_sim *s, double t, double *u);

/* A controller in the loop: fn(ctx, t, q, v, u) writes the inputs it sets
 * into u [nu], which holds the inputs' own values at t on entry (the
 * constants set, the model's signals), and returns 0, or a nonzero
 * status that stops the run with it, as on_event's does (the rows so far
 * stand).  drives [nu] marks the inputs it sets (NULL: all); an input it
 * sets to a value that is not finite stops the run (EOMC_ENUMERIC, the
 * message naming the input and the time).
 *  - period > 0: a sampled controller, as a digital one: called at
 *    t0 + k period (k = 0, 1, ..., before t_end) with the state there,
 *    its outputs held until the next sample (a zero-order hold).  The
 *    steps end at every sample, as at an event, so the error control,
 *    the events and the reference solution (which calls fn at the same
 *    instants, with its own state rounded to doubles) stay exact: fn must
 *    be a function of (t, q, v) alone, with no memory of its own calls.
 *  - period = 0: a continuous controller, u(t, q, v), called inside every
 *    evaluation of the model at a state (each right-hand side); not with
 *    Taylor's method (it has no series) nor the reference (a continuous
 *    law is the model's: write it in the spec).
 * The analyses (eomc_sim_jacobian, linearize, equilibrium) are of the open
 * loop, the inputs as the controller leaves them.  fn NULL removes it;
 * EOMC_EUSAGE for a period that is negative or not finite. */
typedef int (*eomc_controller_fn)(void *ctx, double t, const double *q, const double *v,
                                  double *u);
int eomc_sim_set_controller(eomc_sim *s, eomc_controller_fn fn, void *ctx, double period,
                            const unsigned char *drives);

/* The model's initial state for the current parameters. */
void eomc_sim_initial(const eomc_sim *s, double *q, double *v);

/* q'' at (t, q, v): solves M q'' = -h.  EOMC_ENUMERIC if M is singular or
 * not positive definite, or q'' is not finite. */
int eomc_sim_accel(eomc_sim *s, double t, const double *q, const double *v,
                   double *a);
/* The mass matrix M [nv*nv] and the bias h [nv] at (t, q, v): the motion
 * is M q'' + h = 0 (with constraints, M q'' + h + B^T lambda = 0), h all
 * but M q'' (velocity terms, gravity and the other forces, the inputs' as
 * they are at that state).  EOMC_ENUMERIC where they are not finite. */
int eomc_sim_mass_bias(eomc_sim *s, double t, const double *q, const double *v, double *M,
                       double *h);
/* The derivatives of the accelerations at any state (t, q, v), exact
 * (eomc_sim_jacobian's rows of v', with a constrained model's solve
 * carried through): dadq [nv*nq] = dv'/dq, dadv [nv*nv] = dv'/dv, dadu
 * [nv*nu] = dv'/du (each NULL: not wanted), row-major.  The model built
 * with its Jacobian (else EOMC_EUSAGE, saying how to rebuild it). */
int eomc_sim_accel_derivatives(eomc_sim *s, double t, const double *q, const double *v,
                               double *dadq, double *dadv, double *dadu);
/* Forward kinematics.  A model's places (eomc_model.h's places) are its
 * bodies (each at its centre of mass, in its axes) and particles, then
 * every frame and point its spec names (a frame at its origin).
 * eomc_model_place: the index of the place so named, or -1; and into
 * *axes (unless NULL) 1 if it has axes (a body or frame whose orientation
 * the model gives), else 0.
 * eomc_sim_place: place k's position pos [3] and rotation R [9]
 * (row-major: its axes' world components are R's columns) at (t, q); each
 * NULL: not wanted.  eomc_sim_place_jacobian: its velocity Jacobian Jv
 * [3 nv] and angular velocity Jacobian Jw [3 nv] (row-major, world
 * components; each NULL: not wanted), so that its velocity is Jv v and
 * its angular velocity Jw v, leaving out what time alone moves (a driven
 * frame); exact (the generated velocities at unit speeds), at the cost of
 * nv evaluations of every place's velocity.  EOMC_EUSAGE for k out of
 * range, or for R or Jw of a particle or point, or of a body the model
 * gives no orientation of; EOMC_ENUMERIC where a value is not finite. */
int eomc_model_place(const eomc_model *m, const char *name, int *axes);
int eomc_sim_place(eomc_sim *s, int k, double t, const double *q, double *pos, double *R);
int eomc_sim_place_jacobian(eomc_sim *s, int k, double t, const double *q, double *Jv,
                            double *Jw);
/* Constrained models (model->nc > 0): the multipliers lambda [nc] of the
 * last eomc_sim_accel (constraint forces: the motion is E + B^T lambda =
 * 0), or NULL for a model without constraints. */
const double *eomc_sim_multipliers(const eomc_sim *s);
/* Each constraint's residual at its own level [nc]: g (holonomic), phi
 * (first order) or f at the accelerations (second order). */
int eomc_sim_residuals(eomc_sim *s, double t, const double *q, const double *v,
                       double *res);
/* How far (q, v) is from its holonomic and velocity-level constraints,
 * whatever the model's units: the largest |g|, |g'| or |phi| relative to
 * the magnitude of its terms (0 when all hold exactly, near rounding when
 * they hold to it, 1 when one is nowhere near).  *worst gets that
 * constraint's index (-1 when the model has no such constraint) and
 * *level 0 when it is its position g, 1 when its g' or phi. */
double eomc_sim_inconsistency(eomc_sim *s, double t, const double *q, const double *v,
                              int *worst, int *level);
/* Each constraint's inconsistency as eomc_sim_inconsistency measures it,
 * into e [nc]: for a holonomic one the larger of its two, at g and at g',
 * for a first-order one its phi's, 0 for a second-order one (nothing of it
 * lies below acceleration level); level [nc] (unless NULL) gets which (0:
 * g, 1: g' or phi).  Returns the largest, as eomc_sim_inconsistency does. */
double eomc_sim_inconsistencies(eomc_sim *s, double t, const double *q, const double *v,
                                double *e, int *level);
/* The inconsistency above which a state is said to be off its
 * constraints: far above the rounding of a state that satisfies them,
 * far below any violation a user would have meant. */
#define EOMC_INCONSISTENT 1e-8

/* The condition number of the linear system whose solution is q'' at
 * (t, q, v): the mass matrix balanced by its diagonal (free of the
 * coordinates' units), or the scaled KKT or elimination matrix of a
 * constrained model; estimated in the 1-norm from a factorization (Hager
 * and Higham).  The solve may lose about log10 of it of the 16 digits of
 * q''.  NAN when the solve fails there.  *what (unless NULL) names the
 * system and what its nearly singular direction mixes: "the mass matrix
 * (coordinates th1, th2)"; it stays valid until the next call. */
double eomc_sim_condition(eomc_sim *s, double t, const double *q, const double *v,
                          const char **what);

/* Drift control for the holonomic and first-order constraints, which
 * the solve enforces only at acceleration level:
 *   EOMC_STABILIZE_BAUMGARTE  solve g'' + 2 alpha g' + beta^2 g = 0 and
 *                             phi' + alpha phi = 0 instead (rates in 1/time);
 *   EOMC_STABILIZE_PROJECT    after every step, eomc_sim_project.
 * EOMC_EUSAGE when the model has no such constraint or alpha, beta are
 * negative or not finite. */
enum { EOMC_STABILIZE_NONE, EOMC_STABILIZE_BAUMGARTE, EOMC_STABILIZE_PROJECT };
int eomc_sim_stabilize(eomc_sim *s, int method, double alpha, double beta);
/* Move (q, v) onto the constraints, in place: q onto every holonomic
 * g = 0, then v onto every g' = 0 and phi = 0, each by Gauss-Newton for
 * the least change in the mass matrix's metric (a velocity it leaves at
 * the rounding of those it started from is 0).  A no-op without such
 * constraints; EOMC_ENUMERIC when it cannot converge. */
int eomc_sim_project(eomc_sim *s, double t, double *q, double *v);
/* The same keeping what hold [nx] marks as it is (hold[i]: q_i,
 * hold[nq + k]: speed k): the rest moves, for the least change in the mass
 * matrix's metric on it.  With speeds that are not the coordinates' rates,
 * a speed moves the positions unless every coordinate it moves (a column
 * of W(q)) is held, and a held coordinate that a moving speed would move
 * is refused (EOMC_EUSAGE: a unit quaternion's four coordinates are held
 * together or not at all).  EOMC_ENUMERIC also when what is left free cannot
 * meet the constraints (the message says what was held). */
int eomc_sim_project_held(eomc_sim *s, double t, double *q, double *v,
                          const unsigned char *hold);

/* T and V at (t, q, v). */
void eomc_sim_energy(eomc_sim *s, double t, const double *q, const double *v,
                     double *T, double *V);
/* The model's conserved quantity (model->invariant_name: E = T + V, or
 * the energy function h) at (t, q, v); EOMC_EUSAGE when it conserves
 * none (the message says why). */
int eomc_sim_invariant(eomc_sim *s, double t, const double *q, const double *v,
                       double *h);
/* The scene's outputs [model->nout] at (t, q, v), with the accelerations
 * and multipliers of that state (solved here); EOMC_ENUMERIC when that
 * solve fails.  A no-op when the scene has none. */
int eomc_sim_outputs(eomc_sim *s, double t, const double *q, const double *v,
                     double *out);
/* The scene's event functions g [model->nevent] at (t, q, v). */
void eomc_sim_events(eomc_sim *s, double t, const double *q, const double *v, double *g);
/* Event k's reset at (t, x): x1 [nx] gets x with what the event sets
 * (x1 may be x). */
void eomc_sim_event_set(eomc_sim *s, int k, double t, const double *x, double *x1);
/* Whether input k is held constant (eomc_sim_set), and at which value. */
int eomc_sim_input_held(const eomc_sim *s, int k, double *value);
/* The Jacobian of x' = f(t, x), exact, from the generated residual
 * Jacobians: dv'/dx = -M^-1 dE/dx, and dq'/dx = [0, I] or, with speeds
 * that are not the rates, [dq'/dq, W(q)] (model->qdot_jacobian).  dfdx is
 * (nx x nx) row-major; dfdt [nx] includes the inputs' time derivatives.
 * Either may be NULL. */
int eomc_sim_jacobian(eomc_sim *s, double t, const double *x, double *dfdx,
                      double *dfdt);

/* ---- linearization and equilibria (linearize.c) ----
 * The state z is the tangent space's: one position component per speed
 * and the speeds (2 nq where the speeds are the rates).  A model whose
 * speeds are not its coordinates' rates (model->nv > 0) has, for each
 * unit quaternion e, the three components of the small rotation dtheta
 * in its body's axes, e = e0 (x) (1, dtheta/2), in place of its four
 * parameters; dtheta is measured from the motion through the state
 * (dtheta' = dw - w0 x dtheta), docs/cli.md. */

/* The size nl of the linearization's state: 2 nv (2 nq where the speeds
 * are the rates), or for a constrained model the independent components
 * of the elimination (a holonomic constraint removes its dependent
 * position and speed, a first-order one its dependent speed). */
int eomc_sim_linear_size(const eomc_sim *s);
/* Its k-th component: order 0, coordinate coord; 1, speed coord (the
 * coordinate's rate where the speeds are the rates); 2, the small
 * rotation about the axis of angular velocity speed coord (a unit
 * quaternion's).  coord = order = -1 where the kinematic equation is of
 * no form the runtime knows (then eomc_sim_linearize refuses). */
void eomc_sim_linear_state(const eomc_sim *s, int k, int *coord, int *order);
/* A = dz'/dz [nl x nl] and B = dz'/du [nl x nu] at (t, x) (x [nx], on
 * the constraints), exact from the generated Jacobians, row-major.
 * EOMC_ENUMERIC when x is off its holonomic or velocity-level constraints
 * (eomc_sim_inconsistency above EOMC_INCONSISTENT): the message names
 * every one it violates, worst first. */
int eomc_sim_linearize(eomc_sim *s, double t, const double *x, double *A, double *B);
/* A model with switched expressions (model->nmode > 0) is linearized in
 * the modes of the state itself (each from the sign of its switch
 * function there), as eomc_sim_accel takes them; an equilibrium's Newton
 * steps take each iterate's.  On a kink the two sides' A and B differ:
 * eomc_sim_kinks counts the switches whose function is 0 at (t, x) to the
 * rounding of its scale (what the rounding of t and x's values would
 * change it by; size [nx], or NULL, the magnitude each x_j is known to
 * where larger than |x_j|: an equilibrium's start, to whose scale Newton's
 * steps settle), marking each in on [nmode] (may be NULL; their names are
 * model->sw_names); -1 out of memory. */
int eomc_sim_kinks(eomc_sim *s, double t, const double *x, const double *size,
                   unsigned char *on);
/* The eigenvalues of A [nl x nl] (re + i im, unordered).  Those that rows
 * or columns of zeros isolate (a cyclic coordinate's) are exact, taken
 * out before the QR iteration. */
int eomc_sim_eigenvalues(eomc_sim *s, const double *A, int nl, double *re, double *im);
/* An equilibrium (q' = 0, q'' = 0) by Newton's method with the exact
 * Jacobian from x's coordinates: x [nx] becomes it (velocities 0);
 * *iterations counts the Newton steps.  Found only where q'' is 0 (each
 * q''_i within EOMC_ACCEL_ZERO of its scale at the start, or of what the
 * rounding of the coordinates found would change it by).  EOMC_ENUMERIC
 * when it does not converge, when it stops where q'' is not 0, and when
 * it runs away (its full steps not shrinking, each farther from the
 * start); EOMC_EUSAGE when the equilibria are not isolated points
 * (nonholonomic models).  The coordinates are left as found, not wrapped
 * (nothing says which are angles); a unit quaternion is stepped by
 * rotations and left of length 1. */
int eomc_sim_equilibrium(eomc_sim *s, double t, double *x, int *iterations);
/* How far q'' at (t, x) (on the constraints) is from 0, whatever the
 * units: the largest |q''_i| relative to sum_k |dq''_i/dz_k| |z_k| (z the
 * linearization's state), what q''_i would change by if every z_k moved
 * by its own size (a rotation's is 1).  0 where q'' is 0, at most
 * EOMC_ACCEL_ZERO where it is 0 to the rounding of z (an equilibrium, or a
 * steady motion); the speeds' rates v' [nv] into acc, that speed into
 * *worst.  NAN when q'' or its Jacobian
 * fails (the message says why). */
double eomc_sim_accel_residual(eomc_sim *s, double t, const double *x, double *acc,
                               int *worst);
/* q'' counts as 0 up to 1024 units of rounding (DBL_EPSILON) of that
 * scale: at the equilibria found from random starts on the specs of
 * specs/ and tests/sim/specs the most was 15, and the points where a
 * search stopped with q'' not 0 (a minimum of |q''|, or far out on a
 * runaway) were 1e8 units and more. */
#define EOMC_ACCEL_ZERO (1024 * 2.220446049250313e-16)

/* ---- sweeps over many machines ----
 * A sweep (--sweep, --sweep-file) runs on the threads of one machine; a
 * simulator built with `eomc build --mpi` also shares its runs among the
 * ranks of an MPI job through this hook (eomc_mpi.h sets it): rank and
 * size, and gather, which hands rank 0 every rank's text (their rows),
 * concatenated by rank with lens[r] the length of rank r's (*all and
 * *lens malloc'd there; elsewhere left NULL).  0, or -1 on failure. */
typedef struct eomc_parallel {
    int rank, size;
    int (*gather)(const char *mine, size_t len, char **all, size_t **lens);
} eomc_parallel;
void eomc_set_parallel(const eomc_parallel *p);

/* ---- integration ---- */

/* The integration methods by name, NULL-terminated (runtime/base/methods.def). */
extern const char *const eomc_methods[];
/* One line about a method, or NULL for an unknown name. */
const char *eomc_method_description(const char *name);
/* How a method takes steps: EOMC_STEPS_ADAPTIVE (multistep: only steps
 * of its own choosing), EOMC_STEPS_EMBEDDED (adaptive, or fixed by the
 * same stepper), EOMC_STEPS_DOUBLING (GSL's stepper estimates the error
 * by step doubling, so fixed steps are the method's plain steps: the
 * methods usually run with fixed steps); -1 for an unknown name. */
enum { EOMC_STEPS_ADAPTIVE, EOMC_STEPS_EMBEDDED, EOMC_STEPS_DOUBLING };
int eomc_method_steps(const char *name);
/* 1 if a method solves with the Jacobian of the equations (the implicit
 * ones), 0 if not, -1 for an unknown name.  A model built without its
 * Jacobian (eomc_model.jacobian NULL) refuses them, as it refuses
 * eomc_sim_jacobian, eomc_sim_linearize and eomc_sim_equilibrium, with
 * EOMC_EUSAGE and a message that says how to rebuild it. */
int eomc_method_jacobian(const char *name);

typedef struct eomc_run_opts {
    double t0, t_end;  /* time span */
    double dt;         /* output interval (> 0) */
    const char *method;
    double rtol, atol; /* adaptive tolerances */
    double h_fixed;    /* > 0: fixed steps (adjusted down to divide the span
                        * t_end - t0 evenly) */
    long max_steps;    /* per run; 0 = no limit */
    /* How far the run has come, t, now and then: every few hundred
     * right-hand sides (NULL: not told).  The library prints nothing; the
     * simulator shows t on a terminal when a run takes over a second. */
    void (*on_progress)(void *ctx, double t);
    void *progress_ctx;
    /* The scene's events (model->nevent > 0): called as each fires, with
     * its index k, its time and the state x [nx] there, before its action
     * (NULL: not told).  k = nevent + j: switch j of the model's max, min
     * or clamp (eomc_model.h), flipping its mode there.  A nonzero return stops the integration with that
     * status. */
    int (*on_event)(void *ctx, int k, double t, const double *x);
    void *event_ctx;
} eomc_run_opts;

/* Defaults from the model's scene. */
eomc_run_opts eomc_run_defaults(const eomc_model *m);
/* The output times: rows k = 0 .. eomc_run_rows(o) - 1 at t0 + k dt, the
 * last one exactly t_end (a time within 1e-9 dt of t_end is t_end: no
 * sliver of an interval at the end). */
long eomc_run_rows(const eomc_run_opts *o);
double eomc_run_row_time(const eomc_run_opts *o, long k);

typedef struct eomc_stats {
    long steps, rejected;    /* accepted and rejected steps */
    long rhs_evals, jac_evals;
    double cpu_seconds;
    double h_used;           /* the fixed step actually taken, or 0 */
    /* Constrained models: the largest |g|, |g'| or |phi| of the state at
     * t0 and after every step (after projection, when projecting), and
     * the largest found right after a step, before any projection. */
    double max_residual, max_drift;
    /* Rows computed by a step of their own, from the step end before them,
     * where the interpolant's error estimate failed the tolerances (long
     * steps; see runtime/step/dense.h).  Their right-hand sides are counted. */
    long side_steps;
    /* The conditioning of the linear system solved for q'' (the mass
     * matrix balanced by its diagonal, or the scaled KKT or elimination
     * matrix: free of units), estimated after every step: the largest
     * condition number and its time.  The solve may lose about
     * log10(condition) of the 16 digits of q''; when that passed what the
     * tolerance leaves (condition * DBL_EPSILON > cond_tol: the run's rtol,
     * 1e-8 for fixed steps), ill_t is the first time it did and ill names
     * the system and the coordinates (and constraints) it mixed there; else
     * ill_t is NAN. */
    double max_condition, t_condition, cond_tol, ill_t;
    char ill[512];
    long condition_estimates; /* how many (each a factorization and a few solves) */
    /* The time the checks after each step took (the condition above, the
     * conserved quantity's budget below, a constrained model's drift and
     * degenerate rows; not a projection asked for), on the monotonic
     * clock: part of cpu_seconds, and what the run's figures cost beside
     * the method. */
    double monitor_seconds;
    /* A model that conserves a quantity h (model->invariant), adaptive
     * steps (and projection, when constrained: otherwise the constraints'
     * drift moves h too): its largest change over the steps, and its
     * budget: the sum
     * over the steps of the change the step's own error estimate makes,
     * |h(x + err) - h(x)|.  h changes only by the steps' errors, so a
     * drift well beyond the budget is an error the estimates did not see
     * (an ill-conditioned solve, a discontinuity).  0 otherwise. */
    double invariant_drift, invariant_budget;
    /* The scene's events: how many fired, how many evaluations of the
     * state their location took (steps of their own), and the `stop`
     * event that ended the run (-1: none). */
    long events, event_evals;
    int stop_event;
    /* Taylor's method: the sum of the orders of its steps (their mean is
     * order_sum / steps); 0 for the other methods. */
    long order_sum;
    /* The time of the state eomc_sim_integrate leaves in x: t_end when the
     * run went to the end, else the time it stopped at (see there). */
    double t_stop;
    /* The first `set` of an event that left the state off its holonomic or
     * velocity-level constraints (eomc_sim_inconsistency above
     * EOMC_INCONSISTENT): the event (-1: none did), its time, the
     * constraint, its level (0: g, 1: g' or phi) and the inconsistency.
     * reset_off lists every constraint that set left off, worst first,
     * each with its level and inconsistency: "plane (velocities: 0.00056),
     * rod (velocities: 0.00028)".  The motion goes on from the state as
     * set. */
    int reset_event, reset_constraint, reset_level;
    double reset_t, reset_inconsistency;
    char reset_off[512];
    /* A model with unit quaternions (model->nquat > 0): after every step
     * each is renormalized; quat_drift is the largest ||e| - 1| found
     * before that (a pure number: |e| is 1 in the exact motion), the step's
     * own change of |e| for the one-step methods, the drift of the
     * method's own history for the multistep ones (msadams, msbdf: they
     * continue from their history, not from the state renormalized, which
     * only the rows and the checks see).  quat_ratio: the largest ratio
     * of a step's change of |e| to the change its own error estimate
     * allows (the estimate's length over e's four components): above
     * about 1 the steps' errors are not what their estimates say
     * (adaptive one-step methods; 0 otherwise); quat_t, the time of
     * quat_drift's step, quat_name its first coordinate ("root_e0"). */
    double quat_drift, quat_ratio, quat_t;
    const char *quat_name;
} eomc_stats;

/* Called at every output time t0 + k dt, t0 first and t_end last, with
 * the state x [nx].  Output times are not step ends: the state there is
 * the interpolant's (runtime/step/dense.h), except at t0.  A nonzero return
 * stops the integration with that status. */
typedef int (*eomc_row_fn)(void *ctx, double t, const double *x);

/* Whether o can run on s as it is set up: EOMC_OK, or EOMC_EUSAGE with a
 * message (eomc_sim_integrate checks this first). */
int eomc_run_check(eomc_sim *s, const eomc_run_opts *o);

/* Integrate from x.  Returns EOMC_OK, EOMC_EUSAGE for bad options (a
 * multistep method with EOMC_STABILIZE_PROJECT among them), EOMC_ENUMERIC,
 * or the nonzero status of a callback that stopped the run; the rows
 * already passed to `row` stand.  Whatever the ending, x is left at the
 * state of time st->t_stop:
 *  - the run went to t_end, or a `stop` event ended it: the state there,
 *    which is also the last row's (under EOMC_STABILIZE_PROJECT, to the
 *    rounding of projecting the row again);
 *  - `row` or on_event returned nonzero: the state that call was given, at
 *    its time (a row's is the interpolant's, as every row's is).  A
 *    program that stops on a signal by a flag its handler sets, returned
 *    from `row`, gets the row it stopped at (eomc_main's SIGINT);
 *  - a numerical failure (EOMC_ENUMERIC): the last state the steps reached
 *    to their tolerance, the end of the last accepted step (when a
 *    constraint degenerated within a step, that step's start).  The
 *    message's time is where the failure showed, which may differ: a
 *    trial state past t_stop where the accelerations fail, the
 *    degeneracy, or a row before t_stop that could not be computed.  No
 *    row passed lies beyond the failure;
 *  - no step was taken (bad options, a failure at t0, t_end = t0): x as
 *    given, t_stop = t0. */
int eomc_sim_integrate(eomc_sim *s, const eomc_run_opts *o, double *x,
                       eomc_row_fn row, void *ctx, eomc_stats *st);

/* ---- one step at a time ----
 *
 * The steps of eomc_sim_integrate, one per call, for a loop of one's own
 * (a front end, a controller in the loop), as GSL's odeiv2 evolve takes
 * them: eomc_sim_integrate is this loop with output rows read off the
 * steps.  The same method, tolerances or fixed steps, step control,
 * checks after each step (drift, projection, degenerate constraints,
 * conditioning) and events (located, reported through on_event, a `stop`
 * ending the run, a `set` resetting the state) and progress as o sets
 * up; o's dt makes no rows here (it must still be positive).
 *
 *     eomc_evolve *e = eomc_evolve_alloc(sim, &o, x0);
 *     eomc_step d;
 *     do {
 *         if (eomc_sim_step(sim, e, &d) != EOMC_OK)
 *             break;                      // eomc_sim_error(sim) says why
 *         for (double t = ...; t <= d.t1; t += ...)
 *             eomc_step_eval(&d, t, x);   // the state at t inside the step
 *     } while (!d.last);
 *     eomc_evolve_free(e);
 */
typedef struct eomc_evolve eomc_evolve;

/* What one accepted step covered, valid until the next eomc_sim_step:
 * from t0 to t1 (t1 > t0), the state x = (q, v) [nx = nq + nv] and its
 * derivative x' = (q', q'') at both ends.  x1 is the state the next step
 * starts from, except after a `set` event (event >= 0 with that action):
 * the step ends at the event with the state before its reset, and the
 * next step starts from the state the reset sets (its x0).  Under
 * EOMC_STABILIZE_PROJECT x1 is the projected end.  The dense output over
 * the step (eomc_step_eval) is exact at both ends.  Inside, under Taylor's
 * method it is the step's own polynomial, the one its rows and events
 * use, to the method's order; under the other methods it is the cubic
 * Hermite interpolant through (x0, f0) and (x1, f1): with h = t1 - t0 and
 * s = (t - t0) / h,
 *     x(t) = (2s^3 - 3s^2 + 1) x0 + (s^3 - 2s^2 + s) h f0
 *          + (3s^2 - 2s^3) x1 + (s^3 - s^2) h f1,
 * its error O(h^4) (eomc_sim_integrate's rows come from an interpolant of
 * higher order over several steps, runtime/step/dense.h). */
typedef struct eomc_step {
    int nx;                  /* nq + nv */
    double t0, t1;
    const double *x0, *f0;   /* [nx] at t0 */
    const double *x1, *f1;   /* [nx] at t1 */
    int event;               /* the `stop` or `set` event that ended the step at
                              * t1, or -1 (a `record` event is only reported) */
    int last;                /* the run is over: t1 is t_end, or a `stop` event */
    const void *series;      /* the runtime's own: Taylor's method's polynomial
                              * over the step (NULL under the other methods) */
    const eomc_model *model; /* the model stepped: eomc_step_eval renormalizes its
                              * unit quaternions, as the rows are */
} eomc_step;

/* Steps of s from x0 [nx] at o->t0 (o is copied; x0 is not kept).  NULL
 * when o cannot run on s (eomc_run_check), x0 or a parameter is not
 * finite, the model fails at the start, or memory runs out: the message
 * is in eomc_sim_error(s). */
eomc_evolve *eomc_evolve_alloc(eomc_sim *s, const eomc_run_opts *o, const double *x0);
void eomc_evolve_free(eomc_evolve *e);
/* The steps' statistics so far (eomc_stats, as eomc_sim_integrate keeps
 * them; t_stop: the time reached). */
const eomc_stats *eomc_evolve_stats(const eomc_evolve *e);
/* Advance by one accepted step, into *d.  EOMC_OK; EOMC_ENUMERIC with the
 * message of eomc_sim_integrate's failure; on_event's nonzero status; or
 * EOMC_EUSAGE once the run is over (d->last was set) or for another
 * simulator's steps.  After a failure the run is over. */
int eomc_sim_step(eomc_sim *s, eomc_evolve *e, eomc_step *d);
/* eomc_sim_step, the step ending at t at the latest: a stop of the
 * caller's (a sample of its own loop), reached exactly by the last step
 * before it, as t_end is.  Loop until d->t1 == t.  EOMC_EUSAGE when t is
 * not after the time reached or is past o's t_end. */
int eomc_sim_advance(eomc_sim *s, eomc_evolve *e, double t, eomc_step *d);
/* The caller changed what the steps start from, at the time reached:
 * the inputs (eomc_sim_set of an input, between steps), or the state, x
 * [nx] (NULL: as it is), each unit quaternion renormalized.  The next
 * step starts afresh from there, as after a controller's sample: x'
 * again, the steppers' history dropped, the switches the jump moved
 * flipped at that instant; the step size goes on.  A hand-written loop
 * that sets the inputs at t0 + k T and advances to each next one takes
 * the steps a sampled controller's run takes. */
int eomc_evolve_restart(eomc_sim *s, eomc_evolve *e, const double *x);
/* The step's dense output at t in [d->t0, d->t1] into x [d->nx], each unit
 * quaternion renormalized (model->quat: the cubic is off |e| = 1 by its
 * error inside the step). */
void eomc_step_eval(const eomc_step *d, double t, double *x);

/* ---- the reference solution ----
 *
 * The trajectory of a run's output times, computed from the model's
 * extended-precision functions (eomc_model_ext) by a method that is not
 * one of those it judges: Gragg-Bulirsch-Stoer extrapolation, or for a
 * stiff problem the linearly implicit Euler method with extrapolation, in
 * eomc_ext, to a tolerance refined until two successive solutions agree
 * (docs/accuracy.md says how stiffness is told).  The same
 * parameters, held inputs and initial state as the double runs; the true
 * motion, so no stabilization (a consistent start stays on the
 * constraints).  Or read from a CSV with the simulator's columns. */
typedef struct eomc_reference {
    long nrows;           /* output times t0 + k dt and t_end */
    int nx;               /* nq + nv */
    double *t, *x;        /* [nrows], [nrows * nx] */
    double error;         /* its estimated largest error in any entry of x (the
                           * difference of the last two refinements, and at
                           * least the rounding of x to doubles, half a unit
                           * in the last place of scale), or NAN when read
                           * from a file */
    double scale;         /* the largest |x| entry over the rows */
    int refinements;      /* solutions computed */
    double tolerance;     /* the last one's relative tolerance */
    long steps, rhs_evals;  /* of the last solution */
    double cpu_seconds;   /* all solutions */
    const char *method;   /* "Gragg-Bulirsch-Stoer extrapolation", "linearly implicit
                           * Euler extrapolation", "Taylor's method" or "a file"
                           * (static) */
    int stiff;            /* the linearly implicit method made it, the problem being
                           * stiff (source says why) */
    char source[768];     /* how it was made (and why that method), or the file */
    long nswitch;         /* the flips of the model's switches along it (max, min,
                           * clamp, step: eomc_model.h's modes), or -1 when not
                           * known (read from a file) */
    double *sw_t;         /* [nswitch] their times, in order */
    int *sw_k;            /* [nswitch] which switch flipped */
    double *sw_sens;      /* [nswitch * nx] how far each flip's time moves per unit
                           * error of each component, |ds/dx_i| / |ds/dt| (s the
                           * switch function; INFINITY where s is tangent) */
    double *sw_x, *sw_f;  /* [nswitch * nx] the state as each flip's instant
                           * arrived, and its rate there in the modes before
                           * (NULL: not known) */
} eomc_reference;

/* Compute the reference for o's output times from x0 [nx].  Returns
 * EOMC_OK, EOMC_EUSAGE (bad options, or ext NULL or not this model's),
 * or EOMC_ENUMERIC when the model fails (message as for a run). */
int eomc_reference_compute(eomc_sim *s, const eomc_model_ext *ext, const eomc_run_opts *o,
                           const double *x0, eomc_reference *ref);
/* The same, made by extrapolation (EOMC_REFERENCE_EXTRAPOLATION, what
 * eomc_reference_compute does) or by Taylor's method in extended
 * precision on the twin's series (EOMC_REFERENCE_TAYLOR: a second way
 * that shares nothing with the first but the model's functions; the
 * model built with its series, every constraint affine in q'', every
 * input held). */
enum { EOMC_REFERENCE_EXTRAPOLATION, EOMC_REFERENCE_TAYLOR };
int eomc_reference_compute_by(eomc_sim *s, const eomc_model_ext *ext, const eomc_run_opts *o,
                              const double *x0, int how, eomc_reference *ref);
/* Read a reference from a CSV whose header names t, every coordinate and
 * every velocity (name') among its columns (other columns are ignored),
 * with one row at each of o's output times.  EOMC_EUSAGE with a message
 * "FILE:LINE: ..." when it does not fit. */
int eomc_reference_read(eomc_sim *s, const char *path, const eomc_run_opts *o,
                        eomc_reference *ref);
void eomc_reference_free(eomc_reference *ref);
/* q'' [nv] and the multipliers lam [nc] (NULL: not wanted) at (t, x) as
 * the model's extended-precision functions solve them, rounded to double:
 * what eomc_sim_accel computes, carried in long double.  EOMC_EUSAGE
 * when ext is NULL or not this model's, EOMC_ENUMERIC when the solve
 * fails there. */
int eomc_reference_accel(eomc_sim *s, const eomc_model_ext *ext, double t, const double *x,
                         double *a, double *lam);

/* The last error: "t = 1.25: mass matrix is not positive definite (pivot
 * 2, q2); state q1 = ..., ..." */
const char *eomc_sim_error(const eomc_sim *s);

/* ---- the standalone simulator ---- */

/* The command line of a built simulator (see `EXE --help`); ext is the
 * model's extended-precision functions for the reference solution, or
 * NULL.  Returns the exit status: 0, 2 (usage) or 3 (numerical failure). */
int eomc_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext);

/* The simulator's command line (eomc_main) with what it would print on
 * stdout and stderr returned as text instead: *out and *err get malloc'd,
 * NUL-terminated text (free with eomc_free), out_len and err_len (unless
 * NULL) its length.  Files named on the line (-o FILE, --csv FILE, ...)
 * are written as eomc_main writes them.  For a caller that is not a
 * program of its own (the Python package): it installs no signal handler,
 * leaves GSL's error handler as it is (turn it off first:
 * gsl_set_error_handler_off), never exits, and its streams are the
 * calling thread's, so calls in several threads at once keep their text
 * apart.  Returns the exit status, as eomc_main (2, with *out and *err
 * NULL, when memory for the text runs out). */
int eomc_main_mem(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext,
                  char **out, size_t *out_len, char **err, size_t *err_len);
void eomc_free(void *p);

/* What eomc_main_with adds to eomc_main_mem: a controller on the run's
 * simulator (eomc_sim_set_controller's arguments; controller NULL: none),
 * and the run's rows as numbers instead of CSV text on stdout (-o FILE,
 * when given, is still written).  With rows_in_memory set, after the call
 * rows [nrows * ncols] holds every row written (also those before a
 * failure, as the CSV would have them: the same doubles the CSV prints in
 * their shortest digits) and columns the CSV's header line, each
 * malloc'd (eomc_free; NULL when no run wrote rows). */
typedef struct eomc_main_extra {
    eomc_controller_fn controller;
    void *controller_ctx;
    double period;
    const unsigned char *drives;
    int rows_in_memory;
    double *rows;   /* out */
    long nrows;     /* out */
    int ncols;      /* out */
    char *columns;  /* out */
} eomc_main_extra;
int eomc_main_with(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext,
                   eomc_main_extra *extra, char **out, size_t *out_len, char **err,
                   size_t *err_len);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#endif
