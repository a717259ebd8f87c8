/*
 * evolve: one accepted step at a time (eomc_sim_step, and evolve.h for
 * the driver above it, integrate.c).
 *
 * GSL provides the steppers (odeiv2 step types, or fixed.c's, which are
 * the same kind of object) and the step-size control; this file is the
 * evolve layer above them: take_step takes one accepted step, GSL's evolve
 * with these differences:
 *  - steps go as the tolerance allows, straight to t_end: no output time
 *    shortens one (the driver reads its rows off an interpolant);
 *  - the derivative at a step's end is kept for the next step and for
 *    the step's dense output, and recomputed when the state was changed
 *    (projection), where GSL's evolve would reuse a stale one;
 *  - after every accepted step of a constrained model, the checks and
 *    corrections of after_step: a degenerate constraint stops the run,
 *    the drift is measured, and the state is projected when asked;
 *  - after every accepted step, the scene's events (stepevents.h): one
 *    that fired is located, reported, and stops the run or resets the
 *    state and starts the integration again from there (check_events);
 *  - the watch over the adaptive steps (stepwatch.h): they stop when
 *    they collapse or grind;
 *  - after every accepted step, each unit quaternion renormalized
 *    (keep_unit), its drift measured;
 *  - Taylor's method (taylor.h) in place of GSL's stepper: a step is the
 *    series through its start, to the length the series allows, and its
 *    polynomial is the step's dense output, for the events and the rows.
 * The stepper and the checks after a step read and change the one step's
 * state (Run), so they stay together here.  The events and the watch need
 * of it only what they are handed: a step's ends, and x' and side steps
 * as callbacks, for the events (stepevents.c); the attempts and the steps'
 * sizes, for the watch (stepwatch.c).  Each keeps its own state, and
 * neither calls back into this file but through the callbacks it was
 * given, so the calls go one way; what an event does to the step (its end
 * moved to the event, the stepper restarted after a reset) is done here.
 */
#include "evolve.h"
#include "model/simimpl.h"
#include "model/state.h"
#include "stepevents.h"
#include "stepwatch.h"
#include "dense.h"
#include "model/linalg.h"
#include "methods.h"
#include "taylor.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- one run ---- */

/* A step below this fraction of max(|t|, t_end - t0) makes no progress. */
#define HMIN_REL 1e-14
/* The first trial step, as a fraction of the span: the control grows it
 * by up to 5 a step, so it costs a few steps, and never depends on dt. */
#define H0_REL 1e-5
/* The first step after a reset: at most this fraction of the time since
 * the event before, so that the steps resolve the next interval (each
 * bounce of a ball is shorter than the last by the restitution). */
#define RESTART_REL 1e-3
/* The steps after a reset start that small on purpose: they are not
 * watched for a collapse until this many have grown them again (by up to
 * 5 each), and events that come too fast are caught as such. */
enum { RESTART_STEPS = 30 };
/* ... growing by at most this much a step, as GSL's control grows them
 * (for Taylor's method, which has no such control). */
#define RESTART_GROWTH 5.0
typedef struct Run {
    eomc_sim *s;
    const eomc_model *m;          /* s's */
    const eomc_run_opts *o;
    eomc_stats *st;
    int n, nv, N;                 /* coordinates, speeds, state size n + nv */
    int multistep;                /* the stepper continues from its own history
                                   * (msadams, msbdf), not from the state */
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *d;         /* step, control; d->e is not used */
    gsl_odeiv2_step *step;        /* the stepper: d->s, or fixed.c's */
    double t, *x;                 /* the current state (the caller's array) */
    double *f0, *f1;              /* x' at the start and the end of a step */
    double *y0, *yerr;            /* the state before a step, error estimate */
    double *xt, *xerr;            /* trial states of the degeneracy search */
    double *B0, *B1;              /* rows of B before and after a step */
    double *fs, *fs2;             /* a side step's derivatives, in and out */
    gsl_odeiv2_step *side;        /* the stepper of side steps: the method's own
                                   * for a one-step method, else side_own */
    gsl_odeiv2_step *side_own;
    double hmin;
    double reached;               /* a failed step's motion is known up to here
                                   * (EvolveStep), or NAN ... */
    double *fr;                   /* [N] ... x' there (its state: xt) */
    int stop_status;              /* a callback's nonzero status: EVOLVE_STOPPED */
    double stop_t;                /* ... the time it was called with */
    const double *stop_x;         /* ... and the state (kept until the next step) */
    double h0;                    /* the conserved quantity at the start */
    int have_h0;
    StepWatch *watch;             /* the watch over the adaptive steps */
    StepEvents *ev;               /* the scene's events (NULL: none) */
    long since_reset;             /* steps since the last reset (RESTART_STEPS
                                   * before the first: none to watch for) */
    double h;                     /* the next adaptive step to try */
    unsigned long nfixed, i;      /* fixed steps: how many, and the last taken */
    int pending;                  /* a `set` event whose reset starts the next
                                   * step (-1: none) */
    double cond_pivot;            /* the pivot at the last condition estimate */
    long inv_rhs, inv_steps;      /* rhs_evals and steps at the conserved
                                   * quantity's last look (watch_invariant;
                                   * steps 0: none yet) */
    Taylor *taylor;               /* Taylor's method: the step's series (NULL:
                                   * GSL's stepper) */
    Taylor *taylor_side;          /* ... a side step's, from elsewhere */
    /* a sampled controller (sim_control_period > 0): its period, the next
     * sample t_sample = t0 + k_sample period, and whether one is due at
     * the next step's start (the last step ended there) */
    double period, t_sample;
    long k_sample;
    int sample_due;
    /* a caller's own stop (eomc_sim_advance; INFINITY: none), and a jump
     * of the inputs or the state it made at the time reached, due at the
     * next step's start (eomc_evolve_restart) */
    double t_hold;
    int jump_due;
    /* fixed steps: the stretch they divide evenly (t0 .. t_end, or with a
     * sampled controller the samples' intervals) and its first */
    double seg0, seg1;
} Run;

/* The caller is told of the progress every PROGRESS_EVERY right-hand

 * sides (a power of 2): often enough to follow, far too rarely to cost. */
enum { PROGRESS_EVERY = 256 };

static int
rhs(double t, const double *x, double *dxdt, void *ctx)
{
    Run *r = ctx;
    int n = r->n;
    r->st->rhs_evals++;
    if (r->o->on_progress && (r->st->rhs_evals & (PROGRESS_EVERY - 1)) == 0)
        r->o->on_progress(r->o->progress_ctx, t);
    if (eomc_sim_accel(r->s, t, x, x + n, dxdt + n) != EOMC_OK)
        return sim_control_failed(r->s) != EOMC_OK ? EVOLVE_CONTROL : GSL_EBADFUNC;
    sim_qdot(r->s, x, x + n, dxdt);
    return GSL_SUCCESS;
}

static int
jac(double t, const double *x, double *dfdx, double *dfdt, void *ctx)
{
    Run *r = ctx;
    r->st->jac_evals++;
    return eomc_sim_jacobian(r->s, t, x, dfdx, dfdt) == EOMC_OK ? GSL_SUCCESS
                                                                : GSL_EBADFUNC;
}

/* A callback (on_event here, a row's in the driver) returned status at
 * (t, x): the run stops there, and x is the state the caller gets back
 * (eomc_sim_integrate). */
static int
callback_stop(Run *r, int status, double t, const double *x)
{
    r->stop_status = status;
    r->stop_t = t;
    r->stop_x = x;
    return EVOLVE_STOPPED;
}

/* With --atol 0, each component's tolerance is rtol times its own size:
 * where components are exactly 0 (a block at rest, its sideways
 * coordinate), any error a step makes in them, rounding's included, is
 * beyond it.  Names them into buf (the first few); 0 where none is 0. */
enum { ZEROS_NAMED = 4 };
static int
zeros(const Run *r, char *buf, size_t len)
{
    int N = eomc_nx(r->m), count = 0;
    size_t at = (size_t)snprintf(buf, len, "--atol 0 asks each component for rtol of its "
                                 "own size, and ");
    for (int i = 0; i < N; i++) {
        if (r->x[i] != 0)
            continue;
        char name[STATE_NAME_MAX];
        if (count < ZEROS_NAMED && at < len)
            at += (size_t)snprintf(buf + at, len - at, "%s%s", count ? ", " : "",
                                   state_name(r->m, i, name, sizeof name));
        count++;
    }
    if (count > ZEROS_NAMED && at < len)
        at += (size_t)snprintf(buf + at, len - at, " and %d more", count - ZEROS_NAMED);
    if (at < len)
        snprintf(buf + at, len - at, " %s 0 there: a step that moves %s at all, by rounding "
                 "even, cannot meet it (give --atol a value above 0, a size below which "
                 "an error does not matter)", count == 1 ? "is" : "are",
                 count == 1 ? "it" : "them");
    return count > 0;
}

/* Why the steps may have collapsed at the current state, as far as the
 * runtime can see: an ill-conditioned solve (losing more than half the
 * digits of q''), a vanishing constraint row, or neither. */
#define LIKELY_COND 1e-8
static void
likely_cause(Run *r, char *buf, size_t len)
{
    eomc_sim *s = r->s;
    double c = sim_condition(s, r->t, r->x, r->x + r->n), fraction;
    int k;
    if (c * DBL_EPSILON > LIKELY_COND)
        snprintf(buf, len, "%s is nearly singular there (condition %.2g)",
                 sim_condition_what(s), c);
    else if (!isnan(c) && (k = sim_vanished(s, &fraction)) >= 0)
        snprintf(buf, len, "the constraint %s's row df/dq'' is vanishing there (%.2g of "
                 "its largest)", r->m->c_names[k], fraction);
    else if (!isnan(c) && r->o->atol == 0 && zeros(r, buf, len))
        ; /* (a relative tolerance alone, at components that are 0) */
    else if (!isnan(c))
        snprintf(buf, len, "not the solve for q'', which is well-conditioned there "
                 "(condition %.2g): a force or the motion that is singular or not smooth "
                 "there, or a tolerance the method cannot meet", c);
    else
        snprintf(buf, len, "the accelerations cannot be computed there");
}

/* The message for a stepping status other than success. */
static int
step_error(Run *r, int status)
{
    eomc_sim *s = r->s;
    int n = r->n;
    char cause[1024], what[1024];
    if (status == GSL_ENOPROG || status == STEPWATCH_COLLAPSE || status == STEPWATCH_GRIND)
        likely_cause(r, cause, sizeof cause);
    switch (status) {
    case STEPWATCH_COLLAPSE:
    case STEPWATCH_GRIND:
        stepwatch_what(r->watch, status, what, sizeof what);
        return sim_numeric_error(s, r->t, r->x, r->x + n, "%s%s", what, cause);
    case STEPEV_ACCUMULATE:
    case STEPEV_RETURNED:
        return stepev_error(r->ev, status, r->t, r->x);
    case GSL_EBADFUNC:
        return EOMC_ENUMERIC; /* the right-hand side said why */
    case EVOLVE_CONTROL:
        return sim_control_failed(s); /* (and said why) */
    case GSL_EMAXITER:
        return sim_numeric_error(s, r->t, r->x, r->x + n, "too many steps (the limit is "
                                 "%ld)", r->o->max_steps);
    case GSL_ENOPROG:
        return sim_numeric_error(s, r->t, r->x, r->x + n, "step size underflow (below "
                                 "%.3g); the likely cause: %s", r->hmin, cause);
    case GSL_FAILURE: /* fixed steps: fixed.c's Newton iteration */
        return sim_numeric_error(s, r->t, r->x, r->x + n, "the fixed %s step of %.3g "
                                 "failed (an implicit method's Newton iteration, or "
                                 "bsimp's extrapolation, did not converge); take smaller "
                                 "fixed steps", r->o->method, r->st->h_used);
    default:
        return sim_numeric_error(s, r->t, r->x, r->x + n, "the integrator failed: %s",
                                 gsl_strerror(status));
    }
}

/* ---- degenerate constraints ----
 *
 * A constraint degenerates where its row of B = df/dq'' vanishes (Appell's
 * cone at v = 0): there the accelerations are not determined, and the
 * KKT solution can pass smoothly through the point onto another branch
 * without the integrator noticing.  After each step we compare every row
 * with the row before it: a row that reversed direction went through zero
 * or close to it.  The step is then bisected to the reversal, and if the
 * row is small there relative to its size at either end (not merely
 * turned by a right angle in one long step), the run stops with an error
 * at that time and state. */

#define DEGENERATE_TOL 1e-3 /* |B_k| at the reversal, relative to the ends */
enum { BISECTIONS = 60 };

/* The first row k of B1 that reversed direction since B0, or -1; not a
 * row left out of the solves (sim_dropped_rows: the kept rows decide the
 * motion, and sim_dropped_watch watches it). */
static int
reversed_row(const Run *r)
{
    int n = r->nv;
    const unsigned char *drop = sim_dropped_rows(r->s);
    for (int k = 0; k < r->m->nc; k++)
        if ((!drop || !drop[k]) && la_dot(r->B0 + k * n, r->B1 + k * n, n) <= 0)
            return k;
    return -1;
}

static double
row_norm(const double *B, int k, int n)
{
    return sqrt(la_dot(B + k * n, B + k * n, n));
}

/* Row k reversed in the step from (t0, r->y0) to t1: bisect the step for
 * the reversal; an error there if the row is (nearly) zero. */
static int
locate_degeneracy(Run *r, int k, double t0, double t1)
{
    int n = r->nv, N = r->N;
    double *Bk0 = r->B0 + k * n, ends = fmax(row_norm(r->B0, k, n), row_norm(r->B1, k, n));
    double lo = 0, hi = t1 - t0, small = INFINITY;
    for (int it = 0; it < BISECTIONS; it++) {
        double h = 0.5 * (lo + hi);
        memcpy(r->xt, r->y0, (size_t)N * sizeof *r->xt);
        gsl_odeiv2_step_reset(r->step);
        if (gsl_odeiv2_step_apply(r->step, t0, h, r->xt, r->xerr, NULL, NULL, &r->sys) !=
                GSL_SUCCESS ||
            sim_constraint_rows(r->s, t0 + h, r->xt, r->B1) != 0) {
            small = 0; /* the solve broke down this close to it */
            break;
        }
        small = fmin(small, row_norm(r->B1, k, n));
        *(la_dot(Bk0, r->B1 + k * n, n) > 0 ? &lo : &hi) = h;
    }
    gsl_odeiv2_step_reset(r->step);
    if (!(small <= DEGENERATE_TOL * ends))
        return GSL_SUCCESS; /* the row turned, it did not vanish */
    memcpy(r->xt, r->y0, (size_t)N * sizeof *r->xt);
    /* the motion up to the degeneracy is known: the driver's last node
     * there (EvolveStep's reached), so that the rows before it are kept */
    if (lo > 0 &&
        gsl_odeiv2_step_apply(r->step, t0, lo, r->xt, r->xerr, NULL, r->fr, &r->sys) ==
            GSL_SUCCESS)
        r->reached = t0 + lo;
    gsl_odeiv2_step_reset(r->step);
    sim_numeric_error(r->s, t0 + lo, r->xt, r->xt + r->n, "the constraint %s degenerates: "
                      "its row of B = df/dq'' vanishes here (it reverses direction), so "
                      "the accelerations are no longer determined", r->m->c_names[k]);
    /* the step through it is not taken: the run ends at its start, the last
     * state the steps reached to their tolerance (the one step to the
     * degeneracy evaluates the accelerations where they are not
     * determined, so its state there may be off) */
    memcpy(r->x, r->y0, (size_t)N * sizeof *r->x);
    r->t = t0;
    return GSL_EBADFUNC;
}

/* The relative error of q'' that a run's tolerance allows: its rtol, or
 * for fixed steps (and atol alone), half the digits. */
#define FIXED_COND_TOL 1e-8
/* The condition is estimated in full (sim_condition: a factorization
 * and a few solves, some right-hand sides' worth) every WATCH_EVERY
 * steps, and at any step whose solves had a pivot small enough that the
 * condition may be within PIVOT_SLACK of the tolerance's limit: the
 * inverse of the smallest pivot is only about a lower bound (by a factor
 * of 4 for two coordinates, more for more).  A run whose pivots stay
 * that small (a chain at 1e-12: every step) would estimate at every step,
 * a quarter of its work besides the right-hand sides, so after an
 * estimate the pivot must fall below PIVOT_DROP of the pivot then before
 * it triggers another: the condition grows about as the pivot shrinks,
 * and the estimate every WATCH_EVERY steps catches the rest. */
enum { WATCH_EVERY = 64 };
#define PIVOT_SLACK 1e3
#define PIVOT_DROP 0.5

/* A condition cond of the system solved for q'' at t, of what: the
 * largest kept, and the first time one passed what the tolerance allows
 * (callers that must work out what test cond first). */
static void
note_condition(eomc_stats *st, double cond, double t, const char *what)
{
    if (!(cond > st->max_condition)) /* NAN: the next solve will say why */
        return;
    st->max_condition = cond, st->t_condition = t;
    if (isnan(st->ill_t) && cond * DBL_EPSILON > st->cond_tol) {
        st->ill_t = t;
        snprintf(st->ill, sizeof st->ill, "%s", what);
    }
}

/* After each step: the condition of the system solved for q'', and the
 * first time it passed what the tolerance allows; and the stuck friction
 * rows' where an item let go in the step (their modes gone by now). */
static void
watch_condition(Run *r)
{
    eomc_stats *st = r->st;
    double tol = st->cond_tol, t_flip;
    const char *flip_what;
    double flip = sim_take_flip_condition(r->s, &t_flip, &flip_what);
    if (flip > 0)
        note_condition(st, flip, t_flip, flip_what);
    double pivot = sim_take_pivot(r->s);
    if (st->steps % WATCH_EVERY != 0 &&
        !(PIVOT_SLACK * DBL_EPSILON > tol * pivot && pivot < PIVOT_DROP * r->cond_pivot))
        return;
    r->cond_pivot = pivot;
    st->condition_estimates++;
    double c0 = sim_seconds(0);
    double cond = sim_condition(r->s, r->t, r->x, r->x + r->n);
    st->monitor_seconds += sim_seconds(0) - c0;
    if (cond > st->max_condition)
        note_condition(st, cond, r->t, sim_condition_what(r->s));
}

/* The conserved quantity is looked at once INVARIANT_EVERY right-hand
 * sides have been spent since the last look, and at the first step; at
 * every step of a scene with events, whose steps differ too much for one
 * to stand for others (an event's step, those after its reset):
 * two evaluations of h, each costing less than a right-hand side, at
 * every step of a method that takes 3 (rk2) were 15 % of a chain's run. */
enum { INVARIANT_EVERY = 50 };

/* After an adaptive step, now and then (above): how far the conserved
 * quantity has moved, and how far the step's error estimate says it could
 * have (eomc_stats), that step's change standing for each of the steps
 * since the last look (their errors change slowly from step to step, and
 * the drift is held against the budget only within a factor 1000). */
static void
watch_invariant(Run *r)
{
    eomc_sim *s = r->s;
    eomc_stats *st = r->st;
    int n = r->n;
    double h, he;
    /* without projection a constrained state drifts off its constraints,
     * and h with it, by more than the steps' errors say: no budget then */
    if (!r->m->invariant || r->o->h_fixed > 0 ||
        (r->m->nc > 0 && sim_stabilize_method(s) != EOMC_STABILIZE_PROJECT))
        return;
    if (r->inv_steps > 0 && !r->ev && st->rhs_evals - r->inv_rhs < INVARIANT_EVERY)
        return;
    double c0 = sim_seconds(0);
    long stood = st->steps - r->inv_steps;
    r->inv_rhs = st->rhs_evals, r->inv_steps = st->steps;
    if (eomc_sim_invariant(s, r->t, r->x, r->x + n, &h) == EOMC_OK) {
        if (!r->have_h0)
            r->h0 = h, r->have_h0 = 1;
        for (int i = 0; i < r->N; i++)
            r->xt[i] = r->x[i] + r->yerr[i];
        eomc_sim_invariant(s, r->t, r->xt, r->xt + n, &he);
        st->invariant_drift = fmax(st->invariant_drift, fabs(h - r->h0));
        if (isfinite(he - h))
            st->invariant_budget += (double)stood * fabs(he - h);
    }
    st->monitor_seconds += sim_seconds(0) - c0;
}

/* A step's change of |e| is judged against what its error estimate allows
 * plus this many units of the rounding of |e| itself (a step at a tight
 * tolerance has an estimate below |e|'s rounding). */
#define QUAT_ROUNDING 8.0

/* After an accepted step to r->t: each unit quaternion back to length 1,
 * its drift ||e| - 1| before that measured (eomc_stats: quat_drift, and
 * quat_ratio against the step's own error estimate, r->yerr, for the
 * one-step methods, whose step started from |e| = 1), and x' at the end
 * evaluated again when that moved the state (so that the next step and
 * the dense output start from the state kept).  GSL_SUCCESS or the
 * right-hand side's failure. */
static int
keep_unit(Run *r)
{
    const eomc_model *m = r->m;
    eomc_stats *st = r->st;
    if (m->nquat == 0)
        return GSL_SUCCESS;
    for (int j = 0; j < m->nquat && !r->multistep && r->o->h_fixed <= 0; j++) {
        const int *e = m->quat + 4 * j;
        double moved = fabs(state_quat_norm(m, r->x, j) - state_quat_norm(m, r->y0, j));
        double est = 0;
        for (int i = 0; i < 4; i++)
            est += r->yerr[e[i]] * r->yerr[e[i]];
        est = sqrt(est) + QUAT_ROUNDING * DBL_EPSILON;
        st->quat_ratio = fmax(st->quat_ratio, moved / est);
    }
    memcpy(r->xt, r->x, (size_t)r->N * sizeof *r->x);
    int which;
    double drift = state_normalize(m, r->x, &which);
    if (drift > st->quat_drift) {
        st->quat_drift = drift, st->quat_t = r->t;
        st->quat_name = m->q_names[m->quat[4 * which]];
    }
    if (!memcmp(r->xt, r->x, (size_t)r->n * sizeof *r->x))
        return GSL_SUCCESS;
    return rhs(r->t, r->x, r->f1, r);
}

/* After each accepted step from t0: watch the conditioning; for a
 * constrained model, check that no constraint degenerated, measure the
 * drift, and project when asked.  A projected state is not the one the
 * stepper produced: its derivative is evaluated again (multistep methods,
 * whose history it would spoil, are refused with projection by
 * eomc_run_check). */
static int
after_step(Run *r, double t0)
{
    eomc_sim *s = r->s;
    int n = r->n;
    double *x = r->x, t = r->t;
    int rc = keep_unit(r);
    if (rc != GSL_SUCCESS)
        return rc;
    watch_condition(r);
    if (r->m->nc == 0) {
        watch_invariant(r);
        return GSL_SUCCESS;
    }
    /* the constrained checks' time, as the watches' (eomc_stats) */
    double c0 = sim_seconds(0);
    if (sim_constraint_rows(s, t, x, r->B1) != 0)
        return GSL_EBADFUNC;
    int k = reversed_row(r);
    if (k >= 0 && locate_degeneracy(r, k, t0, t) != GSL_SUCCESS)
        return GSL_EBADFUNC;
    if (sim_has_levels(s)) {
        double res = sim_level_residual(s, t, x, x + n);
        r->st->max_drift = fmax(r->st->max_drift, res);
        /* the rows left out still hold (the kept ones span them) */
        if (sim_dropped_watch(s, t, x, x + n) != EOMC_OK)
            return GSL_EBADFUNC;
        if (sim_stabilize_method(s) == EOMC_STABILIZE_PROJECT) {
            /* projecting is the method's, asked for, not a check's */
            r->st->monitor_seconds += sim_seconds(0) - c0;
            /* a failed projection leaves the step's end as it was */
            memcpy(r->xt, x, (size_t)r->N * sizeof *x);
            if (eomc_sim_project(s, t, x, x + n) != EOMC_OK) {
                memcpy(x, r->xt, (size_t)r->N * sizeof *x);
                return GSL_EBADFUNC;
            }
            if (r->step) /* Taylor's series starts afresh from x anyway */
                gsl_odeiv2_step_reset(r->step);
            res = sim_level_residual(s, t, x, x + n);
            if (sim_constraint_rows(s, t, x, r->B1) != 0)
                return GSL_EBADFUNC;
            rc = rhs(t, x, r->f1, r);
            if (rc != GSL_SUCCESS)
                return rc;
            c0 = sim_seconds(0);
        }
        r->st->max_residual = fmax(r->st->max_residual, res);
    }
    r->st->monitor_seconds += sim_seconds(0) - c0;
    watch_invariant(r);
    double *B = r->B0; /* the rows after this step are the next one's start */
    r->B0 = r->B1, r->B1 = B;
    return GSL_SUCCESS;
}

/* ---- side steps ---- */

/* Taylor's method: the state at t from (tk, xk), t past tk.  Inside the
 * step just taken, from its start, the step's own polynomial (a row, an
 * event's location); else series of their own, each as long as it
 * allows. */
static int
taylor_side(Run *r, double tk, const double *xk, double t, double *x)
{
    if (tk == taylor_start(r->taylor) && !memcmp(xk, r->y0, (size_t)r->N * sizeof *xk)) {
        taylor_eval(r->taylor, t - tk, x);
        return GSL_SUCCESS;
    }
    memcpy(x, xk, (size_t)r->N * sizeof *x);
    for (int piece = 0; tk < t && piece < EVOLVE_SIDE_PIECES; piece++) {
        double h;
        if (taylor_series(r->taylor_side, tk, x, t - tk, &h) != 0)
            return GSL_EBADFUNC;
        double t1 = h >= t - tk ? t : tk + h;
        taylor_eval(r->taylor_side, t1 - tk, x);
        tk = t1;
    }
    return tk < t ? GSL_EBADFUNC : GSL_SUCCESS;
}

/* The state at t by a step of its own from the node before it (a row's,
 * or an event's from the step's start): 1, 2, 4, ... pieces until each
 * passes the step control.  It is part of an
 * accepted step, so the method's truncation error is smaller there; it
 * leaves the run's steps as they are. */
static int
side_from(Run *r, double tk, const double *xk, const double *fk, double t, double *x)
{
    size_t bytes = (size_t)r->N * sizeof *x;
    if (r->taylor)
        return taylor_side(r, tk, xk, t, x);
    for (int pieces = 1; pieces <= EVOLVE_SIDE_PIECES; pieces *= 2) {
        double h = (t - tk) / pieces;
        memcpy(x, xk, bytes);
        memcpy(r->fs, fk, bytes);
        int p = 0;
        for (; p < pieces; p++) {
            double h1 = h, *f = r->fs;
            if (gsl_odeiv2_step_apply(r->side, tk + p * h, h, x, r->xerr, r->fs, r->fs2,
                                      &r->sys) != GSL_SUCCESS ||
                gsl_odeiv2_control_hadjust(r->d->c, r->side, x, r->xerr, r->fs2, &h1) ==
                    GSL_ODEIV_HADJ_DEC)
                break;
            r->fs = r->fs2, r->fs2 = f;
        }
        if (p == pieces)
            return GSL_SUCCESS;
    }
    return GSL_EBADFUNC;
}

/* ---- events (stepevents.h) ---- */

static int
side_motion(void *ctx, double tk, const double *xk, const double *fk, double t, double *x)
{
    return side_from(ctx, tk, xk, fk, t, x);
}

/* After the step from t0 to r->t: the events that fired in it.  One that
 * ends the step moves the step's end to it: r->t, r->x and r->f1 become
 * the event's, *what is EVOLVE_STOP or EVOLVE_SET and *fired its index
 * (else they are left as they are).  Returns GSL_SUCCESS or a failure
 * status. */
static int
check_events(Run *r, double t0, int *what, int *fired)
{
    StepevSpan sp = {.t0 = t0, .t1 = r->t, .x0 = r->y0, .f0 = r->f0, .x1 = r->x,
                     .f1 = r->f1};
    StepevHit hit;
    int rc = stepev_check(r->ev, &sp, &hit);
    if (rc != GSL_SUCCESS)
        return rc;
    if (hit.status != EOMC_OK)
        return callback_stop(r, hit.status, hit.t, hit.x);
    if (hit.k < 0)
        return GSL_SUCCESS;
    memcpy(r->x, hit.x, (size_t)r->N * sizeof *r->x);
    r->t = hit.t;
    if (hit.t != sp.t1 && (rc = rhs(hit.t, r->x, r->f1, r)) != GSL_SUCCESS)
        return rc;
    if (r->m->nc > 0 && sim_constraint_rows(r->s, hit.t, r->x, r->B0) != 0)
        return GSL_EBADFUNC;
    *fired = hit.k;
    *what = stepev_action(r->ev, hit.k) == EOMC_EVENT_STOP ? EVOLVE_STOP : EVOLVE_SET;
    return GSL_SUCCESS;
}

/* The steppers' history dropped: a multistep method's past, a one-step
 * method's remembered derivative; the next step starts from the state. */
static void
steppers_reset(Run *r)
{
    if (r->step)
        gsl_odeiv2_step_reset(r->step);
    if (r->side && r->side != r->step)
        gsl_odeiv2_step_reset(r->side);
}

/* Event k's reset at r->t (stepev_reset): the integration starts again
 * from the new state, with nothing of the history before (a multistep
 * method's past here; the driver drops its interpolant's nodes).  r->f0
 * is the right-hand side at r->x, the state the event found (take_step
 * has made the step's end the next one's start). */
static int
apply_reset(Run *r, int k)
{
    int rc = stepev_reset(r->ev, k, r->t, r->x, r->f0); /* f0: the next step's start */
    if (rc != GSL_SUCCESS)
        return rc;
    steppers_reset(r);
    r->since_reset = 0;
    if (r->m->nc > 0 && sim_constraint_rows(r->s, r->t, r->x, r->B0) != 0)
        return GSL_EBADFUNC;
    r->have_h0 = 0; /* the conserved quantity, measured afresh from here */
    return GSL_SUCCESS;
}

/* ---- steps ---- */

static int
budget_left(const Run *r)
{
    return r->o->max_steps <= 0 || r->st->steps < r->o->max_steps;
}

/* Where the steps must end next: t_end, or before it a stop of the
 * caller's (eomc_sim_advance) or a sampled controller's next sample. */
static double
stop_time(const Run *r)
{
    double stop = fmin(r->t_hold, r->o->t_end);
    return r->period > 0 && r->t_sample < stop ? r->t_sample : stop;
}

/* The sample after the one at r->t_sample: t0 + k period (not a sum of
 * periods, whose rounding would drift), none near t_end
 * (SIM_SAMPLE_AT_END_REL). */
static void
next_sample(Run *r)
{
    r->t_sample = r->o->t0 + (double)++r->k_sample * r->period;
    if (r->t_sample > r->o->t_end - SIM_SAMPLE_AT_END_REL * r->period)
        r->t_sample = INFINITY;
}

/* One accepted step from r->t of at most *h (adaptive): GSL's evolve,
 * with rejected steps retried from the same start as its steppers
 * expect.  *h becomes the size the control suggests next. */
static int
adaptive_step(Run *r, double *h)
{
    double t0 = r->t, h0 = *h, stop = stop_time(r), left = stop - t0;
    size_t bytes = (size_t)r->N * sizeof *r->x;
    memcpy(r->y0, r->x, bytes);
    sim_save_start(r->s);
    for (;;) {
        sim_restore_start(r->s);
        int final = h0 >= left;
        if (final)
            h0 = left;
        else if (2 * h0 > left) /* two halves, not a step and a sliver */
            h0 = 0.5 * left;
        int rc = gsl_odeiv2_step_apply(r->step, t0, h0, r->x, r->yerr, r->f0, r->f1,
                                       &r->sys);
        if (rc == GSL_EFAULT || rc == EVOLVE_CONTROL) {
            memcpy(r->x, r->y0, bytes);
            return rc;
        }
        double h_old = h0;
        int retry = 0;
        if (rc != GSL_SUCCESS) {
            /* the stepper could not, or a stage met a state where the
             * accelerations fail (past a singularity): halve, to go as
             * close to it as steps can; the message of the nearest such
             * state stands if no step gets further */
            h0 *= 0.5;
            retry = 1;
        } else if (gsl_odeiv2_control_hadjust(r->d->c, r->step, r->x, r->yerr, r->f1,
                                              &h0) == GSL_ODEIV_HADJ_DEC) {
            retry = 1;
        }
        stepwatch_tried(r->watch, retry);
        if (retry) {
            memcpy(r->x, r->y0, bytes);
            r->st->rejected++;
            if (!(h0 < h_old) || t0 + h0 == t0 || h0 < r->hmin)
                return rc == GSL_EBADFUNC ? rc : GSL_ENOPROG;
            continue;
        }
        r->t = final ? stop : t0 + h_old;
        if (!final) {
            *h = h0;
            stepwatch_accepted(r->watch, h_old);
        }
        return GSL_SUCCESS;
    }
}

/* One step of Taylor's method from r->t: the series through the state,
 * as far as it allows (to t_end at most, in two halves rather than a
 * step and a sliver), its value there, and the error its last term
 * estimates (for the conserved quantity's budget).  The series is the
 * step's dense output (taylor_side).  A series that cannot be computed
 * (M not positive definite, a coefficient not finite) is the
 * right-hand side's failure at the step's start: rhs there says why. */
static int
taylor_step(Run *r)
{
    double t0 = r->t, stop = stop_time(r), left = stop - t0, h, hmax = left;
    /* after an event's reset, as for the other methods: the first step
     * the restart's (take_step), each next at most RESTART_GROWTH times
     * the one before, so that the steps see g leave zero before they could
     * cross it again (a bounce's parabola has an infinite radius: its
     * series would step straight through the floor) */
    if (r->since_reset < RESTART_STEPS)
        hmax = fmin(hmax, r->since_reset == 0 ? r->h : RESTART_GROWTH * r->h);
    memcpy(r->y0, r->x, (size_t)r->N * sizeof *r->x);
    if (taylor_series(r->taylor, t0, r->x, hmax, &h) != 0)
        return GSL_EBADFUNC;
    int final = h >= left;
    if (final)
        h = left;
    else if (2 * h > left)
        h = 0.5 * left;
    double cut = taylor_event_cut(r->taylor, h);
    if (cut < h)
        h = cut, final = 0;
    taylor_advance(r->taylor, h, r->x);
    taylor_error(r->taylor, h, r->yerr);
    r->st->order_sum += taylor_order(r->taylor);
    r->t = final ? stop : t0 + h;
    int rc = rhs(r->t, r->x, r->f1, r);
    if (rc != GSL_SUCCESS) {
        memcpy(r->x, r->y0, (size_t)r->N * sizeof *r->x);
        r->t = t0;
        return rc;
    }
    if (!final) {
        r->h = h;
        stepwatch_tried(r->watch, 0);
        stepwatch_accepted(r->watch, h);
    }
    return GSL_SUCCESS;
}

/* One fixed step, from r->t to t1. */
static int
fixed_step(Run *r, double t1)
{
    double t0 = r->t;
    memcpy(r->y0, r->x, (size_t)r->N * sizeof *r->x);
    int rc = gsl_odeiv2_step_apply(r->step, t0, t1 - t0, r->x, r->yerr, r->f0, r->f1,
                                   &r->sys);
    /* bsimp says a step failed by an infinite error estimate, not a status */
    for (int i = 0; rc == GSL_SUCCESS && i < r->N; i++)
        if (!isfinite(r->yerr[i]))
            rc = GSL_FAILURE;
    if (rc != GSL_SUCCESS) {
        memcpy(r->x, r->y0, (size_t)r->N * sizeof *r->x);
        return rc;
    }
    r->t = t1;
    return GSL_SUCCESS;
}

/* Fixed steps: the stretch from r->t to the next stop (t_end, or a
 * sample), divided evenly into steps of at most h_fixed (st->h_used: the
 * first stretch's, the whole span's without a sampled controller). */
static void
fixed_stretch(Run *r)
{
    double h = r->o->h_fixed, span;
    r->seg0 = r->t, r->seg1 = stop_time(r), span = r->seg1 - r->seg0;
    r->i = 0;
    r->nfixed = (unsigned long)ceil(span / h * (1 - 1e-12));
    if (r->nfixed < 1)
        r->nfixed = 1;
    if (r->st->h_used == 0)
        r->st->h_used = span / (double)r->nfixed;
}

/* The fixed steps of the span (st->h_used), or none (adaptive): before
 * the first step. */
static void
steps_begin(Run *r)
{
    const eomc_run_opts *o = r->o;
    double span = o->t_end - o->t0;
    r->h = H0_REL * span;
    r->pending = -1;
    if (o->h_fixed > 0)
        fixed_stretch(r);
}

/* Whether a step is left to take: before t_end, or a reset to apply. */
static int
steps_left(const Run *r)
{
    return r->t < r->o->t_end || r->pending >= 0;
}

static int restart_here(Run *r);

/* The sampled controller's call at r->t, where the last step ended (its
 * state the next one's start): the inputs it sets held from here, so
 * the steps start afresh as after a reset (x' at the state again, the
 * steppers' history dropped, the switches its inputs moved flipped at
 * this instant: stepev_jump), but for the step size, which the motion
 * sets, not the sample.  The next fixed stretch starts here.  A
 * controller's failure stops the run at the sample (evolve_stop). */
static int
take_sample(Run *r)
{
    int rc = sim_sample(r->s, r->t, r->x);
    if (rc != EOMC_OK)
        return callback_stop(r, rc, r->t, r->x);
    next_sample(r);
    return restart_here(r);
}

/* The inputs (a sample's), or the state, jumped at r->t: the steps start
 * afresh from there (take_sample says how). */
static int
restart_here(Run *r)
{
    int rc;
    if (r->ev)
        rc = stepev_jump(r->ev, r->t, r->x, r->f0);
    else
        rc = rhs(r->t, r->x, r->f0, r);
    if (rc != GSL_SUCCESS)
        return rc;
    steppers_reset(r);
    if (r->m->nc > 0 && sim_constraint_rows(r->s, r->t, r->x, r->B0) != 0)
        return GSL_EBADFUNC;
    if (r->nfixed)
        fixed_stretch(r);
    r->have_h0 = 0; /* the conserved quantity, measured afresh from here */
    return GSL_SUCCESS;
}

/* One accepted step, GSL's evolve with the checks of after_step and the
 * events: a pending reset applied first, then a fixed or an adaptive
 * step, and the watch over the steps.  tk says what it did (EvolveStep). */
static int
take_step(Run *r, EvolveStep *tk)
{
    const eomc_run_opts *o = r->o;
    double span = o->t_end - o->t0;
    int rc;
    *tk = (EvolveStep){.ev = EVOLVE_NONE, .fired = -1, .reached = NAN, .series = r->taylor};
    r->reached = NAN;
    if (r->pending >= 0) {
        int k = r->pending;
        r->pending = -1;
        tk->restarted = 1;
        if ((rc = apply_reset(r, k)) != GSL_SUCCESS)
            return rc;
        /* a fresh start: a first trial step as at t0, and a fraction of
         * the interval since the event before, so that the steps grow
         * again from the event and see g leave zero before they could
         * cross it a second time (the top of a bounce) */
        r->h = H0_REL * span;
        if (k < r->m->nevent) /* a switch leaves the state as it was: no bounce to resolve,
                               * and two switches close together (contacts touching one
                               * after another) must not shrink the step below hmin */
            r->h = fmin(r->h, RESTART_REL * stepev_gap(r->ev));
        if (!(r->t < o->t_end))
            return GSL_SUCCESS;
    }
    if (r->sample_due && (rc = take_sample(r)) != GSL_SUCCESS)
        return rc;
    if (r->jump_due && !r->sample_due && (rc = restart_here(r)) != GSL_SUCCESS)
        return rc;
    tk->restarted |= r->sample_due | r->jump_due;
    r->sample_due = r->jump_due = 0;
    if (r->nfixed && r->seg1 != stop_time(r)) /* a stop of the caller's moved */
        fixed_stretch(r);
    if (!budget_left(r))
        return GSL_EMAXITER;
    double t0 = r->t;
    r->i++;
    if (r->taylor)
        rc = taylor_step(r);
    else if (r->nfixed) /* (one stretch: i h_used from t0, as without samples) */
        rc = fixed_step(r, r->i == r->nfixed ? r->seg1
                                             : r->seg0 + (double)r->i * (r->seg1 - r->seg0) /
                                                             (double)r->nfixed);
    else
        rc = adaptive_step(r, &r->h);
    if (rc != GSL_SUCCESS)
        return rc;
    r->st->steps++;
    r->since_reset++;
    if ((rc = after_step(r, t0)) != GSL_SUCCESS)
        return rc;
    if (r->ev && (rc = check_events(r, t0, &tk->ev, &tk->fired)) != GSL_SUCCESS)
        return rc;
    double *f = r->f0; /* this step's end is the next one's start */
    r->f0 = r->f1, r->f1 = f;
    /* a step that ends at a sample (and not at a stop event) leaves it due */
    r->sample_due = r->period > 0 && r->t == r->t_sample && tk->ev != EVOLVE_STOP;
    *tk = (EvolveStep){.taken = 1, .t0 = t0, .t1 = r->t, .x0 = r->y0, .f0 = r->f1,
                       .x1 = r->x, .f1 = r->f0, .restarted = tk->restarted, .ev = tk->ev,
                       .fired = tk->fired, .reached = NAN, .series = r->taylor,
                       .sampled = r->sample_due};
    if (tk->ev == EVOLVE_STOP) {
        r->st->stop_event = tk->fired;
        return GSL_SUCCESS;
    }
    if (tk->ev == EVOLVE_SET) {
        r->pending = tk->fired;
        return GSL_SUCCESS;
    }
    if (r->t < o->t_end && !r->nfixed && fabs(r->h) < r->hmin)
        return GSL_ENOPROG;
    int restarting = r->since_reset < RESTART_STEPS;
    if (!r->nfixed && (rc = stepwatch_check(r->watch, r->t, restarting)) != GSL_SUCCESS)
        return rc;
    return GSL_SUCCESS;
}

static void
run_free(Run *r)
{
    if (r->side_own)
        gsl_odeiv2_step_free(r->side_own);
    if (r->step && (!r->d || r->step != r->d->s))
        gsl_odeiv2_step_free(r->step);
    if (r->d)
        gsl_odeiv2_driver_free(r->d);
    double *arrays[] = {r->f0, r->f1, r->y0, r->yerr, r->xt, r->xerr, r->B0, r->B1,
                        r->fr, r->fs, r->fs2};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    stepev_free(r->ev);
    if (r->s) /* the modes of a state given alone again */
        sim_modes_run(r->s, 0);
    stepwatch_free(r->watch);
    taylor_free(r->taylor);
    taylor_free(r->taylor_side);
}

/* The steppers of a run: GSL's driver, the stepper (fixed.c's for fixed
 * steps) and the stepper of side steps; or, for Taylor's method, which
 * has no GSL stepper, its series (the step's and the side steps').
 * Whether all were made. */
static int
steppers_alloc(Run *r, const Method *m)
{
    size_t N = (size_t)r->N;
    double span = r->o->t_end - r->o->t0;
    if (!*m->adaptive) {
        r->taylor = taylor_alloc(r->s, r->o);
        r->taylor_side = taylor_alloc(r->s, r->o);
        return r->taylor && r->taylor_side;
    }
    r->d = gsl_odeiv2_driver_alloc_y_new(&r->sys, *m->adaptive,
                                         span > 0 ? H0_REL * span : 1.0, r->o->atol,
                                         r->o->rtol);
    r->step = r->d ? r->d->s : NULL;
    if (r->d && r->o->h_fixed > 0 && *m->fixed != *m->adaptive) {
        r->step = gsl_odeiv2_step_alloc(*m->fixed, N);
        if (r->step)
            gsl_odeiv2_step_set_driver(r->step, r->d);
    }
    /* a multistep method's stepper has a history a side step would spoil:
     * its side steps are a one-step method's of the same kind, explicit
     * for msadams, implicit for msbdf (an explicit one could not take a
     * stiff problem's side steps, the Van der Pol oscillator's at
     * stiffness 1e6: not 1e-8 in 64 pieces) */
    r->side = r->step;
    if (r->d && !m->fixed) {
        r->side = r->side_own = gsl_odeiv2_step_alloc(m->jacobian ? gsl_odeiv2_step_bsimp
                                                                  : gsl_odeiv2_step_rk8pd, N);
        if (r->side)
            gsl_odeiv2_step_set_driver(r->side, r->d);
    }
    return r->d && r->step && r->side;
}

static int
run_alloc(Run *r, const Method *m)
{
    size_t N = (size_t)r->N, nB = (size_t)r->m->nc * (size_t)r->nv;
    r->sys = (gsl_odeiv2_system){rhs, jac, N, r};
    double **arrays[] = {&r->f0, &r->f1, &r->y0, &r->yerr, &r->xt, &r->xerr, &r->B0,
                         &r->B1, &r->fr, &r->fs, &r->fs2};
    size_t sizes[] = {N, N, N, N, N, N, nB, nB, N, N, N};
    int ok = steppers_alloc(r, m) && (r->watch = stepwatch_alloc(r->o->t0)) != NULL;
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        ok &= (*arrays[k] = sim_zeros(sizes[k])) != NULL;
    if (r->m->nevent > 0 || r->m->nmode > 0) {
        StepevMotion motion = {.rate = rhs, .side = side_motion, .ctx = r,
                               .steps_split_pairs = r->taylor != NULL};
        ok &= (r->ev = stepev_alloc(r->s, r->o, r->st, motion)) != NULL;
    }
    return ok ? EOMC_OK : sim_usage_error(r->s, "out of memory setting up %s",
                                          r->o->method);
}

/* A run from x at o->t0 set up: the options checked, the work arrays
 * (r zeroed by the caller; run_free either way).  EOMC_OK or a status
 * with its message. */
static int
run_open(Run *r, eomc_sim *s, const eomc_run_opts *o, double *x, eomc_stats *st)
{
    memset(st, 0, sizeof *st);
    st->ill_t = NAN;
    st->t_stop = o->t0;
    st->cond_tol = o->h_fixed > 0 || !(o->rtol > 0) ? FIXED_COND_TOL : o->rtol;
    int rc = eomc_run_check(s, o);
    if (rc)
        return rc;
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, nv = eomc_nv(m);
    if (!sim_all_finite(x, n + nv) || !sim_all_finite(eomc_sim_params(s), m->np))
        return sim_numeric_error(s, o->t0, x, x + n,
                                 "the initial state or a parameter is not finite");
    const Method *method = method_find(o->method);
    *r = (Run){.s = s, .m = m, .o = o, .st = st, .n = n, .nv = nv, .N = n + nv, .t = o->t0,
               .x = x, .since_reset = RESTART_STEPS, .pending = -1, .reached = NAN,
               .t_hold = INFINITY,
               .cond_pivot = INFINITY,
               .multistep = !method->fixed && *method->adaptive != NULL};
    st->stop_event = -1;
    st->reset_event = -1;
    sim_control_start(s);
    r->period = fmax(sim_control_period(s), 0);
    r->hmin = HMIN_REL * fmax(fmax(fabs(o->t0), fabs(o->t_end)), o->t_end - o->t0);
    return run_alloc(r, method);
}

/* A switch function exactly 0 at the start says nothing of the mode: the
 * side the motion leaves to does, the sign of s's rate along it, by a
 * central difference over START_PROBE_REL of the time span along x' (in
 * the mode so far; the sign is all that is used).  Where the other mode
 * sends s back, neither side is left to (a motion sliding along the
 * kink, which no mode follows): the run stops there, naming the switch. */
#define START_PROBE_REL 1e-7

/* Switch k's rate along the motion at the start, in the modes as they
 * are, into *rate (sw: scratch [2 nmode]). */
static int
start_rate(Run *r, int k, double *sw, double *rate)
{
    int n = r->n, N = r->N, nm = r->m->nmode;
    double d = START_PROBE_REL * (r->o->t_end - r->o->t0);
    int rc = rhs(r->t, r->x, r->fr, r);
    if (rc != GSL_SUCCESS)
        return rc;
    for (int i = 0; i < N; i++) {
        r->fs[i] = r->x[i] - d * r->fr[i];
        r->fs2[i] = r->x[i] + d * r->fr[i];
    }
    sim_switches(r->s, r->t - d, r->fs, r->fs + n, sw);
    sim_switches(r->s, r->t + d, r->fs2, r->fs2 + n, sw + nm);
    *rate = sw[nm + k] - sw[k];
    return GSL_SUCCESS;
}

static int
start_modes(Run *r)
{
    eomc_sim *s = r->s;
    int n = r->n, nm = r->m->nmode, rc = GSL_SUCCESS;
    if (sim_set_modes(s, r->t, r->x, r->x + n) != EOMC_OK)
        return GSL_EBADFUNC;
    double *at = sim_zeros(3 * (size_t)nm), *sw = at + nm;
    if (!at)
        return GSL_ENOMEM;
    sim_switches(s, r->t, r->x, r->x + n, at);
    for (int k = 0; k < nm && rc == GSL_SUCCESS; k++) {
        double r0, r1;
        /* (dry friction's stick switches are friction's: sim_set_modes) */
        if (at[k] != 0 || sim_mode_held(s, k) || (rc = start_rate(r, k, sw, &r0)) != GSL_SUCCESS)
            continue;
        if (r0 == 0 || (r0 > 0) == sim_mode(s, k)) /* (a tangency keeps mode 0) */
            continue;
        sim_set_mode(s, k, r0 > 0);
        if ((rc = start_rate(r, k, sw, &r1)) == GSL_SUCCESS && r1 != 0 && (r1 > 0) != (r0 > 0)) {
            char name[STATE_NAME_MAX];
            sim_numeric_error(s, r->t, r->x, r->x + n, "%s starts on its kink (its "
                              "function is 0) and neither mode leaves it: the motion would "
                              "slide along it, which no mode follows",
                              state_switch_name(r->m, k, name, sizeof name));
            rc = GSL_EBADFUNC;
        }
    }
    free(at);
    return rc;
}

/* The start of a run: the equations at t0 first (a model that cannot be
 * solved there, a singular M, a NaN of a parameter's value, writes no
 * row). */
static int
run_start(Run *r, int derivative)
{
    eomc_sim *s = r->s;
    double *x = r->x;
    int n = r->n;
    if (r->period > 0) { /* the first sample, at t0: the inputs from the start */
        int rc = sim_sample(s, r->t, x);
        if (rc != EOMC_OK)
            return rc;
        r->k_sample = 0;
        next_sample(r);
    }
    if (r->m->nmode > 0) { /* each from its switch function's sign at the start */
        sim_modes_run(s, 1);
        int rc = start_modes(r);
        if (rc != GSL_SUCCESS)
            return step_error(r, rc);
    }
    if (sim_has_levels(s))
        r->st->max_residual = r->st->max_drift = sim_level_residual(s, r->t, x, x + n);
    int status = derivative ? rhs(r->t, x, r->f0, r) : GSL_SUCCESS;
    return status != GSL_SUCCESS ? step_error(r, status) : EOMC_OK;
}

/* After the first row (the initial state, as it is, written by the
 * driver): what the watches start from. */
static int
run_watch(Run *r)
{
    eomc_sim *s = r->s;
    double *x = r->x;
    int n = r->n;
    if (r->m->nc > 0 && sim_constraint_rows(s, r->t, x, r->B0) != 0)
        return EOMC_ENUMERIC;
    watch_condition(r);
    if (r->m->invariant && eomc_sim_invariant(s, r->t, x, x + n, &r->h0) == EOMC_OK)
        r->have_h0 = 1;
    if (r->ev)
        stepev_start(r->ev, r->t, x);
    return EOMC_OK;
}

/* ---- one step at a time (eomc_sim_step, and evolve.h's) ---- */

struct eomc_evolve {
    Run r;
    eomc_run_opts o;     /* eomc_evolve_alloc's copy: r.o */
    eomc_stats st;       /* r.st */
    double *x;           /* [nx] the state: r.x (NULL: the driver's) */
    int over;            /* t_end reached, a stop event, or a failure */
};

int
evolve_open(eomc_evolve **pe, eomc_sim *s, const eomc_run_opts *o, double *x,
            eomc_stats *st)
{
    eomc_evolve *e = *pe = calloc(1, sizeof *e);
    if (!e)
        return sim_usage_error(s, "out of memory setting up the steps");
    return run_open(&e->r, s, o, x, st);
}

int
evolve_start(eomc_evolve *e, int derivative)
{
    return run_start(&e->r, derivative);
}

int
evolve_watch(eomc_evolve *e)
{
    return run_watch(&e->r);
}

void
evolve_begin(eomc_evolve *e)
{
    steps_begin(&e->r);
}

int
evolve_more(const eomc_evolve *e)
{
    return steps_left(&e->r);
}

int
evolve_step(eomc_evolve *e, EvolveStep *tk)
{
    Run *r = &e->r;
    int rc = take_step(r, tk);
    if (!isnan(r->reached)) {
        tk->reached = r->reached;
        tk->xr = r->xt;
        tk->fr = r->fr;
    }
    return rc;
}

double
evolve_time(const eomc_evolve *e)
{
    return e->r.t;
}

struct Taylor *
evolve_taylor(eomc_evolve *e, const double **x)
{
    *x = e->r.x;
    return e->r.pending < 0 && !e->r.sample_due && !e->r.jump_due ? e->r.taylor : NULL;
}

const double *
evolve_rate(const eomc_evolve *e)
{
    return e->r.f0;
}

int
evolve_side(eomc_evolve *e, double tk, const double *xk, const double *fk, double t,
            double *x)
{
    return side_from(&e->r, tk, xk, fk, t, x);
}

int
evolve_stop(eomc_evolve *e, int status, double t, const double *x)
{
    return callback_stop(&e->r, status, t, x);
}

int
evolve_stopped(const eomc_evolve *e, double *t, const double **x)
{
    *t = e->r.stop_t;
    *x = e->r.stop_x;
    return e->r.stop_status;
}

int
evolve_error(eomc_evolve *e, int status)
{
    return step_error(&e->r, status);
}

eomc_evolve *
eomc_evolve_alloc(eomc_sim *s, const eomc_run_opts *o, const double *x0)
{
    size_t N = (size_t)eomc_nx(eomc_sim_model(s));
    eomc_evolve *e = calloc(1, sizeof *e);
    double *x = sim_zeros(N);
    if (!e || !x) {
        free(e);
        free(x);
        sim_usage_error(s, "out of memory setting up the steps");
        return NULL;
    }
    memcpy(x, x0, N * sizeof *x);
    e->o = *o;
    e->x = x;
    int rc = run_open(&e->r, s, &e->o, x, &e->st);
    double c0 = sim_seconds(1);
    if (rc == EOMC_OK)
        rc = run_start(&e->r, e->o.t0 < e->o.t_end);
    if (rc == EOMC_OK)
        rc = run_watch(&e->r);
    e->st.cpu_seconds = sim_seconds(1) - c0;
    if (rc != EOMC_OK) {
        eomc_evolve_free(e);
        return NULL;
    }
    steps_begin(&e->r);
    e->over = !(e->r.t < e->o.t_end);
    return e;
}

void
eomc_evolve_free(eomc_evolve *e)
{
    if (!e)
        return;
    run_free(&e->r);
    free(e->x);
    free(e);
}

const eomc_stats *
eomc_evolve_stats(const eomc_evolve *e)
{
    return &e->st;
}

int
eomc_sim_step(eomc_sim *s, eomc_evolve *e, eomc_step *d)
{
    Run *r = &e->r;
    if (s != r->s)
        return sim_usage_error(s, "eomc_sim_step: the steps were set up for another "
                               "simulator");
    if (e->over)
        return sim_usage_error(s, "eomc_sim_step: the run is over, at t = %.17g", r->t);
    double c0 = sim_seconds(1);
    EvolveStep tk;
    int rc = take_step(r, &tk);
    e->st.cpu_seconds += sim_seconds(1) - c0;
    e->st.t_stop = r->t;
    if (rc != GSL_SUCCESS) {
        e->over = 1;
        return rc == EVOLVE_STOPPED ? r->stop_status : step_error(r, rc);
    }
    *d = (eomc_step){.nx = r->N, .t0 = tk.t0, .t1 = r->t, .x0 = r->y0, .f0 = r->f1,
                     .x1 = r->x, .f1 = r->f0, .event = tk.ev != EVOLVE_NONE ? tk.fired : -1,
                     .last = tk.ev == EVOLVE_STOP || !(r->t < e->o.t_end),
                     .series = tk.series, .model = r->m};
    e->over = d->last;
    return EOMC_OK;
}

int
eomc_sim_advance(eomc_sim *s, eomc_evolve *e, double t, eomc_step *d)
{
    Run *r = &e->r;
    if (s == r->s && !e->over && !(t > r->t && t <= e->o.t_end))
        return sim_usage_error(s, "eomc_sim_advance: %.17g is not after the time reached, "
                               "%.17g, and at most the end %.17g", t, r->t, e->o.t_end);
    r->t_hold = t;
    int rc = eomc_sim_step(s, e, d);
    r->t_hold = INFINITY;
    return rc;
}

int
eomc_evolve_restart(eomc_sim *s, eomc_evolve *e, const double *x)
{
    Run *r = &e->r;
    if (s != r->s || e->over)
        return sim_usage_error(s, "eomc_evolve_restart: %s", e->over ? "the run is over"
                               : "the steps were set up for another simulator");
    if (x && !sim_all_finite(x, r->N))
        return sim_usage_error(s, "eomc_evolve_restart: the state is not finite");
    if (x) {
        memcpy(r->x, x, (size_t)r->N * sizeof *x);
        state_normalize(r->m, r->x, NULL);
    }
    r->jump_due = 1;
    return EOMC_OK;
}

void
eomc_step_eval(const eomc_step *d, double t, double *x)
{
    if (d->series && t != d->t1) { /* at t1 x1, projected or reset, as the rows take it */
        taylor_eval(d->series, t - d->t0, x);
        if (d->model)
            state_normalize(d->model, x, NULL);
        return;
    }
    dense_cubic(d->t0, d->t1, d->x0, d->f0, d->x1, d->f1, d->nx, t, x);
    if (d->model)
        state_normalize(d->model, x, NULL);
}
