/*
 * Hard case: a degenerate constraint.  Appell's particle (specs/appell.yaml,
 * the velocity kept at a fixed angle to the horizontal, z'^2 =
 * a^2 (x'^2 + y'^2)) on its decelerating branch z' = -a v: with y' = 0,
 *     x' = v0 - a g t / (1 + a^2),  x = v0 t - a g t^2 / (2 (1 + a^2)),
 *     z = -a x,
 * until the speed reaches 0 at t* = v0 (1 + a^2) / (a g), where the
 * constraint's row df/dq'' vanishes and the accelerations are no longer
 * determined (past it the KKT solution would slide onto the accelerating
 * branch unnoticed).
 *  - the rows on the closed form up to t*;
 *  - the run stops at t* (exit 3, the constraint named), to 1e-9 of it,
 *    and leaves x at the last state its steps reached before t* (at
 *    eomc_stats.t_stop, on the closed form).
 */
#include "hard.h"

extern const eomc_model appell_model;

int
main(void)
{
    const double g = 9.81, a = 0.5, v0 = 2, tstar = v0 * (1 + a * a) / (a * g);
    eomc_sim *s = eomc_sim_alloc(&appell_model);
    eomc_run_opts o = eomc_run_defaults(&appell_model);
    double x0[6] = {0, 0, 0, v0, 0, -a * v0};
    Rows r = hard_run(s, &o, x0);
    double worst = 0;
    for (long k = 0; k < r.nrows; k++) {
        double t = r.t[k], x = v0 * t - a * g * t * t / (2 * (1 + a * a));
        double xd = v0 - a * g * t / (1 + a * a);
        const double *q = r.x + 6 * k;
        worst = fmax(worst, fmax(fmax(fabs(q[0] - x), fabs(q[2] + a * x)),
                                 fmax(fabs(q[3] - xd), fabs(q[5] + a * xd))));
    }
    double t_stop = HUGE_VAL;
    const char *at = strstr(r.error, "t = ");
    if (at)
        t_stop = atof(at + 4);
    CHECK(r.rc == EOMC_ENUMERIC && strstr(r.error, "the constraint cone degenerates") &&
              fabs(t_stop - tstar) <= 1e-9 * tstar,
          "Appell's particle stops at t* = %.15g: at %.15g (exit 3, the constraint named)",
          tstar, t_stop);
    CHECK(r.nrows == 51 && worst <= 2e-11,
          "... its %ld rows before it on the closed form, to %.2g (<= 2e-11 at rtol 1e-12)", r.nrows, worst);
    /* the state the run returns: the last one its steps reached, before
     * the step that went through t* */
    double x[6];
    memcpy(x, x0, sizeof x);
    eomc_stats st;
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    double ts = st.t_stop, xs = v0 * ts - a * g * ts * ts / (2 * (1 + a * a));
    double xds = v0 - a * g * ts / (1 + a * a);
    double off = fmax(fmax(fabs(x[0] - xs), fabs(x[2] + a * xs)),
                      fmax(fabs(x[3] - xds), fabs(x[5] + a * xds)));
    CHECK(rc == EOMC_ENUMERIC && ts > 0.5 * tstar && ts < tstar && off <= 2e-11,
          "... x is the last state reached before it, at t_stop = %.15g, on the closed form "
          "there to %.2g", ts, off);
    hard_free(&r);
    eomc_sim_free(s);
    return check_done();
}
