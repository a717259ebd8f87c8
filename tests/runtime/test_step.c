/*
 * eomc_sim_step, the steps one at a time (eomc.h), on the oscillator
 * m x'' + k x = 0 (models.h):
 *  - every step end on the closed form, and the dense output inside every
 *    step within the cubic Hermite interpolant's own error bound,
 *    h^4 / 384 max |x''''|, of the closed form; under Taylor's method,
 *    whose dense output is the step's own polynomial, within twice the
 *    step ends' largest error, far inside that bound;
 *  - the last step ends exactly at t_end, and its state is
 *    eomc_sim_integrate's to the last bit, with as many steps and
 *    right-hand sides (adaptive rk8pd, msbdf, taylor, and fixed rk4
 *    steps);
 *  - a `stop` event ends the steps at its closed-form time, as
 *    eomc_sim_integrate stops there;
 *  - once the run is over, another step is a usage error.
 */
#include "../unit/check.h"
#include "rtest.h"

/* The largest |x''''| of the oscillator's coordinate (w^4 A) and of its
 * velocity (w^5 A), A its amplitude. */
static void
fourth_derivatives(double *dq, double *dv)
{
    double w = sqrt(OSC_K / OSC_M), a = hypot(OSC_X0, OSC_V0 / w);
    *dq = pow(w, 4) * a;
    *dv = pow(w, 5) * a;
}

/* Drive o step by step from the initial state; checks along the way: the
 * step ends within tol of the closed form (what the method's global error
 * comes to at its tolerance), and inside the steps within the
 * interpolant's bound of it beyond that, or for a method whose dense
 * output is its step's polynomial (series), within twice the ends'
 * largest error. */
static void
stepwise(const eomc_run_opts *o, const char *what, double tol, int series)
{
    eomc_sim *s = sim_new(&osc_model);
    double x0[2], x[2];
    sim_x0(s, x0);
    eomc_evolve *e = eomc_evolve_alloc(s, o, x0);
    CHECK(e != NULL, "%s: eomc_evolve_alloc: %s", what, e ? "ok" : eomc_sim_error(s));
    if (!e) {
        eomc_sim_free(s);
        return;
    }
    double dq, dv, worst_end = 0, worst_inside = 0, hermite = 0, inside_abs = 0;
    fourth_derivatives(&dq, &dv);
    eomc_step d = {0};
    int rc = EOMC_OK, chained = 1;
    long steps = 0;
    double t_prev = o->t0, x_prev[2] = {x0[0], x0[1]};
    while (rc == EOMC_OK && !d.last) {
        rc = eomc_sim_step(s, e, &d);
        if (rc != EOMC_OK)
            break;
        steps++;
        /* each step starts where the one before ended */
        chained &= d.t0 == t_prev && d.x0[0] == x_prev[0] && d.x0[1] == x_prev[1];
        t_prev = d.t1, x_prev[0] = d.x1[0], x_prev[1] = d.x1[1];
        double xe, ve, h = d.t1 - d.t0, bound = series ? 0 : pow(h, 4) / 384;
        osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, d.t1, &xe, &ve);
        worst_end = fmax(worst_end, fmax(fabs(d.x1[0] - xe), fabs(d.x1[1] - ve)));
        /* inside: against the interpolant's bound, beyond the ends' error */
        for (int j = 1; j < 4; j++) {
            double t = d.t0 + h * j / 4;
            eomc_step_eval(&d, t, x);
            osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, t, &xe, &ve);
            worst_inside = fmax(worst_inside, fmax(fabs(x[0] - xe) / (bound * dq + tol),
                                                   fabs(x[1] - ve) / (bound * dv + tol)));
            inside_abs = fmax(inside_abs, fmax(fabs(x[0] - xe), fabs(x[1] - ve)));
            hermite = fmax(hermite, pow(h, 4) / 384 * dq / tol);
        }
    }
    CHECK(rc == EOMC_OK && d.last && d.t1 == o->t_end && chained,
          "%s: %ld steps, each from the end of the one before, the last ending exactly at "
          "t_end = %g (got %.17g)", what, steps, o->t_end, d.t1);
    CHECK(worst_end < tol, "%s: every step end on the closed form to %g (largest error %.3g)",
          what, tol, worst_end);
    if (series)
        CHECK(inside_abs <= 2 * worst_end && hermite > 1e3,
              "%s: the dense output inside every step, the step's own polynomial, within "
              "twice the step ends' largest error of the closed form (%.3g against %.3g), "
              "where the steps' cubic Hermite interpolant's bound is up to %.3g times %g",
              what, inside_abs, worst_end, hermite, tol);
    else
        CHECK(worst_inside <= 1, "%s: the dense output inside every step within the cubic "
              "Hermite bound h^4/384 max|x''''| of the closed form (worst: %.3g of it)", what,
              worst_inside);

    /* the same run through eomc_sim_integrate */
    eomc_stats st;
    double xi[2] = {x0[0], x0[1]};
    int rci = eomc_sim_integrate(s, o, xi, NULL, NULL, &st);
    const eomc_stats *se = eomc_evolve_stats(e);
    CHECK(rci == EOMC_OK && xi[0] == d.x1[0] && xi[1] == d.x1[1] && st.steps == se->steps &&
              st.rhs_evals == se->rhs_evals && st.h_used == se->h_used,
          "%s: eomc_sim_integrate's state at t_end to the last bit, as many steps (%ld, %ld) "
          "and right-hand sides (%ld, %ld)", what, st.steps, se->steps, st.rhs_evals,
          se->rhs_evals);
    CHECK(eomc_sim_step(s, e, &d) == EOMC_EUSAGE && strstr(eomc_sim_error(s), "over"),
          "%s: a step after the last: EOMC_EUSAGE (%s)", what, eomc_sim_error(s));
    eomc_evolve_free(e);
    eomc_sim_free(s);
}

/* The `stop` event ends the steps where it fires, as it ends a run. */
static void
stop_event(void)
{
    eomc_sim *s = sim_new(&osc_event_model);
    eomc_run_opts o = opts_for(&osc_event_model, 5.0, 0.1, "rk8pd", 1e-12, 1e-12);
    double x0[2];
    sim_x0(s, x0);
    eomc_evolve *e = eomc_evolve_alloc(s, &o, x0);
    eomc_step d = {0};
    int rc = e ? EOMC_OK : EOMC_EUSAGE;
    while (rc == EOMC_OK && !d.last)
        rc = eomc_sim_step(s, e, &d);
    double w = sqrt(OSC_K / OSC_M), te = (acos(-1.0) / 2 + atan(OSC_V0 / (w * OSC_X0))) / w;
    eomc_stats st;
    double xi[2] = {x0[0], x0[1]};
    int rci = eomc_sim_integrate(s, &o, xi, NULL, NULL, &st);
    CHECK(rc == EOMC_OK && d.last && d.event == 0 && fabs(d.t1 - te) < 1e-9 &&
              fabs(d.x1[0]) < 1e-9,
          "stop event: the last step ends at the closed form's t = %.12g (got %.12g), x = 0 "
          "(got %.3g)", te, d.t1, e ? d.x1[0] : NAN);
    CHECK(rci == EOMC_OK && st.t_stop == d.t1 && xi[0] == d.x1[0] && xi[1] == d.x1[1],
          "stop event: eomc_sim_integrate stops at the same time and state, to the last bit");
    eomc_evolve_free(e);
    eomc_sim_free(s);
}

int
main(void)
{
    eomc_run_opts o = opts_for(&osc_model, 10.0, 0.1, "rk8pd", 1e-10, 1e-10);
    stepwise(&o, "rk8pd at 1e-10", 1e-8, 0);
    o = opts_for(&osc_model, 10.0, 0.1, "msbdf", 1e-9, 1e-9);
    stepwise(&o, "msbdf at 1e-9", 1e-5, 0);
    o = opts_for(&osc_model, 10.0, 0.1, "taylor", 1e-12, 1e-12);
    stepwise(&o, "taylor at 1e-12", 1e-10, 1);
    o = opts_for(&osc_model, 10.0, 0.1, "rk4", 0, 0);
    o.h_fixed = 0.01;
    stepwise(&o, "rk4, fixed steps of 0.01", 1e-6, 0);
    stop_event();
    return check_done();
}
