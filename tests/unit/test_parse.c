/*
 * Unit tests of the expression language (parse.c): values of parsed
 * expressions against the same formula written in C, at random points;
 * precedence and associativity; x' and dot() against the chain rule; and
 * the column of each error inside the string.
 */
#define _POSIX_C_SOURCE 200809L
#include "check.h"
#include "expr/parse.h"

#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static ExprPool *P;
static Diff *D;

/* Scope: coordinates x, y; parameter k; input u. */
static ExprId
lookup_scalar(ParseScope *sc, const char *name, SrcLoc at)
{
    if (!strcmp(name, "x"))
        return expr_var(sc->P, 0, 0);
    if (!strcmp(name, "y"))
        return expr_var(sc->P, 1, 0);
    if (!strcmp(name, "k"))
        return expr_param(sc->P, 0);
    if (!strcmp(name, "u"))
        return expr_input(sc->P, 0);
    diag_error(at, "unknown name '%s'", name);
}

static ParseVal
lookup(ParseScope *sc, const char *name, SrcLoc at)
{
    return (ParseVal){0, {lookup_scalar(sc, name, at), EXPR_NONE, EXPR_NONE}};
}

static const char *
leaf_name(ParseScope *sc, ExprId leaf)
{
    const ExprNode *nd = expr_node(sc->P, leaf);
    if (nd->op == EXPR_VAR)
        return nd->a ? "y" : "x";
    return nd->op == EXPR_PARAM ? "k" : "u";
}

/* Column = offset + 1 on line 1 of "test". */
static SrcLoc
where(const ParseSrc *src, size_t off)
{
    (void)src;
    return (SrcLoc){"test", 1, (int)off + 1};
}

static ParseScope scope = {NULL, NULL, lookup, NULL, leaf_name, 0xff, "an expression", 2,
                          NULL, NULL, NULL, NULL};

static ExprId
parse(const char *text)
{
    ParseSrc src = {text, strlen(text), where, NULL};
    return parse_expr(&scope, &src);
}

static double st[4][2];

static double
eval(ExprId e)
{
    double p[1] = {1.7}, u[1] = {0.3};
    ExprEnv env = {.t = 0.4, .q = {st[0], st[1], st[2], st[3]}, .p = p, .u = u};
    return expr_eval(P, e, &env);
}

static void
randomize(void)
{
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 2; i++)
            st[k][i] = check_rand(0.2, 1.4);
}

static void
test_values(void)
{
    int ok = 1;
    for (int trial = 0; trial < 50; trial++) {
        randomize();
        double x = st[0][0], y = st[0][1], k = 1.7, t = 0.4;
        double want[] = {
            2 * x * x - sin(y) / 3,
            -x * x,
            pow(2, pow(x, 2)),
            x - y - k,
            x / y / k,
            atan2(y, x) + sqrt(x) * exp(-y) + log(k) - abs((int)0) + fabs(x - 1),
            pow(x, y) + tanh(x) * cosh(y) - sinh(t),
            asin(x / 2) + acos(y / 2) + atan(x) + tan(y / 2),
            3.14159265358979323846 * 1.5e-3 + .5,
            -(-x),
            pow(x, 2.5),
        };
        const char *text[] = {
            "2*x^2 - sin(y)/3", "-x^2", "2^x^2", "x - y - k", "x / y / k",
            "atan2(y, x) + sqrt(x)*exp(-y) + log(k) - 0 + abs(x - 1)",
            "pow(x, y) + tanh(x)*cosh(y) - sinh(t)",
            "asin(x/2) + acos(y/2) + atan(x) + tan(y/2)", "pi*1.5e-3 + .5", "-(-x)", "x^2.5",
        };
        for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
            if (!check_close(eval(parse(text[i])), want[i], 1e-14)) {
                printf("# %s: got %.17g want %.17g\n", text[i], eval(parse(text[i])), want[i]);
                ok = 0;
            }
    }
    CHECK(ok, "parsed expressions evaluate like the same formulas in C (precedence: "
          "-x^2 = -(x^2), 2^x^2 = 2^(x^2), left-associative - and /)");
    CHECK(parse("x*y + y*x") == parse("2*(x*y)"), "hash-consing through the parser");
}

static void
test_derivatives(void)
{
    int ok = 1;
    for (int trial = 0; trial < 20; trial++) {
        randomize();
        double x = st[0][0], xd = st[1][0], xdd = st[2][0], y = st[0][1], yd = st[1][1];
        ok &= check_close(eval(parse("x'")), xd, 1e-15);
        ok &= check_close(eval(parse("x''")), xdd, 1e-15);
        ok &= check_close(eval(parse("dot(sin(x)*y)")), cos(x) * xd * y + sin(x) * yd, 1e-14);
        ok &= check_close(eval(parse("(x*x)'")), 2 * x * xd, 1e-14);
        ok &= check_close(eval(parse("dot(x')")), xdd, 1e-15);
        ok &= check_close(eval(parse("dot(t^2)")), 2 * 0.4, 1e-15);
    }
    CHECK(ok, "x', x'', dot() of compound expressions follow the chain rule");
    ok = 1;
    for (int trial = 0; trial < 20; trial++) {
        randomize();
        double x = st[0][0], y = st[0][1], xd = st[1][0], dq[2];
        dq[0] = check_rand(-1, 1), dq[1] = check_rand(-1, 1);
        double p[1] = {1.7}, u[1] = {0.3};
        ExprEnv env = {.t = 0.4, .q = {st[0], st[1], st[2], st[3]}, .p = p, .u = u,
                       .seed = {dq, NULL}};
        /* delta(e) = de/dx dx + de/dy dy, t, velocities, k and u held */
        ok &= check_close(expr_eval(P, parse("delta(sin(x)*y*k*u*t)"), &env),
                          (cos(x) * y * dq[0] + sin(x) * dq[1]) * 1.7 * 0.3 * 0.4, 1e-14);
        ok &= check_close(expr_eval(P, parse("x'*delta(x^2)"), &env), xd * 2 * x * dq[0],
                          1e-14);
    }
    CHECK(ok, "delta(e) is the variation sum_i de/dq_i delta(q_i) at fixed t, velocities, "
              "parameters and inputs");
}

/* Parse text expecting an error; return its column (0 if none) and the
 * message in msg. */
static int
error_column(const char *text, unsigned allow, char *msg, size_t len)
{
    fflush(stdout);
    fflush(stderr);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    diag_reset_errors(); /* each case is a run of its own: a place may repeat */
    int failed = 0;
    unsigned before = scope.allow;
    scope.allow = allow;
    if (setjmp(jb) == 0)
        parse(text);
    else
        failed = 1;
    scope.allow = before;
    diag_set_jump(old);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(tmp);
    msg[0] = '\0';
    if (!fgets(msg, (int)len, tmp))
        msg[0] = '\0';
    fclose(tmp);
    msg[strcspn(msg, "\n")] = '\0';
    int col = 0;
    if (failed && sscanf(msg, "test:1:%d:", &col) != 1)
        col = -1;
    return col;
}

static void
test_errors(void)
{
    static const struct {
        const char *text;
        int col;
        const char *says;
        unsigned allow;
    } cases[] = {
        {"2*(x + 1", 9, "expected ')' to close the '(' at column 3", 0xff},
        {"x + * y", 5, "expected a number", 0xff},
        {"x y", 3, "expected an operator", 0xff},
        {"x ** 2", 3, "'**'", 0xff},
        {"2x", 2, "multiplication is written with '*'", 0xff},
        {"x/0", 2, "division by zero", 0xff},
        {"x/(y - y)", 2, "division by zero", 0xff},
        {"1e999", 1, "out of the range", 0xff},
        {"1e", 2, "exponent has no digits", 0xff},
        {"atan2(x)", 1, "atan2 takes 2 arguments, not 1", 0xff},
        {"sin(x, y)", 8, "too many arguments", 0xff},
        {"foo(x)", 1, "unknown function 'foo'", 0xff},
        {"x + zz", 5, "unknown name 'zz'", 0xff},
        {"u'", 2, "cannot differentiate the input 'u'", 0xff},
        {"x''''", 5, "above the third", 0xff},
        {"k*x'", 4, "cannot depend on the velocity 'x''", DEP_P | DEP_ORDER(0)},
        {"k*t", 3, "cannot depend on time t", DEP_P},
        {"x = 1", 3, "not an equation", 0xff},
        {"", 1, "empty expression", 0xff},
        {"x)", 2, "unmatched ')'", 0xff},
        {"sin", 1, "unknown name 'sin'", 0xff}, /* uncalled: a name, the scope's */
        {"x + \xc3\xa9", 5, "unexpected character", 0xff},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char msg[512];
        int col = error_column(cases[i].text, cases[i].allow, msg, sizeof msg);
        CHECK(col == cases[i].col && strstr(msg, cases[i].says),
              "error in \"%s\" at column %d (got %d: %s)", cases[i].text, cases[i].col, col, msg);
    }
    /* nesting: bounded, an error rather than a stack overflow */
    size_t n = 100000;
    char *deep = malloc(2 * n + 2);
    memset(deep, '(', n);
    deep[n] = 'x';
    memset(deep + n + 1, ')', n);
    deep[2 * n + 1] = '\0';
    char msg[512];
    int col = error_column(deep, 0xff, msg, sizeof msg);
    CHECK(col > 0 && strstr(msg, "nested more than"), "100000 nested parentheses: %s", msg);
    memset(deep, '-', n);
    deep[n] = 'x';
    deep[n + 1] = '\0';
    col = error_column(deep, 0xff, msg, sizeof msg);
    CHECK(col > 0 && strstr(msg, "nested more than"), "100000 prefix minus signs: an error");
    /* a long flat sum is a loop, not recursion; past 10000 operators it
     * is an error at the 10001st (each term is "- x " or "+ y ") */
    char *flat = malloc(4 * n + 2);
    flat[0] = 'x';
    for (size_t i = 0; i < n; i++)
        memcpy(flat + 1 + 4 * i, i % 2 ? "+ y " : "- x ", 4);
    flat[4 * n + 1] = '\0';
    col = error_column(flat, 0xff, msg, sizeof msg);
    CHECK(col == 2 + 4 * 10000 && strstr(msg, "more than 10000 operators"),
          "a sum of 100000 terms: an error at the 10001st operator (%s)", msg);
    size_t m = 10000;
    flat[4 * m + 1] = '\0';
    randomize();
    CHECK_NEAR(eval(parse(flat)), (double)(m / 2) * st[0][1] - (double)(m / 2 - 1) * st[0][0],
               1e-9, "a flat sum of 10000 terms parses and evaluates");
    free(flat);
    free(deep);
}

int
main(void)
{
    P = expr_pool_new();
    D = diff_new(P);
    scope.P = P;
    scope.D = D;
    test_values();
    test_derivatives();
    test_errors();
    diff_free(D);
    expr_pool_free(P);
    return check_done();
}
