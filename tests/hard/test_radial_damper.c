/*
 * Hard case: the radial damper of issue 9, item 1, written as virtual work
 * (work: -c*r'*delta(r), tests/hard/specs/radial_damper.yaml).
 *  - q'' against the closed form a = -(k/m) q - (c/m) r' q / r at the
 *    issue's state (x = 1, y = 0.5, x' = 0.3, y' = -0.2, k = 0:
 *    a = (-0.16, -0.08)) and at 100 random states;
 *  - over 10 s, the angular momentum m (x y' - y x') is conserved (the
 *    force is central), and the energy balance E(t) + int_0^t c r'^2 = E(0)
 *    holds, both computed here from the rows (Simpson's rule on rows every
 *    1e-3 s: its error, about 1e-13 here, is far below the test's).
 */
#include "hard.h"

extern const eomc_model radial_damper_model;

static void
accelerations(void)
{
    eomc_sim *s = eomc_sim_alloc(&radial_damper_model);
    double q[2] = {1, 0.5}, v[2] = {0.3, -0.2}, a[2];
    eomc_sim_set(s, "k", 0.0);
    int rc = eomc_sim_accel(s, 0.0, q, v, a);
    CHECK(rc == EOMC_OK && fabs(a[0] + 0.16) <= 1e-16 && fabs(a[1] + 0.08) <= 1e-16,
          "radial damper at (1, 0.5, 0.3, -0.2): q'' = (%.17g, %.17g), want (-0.16, -0.08)",
          a[0], a[1]);
    double worst = 0;
    for (int k = 0; k < 100; k++) {
        double m = check_rand(0.5, 3), c = check_rand(0, 2), kk = check_rand(0, 5);
        eomc_sim_set(s, "m", m), eomc_sim_set(s, "c", c), eomc_sim_set(s, "k", kk);
        q[0] = check_rand(-2, 2), q[1] = check_rand(-2, 2);
        v[0] = check_rand(-2, 2), v[1] = check_rand(-2, 2);
        double r = hypot(q[0], q[1]), rd = (q[0] * v[0] + q[1] * v[1]) / r;
        if (eomc_sim_accel(s, 0.0, q, v, a) != EOMC_OK)
            worst = HUGE_VAL;
        for (int i = 0; i < 2; i++) {
            double want = -(kk / m) * q[i] - (c / m) * rd * q[i] / r;
            worst = fmax(worst, fabs(a[i] - want) / (kk / m * r + c / m * fabs(rd) + 1e-300));
        }
    }
    CHECK(worst <= 1e-14, "radial damper: q'' = -(k/m) q - (c/m) r' q/r at 100 random "
          "states, to %.2g relative", worst);
    eomc_sim_free(s);
}

static void
motion(void)
{
    eomc_sim *s = eomc_sim_alloc(&radial_damper_model);
    eomc_run_opts o = eomc_run_defaults(&radial_damper_model);
    o.dt = 1e-3;
    Rows r = hard_run(s, &o, NULL);
    const double m = 1, c = 1, k = 4;
    double *E = calloc((size_t)r.nrows + 1, sizeof *E), *pw = calloc((size_t)r.nrows + 1, sizeof *pw);
    double L0 = 0, worst_L = 0, worst_E = 0, integral = 0;
    for (long i = 0; r.rc == EOMC_OK && i < r.nrows; i++) {
        const double *x = r.x + 4 * i;
        double rr = hypot(x[0], x[1]), rd = (x[0] * x[2] + x[1] * x[3]) / rr;
        double L = m * (x[0] * x[3] - x[1] * x[2]);
        E[i] = 0.5 * m * (x[2] * x[2] + x[3] * x[3]) + 0.5 * k * rr * rr;
        pw[i] = c * rd * rd; /* the power the damper takes */
        if (i == 0)
            L0 = L;
        worst_L = fmax(worst_L, fabs(L - L0));
        if (i % 2 == 0 && i > 0) { /* Simpson's rule over rows i - 2 .. i */
            integral += (r.t[i] - r.t[i - 2]) / 6 * (pw[i - 2] + 4 * pw[i - 1] + pw[i]);
            worst_E = fmax(worst_E, fabs(E[i] + integral - E[0]));
        }
    }
    CHECK(r.rc == EOMC_OK && worst_L <= 1e-11 * fabs(L0),
          "radial damper over 10 s: the angular momentum %.6g holds to %.2g (<= 1e-11 of "
          "it at rtol 1e-12)", L0, worst_L);
    CHECK(r.rc == EOMC_OK && r.nrows > 2 && worst_E <= 1e-10 * E[0],
          "radial damper over 10 s: E(t) + int c r'^2 = E(0) = %.6g to %.2g (<= 1e-10 of "
          "it; %.3g of it dissipated)", E[0], worst_E, integral / E[0]);
    free(E);
    free(pw);
    hard_free(&r);
    eomc_sim_free(s);
}

int
main(void)
{
    accelerations();
    motion();
    return check_done();
}
