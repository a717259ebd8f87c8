/*
 * Hard case: a pendulum released 1e-6 from its unstable equilibrium
 * (specs/pendulum.yaml, theta0 = pi - 1e-6, from rest).  Its period is
 * 4 K(k) sqrt(l/g), k = sin(theta0 / 2), with K computed here as
 * pi / (2 AGM(1, k')), k' = cos(theta0 / 2) = sin(1e-6 / 2) (no
 * cancellation: 1 - k^2 would lose 13 digits), about 20.3 s, most of it
 * spent near the top where every error grows as e^(sqrt(g/l) t).
 *  - it passes the bottom at T/4 (the time of the crossing from the row
 *    there, theta / theta'), to within 5e-8 s (1e-8 of T/4);
 *  - it comes up to the top on the other side at T/2, within half its
 *    release distance of -theta0 (neither falling back nor going over).
 * rk8pd at rtol 1e-12.
 */
#include "hard.h"

extern const eomc_model pendulum_model;

int
main(void)
{
    const double delta = 1e-6, g = 9.81, l = 1, th0 = 3.14159265358979323846 - delta;
    double a = 1, b = sin(delta / 2);
    for (int i = 0; i < 60; i++) { /* the arithmetic-geometric mean */
        double m = 0.5 * (a + b);
        b = sqrt(a * b), a = m;
    }
    double K = 3.14159265358979323846 / (2 * a), T = 4 * K * sqrt(l / g);
    eomc_sim *s = eomc_sim_alloc(&pendulum_model);
    eomc_run_opts o = eomc_run_defaults(&pendulum_model);
    o.rtol = o.atol = 1e-12, o.t_end = T / 2, o.dt = T / 4;
    double x0[2] = {th0, 0};
    Rows r = hard_run(s, &o, x0);
    int ok = r.rc == EOMC_OK && r.nrows == 3;
    double cross = ok ? r.x[2] / r.x[3] : HUGE_VAL; /* theta / theta' at T/4 */
    double top = ok ? r.x[4] + th0 : HUGE_VAL;
    CHECK(ok && fabs(cross) <= 5e-8,
          "pendulum from 1e-6 below the top: it passes the bottom at T/4 = %.12g s "
          "(K = %.15g) to within %.2g s (<= 5e-8)", T / 4, K, fabs(cross));
    CHECK(ok && fabs(top) <= 0.5 * delta,
          "... and is at the top on the other side at T/2 = %.10g s, %.2g from -theta0 "
          "(<= 5e-7: half the release distance), %ld steps", T / 2, top, r.st.steps);
    hard_free(&r);
    eomc_sim_free(s);
    return check_done();
}
