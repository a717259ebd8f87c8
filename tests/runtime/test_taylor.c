/*
 * Taylor's method (--method taylor; runtime/step/taylor.c) on the oscillator
 * m x'' + k x = 0 with its hand-written series (models.c), against the
 * closed form x0 cos(w t) + v0 / w sin(w t), w = sqrt(k/m):
 *  - every row (the steps' own polynomials) within the tolerance of the
 *    closed form, no side step, the order Jorba and Zou's rule gives
 *    for the tolerance;
 *  - units: the same motion with time in another unit (k scaled, so w
 *    is; atol 0) takes the same steps, its rows on the closed form;
 *  - a `stop` event at its closed-form time, within a few ulp;
 *  - the refusals, each naming its cause: a model without series, rtol
 *    0, fixed steps.
 * The steps one at a time (eomc_sim_step) are test_step.c's, with the
 * other methods'.
 */
#include "../unit/check.h"
#include "rtest.h"

#include <float.h>

/* The largest difference of the rows from the closed form, relative to
 * the amplitude (x) and to w times it (x'). */
static double
worst_row(const Rows *r, double m, double k)
{
    double w = sqrt(k / m), a = hypot(OSC_X0, OSC_V0 / w), worst = 0;
    for (int i = 0; i < r->n; i++) {
        double xe, ve;
        osc_exact(m, k, OSC_X0, OSC_V0, r->t[i], &xe, &ve);
        const double *x = rows_x(r, i);
        worst = fmax(worst, fmax(fabs(x[0] - xe) / a, fabs(x[1] - ve) / (w * a)));
    }
    return worst;
}

static void
accuracy(void)
{
    static const double tols[] = {1e-6, 1e-10, 1e-13};
    for (int j = 0; j < 3; j++) {
        double tol = tols[j];
        eomc_sim *s = sim_new(&osc_model);
        eomc_run_opts o = opts_for(&osc_model, 10.0, 0.01, "taylor", tol, tol);
        double x[2];
        sim_x0(s, x);
        Rows r;
        rows_init(&r, 1);
        eomc_stats st;
        int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
        /* the global error of about 30 steps of local error rtol, and the
         * rounding of a few hundred operations a row */
        double worst = worst_row(&r, OSC_M, OSC_K), bound = 30 * tol + 1e-14;
        int p = (int)ceil(-0.5 * log(tol) + 1);
        CHECK(rc == EOMC_OK && r.n == 1001 && worst <= bound && st.side_steps == 0 &&
                  st.order_sum == (long)p * st.steps && st.rejected == 0,
              "rtol %g: %d rows within %.2g of the closed form (worst %.3g), %ld steps of "
              "order %d (%.3g on average), no side step (%ld)", tol, r.n, bound, worst,
              st.steps, p, st.steps ? (double)st.order_sum / st.steps : 0.0, st.side_steps);
        rows_free(&r);
        eomc_sim_free(s);
    }
}

/* Time in units c times smaller: the same motion is w' = c w, m' = m and
 * k' = c^2 k, the span and the output interval 1/c of the old. */
static void
units(void)
{
    const double c = 8.0; /* a power of 2: the times themselves scale exactly */
    double worst[2];
    long steps[2];
    for (int j = 0; j < 2; j++) {
        double sc = j ? c : 1.0;
        eomc_sim *s = sim_new(&osc_model);
        eomc_sim_set(s, "k", OSC_K * sc * sc);
        /* atol 0: the tolerance has no unit (docs/numerics.md, Time) */
        eomc_run_opts o = opts_for(&osc_model, 10.0 / sc, 0.01 / sc, "taylor", 1e-12, 0);
        double x[2];
        sim_x0(s, x);
        x[1] *= sc;
        Rows r;
        rows_init(&r, 1);
        eomc_stats st;
        eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
        for (int i = 0; i < r.n; i++) { /* back to the old units */
            r.t[i] *= sc;
            r.x[2 * i + 1] /= sc;
        }
        worst[j] = worst_row(&r, OSC_M, OSC_K);
        steps[j] = st.steps;
        rows_free(&r);
        eomc_sim_free(s);
    }
    CHECK(steps[0] == steps[1] && worst[1] <= 2e-14 && worst[0] <= 2e-14,
          "time in units 8 times smaller: as many steps (%ld, %ld), both on the closed form "
          "(%.3g, %.3g)", steps[0], steps[1], worst[0], worst[1]);
}

/* The `stop` event where x falls through 0, at
 * t = (pi/2 + atan(v0 / (w x0))) / w. */
static void
stop_event(void)
{
    eomc_sim *s = sim_new(&osc_event_model);
    eomc_run_opts o = opts_for(&osc_event_model, 5.0, 0.1, "taylor", 1e-13, 1e-13);
    double x[2];
    sim_x0(s, x);
    eomc_stats st;
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    double w = sqrt(OSC_K / OSC_M), te = (acos(-1.0) / 2 + atan(OSC_V0 / (w * OSC_X0))) / w;
    CHECK(rc == EOMC_OK && st.stop_event == 0 && fabs(st.t_stop - te) <= 8 * DBL_EPSILON * te &&
              fabs(x[0]) <= 8 * DBL_EPSILON * OSC_X0,
          "stop event at the closed form's t = %.17g: %.17g (%.2g ulp), x = %.3g", te,
          st.t_stop, (st.t_stop - te) / (DBL_EPSILON * te), x[0]);
    eomc_sim_free(s);
}

static void
refusals(void)
{
    struct {
        const eomc_model *m;
        double rtol, h;
        const char *says;
    } cases[] = {
        {&coupled_model, 1e-10, 0, "coupled has no Taylor series: a hand-written test model"},
        {&osc_model, 0, 0, "--rtol must be positive"},
        {&osc_model, 1e-10, 0.1, "chooses its own steps"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        eomc_sim *s = sim_new(cases[k].m);
        eomc_run_opts o = opts_for(cases[k].m, 1.0, 0.1, "taylor", cases[k].rtol, 1e-10);
        o.h_fixed = cases[k].h;
        int rc = eomc_run_check(s, &o);
        CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), cases[k].says),
              "refused: %s", eomc_sim_error(s));
        eomc_sim_free(s);
    }
}

int
main(void)
{
    accuracy();
    units();
    stop_event();
    refusals();
    return check_done();
}
