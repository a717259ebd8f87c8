/*
 * Unit tests of invariant.c's question whether T, V and the constraints
 * are free of t, by structure or by the numerical zero test, and of
 * expr_eval_bound, on which that test stands.  Against independent values:
 *  - a bead on a hoop turning about its vertical diameter at a constant
 *    rate w: t cancels in T only through cos(w t)^2 + sin(w t)^2 inside
 *    squares of sums.  h is conserved, the numerical test said so, and h
 *    is the closed form 1/2 m R^2 (th'^2 - w^2 sin^2 th) - m g R cos th
 *    at random states and parameters;
 *  - the hoop turned at a rate w0 + a t (angle w0 t + a t^2 / 2): nothing
 *    is conserved, the numerical test said so, also with the spec's a = 0
 *    (the simulator's --set may change it);
 *  - t cancelling only numerically in V and in a constraint: E and T + V,
 *    written out here, agree;
 *  - a true dependence on t 1e-16 of V's terms, below double's rounding,
 *    is found;
 *  - a support that reverses at t = 5 (x + |t - 5|): T holds sign(t - 5),
 *    whose derivative is 0 on both sides of its jump: refused;
 *  - the pendulum's T has no theta left (sin^2 + cos^2 folded): by structure;
 *  - expr_eval_bound's bound holds against exact values ((a + b) - a = b
 *    for doubles a, b; (x + y)^2 - x^2 - 2 x y - y^2 = 0), is not vacuous,
 *    and refuses a sign it cannot know.
 */
#include "check.h"
#include "mechanics/invariant.h"

#include <float.h>
#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

static Invariant *
derive(const char *text, const Mech **mech)
{
    Spec *s = spec_load_buffer("i.yaml", text, strlen(text), NULL, A, P);
    if (!s)
        return NULL;
    Mech *m = mech_build(s, A, P, D);
    Constraints *c = constraints_build(s, m, A, P, D);
    if (mech)
        *mech = m;
    return invariant_derive(s, m, c, A, P, D);
}

static int
says(const Invariant *inv, const char *what)
{
    return inv && strstr(inv->test, what) != NULL;
}

static const char *const hoop =
    "parameters: {m: 1.3, R: 0.7, g: 9.81, w: 3.0}\n"
    "coordinates: [th]\n"
    "particles:\n"
    "  bead: {mass: m, position: [R*sin(th)*cos(w*t), R*sin(th)*sin(w*t), -R*cos(th)]}\n"
    "effects: {gravity: {gravity: [0, 0, -g]}}\n";

static void
test_hoop(void)
{
    const Mech *m;
    Invariant *inv = derive(hoop, &m);
    CHECK(inv && inv->h != EXPR_NONE && !strcmp(inv->name, "h"),
          "turning hoop: h is conserved (%s)", inv ? inv->note : "no spec");
    if (!inv || inv->h == EXPR_NONE)
        return;
    CHECK(says(inv, "decided by the numerical zero test, not by structure") &&
              says(inv, "at 100 random states") && says(inv, "t and all"),
          "... and --explain says the numerical zero test decided: %s", inv->test);
    CHECK(expr_deps(P, inv->h) & DEP_T, "... h is computed as written, t and all");
    double worst = 0;
    for (int k = 0; k < 100; k++) {
        double p[4] = {check_rand(0.5, 2), check_rand(0.2, 2), check_rand(1, 20),
                       check_rand(-5, 5)};
        double th = check_rand(-3, 3), v = check_rand(-5, 5), zero[1] = {0};
        ExprEnv env = {.t = check_rand(0, 100), .q = {&th, &v, zero, zero}, .p = p};
        double mm = p[0], R = p[1], g = p[2], w = p[3], s = sin(th);
        double want = 0.5 * mm * R * R * (v * v - w * w * s * s) - mm * g * R * cos(th);
        double scale = 0.5 * mm * R * R * (v * v + w * w) + mm * g * R;
        worst = fmax(worst, fabs(expr_eval(P, inv->h, &env) - want) / scale);
    }
    CHECK(worst < 1e-13, "... h = 1/2 m R^2 (th'^2 - w^2 sin^2 th) - m g R cos th at 100 "
          "random states and parameters, to %.2g of its terms", worst);
}

static void
test_forced_hoop(void)
{
    /* the angle w0 t + a t^2/2: a rate w0 + a t */
    const char *fmt =
        "parameters: {m: 1.3, R: 0.7, g: 9.81, w0: 3.0, a: %s}\n"
        "coordinates: [th]\n"
        "define: {phi: w0*t + a*t^2/2}\n"
        "particles:\n"
        "  bead: {mass: m, position: [R*sin(th)*cos(phi), R*sin(th)*sin(phi), -R*cos(th)]}\n"
        "effects: {gravity: {gravity: [0, 0, -g]}}\n";
    const char *a[] = {"0.2", "0"};
    for (int k = 0; k < 2; k++) {
        char text[600];
        snprintf(text, sizeof text, fmt, a[k]);
        Invariant *inv = derive(text, NULL);
        CHECK(inv && inv->h == EXPR_NONE && !strcmp(inv->note, "nothing is conserved: T "
                                                    "depends on t") &&
                  says(inv, "the numerical zero test decided: dT/dt is not 0"),
              "hoop at a rate w0 + a t (a = %s in the spec): nothing is conserved, by the "
              "numerical test: %s", a[k], inv ? inv->test : "no spec");
    }
}

/* t that cancels only numerically, in V and in a constraint. */
static void
test_cancels_elsewhere(void)
{
    const Mech *m;
    Invariant *inv = derive("parameters: {m: 1.5, k: 4.0}\n"
                            "coordinates: [x]\n"
                            "particles: {p: {mass: m, position: [x, 0]}}\n"
                            "potential: k/2*x^2*((sin(t) + cos(t))^2 - 2*sin(t)*cos(t))\n",
                            &m);
    double x = 0.7, v = -1.1, zero[1] = {0}, p[2] = {1.5, 4.0};
    ExprEnv env = {.t = 2.5, .q = {&x, &v, zero, zero}, .p = p};
    CHECK(inv && inv->h != EXPR_NONE && !strcmp(inv->name, "E") && says(inv, "V holds t") &&
              check_close(expr_eval(P, inv->h, &env), 0.5 * 1.5 * v * v + 2.0 * x * x, 1e-14),
          "t in V through (sin t + cos t)^2 - 2 sin t cos t: E = m x'^2/2 + k x^2/2, "
          "by the numerical test: %s", inv ? inv->test : "no spec");
    inv = derive("parameters: {m: 1.5, l: 0.8, g: 9.81}\n"
                 "coordinates: [x, y]\n"
                 "particles: {p: {mass: m, position: [x, y]}}\n"
                 "effects: {gravity: {gravity: [0, -g]}}\n"
                 "constraints:\n"
                 "  rod: x^2 + y^2 - l^2*((cos(t) + sin(t))^2 - 2*sin(t)*cos(t))\n",
                 NULL);
    CHECK(inv && inv->h != EXPR_NONE && !strcmp(inv->name, "E") &&
              says(inv, "the constraint 'rod' holds t"),
          "t in a constraint through the same: E, by the numerical test: %s",
          inv ? inv->test : "no spec");
}

static void
test_small_dependence(void)
{
    Invariant *inv =
        derive("parameters: {m: 1.5, k: 4.0}\n"
               "coordinates: [x]\n"
               "particles: {p: {mass: m, position: [x, 0]}}\n"
               "potential: k/2*x^2*((sin(t) + cos(t))^2 - 2*sin(t)*cos(t) + 1e-16*sin(t))\n",
               NULL);
    CHECK(inv && inv->h == EXPR_NONE && says(inv, "dV/dt is not 0"),
          "a dependence on t 1e-16 of V's terms, below double's rounding, is found: %s",
          inv ? inv->test : "no spec");
    /* the support reverses at t = 5: x' + sign(t - 5) in T */
    inv = derive("parameters: {m: 1.5, k: 4.0}\n"
                 "coordinates: [x]\n"
                 "particles: {p: {mass: m, position: [x + abs(t - 5), 0]}}\n"
                 "potential: k/2*x^2\n",
                 NULL);
    CHECK(inv && inv->h == EXPR_NONE && says(inv, "T holds t inside sign()"),
          "a support that reverses at t = 5: T holds sign(t - 5), whose derivative is 0 "
          "on both sides of the jump: not credited: %s", inv ? inv->test : "no spec");
}

static void
test_structure(void)
{
    const Mech *m;
    Invariant *inv = derive("parameters: {m: 1.0, l: 1.0, g: 9.81}\n"
                            "coordinates: [theta]\n"
                            "particles:\n"
                            "  bob: {mass: m, position: [l*sin(theta), -l*cos(theta)]}\n"
                            "effects: {gravity: {gravity: [0, -g]}}\n",
                            &m);
    CHECK(inv && !(expr_deps(P, m->T) & DEP_ORDER(0)),
          "the pendulum's T = 1/2 m l^2 theta'^2 holds no theta: sin^2 + cos^2 folded");
    CHECK(inv && !strcmp(inv->name, "E") &&
              !strcmp(inv->test, "t: by structure: T and V hold neither t nor an input"),
          "... and E = T + V, free of t by structure: %s", inv ? inv->test : "no spec");
}

/* expr_eval_bound against exact values. */
static void
test_bound(void)
{
    ExprId x = expr_var(P, 0, 0), y = expr_var(P, 1, 0);
    /* ((1e10 + y)^2 - 1e20) - 2e10 y = y^2 (exactly, for y = k/1024), the
     * value lost in rounding: only the bound can say so */
    ExprId big = expr_const(P, 1e10);
    ExprId lost = expr_sub(P, expr_sub(P, expr_powi(P, expr_add(P, big, y), 2),
                                       expr_powi(P, big, 2)),
                           expr_mul(P, expr_const(P, 2e10), y));
    ExprId sq = expr_powi(P, expr_add(P, x, y), 2);
    ExprId zero = expr_sub(P, expr_sub(P, expr_sub(P, sq, expr_powi(P, x, 2)),
                                       expr_mul(P, expr_const(P, 2), expr_mul(P, x, y))),
                           expr_powi(P, y, 2));
    ExprId s = expr_unary(P, EXPR_SIN, x), c = expr_unary(P, EXPR_COS, x);
    ExprId trig = expr_sub(P, expr_sub(P, expr_powi(P, expr_add(P, s, c), 2),
                                       expr_mul(P, expr_const(P, 2), expr_mul(P, s, c))),
                           EXPR_ONE);
    enum { NS = 200 };
    static double q[NS][2];
    static ExprEnv env[NS];
    for (int k = 0; k < NS; k++) {
        q[k][0] = check_rand(-10, 10);
        q[k][1] = floor(check_rand(-10240, 10240)) / 1024;
        env[k] = (ExprEnv){.t = 0, .q = {q[k], q[k], q[k], q[k]}};
    }
    ExprBound b[3][NS];
    expr_eval_bound(P, lost, NS, env, b[0]);
    expr_eval_bound(P, zero, NS, env, b[1]);
    expr_eval_bound(P, trig, NS, env, b[2]);
    int held = 1, tight = 1, wrong = 0;
    for (int k = 0; k < NS; k++) {
        long double y2 = (long double)q[k][1] * q[k][1];
        held = held && fabsl(b[0][k].value - y2) <= b[0][k].err &&
               fabsl(b[1][k].value) <= b[1][k].err && fabsl(b[2][k].value) <= b[2][k].err;
        wrong += fabsl(b[0][k].value - y2) > 1e-3L * y2;
        for (int i = 1; i < 3; i++) /* a few long double roundings of the terms */
            tight = tight && b[i][k].err <= 64 * LDBL_EPSILON * b[i][k].mag;
    }
    CHECK(held && wrong > NS / 2, "|value - exact| <= err at %d states: ((1e10 + y)^2 - "
          "1e20) - 2e10 y = y^2 (the value itself wrong at %d), (x + y)^2 - x^2 - 2 x y - "
          "y^2 = 0, (sin x + cos x)^2 - 2 sin x cos x - 1 = 0", NS, wrong);
    CHECK(tight, "... the bound of the last two is at most 64 ulps of their terms' magnitude");
    ExprBound r;
    expr_eval_bound(P, expr_unary(P, EXPR_SIGN, lost), 1, &env[0], &r);
    CHECK(isinf(r.err) && isinf(b[0][0].err) == 0,
          "the sign of ((1e10 + y)^2 - 1e20) - 2e10 y, lost in rounding, is not trusted");
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    test_hoop();
    test_forced_hoop();
    test_cancels_elsewhere();
    test_small_dependence();
    test_structure();
    test_bound();
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}
