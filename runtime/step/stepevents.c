/*
 * stepevents: the scene's events in the steps (stepevents.h).
 *
 * An event fires in a step where its g crossed zero (events.h).  Its time
 * is located first on the step's cubic Hermite interpolant (dense.h),
 * cheap and good enough to start from, then on the solution: a side step
 * from the step's start, the step layer's (StepevMotion).  An event
 * whose g has the same sign at both ends of a step may have crossed
 * twice in it (a grazing motion, a long step): the cubic Hermite
 * polynomial of g through its values and rates at the ends (polyroots.h)
 * says where to look, a point between its first two roots, and g on the
 * solution there says whether the motion did cross.  The layer
 * sits between the steps (evolve.c) and the root search (events.c, which
 * knows no model): it knows the model's events, and the step only by the
 * ends it is handed, so that the stepper, the step's state and the watch
 * over the steps stay evolve.c's alone.
 *
 * The model's switches (eomc_model.h: the kinks of max, min, clamp) are
 * events here too, after the scene's: index nevent + j is switch j,
 * crossing either way, located as any event is, and its action flips
 * mode j where it crossed, the state going on unchanged.
 */
#include "stepevents.h"
#include "model/simimpl.h"
#include "model/state.h"
#include "events.h"
#include "dense.h"

#include <gsl/gsl_errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A reset passes through its event when it leaves g moving on the way it
 * crossed at more than PASS_REL of the rate it arrived with (a kick, a
 * switch of mode).  Anything slower, at rest or turned back (an impact),
 * is held at g = 0 until it leaves (stepev_check). */
#define PASS_REL 1e-6

/* "switch j", the name of index nevent + j (room for any int) */

struct StepEvents {
    eomc_sim *s;
    const eomc_model *m;          /* s's */
    const eomc_run_opts *o;
    eomc_stats *st;
    StepevMotion mo;
    int n, N;                     /* coordinates, state size nq + nv */
    int ne;                       /* events: the scene's, then the switches */
    int nev;                      /* the scene's (m->nevent) */
    double *tsw;                  /* [ne - nev] each switch's last flip */
    int *quick;                   /* [ne - nev] its flips in a row within
                                   * STEPEV_ACCUMULATE_REL of the one before */
    double *seq;                  /* [ne - nev] the order of its flip at that instant */
    unsigned char *was;           /* [ne - nev] the modes before a flip (also_set) */
    unsigned char *fricsw;        /* [ne - nev] 1: dry friction's (a slip or stick switch) */
    int switch_to;                /* the mode a located switch flips to */
    double *g0, *g1;              /* [ne] g at the step's start and end */
    double *ge, *te;              /* [ne] scratch: g, and each event's time */
    double *te2;                  /* [ne] a second crossing in the step (a pair,
                                   * both in the event's direction), or NAN */
    double *gd0, *gd1;            /* [ne] g's rates at the step's ends (pairs) */
    int have_gd0;                 /* gd0 holds the rates at this step's start: the
                                   * last step's end, left as it was */
    double *xs, *fs, *gs;         /* [N], [N], [ne]: the solution inside a step,
                                   * its rate, and g or g's rate there (pair) */
    double *xe;                   /* [N] the state at an event's trial time */
    double *fi;                   /* [N] the rate in a switch's other mode (inert) */
    double *gi, *gj;              /* [ne], [ne] the functions in both (inert) */
    unsigned char *lost;          /* [ne] not located in the step at first */
    int ev_k;                     /* the event being located */
    StepevSpan sp;                /* the step it is located in (its arrays
                                   * during stepev_check only) */
    double last_set;              /* the time of the last `set` event */
    long nsets;                   /* `set` events so far */
    unsigned char *held;          /* [ne] reset at g = 0, not yet left it */
    double gap;                   /* from the `set` event before to the last */
    double left_rate;             /* g's rate after the last reset, a share of
                                     its rate on arrival (0 unless on the way
                                     it crossed, slower than passing) */
    double *ce;                   /* [nc] each constraint's inconsistency */
    int *cl;                      /* [nc] and its level, after a reset */
};

StepEvents *
stepev_alloc(eomc_sim *s, const eomc_run_opts *o, eomc_stats *st, StepevMotion motion)
{
    StepEvents *v = calloc(1, sizeof *v);
    if (!v)
        return NULL;
    const eomc_model *m = eomc_sim_model(s);
    *v = (StepEvents){.s = s, .m = m, .o = o, .st = st, .mo = motion, .n = m->nq,
                      .N = eomc_nx(m), .ne = m->nevent + m->nmode, .nev = m->nevent,
                      .last_set = -INFINITY};
    double **arrays[] = {&v->g0, &v->g1, &v->ge, &v->te, &v->xe, &v->ce, &v->te2, &v->gd0,
                         &v->gd1, &v->xs, &v->fs, &v->gs, &v->fi, &v->gi, &v->gj};
    size_t ne = (size_t)v->ne, nc = (size_t)m->nc, N = (size_t)v->N;
    size_t sizes[] = {ne, ne, ne, ne, N, nc, ne, ne, ne, N, N, ne, N, ne, ne};
    int ok = 1;
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        ok &= (*arrays[k] = sim_zeros(sizes[k])) != NULL;
    ok &= (v->held = calloc(ne + 1, 1)) != NULL;
    ok &= (v->lost = calloc(ne + 1, 1)) != NULL;
    ok &= (v->tsw = sim_zeros((size_t)m->nmode)) != NULL;
    ok &= (v->seq = sim_zeros((size_t)m->nmode)) != NULL;
    ok &= (v->quick = calloc((size_t)m->nmode + 1, sizeof *v->quick)) != NULL;
    ok &= (v->was = calloc((size_t)m->nmode + 1, 1)) != NULL;
    ok &= (v->fricsw = calloc((size_t)m->nmode + 1, 1)) != NULL;
    for (int j = 0; ok && j < m->nmode; j++)
        v->tsw[j] = -INFINITY;
    for (int j = 0; ok && j < m->nfric; j++)
        v->fricsw[m->fric_slip[j]] = v->fricsw[m->fric_stick[j]] = 1;
    ok &= (v->cl = calloc(nc + 1, sizeof *v->cl)) != NULL;
    if (!ok) {
        stepev_free(v);
        return NULL;
    }
    sim_span(s, o->t_end - o->t0);
    return v;
}

void
stepev_free(StepEvents *v)
{
    if (!v)
        return;
    double *arrays[] = {v->g0, v->g1, v->ge, v->te, v->xe, v->ce, v->te2, v->gd0, v->gd1,
                        v->xs, v->fs, v->gs, v->fi, v->gi, v->gj};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    free(v->held);
    free(v->lost);
    free(v->tsw);
    free(v->seq);
    free(v->quick);
    free(v->was);
    free(v->fricsw);
    free(v->cl);
    free(v);
}

/* g of the scene's events, then the switch functions, at (t, q, qv). */
static void
g_all(StepEvents *v, double t, const double *q, const double *qv, double *g)
{
    if (v->nev)
        eomc_sim_events(v->s, t, q, qv, g);
    if (v->ne > v->nev)
        sim_switches(v->s, t, q, qv, g + v->nev);
}

static int
dir_of(const StepEvents *v, int k)
{
    return k < v->nev ? v->m->ev_direction[k] : 0; /* a switch: either way */
}

static const char *
name_of(const StepEvents *v, int k)
{
    if (k < v->nev)
        return v->m->ev_names[k];
    return v->m->sw_names ? v->m->sw_names[k - v->nev] : "a switch"; /* (a model by hand) */
}

int
stepev_action(const StepEvents *v, int k)
{
    return k < v->nev ? v->m->ev_action[k] : STEPEV_SWITCH;
}

void
stepev_start(StepEvents *v, double t, const double *x)
{
    g_all(v, t, x, x + v->n, v->g0);
    v->have_gd0 = 0;
}

double
stepev_gap(const StepEvents *v)
{
    return v->gap;
}

/* ---- located ---- */

static double
g_interpolant(void *ctx, double t)
{
    StepEvents *v = ctx;
    const StepevSpan *sp = &v->sp;
    dense_cubic(sp->t0, sp->t1, sp->x0, sp->f0, sp->x1, sp->f1, v->N, t, v->xe);
    g_all(v, t, v->xe, v->xe + v->n, v->ge);
    return v->ge[v->ev_k];
}

/* g on the solution: the state at t by a step of its own from the step's
 * start, controlled as a row's side step is. */
static double
g_solution(void *ctx, double t)
{
    StepEvents *v = ctx;
    v->st->event_evals++;
    if (v->mo.side(v->mo.ctx, v->sp.t0, v->sp.x0, v->sp.f0, t, v->xe) != GSL_SUCCESS)
        return NAN;
    g_all(v, t, v->xe, v->xe + v->n, v->ge);
    return v->ge[v->ev_k];
}

/* How fast each event's g changes along the motion at (t, x), whose
 * right-hand side is f, into out [ne]: a central difference along the
 * tangent over a probe PROBE_REL of the step in hand (v->sp).  It is
 * exact for a g quadratic in the state, and otherwise off by (probe)^2
 * g'''/6, a millionth of what g changes by over a step; the rounding of
 * g, spread over a probe a thousandth of the step, stays far below
 * PASS_REL of the rate it arrived with (a millionth of the step lost 60%
 * of a rate of 1e-8 to it). */
#define PROBE_REL 1e-3
static void
g_rates(StepEvents *v, double t, const double *x, const double *f, double *out)
{
    double d = PROBE_REL * (v->sp.t1 - v->sp.t0);
    for (int side = 0; side < 2; side++) {
        double s = side ? d : -d;
        for (int i = 0; i < v->N; i++)
            v->xe[i] = x[i] + s * f[i];
        g_all(v, t + s, v->xe, v->xe + v->n, side ? v->ge : out);
    }
    for (int k = 0; k < v->ne; k++)
        out[k] = (v->ge[k] - out[k]) / (2 * d);
}

/* Event k's alone (gd1 is scratch outside stepev_check). */
static double
g_rate(StepEvents *v, int k, double t, const double *x, const double *f)
{
    g_rates(v, t, x, f, v->gd1);
    return v->gd1[k];
}

/* g of event k on the solution at t and its rate there into *g and *gd:
 * a side step from the step's start, then g_rates.  GSL_SUCCESS or a
 * failure status. */
static int
g_and_rate(StepEvents *v, int k, double t, double *g, double *gd)
{
    const StepevSpan *sp = &v->sp;
    v->st->event_evals++;
    int rc = v->mo.side(v->mo.ctx, sp->t0, sp->x0, sp->f0, t, v->xs);
    if (rc == GSL_SUCCESS)
        rc = v->mo.rate(t, v->xs, v->fs, v->mo.ctx);
    if (rc != GSL_SUCCESS)
        return rc;
    g_all(v, t, v->xs, v->xs + v->n, v->gs);
    *g = v->gs[k];
    g_rates(v, t, v->xs, v->fs, v->gs);
    *gd = v->gs[k];
    return GSL_SUCCESS;
}

/* Bisections of g's turning point in a step, at most: they shrink the
 * bracket to 2^-EXTREMUM_ITERS of the step, where g differs from its
 * extreme value by (2^-12 h)^2 g''/2, 6e-8 of what its rate turns by. */
enum { EXTREMUM_ITERS = 12 };

/* Roots of two switch functions closer than this many ulps of the time
 * are one instant: ev_root brackets each to 4, so two located apart
 * differ by up to 8 for rounding alone. */
#define SIMULTANEOUS_ULPS 16

static int inert(StepEvents *v, int k, double t, const double *x, double *f);

/* Event k, of one sign at both ends of the step, crossing twice inside
 * it: g heads for 0 at the step's start and away from it at its end
 * (gd0, gd1), so it turns in between.  The turning point is found on the
 * solution by bisection on the sign of g's rate, starting where the cubic
 * through g and its rates at the ends turns; where g there has crossed
 * 0, each crossing on either side of it in k's direction is located on
 * the solution, the first into te[k] and a second into te2[k].
 * GSL_SUCCESS, or a failure status where the solution cannot be
 * computed. */
static int
pair(StepEvents *v, int k, int *any)
{
    const StepevSpan *sp = &v->sp;
    double t0 = sp->t0, t1 = sp->t1, h = t1 - t0, g0 = v->g0[k], g1 = v->g1[k];
    double side = g0 > 0 ? 1 : -1;
    if (g0 == 0 || !(side * v->gd0[k] < 0 && side * v->gd1[k] > 0))
        return GSL_SUCCESS;
    /* the cubic's turning point: c1 + 2 c2 tau + 3 c3 tau^2 = 0 in (0, 1) */
    double d0 = v->gd0[k] * h, d1 = v->gd1[k] * h;
    double c2 = 3 * (g1 - g0) - 2 * d0 - d1, c3 = 2 * (g0 - g1) + d0 + d1;
    double qa = 3 * c3, qb = 2 * c2, disc = qb * qb - 4 * qa * d0, tau = 0.5;
    if (qa != 0 && disc >= 0) {
        double r1 = (-qb - sqrt(disc)) / (2 * qa), r2 = (-qb + sqrt(disc)) / (2 * qa);
        tau = r1 > 0 && r1 < 1 ? r1 : r2 > 0 && r2 < 1 ? r2 : 0.5;
    } else if (qa == 0 && qb != 0 && -d0 / qb > 0 && -d0 / qb < 1) {
        tau = -d0 / qb;
    }
    /* Where the cubic's turn stays farther from 0 than g's rates move it
     * over the whole step, the solution does not reach 0 either: the cubic
     * matches g and its rate at both ends, and differs from it by far less
     * than that.  (At rest on a contact the rates are rounding, and each
     * switch would cost a dozen side steps per step.) */
    double gc = g0 + tau * (d0 + tau * (c2 + tau * c3));
    if (side * gc > fabs(d0) + fabs(d1))
        return GSL_SUCCESS;
    /* A switch whose mode changes nothing (a capsule pair's inner switch
     * while the pair is apart: its function at rounding's level, its rates
     * of either sign) would cost up to EXTREMUM_ITERS side steps in every
     * step to find crossings that flip nothing.  Inert at the step's start
     * and at the cubic's turn (the state there interpolated, as the cubic
     * of g is), its crossings are not looked for.  Not so a contact that
     * starts the step on its kink and dips in between: at the turn its
     * push acts, and the search goes on.  Nor in a model with dry
     * friction, whose stick and slip are decided where steps end: there
     * the steps the search cut stay (without them the quadruped dropped
     * with friction met a chattering slip switch at t = 4.21, exit 3). */
    if (!v->m->nfric && k >= v->nev && inert(v, k, t0, sp->x0, v->fs) == 1) {
        dense_cubic(t0, t1, sp->x0, sp->f0, sp->x1, sp->f1, v->N, t0 + tau * h, v->xe);
        if (inert(v, k, t0 + tau * h, v->xe, v->fs) == 1)
            return GSL_SUCCESS;
    }
    double lo = t0, hi = t1, tc = NAN;
    gc = NAN;
    for (int it = 0; it < EXTREMUM_ITERS && isnan(tc); it++) {
        double tm = it == 0 ? t0 + tau * h : 0.5 * (lo + hi), gm, dm;
        int rc = g_and_rate(v, k, tm, &gm, &dm);
        if (rc != GSL_SUCCESS)
            return rc;
        if (gm == 0 || (gm > 0) != (g0 > 0))
            tc = tm, gc = gm;
        else if (side * dm < 0) /* still heading for 0: the turn is later */
            lo = tm;
        else
            hi = tm;
    }
    if (isnan(tc)) /* it turned short of 0 */
        return GSL_SUCCESS;
    int dir = dir_of(v, k), evals, there = ev_crossed(dir, g0, gc);
    int back = ev_crossed(dir, gc, g1);
    double first = there ? ev_root(g_solution, v, t0, g0, tc, gc, NAN, &evals) : NAN;
    double second = back ? ev_root(g_solution, v, tc, gc, t1, g1, NAN, &evals) : NAN;
    if ((there && isnan(first)) || (back && isnan(second)))
        return GSL_EBADFUNC;
    v->te[k] = there ? first : second;
    v->te2[k] = there ? second : NAN;
    *any |= !isnan(v->te[k]);
    return GSL_SUCCESS;
}

/* Whether switch k's mode changes nothing at (t, x): the rate is the
 * same, to the bit, in both, and every other function is on the same
 * side in both (a capsule pair's nearest end while the capsules are
 * apart: the gap it picks acts on nothing, and is below 0 either way;
 * not a pair's near switch, which wakes the pair's own).  Its crossings
 * are then the motion's whichever mode it is in; f [N] the rate in its
 * mode, overwritten.  -1 where a rate fails. */
static int
inert(StepEvents *v, int k, double t, const double *x, double *f)
{
    int j = k - v->nev, mode = sim_mode(v->s, j), same = 1;
    if (v->mo.rate(t, x, f, v->mo.ctx) != GSL_SUCCESS)
        return -1;
    g_all(v, t, x, x + v->n, v->gi);
    sim_set_mode(v->s, j, !mode);
    int rc = v->mo.rate(t, x, v->fi, v->mo.ctx);
    g_all(v, t, x, x + v->n, v->gj);
    sim_set_mode(v->s, j, mode);
    if (rc != GSL_SUCCESS)
        return -1;
    for (int i = 0; i < v->N && same; i++)
        same = f[i] == v->fi[i];
    for (int i = 0; i < v->ne && same; i++)
        same = i == k || (v->gi[i] > 0) == (v->gj[i] > 0);
    return same;
}

/* Switch k flipped at the step's start (its g0 is 0) and its function
 * ends the step on the side of the mode it left: it went into its new
 * mode's side and came back across, or never went.  The crossing back is
 * located after a point found on the new side, by halving toward the
 * start; found no later than 2^-EXTREMUM_ITERS of the step, the motion
 * leaves the new mode as soon as it enters it: it would slide along the
 * kink, which no mode follows (STEPEV_RETURNED), unless its mode
 * changes nothing there (inert).  GSL_SUCCESS, or a failure status. */
static int
back_across(StepEvents *v, int k, int *any)
{
    const StepevSpan *sp = &v->sp;
    double side = sim_mode(v->s, k - v->nev) ? 1 : -1, g1 = v->g1[k];
    if (!(side * g1 < 0))
        return GSL_SUCCESS; /* on its new side, or still on the kink */
    /* one of the geometry whose mode changes nothing (inert) flips back
     * at the step's end, where the motion is the same either way */
    int same = v->fricsw[k - v->nev] ? 0 : inert(v, k, sp->t1, sp->x1, v->fs);
    if (same < 0)
        return GSL_EBADFUNC;
    if (same) {
        v->te[k] = sp->t1;
        *any = 1;
        return GSL_SUCCESS;
    }
    double lo = sp->t0, hi = sp->t1, tm = NAN, gm = NAN;
    v->ev_k = k;
    for (int it = 0; it < EXTREMUM_ITERS; it++) {
        double t = 0.5 * (lo + hi), g = g_solution(v, t);
        if (isnan(g))
            break;
        if (side * g > 0) {
            tm = t, gm = g;
            break;
        }
        hi = t; /* already back: the excursion, if any, is earlier */
    }
    int evals;
    if (isnan(tm) && isnan(gm)) {
        v->left_rate = 0;
        return STEPEV_RETURNED;
    }
    if (!isnan(tm))
        v->te[k] = ev_root(g_solution, v, tm, gm, sp->t1, g1, NAN, &evals);
    if (isnan(v->te[k])) {
        sim_numeric_error(v->s, sp->t1, sp->x1, sp->x1 + v->n, "switch %s crossed back in "
                          "the step from t = %.17g, but the state inside it could not be "
                          "computed", name_of(v, k), sp->t0);
        return GSL_EBADFUNC;
    }
    *any = 1;
    return GSL_SUCCESS;
}

/* Switch k's function is 0 at the step's start by itself, not by a flip
 * there: it sat on its kink (a touch point's slip speed through a
 * flight, 0 to the last bit while nothing acts along it).  Ending the
 * step across, on the side its mode is not, it left the kink in the step:
 * a crossing, located as the first time it is across, by halving between
 * the last time found on the kink or its mode's side and the first time
 * across until the two are a few units of rounding of t apart (a
 * bracket-settled root, as ev_root's).  GSL_SUCCESS, or GSL_EBADFUNC where
 * the state inside the step cannot be computed. */
static int
leaves_kink(StepEvents *v, int k, int *any)
{
    double side = sim_mode(v->s, k - v->nev) ? 1 : -1;
    if (!(side * v->g1[k] < 0))
        return GSL_SUCCESS; /* still on it, or off it on its mode's side */
    double lo = v->sp.t0, hi = v->sp.t1;
    v->ev_k = k;
    for (;;) {
        double t = 0.5 * (lo + hi);
        if (!(t > lo && t < hi) || hi - lo <= EV_SETTLED_ULPS * DBL_EPSILON * fabs(hi))
            break;
        double g = g_solution(v, t);
        if (isnan(g)) {
            sim_numeric_error(v->s, v->sp.t1, v->sp.x1, v->sp.x1 + v->n, "switch %s left "
                              "its kink in the step from t = %.17g, but the state inside "
                              "it could not be computed", name_of(v, k), v->sp.t0);
            return GSL_EBADFUNC;
        }
        if (side * g < 0)
            hi = t;
        else
            lo = t;
    }
    v->te[k] = hi;
    *any = 1;
    return GSL_SUCCESS;
}

int
stepev_check(StepEvents *v, const StepevSpan *sp, StepevHit *hit)
{
    eomc_sim *s = v->s;
    const eomc_model *m = v->m;
    double t0 = sp->t0, t1 = sp->t1;
    const double *x1 = sp->x1;
    int any = 0, lost = 0;
    *hit = (StepevHit){.k = -1, .status = EOMC_OK, .t = NAN};
    v->sp = *sp;
    g_all(v, t1, x1, x1 + v->n, v->g1);
    int rates = 0; /* gd0, gd1 at this step's ends */
    for (int k = 0; k < v->ne; k++) {
        v->te[k] = v->te2[k] = NAN;
        /* an event reset at g = 0 must leave it away from where it fires
         * (up for a downward event): back there already, the motion
         * returned within one step, faster than the steps can follow */
        int dir = dir_of(v, k);
        if (v->held[k] && dir != 0 && (v->g1[k] == 0 || (v->g1[k] < 0) == (dir < 0))) {
            v->ev_k = k;
            return STEPEV_RETURNED;
        }
        v->held[k] = 0;
        if (k >= v->nev && v->g0[k] == 0) { /* a switch this step starts on */
            int rc = v->tsw[k - v->nev] == t0 ? back_across(v, k, &any)
                                              : leaves_kink(v, k, &any);
            if (rc != GSL_SUCCESS)
                return rc;
            continue;
        }
        /* a switch across to its mode's side: its mode went there already,
         * at a flip that saw it coming a rounding short of 0 (side_soon) */
        if (k >= v->nev && (sim_mode(s, k - v->nev) ? v->g1[k] > 0 : v->g1[k] < 0) &&
            ev_crossed(0, v->g0[k], v->g1[k]))
            continue;
        if (!ev_crossed(dir_of(v, k), v->g0[k], v->g1[k])) {
            if (v->mo.steps_split_pairs || (v->g0[k] > 0) != (v->g1[k] > 0))
                continue;
            if (!rates++) {
                if (!v->have_gd0)
                    g_rates(v, t0, sp->x0, sp->f0, v->gd0);
                g_rates(v, t1, sp->x1, sp->f1, v->gd1);
            }
            v->ev_k = k;
            if (pair(v, k, &any) != GSL_SUCCESS) { /* (a side step's failure) */
                sim_numeric_error(s, t1, x1, x1 + v->n, "event %s may have crossed twice "
                                  "in the step from t = %.17g, but the state inside it "
                                  "could not be computed", name_of(v, k), t0);
                return GSL_EBADFUNC;
            }
            continue;
        }
        int evals;
        v->ev_k = k;
        double guess = ev_root(g_interpolant, v, t0, v->g0[k], t1, v->g1[k], NAN, &evals);
        v->te[k] = ev_root(g_solution, v, t0, v->g0[k], t1, v->g1[k], guess, &evals);
        v->lost[k] = isnan(v->te[k]);
        lost |= v->lost[k];
        any |= !v->lost[k];
    }
    /* An event whose trial times could not be computed (the side steps
     * failed their control: a kink inside the step, another event's) is
     * looked for again short of the first one located, whose kink the
     * step ends at: crossed by then, it is located there; not crossed,
     * it is the next step's */
    double first = NAN;
    for (int j = 0; lost && j < v->ne; j++)
        if (!isnan(v->te[j]) && !(first <= v->te[j]))
            first = v->te[j];
    for (int k = 0; lost && k < v->ne; k++) {
        if (!v->lost[k])
            continue;
        v->lost[k] = 0;
        v->ev_k = k;
        int evals;
        double g = isnan(first) ? NAN : g_solution(v, first);
        if (isnan(g) || (ev_crossed(dir_of(v, k), v->g0[k], g) &&
                         isnan(v->te[k] = ev_root(g_solution, v, t0, v->g0[k], first, g, NAN,
                                                  &evals)))) {
            sim_numeric_error(s, t1, x1, x1 + v->n, "event %s fired in the step from t = "
                              "%.17g, but the state at its trial times could not be "
                              "computed", name_of(v, k), t0);
            return GSL_EBADFUNC;
        }
    }
    memcpy(v->g0, v->g1, (size_t)v->ne * sizeof *v->g0);
    /* the next step starts at this one's end (a reset says otherwise) */
    if ((v->have_gd0 = rates > 0))
        memcpy(v->gd0, v->gd1, (size_t)v->ne * sizeof *v->gd0);
    while (any) {
        int k = -1;
        for (int j = 0; j < v->ne; j++)
            if (!isnan(v->te[j]) && (k < 0 || v->te[j] < v->te[k]))
                k = j;
        if (k < 0)
            break;
        double t = v->te[k];
        v->te[k] = NAN;
        v->st->events++;
        if (t == t1)
            memcpy(v->xe, x1, (size_t)v->N * sizeof *v->xe);
        else if (v->mo.side(v->mo.ctx, t0, sp->x0, sp->f0, t, v->xe) != GSL_SUCCESS)
            return GSL_EBADFUNC;
        else /* a state of the motion, as a row is: its unit quaternions renormalized */
            state_normalize(m, v->xe, NULL);
        int rc = v->o->on_event ? v->o->on_event(v->o->event_ctx, k, t, v->xe) : EOMC_OK;
        if (rc != EOMC_OK) {
            *hit = (StepevHit){.k = -1, .status = rc, .t = t, .x = v->xe};
            return GSL_SUCCESS;
        }
        if (stepev_action(v, k) == EOMC_EVENT_RECORD) {
            v->te[k] = v->te2[k], v->te2[k] = NAN; /* the pair's second, if any */
            continue;
        }
        /* a flip goes to the other mode: the side the switch function went
         * to here (by the step's end it may be back, a pair's first) */
        v->switch_to = k >= v->nev && !sim_mode(s, k - v->nev);
        *hit = (StepevHit){.k = k, .status = EOMC_OK, .t = t, .x = v->xe};
        return GSL_SUCCESS;
    }
    return GSL_SUCCESS;
}

/* ---- reset ---- */

/* Event k's `set` at t left the state off its constraints (their
 * inconsistencies in v->ce, levels in v->cl): the first such is kept in
 * the statistics, with every constraint it left off, worst first. */
static void
note_reset_off(StepEvents *v, int k, double t)
{
    eomc_stats *st = v->st;
    const eomc_model *m = v->m;
    size_t at = 0, len = sizeof st->reset_off;
    st->reset_event = k;
    st->reset_t = t;
    st->reset_off[0] = '\0';
    for (int listed = 0;; listed++) {
        int worst = -1;
        for (int j = 0; j < m->nc; j++)
            if (v->ce[j] > EOMC_INCONSISTENT && (worst < 0 || v->ce[j] > v->ce[worst]))
                worst = j;
        if (worst < 0)
            break;
        if (!listed) {
            st->reset_constraint = worst;
            st->reset_level = v->cl[worst];
            st->reset_inconsistency = v->ce[worst];
        }
        if (at < len)
            at += (size_t)snprintf(st->reset_off + at, len - at, "%s%s (%s: %.2g)",
                                   listed ? ", " : "", m->c_names[worst],
                                   v->cl[worst] ? "velocities" : "positions", v->ce[worst]);
        v->ce[worst] = 0; /* listed */
    }
}

/* The modes before a flip, for also_set. */
static void
modes_before(StepEvents *v)
{
    for (int j = 0; j < v->m->nmode; j++)
        v->was[j] = (unsigned char)sim_mode(v->s, j);
}

/* Switch j's flip at t set others' modes too (dry friction: a group of
 * points stuck with it, or let go with it, and the slip side each let go
 * takes, the way the rest drives it, or a point that touches taking its
 * speed's sign): each is a flip at t as well.  One whose function is not
 * on its new mode's side is at its kink there (a speed held at 0, whose
 * sign is rounding): it fires again only once it has left it, and a pass
 * at this instant does not flip it back; one on its side crosses as any
 * switch does (a touching point's speed, 0 but for rounding, that the
 * floor's friction drives across at once: it sticks there).  The stick
 * switches among them are listed after j, in the order of the switches
 * (a let-go's slip side is its stick switch's flip, not an event of its
 * own). */
static void
also_set(StepEvents *v, int j, double t, const double *x)
{
    const eomc_model *m = v->m;
    /* an item let go (stuck before the flip, not now): its speed is 0
     * but for rounding, and its rate is the side the let-go gave it (the
     * one Coulomb's choice names, stick.h), or 0 but for rounding where
     * the choice was made on its edge; either way its slip switch is on
     * its kink, on that side, whether the side changed or not, and fires
     * again only once it has left it (leaves_kink) */
    for (int k = 0; k < m->nfric; k++)
        if (v->was[m->fric_stick[k]] && !sim_mode(v->s, m->fric_stick[k])) {
            v->tsw[m->fric_slip[k]] = t;
            v->seq[m->fric_slip[k]] = 0;
        }
    int any = 0;
    for (int i = 0; i < v->m->nmode && !any; i++)
        any = i != j && v->was[i] != sim_mode(v->s, i);
    if (!any)
        return;
    g_all(v, t, x, x + v->n, v->gs);
    for (int i = 0; i < v->m->nmode; i++) {
        int on = sim_mode(v->s, i);
        if (i == j || v->was[i] == on)
            continue;
        double g = v->gs[v->nev + i];
        if (!(on ? g > 0 : g < 0)) {
            v->tsw[i] = t;
            v->seq[i] = 0;
        }
        if (!sim_mode_held(v->s, i))
            continue;
        v->st->events++;
        if (v->o->on_event)
            (void)v->o->on_event(v->o->event_ctx, v->nev + i, t, x);
    }
}

/* The side switch i's function (g0, its rate gd1) is on at this instant,
 * or reaches within soon at the rate it moves: one on its kink goes where
 * its rate takes it (a mirror image's of the switch that flipped), and
 * one a rounding short of 0 that crosses within soon (two contacts
 * touching together, located apart by rounding) is on the side it is
 * crossing to, whether its mode went there already or not. */
static int
side_soon(const StepEvents *v, int i, int mode, double soon)
{
    double g = v->g0[i], r = v->gd1[i];
    if (g == 0)
        return r > 0 ? 1 : r < 0 ? 0 : mode;
    if (r != 0 && (r > 0) != (g > 0) && -g / r <= soon)
        return r > 0; /* about to cross */
    return g > 0;
}

/* With dry friction, the switches at instant t (on or within soon of
 * their kinks, side_soon), settled in passes: each pass evaluates the
 * functions (ge: the mode each goes to, or -1) and flips the first that
 * disagrees, since a flip moves others' functions: a geometry switch's
 * those that read its mode (a capsule's clamps, then which end is
 * nearest), a friction switch's every stick switch (Coulomb's choice,
 * made for all the stuck points at once, may keep one that the
 * functions before it said would let go), and may set others' modes (a
 * group stuck or let go with it).  A geometry switch flipped at t flips
 * again where one before it flipped after it, as without friction; a
 * friction switch flips once an instant.  A pass that
 * flips a contact's switch (its touch, push or clamp) flips no friction
 * switch: who sticks and who slips is decided with the contacts of the
 * instant all made (two feet touching together, located apart by
 * rounding: the friction of the first is decided under the normal force
 * of both).  contacts_only: friction's wait. */
static int
together(StepEvents *v, double t, double *x, double soon, int contacts_only)
{
    double order = 0; /* the latest flip's at t */
    for (int j = 0; j < v->ne - v->nev; j++)
        if (v->tsw[j] == t)
            order = fmax(order, v->seq[j]);
    for (int pass = 0; pass < 2 * (v->ne - v->nev); pass++) {
        int changed = 0, contact = contacts_only;
        double below = 0; /* the latest flip at t of the switches before i */
        g_all(v, t, x, x + v->n, v->g0);
        for (int i = v->nev; i < v->ne; i++) {
            int j = i - v->nev, mode = sim_mode(v->s, j), on = side_soon(v, i, mode, soon);
            /* flipped at t already: a friction switch stays (each once);
             * another flips again where one before it flipped after it
             * (its function reads their modes: a capsule's clamps, then
             * which end is nearest), as without friction */
            int again = v->tsw[j] == t && (v->fricsw[j] || !(below > v->seq[j]));
            if (v->tsw[j] == t)
                below = fmax(below, v->seq[j]);
            v->ge[i] = again || on == mode ? -1 : on;
            contact |= v->ge[i] >= 0 && !v->fricsw[j];
        }
        for (int i = v->nev; i < v->ne; i++) {
            int on = v->ge[i] > 0;
            if (v->ge[i] < 0 || on == sim_mode(v->s, i - v->nev) ||
                (contact && v->fricsw[i - v->nev]))
                continue;
            modes_before(v);
            if (sim_flip(v->s, i - v->nev, on, t, x) != EOMC_OK)
                return GSL_EBADFUNC;
            v->tsw[i - v->nev] = t;
            v->seq[i - v->nev] = ++order;
            v->st->events++;
            if (v->o->on_event)
                (void)v->o->on_event(v->o->event_ctx, i, t, x);
            also_set(v, i - v->nev, t, x);
            changed = 1;
            break; /* (the functions after it may read its mode: again) */
        }
        if (!changed)
            break;
    }
    return GSL_SUCCESS;
}

/* Switch k's flip at t: its mode to where its function went, x as it
 * is (but for a speed dry friction sticks, exactly 0 then: sim_flip),
 * f [nx] its rate in the new mode.  STEPEV_CHATTER_FLIPS flips of one
 * switch in a row, each within STEPEV_ACCUMULATE_REL of the span after the one
 * before, chatter (Zeno), as resets do. */
static int settle(StepEvents *v, double t, double *x, double *f, double soon, double order);

static int
flip(StepEvents *v, int k, double t, double *x, double *f)
{
    int j = k - v->nev;
    double span = v->o->t_end - v->o->t0;
    v->quick[j] = t - v->tsw[j] < STEPEV_ACCUMULATE_REL * span ? v->quick[j] + 1 : 0;
    if (v->quick[j] >= STEPEV_CHATTER_FLIPS) {
        v->last_set = v->tsw[j];
        return STEPEV_ACCUMULATE;
    }
    v->tsw[j] = t;
    v->seq[j] = 1;
    v->gap = t - v->last_set;
    v->last_set = t;
    v->nsets++;
    double soon = SIMULTANEOUS_ULPS * DBL_EPSILON * fmax(fabs(t), v->o->t_end - v->o->t0);
    if (v->fricsw[j]) { /* (the contacts of this instant first: together's) */
        g_rates(v, t, x, f, v->gd1);
        if (together(v, t, x, soon, 1) != GSL_SUCCESS)
            return GSL_EBADFUNC;
    }
    modes_before(v);
    int rc = sim_flip(v->s, j, v->switch_to, t, x);
    if (rc != EOMC_OK)
        return GSL_EBADFUNC;
    also_set(v, j, t, x);
    if ((rc = settle(v, t, x, f, soon, 1)) != GSL_SUCCESS)
        return rc;
    v->held[k] = 0;
    v->left_rate = 0;
    return GSL_SUCCESS;
}

/* After a flip at t (order: its place, 1), or a jump of the inputs
 * (order 0), with x' in f (the rate before the flip): the other switches
 * that disagree with their modes flip at t too, then f, g0 afresh. */
static int
settle(StepEvents *v, double t, double *x, double *f, double soon, double order)
{
    int rc;
    long flips = v->st->events; /* a jump that flips none leaves f as it came */
    int jump = order == 0;
    /* Switches that cross at this very instant (two kinks at once: a
     * clamp with lo = hi, two contacts touching together) are past 0 here
     * already, or reach it within SIMULTANEOUS_ULPS of t at the rate they
     * move (their roots, located apart, differ by rounding: the steps
     * between them would be too short to take): each flips now too, told
     * as the first was (a nonzero return of on_event cannot undo what
     * that one started).  A flip may move another's function (a max of a
     * max): again until none disagrees. */
    g_rates(v, t, x, f, v->gd1); /* (f: the rate before the flip) */
    /* Without dry friction the switches settle in their order, one flip
     * a pass: a switch's function reads only the modes of those before
     * it (a capsule's clamp, the one it clamps next), so once the first
     * that disagrees has flipped, those before it stay settled; one
     * flipped at t already flips again where one before it flipped after
     * it (its function is not the one it was flipped by).  Each pass
     * settles one more switch: at most two passes a switch.  With dry
     * friction (stick switches reading every mode, a group of stuck
     * points letting go at once) together settles them, a friction
     * switch once an instant. */
    if (v->m->nfric > 0)
        goto together;
    for (int pass = 0; pass <= 2 * (v->ne - v->nev); pass++) {
        int pick = -1;
        double below = 0; /* the latest flip at t of the switches before i */
        g_all(v, t, x, x + v->n, v->g0);
        for (int i = v->nev; i < v->ne && pick < 0; i++) {
            int j = i - v->nev, mode = sim_mode(v->s, j), on = side_soon(v, i, mode, soon);
            int again = v->tsw[j] == t && !(below > v->seq[j]);
            if (v->tsw[j] == t)
                below = fmax(below, v->seq[j]);
            if (!again && on != mode)
                pick = i;
        }
        if (pick < 0)
            break;
        int j = pick - v->nev;
        if (sim_flip(v->s, j, !sim_mode(v->s, j), t, x) != EOMC_OK)
            return GSL_EBADFUNC;
        v->tsw[j] = t, v->seq[j] = ++order;
        v->st->events++;
        if (v->o->on_event)
            (void)v->o->on_event(v->o->event_ctx, pick, t, x);
    }
    goto settled;
together:
    if (together(v, t, x, soon, 0) != GSL_SUCCESS)
        return GSL_EBADFUNC;
settled:
    rc = jump && v->st->events == flips ? GSL_SUCCESS : v->mo.rate(t, x, f, v->mo.ctx);
    if (rc != GSL_SUCCESS)
        return rc;
    g_all(v, t, x, x + v->n, v->g0);
    for (int i = v->nev; i < v->ne; i++) /* on their kinks: each fires again only */
        if (v->tsw[i - v->nev] == t)      /* once it has left it */
            v->g0[i] = 0;
    return GSL_SUCCESS;
}

int
stepev_jump(StepEvents *v, double t, double *x, double *f)
{
    v->have_gd0 = 0; /* the next step starts from the inputs set here */
    int rc = v->mo.rate(t, x, f, v->mo.ctx);
    if (rc != GSL_SUCCESS)
        return rc;
    double soon = SIMULTANEOUS_ULPS * DBL_EPSILON * fmax(fabs(t), v->o->t_end - v->o->t0);
    return settle(v, t, x, f, soon, 0);
}

int
stepev_reset(StepEvents *v, int k, double t, double *x, double *f)
{
    eomc_sim *s = v->s;
    const eomc_model *m = v->m;
    double span = v->o->t_end - v->o->t0;
    v->ev_k = k;
    v->have_gd0 = 0; /* the state the next step starts from is the reset's */
    if (k >= v->nev)
        return flip(v, k, t, x, f);
    if (v->nsets > 0 && t - v->last_set < STEPEV_ACCUMULATE_REL * span)
        return STEPEV_ACCUMULATE;
    v->gap = t - v->last_set;
    v->last_set = t;
    v->nsets++;
    int dir = dir_of(v, k);
    double arrived = dir ? g_rate(v, k, t, x, f) : 0;
    eomc_sim_event_set(s, k, t, x, x);
    /* a unit quaternion set is one, whatever rounding the values carry */
    state_normalize(m, x, NULL);
    if (!sim_all_finite(x, v->N)) {
        sim_numeric_error(s, t, x, x + v->n, "event %s set a value that is not finite",
                          name_of(v, k));
        return GSL_EBADFUNC;
    }
    if (v->st->reset_event < 0 && m->nc > 0 &&
        eomc_sim_inconsistencies(s, t, x, x + v->n, v->ce, v->cl) > EOMC_INCONSISTENT)
        note_reset_off(v, k, t);
    int rc = v->mo.rate(t, x, f, v->mo.ctx);
    if (rc != GSL_SUCCESS)
        return rc;
    g_all(v, t, x, x + v->n, v->g0);
    v->g0[k] = 0;
    double left = dir && dir * arrived > 0 ? g_rate(v, k, t, x, f) / arrived : 0;
    v->held[k] = !(left > PASS_REL);
    v->left_rate = v->held[k] && left > 0 ? left : 0;
    return GSL_SUCCESS;
}

int
stepev_error(const StepEvents *v, int status, double t, const double *x)
{
    eomc_sim *s = v->s;
    const char *name = name_of(v, v->ev_k);
    if (status == STEPEV_ACCUMULATE && v->ev_k >= v->nev)
        return sim_numeric_error(s, t, x, x + v->n, "switch %s chatters: %d of its flips "
                                 "in a row each came within %g of the time span after the "
                                 "one before (the last two %.3g apart): the motion comes "
                                 "to rest against its kink in ever shorter intervals "
                                 "(Zeno), which no step can follow", name, STEPEV_CHATTER_FLIPS,
                                 STEPEV_ACCUMULATE_REL, t - v->last_set);
    if (status == STEPEV_ACCUMULATE)
        return sim_numeric_error(s, t, x, x + v->n, "the events accumulate: %s fired %ld "
                                 "times, the last two %.3g apart, below %g of the time "
                                 "span: the motion comes to rest against it in ever "
                                 "shorter intervals (Zeno), which no step can follow",
                                 name, v->nsets + 1, t - v->last_set, STEPEV_ACCUMULATE_REL);
    double flipped = v->ev_k >= v->nev ? v->tsw[v->ev_k - v->nev] : 0;
    if (v->ev_k >= v->nev && flipped == -INFINITY) /* on its kink since the start */
        return sim_numeric_error(s, t, x, x + v->n, "switch %s starts on its kink, and its "
                                 "function is across it at the end of the first step, with "
                                 "no point of the step on the side its mode was given: the "
                                 "motion slides along the kink (or its function is 0 to "
                                 "rounding there), which no mode follows", name);
    if (v->ev_k >= v->nev)
        return sim_numeric_error(s, t, x, x + v->n, "switch %s flipped at t = %.17g and its "
                                 "function is back across its kink at the end of the next "
                                 "step, within %g of it: the motion leaves the new mode as "
                                 "soon as it enters it, as if it slid along the kink, which "
                                 "no mode follows", name, flipped, t - flipped);
    if (v->left_rate > 0) /* moving on, too slowly to pass: not a return */
        return sim_numeric_error(s, t, x, x + v->n, "event %s holds still at the end of "
                                 "the first step after its reset at t = %.17g: the reset "
                                 "left the motion crossing it at %.2g of the rate it "
                                 "arrived with, too slow to tell from resting on it "
                                 "(passing through takes more than %g); a reset that "
                                 "passes should leave it faster, one that stops it should "
                                 "turn it back", name, v->last_set, v->left_rate, PASS_REL);
    return sim_numeric_error(s, t, x, x + v->n, "the events accumulate: %s holds again at "
                             "the end of the first step after its reset at t = %.17g (a "
                             "step of %.3g): the motion returns to it faster than the steps "
                             "can follow (it comes to rest against it%s)", name, v->last_set,
                             t - v->last_set, v->o->h_fixed > 0
                             ? ", or the fixed steps are too long" : "");
}
