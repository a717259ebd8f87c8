/*
 * Unit tests of the expression engine (expr.c, diff.c): hash-consing and
 * simplification, and every operator's derivative (forward, reverse and
 * total time derivative) against central finite differences.
 */
#include "check.h"
#include "expr/diff.h"
#include "expr/expr.h"

#include <math.h>
#include <string.h>

static ExprPool *P;
static Diff *D;

/* Evaluate e with q_0 = x, q_1 = y (order 0), q_2 = 0.5, velocities
 * (0.3, -0.2, 0.1), parameters (1.7, 0.6), nothing else. */
static double
at(ExprId e, double x, double y)
{
    double q0[3] = {x, y, 0.5}, q1[3] = {0.3, -0.2, 0.1}, z[3] = {0, 0, 0};
    double p[2] = {1.7, 0.6};
    ExprEnv env = {.t = 0, .q = {q0, q1, z, z}, .p = p};
    return expr_eval(P, e, &env);
}

static void
test_hashcons(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    CHECK(expr_add(P, x, y) == expr_add(P, y, x), "x+y and y+x are one node");
    CHECK(expr_mul(P, x, y) == expr_mul(P, y, x), "x*y and y*x are one node");
    CHECK(expr_add(P, x, EXPR_ZERO) == x, "x+0 = x");
    CHECK(expr_mul(P, x, EXPR_ONE) == x, "x*1 = x");
    CHECK(expr_mul(P, EXPR_ZERO, x) == EXPR_ZERO, "0*x = 0");
    CHECK(expr_neg(P, expr_neg(P, x)) == x, "--x = x");
    CHECK(expr_sub(P, x, x) == EXPR_ZERO, "x-x = 0");
    CHECK(expr_mul(P, x, x) == expr_powi(P, x, 2), "x*x = x^2");
    CHECK(expr_mul(P, expr_powi(P, x, 2), x) == expr_powi(P, x, 3), "x^2*x = x^3");
    ExprId c = expr_mul(P, expr_const(P, 2), expr_mul(P, expr_const(P, 3), x));
    CHECK(c == expr_mul(P, expr_const(P, 6), x), "2*(3*x) = 6*x");
    ExprId d = expr_mul(P, expr_mul(P, expr_const(P, 2), x), y);
    CHECK(d == expr_mul(P, expr_const(P, 2), expr_mul(P, x, y)), "(2x)y = 2(xy)");
    CHECK(expr_const(P, -0.0) == EXPR_ZERO, "-0.0 is stored as 0.0");
    double v;
    CHECK(expr_is_const(P, expr_add(P, expr_const(P, 0.1), expr_const(P, 0.2)), &v)
          && v == 0.1 + 0.2, "constant folding is IEEE addition");
    ExprId nan = expr_div(P, EXPR_ZERO, EXPR_ZERO);
    CHECK(!expr_is_const(P, nan, NULL), "0/0 is not folded into a NaN constant");
    ExprId inf = expr_div(P, EXPR_ONE, EXPR_ZERO);
    CHECK(!expr_is_const(P, inf, NULL), "1/0 is not folded into an infinity");
    CHECK(expr_pow(P, x, expr_const(P, 2)) == expr_powi(P, x, 2), "pow(x,2) = x^2");
    CHECK(expr_pow(P, x, expr_const(P, 0.5)) == expr_unary(P, EXPR_SQRT, x),
          "pow(x,0.5) = sqrt x");
    CHECK(expr_unary(P, EXPR_COS, expr_neg(P, x)) == expr_unary(P, EXPR_COS, x),
          "cos(-x) = cos x");
    CHECK(expr_powi(P, expr_powi(P, x, 2), 3) == expr_powi(P, x, 6), "(x^2)^3 = x^6");
    ExprId big = EXPR_ZERO;
    for (int i = 0; i < 100; i++)
        big = expr_add(P, big, expr_mul(P, expr_unary(P, EXPR_SIN, x), y));
    size_t before = expr_pool_size(P);
    for (int i = 0; i < 100; i++)
        (void)expr_mul(P, expr_unary(P, EXPR_SIN, x), y);
    CHECK(expr_pool_size(P) == before, "rebuilding existing nodes allocates none");
    ExprCount cnt = expr_count_ops(P, 1, &big);
    CHECK(cnt.calls == 1, "a shared sin(x) is counted once (got %ld)", cnt.calls);
}

/* Work that cancels is 0 by structure (issue 22): the residual's exact
 * zeros were computed as rounding noise. */
static void
test_cancel(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0), z = expr_var(P, 2, 0);
    ExprId a = expr_unary(P, EXPR_SIN, x), b = expr_mul(P, y, expr_unary(P, EXPR_COS, z));
    ExprId r = expr_add(P, expr_sub(P, expr_sub(P, a, b), a), b);
    CHECK(r == EXPR_ZERO, "(a - b) - a + b is the node 0");
    CHECK(expr_sub(P, expr_add(P, a, b), expr_add(P, b, a)) == EXPR_ZERO, "(a + b) - (b + a) = 0");
    ExprId c = expr_unary(P, EXPR_EXP, y);
    CHECK(expr_sub(P, expr_add(P, expr_add(P, a, b), c), b) == expr_add(P, a, c),
          "(a + b + c) - b = a + c");
    CHECK(expr_add(P, expr_neg(P, expr_sub(P, b, a)), b) == a, "-(b - a) + b = a");
    /* the same product grouped differently, a sum among its factors (the
     * canonical product leaves those binary) */
    ExprId s = expr_add(P, a, c);
    ExprId p1 = expr_mul(P, expr_mul(P, x, y), s), p2 = expr_mul(P, x, expr_mul(P, y, s));
    CHECK(p1 != p2, "(x y) s and x (y s) are two nodes");
    CHECK(expr_sub(P, expr_add(P, p1, z), p2) == z, "(x y) s + z - x (y s) = z");
    CHECK(expr_add(P, expr_sub(P, a, p1), p2) == a, "a - (x y) s + x (y s) = a");
    /* nothing cancels: the sum is built as it was, its parts shared */
    ExprId ab = expr_add(P, a, b), abc = expr_add(P, ab, c);
    const ExprNode *n = expr_node(P, abc);
    CHECK(n->op == EXPR_ADD && (n->a == ab || n->b == ab),
          "(a + b) + c keeps its partial sum a + b");
    ExprId r2 = expr_sub(P, ab, expr_mul(P, expr_const(P, 2), b));
    CHECK(r2 != a && check_close(at(r2, 0.3, 0.7), at(expr_sub(P, a, b), 0.3, 0.7), 1e-15),
          "(a + b) - 2 b is a - b, not a: a term with another coefficient is another term");
}

typedef struct Case {
    const char *name;
    int op;
    double lo, hi;   /* domain of x */
    double ylo, yhi; /* domain of y (binary ops) */
} Case;

static const Case cases[] = {
    {"add", EXPR_ADD, -3, 3, -3, 3},     {"sub", EXPR_SUB, -3, 3, -3, 3},
    {"mul", EXPR_MUL, -3, 3, -3, 3},     {"div", EXPR_DIV, -3, 3, 0.5, 3},
    {"pow", EXPR_POW, 0.2, 3, -2, 2},    {"atan2", EXPR_ATAN2, -3, 3, -3, 3},
    {"neg", EXPR_NEG, -3, 3, 0, 0},      {"sin", EXPR_SIN, -4, 4, 0, 0},
    {"cos", EXPR_COS, -4, 4, 0, 0},      {"tan", EXPR_TAN, -1.2, 1.2, 0, 0},
    {"asin", EXPR_ASIN, -0.9, 0.9, 0, 0}, {"acos", EXPR_ACOS, -0.9, 0.9, 0, 0},
    {"atan", EXPR_ATAN, -4, 4, 0, 0},    {"sinh", EXPR_SINH, -2, 2, 0, 0},
    {"cosh", EXPR_COSH, -2, 2, 0, 0},    {"tanh", EXPR_TANH, -2, 2, 0, 0},
    {"exp", EXPR_EXP, -2, 2, 0, 0},      {"log", EXPR_LOG, 0.1, 4, 0, 0},
    {"sqrt", EXPR_SQRT, 0.1, 4, 0, 0},   {"abs", EXPR_ABS, 0.1, 3, 0, 0},
};

/* Central difference of f along x (k = 0) or y (k = 1). */
static double
fd(ExprId f, double x, double y, int k)
{
    double h = 1e-5 * (1 + fabs(k ? y : x));
    if (k == 0)
        return (at(f, x + h, y) - at(f, x - h, y)) / (2 * h);
    return (at(f, x, y + h) - at(f, x, y - h)) / (2 * h);
}

/* Each operator applied to compound operands (so the chain rule is
 * exercised), differentiated three ways and checked against FD. */
static void
test_derivatives(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    ExprId leaves[2] = {x, y};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const Case *k = &cases[c];
        int binary = k->ylo != k->yhi;
        /* operands: x + 0.1 y^2 (stays in the domain for small y) and y */
        ExprId ax = expr_add(P, x, expr_mul(P, expr_const(P, 0.01), expr_powi(P, y, 2)));
        ExprId f = binary ? expr_binary(P, k->op, ax, y) : expr_unary(P, k->op, ax);
        int worst_ok = 1;
        for (int trial = 0; trial < 20; trial++) {
            double xv = check_rand(k->lo, k->hi * 0.9);
            double yv = binary ? check_rand(k->ylo, k->yhi) : check_rand(-1, 1);
            if (!binary && xv + 0.01 * yv * yv >= k->hi)
                xv -= 0.1;
            ExprId grad[2];
            diff_gradient(D, f, 2, leaves, grad);
            for (int i = 0; i < 2; i++) {
                double want = fd(f, xv, yv, i);
                double fwd = at(diff_partial(D, f, leaves[i]), xv, yv);
                double rev = at(grad[i], xv, yv);
                if (!check_close(fwd, want, 1e-6) || !check_close(rev, want, 1e-6)) {
                    printf("# %s d/d%c at (%g, %g): fwd %.12g rev %.12g fd %.12g\n",
                           k->name, "xy"[i], xv, yv, fwd, rev, want);
                    worst_ok = 0;
                }
            }
        }
        CHECK(worst_ok, "d(%s) forward and reverse match central differences", k->name);
    }
}

/* Integer powers, including negative ones and compositions. */
static void
test_powi(void)
{
    ExprId x = expr_var(P, 0, 0);
    int ok = 1;
    for (int n = -4; n <= 7; n++) {
        ExprId f = expr_powi(P, expr_unary(P, EXPR_SIN, x), n);
        ExprId d = diff_partial(D, f, x);
        for (int trial = 0; trial < 5; trial++) {
            double xv = check_rand(0.3, 2.8);
            double want = fd(f, xv, 0, 0), got = at(d, xv, 0);
            if (!check_close(got, want, 1e-6) || !check_close(at(f, xv, 0), pow(sin(xv), n), 1e-14))
                ok = 0;
        }
    }
    CHECK(ok, "x^n for n in -4..7: value and derivative");
}

/* d/dt along a trajectory: q(t) = polynomials, so q', q'', q''' are known
 * exactly; compare diff_time(e) with FD in t of e(t, q(t), q'(t)). */
static double traj_c[2][5] = {{0.3, -0.7, 0.4, 0.25, -0.1}, {-0.5, 0.2, 0.9, -0.3, 0.05}};

static double
poly(int i, int k, double t) /* k-th derivative of q_i at t */
{
    double s = 0;
    for (int p = k; p < 5; p++) {
        double c = traj_c[i][p];
        for (int m = 0; m < k; m++)
            c *= p - m;
        s += c * pow(t, p - k);
    }
    return s;
}

static double
at_time(ExprId e, double t)
{
    double q[4][2];
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 2; i++)
            q[k][i] = poly(i, k, t);
    ExprEnv env = {.t = t, .q = {q[0], q[1], q[2], q[3]}};
    return expr_eval(P, e, &env);
}

static void
test_time_derivative(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0), t = expr_time(P);
    ExprId xd = expr_var(P, 0, 1), yd = expr_var(P, 1, 1);
    /* a kinetic-energy-like expression with explicit time dependence */
    ExprId e = expr_add(P,
        expr_mul(P, expr_unary(P, EXPR_COS, expr_sub(P, x, y)), expr_mul(P, xd, yd)),
        expr_mul(P, expr_unary(P, EXPR_SIN, t), expr_powi(P, xd, 2)));
    ExprId e1 = diff_time(D, e), e2 = diff_time(D, e1);
    int ok1 = 1, ok2 = 1;
    for (int trial = 0; trial < 10; trial++) {
        double tv = check_rand(-1, 1), h = 1e-5;
        double fd1 = (at_time(e, tv + h) - at_time(e, tv - h)) / (2 * h);
        double fd2 = (at_time(e1, tv + h) - at_time(e1, tv - h)) / (2 * h);
        ok1 &= check_close(at_time(e1, tv), fd1, 1e-7);
        ok2 &= check_close(at_time(e2, tv), fd2, 1e-7);
    }
    CHECK(ok1, "first total time derivative matches FD along a trajectory");
    CHECK(ok2, "second total time derivative (with q''') matches FD");
    CHECK(expr_max_order(P, e2) == 3, "e'' contains q''' (order %d)", expr_max_order(P, e2));
    CHECK(diff_time(D, expr_input(P, 0)) == EXPR_NONE, "an input's derivative is unknown");
    CHECK(diff_time(D, expr_var(P, 0, EXPR_MAX_ORDER)) == EXPR_NONE,
          "derivative order beyond the maximum is refused");
}

static void
test_subst(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    ExprId f = expr_add(P, expr_mul(P, x, y), expr_unary(P, EXPR_SIN, y));
    ExprId g = expr_subst(P, f, 1, &y, (ExprId[]){EXPR_ZERO});
    CHECK(g == EXPR_ZERO, "x*y + sin y at y = 0 simplifies to 0");
    ExprId h = expr_subst(P, f, 1, &x, (ExprId[]){expr_const(P, 2)});
    CHECK_NEAR(at(h, 0, 0.7), 2 * 0.7 + sin(0.7), 1e-15, "substitution of a constant");
}

/* The magnitude of terms (lower.c's c_scale): every sum a sum of |terms|,
 * at a point where the value itself cancels to 0, against the same sum
 * written out. */
static void
test_magnitude(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    /* g = x - y*(3 - x)/2 + cos(y)/y^2 - 0.5 */
    ExprId g = expr_sub(P, expr_sub(P, x, expr_div(P, expr_mul(P, y, expr_sub(P,
                            expr_const(P, 3), x)), expr_const(P, 2))),
                        expr_const(P, 0.5));
    g = expr_add(P, g, expr_mul(P, expr_unary(P, EXPR_COS, y), expr_powi(P, y, -2)));
    ExprId m;
    expr_magnitude_many(P, 1, &g, &m);
    double xv = 0.3, yv = -1.1;
    double want = fabs(xv) + fabs(yv) * (3 + fabs(xv)) / 2 + fabs(cos(yv)) / (yv * yv) + 0.5;
    CHECK_NEAR(at(m, xv, yv), want, 1e-15, "magnitude of x - y (3 - x)/2 + cos(y)/y^2 - 0.5: "
               "the sum of its terms' sizes");
    ExprId zero = EXPR_ZERO, mz;
    expr_magnitude_many(P, 1, &zero, &mz);
    CHECK(mz == EXPR_ZERO, "the magnitude of 0 is 0");
}

/* Pseudo-random points in [lo, hi] (deterministic: a fixed LCG). */
static double
rnd(double lo, double hi)
{
    static unsigned long long state = 88172645463325252ull;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

/* a and b agree at random points (x, y) in [-3, 3]^2. */
static int
same_at_random_points(ExprId a, ExprId b)
{
    for (int k = 0; k < 20; k++) {
        double x = rnd(-3, 3), y = rnd(-3, 3);
        if (!check_close(at(a, x, y), at(b, x, y), 1e-12))
            return 0;
    }
    return 1;
}

/* Products of monomial factors are one node however they are built. */
static void
test_canonical_products(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    ExprId s = expr_unary(P, EXPR_SIN, x), c = expr_unary(P, EXPR_COS, x);
    ExprId l = expr_mul(P, expr_mul(P, s, y), expr_mul(P, c, y));
    ExprId r = expr_mul(P, expr_mul(P, c, y), expr_mul(P, s, y));
    CHECK(l == r, "sin*y*(cos*y) and cos*y*(sin*y) are one node");
    CHECK(same_at_random_points(l, expr_mul(P, expr_mul(P, s, c), expr_powi(P, y, 2))),
          "sin*y*(cos*y) = sin*cos*y^2 numerically");
    ExprId t = expr_mul(P, x, expr_mul(P, y, x));
    CHECK(t == expr_mul(P, expr_powi(P, x, 2), y), "x*(y*x) = x^2*y");
    CHECK(same_at_random_points(t, expr_mul(P, expr_mul(P, x, x), y)), "x*(y*x) numerically");
    ExprId u = expr_mul(P, expr_add(P, x, y), s), w = expr_mul(P, s, expr_add(P, x, y));
    CHECK(u == w, "a sum factor commutes but is not flattened");
    CHECK(expr_sub(P, l, r) == EXPR_ZERO, "reordered monomials cancel");
}

/* cos(x)^2 + sin(x)^2 = 1, also under a common coefficient. */
static void
test_pythagorean(void)
{
    ExprId x = expr_add(P, expr_var(P, 0, 0), expr_var(P, 1, 0));
    ExprId c2 = expr_powi(P, expr_unary(P, EXPR_COS, x), 2);
    ExprId s2 = expr_mul(P, expr_unary(P, EXPR_SIN, x), expr_unary(P, EXPR_SIN, x));
    CHECK(expr_add(P, c2, s2) == EXPR_ONE, "cos^2 + sin^2 = 1");
    CHECK(expr_add(P, s2, c2) == EXPR_ONE, "sin^2 + cos^2 = 1");
    CHECK(same_at_random_points(expr_add(P, c2, s2), EXPR_ONE), "cos^2 + sin^2 = 1 numerically");
    ExprId k = expr_mul(P, expr_const(P, 3), expr_param(P, 0));
    ExprId e = expr_add(P, expr_mul(P, k, c2), expr_mul(P, k, s2));
    CHECK(e == k, "k cos^2 + k sin^2 = k");
    ExprId y = expr_var(P, 1, 0);
    ExprId o = expr_add(P, c2, expr_powi(P, expr_unary(P, EXPR_SIN, y), 2));
    CHECK(o != EXPR_ONE && !same_at_random_points(o, EXPR_ONE),
          "cos(x)^2 + sin(y)^2 is not folded");
}

/* Does e still hold sin(x) or cos(x)? */
static int
holds_trig(ExprId e, ExprId x)
{
    return expr_depends(P, e, expr_unary(P, EXPR_SIN, x)) ||
           expr_depends(P, e, expr_unary(P, EXPR_COS, x));
}

/* The identity where mechanics meets it: scaled by anything, squares of
 * products, among other terms, subtracted, times further powers. */
static void
test_pythagorean_terms(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0), z = expr_var(P, 2, 0);
    ExprId v = expr_var(P, 0, 1), l = expr_param(P, 0);
    ExprId s = expr_unary(P, EXPR_SIN, x), c = expr_unary(P, EXPR_COS, x);
    ExprId s2 = expr_powi(P, s, 2), c2 = expr_powi(P, c, 2);
    CHECK(expr_add(P, expr_mul(P, y, c2), expr_mul(P, s2, y)) == y,
          "y cos^2 + y sin^2 is the node y (a scale that is not a coefficient)");
    /* a pendulum's |r'|^2, as mech.c builds it: (l cos x x')^2 + (l sin x x')^2 */
    ExprId vx = expr_mul(P, l, expr_mul(P, c, v)), vy = expr_mul(P, l, expr_mul(P, s, v));
    ExprId sq = expr_add(P, expr_mul(P, vx, vx), expr_mul(P, vy, vy));
    ExprId want = expr_mul(P, expr_powi(P, l, 2), expr_powi(P, v, 2));
    CHECK(sq == want, "(l cos x x')^2 + (l sin x x')^2 is the node l^2 x'^2");
    ExprId w = expr_powi(P, expr_mul(P, expr_mul(P, l, c), v), 2);
    CHECK(expr_add(P, w, expr_powi(P, expr_mul(P, expr_mul(P, l, s), v), 2)) == want,
          "... also written (l cos x x')^2 with the power outside the product");
    ExprId three = expr_const(P, 3);
    ExprId mixed = expr_add(P, expr_add(P, expr_add(P, y, expr_mul(P, three, c2)), z),
                            expr_mul(P, three, s2));
    CHECK(!holds_trig(mixed, x) &&
              same_at_random_points(mixed, expr_add(P, expr_add(P, y, z), three)),
          "(y + 3 cos^2 + z) + 3 sin^2 = y + z + 3, with no sin or cos left");
    ExprId chain = expr_mul(P, expr_param(P, 1), c2), other = EXPR_ZERO;
    for (int k = 0; k < 20; k++) { /* terms with sin x that are not partners */
        ExprId t = expr_mul(P, expr_const(P, k + 1), expr_mul(P, s, expr_powi(P, y, k + 1)));
        chain = expr_add(P, chain, t);
        other = expr_add(P, other, t);
    }
    chain = expr_add(P, chain, expr_mul(P, expr_param(P, 1), s2));
    CHECK(!expr_depends(P, chain, c2) && !expr_depends(P, chain, s2) &&
              same_at_random_points(chain, expr_add(P, other, expr_param(P, 1))),
          "p cos^2 + (20 other terms) + p sin^2: the pair 21 terms apart is found");
    ExprId two = expr_const(P, 2);
    CHECK(expr_sub(P, expr_mul(P, two, c2), expr_mul(P, expr_const(P, -2), s2)) == two,
          "2 cos^2 - (-2) sin^2 is the node 2");
    ExprId d = expr_sub(P, expr_sub(P, y, s2), c2);
    CHECK(!holds_trig(d, x) && same_at_random_points(d, expr_sub(P, y, EXPR_ONE)),
          "y - sin^2 - cos^2 = y - 1");
    ExprId s4 = expr_mul(P, expr_powi(P, s, 4), y), sc = expr_mul(P, expr_mul(P, s2, c2), y);
    CHECK(expr_add(P, s4, sc) == expr_mul(P, s2, y), "y sin^4 + y sin^2 cos^2 is the node y sin^2");
    ExprId a = expr_add(P, x, y), b = expr_add(P, y, x);
    CHECK(expr_add(P, expr_powi(P, expr_unary(P, EXPR_SIN, a), 2),
                   expr_powi(P, expr_unary(P, EXPR_COS, b), 2)) == EXPR_ONE,
          "sin(x + y)^2 + cos(y + x)^2 = 1: one argument node");
    ExprId uneven = expr_add(P, expr_mul(P, two, c2), expr_mul(P, three, s2));
    CHECK(holds_trig(uneven, x) && !same_at_random_points(uneven, two),
          "2 cos^2 + 3 sin^2 is left alone (different scales)");
    ExprId apart = expr_add(P, expr_mul(P, y, c2), expr_mul(P, z, s2));
    CHECK(holds_trig(apart, x), "y cos^2 + z sin^2 is left alone (different scales)");
    ExprId cube = expr_add(P, expr_powi(P, c, 3), expr_mul(P, c, s2));
    CHECK(cube == c, "cos^3 + cos sin^2 is the node cos");
}

/* c x + d x = (c + d) x for coefficients c, d (constants, parameters). */
static void
test_like_terms(void)
{
    ExprId x = expr_mul(P, expr_unary(P, EXPR_SIN, expr_var(P, 0, 0)), expr_var(P, 1, 1));
    ExprId two = expr_const(P, 2), m = expr_param(P, 0);
    CHECK(expr_add(P, expr_mul(P, expr_const(P, -2), x), expr_mul(P, two, x)) == EXPR_ZERO,
          "-2 x + 2 x = 0");
    CHECK(expr_sub(P, expr_mul(P, two, x), expr_mul(P, two, x)) == EXPR_ZERO, "2 x - 2 x = 0");
    ExprId e = expr_add(P, x, expr_mul(P, expr_const(P, 3), x));
    CHECK(e == expr_mul(P, expr_const(P, 4), x), "x + 3 x = 4 x");
    ExprId f = expr_sub(P, expr_mul(P, m, x), x), g = expr_mul(P, expr_sub(P, m, EXPR_ONE), x);
    CHECK(f == g && same_at_random_points(f, g), "m x - x = (m - 1) x");
    ExprId y = expr_var(P, 2, 0);
    ExprId h = expr_add(P, expr_mul(P, two, x), expr_mul(P, two, y));
    /* the structure, not only the value: a product whose first factor is
     * the number 2 and whose second is the sum x + y itself */
    const ExprNode *hn = expr_node(P, h);
    CHECK(hn->op == EXPR_MUL && hn->a == two && hn->b == expr_add(P, x, y) &&
              expr_node(P, hn->b)->op == EXPR_ADD,
          "2 x + 2 y stays 2 (x + y): the node is 2 * (x + y)");
    CHECK(same_at_random_points(h, expr_mul(P, two, expr_add(P, x, y))),
          "... and equal in value");
}

/* An offset and its return cancel by structure, not only in value: a
 * point from another and the difference of their positions (kin.h). */
static void
test_offsets_cancel(void)
{
    ExprId x = expr_var(P, 0, 0), a = expr_mul(P, expr_param(P, 0), expr_unary(P, EXPR_SIN, x));
    ExprId y = expr_var(P, 1, 0);
    CHECK(expr_add(P, expr_sub(P, y, a), a) == y, "(y - a) + a is the node y");
    CHECK(expr_add(P, a, expr_sub(P, y, a)) == y, "a + (y - a) is the node y");
    CHECK(expr_sub(P, expr_add(P, y, a), a) == y && expr_sub(P, expr_add(P, y, a), y) == a,
          "(y + a) - a is y, and (y + a) - y is a");
    CHECK(expr_sub(P, y, expr_sub(P, y, a)) == a, "y - (y - a) is the node a");
}

/* Numbers gather across products of parameters, and like terms whose
 * coefficients are parameter expressions are collected: the structure is
 * asserted (node identity), not only the value. */
static void
test_parameter_folding(void)
{
    ExprId m = expr_param(P, 0), l = expr_param(P, 1), x = expr_var(P, 0, 0);
    ExprId half_m = expr_mul(P, expr_const(P, 0.5), m);
    CHECK(expr_mul(P, expr_const(P, 2.0), half_m) == m, "2*(0.5*m) is the node m");
    ExprId ml = expr_mul(P, m, l);
    ExprId six_ml = expr_mul(P, expr_const(P, 6.0), ml);
    CHECK(expr_mul(P, expr_mul(P, expr_const(P, 2.0), m), expr_mul(P, expr_const(P, 3.0), l)) ==
          six_ml, "(2*m)*(3*l) is the node 6*(m*l)");
    ExprId four = expr_mul(P, expr_const(P, 4.0), ml), two = expr_mul(P, expr_const(P, -2.0), ml);
    CHECK(expr_add(P, four, two) == expr_mul(P, expr_const(P, 2.0), ml),
          "4*(m*l) + (-2)*(m*l) is the node 2*(m*l)");
    ExprId twice = expr_mul(P, expr_const(P, 2.0), expr_mul(P, expr_const(P, 2.0), ml));
    CHECK(expr_sub(P, twice, four) == EXPR_ZERO, "2*(2*(m*l)) - 4*(m*l) is the node 0");
    ExprId e = expr_mul(P, expr_sub(P, twice, four), expr_unary(P, EXPR_SIN, x));
    CHECK(e == EXPR_ZERO, "(2*(2 m l) - 4 m l) sin x is 0: no dead code for an entry that is 0");
    const ExprNode *nd = expr_node(P, six_ml);
    CHECK(nd->op == EXPR_MUL && expr_node(P, nd->a)->op == EXPR_CONST &&
          expr_node(P, nd->a)->value == 6.0, "the number stays in front: 6*(m*l)");
}

/* max, min and clamp: one switch per kink, shared where the switch
 * function is; each mode's branch exact, its derivatives the branch's
 * (against central differences away from the kink), and no value
 * without a mode. */
static void
test_switched(void)
{
    ExprPool *Q = expr_pool_new();
    Diff *E = diff_new(Q);
    ExprId x = expr_var(Q, 0, 0), y = expr_var(Q, 1, 0), v = expr_var(Q, 0, 1);
    ExprId sx = expr_unary(Q, EXPR_SIN, x), y2 = expr_powi(Q, y, 2);
    ExprId mx = expr_max(Q, sx, y2), mn = expr_min(Q, sx, y2);
    CHECK(expr_nswitch(Q) == 1 && expr_switch(Q, 0) == expr_sub(Q, sx, y2),
          "max(a, b) and min(a, b) share one switch, s = a - b");
    CHECK(expr_max(Q, sx, y2) == mx, "max(a, b) built again is the same node");
    CHECK(expr_max(Q, sx, sx) == sx, "max(a, a) = a, no switch");
    double c;
    CHECK(expr_is_const(Q, expr_max(Q, expr_const(Q, 2), expr_const(Q, 3)), &c) && c == 3 &&
          expr_nswitch(Q) == 1, "max of constants is folded, no switch");
    CHECK(!(expr_deps(Q, mx) & DEP_P) && (expr_deps(Q, mx) & DEP_M) && !expr_is_coeff(Q, mx),
          "a switched expression reads a mode (DEP_M), is never a coefficient");
    ExprId cl = expr_clamp(Q, x, expr_const(Q, -1), expr_const(Q, 2));
    CHECK(expr_nswitch(Q) == 3, "clamp makes two switches (got %d)", expr_nswitch(Q));
    double q0[2] = {0.3, 0.7}, q1[2] = {0.5, 0}, z[2] = {0, 0};
    ExprEnv env = {.q = {q0, q1, z, z}};
    CHECK(isnan(expr_eval(Q, mx, &env)), "no mode: NaN, not a guessed branch");
    /* the modes each side takes, from its switch functions' signs */
    int ok = 1;
    for (int trial = 0; trial < 40; trial++) {
        q0[0] = check_rand(-3, 3);
        q0[1] = check_rand(-1.5, 1.5);
        double mode[3];
        for (int k = 0; k < 3; k++)
            mode[k] = expr_eval(Q, expr_switch(Q, k), &env) > 0;
        env.mode = mode;
        double a = sin(q0[0]), b = q0[1] * q0[1];
        ok &= expr_eval(Q, mx, &env) == fmax(a, b) && expr_eval(Q, mn, &env) == fmin(a, b);
        ok &= expr_eval(Q, cl, &env) == fmin(fmax(q0[0], -1), 2);
        /* d max / dq0 and the time derivative: the branch's */
        ok &= expr_eval(Q, diff_partial(E, mx, x), &env) == (a > b ? cos(q0[0]) : 0.0);
        ok &= check_close(expr_eval(Q, diff_time(E, cl), &env),
                          q0[0] > -1 && q0[0] < 2 ? q1[0] : 0.0, 1e-15);
        ExprId g[2];
        diff_gradient(E, mn, 2, (ExprId[]){x, y}, g);
        ok &= expr_eval(Q, g[1], &env) == (a > b ? 2 * q0[1] : 0.0);
        ExprId mag;
        expr_magnitude_many(Q, 1, &mx, &mag);
        ok &= expr_eval(Q, mag, &env) == fabs(fmax(a, b));
        env.mode = NULL;
    }
    CHECK(ok, "each mode: max, min, clamp, their partials, time derivatives and magnitudes "
              "are the branch's");
    ExprId d = diff_partial(E, mx, x);
    CHECK(expr_node(Q, d)->op == EXPR_SELECT && expr_select_mode(Q, d) == 0,
          "d max(a, b) = SELECT(k, da, db)");
    ExprId sub = expr_subst(Q, mx, 1, &y, &v), w = expr_var(Q, 1, 1);
    CHECK(expr_node(Q, sub)->op == EXPR_SELECT && expr_select_mode(Q, sub) == 3 &&
          expr_switch(Q, 3) == expr_sub(Q, sx, expr_powi(Q, v, 2)),
          "a substitution in a SELECT's branches is one in its switch function too: "
          "max(sin x, v^2) is on its own switch");
    CHECK(expr_subst(Q, mx, 1, &w, &v) == mx, "a substitution that misses it keeps it");
    diff_free(E);
    expr_pool_free(Q);
}

int
main(void)
{
    P = expr_pool_new();
    D = diff_new(P);
    test_hashcons();
    test_cancel();
    test_derivatives();
    test_powi();
    test_time_derivative();
    test_subst();
    test_magnitude();
    test_canonical_products();
    test_pythagorean();
    test_pythagorean_terms();
    test_like_terms();
    test_parameter_folding();
    test_offsets_cancel();
    test_switched();
    diff_free(D);
    expr_pool_free(P);
    return check_done();
}
