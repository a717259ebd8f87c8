/*
 * Hard case: long-time drift.  Kepler's orbit with e = 0.6 over 100
 * periods (specs/kepler.yaml, a = mu = 1, from periapsis): after every
 * whole period the body is back at periapsis (a (1 - e), 0), and the
 * energy -mu/(2a) and angular momentum sqrt(mu a (1 - e^2)) hold, both
 * computed here from the rows.  rk8pd at rtol 1e-12.
 */
#include "hard.h"

extern const eomc_model kepler_model;

#define PERIOD (2 * 3.14159265358979323846)

int
main(void)
{
    const double e = 0.6;
    eomc_sim *s = eomc_sim_alloc(&kepler_model);
    eomc_sim_set(s, "e", e);
    eomc_run_opts o = eomc_run_defaults(&kepler_model);
    o.rtol = o.atol = 1e-12, o.t_end = 100 * PERIOD, o.dt = PERIOD;
    Rows r = hard_run(s, &o, NULL);
    double pos = 0, dE = 0, dL = 0, L0 = sqrt(1 - e * e);
    for (long k = 0; k < r.nrows; k++) {
        const double *x = r.x + 4 * k;
        double rr = hypot(x[0], x[1]);
        pos = fmax(pos, hypot(x[0] - (1 - e), x[1]));
        dE = fmax(dE, fabs(0.5 * (x[2] * x[2] + x[3] * x[3]) - 1 / rr + 0.5));
        dL = fmax(dL, fabs(x[0] * x[3] - x[1] * x[2] - L0));
    }
    CHECK(r.rc == EOMC_OK && r.nrows == 101 && pos <= 1e-7,
          "Kepler e = 0.6, 100 periods: back at periapsis after each, within %.2g (<= 1e-7; "
          "the phase drifts linearly), %ld steps", pos, r.st.steps);
    CHECK(r.rc == EOMC_OK && dE <= 1e-10 && dL <= 2e-11,
          "Kepler e = 0.6, 100 periods: energy -1/2 held to %.2g (<= 1e-10), angular "
          "momentum %.6g to %.2g (<= 2e-11)", dE, L0, dL);
    hard_free(&r);
    eomc_sim_free(s);
    return check_done();
}
