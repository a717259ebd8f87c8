/*
 * Hard case: stiff systems.  tests/hard/specs/stiff_spring.yaml: a damped
 * spring with roots -1 and -1e4, x = (e^-t - 1e-4 e^-(1e4 t)) / (1 - 1e-4),
 * over 100 s at rtol 1e-8.
 *  - every method (explicit and implicit) on the closed form;
 *  - the implicit methods do the work in a hundredth or less: right-hand
 *    sides plus Jacobians (each counted as 2n + 1 right-hand sides, what a
 *    finite-difference one would cost) of the cheapest explicit method
 *    against the dearest implicit one, at least 10 times.  (The CPU times,
 *    which follow, are measured by bench/hard_bench.sh and in the README's
 *    table; tests do not time.)
 * tests/hard/specs/vdpol.yaml, the test set for IVP solvers' Van der Pol
 * problem VDPOL (stiffness 1e6; its jumps at |x| = 1 take steps a million
 * times shorter than the creep between, and msbdf rejects 12% of its
 * attempts):
 *  - msbdf at rtol 1e-10 runs to t = 2, neither collapsing nor grinding,
 *    to the test set's reference y(2) (RADAU in extended precision, its
 *    vdpol.f) within 5e-8, its error at 1.4e-8 (before issue 21 its rows
 *    could not be computed: their side steps were rk8pd's, explicit).
 */
#include "hard.h"

extern const eomc_model stiff_spring_model, vdpol_model;

static double
exact(double t)
{
    return (exp(-t) - 1e-4 * exp(-1e4 * t)) / (1 - 1e-4);
}

/* The test set's reference at t = 2 (solut in vdpol.f). */
static const double vdpol_ref[2] = {0.1706167732170483e+01, -0.8928097010247975e+00};

static void
vdpol(void)
{
    eomc_sim *s = eomc_sim_alloc(&vdpol_model);
    eomc_run_opts o = eomc_run_defaults(&vdpol_model);
    Rows r = hard_run(s, &o, NULL);
    const double *x = r.nrows ? r.x + 2 * (r.nrows - 1) : NULL;
    double err = x ? fmax(fabs(x[0] - vdpol_ref[0]), fabs(x[1] - vdpol_ref[1])) : HUGE_VAL;
    CHECK(r.rc == EOMC_OK && r.t[r.nrows - 1] == 2 && err <= 5e-8,
          "Van der Pol (VDPOL, stiffness 1e6), msbdf at rtol 1e-10: runs to t = 2 (%s), "
          "%ld steps and %ld rejected, within %.2g of the test set's y(2) (<= 5e-8)",
          r.rc ? r.error : "ok", r.st.steps, r.st.rejected, err);
    hard_free(&r);
    eomc_sim_free(s);
}

int
main(void)
{
    vdpol();
    const char *methods[] = {"rkf45", "rk8pd", "msbdf", "rk4imp", "bsimp"};
    const int implicit[] = {0, 0, 1, 1, 1};
    double work[5], err[5];
    for (int k = 0; k < 5; k++) {
        eomc_sim *s = eomc_sim_alloc(&stiff_spring_model);
        eomc_run_opts o = eomc_run_defaults(&stiff_spring_model);
        o.method = methods[k];
        Rows r = hard_run(s, &o, NULL);
        err[k] = r.rc == EOMC_OK ? 0 : HUGE_VAL;
        for (long i = 0; i < r.nrows; i++)
            err[k] = fmax(err[k], fabs(r.x[2 * i] - exact(r.t[i])));
        work[k] = (double)r.st.rhs_evals + 3.0 * (double)r.st.jac_evals;
        CHECK(err[k] <= (implicit[k] ? 1e-6 : 1e-10),
              "stiff spring, %s at rtol 1e-8: within %.2g of the closed form (<= %g), "
              "%ld steps, work %.0f", methods[k], err[k], implicit[k] ? 1e-6 : 1e-10,
              r.st.steps, work[k]);
        hard_free(&r);
        eomc_sim_free(s);
    }
    double explicit_min = fmin(work[0], work[1]);
    double implicit_max = fmax(work[2], fmax(work[3], work[4]));
    CHECK(explicit_min >= 10 * implicit_max,
          "stiff spring: the cheapest explicit method does %.0f times the work of the "
          "dearest implicit one (>= 10)", explicit_min / implicit_max);
    return check_done();
}
