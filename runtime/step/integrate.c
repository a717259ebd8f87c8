/*
 * integrate: the integration driver (eomc_sim_integrate), on the steps of
 * evolve.h.
 *
 * It is GSL's driver with these differences:
 *  - output rows are not step ends: the steps go as the tolerance allows,
 *    straight to t_end, and each row is read off the interpolant of
 *    dense.c (so a small --dt costs no steps);
 *  - a row the interpolant cannot give to the tolerances is computed by a
 *    step of its own (side_step);
 *  - a `set` event's reset starts the interpolant afresh, and a `stop`
 *    event ends the rows with one at the event itself;
 *  - Taylor's method's rows are its steps' own polynomials (taylor.h),
 *    no interpolant and no side step;
 *  - a row's unit quaternions are renormalized, as the steps' ends are
 *    (the exact motion has |e| = 1; the interpolant is off it by its error).
 */
#include "integrate.h"
#include "evolve.h"
#include "model/simimpl.h"
#include "model/state.h"
#include "dense.h"
#include "taylor.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* An output time within this fraction of dt of t_end is t_end: no sliver
 * of an interval at the end. */
#define SLIVER 1e-9
/* march's status when a stop event ended the run (not a GSL code, and
 * not one of the step layer's, evolve.h). */
enum { EVENT_STOPPED = -1100 };
/* march_step's status when the run goes on. */
enum { MARCH_ON = -1101 };

typedef struct Driver {
    eomc_evolve *e;               /* the steps */
    eomc_sim *s;
    const eomc_run_opts *o;
    eomc_stats *st;
    int n, N;                     /* coordinates, state size nq + nv */
    double *x;                    /* the current state (the caller's array) */
    Dense *dense;
    double *xrow, *erow;          /* an interpolated row, its error estimate */
    double *qdd;                  /* [nq] a node's q'' (speeds of their own), or NULL */
    long k, nrows;                /* the next row, and how many there are */
    eomc_row_fn row;
    void *ctx;
    double c0;                    /* the CPU time at the start */
    int rc;                       /* driver_start's status */
} Driver;

/* ---- rows ---- */

/* Row k's time of nrows: t0 + k dt is computed from k, so no rounding
 * accumulates. */
static double
row_at(const eomc_run_opts *o, long nrows, long k)
{
    return k == nrows - 1 ? o->t_end : o->t0 + (double)k * o->dt;
}

double
eomc_run_row_time(const eomc_run_opts *o, long k)
{
    return row_at(o, eomc_run_rows(o), k);
}

long
eomc_run_rows(const eomc_run_opts *o)
{
    double span = o->t_end - o->t0;
    if (!(span > 0))
        return 1;
    /* rows 0 .. K, K the first k with t0 + k dt within a sliver of t_end */
    double K = ceil(span / o->dt - SLIVER);
    if (!(o->t0 + K * o->dt >= o->t_end - SLIVER * o->dt))
        K += 1;
    return (long)K + 1;
}

/* eomc_run_row_time with the rows counted once (the count is a division
 * and a ceil, at every step). */
static double
row_time(const Driver *r, long k)
{
    return row_at(r->o, r->nrows, k);
}

/* Whether the interpolant's error estimate err passes the run's test,
 * |err_i| <= atol + rtol |x_i|, the test of GSL's step control.  Fixed
 * steps have no tolerance to pass: there the interpolant stands (its
 * error is that of the node values it passes through, or less). */
static int
interpolant_ok(const Driver *r, const double *x, const double *err)
{
    if (r->o->h_fixed > 0)
        return 1;
    for (int i = 0; i < r->N; i++)
        if (!(err[i] <= r->o->atol + r->o->rtol * fabs(x[i])))
            return 0;
    return 1;
}

/* The row at t by a step of its own from the node before it
 * (evolve_side). */
static int
side_step(Driver *r, double t, double *x)
{
    const double *xk, *fk;
    double tk = dense_start(r->dense, t, &xk, &fk);
    r->st->side_steps++;
    if (evolve_side(r->e, tk, xk, fk, t, x) == GSL_SUCCESS)
        return GSL_SUCCESS;
    sim_numeric_error(r->s, t, NULL, NULL, "the row at this time could not be computed to "
                      "the tolerances, neither by interpolation nor by %d steps from "
                      "t = %.17g", EVOLVE_SIDE_PIECES, tk);
    return GSL_EBADFUNC;
}

/* Pass every row whose value is settled to the callback (all up to the
 * last node when final); EVOLVE_STOPPED when the callback says stop. */
static int
emit_rows(Driver *r, int final)
{
    while (r->k < r->nrows) {
        double t = row_time(r, r->k);
        if (t > dense_last(r->dense) || !dense_ready(r->dense, t, final))
            return GSL_SUCCESS;
        dense_eval(r->dense, t, final, r->xrow, r->erow);
        if (!interpolant_ok(r, r->xrow, r->erow)) {
            dense_refine(r->dense);
            dense_eval(r->dense, t, final, r->xrow, r->erow);
        }
        if (!interpolant_ok(r, r->xrow, r->erow)) {
            int rc = side_step(r, t, r->xrow);
            if (rc != GSL_SUCCESS)
                return rc;
        }
        /* renormalized steps, renormalized rows; projected steps, projected
         * rows: the interpolant is only as close to the unit quaternions and
         * the constraints as it is to the motion */
        state_normalize(eomc_sim_model(r->s), r->xrow, NULL);
        if (sim_stabilize_method(r->s) == EOMC_STABILIZE_PROJECT &&
            eomc_sim_project(r->s, t, r->xrow, r->xrow + r->n) != EOMC_OK)
            return GSL_EBADFUNC;
        int rc = r->row ? r->row(r->ctx, t, r->xrow) : EOMC_OK;
        if (rc != EOMC_OK)
            return evolve_stop(r->e, rc, t, r->xrow); /* xrow: the driver's until it returns */
        r->k++;
    }
    return GSL_SUCCESS;
}

/* Taylor's method: every row up to the step's end tk->t1, from the step's
 * series (EVOLVE_STOPPED when the callback says stop). */
static int
series_rows(Driver *r, const EvolveStep *tk)
{
    while (r->k < r->nrows) {
        double t = row_time(r, r->k);
        if (t > tk->t1)
            return GSL_SUCCESS;
        if (t == tk->t1) {
            memcpy(r->xrow, tk->x1, (size_t)r->N * sizeof *r->xrow);
        } else { /* a row of the motion: its unit quaternions renormalized, as
                  * the steps' ends are */
            taylor_eval(tk->series, t - tk->t0, r->xrow);
            state_normalize(eomc_sim_model(r->s), r->xrow, NULL);
        }
        int rc = r->row ? r->row(r->ctx, t, r->xrow) : EOMC_OK;
        if (rc != EOMC_OK)
            return evolve_stop(r->e, rc, t, r->xrow);
        r->k++;
    }
    return GSL_SUCCESS;
}

/* A stop event ended the run at tk->t1: the rows up to it, then a last
 * row at the event itself. */
static int
finish_at_event(Driver *r, const EvolveStep *tk)
{
    int rc = tk->series ? series_rows(r, tk) : emit_rows(r, 1);
    if (rc != GSL_SUCCESS)
        return rc;
    if (r->k > 0 && row_time(r, r->k - 1) >= tk->t1)
        return EVENT_STOPPED;
    rc = r->row ? r->row(r->ctx, tk->t1, tk->x1) : EOMC_OK;
    return rc != EOMC_OK ? evolve_stop(r->e, rc, tk->t1, tk->x1) : EVENT_STOPPED;
}

/* ---- the loop ---- */

/* Speeds from the coordinates' rates, for the interpolant (dense.h). */
static int
to_speeds(void *ctx, const double *q, const double *qd, double *v)
{
    return sim_speeds_of(ctx, q, qd, v);
}

/* A node of the interpolant at (t, x) with x' = f: with speeds of their
 * own, the coordinates' q'' too, where the model can give it. */
static void
push_node(Driver *r, double t, const double *x, const double *f)
{
    int have = r->qdd && sim_qddot(r->s, x, f, r->qdd) == 0;
    dense_push(r->dense, t, x, f, have ? r->qdd : NULL);
}

/* One step by evolve_step, passing rows as they are settled: the step
 * ends are the interpolant's nodes (dense.h).  MARCH_ON while t_end is
 * not reached, else march's status. */
static int
march_step(Driver *r)
{
    if (!evolve_more(r->e))
        return GSL_SUCCESS;
    EvolveStep tk;
    int rc = evolve_step(r->e, &tk);
    if (tk.series) { /* Taylor's method: each step's own polynomial */
        if (rc != GSL_SUCCESS)
            return rc;
        if (tk.taken && tk.ev == EVOLVE_STOP)
            return finish_at_event(r, &tk);
        if (tk.taken && (rc = series_rows(r, &tk)) != GSL_SUCCESS)
            return rc;
        return MARCH_ON;
    }
    if (tk.restarted) /* the nodes before the reset are another motion's */
        dense_clear(r->dense);
    if (tk.restarted && tk.taken)
        push_node(r, tk.t0, tk.x0, tk.f0);
    if (tk.taken)
        push_node(r, tk.t1, tk.x1, tk.f1);
    else if (!isnan(tk.reached) && !tk.restarted)
        push_node(r, tk.reached, tk.xr, tk.fr);
    if (rc != GSL_SUCCESS)
        return rc;
    if (tk.ev == EVOLVE_STOP)
        return finish_at_event(r, &tk);
    /* before a reset (or a sample's new inputs), every row up to it */
    if ((rc = emit_rows(r, tk.ev == EVOLVE_SET || tk.sampled)) != GSL_SUCCESS)
        return rc;
    return MARCH_ON;
}

/* Integrate to t_end: GSL_SUCCESS, or a status for driver_close. */
static int
march(Driver *r)
{
    int rc;
    while ((rc = march_step(r)) == MARCH_ON)
        ;
    return rc;
}

static void
driver_free(Driver *r)
{
    eomc_evolve_free(r->e);
    dense_free(r->dense);
    free(r->xrow);
    free(r->erow);
    free(r->qdd);
}

/* The first row: the initial state, as it is, after the equations at t0
 * (a model that cannot be solved there writes no row); then what the
 * steps' watches start from. */
static int
driver_start(Driver *r)
{
    int rc = evolve_start(r->e, r->nrows > 1);
    if (rc != EOMC_OK)
        return rc;
    rc = r->row ? r->row(r->ctx, r->o->t0, r->x) : EOMC_OK;
    r->k = 1;
    return rc == EOMC_OK ? evolve_watch(r->e) : rc;
}

/* A run of s from x as eomc_sim_integrate's, up to its first step: the
 * first row written (driver_start), the steps begun.  EOMC_OK with
 * *status MARCH_ON where steps follow (march_step takes them), else
 * GSL_SUCCESS; or a status with its message, and driver_close is not
 * called. */
static int
driver_open(Driver *r, eomc_sim *s, const eomc_run_opts *o, double *x, eomc_row_fn row,
            void *ctx, eomc_stats *st, int *status)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq;
    *r = (Driver){.s = s, .o = o, .st = st, .n = n, .N = eomc_nx(m), .x = x, .row = row,
                  .ctx = ctx};
    /* a unit quaternion starts at length 1: the motion keeps |e|, and the
     * steps renormalize it (a start off 1 is the caller's to warn about:
     * eomc_main does) */
    if (sim_all_finite(x, r->N))
        state_normalize(m, x, NULL);
    /* the constraint rows this run's solves use, chosen where it starts */
    int rc = sim_start_rows(s, o->t0, x, x + n);
    if (rc == EOMC_OK)
        rc = evolve_open(&r->e, s, o, x, st);
    if (rc == EOMC_OK) {
        r->nrows = eomc_run_rows(o);
        r->dense = dense_alloc(n, m->nv > 0 ? m->nv : 0);
        r->xrow = sim_zeros((size_t)r->N);
        r->erow = sim_zeros((size_t)r->N);
        r->qdd = m->nv > 0 && m->qdot_jacobian ? sim_zeros((size_t)n) : NULL;
        if (r->dense && r->qdd)
            dense_set_speeds(r->dense, to_speeds, s);
        if (!r->dense || !r->xrow || !r->erow || (m->nv > 0 && m->qdot_jacobian && !r->qdd))
            rc = sim_usage_error(s, "out of memory setting up %s", o->method);
    }
    if (rc != EOMC_OK) {
        driver_free(r);
        return rc;
    }
    r->c0 = sim_seconds(1);
    *status = GSL_SUCCESS;
    rc = driver_start(r);
    if (rc == EOMC_OK && r->nrows > 1) {
        push_node(r, o->t0, x, evolve_rate(r->e));
        evolve_begin(r->e);
        *status = MARCH_ON;
    }
    r->rc = rc;
    return EOMC_OK;
}

/* The run's end after march's status: its last rows, x where it stopped,
 * st's time, the driver freed; eomc_sim_integrate's status. */
static int
driver_close(Driver *r, int status)
{
    int rc = r->rc;
    if (rc == EOMC_OK && r->nrows > 1) {
        /* the rows up to the last step reached stand, also after a failure */
        if (status != EVOLVE_STOPPED && status != EVENT_STOPPED) {
            int flushed = emit_rows(r, 1);
            if (status == GSL_SUCCESS)
                status = flushed;
        }
        /* x is where the run stopped: the last state reached (t_end, a stop
         * event, a failure), or the state a callback stopped it at */
        double t = evolve_time(r->e);
        r->st->t_stop = t;
        if (status == EVOLVE_STOPPED) { /* a callback (a row's or on_event) said stop */
            const double *stop_x;
            rc = evolve_stopped(r->e, &r->st->t_stop, &stop_x);
            if (stop_x != r->x)
                memcpy(r->x, stop_x, (size_t)r->N * sizeof *r->x);
        } else if (status == EVENT_STOPPED)
            rc = EOMC_OK;
        else if (status != GSL_SUCCESS)
            rc = evolve_error(r->e, status);
        else if (!sim_all_finite(r->x, r->N))
            rc = sim_numeric_error(r->s, t, r->x, r->x + r->n, "the state is not finite");
    }
    r->st->cpu_seconds = sim_seconds(1) - r->c0;
    driver_free(r);
    return rc;
}

int
eomc_sim_integrate(eomc_sim *s, const eomc_run_opts *o, double *x, eomc_row_fn row,
                   void *ctx, eomc_stats *st)
{
    eomc_stats local;
    Driver r;
    int status, rc = driver_open(&r, s, o, x, row, ctx, st ? st : &local, &status);
    if (rc != EOMC_OK)
        return rc;
    if (status == MARCH_ON)
        status = march(&r);
    return driver_close(&r, status);
}

/* ---- runs EOMC_LANES at a time (integrate.h) ---- */

/* Lane l's next run, from next(), up to its first step; a run that ends
 * there (a failure, or a single row) goes back by done() at once. */
static void
lane_start(Driver *d, int *status, int *live, IntegrateLane *lane, const eomc_run_opts *o,
           const IntegrateRuns *runs)
{
    *live = 0;
    while (runs->next(runs->ctx, lane)) {
        lane->rc = driver_open(d, lane->s, o, lane->x, lane->row, lane->ctx, lane->st, status);
        if (lane->rc == EOMC_OK && *status == MARCH_ON) {
            *live = 1;
            return;
        }
        if (lane->rc == EOMC_OK)
            lane->rc = driver_close(d, *status);
        runs->done(runs->ctx, lane);
    }
}

int
integrate_lanes(const eomc_model *m, const eomc_run_opts *o, const IntegrateRuns *runs)
{
    Driver d[EOMC_LANES];
    IntegrateLane lane[EOMC_LANES];
    int status[EOMC_LANES], live[EOMC_LANES], any = 0;
    TaylorLanes *b = taylor_lanes_alloc(m, o); /* NULL: each run alone */
    for (int l = 0; l < EOMC_LANES; l++) {
        lane[l] = (IntegrateLane){0};
        lane_start(&d[l], &status[l], &live[l], &lane[l], o, runs);
        any |= live[l];
    }
    while (any) {
        Taylor *tp[EOMC_LANES];
        double t0[EOMC_LANES];
        const double *x[EOMC_LANES];
        int fill = 0;
        for (int l = 0; l < EOMC_LANES && b; l++) {
            tp[l] = live[l] ? evolve_taylor(d[l].e, &x[l]) : NULL;
            t0[l] = live[l] ? evolve_time(d[l].e) : 0;
            fill += tp[l] != NULL;
        }
        /* one lane alone gains nothing from the vectors */
        if (fill > 1 && taylor_lanes_fill(b, tp, t0, x) != 0) {
            taylor_lanes_free(b);
            b = NULL;
        }
        any = 0;
        for (int l = 0; l < EOMC_LANES; l++) {
            if (!live[l])
                continue;
            status[l] = march_step(&d[l]);
            if (status[l] != MARCH_ON) {
                lane[l].rc = driver_close(&d[l], status[l]);
                runs->done(runs->ctx, &lane[l]);
                lane_start(&d[l], &status[l], &live[l], &lane[l], o, runs);
            }
            any |= live[l];
        }
    }
    taylor_lanes_free(b);
    return EOMC_OK;
}
