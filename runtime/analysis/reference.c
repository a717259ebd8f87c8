/*
 * reference: the reference solution (eomc.h), computed in extended
 * precision by extrapolation (one read from a file: rows.c).
 *
 * The method.  Gragg-Bulirsch-Stoer extrapolation of order 16, or, when
 * the problem is stiff, the linearly implicit Euler method extrapolated
 * to order 8 (extrap.c has both).  The error estimate of a step (the
 * difference of its two highest extrapolations, the error of the lower
 * one) controls its size, so the value kept is better than the control
 * asks.  Nothing in it is one of the methods being judged (GSL's bsimp is
 * a semi-implicit extrapolation of the midpoint rule, in doubles, with
 * another sequence and control).
 *
 * Stiffness.  The first solution starts with GBS and, after every step it
 * accepts, estimates the spectral radius rho of the Jacobian df/dx
 * (extrap_spectral_radius, two right-hand sides).  When STIFF_STEPS
 * successive steps have H rho >= EXTRAP_GBS_STIFF, the steps are held by
 * stability, not accuracy (extrap.c): the problem is stiff.  The measure
 * is a ratio of times (H against 1 / rho), so it means the same in any
 * units; STIFF_STEPS successive steps, as Hairer's DOPRI5 asks, keep one
 * step's rough estimate from deciding.  The first solution is then
 * computed again, from the start, by the linearly implicit method, as
 * long as it spends less than 1 / LI_ADVANTAGE of what GBS would at the
 * pace of the steps held; if it does, every solution is made by it, and
 * if not (a problem stiff only mildly, or only for a while), GBS makes
 * them all, without watching.  The linearly implicit method's Jacobian is
 * taken by forward differences at the start of every step (the
 * extended-precision functions have no Jacobian; its accuracy decides
 * only the stability, extrap.c).
 *
 * The error test of a component is relative to its magnitude so far,
 * floored at FLOOR of its group's (coordinates, velocities), and below
 * that at the group's rounding (step_error): scaling the units of length
 * or time scales every test alike.
 *
 * The refinement.  Solutions are computed at the tolerances TOL_FIRST,
 * TOL_FIRST / TOL_STEP, ... until two successive ones agree to the
 * rounding of doubles (AGREE_ULPS at the trajectory's largest entry), or
 * a refinement needs STEP_GROWTH times the steps of the one before (the
 * step-size control then fights rounding, not truncation), or
 * MAX_SOLUTIONS were made.  The reference is the last one; its error
 * estimate is the last difference, which is the error of the solution
 * before it: the last one improves on it, so the estimate is cautious.
 * On chain5 (t = 0 .. 10, q1 = 1) the solutions at 1e-15, 1e-16, 1e-17
 * differ by 1.1e-14 and 8.9e-16, and those at 1e-17, 1e-18, 1e-19 agree
 * to the last bit of their doubles.
 *
 * Taylor's method (eomc_reference_compute_by, --reference-method taylor)
 * is the second way: the same refinements, each solution summed from the
 * twin's own Taylor series in extended precision (reftaylor.c), for a
 * reference that shares nothing with extrapolation but the model's
 * functions.  Two references made so independently agreeing is the
 * check of both (tests/sim/test_accuracy.c).
 *
 * The arithmetic.  Every right-hand side is the model's own functions
 * compiled in eomc_ext (eomc_model_ext): accel's unrolled solve, or M and
 * h with an LU solve; constrained models solve the KKT system (Newton's
 * method when a constraint is not affine in q'') whatever the doubles use.
 * GSL has no extended-precision linear algebra, hence linalg.c's la_ext.
 * A model whose speeds are not its coordinates' rates has its q' from the
 * twin's qdot, and its unit quaternions renormalized after every step and
 * in every row, in eomc_ext, as the double runs renormalize theirs.
 *
 * Switches (max, min, clamp, step: eomc_model.h's modes).  The modes
 * start as a run's do and are held through each step, in u[nu + k],
 * which the twin's functions read (the inputs fill only u[0 .. nu)); a
 * step whose end finds a switch function past 0 ends where it crossed,
 * located on side steps, and the switch flips there (refswitch.c).  The
 * flips of the solution kept are the reference's record, which a run's
 * are compared with (compare.h).
 */
#include "model/simimpl.h"
#include "model/state.h"
#include "extrap.h"
#include "model/linalg.h"
#include "reftaylor.h"
#include "refswitch.h"
#include "reffric.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    MAX_SOLUTIONS = 5,
    STEP_BUDGET = 2000000,   /* steps of the first solution before giving up */
    STEP_GROWTH = 8,      /* a refinement taking more times the steps than the
                           * solution before it is in rounding's realm: stop */
    SIDE_PIECES_MAX = 64, /* a side step is split at most this much */
    NEWTON_MAX = 50,
    STIFF_STEPS = 15,     /* successive GBS steps held by stability: stiff */
};
/* On a stiff problem the linearly implicit method replaces GBS only when
 * its first solution spends at most 1 / LI_ADVANTAGE of the right-hand
 * sides GBS would.  Its right-hand sides cost more: each step also
 * factors 8 matrices of order 2n and solves with them 51 times (4 times
 * GBS's time per right-hand side on the 2-state Van der Pol oscillator,
 * tests/sim/specs/van_der_pol.yaml).  And on a nonlinear stiff problem its
 * refinements cost more: its extrapolation loses order, and there all its
 * solutions took 42 times its first, GBS's 6.5 times.  4 x 6.5 = 26: with
 * eps = 1e-5 GBS's pace would spend 9.7 times its first solution's
 * right-hand sides, and GBS is the faster (1.7 s against 2.8 s); with
 * eps = 1e-6 61 times, and it is the slower (13.6 s against 9.9 s, with
 * an error estimate 14 times larger). */
#define LI_ADVANTAGE 25.0
#define TOL_FIRST 1e-15   /* relative tolerance of the first solution */
#define TOL_STEP 10.0     /* each refinement's tolerance is this much tighter */
/* Two solutions agree when they differ by at most this many units of
 * double rounding at the trajectory's largest entry: the rows are doubles,
 * and no reference of doubles is better than that. */
#define AGREE_ULPS 4.0
#define FLOOR 1e-6        /* a component's scale is at least this of its group's */
#define SAFETY 0.9        /* step-size control: aim below the tolerance */
#define GROW_MAX 4.0      /* ... and change the step by at most these factors */
#define SHRINK_MAX 0.2
#define HMIN_REL 1e-15    /* a step below this of the span makes no progress */
#define SIDE_SLACK 10.0   /* side_step's error test, in tolerances */

typedef struct Ref {
    eomc_sim *s;
    const eomc_model *m;
    const eomc_model_ext *x;
    int n, nv, N, nc, nu;         /* coordinates, speeds, N = n + nv, ... */
    eomc_ext *p, *u, *dudt;       /* [np], [nu], [nu] */
    eomc_ext *M, *h, *K, *r;      /* [nv*nv], [nv], [(nv+nc)^2], [nv+nc] */
    eomc_ext *f, *B, *a, *lam;    /* [nc], [nc*nv], [nv], [nc] */
    eomc_ext *cj[9];              /* c_jacobian's outputs; cj[6] is dBda */
    int *perm;                    /* [nv+nc] */
    eomc_ext *eq, *dK;            /* [2(nv+nc)] the LU's equilibration, [nv+nc] */
    int have_prev;                /* a and lam hold the last solution */
    eomc_ext *X, *F, *Xn;         /* [N] the state, x' there, the next state */
    eomc_ext *Fn, *Xh;            /* [N] x' at the next state, the state at a switch */
    eomc_ext *Y, *G, *Y2;         /* [N] side steps' state, x', result */
    eomc_ext *D;                  /* [N] a step's error estimate */
    eomc_ext *mag, *sc;           /* [N] the largest |X_i| so far, the scales */
    Extrap *ex;
    int method;                   /* EXTRAP_GBS or EXTRAP_LINEARLY_IMPLICIT */
    int detect;                   /* watch GBS's steps for stiffness */
    int held;                     /* successive steps held by stability */
    double held_t;                /* where the first of them started */
    long held_evals;              /* and the steps' right-hand sides before it */
    int stiff;                    /* GBS found the problem stiff */
    double stiff_t, stiff_hrho;   /* where the last step held ended, its H rho */
    double gbs_evals;             /* what GBS would spend on the first solution */
    double eval_budget;           /* right-hand sides a solution may spend */
    long li_evals;                /* what it spent on the first solution */
    int dearer;                   /* stiff, but the linearly implicit method was not
                                   * cheaper than GBS (-1: it failed) */
    double tol;
    eomc_ext span;                /* the run's, t_end - t0 (0: none) */
    long steps, evals, side_evals; /* evals: all right-hand sides; side_evals:
                                    * the rows' side steps' (stepping) */
    double fail_t, *fail_x;       /* where a right-hand side failed [N], then
                                   * room for the doubles' q'' there [nv] */
    RefTaylor *rt;                /* Taylor's method makes the solutions, or NULL */
    RefSwitches *sw;              /* the switches (modes at u[nu + k]), or NULL */
    RefFric *fr;                  /* dry friction's stuck speeds, or NULL */
    int bad_switch;               /* the one a solution could not follow */
    /* a sampled controller (eomc_sim_set_controller): its period (0:
     * none), the inputs it drives, the next sample t0 + k_sample period,
     * the state rounded to doubles it is called with [N] and its outputs
     * [nu], held (have_cu) until the next sample; its failure's status */
    double period;
    const unsigned char *drives;
    long k_sample;
    eomc_ext t_sample;
    double *cx, *cu;
    int have_cu, ctrl_status;
} Ref;

/* The model's inputs at t into r->u, held ones as the doubles hold them. */
static void
inputs_at(Ref *r, eomc_ext t)
{
    if (r->nu == 0)
        return;
    r->x->inputs(t, r->p, r->u, r->dudt);
    for (int k = 0; k < r->nu; k++) {
        double held;
        if (eomc_sim_input_held(r->s, k, &held))
            r->u[k] = held;
        if (r->have_cu && r->drives[k])
            r->u[k] = r->cu[k];
    }
}

/* The sample after the one at r->t_sample, at the doubles' instant of it
 * (none near t_end: evolve.c's next_sample). */
static void
next_sample(Ref *r, const eomc_run_opts *o)
{
    double t = o->t0 + (double)++r->k_sample * r->period;
    r->t_sample = t > o->t_end - SIM_SAMPLE_AT_END_REL * r->period ? INFINITY : t;
}

/* The sampled controller's call at (t, X), X rounded to doubles as the
 * doubles' run would hand it its state, with the inputs' own values
 * there: its outputs held from here (inputs_at).  0, or -7 when it
 * fails (r->ctrl_status, the message set). */
static int
sample(Ref *r, eomc_ext t, const eomc_ext *X)
{
    r->have_cu = 0;
    inputs_at(r, t);
    for (int i = 0; i < r->N; i++)
        r->cx[i] = (double)X[i];
    for (int k = 0; k < r->nu; k++)
        r->cu[k] = (double)r->u[k];
    if ((r->ctrl_status = sim_control_call(r->s, (double)t, r->cx, r->cu)) != EOMC_OK)
        return -7;
    r->have_cu = 1;
    return 0;
}

/* q'' = -M^-1 h for an unconstrained model, the speeds dry friction
 * holds held (reffric.h, the bounds checked either way); 0 or -1. */
static int
accel_free(Ref *r, eomc_ext t, const eomc_ext *q, const eomc_ext *v, eomc_ext *a)
{
    int n = r->nv;
    if (r->fr && reffric_any(r->fr, r->u))
        return reffric_solve(r->fr, t, q, v, r->p, r->u, a) == STICK_OK ? 0 : -1;
    if (r->fr && reffric_bounds(r->fr, t, q, v, r->p, r->u) != STICK_OK)
        return -1;
    if (r->x->accel)
        return r->x->accel(t, q, v, r->p, r->u, a, NULL) == 0 ? 0 : -1;
    r->x->mass_bias(t, q, v, r->p, r->u, r->M, a);
    if (la_ext_lu_factor(r->M, n, r->perm, r->eq, NULL) != 0)
        return -1;
    la_ext_lu_solve(r->M, n, r->perm, r->eq, a);
    for (int i = 0; i < n; i++)
        a[i] = -a[i];
    return 0;
}

/* One Newton step on M a + h + B^T lam = 0, f = 0 at (r->a, r->lam);
 * the largest relative change, or -1 when the KKT matrix is singular. */
static eomc_ext
kkt_step(Ref *r, eomc_ext t, const eomc_ext *q, const eomc_ext *v)
{
    int n = r->nv, nc = r->nc, W = n + nc, affine = r->m->c_affine;
    /* the rows the doubles leave out, left out here too (kkt.c) */
    const unsigned char *drop = sim_dropped_rows(r->s);
    r->x->constraint(t, q, v, r->a, r->p, r->u, r->f, r->B);
    eomc_ext **c = r->cj, *dBda = c[6];
    if (!affine)
        r->x->c_jacobian(t, q, v, r->a, r->p, r->u, c[0], c[1], c[2], c[3], c[4], c[5],
                         c[6], c[7], c[8]);
    for (int i = 0; i < n; i++) {
        eomc_ext e = r->h[i];
        for (int j = 0; j < n; j++) {
            eomc_ext k = r->M[i * n + j];
            for (int c = 0; !affine && c < nc; c++)
                k += r->lam[c] * dBda[(c * n + i) * n + j];
            r->K[i * W + j] = k;
            e += r->M[i * n + j] * r->a[j];
        }
        for (int c = 0; c < nc; c++) {
            r->K[i * W + n + c] = r->K[(n + c) * W + i] = drop && drop[c] ? 0 : r->B[c * n + i];
            e += r->B[c * n + i] * r->lam[c];
        }
        r->r[i] = -e;
    }
    for (int c = 0; c < nc; c++) {
        for (int d = 0; d < nc; d++)
            r->K[(n + c) * W + n + d] = c == d && drop && drop[c];
        r->r[n + c] = drop && drop[c] ? 0 : -r->f[c];
    }
    la_ext_kkt_scaling(r->K, n, nc, r->dK);
    if (la_ext_lu_factor(r->K, W, r->perm, r->eq, r->dK) != 0)
        return -1;
    la_ext_lu_solve(r->K, W, r->perm, r->eq, r->r);
    eomc_ext change[2] = {0, 0}, size[2] = {0, 0};
    for (int i = 0; i < W; i++) {
        eomc_ext *y = i < n ? &r->a[i] : &r->lam[i - n];
        *y += r->r[i];
        change[i >= n] = fmaxl(change[i >= n], fabsl(r->r[i]));
        size[i >= n] = fmaxl(size[i >= n], fabsl(*y));
    }
    /* relative, q'' and lambda apart (their units differ) */
    return fmaxl(size[0] > 0 ? change[0] / size[0] : change[0],
                 size[1] > 0 ? change[1] / size[1] : change[1]);
}

/* q'' of a constrained model: the KKT system, one solve when affine in
 * q'', else Newton's method from the last solution until its relative
 * steps reach rounding, or stop shrinking below NEWTON_LOOSE (they can go
 * no further: quadratic convergence would have taken the next one to
 * rounding).  Far from the solution the steps may grow for a while (the
 * cubic constraint from rest: 1, 0.54, 0.76, 1.8, then 0.10, 7e-5, 6e-11,
 * 4e-20), which is no stall.  0, or -1 when singular or not converging. */
#define NEWTON_LOOSE 1e-10L
static int
accel_kkt(Ref *r, eomc_ext t, const eomc_ext *q, const eomc_ext *v, eomc_ext *a)
{
    int n = r->nv, nc = r->nc;
    r->x->mass_bias(t, q, v, r->p, r->u, r->M, r->h);
    if (r->m->c_affine || !r->have_prev) {
        memset(r->a, 0, (size_t)n * sizeof *r->a);
        memset(r->lam, 0, (size_t)nc * sizeof *r->lam);
    }
    int done = r->m->c_affine;
    eomc_ext last = INFINITY, d;
    for (int it = 0; it < NEWTON_MAX; it++) {
        if ((d = kkt_step(r, t, q, v)) < 0)
            return -1;
        if (done || d <= 16 * LDBL_EPSILON || (it > 2 && d >= last && d <= NEWTON_LOOSE)) {
            done = 1;
            break;
        }
        last = d;
    }
    if (!done)
        return -1;
    r->have_prev = 1;
    memcpy(a, r->a, (size_t)n * sizeof *a);
    return 0;
}

/* F = (q', v') at (t, X); -1 (r->fail_t set) when the model fails there. */
static int
rhs(Ref *r, eomc_ext t, const eomc_ext *X, eomc_ext *F)
{
    int n = r->n;
    r->evals++;
    inputs_at(r, t);
    if (r->m->nv > 0)
        r->x->qdot(X, X + n, F);
    else
        memcpy(F, X + n, (size_t)n * sizeof *F);
    int rc = r->nc ? accel_kkt(r, t, X, X + n, F + n) : accel_free(r, t, X, X + n, F + n);
    for (int i = 0; rc == 0 && i < r->N; i++)
        if (!isfinite(F[i]))
            rc = -1;
    if (rc) {
        r->fail_t = (double)t;
        for (int i = 0; i < r->N; i++)
            r->fail_x[i] = (double)X[i];
    }
    return rc;
}

/* rhs as extrap.c calls it. */
static int
ext_rhs(void *ctx, eomc_ext t, const eomc_ext *X, eomc_ext *F)
{
    return rhs(ctx, t, X, F);
}

/* The error of a step ending at x with estimate d, in tolerances: each
 * component's |d_i| against tol times its magnitude over the solution so
 * far, the step's end included; a component within FLOOR of its group's
 * (coordinates, velocities; the end included again; or of its rounding
 * scale, below) against tol FLOOR of it, or one rounding of it in eomc_ext
 * where that is more.
 *  - The end counts for the group: at a start from rest every velocity
 *    is 0 so far, and a q'' that is 0 in exact arithmetic (of a body
 *    symmetric about a plane, of a finger coupled to another) comes out
 *    as rounding (1e-17 to 1e-40), which against a scale of 0, or its own
 *    size, is an error of any size: no step could be taken.  The first
 *    step's own motion gives the group its scale.
 *  - tol FLOOR is 1e-21 of the group at the first tolerance, below long
 *    double's resolution.  Such a component is the rounding of the
 *    group's terms (a ball joint's quaternion rates on a falling base),
 *    and judged finer than that the steps were held by rounding, not
 *    truncation (2890 steps of a rigid fall where 111 do,
 *    tests/cli/rest_biped.xml), or no refinement could be made at all.
 *    The others keep tol alone: long double resolves more than its
 *    rounding of the group in a component of the group's size (the
 *    Arenstorf orbit's reference at 1e-19 is 6.8e-15 from Taylor's; with
 *    every component held to the group's rounding, 4.8e-13).
 *  - A group's scale is at least the other group's carried over the
 *    span: velocities off by LDBL_EPSILON of the coordinates' size over
 *    the span move them by a rounding of theirs, coordinates off by
 *    LDBL_EPSILON of the velocities' size times the span are a rounding
 *    of what they move.  A box at rest on its floor has
 *    velocities of rounding alone (its depth's, in doubles, an
 *    oscillation of 1e-19 m/s), which held against their own size held
 *    the reference's steps at 1e-12 s: --error never ended. */
static double
step_error(const Ref *r, const eomc_ext *x, const eomc_ext *d)
{
    int n = r->n;
    eomc_ext group[2] = {0, 0}, worst = 0;
    for (int i = 0; i < r->N; i++)
        group[i >= n] = fmaxl(group[i >= n], fmaxl(r->mag[i], fabsl(x[i])));
    eomc_ext round[2] = {group[0], group[1]};
    if (r->span > 0 && r->nv > 0) {
        round[0] = fmaxl(round[0], group[1] * r->span);
        round[1] = fmaxl(round[1], group[0] / r->span);
    }
    for (int i = 0; i < r->N; i++) {
        eomc_ext own = fmaxl(r->mag[i], fabsl(x[i])), least = FLOOR * round[i >= n];
        eomc_ext allowed = own > least ? r->tol * own
                                       : fmaxl(r->tol * least, LDBL_EPSILON * round[i >= n]);
        if (d[i] != 0)
            worst = fmaxl(worst, allowed > 0 ? fabsl(d[i]) / allowed : INFINITY);
    }
    return (double)worst;
}

/* The state at t1 inside an accepted step from (t, r->X): a step of its
 * own from there, leaving the main steps as they are.  Being part of an
 * accepted step, its truncation error is smaller than the step's (the
 * error expansion goes in powers of its size); at tolerances near the
 * rounding level its estimate can still exceed the tolerance by rounding
 * alone, so it is split (2, 4, ... equal pieces) only when the estimate
 * passes SIDE_SLACK times the tolerance.  0 or -1. */
static int
side_step(Ref *r, eomc_ext t, eomc_ext t1, eomc_ext *out)
{
    int N = r->N;
    for (int pieces = 1; pieces <= SIDE_PIECES_MAX; pieces *= 2) {
        eomc_ext h = (t1 - t) / pieces;
        memcpy(r->Y, r->X, (size_t)N * sizeof *r->Y);
        memcpy(r->G, r->F, (size_t)N * sizeof *r->G);
        int p = 0;
        for (; p < pieces; p++) {
            if ((p > 0 && rhs(r, t + p * h, r->Y, r->G) != 0) ||
                extrap_step(r->ex, r->method, t + p * h, h, r->Y, r->G, r->Y, r->D) != 0 ||
                !(step_error(r, r->Y, r->D) <= SIDE_SLACK))
                break;
        }
        if (p == pieces) {
            memcpy(out, r->Y, (size_t)N * sizeof *out);
            return 0;
        }
    }
    r->fail_t = (double)t;
    for (int i = 0; i < N; i++)
        r->fail_x[i] = (double)r->X[i];
    return -1;
}

/* Each component's scale for the difference quotients (the Jacobian, the
 * spectral radius) and Taylor's step rule: its largest magnitude so far,
 * at least FLOOR of its group's; 0 for a group still at 0 (extrap.c then
 * takes another's). */
static void
scales(Ref *r)
{
    int n = r->n;
    eomc_ext group[2] = {0, 0};
    for (int i = 0; i < r->N; i++)
        group[i >= n] = fmaxl(group[i >= n], r->mag[i]);
    for (int i = 0; i < r->N; i++)
        r->sc[i] = fmaxl(r->mag[i], FLOOR * group[i >= n]);
}

/* The right-hand sides of the steps so far, those of the rows' side
 * steps apart: the methods are compared by them, as both pay for the rows
 * alike. */
static long
stepping(const Ref *r)
{
    return r->evals - r->side_evals;
}

/* Whether GBS's steps are held by stability, after a step of size H
 * from t0 to (t, r->X), with r->F there and e0 right-hand sides spent by
 * the steps before it.  A failed estimate (the model failing a little off
 * the solution) counts as not held.  When the problem is found stiff,
 * what GBS would spend on the whole span, at the rate of the steps held. */
static int
held_by_stability(Ref *r, eomc_ext t0, eomc_ext t, eomc_ext H, long e0, eomc_ext t_end)
{
    double rho;
    if (extrap_spectral_radius(r->ex, t, r->X, r->F, r->sc, &rho) != 0)
        rho = 0;
    if (!((double)H * rho >= EXTRAP_GBS_STIFF)) {
        r->held = 0;
        return 0;
    }
    if (r->held++ == 0) /* the first of them */
        r->held_t = (double)t0, r->held_evals = e0;
    if (r->held < STIFF_STEPS)
        return 0;
    r->stiff = 1;
    r->stiff_t = (double)t;
    r->stiff_hrho = (double)H * rho;
    double rate = (double)(stepping(r) - r->held_evals) / ((double)t - r->held_t);
    r->gbs_evals = (double)stepping(r) + rate * (double)(t_end - t);
    return 1;
}

/* status, the solution having stopped at (t, x) */
static int
fail_at(Ref *r, eomc_ext t, const eomc_ext *x, int status)
{
    r->fail_t = (double)t;
    for (int i = 0; i < r->N; i++)
        r->fail_x[i] = (double)x[i];
    return status;
}

/* A solution's first sample, at t0 (none without a sampled controller:
 * no sample is ever due); 0 or -7. */
static int
first_sample(Ref *r, const eomc_run_opts *o)
{
    r->have_cu = 0;
    r->k_sample = 0;
    r->t_sample = INFINITY;
    if (!(r->period > 0))
        return 0;
    if (sample(r, o->t0, r->X) != 0)
        return -7;
    next_sample(r, o);
    return 0;
}

/* One solution at tolerance r->tol: the rows [nrows * N] (doubles).
 * The steps go as the tolerance allows, not to the output times, so that
 * rounding accumulates over as few of them as it can; an output time
 * inside a step gets a side step from the step's start (with the
 * linearly implicit method, from its Jacobian there too).  0, -1 when the
 * model fails or the steps become too small, -2 over the step budget, -3
 * when GBS finds the problem stiff (r->detect), -4 over r->eval_budget,
 * -5 when switch r->bad_switch chatters, -6 when it starts on its kink
 * and neither mode leaves it. */
static int
solve(Ref *r, const eomc_run_opts *o, const double *x0, double *rows, long budget)
{
    int N = r->N, implicit = r->method == EXTRAP_LINEARLY_IMPLICIT;
    int need_jacobian = implicit;
    long nrows = eomc_run_rows(o), k = 1, e0 = 0; /* e0: right-hand sides before a step */
    memcpy(rows, x0, (size_t)N * sizeof *rows);
    state_normalize(r->m, rows, NULL); /* the start of eomc_sim_integrate's run */
    for (int i = 0; i < N; i++) {
        r->X[i] = rows[i];
        r->mag[i] = fabsl(r->X[i]);
    }
    scales(r);
    r->have_prev = 0;
    r->held = 0;
    r->steps = r->evals = r->side_evals = 0;
    eomc_ext t = o->t0, t_end = o->t_end, span = t_end - t, H = span / 100;
    if (first_sample(r, o) != 0)
        return fail_at(r, t, r->X, -7);
    int st = r->sw ? refsw_start(r->sw, r->X, &r->bad_switch) : 0;
    if (st != 0)
        return fail_at(r, t, r->X, st == -2 ? -6 : -1);
    if (nrows > 1 && rhs(r, t, r->X, r->F) != 0)
        return -1;
    while (t < t_end) {
        if (r->steps >= budget)
            return -2;
        if (stepping(r) > r->eval_budget)
            return -4;
        if (need_jacobian && extrap_jacobian(r->ex, t, r->X, r->F, r->sc) != 0)
            return -1;
        need_jacobian = 0;
        /* (steps end at the controller's samples as at t_end) */
        eomc_ext stop = fminl(r->t_sample, t_end), left = stop - t;
        eomc_ext step = H >= left ? left : 2 * H > left ? left / 2 : H;
        double err = INFINITY; /* a stage failed: a smaller step may not */
        if (extrap_step(r->ex, r->method, t, step, r->X, r->F, r->Xn, r->D) == 0)
            err = step_error(r, r->Xn, r->D);
        double fac = err > 0 ? SAFETY * pow(err, -1.0 / extrap_error_order(r->method))
                             : GROW_MAX;
        fac = fmin(GROW_MAX, fmax(SHRINK_MAX, fac));
        if (!(err <= 1.0)) {
            H = step * (isfinite(err) ? fac : 0.5);
            if (!(t + H > t) || H < HMIN_REL * span) {
                r->fail_t = (double)t;
                for (int i = 0; i < N; i++)
                    r->fail_x[i] = (double)r->X[i];
                return -1;
            }
            continue;
        }
        eomc_ext t1 = step == left ? stop : t + step, t0 = t;
        /* the unit quaternions back to length 1, as the doubles' steps do */
        state_normalize_ext(r->m, r->Xn);
        /* a switch crossed in the step: it ends there (rows before it
         * from side steps, as any) */
        int hit = 0;
        if (r->sw && (rhs(r, t1, r->Xn, r->Fn) != 0 ||
                      (hit = refsw_check(r->sw, t, r->X, r->F, t1, r->Xn, r->Fn, &t1,
                                         r->Xh)) < 0))
            return -1;
        if (hit) {
            memcpy(r->Xn, r->Xh, (size_t)N * sizeof *r->Xn);
            state_normalize_ext(r->m, r->Xn);
        }
        for (; k < nrows && eomc_run_row_time(o, k) <= t1; k++) {
            eomc_ext tk = eomc_run_row_time(o, k), *x = r->Xn;
            long before = r->evals;
            if (tk != t1 && side_step(r, t, tk, x = r->Y2) != 0)
                return -1;
            state_normalize_ext(r->m, x); /* as the step's end, below */
            r->side_evals += r->evals - before;
            for (int i = 0; i < N; i++)
                rows[(size_t)k * N + i] = (double)x[i];
        }
        memcpy(r->X, r->Xn, (size_t)N * sizeof *r->X);
        t = t1;
        r->steps++;
        for (int i = 0; i < N; i++)
            r->mag[i] = fmaxl(r->mag[i], fabsl(r->X[i]));
        scales(r);
        if (hit && (st = refsw_flip(r->sw, t, r->X, r->sc, &r->bad_switch)) != 0)
            return fail_at(r, t, r->X, st == -2 ? -5 : -1);
        int sampled = !hit && t == r->t_sample; /* new inputs: x' again, below */
        if (sampled) {
            if (sample(r, t, r->X) != 0)
                return fail_at(r, t, r->X, -7);
            next_sample(r, o);
            /* the switches the new inputs moved past their kinks flip
             * here, as the runs' do (stepevents.c's stepev_jump) */
            if (r->sw && (st = refsw_jump(r->sw, t, r->X, r->sc, &r->bad_switch)) != 0)
                return fail_at(r, t, r->X, st == -2 ? -5 : -1);
        }
        if (r->sw && !hit && !sampled) /* the end's, in the same modes */
            memcpy(r->F, r->Fn, (size_t)N * sizeof *r->F);
        else if (rhs(r, t, r->X, r->F) != 0)
            return -1;
        eomc_ext taken = hit ? t - t0 : step; /* (a step ended at a switch is shorter) */
        if (r->detect && !implicit && held_by_stability(r, t0, t, taken, e0, t_end))
            return -3;
        e0 = stepping(r);
        need_jacobian = implicit;
        H = step * fac;
    }
    return 0;
}

/* A solution by Taylor's method (reftaylor.h) at r->tol, as solve's:
 * rows at o's output times off each step's polynomial.  0; -1 where the
 * series fails or the steps become too small (r->fail_t, r->fail_x); -2
 * after budget steps. */
static int
solve_taylor(Ref *r, const eomc_run_opts *o, const double *x0, double *rows, long budget)
{
    int N = r->N;
    long nrows = eomc_run_rows(o), k = 1;
    memcpy(rows, x0, (size_t)N * sizeof *rows);
    state_normalize(r->m, rows, NULL); /* the start of eomc_sim_integrate's run */
    for (int i = 0; i < N; i++) {
        r->X[i] = rows[i];
        r->mag[i] = fabsl(r->X[i]);
    }
    scales(r);
    r->steps = r->evals = r->side_evals = 0;
    eomc_ext t = o->t0, t_end = o->t_end, span = t_end - t;
    if (first_sample(r, o) != 0)
        return fail_at(r, t, r->X, -7);
    while (t < t_end) {
        if (r->steps >= budget)
            return -2;
        inputs_at(r, t);
        eomc_ext stop = fminl(r->t_sample, t_end), left = stop - t, h;
        r->evals++;
        if (reftaylor_series(r->rt, t, r->X, r->p, r->u, r->tol, r->sc, left, &h) != 0 ||
            !(h > HMIN_REL * span)) {
            r->fail_t = (double)t;
            for (int i = 0; i < N; i++)
                r->fail_x[i] = (double)r->X[i];
            return -1;
        }
        eomc_ext step = h >= left ? left : 2 * h > left ? left / 2 : h;
        eomc_ext t1 = step == left ? stop : t + step;
        /* the unit quaternions back to length 1, in every row and at the
         * step's end, as the doubles' steps do */
        for (; k < nrows && eomc_run_row_time(o, k) <= t1; k++) {
            reftaylor_eval(r->rt, eomc_run_row_time(o, k) - t, r->Y2);
            state_normalize_ext(r->m, r->Y2);
            for (int i = 0; i < N; i++)
                rows[(size_t)k * N + i] = (double)r->Y2[i];
        }
        reftaylor_eval(r->rt, step, r->X);
        state_normalize_ext(r->m, r->X);
        t = t1;
        r->steps++;
        if (t == r->t_sample) {
            if (sample(r, t, r->X) != 0)
                return fail_at(r, t, r->X, -7);
            next_sample(r, o);
        }
        for (int i = 0; i < N; i++)
            r->mag[i] = fmaxl(r->mag[i], fabsl(r->X[i]));
        scales(r);
    }
    return 0;
}

static void
ref_free(Ref *r)
{
    eomc_ext *arrays[] = {r->p, r->u, r->dudt, r->M,      r->h, r->K, r->r,  r->f,
                          r->B, r->a, r->lam,  r->cj[0], r->X, r->F, r->Xn, r->Y,
                          r->G, r->Y2, r->mag, r->sc,    r->eq, r->dK, r->D, r->Fn,
                          r->Xh};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    reffric_free(r->fr);
    free(r->perm);
    free(r->fail_x);
    free(r->cx);
    free(r->cu);
    extrap_free(r->ex);
    reftaylor_free(r->rt);
    refsw_free(r->sw);
}

static eomc_ext *
ext_zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(eomc_ext));
}

/* The motion as refswitch.c sees it: a side step, x', the switch
 * functions in the modes held. */
static int
sw_state(void *ctx, eomc_ext t0, eomc_ext t, eomc_ext *x)
{
    return side_step(ctx, t0, t, x);
}

static int
sw_rate(void *ctx, eomc_ext t, const eomc_ext *x, eomc_ext *f)
{
    return rhs(ctx, t, x, f);
}

static void
sw_functions(void *ctx, eomc_ext t, const eomc_ext *x, eomc_ext *s)
{
    Ref *r = ctx;
    inputs_at(r, t);
    r->x->switches(t, x, x + r->n, r->p, r->u, s);
    if (r->fr) /* the stick switches' (NAN where the holding forces fail) */
        (void)reffric_functions(r->fr, t, x, x + r->n, r->p, r->u, s);
}

static int
sw_held(void *ctx, int k)
{
    Ref *r = ctx;
    return reffric_item_stick(r->fr, k) >= 0;
}

static int
sw_friction(void *ctx, int k)
{
    const eomc_model *m = ((Ref *)ctx)->m;
    for (int j = 0; j < m->nfric; j++)
        if (m->fric_slip[j] == k || m->fric_stick[j] == k)
            return 1;
    return 0;
}

static int
sw_settle(void *ctx, eomc_ext t, const eomc_ext *x)
{
    Ref *r = ctx;
    inputs_at(r, t);
    return reffric_settle(r->fr, t, x, x + r->n, r->p, r->u) == STICK_OK ? 0 : -1;
}

static int
sw_flip(void *ctx, int k, int on, eomc_ext t, eomc_ext *x)
{
    Ref *r = ctx;
    inputs_at(r, t);
    return reffric_flip(r->fr, k, on, t, x, x + r->n, r->p, r->u) == STICK_OK ? 0
                                                                                   : -1;
}

/* For s's model with twin x, runs over o's span (NULL: none, a state
 * alone); 0, or -1 when memory runs out. */
static int
ref_alloc(Ref *r, eomc_sim *s, const eomc_model_ext *x, const eomc_run_opts *o)
{
    const eomc_model *m = eomc_sim_model(s);
    size_t nq = (size_t)m->nq, n = (size_t)eomc_nv(m), nc = (size_t)m->nc;
    size_t nu = (size_t)m->nu, W = n + nc, N = nq + n;
    *r = (Ref){.s = s, .m = m, .x = x, .n = m->nq, .nv = (int)n, .N = (int)N, .nc = m->nc,
               .nu = m->nu};
    /* c_jacobian's nine outputs in one block (n: the speeds): dfdq [nc
     * nq], dfdv [nc n], dfdu [nc nu], dfdt [nc], dBdq [nc n nq], dBdv,
     * dBda [nc n n], dBdu [nc n nu], dBdt [nc n] */
    size_t cj[9] = {nc * nq, nc * n, nc * nu, nc, nc * n * nq, nc * n * n, nc * n * n,
                    nc * n * nu, nc * n}, ncj = 0;
    for (int k = 0; k < 9; k++)
        ncj += cj[k];
    eomc_ext **arrays[] = {&r->p, &r->u, &r->dudt, &r->M,      &r->h, &r->K, &r->r,
                           &r->f, &r->B, &r->a,    &r->lam,    &r->cj[0], &r->X, &r->F,
                           &r->Xn, &r->Y, &r->G,   &r->Y2,     &r->mag, &r->sc, &r->eq,
                           &r->dK, &r->D, &r->Fn, &r->Xh};
    /* u: the inputs, then the modes (eomc_model.h) */
    size_t sizes[] = {(size_t)(m->np + m->nd), nu + (size_t)m->nmode, nu, n * n, n, W * W, W,
                      nc, nc * n, n, nc, ncj, N, N,
                      N, N, N, N, N, N, 2 * W,
                      W, N, N, N};
    int ok = 1;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        ok &= (*arrays[k] = ext_zeros(sizes[k])) != NULL;
    ok &= (r->perm = calloc(W, sizeof *r->perm)) != NULL;
    ok &= (r->fail_x = calloc(N + n, sizeof *r->fail_x)) != NULL;
    ok &= (r->cx = calloc(N, sizeof *r->cx)) != NULL;
    ok &= (r->cu = calloc(nu + 1, sizeof *r->cu)) != NULL;
    r->period = fmax(sim_control_period(s), 0);
    r->drives = sim_control_drives(s);
    ok &= (r->ex = extrap_alloc(r->N, ext_rhs, r)) != NULL;
    if (ok && m->nfric > 0)
        ok &= (r->fr = reffric_alloc(m, x)) != NULL;
    if (o)
        r->span = (eomc_ext)o->t_end - (eomc_ext)o->t0;
    if (ok && r->fr && o)
        reffric_span(r->fr, r->span);
    if (ok && m->nmode > 0) {
        RefSwMotion mo = {.ctx = r, .state = sw_state, .rate = sw_rate,
                          .functions = sw_functions};
        if (r->fr)
            mo.held = sw_held, mo.settle = sw_settle, mo.flip = sw_flip,
            mo.friction = sw_friction;
        ok &= (r->sw = refsw_alloc(m->nmode, r->N, r->u + nu, mo, o ? o->t0 : 0,
                                   o ? o->t_end : 0)) != NULL;
    }
    if (!ok)
        return -1;
    for (int k = 1; k < 9; k++)
        r->cj[k] = r->cj[k - 1] + cj[k - 1];
    for (int k = 0; k < m->np; k++)
        r->p[k] = eomc_sim_params(s)[k];
    if (r->x->derive) /* in extended precision too */
        r->x->derive(r->p, r->p + m->np);
    return 0;
}

static const char *
method_name(const Ref *r)
{
    return r->rt ? "Taylor's method"
           : r->method == EXTRAP_GBS ? "Gragg-Bulirsch-Stoer extrapolation"
                                     : "linearly implicit Euler extrapolation";
}

/* Why a solution stopped (solve's -1: the model failed at r->fail_x, or
 * the steps became too small; -2: too many steps; -5, -6: a switch it
 * cannot follow, as a run cannot): the doubles' own message where their
 * solve fails at that state too. */
static int
failure(Ref *r, int st)
{
    eomc_sim *s = r->s;
    const double *x = r->fail_x;
    char name[STATE_NAME_MAX];
    if (st == -5 || st == -6)
        state_switch_name(r->m, r->bad_switch, name, sizeof name);
    if (st == -5)
        return sim_numeric_error(s, r->fail_t, x, x + r->n, "the reference solution (%s) "
                                 "cannot follow %s: it flips %d times in a row, each within "
                                 "%g of the time span after the one before (it chatters: "
                                 "the motion slides along its kink, which no mode "
                                 "follows)", method_name(r), name, STEPEV_CHATTER_FLIPS,
                                 STEPEV_ACCUMULATE_REL);
    if (st == -6)
        return sim_numeric_error(s, r->fail_t, x, x + r->n, "%s starts on its kink (its "
                                 "function is 0) and neither mode leaves it: the motion "
                                 "would slide along it, which no mode follows", name);
    if (st == -7) /* the controller's, said by sim_control_call */
        return r->ctrl_status;
    if (st == -2)
        return sim_numeric_error(s, r->fail_t, NULL, NULL, "the reference solution (%s) "
                                 "took more than %d steps at tolerance %.0e",
                                 method_name(r), STEP_BUDGET, r->tol);
    if (eomc_sim_accel(s, r->fail_t, x, x + r->n, r->fail_x + r->N) != EOMC_OK)
        return EOMC_ENUMERIC; /* that message says why */
    return sim_numeric_error(s, r->fail_t, x, x + r->n, "the reference solution (%s) "
                             "cannot be continued here at tolerance %.0e: the model "
                             "fails in extended precision, or its steps became too "
                             "small", method_name(r), r->tol);
}

/* Why the method is what it is, once the problem was found stiff. */
static void
stiff_note(const Ref *r, char *buf, size_t len)
{
    const char *li = "linearly implicit Euler extrapolation";
    int at = snprintf(buf, len, "; the problem is stiff: from t = %.4g to %.4g, %d steps "
                      "of Gragg-Bulirsch-Stoer extrapolation were held by stability (up "
                      "to %.3g times the inverse of the Jacobian's spectral radius, where "
                      "accuracy alone holds them below %.3g), a pace that would spend "
                      "%.3g right-hand sides on the first solution", r->held_t,
                      r->stiff_t, STIFF_STEPS, r->stiff_hrho, EXTRAP_GBS_STIFF,
                      r->gbs_evals);
    if (at < 0 || (size_t)at >= len)
        return;
    buf += at, len -= (size_t)at;
    if (r->dearer == 0)
        snprintf(buf, len, "; the %s spent %ld", li, r->li_evals);
    else if (r->dearer > 0)
        snprintf(buf, len, "; the %s would have spent more than 1/%.0f of that, the "
                 "least it must save to pay (it was stopped)", li, LI_ADVANTAGE);
    else
        snprintf(buf, len, "; the %s failed", li);
}

/* The largest |a_i - b_i|. */
static double
max_diff(const double *a, const double *b, size_t n)
{
    double d = 0;
    for (size_t i = 0; i < n; i++)
        d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

/* The flips of the solution just made, its record, into ref; 0, or -1
 * when memory runs out. */
static int
keep_switches(eomc_reference *ref, const Ref *r)
{
    if (!r->sw)
        return 0;
    long n = refsw_count(r->sw);
    size_t N = (size_t)r->N, k = (size_t)(n > 0 ? n : 1);
    free(ref->sw_t);
    free(ref->sw_k);
    free(ref->sw_sens);
    free(ref->sw_x);
    free(ref->sw_f);
    ref->nswitch = 0;
    ref->sw_t = malloc(k * sizeof *ref->sw_t);
    ref->sw_k = malloc(k * sizeof *ref->sw_k);
    ref->sw_sens = malloc(k * N * sizeof *ref->sw_sens);
    ref->sw_x = malloc(k * N * sizeof *ref->sw_x);
    ref->sw_f = malloc(k * N * sizeof *ref->sw_f);
    if (!ref->sw_t || !ref->sw_k || !ref->sw_sens || !ref->sw_x || !ref->sw_f)
        return -1;
    ref->nswitch = n;
    if (n == 0) /* refsw's arrays may be NULL then, which memcpy may not take */
        return 0;
    memcpy(ref->sw_t, refsw_times(r->sw), (size_t)n * sizeof *ref->sw_t);
    memcpy(ref->sw_k, refsw_which(r->sw), (size_t)n * sizeof *ref->sw_k);
    memcpy(ref->sw_sens, refsw_sens(r->sw), (size_t)n * N * sizeof *ref->sw_sens);
    memcpy(ref->sw_x, refsw_states(r->sw), (size_t)n * N * sizeof *ref->sw_x);
    memcpy(ref->sw_f, refsw_rates(r->sw), (size_t)n * N * sizeof *ref->sw_f);
    return 0;
}

/* EOMC_OK when ext is this model's twin with what a solve needs, else
 * the usage error saying so (what: what it would compute). */
static int
twin_fits(eomc_sim *s, const eomc_model_ext *ext, const char *what)
{
    const eomc_model *m = eomc_sim_model(s);
    if (!ext || ext->abi != EOMC_ABI_VERSION || !ext->name || strcmp(ext->name, m->name))
        return sim_usage_error(s, "no extended-precision functions of %s to compute %s "
                               "with (the model's C compiled again with -DEOMC_EXTENDED, "
                               "as eomc build does)", m->name, what);
    if (m->nmode > 0 && !ext->switches)
        return sim_usage_error(s, "the extended-precision functions of %s lack switches, "
                               "its switch functions", m->name);
    if (m->nfric > 0 && !ext->fric_bound)
        return sim_usage_error(s, "the extended-precision functions of %s lack fric_bound, "
                               "its dry friction's forces", m->name);
    if (m->nc && !m->c_affine && !ext->c_jacobian)
        return sim_usage_error(s, "the extended-precision functions of %s lack "
                               "c_jacobian", m->name);
    if (m->nv > 0 && !ext->qdot)
        return sim_usage_error(s, "the extended-precision functions of %s lack qdot, its "
                               "kinematic equation q' = W(q) v", m->name);
    return EOMC_OK;
}

/* EOMC_OK when the twin can make the reference by Taylor's method, else
 * the usage error saying why not. */
static int
taylor_fits(eomc_sim *s, const eomc_model_ext *ext)
{
    const eomc_model *m = eomc_sim_model(s);
    if (!ext->taylor)
        return sim_usage_error(s, "--reference-method taylor: %s has no Taylor series: %s",
                               m->name, m->taylor_why ? m->taylor_why : "its twin has none");
    if (m->nmode > 0)
        return sim_usage_error(s, "--reference-method taylor: %s has switched expressions "
                               "(max, min, clamp, step, abs), whose switches the reference "
                               "by Taylor's method does not locate; extrapolation does",
                               m->name);
    if (m->nv > 0 && !m->taylor_qd)
        return sim_usage_error(s, "--reference-method taylor: %s's speeds are not its "
                               "coordinates' rates, and its series lack the kinematic "
                               "equation q' = W(q) v (taylor_qd); extrapolation does not "
                               "need it", m->name);
    if (ext->taylor_a)
        return sim_usage_error(s, "--reference-method taylor: a constraint of %s is "
                               "nonlinear in q'', which the reference by Taylor's method "
                               "does not take; extrapolation does", m->name);
    for (int k = 0; k < m->nu; k++) {
        double v;
        if (!eomc_sim_input_held(s, k, &v))
            return sim_usage_error(s, "--reference-method taylor: input %s is a signal of "
                                   "time, whose series Taylor's method does not take",
                                   m->u_names[k]);
    }
    return EOMC_OK;
}

int
eomc_reference_compute(eomc_sim *s, const eomc_model_ext *ext, const eomc_run_opts *o,
                       const double *x0, eomc_reference *ref)
{
    return eomc_reference_compute_by(s, ext, o, x0, EOMC_REFERENCE_EXTRAPOLATION, ref);
}

int
eomc_reference_compute_by(eomc_sim *s, const eomc_model_ext *ext, const eomc_run_opts *o,
                          const double *x0, int how, eomc_reference *ref)
{
    const eomc_model *m = eomc_sim_model(s);
    memset(ref, 0, sizeof *ref);
    int rc = twin_fits(s, ext, "a reference");
    if (rc == EOMC_OK && sim_control_period(s) == 0)
        rc = sim_usage_error(s, "a reference of a run under a continuous controller: its law "
                             "has no extended-precision twin (write it in the spec, or give "
                             "it a period)");
    if (rc == EOMC_OK && sim_control_period(s) > 0 && m->nfric > 0)
        rc = sim_usage_error(s, "a reference of %s under a sampled controller: its dry "
                             "friction's stick and slip at the jumps of the inputs are not "
                             "followed in extended precision yet", m->name);
    if (rc == EOMC_OK && how == EOMC_REFERENCE_TAYLOR)
        rc = taylor_fits(s, ext);
    if (rc == EOMC_OK && how != EOMC_REFERENCE_EXTRAPOLATION && how != EOMC_REFERENCE_TAYLOR)
        rc = sim_usage_error(s, "unknown way %d to compute a reference", how);
    /* the constraint rows the doubles' solves use, where they start */
    if (rc == EOMC_OK)
        rc = sim_choose_rows(s, o->t0, x0, x0 + m->nq);
    if (rc != EOMC_OK)
        return rc;
    if (!(o->t_end >= o->t0) || !(o->dt > 0) || !isfinite(o->t_end) || !isfinite(o->dt))
        return sim_usage_error(s, "the reference needs an output interval and an end "
                               "time after the start");
    Ref r;
    long nrows = eomc_run_rows(o);
    size_t size = (size_t)nrows * (size_t)eomc_nx(m);
    double *prev = calloc(size, sizeof *prev);
    ref->t = calloc((size_t)nrows, sizeof *ref->t);
    ref->x = calloc(size, sizeof *ref->x);
    int alloc = ref_alloc(&r, s, ext, o);
    if (alloc == 0 && how == EOMC_REFERENCE_TAYLOR &&
        !(r.rt = reftaylor_alloc(ext, m->taylor_qd, r.n, r.nv, r.nc, sim_dropped_rows(s))))
        alloc = -1;
    if (alloc != 0 || !prev || !ref->t || !ref->x) {
        ref_free(&r);
        free(prev);
        eomc_reference_free(ref);
        return sim_usage_error(s, "out of memory for a reference of %ld rows", nrows);
    }
    ref->nrows = nrows;
    ref->nx = r.N;
    for (long k = 0; k < nrows; k++)
        ref->t[k] = eomc_run_row_time(o, k);
    double c0 = sim_seconds(1);
    long budget = STEP_BUDGET;
    rc = EOMC_OK;
    r.method = EXTRAP_GBS;
    r.detect = 1;
    r.eval_budget = INFINITY;
    r.tol = TOL_FIRST;
    for (int k = 0; k < MAX_SOLUTIONS; k++, r.tol /= TOL_STEP) {
        double *rows = k ? prev : ref->x; /* the new solution goes to prev */
        int st = r.rt ? solve_taylor(&r, o, x0, rows, budget) : solve(&r, o, x0, rows, budget);
        r.detect = 0;
        if (st == -3) { /* stiff: the linearly implicit method, if it is cheaper */
            r.method = EXTRAP_LINEARLY_IMPLICIT;
            r.eval_budget = r.gbs_evals / LI_ADVANTAGE;
            st = solve(&r, o, x0, rows, budget);
            r.eval_budget = INFINITY;
            r.li_evals = stepping(&r);
            if (st != 0) { /* dearer, or failing where GBS may not: GBS after all */
                r.method = EXTRAP_GBS;
                r.dearer = st == -4 ? 1 : -1;
                st = solve(&r, o, x0, rows, budget);
            }
        }
        if (st != 0 && k == 0) {
            rc = failure(&r, st);
            break;
        }
        if (st != 0)
            break; /* rounding (or the model) allows no finer one: keep the last */
        if (keep_switches(ref, &r) != 0) {
            rc = sim_usage_error(s, "out of memory for the reference's switches");
            break;
        }
        budget = STEP_GROWTH * r.steps;
        ref->refinements = k + 1;
        ref->tolerance = r.tol;
        ref->steps = r.steps;
        ref->rhs_evals = r.evals;
        if (k == 0) {
            ref->scale = la_max_abs(ref->x, size);
            continue;
        }
        ref->error = max_diff(ref->x, prev, size);
        memcpy(ref->x, prev, size * sizeof *prev);
        if (ref->error <= AGREE_ULPS * DBL_EPSILON * ref->scale)
            break;
    }
    /* the solutions agreeing to every bit says nothing finer than the
     * doubles they are kept in: their rounding bounds what x can tell */
    ref->error = fmax(ref->error, 0.5 * DBL_EPSILON * ref->scale);
    if (rc == EOMC_OK && ref->refinements < 2)
        rc = sim_numeric_error(s, o->t0, x0, x0 + m->nq, "no refinement of the reference "
                               "solution (%s) could be computed at tolerance %.0e, so it "
                               "cannot say how good it is", method_name(&r), r.tol);
    ref->cpu_seconds = sim_seconds(1) - c0;
    ref->method = method_name(&r);
    ref->stiff = r.method == EXTRAP_LINEARLY_IMPLICIT;
    int len = snprintf(ref->source, sizeof ref->source, "%s of order %d in %d-bit "
                       "floating point (long double)%s, %d solutions to relative "
                       "tolerance %.0e", ref->method,
                       r.rt ? reftaylor_order(r.rt)
                       : ref->stiff ? EXTRAP_LI_LEVELS : 2 * EXTRAP_GBS_LEVELS,
                       LDBL_MANT_DIG, ref->stiff ? " with a finite-difference Jacobian" : "",
                       ref->refinements, ref->tolerance);
    if (r.stiff && len > 0 && (size_t)len < sizeof ref->source)
        stiff_note(&r, ref->source + len, sizeof ref->source - (size_t)len);
    free(prev);
    ref_free(&r);
    if (rc != EOMC_OK)
        eomc_reference_free(ref);
    return rc;
}

int
eomc_reference_accel(eomc_sim *s, const eomc_model_ext *ext, double t, const double *x,
                     double *a, double *lam)
{
    const eomc_model *m = eomc_sim_model(s);
    int fits = twin_fits(s, ext, "q''");
    if (fits == EOMC_OK)
        fits = sim_choose_rows(s, t, x, x + m->nq);
    if (fits != EOMC_OK)
        return fits;
    Ref r;
    if (ref_alloc(&r, s, ext, NULL) != 0) {
        ref_free(&r);
        return sim_usage_error(s, "out of memory for the extended-precision q''");
    }
    for (int i = 0; i < r.N; i++)
        r.X[i] = x[i];
    /* the modes of the state itself, as eomc_sim_accel takes them */
    int rc = r.sw ? refsw_signs(r.sw, t, r.X) : 0;
    if (rc == 0)
        rc = rhs(&r, t, r.X, r.F);
    for (int i = 0; rc == 0 && i < r.nv; i++)
        a[i] = (double)r.F[r.n + i];
    for (int k = 0; rc == 0 && lam && k < r.nc; k++)
        lam[k] = (double)r.lam[k];
    ref_free(&r);
    if (rc == 0)
        return EOMC_OK;
    if (eomc_sim_accel(s, t, x, x + m->nq, a) != EOMC_OK)
        return EOMC_ENUMERIC; /* that message says why */
    return sim_numeric_error(s, t, x, x + m->nq, "q'' cannot be solved in extended "
                             "precision here (the doubles' solve can)");
}

void
eomc_reference_free(eomc_reference *ref)
{
    free(ref->t);
    free(ref->x);
    free(ref->sw_t);
    free(ref->sw_k);
    free(ref->sw_sens);
    free(ref->sw_x);
    free(ref->sw_f);
    ref->t = ref->x = ref->sw_t = ref->sw_sens = ref->sw_x = ref->sw_f = NULL;
    ref->sw_k = NULL;
    ref->nrows = ref->nswitch = 0;
}
