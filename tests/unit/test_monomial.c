/*
 * Unit tests of monomial.c: products written again as a constant times
 * powers of bases.  Each rewrite is checked for its shape (the node it
 * should be, built here by hand) and for its value against the original's
 * at points away from the roots' domains' edges (expr_eval of both).
 */
#include "check.h"
#include "expr/expr.h"
#include "expr/monomial.h"

#include <math.h>

static ExprPool *P;

/* e at q_0 = x, q_1 = y, q_2 = z (order 0), parameters (1.7, 0.6). */
static double
at(ExprId e, double x, double y, double z)
{
    double q0[3] = {x, y, z}, none[3] = {0, 0, 0};
    double p[2] = {1.7, 0.6};
    ExprEnv env = {.t = 0, .q = {q0, none, none, none}, .p = p};
    return expr_eval(P, e, &env);
}

/* The largest relative difference of a and b over a few points. */
static double
apart(ExprId a, ExprId b)
{
    static const double pts[][3] = {{0.3, -1.2, 0.7}, {-2.1, 0.4, 1.9}, {1.1, 1.3, -0.2}};
    double worst = 0;
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        double va = at(a, pts[i][0], pts[i][1], pts[i][2]);
        double vb = at(b, pts[i][0], pts[i][1], pts[i][2]);
        worst = fmax(worst, fabs(va - vb) / fmax(fabs(va), 1e-300));
    }
    return worst;
}

int
main(void)
{
    P = expr_pool_new();
    Monomials *mo = mono_new(P, DEP_T | DEP_ANY_Q | DEP_S | DEP_L);
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0), z = expr_var(P, 2, 0);
    ExprId mu = expr_param(P, 0), half = expr_const(P, 0.5), two = expr_const(P, 2);
    ExprId s = expr_add(P, expr_powi(P, x, 2), expr_powi(P, y, 2));
    ExprId r = expr_unary(P, EXPR_SQRT, s);

    /* Kepler's force as differentiation writes it */
    ExprId force = expr_mul(P, two, expr_mul(P, expr_mul(P, expr_div(P, expr_div(P, mu, r), r),
                                                           expr_div(P, half, r)),
                                              x));
    ExprId want = expr_mul(P, mu, expr_mul(P, x, expr_pow(P, s, expr_const(P, -1.5))));
    ExprId got = mono_rewrite(mo, force);
    CHECK(got == want, "2 ((mu/r)/r (0.5/r)) x with r = sqrt(s) is mu x s^(-3/2)");
    CHECK(apart(got, force) <= 4e-16, "... with its value (%.1e apart)", apart(got, force));
    CHECK(mono_real_powers(mo, got) == 1 && mono_real_powers(mo, force) == 3,
          "its real powers: one, where the original has r three times (%d, %d)",
          mono_real_powers(mo, got), mono_real_powers(mo, force));

    /* a shared power: the y force's is the same node */
    ExprId fy = mono_rewrite(mo, expr_mul(P, expr_div(P, mu, expr_powi(P, r, 3)), y));
    CHECK(fy == expr_mul(P, mu, expr_mul(P, y, expr_pow(P, s, expr_const(P, -1.5)))),
          "mu y / r^3 shares s^(-3/2)");

    /* a root of an even power is |b|, not b: left a base */
    ExprId even = expr_unary(P, EXPR_SQRT, expr_powi(P, z, 2));
    ExprId e2 = mono_rewrite(mo, expr_mul(P, even, x));
    CHECK(e2 == expr_mul(P, even, x), "sqrt(z^2) x is left as it is");
    CHECK(apart(e2, expr_mul(P, expr_unary(P, EXPR_ABS, z), x)) == 0, "... which is |z| x");

    /* a root of a product stays a base; inside a sum the terms are
     * written again */
    ExprId rp = expr_unary(P, EXPR_SQRT, expr_mul(P, x, y));
    CHECK(mono_rewrite(mo, expr_mul(P, rp, rp)) == expr_powi(P, rp, 2),
          "sqrt(x y)^2 stays a power of the root");
    ExprId sum = expr_add(P, expr_unary(P, EXPR_SIN, force), z);
    ExprId sr = mono_rewrite(mo, sum);
    CHECK(sr == expr_add(P, expr_unary(P, EXPR_SIN, want), z), "sin(force) + z: the force inside rewritten");
    CHECK(apart(sr, sum) <= 4e-16, "... with its value (%.1e apart)", apart(sr, sum));

    /* quotients cancel; constants stay whole */
    ExprId q = mono_rewrite(mo, expr_div(P, expr_mul(P, x, y), expr_mul(P, y, z)));
    CHECK(q == expr_div(P, x, z), "(x y) / (y z) is x / z");
    ExprId k = expr_mul(P, mu, expr_param(P, 1));
    CHECK(mono_rewrite(mo, k) == k, "a product of parameters is left whole");

    mono_free(mo);
    expr_pool_free(P);
    return check_done();
}
