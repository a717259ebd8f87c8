/*
 * Hard case: a periodic return.  Arenstorf's orbit of the restricted
 * three-body problem (specs/arenstorf.yaml), which passes close to the
 * moon: after its published period T = 17.0652165601579625588917206249
 * (Hairer, Norsett and Wanner, Solving ODEs I) the satellite is back at
 * its start; Jacobi's integral h = |v|^2/2 - |r|^2/2 + V, written out
 * here, holds.  rk8pd and bsimp at rtol 1e-12.
 */
#include "hard.h"

extern const eomc_model arenstorf_model;

static double
jacobi(const double *x, double *scale)
{
    const double mu = 0.012277471;
    double r1 = hypot(x[0] + mu, x[1]), r2 = hypot(x[0] - 1 + mu, x[1]);
    double T2 = 0.5 * (x[2] * x[2] + x[3] * x[3]), T0 = 0.5 * (x[0] * x[0] + x[1] * x[1]);
    double V = -(1 - mu) / r1 - mu / r2;
    *scale = T2 + T0 + fabs(V);
    return T2 - T0 + V;
}

int
main(void)
{
    const char *methods[] = {"rk8pd", "bsimp"};
    const double bound[] = {1e-8, 1e-8};
    for (int k = 0; k < 2; k++) {
        eomc_sim *s = eomc_sim_alloc(&arenstorf_model);
        eomc_run_opts o = eomc_run_defaults(&arenstorf_model);
        o.method = methods[k];
        Rows r = hard_run(s, &o, NULL);
        double back = 0, h0 = 0, drift = 0, scale = 0;
        for (int i = 0; r.rc == EOMC_OK && i < 4; i++)
            back = fmax(back, fabs(r.x[(r.nrows - 1) * 4 + i] - r.x[i]));
        for (long i = 0; i < r.nrows; i++) {
            double sc, h = jacobi(r.x + 4 * i, &sc);
            if (i == 0)
                h0 = h;
            scale = fmax(scale, sc);
            drift = fmax(drift, fabs(h - h0));
        }
        CHECK(r.rc == EOMC_OK && back <= bound[k] && drift <= 1e-11 * scale,
              "Arenstorf, %s at rtol 1e-12: back at the start after the period within %.2g "
              "(<= %g), Jacobi's integral held to %.2g of its terms (<= 1e-11), %ld steps",
              methods[k], back, bound[k], drift / scale, r.st.steps);
        hard_free(&r);
        eomc_sim_free(s);
    }
    return check_done();
}
