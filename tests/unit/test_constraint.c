/*
 * Unit tests of constraint.c: classification by order, the acceleration
 * level f, the virtual-displacement rows B = df/dq'' and b = f(q'' = 0),
 * against formulas differentiated by hand, at random states; the choice
 * of dependent coordinates (augmenting paths where the greedy choice runs
 * out); and the errors, each at its place.
 */
#define _POSIX_C_SOURCE 200809L
#include "check.h"
#include "mechanics/constraint.h"

#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

static const char *const particle =
    "parameters: {m: 1, a: 0.7, l: 1.3, k: 2}\n"
    "particles: {b: {mass: m, position: [x, y, z]}}\n";

static Constraints *
build(const char *body)
{
    char text[2048];
    snprintf(text, sizeof text, "coordinates: [x, y, z]\n%s%s", particle, body);
    Spec *s = spec_load_buffer("c.yaml", text, strlen(text), NULL, A, P);
    if (!s)
        return NULL;
    return constraints_build(s, mech_build(s, A, P, D), A, P, D);
}

/* The first line of the diagnostic that building `body` prints, without
 * the file name; "(no error)" if there is none. */
static void
build_error(const char *body, char *msg, size_t len)
{
    fflush(stdout);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    int failed = setjmp(jb) != 0 || !build(body);
    diag_set_jump(old);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(tmp);
    if (!fgets(msg, (int)len, tmp))
        msg[0] = '\0';
    fclose(tmp);
    msg[strcspn(msg, "\n")] = '\0';
    if (!failed)
        snprintf(msg, len, "(no error)");
    else if (!strncmp(msg, "c.yaml:", 7))
        memmove(msg, msg + 7, strlen(msg + 7) + 1);
}

typedef struct State {
    double q[3], v[3], acc[3], p[4];
} State;

static State
random_state(void)
{
    State s = {{0}, {0}, {0}, {1, 0.7, 1.3, 2}};
    for (int i = 0; i < 3; i++) {
        s.q[i] = check_rand(-2, 2);
        s.v[i] = check_rand(-2, 2);
        s.acc[i] = check_rand(-2, 2);
    }
    return s;
}

static double
eval(ExprId e, const State *s)
{
    double zero[4] = {0};
    ExprEnv env = {.t = 0.3, .q = {s->q, s->v, s->acc, zero}, .p = s->p, .u = zero};
    return expr_eval(P, e, &env);
}

/* Appell's cone: z'^2 - a^2 (x'^2 + y'^2), first order, nonlinear in q'. */
static void
test_appell(void)
{
    Constraints *c = build("constraints: {cone: \"z'^2 - a^2*(x'^2 + y'^2)\"}\n");
    CHECK(c && c->nc == 1 && c->spec[0].order == 1 && c->affine,
          "cone: first order, affine at acceleration level");
    int ok = 1;
    for (int k = 0; k < 20 && c; k++) {
        State s = random_state();
        const double *v = s.v, *w = s.acc, a2 = 0.49;
        double f = 2 * v[2] * w[2] - a2 * (2 * v[0] * w[0] + 2 * v[1] * w[1]);
        double B[3] = {-2 * a2 * v[0], -2 * a2 * v[1], 2 * v[2]};
        ok &= check_close(eval(c->f[0], &s), f, 1e-13) && check_close(eval(c->b[0], &s), 0, 1e-13);
        for (int j = 0; j < 3; j++)
            ok &= check_close(eval(c->B[j], &s), B[j], 1e-13);
        ok &= check_close(eval(c->vel[0], &s), v[2] * v[2] - a2 * (v[0] * v[0] + v[1] * v[1]), 1e-13);
    }
    CHECK(ok, "cone: f = 2 z' z'' - 2 a^2 (x' x'' + y' y''), B = (-2a^2 x', -2a^2 y', 2 z')");
    CHECK(c && c->dependent[0] == 2 && c->pos[0] == EXPR_NONE,
          "cone: the compiler eliminates the last coordinate it involves (z)");
}

/* A holonomic sphere |r|^2 = l^2 and a first-order linear constraint. */
static void
test_holonomic(void)
{
    Constraints *c = build("constraints:\n"
                           "  sphere: x^2 + y^2 + z^2 - l^2\n"
                           "  roll: {expr: \"x' - k*y'\", dependent: x}\n");
    CHECK(c && c->nc == 2 && c->spec[0].order == 0 && c->spec[1].order == 1 && c->affine,
          "sphere holonomic, roll first order");
    int ok = 1;
    for (int k = 0; k < 20 && c; k++) {
        State s = random_state();
        const double *q = s.q, *v = s.v;
        double g = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1.69;
        double gd = 2 * (q[0] * v[0] + q[1] * v[1] + q[2] * v[2]);
        double b = 2 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        ok &= check_close(eval(c->pos[0], &s), g, 1e-13) && check_close(eval(c->vel[0], &s), gd, 1e-13);
        ok &= check_close(eval(c->b[0], &s), b, 1e-13);
        for (int j = 0; j < 3; j++)
            ok &= check_close(eval(c->B[j], &s), 2 * q[j], 1e-13);
        ok &= check_close(eval(c->B[3], &s), 1, 1e-15) && check_close(eval(c->B[4], &s), -2, 1e-15) &&
              check_close(eval(c->B[5], &s), 0, 0) && check_close(eval(c->b[1], &s), 0, 0);
    }
    CHECK(ok, "sphere: B = 2 r, b = 2 |r'|^2, g' = 2 r.r'; roll: B = (1, -k, 0)");
    CHECK(c && c->dependent[1] == 0 && c->dependent[0] == 2,
          "named dependents are kept (roll: x), the others choose among the rest (sphere: z)");
}

/* Where the greedy choice runs out (a takes z, the last it involves,
 * and b involves z alone), a takes another of its own: x, the last
 * that is free; with a named on z, b cannot be placed. */
static void
test_matching(void)
{
    Constraints *c = build("constraints:\n"
                           "  a: x + z - 1\n"
                           "  b: z - a\n");
    CHECK(c && c->dependent[0] == 0 && c->dependent[1] == 2,
          "a moves from z to x so that b can take z (an augmenting path)");
    char msg[400];
    build_error("constraints:\n"
                "  a: {expr: x + z - 1, dependent: z}\n"
                "  b: z - a\n", msg, sizeof msg);
    CHECK(strstr(msg, "error: no coordinate is left for constraint 'b' to determine") != NULL,
          "a named dependent stays: with a's named z, b has none (%s)", msg);
    /* a row that is a combination of those before it at the initial
     * state shares a coordinate: the runtime leaves it out of its solves */
    c = build("constraints:\n"
              "  a: x - 1\n"
              "  b: 2*x - 3\n");
    CHECK(c && c->dependent[0] == 0 && c->dependent[1] == 0,
          "b = 2 a - 1, dependent on a: it shares a's x");
}

static void
test_second_order(void)
{
    Constraints *c = build("constraints: {g2: \"x''^2 + y'' - z'*x\"}\n");
    CHECK(c && c->spec[0].order == 2 && !c->affine, "x''^2 + y'' - z' x: second order, nonlinear in q''");
    int ok = 1;
    for (int k = 0; k < 10 && c; k++) {
        State s = random_state();
        ok &= check_close(eval(c->B[0], &s), 2 * s.acc[0], 1e-13) &&
              check_close(eval(c->B[1], &s), 1, 1e-15) && check_close(eval(c->B[2], &s), 0, 0);
    }
    CHECK(ok, "B = (2 x'', 1, 0)");
}

static void
test_errors(void)
{
    static const struct { const char *body, *want; } cases[] = {
        {"constraints: {c: a - 1}\n",
         "4:18: error: constraint 'c' involves no coordinate"},
        {"inputs: {u: sin(t)}\nconstraints: {c: x - u}\n",
         "5:22: error: a holonomic constraint cannot depend on the input 'u'"},
        {"constraints: {c: {expr: x - 1, dependent: y}}\n",
         "4:43: error: constraint 'c' does not involve 'y' at acceleration level"},
        {"constraints: {c: {expr: x - 1, dependent: w}}\n",
         "4:43: error: 'w' is not a coordinate"},
        {"constraints: {c: x''' - 1}\n", "4:21: error: a constraint cannot depend on the jerk"},
        {"constraints: {c: x - 1, d: y, e: z}\n",
         "4:31: error: 3 constraints on 3 coordinates leave no freedom"},
        {"constraints: {c: {expr: x, dependent: x}, d: {expr: x + y, dependent: x}}\n",
         "4:71: error: coordinate 'x' is already the dependent coordinate of constraint 'c'"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char msg[512];
        build_error(cases[k].body, msg, sizeof msg);
        int ok = !strncmp(msg, cases[k].want, strlen(cases[k].want));
        if (!ok)
            printf("# got:  %s\n# want: %s\n", msg, cases[k].want);
        CHECK(ok, "error %zu: %s", k, cases[k].want);
    }
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    test_appell();
    test_holonomic();
    test_matching();
    test_second_order();
    test_errors();
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}
