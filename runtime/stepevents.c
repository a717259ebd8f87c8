/*
 * stepevents: the scene's events in the steps (stepevents.h).
 *
 * An event fires in a step where its g crossed zero (events.h).  Its time
 * is located first on the step's cubic Hermite interpolant (dense.h),
 * cheap and good enough to start from, then on the solution: a side step
 * from the step's start, the step layer's (StepevMotion).  The layer
 * sits between the steps (evolve.c) and the root search (events.c, which
 * knows no model): it knows the model's events, and the step only by the
 * ends it is handed, so that the stepper, the step's state and the watch
 * over the steps stay evolve.c's alone.
 */
#include "stepevents.h"
#include "simimpl.h"
#include "events.h"
#include "dense.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Events accumulate (a bouncing ball coming to rest, Zeno's paradox) when
 * a `set` event fires within ACCUMULATE_REL of the time span of the one
 * before: their times are no longer resolved (the steps between them
 * would be below the collapse limit of any run), and the next ones come
 * ever faster. */
#define ACCUMULATE_REL 1e-9
/* A reset passes through its event when it leaves g moving on the way it
 * crossed at more than PASS_REL of the rate it arrived with (a kick, a
 * switch of mode).  Anything slower, at rest or turned back (an impact),
 * is held at g = 0 until it leaves (stepev_check). */
#define PASS_REL 1e-6

struct StepEvents {
    eomc_sim *s;
    const eomc_model *m;          /* s's */
    const eomc_run_opts *o;
    eomc_stats *st;
    StepevMotion mo;
    int n, N;                     /* coordinates, state size 2n */
    int ne;                       /* events */
    double *g0, *g1;              /* [ne] g at the step's start and end */
    double *ge, *te;              /* [ne] scratch: g, and each event's time */
    double *xe;                   /* [N] the state at an event's trial time */
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
                      .N = 2 * m->nq, .ne = m->nevent, .last_set = -INFINITY};
    double **arrays[] = {&v->g0, &v->g1, &v->ge, &v->te, &v->xe, &v->ce};
    size_t ne = (size_t)v->ne, nc = (size_t)m->nc;
    size_t sizes[] = {ne, ne, ne, ne, (size_t)v->N, nc};
    int ok = 1;
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        ok &= (*arrays[k] = sim_zeros(sizes[k])) != NULL;
    ok &= (v->held = calloc(ne + 1, 1)) != NULL;
    ok &= (v->cl = calloc(nc + 1, sizeof *v->cl)) != NULL;
    if (!ok) {
        stepev_free(v);
        return NULL;
    }
    return v;
}

void
stepev_free(StepEvents *v)
{
    if (!v)
        return;
    double *arrays[] = {v->g0, v->g1, v->ge, v->te, v->xe, v->ce};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    free(v->held);
    free(v->cl);
    free(v);
}

void
stepev_start(StepEvents *v, double t, const double *x)
{
    eomc_sim_events(v->s, t, x, x + v->n, v->g0);
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
    eomc_sim_events(v->s, t, v->xe, v->xe + v->n, v->ge);
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
    eomc_sim_events(v->s, t, v->xe, v->xe + v->n, v->ge);
    return v->ge[v->ev_k];
}

int
stepev_check(StepEvents *v, const StepevSpan *sp, StepevHit *hit)
{
    eomc_sim *s = v->s;
    const eomc_model *m = v->m;
    double t0 = sp->t0, t1 = sp->t1;
    const double *x1 = sp->x1;
    int any = 0;
    *hit = (StepevHit){.k = -1, .status = EOMC_OK, .t = NAN};
    v->sp = *sp;
    eomc_sim_events(s, t1, x1, x1 + v->n, v->g1);
    for (int k = 0; k < v->ne; k++) {
        v->te[k] = NAN;
        /* an event reset at g = 0 must leave it away from where it fires
         * (up for a downward event): back there already, the motion
         * returned within one step, faster than the steps can follow */
        int dir = m->ev_direction[k];
        if (v->held[k] && dir != 0 && (v->g1[k] == 0 || (v->g1[k] < 0) == (dir < 0))) {
            v->ev_k = k;
            return STEPEV_RETURNED;
        }
        v->held[k] = 0;
        if (!ev_crossed(m->ev_direction[k], v->g0[k], v->g1[k]))
            continue;
        int evals;
        v->ev_k = k;
        double guess = ev_root(g_interpolant, v, t0, v->g0[k], t1, v->g1[k], NAN, &evals);
        v->te[k] = ev_root(g_solution, v, t0, v->g0[k], t1, v->g1[k], guess, &evals);
        if (isnan(v->te[k])) {
            sim_numeric_error(s, t1, x1, x1 + v->n, "event %s fired in the step from t = "
                              "%.17g, but the state at its trial times could not be "
                              "computed", m->ev_names[k], t0);
            return GSL_EBADFUNC;
        }
        any = 1;
    }
    memcpy(v->g0, v->g1, (size_t)v->ne * sizeof *v->g0);
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
        int rc = v->o->on_event ? v->o->on_event(v->o->event_ctx, k, t, v->xe) : EOMC_OK;
        if (rc != EOMC_OK) {
            *hit = (StepevHit){.k = -1, .status = rc, .t = t, .x = v->xe};
            return GSL_SUCCESS;
        }
        if (m->ev_action[k] == EOMC_EVENT_RECORD)
            continue;
        *hit = (StepevHit){.k = k, .status = EOMC_OK, .t = t, .x = v->xe};
        return GSL_SUCCESS;
    }
    return GSL_SUCCESS;
}

/* ---- reset ---- */

/* How fast event k's g changes along the motion at (t, x), whose
 * right-hand side is f: a central difference along the tangent over a
 * probe PROBE_REL of the step the event was found in.  It is exact for a
 * g quadratic in the state, and otherwise off by (probe)^2 g'''/6, a
 * millionth of what g changes by over a step; the rounding of g, spread
 * over a probe a thousandth of the step, stays far below PASS_REL of the
 * rate it arrived with (a millionth of the step lost 60% of a rate of
 * 1e-8 to it). */
#define PROBE_REL 1e-3
static double
g_rate(StepEvents *v, int k, double t, const double *x, const double *f)
{
    double d = PROBE_REL * (v->sp.t1 - v->sp.t0), g[2];
    for (int side = 0; side < 2; side++) {
        double s = side ? d : -d;
        for (int i = 0; i < v->N; i++)
            v->xe[i] = x[i] + s * f[i];
        eomc_sim_events(v->s, t + s, v->xe, v->xe + v->n, v->ge);
        g[side] = v->ge[k];
    }
    return (g[1] - g[0]) / (2 * d);
}

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

int
stepev_reset(StepEvents *v, int k, double t, double *x, double *f)
{
    eomc_sim *s = v->s;
    const eomc_model *m = v->m;
    double span = v->o->t_end - v->o->t0;
    v->ev_k = k;
    if (v->nsets > 0 && t - v->last_set < ACCUMULATE_REL * span)
        return STEPEV_ACCUMULATE;
    v->gap = t - v->last_set;
    v->last_set = t;
    v->nsets++;
    int dir = m->ev_direction[k];
    double arrived = dir ? g_rate(v, k, t, x, f) : 0;
    eomc_sim_event_set(s, k, t, x, x);
    if (!sim_all_finite(x, v->N)) {
        sim_numeric_error(s, t, x, x + v->n, "event %s set a value that is not finite",
                          m->ev_names[k]);
        return GSL_EBADFUNC;
    }
    if (v->st->reset_event < 0 && m->nc > 0 &&
        eomc_sim_inconsistencies(s, t, x, x + v->n, v->ce, v->cl) > EOMC_INCONSISTENT)
        note_reset_off(v, k, t);
    int rc = v->mo.rate(t, x, f, v->mo.ctx);
    if (rc != GSL_SUCCESS)
        return rc;
    eomc_sim_events(s, t, x, x + v->n, v->g0);
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
    const char *name = v->m->ev_names[v->ev_k];
    if (status == STEPEV_ACCUMULATE)
        return sim_numeric_error(s, t, x, x + v->n, "the events accumulate: %s fired %ld "
                                 "times, the last two %.3g apart, below %g of the time "
                                 "span: the motion comes to rest against it in ever "
                                 "shorter intervals (Zeno), which no step can follow",
                                 name, v->nsets + 1, t - v->last_set, ACCUMULATE_REL);
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
