/*
 * A constraint nonlinear in q'' (tests/sim/specs/cubic.yaml): the
 * runtime's Newton iteration against the root of the scalar equation the
 * KKT system reduces to (found here by bisection), with multipliers and
 * with elimination, from a cold start and from the previous solution.
 */
#include "../unit/check.h"
#include "eomc.h"

extern const eomc_model cubic_model, cubic_elim_model;

/* x'' + (x''^3 + x'' + g)(3 x''^2 + 1) = 0: increasing in x'', one root. */
static double
root(double g)
{
    double lo = -10, hi = 10;
    for (int it = 0; it < 200; it++) {
        double x = 0.5 * (lo + hi);
        double r = x + (x * x * x + x + g) * (3 * x * x + 1);
        *(r > 0 ? &hi : &lo) = x;
    }
    return 0.5 * (lo + hi);
}

static void
check(const eomc_model *m)
{
    eomc_sim *s = eomc_sim_alloc(m);
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        double g = check_rand(1, 20);
        eomc_sim_set(s, "g", g);
        double q[2] = {check_rand(-1, 1), check_rand(-1, 1)};
        double v[2] = {check_rand(-1, 1), check_rand(-1, 1)}, a[2];
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        double x = root(g);
        ok &= check_close(a[0], x, 1e-12) && check_close(a[1], x * x * x + x, 1e-12) &&
              check_close(eomc_sim_multipliers(s)[0], 1.5 * (a[1] + g), 1e-12);
    }
    CHECK(ok, "%s%s: Newton's q'' and lambda = the root of the reduced equation", m->form,
          m->eliminate ? " (eliminated)" : "");
    eomc_sim_free(s);
}

int
main(void)
{
    CHECK(!cubic_model.c_affine, "the cubic constraint is classified as nonlinear in q''");
    check(&cubic_model);
    check(&cubic_elim_model);
    return check_done();
}
