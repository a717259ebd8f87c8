/*
 * Fuzz target: the expression parser and the derivative engine.  The
 * input is one expression's text, in a scope with coordinates x and y,
 * parameter k and input u (as tests/unit/test_parse.c), and a frame F
 * (turned by x about z, then about a fixed axis by y, origin P) and a
 * point P (in F, at [k, x, 1]) for vector expressions.  A parsed
 * expression is evaluated, differentiated (d/dt, partials, a gradient, a
 * directional derivative) and the derivatives evaluated: any error is
 * fine, a crash, a sanitizer report, a leak or a hang is not.
 */
#include "fuzz.h"

#include "expr/parse.h"

#include <setjmp.h>
#include <string.h>

enum { FRAME_F = 1, POINT_P = 1 };

static int
frame(ParseScope *sc, const char *name, SrcLoc at)
{
    (void)sc;
    if (!strcmp(name, "F"))
        return FRAME_F;
    if (!strcmp(name, "world"))
        return KIN_WORLD;
    diag_error(at, "unknown frame '%s'", name);
}

static int
point(ParseScope *sc, const char *name, SrcLoc at)
{
    (void)sc;
    if (!strcmp(name, "P"))
        return POINT_P;
    if (!strcmp(name, "origin"))
        return KIN_ORIGIN;
    diag_error(at, "unknown point '%s'", name);
}

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
    static const char *const names[] = {"x", "y", "k", "u"};
    const char *near = diag_nearest(name, names, 4);
    diag_error(at, "unknown name '%s'%s%s%s", name, near ? "; did you mean " : "",
               near ? near : "", near ? "?" : "");
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

static SrcLoc
where(const ParseSrc *src, size_t off)
{
    (void)src;
    return (SrcLoc){"fuzz", 1, (int)off + 1};
}

static void
count_name(void *ctx, const char *name, size_t len, size_t off)
{
    (void)name, (void)len, (void)off;
    ++*(int *)ctx;
}

static double
eval(ExprPool *P, ExprId e)
{
    static const double q[4][2] = {{0.3, -1.1}, {0.7, 0.2}, {-0.4, 1.3}, {0.1, 0.9}};
    static const double p[1] = {1.7}, u[1] = {0.6}, seed[2][2] = {{1, 0.5}, {-0.25, 2}};
    ExprEnv env = {.t = 0.4, .q = {q[0], q[1], q[2], q[3]}, .p = p, .u = u,
                   .seed = {seed[0], seed[1]}};
    return e == EXPR_NONE ? 0 : expr_eval(P, e, &env);
}

typedef struct Input {
    const uint8_t *data;
    size_t size;
} Input;

static void
exercise(ExprPool *P, Diff *D, ExprId e)
{
    ExprId leaves[6] = {expr_var(P, 0, 0), expr_var(P, 1, 0), expr_var(P, 0, 1),
                        expr_var(P, 1, 1), expr_param(P, 0), expr_time(P)};
    ExprId d[12];
    int n = 0;
    d[n++] = e;
    d[n++] = diff_time(D, e);
    if (d[1] != EXPR_NONE)
        d[n++] = diff_time(D, d[1]);
    for (int i = 0; i < 6; i += 2)
        d[n++] = diff_partial(D, e, leaves[i]);
    ExprId grad[6];
    diff_gradient(D, e, 6, leaves, grad);
    d[n++] = grad[1];
    d[n++] = grad[4];
    ExprId seeds[2] = {expr_seed(P, 0, 0), expr_seed(P, 1, 1)}, jvp;
    ExprId dir[2] = {leaves[0], leaves[3]};
    diff_jvp(D, 1, &e, 2, dir, seeds, &jvp);
    d[n++] = jvp;
    double sink = 0;
    for (int i = 0; i < n; i++)
        sink += eval(P, d[i]);
    double many[12];
    int m = 0;
    for (int i = 0; i < n; i++)
        if (d[i] != EXPR_NONE)
            d[m++] = d[i];
    ExprEnv env = {0};
    static const double zero[2], p[1] = {1};
    env.q[0] = env.q[1] = env.q[2] = env.q[3] = zero;
    env.p = p, env.u = p;
    expr_eval_many(P, m, d, &env, many);
    ExprId from = leaves[0], to = leaves[1];
    expr_count_ops(P, 1, (ExprId[]){expr_subst(P, e, 1, &from, &to)});
    (void)sink;
}

static void
parse_one(void *ctx)
{
    Input *in = ctx;
    ExprPool *P = expr_pool_new();
    Diff *D = diff_new(P);
    Arena *A = arena_new();
    Kin *K = kin_new(A, P, D, 1, 1);
    int f = kin_frame(K, KIN_WORLD);
    kin_turn_axis(K, f, 2, expr_var(P, 0, 0));
    ExprId third = expr_const(P, 1.0 / 3), axis[3] = {third, third, expr_const(P, 0.88)};
    kin_turn(K, f, axis, expr_var(P, 1, 0)); /* not unit: kin takes it as given */
    ExprId at[3] = {expr_param(P, 0), expr_var(P, 0, 0), EXPR_ONE};
    kin_set_origin(K, f, kin_point(K, KIN_ORIGIN, f, at));
    ParseScope sc = {P, D, lookup, NULL, leaf_name, DEP_T | DEP_ANY_Q | DEP_P | DEP_U | DEP_S,
                     "an expression", 2, frame, point, K, NULL};
    ParseSrc src = {(const char *)in->data, in->size, where, NULL};
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    if (setjmp(jb) == 0) {
        int names = 0;
        parse_names(&src, count_name, &names);
        ParseVal v = parse_value(&sc, &src);
        for (int i = 0; i < (v.vec ? 3 : 1); i++)
            exercise(P, D, v.e[i]);
        /* the same text where only parameters and t may appear */
        sc.allow = DEP_P | DEP_T;
        sc.what = "a mass";
        parse_expr(&sc, &src);
    }
    diag_set_jump(old);
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
}

FUZZ_ENTRY(expr)
{
    Input in = {data, size};
    fuzz_run(parse_one, &in);
    return 0;
}
