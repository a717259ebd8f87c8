/*
 * Hard case: a chaotic double pendulum (specs/double_pendulum.yaml,
 * th1 = 2, th2 = 1 from rest).
 *  - its energy, written out here, holds to the tolerance: at most 10 rtol
 *    of its terms, at rtol 1e-10 and 1e-12, over 30 s;
 *  - the runs at rtol 1e-10 and 1e-12 agree to 1e-6 up to t = 10 and to
 *    1e-3 up to t = 15 (measured: they part at 11.1 and 16.6), and then
 *    part by more than 0.1 rad before t = 30: beyond the horizon the
 *    tolerance sets, no run says where the pendulum is.
 */
#include "hard.h"

extern const eomc_model double_pendulum_model;

static double
energy(const double *x, double *scale)
{
    const double m1 = 1, m2 = 1, l1 = 1, l2 = 1, g = 9.81;
    double T = 0.5 * (m1 + m2) * l1 * l1 * x[2] * x[2] + 0.5 * m2 * l2 * l2 * x[3] * x[3] +
               m2 * l1 * l2 * x[2] * x[3] * cos(x[0] - x[1]);
    double V = -(m1 + m2) * g * l1 * cos(x[0]) - m2 * g * l2 * cos(x[1]);
    *scale = fabs(T) + fabs(V);
    return T + V;
}

static Rows
run(double rtol)
{
    eomc_sim *s = eomc_sim_alloc(&double_pendulum_model);
    eomc_run_opts o = eomc_run_defaults(&double_pendulum_model);
    o.rtol = o.atol = rtol, o.t_end = 30, o.dt = 0.01;
    Rows r = hard_run(s, &o, NULL);
    double E0 = 0, scale = 0, drift = 0;
    for (long k = 0; k < r.nrows; k++) {
        double sc, E = energy(r.x + 4 * k, &sc);
        if (k == 0)
            E0 = E;
        scale = fmax(scale, sc);
        drift = fmax(drift, fabs(E - E0));
    }
    CHECK(r.rc == EOMC_OK && drift <= 10 * rtol * scale,
          "double pendulum at rtol %g over 30 s: energy held to %.2g of its terms (<= 10 "
          "rtol), %ld steps", rtol, drift / scale, r.st.steps);
    eomc_sim_free(s);
    return r;
}

int
main(void)
{
    Rows a = run(1e-10), b = run(1e-12);
    double d10 = 0, d15 = 0, late = 0;
    for (long k = 0; k < a.nrows && k < b.nrows; k++) {
        double d = fmax(fabs(a.x[4 * k] - b.x[4 * k]), fabs(a.x[4 * k + 1] - b.x[4 * k + 1]));
        if (a.t[k] <= 10)
            d10 = fmax(d10, d);
        if (a.t[k] <= 15)
            d15 = fmax(d15, d);
        late = fmax(late, d);
    }
    CHECK(a.nrows == b.nrows && d10 <= 1e-6 && d15 <= 1e-3 && late > 0.1,
          "rtol 1e-10 and 1e-12 agree to %.2g up to t = 10 (<= 1e-6), to %.2g up to 15 "
          "(<= 1e-3), and part by %.2g rad before 30 (> 0.1: chaos)", d10, d15, late);
    hard_free(&a);
    hard_free(&b);
    return check_done();
}
