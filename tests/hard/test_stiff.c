/*
 * Hard case: a stiff system, tests/hard/specs/stiff_spring.yaml: a damped
 * spring with roots -1 and -1e4, x = (e^-t - 1e-4 e^-(1e4 t)) / (1 - 1e-4),
 * over 100 s at rtol 1e-8.
 *  - every method (explicit and implicit) on the closed form;
 *  - the implicit methods do the work in a hundredth or less: right-hand
 *    sides plus Jacobians (each counted as 2n + 1 right-hand sides, what a
 *    finite-difference one would cost) of the cheapest explicit method
 *    against the dearest implicit one, at least 10 times.  (The CPU times,
 *    which follow, are measured by bench/hard_bench.sh and in the README's
 *    table; tests do not time.)
 */
#include "hard.h"

extern const eomc_model stiff_spring_model;

static double
exact(double t)
{
    return (exp(-t) - 1e-4 * exp(-1e4 * t)) / (1 - 1e-4);
}

int
main(void)
{
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
