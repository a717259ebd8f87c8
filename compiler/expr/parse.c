/*
 * parse: a recursive-descent parser (grammar in parse.h) that builds DAG
 * nodes as it goes, through the simplifying constructors.
 *
 * Recursion is bounded: nesting deeper than MAX_DEPTH (parentheses,
 * prefix signs, calls) is an error, not a stack overflow.  Long flat
 * expressions (a + b + c + ...) are loops, not recursion, but building a
 * sum or product term by term costs time proportional to its length (the
 * constructors collect like terms), so one expression is limited to
 * MAX_OPERATORS binary operators: a longer one is an error suggesting
 * defines, not minutes of work.  The token stream is never stored: the
 * lexer reads one token ahead.
 *
 * One file past ~800 lines: the lexer, the grammar and its messages
 * (each error names what was expected where, with the nearest known
 * name) are one concept, read together when the grammar changes.
 */
#include "parse.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_DEPTH = 200, MAX_NAME = 128, MAX_OPERATORS = 10000 };
/* The height of an expression with the defines it uses expanded: every
 * later pass (derivatives, emission) walks it, some recursively, and
 * derivatives are a few times higher still. */
enum { MAX_HEIGHT = 10000 };

typedef enum {
    T_END, T_NUM, T_NAME, T_PLUS, T_MINUS, T_STAR, T_SLASH, T_CARET,
    T_LPAREN, T_RPAREN, T_COMMA, T_PRIME, T_LBRACKET, T_RBRACKET, T_DOT,
} TokKind;

typedef struct Token {
    TokKind kind;
    size_t off, len; /* bytes of the source text */
    double num;      /* T_NUM */
} Token;

typedef struct Parser {
    ParseScope *sc;
    const ParseSrc *src;
    Token tok; /* the current token */
    int depth;
    int operators; /* binary operators so far */
} Parser;

static SrcLoc at(const Parser *ps, size_t off) { return ps->src->where(ps->src, off); }

static const char *
tok_text(const Parser *ps, const Token *t, char *buf, size_t len)
{
    if (t->kind == T_END)
        return "end of expression";
    size_t n = t->len < len - 3 ? t->len : len - 3;
    snprintf(buf, len, "'%.*s'", (int)n, ps->src->text + t->off);
    return buf;
}

/* ---- lexer ---- */

static int is_name_start(int c) { return isalpha(c) || c == '_'; }
static int is_name_char(int c) { return isalnum(c) || c == '_'; }

static size_t
scan_number(const ParseSrc *src, size_t i, double *value)
{
    const char *s = src->text;
    size_t start = i, n = src->len;
    while (i < n && isdigit((unsigned char)s[i]))
        i++;
    if (i < n && s[i] == '.')
        for (i++; i < n && isdigit((unsigned char)s[i]);)
            i++;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        size_t j = i + 1;
        if (j < n && (s[j] == '+' || s[j] == '-'))
            j++;
        if (j < n && isdigit((unsigned char)s[j])) {
            for (i = j; i < n && isdigit((unsigned char)s[i]);)
                i++;
        } else {
            diag_error(src->where(src, i), "malformed number: exponent has no digits");
        }
    }
    char buf[400];
    if (i - start >= sizeof buf)
        diag_error(src->where(src, start), "number has too many digits");
    memcpy(buf, s + start, i - start);
    buf[i - start] = '\0';
    errno = 0;
    *value = strtod(buf, NULL);
    if (errno == ERANGE && (isinf(*value) || *value == 0.0) && strspn(buf, "0.eE+-") != strlen(buf))
        diag_error(src->where(src, start), "number %s is out of the range of a double", buf);
    return i;
}

/* The length of YAML's spelling of infinity or NaN after its '.' at i
 * (`.inf`, `.NaN`, ...), or 0: a YAML number that is not finite. */
static size_t
not_finite(const ParseSrc *src, size_t i)
{
    static const char *const words[] = {"inf", "Inf", "INF", "nan", "NaN", "NAN"};
    for (size_t k = 0; k < sizeof words / sizeof words[0]; k++)
        if (src->len - i >= 3 && !memcmp(src->text + i, words[k], 3) &&
            (src->len - i == 3 || !is_name_char((unsigned char)src->text[i + 3])))
            return 3;
    return 0;
}

static _Noreturn void
bad_char(const ParseSrc *src, size_t i)
{
    unsigned char c = (unsigned char)src->text[i];
    if (c >= 0x80) {
        size_t n = 1;
        while (i + n < src->len && ((unsigned char)src->text[i + n] & 0xC0) == 0x80)
            n++;
        diag_error(src->where(src, i), "unexpected character '%.*s' (names are ASCII)",
                   (int)n, src->text + i);
    }
    if (c == '.' && not_finite(src, i + 1))
        diag_error(src->where(src, i), "'%.*s' is not allowed: every value must be a finite "
                   "number", (int)not_finite(src, i + 1) + 1, src->text + i);
    if (c == '=')
        diag_error(src->where(src, i), "unexpected '=': an expression here is a value, "
                   "not an equation (a constraint `f = 0` is written as just f)");
    if (isprint(c))
        diag_error(src->where(src, i), "unexpected character '%c'", c);
    diag_error(src->where(src, i), "unexpected character (byte 0x%02x)", c);
}

static Token
lex(const ParseSrc *src, size_t i)
{
    const char *s = src->text;
    while (i < src->len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r'))
        i++;
    Token t = {T_END, i, 0, 0.0};
    if (i >= src->len)
        return t;
    unsigned char c = (unsigned char)s[i];
    static const char ops[] = "+-*/^(),'[]";
    static const TokKind kinds[] = {T_PLUS, T_MINUS, T_STAR, T_SLASH, T_CARET,
                                    T_LPAREN, T_RPAREN, T_COMMA, T_PRIME,
                                    T_LBRACKET, T_RBRACKET};
    if (isdigit(c) || (c == '.' && i + 1 < src->len && isdigit((unsigned char)s[i + 1]))) {
        t.kind = T_NUM;
        t.len = scan_number(src, i, &t.num) - i;
    } else if (is_name_start(c)) {
        size_t j = i;
        while (j < src->len && is_name_char((unsigned char)s[j]))
            j++;
        t.kind = T_NAME;
        t.len = j - i;
        if (t.len > MAX_NAME)
            diag_error(src->where(src, i), "name is longer than %d characters", MAX_NAME);
    } else if (c == '.' && i + 1 < src->len && is_name_start((unsigned char)s[i + 1]) &&
               !not_finite(src, i + 1)) {
        t.kind = T_DOT; /* a frame's axis: F.x */
        t.len = 1;
    } else if (c && strchr(ops, c)) {
        t.kind = kinds[strchr(ops, c) - ops];
        t.len = 1;
        if (c == '*' && i + 1 < src->len && s[i + 1] == '*')
            diag_error(src->where(src, i), "'**' is not an operator here: write powers as x^2");
    } else {
        bad_char(src, i);
    }
    return t;
}

static void next(Parser *ps) { ps->tok = lex(ps->src, ps->tok.off + ps->tok.len); }

static int
accept(Parser *ps, TokKind k)
{
    if (ps->tok.kind != k)
        return 0;
    next(ps);
    return 1;
}

/* ---- built-in functions ---- */

typedef struct Builtin {
    const char *name;
    int op;    /* EXPR_ op, or a BUILTIN_ */
    int arity;
} Builtin;

enum { BUILTIN_DOT = -1, BUILTIN_DELTA = -2, BUILTIN_MAX = -3, BUILTIN_MIN = -4,
       BUILTIN_CLAMP = -5, BUILTIN_STEP = -6, BUILTIN_ABS = -7 /* abs where modes are read */ };
enum { MAX_ARGS = 3 }; /* clamp's */

/* The functions of frames, points and vectors: not reserved names (a
 * parameter may be called omega), functions only when called.  Their
 * arguments are frames (F), points (P) or values (v). */
typedef enum {
    VF_POS, VF_VEL, VF_ACC, VF_OMEGA, VF_ALPHA, VF_VEC, VF_CROSS, VF_NORM,
} VecFn;

typedef struct VecBuiltin {
    const char *name;
    VecFn fn;
    const char *args, *opt; /* the arguments' kinds, then the optional ones */
    const char *usage;
} VecBuiltin;

static const VecBuiltin vec_builtins[] = {
    {"pos", VF_POS, "P", "P", "pos(P) or pos(P, FROM)"},
    {"vel", VF_VEL, "P", "F", "vel(P), or vel(P, FRAME) for the point of FRAME at P"},
    {"acc", VF_ACC, "P", "F", "acc(P), or acc(P, FRAME) for the point of FRAME at P"},
    {"omega", VF_OMEGA, "F", "F", "omega(F) or omega(F, RELATIVE_TO)"},
    {"alpha", VF_ALPHA, "F", "F", "alpha(F) or alpha(F, RELATIVE_TO)"},
    {"vec", VF_VEC, "Fvvv", "", "vec(F, a, b, c), components in F"},
    {"cross", VF_CROSS, "vv", "", "cross(a, b)"},
    {"norm", VF_NORM, "v", "", "norm(a)"},
};
enum { NVEC_BUILTINS = sizeof vec_builtins / sizeof vec_builtins[0] };

static const Builtin builtins[] = {
    {"sin", EXPR_SIN, 1},   {"cos", EXPR_COS, 1},     {"tan", EXPR_TAN, 1},
    {"asin", EXPR_ASIN, 1}, {"acos", EXPR_ACOS, 1},   {"atan", EXPR_ATAN, 1},
    {"atan2", EXPR_ATAN2, 2}, {"sinh", EXPR_SINH, 1}, {"cosh", EXPR_COSH, 1},
    {"tanh", EXPR_TANH, 1}, {"exp", EXPR_EXP, 1},     {"log", EXPR_LOG, 1},
    {"sqrt", EXPR_SQRT, 1}, {"abs", EXPR_ABS, 1},     {"pow", EXPR_POW, 2},
    {"dot", BUILTIN_DOT, 1}, {"delta", BUILTIN_DELTA, 1},
    {"max", BUILTIN_MAX, 2}, {"min", BUILTIN_MIN, 2}, {"clamp", BUILTIN_CLAMP, 3},
    {"step", BUILTIN_STEP, 1},
};
enum { NBUILTINS = sizeof builtins / sizeof builtins[0] };

static const Builtin *
find_builtin(const char *name)
{
    for (int i = 0; i < NBUILTINS; i++)
        if (strcmp(builtins[i].name, name) == 0)
            return &builtins[i];
    return NULL;
}

/* Only the names no call tells apart are reserved: a function's name is
 * a function only when called, so that a bicycle's steer angle can be
 * delta, and delta(e) its variation beside it. */
int
parse_is_reserved(const char *name)
{
    return !strcmp(name, "t") || !strcmp(name, "pi");
}

int
parse_is_function(const char *name)
{
    for (int i = 0; i < NVEC_BUILTINS; i++)
        if (!strcmp(vec_builtins[i].name, name))
            return 1;
    return find_builtin(name) != NULL;
}

/* ---- dependency checks ---- */

static void
describe_leaf(ParseScope *sc, ExprId leaf, char *buf, size_t len)
{
    const ExprNode *nd = expr_node(sc->P, leaf);
    static const char *const order[] = {"coordinate", "velocity", "acceleration", "jerk"};
    static const char *const primes[] = {"", "'", "''", "'''"};
    switch (nd->op) {
    case EXPR_TIME:
        snprintf(buf, len, "time t");
        break;
    case EXPR_VAR:
        snprintf(buf, len, "the %s '%s%s'", order[nd->b], sc->leaf_name(sc, leaf), primes[nd->b]);
        break;
    case EXPR_SEED:
        snprintf(buf, len, "the variation delta(%s) (only virtual work, `work:`, has "
                 "variations)", sc->leaf_name(sc, expr_var(sc->P, (int)nd->a, 0)));
        break;
    case EXPR_PARAM:
        snprintf(buf, len, "the parameter '%s'", sc->leaf_name(sc, leaf));
        break;
    case EXPR_MULT:
        snprintf(buf, len, "the multiplier lambda[%s] (only a scene's outputs have "
                 "multipliers)", sc->leaf_name(sc, leaf));
        break;
    default:
        snprintf(buf, len, "the input '%s'", sc->leaf_name(sc, leaf));
    }
}

/* e is what `name` (or a derivative, name = NULL) produced at off. */
static void
check_deps(Parser *ps, ExprId e, const char *name, size_t off)
{
    ParseScope *sc = ps->sc;
    unsigned bad = expr_deps(sc->P, e) & ~sc->allow;
    if (!bad)
        return;
    ExprId leaf = expr_find_leaf(sc->P, e, bad);
    if (leaf == EXPR_NONE) /* only a SELECT's mode has no leaf */
        diag_error(at(ps, off), "%s cannot depend on a switched expression (max, min, "
                   "clamp, step, abs)%s%s%s", sc->what, name ? " (through '" : "", name ? name : "",
                   name ? "')" : "");
    char what[200];
    describe_leaf(sc, leaf, what, sizeof what);
    if (name && expr_op_arity[expr_node(sc->P, e)->op] != 0)
        diag_error(at(ps, off), "%s cannot depend on %s (through '%s')", sc->what, what, name);
    diag_error(at(ps, off), "%s cannot depend on %s", sc->what, what);
}

/* ---- values ---- */

typedef ParseVal Val;

static Val
scalar_val(ExprId e)
{
    return (Val){0, {e, EXPR_NONE, EXPR_NONE}};
}

static Val
vector_val(const ExprId e[3])
{
    return (Val){1, {e[0], e[1], e[2]}};
}

static void
check_val(Parser *ps, Val v, const char *name, size_t off)
{
    for (int i = 0; i < (v.vec ? 3 : 1); i++)
        check_deps(ps, v.e[i], name, off);
}

/* v, at off, must be a scalar for `where`: the error says what a vector
 * could become. */
static ExprId
need_scalar(Parser *ps, Val v, size_t off, const char *where)
{
    if (v.vec)
        diag_error(at(ps, off), "this is a vector, and %s takes a scalar: a component is "
                   "dot(v, F.x), a length norm(v)", where);
    return v.e[0];
}

static void
need_vector(Parser *ps, Val v, size_t off, const char *where)
{
    if (!v.vec)
        diag_error(at(ps, off), "this is a scalar, and %s takes a vector (such as pos(P), "
                   "vel(P), omega(F), F.x or vec(F, a, b, c))", where);
}

static Val
cross3(ExprPool *P, const ExprId *a, const ExprId *b)
{
    Val v = {1, {0, 0, 0}};
    kin_cross(P, a, b, v.e);
    return v;
}

static Val
add_val(ExprPool *P, Val a, Val b, int sign)
{
    for (int i = 0; i < (a.vec ? 3 : 1); i++)
        a.e[i] = sign > 0 ? expr_add(P, a.e[i], b.e[i]) : expr_sub(P, a.e[i], b.e[i]);
    return a;
}

/* The total time derivative of e, or an error at off saying why not. */
static ExprId
time_derivative(Parser *ps, ExprId e, size_t off)
{
    ParseScope *sc = ps->sc;
    ExprId d = diff_time(sc->D, e);
    if (d != EXPR_NONE) {
        check_deps(ps, d, NULL, off);
        return d;
    }
    ExprId u = expr_find_leaf(sc->P, e, DEP_U);
    if (u != EXPR_NONE)
        diag_error(at(ps, off), "cannot differentiate the input '%s': an input's time "
                   "derivative is not known (write the signal of t in a define instead)",
                   sc->leaf_name(sc, u));
    diag_error(at(ps, off), "derivatives above the third (q''') are not supported");
}

/* A vector's derivative is its components' (world components: the world
 * does not turn). */
static Val
time_derivative_val(Parser *ps, Val v, size_t off)
{
    for (int i = 0; i < (v.vec ? 3 : 1); i++)
        v.e[i] = time_derivative(ps, v.e[i], off);
    return v;
}

/* delta(e): the virtual displacement of e at fixed time,
 *     delta(e) = sum_i de/dq_i delta(q_i),
 * with the variations delta(q_i) as EXPR_SEED leaves (kind 0), or an
 * error at off saying why e has none.  Of a speed that is no coordinate's
 * rate (a quaternion's w, leaf ncoord + k), its own virtual rotation, the
 * seed ncoord + k. */
static ExprId
variation(Parser *ps, ExprId e, size_t off)
{
    ParseScope *sc = ps->sc;
    ExprPool *P = sc->P;
    unsigned deps = expr_deps(P, e);
    if (deps & DEP_S)
        diag_error(at(ps, off), "delta() of an expression that holds a variation: virtual "
                   "work is linear in the variations, so write each as delta(e) of a position e");
    const ExprNode *nd = expr_node(P, e);
    if (nd->op == EXPR_VAR && nd->b == 1 && (int)nd->a >= sc->ncoord) /* a speed's virtual */
        return expr_seed(P, (int)nd->a, 0);                          /* rotation */
    unsigned moving = DEP_ANY_Q & ~DEP_ORDER(0);
    if (deps & moving) {
        char what[200];
        describe_leaf(sc, expr_find_leaf(P, e, moving), what, sizeof what);
        diag_error(at(ps, off), "delta() varies positions at a fixed time, and this "
                   "expression depends on %s: write the force's factor outside, as in "
                   "-c*r'*delta(r)", what);
    }
    ExprId r = EXPR_ZERO;
    for (int i = 0; i < sc->ncoord; i++) {
        ExprId dq = expr_seed(P, i, 0);
        ExprId de = diff_partial(sc->D, e, expr_var(P, i, 0));
        r = expr_add(P, r, expr_mul(P, de, dq));
    }
    check_deps(ps, r, NULL, off);
    return r;
}

/* ---- constants ---- */

/* e is OP applied at off to the constants a (and b, unless EXPR_NONE).
 * The constructors fold constants only to finite values, so a result that
 * is not a constant is an infinity or a NaN: log(0), 0^-1, 1e308*10,
 * acos(2).  No generated code should compute one. */
static ExprId
finite(Parser *ps, ExprId e, const char *op, ExprId a, ExprId b, size_t off)
{
    ExprPool *P = ps->sc->P;
    double x, y = 0;
    if (!expr_is_const(P, a, &x) || (b != EXPR_NONE && !expr_is_const(P, b, &y)) ||
        expr_is_const(P, e, NULL))
        return e;
    char what[160];
    if (isalpha((unsigned char)op[0]) && b != EXPR_NONE)
        snprintf(what, sizeof what, "%s(%g, %g)", op, x, y);
    else if (isalpha((unsigned char)op[0]))
        snprintf(what, sizeof what, "%s(%g)", op, x);
    else
        snprintf(what, sizeof what, "%g %s %g", x, op, y);
    diag_error(at(ps, off), "%s is not a finite number", what);
}

/* ---- the grammar ---- */

static Val expr(Parser *ps);
static Val unary(Parser *ps);

/* One level deeper, for the '(', sign or '^' at off: the error points at
 * the one that goes too deep, not at what follows it. */
static void
enter(Parser *ps, size_t off)
{
    if (++ps->depth > MAX_DEPTH)
        diag_error(at(ps, off), "expression is nested more than %d levels deep", MAX_DEPTH);
}

static void
expect(Parser *ps, TokKind k, const char *what, size_t open_off)
{
    if (ps->tok.kind == k) {
        next(ps);
        return;
    }
    char buf[80];
    const char *found = tok_text(ps, &ps->tok, buf, sizeof buf);
    if (k == T_RPAREN) {
        SrcLoc o = at(ps, open_off);
        diag_error(at(ps, ps->tok.off), "expected ')' to close the '(' at column %d, found %s",
                   o.col, found);
    }
    diag_error(at(ps, ps->tok.off), "expected %s, found %s", what, found);
}

/* A call of something that is not a function: the nearest function's
 * name, or the list of them. */
static _Noreturn void
unknown_function(Parser *ps, const char *name, size_t off)
{
    const char *names[NBUILTINS + NVEC_BUILTINS];
    char list[512] = "";
    int n = 0;
    for (int i = 0; i < NBUILTINS; i++)
        names[n++] = builtins[i].name;
    for (int i = 0; i < NVEC_BUILTINS && ps->sc->K; i++)
        names[n++] = vec_builtins[i].name;
    for (int i = 0; i < n; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                 names[i]);
    const char *near = diag_nearest(name, names, n);
    if (near)
        diag_error(at(ps, off), "unknown function '%s'; did you mean %s?", name, near);
    diag_error(at(ps, off), "unknown function '%s' (the functions are %s)", name, list);
}

/* A name argument: a frame (kind 'F') or a point ('P'). */
static int
name_arg(Parser *ps, char kind, const char *fn)
{
    ParseScope *sc = ps->sc;
    if (ps->tok.kind != T_NAME) {
        char buf[80];
        diag_error(at(ps, ps->tok.off), "%s takes the name of a %s here, not %s", fn,
                   kind == 'F' ? "frame" : "point", tok_text(ps, &ps->tok, buf, sizeof buf));
    }
    char name[MAX_NAME + 1];
    size_t off = ps->tok.off;
    memcpy(name, ps->src->text + off, ps->tok.len);
    name[ps->tok.len] = '\0';
    next(ps);
    return kind == 'F' ? sc->frame(sc, name, at(ps, off)) : sc->point(sc, name, at(ps, off));
}

/* The velocity (order 1) or acceleration (2) of the point of frame f at
 * point p: its origin's, and the rigid motion about it. */
static Val
frame_point_motion(Parser *ps, int p, int f, int order, size_t off, const char *fn)
{
    ParseScope *sc = ps->sc;
    ExprPool *P = sc->P;
    int o = kin_origin(sc->K, f);
    if (o < 0)
        diag_error(at(ps, off), "%s(P, F) moves P with frame F about F's origin, and this "
                   "frame has none: give it `origin: POINT`", fn);
    ExprId rp[3], ro[3], r[3], w[3];
    kin_pos(sc->K, p, rp);
    kin_pos(sc->K, o, ro);
    kin_omega(sc->K, f, w);
    for (int i = 0; i < 3; i++)
        r[i] = expr_sub(P, rp[i], ro[i]);
    int k = p;
    while (k > KIN_ORIGIN && k != o) {
        ExprId at[3], o3[3];
        int fk;
        k = kin_point_link(sc->K, k, &fk, at, o3);
    }
    if (order == 1 && k == o) {
        /* P offset from the origin O through links o_k = R_fk at_k:
         * v = vel(P) + sum_k (w_F - w_fk) x o_k - R_fk at_k', the form in
         * which a contact point's own motion cancels by structure */
        /* vel(P) as the rate of pos(P) here, not kin_vel: a contact point
         * offset and brought back has a position that simplifies away */
        Val v = time_derivative_val(ps, vector_val(rp), off);
        for (k = p; k != o;) {
            ExprId at[3], o3[3], rel[3];
            int fk, from = kin_point_link(sc->K, k, &fk, at, o3);
            if (kin_omega_rel_in(sc->K, f, fk, rel)) { /* in fk's axes, where at is */
                Val c = cross3(P, rel, at);
                kin_to_world(sc->K, fk, c.e, c.e);
                v = add_val(P, v, c, 1);
            } else {
                kin_omega_rel(sc->K, f, fk, rel);
                v = add_val(P, v, cross3(P, rel, o3), 1);
            }
            Val rate = time_derivative_val(ps, vector_val(at), off);
            kin_to_world(sc->K, fk, rate.e, rate.e);
            v = add_val(P, v, rate, -1);
            k = from < 0 ? KIN_ORIGIN : from;
        }
        return v;
    }
    ExprId vo[3];
    kin_vel(sc->K, o, vo);
    Val v = vector_val(vo);
    Val wr = cross3(P, w, r);
    if (order == 1)
        return add_val(P, v, wr, 1);
    Val a = time_derivative_val(ps, v, off);
    Val al = time_derivative_val(ps, vector_val(w), off);
    a = add_val(P, a, cross3(P, al.e, r), 1);
    return add_val(P, a, cross3(P, w, wr.e), 1);
}

/* A call of a vector function, the name read and the '(' current. */
static Val
vec_call(Parser *ps, const VecBuiltin *b, size_t name_off)
{
    ParseScope *sc = ps->sc;
    ExprPool *P = sc->P;
    size_t open = ps->tok.off;
    next(ps); /* ( */
    enter(ps, open);
    int idx[4] = {0};
    Val v[4];
    size_t voff[4] = {0};
    int nreq = (int)strlen(b->args), nopt = (int)strlen(b->opt), n = 0;
    while (n < nreq + nopt && (n < nreq || ps->tok.kind == T_COMMA)) {
        if (n > 0 && !accept(ps, T_COMMA)) {
            char buf[80];
            diag_error(at(ps, ps->tok.off), "expected ',' and more arguments, found %s: %s",
                       tok_text(ps, &ps->tok, buf, sizeof buf), b->usage);
        }
        char kind = n < nreq ? b->args[n] : b->opt[n - nreq];
        voff[n] = ps->tok.off;
        if (kind == 'v')
            v[n] = expr(ps);
        else
            idx[n] = name_arg(ps, kind, b->name);
        n++;
    }
    if (ps->tok.kind == T_COMMA)
        diag_error(at(ps, ps->tok.off), "too many arguments: %s", b->usage);
    expect(ps, T_RPAREN, "')'", open);
    ps->depth--;
    ExprId a[3], c[3];
    Val r;
    switch (b->fn) {
    case VF_POS:
        kin_pos(sc->K, idx[0], a);
        if (n == 2) {
            kin_pos(sc->K, idx[1], c);
            for (int i = 0; i < 3; i++)
                a[i] = expr_sub(P, a[i], c[i]);
        }
        r = vector_val(a);
        break;
    case VF_VEL:
    case VF_ACC:
        if (n == 2) {
            r = frame_point_motion(ps, idx[0], idx[1], b->fn == VF_VEL ? 1 : 2, name_off,
                                   b->name);
            break;
        }
        kin_vel(sc->K, idx[0], a); /* by the links' structure (kin.h) */
        r = vector_val(a);
        if (b->fn == VF_ACC)
            r = time_derivative_val(ps, r, name_off);
        break;
    case VF_OMEGA:
    case VF_ALPHA:
        /* relative to G: w_F - w_G, and its rate as G sees it */
        kin_omega(sc->K, idx[0], a);
        for (int i = 0; i < 3; i++)
            c[i] = EXPR_ZERO;
        if (n == 2)
            kin_omega(sc->K, idx[1], c);
        for (int i = 0; i < 3; i++)
            a[i] = expr_sub(P, a[i], c[i]);
        r = vector_val(a);
        if (b->fn == VF_ALPHA) {
            Val rel = r;
            r = time_derivative_val(ps, r, name_off);
            r = add_val(P, r, cross3(P, c, rel.e), -1);
        }
        break;
    case VF_VEC:
        for (int k = 0; k < 3; k++)
            a[k] = need_scalar(ps, v[k + 1], voff[k + 1], "a component");
        kin_to_world(sc->K, idx[0], a, c);
        r = vector_val(c);
        break;
    case VF_CROSS:
        need_vector(ps, v[0], voff[0], "cross()");
        need_vector(ps, v[1], voff[1], "cross()");
        r = cross3(P, v[0].e, v[1].e);
        break;
    default: /* VF_NORM */
        need_vector(ps, v[0], voff[0], "norm()");
        r = scalar_val(expr_unary(P, EXPR_SQRT, kin_dot(P, v[0].e, v[0].e)));
        break;
    }
    check_val(ps, r, NULL, name_off);
    return r;
}

/* max, min, clamp or step: a switched expression (expr.h), only where the
 * scope lets a mode be read. */
static ExprId
switched_call(Parser *ps, int op, const char *name, size_t name_off, const Val *args,
              const size_t *offs, const char *where)
{
    ParseScope *sc = ps->sc;
    if ((sc->allow & (DEP_M | DEP_U)) != (DEP_M | DEP_U))
        diag_error(at(ps, name_off), "%s cannot use %s(): its kink is a switch the run "
                   "locates, and only forces, potentials and virtual work have switches",
                   sc->what, name);
    ExprId e[MAX_ARGS], r;
    int n = op == BUILTIN_CLAMP ? 3 : op == BUILTIN_STEP || op == BUILTIN_ABS ? 1 : 2;
    int n0 = expr_nswitch(sc->P);
    for (int i = 0; i < n; i++)
        e[i] = need_scalar(ps, args[i], offs[i], where);
    if (op == BUILTIN_CLAMP) {
        double lo, hi;
        if (expr_is_const(sc->P, e[1], &lo) && expr_is_const(sc->P, e[2], &hi) && lo > hi)
            diag_error(at(ps, offs[1]), "clamp(x, lo, hi) needs lo <= hi, not %g > %g", lo, hi);
        r = expr_clamp(sc->P, e[0], e[1], e[2]);
    } else if (op == BUILTIN_ABS) {
        ExprId neg = expr_neg(sc->P, e[0]);
        r = expr_where(sc->P, e[0], e[0], neg);
    } else if (op == BUILTIN_STEP) {
        ExprId one = expr_const(sc->P, 1), zero = expr_const(sc->P, 0);
        r = expr_where(sc->P, e[0], one, zero);
    }
    else
        r = op == BUILTIN_MAX ? expr_max(sc->P, e[0], e[1]) : expr_min(sc->P, e[0], e[1]);
    /* the new switches' names: owner.max, owner.clamp.lo and .hi */
    ExprId s_lo = op == BUILTIN_CLAMP ? expr_sub(sc->P, e[0], e[1]) : EXPR_NONE;
    for (int k = n0; k < expr_nswitch(sc->P); k++) {
        char nm[2 * MAX_NAME + 16];
        snprintf(nm, sizeof nm, "%s%s%s%s", sc->owner ? sc->owner : "", sc->owner ? "." : "",
                 name, op != BUILTIN_CLAMP ? "" : expr_switch(sc->P, k) == s_lo ? ".lo" : ".hi");
        expr_name_switch(sc->P, k, nm);
    }
    return r;
}

/* NAME "(" expr ("," expr)* ")" with the name already read. */
static Val
call(Parser *ps, const char *name, size_t name_off)
{
    const Builtin *b = find_builtin(name);
    if (!b && ps->sc->K)
        for (int i = 0; i < NVEC_BUILTINS; i++)
            if (!strcmp(vec_builtins[i].name, name))
                return vec_call(ps, &vec_builtins[i], name_off);
    if (!b)
        unknown_function(ps, name, name_off);
    /* dot(e) is the time derivative; dot(a, b) of two vectors, their product */
    int most = b->op == BUILTIN_DOT && ps->sc->K ? 2 : b->arity;
    size_t open = ps->tok.off;
    next(ps); /* ( */
    enter(ps, open);
    Val args[MAX_ARGS];
    size_t offs[MAX_ARGS] = {0, 0, 0};
    int n = 0;
    if (ps->tok.kind != T_RPAREN) {
        do {
            size_t arg_off = ps->tok.off;
            Val a = expr(ps);
            if (n == most)
                diag_error(at(ps, arg_off), "too many arguments: %s takes %d", name, most);
            offs[n] = arg_off;
            args[n++] = a;
        } while (accept(ps, T_COMMA));
    }
    expect(ps, T_RPAREN, "')'", open);
    ps->depth--;
    ExprPool *P = ps->sc->P;
    if (b->op == BUILTIN_DOT && n == 2) {
        need_vector(ps, args[0], offs[0], "dot(a, b)");
        need_vector(ps, args[1], offs[1], "dot(a, b)");
        return scalar_val(kin_dot(P, args[0].e, args[1].e));
    }
    if (n != b->arity)
        diag_error(at(ps, name_off), "%s takes %d argument%s, not %d", name, b->arity,
                   b->arity == 1 ? "" : "s", n);
    if (b->op == BUILTIN_DOT)
        return time_derivative_val(ps, args[0], name_off);
    if (b->op == BUILTIN_DELTA) {
        for (int i = 0; i < (args[0].vec ? 3 : 1); i++)
            args[0].e[i] = variation(ps, args[0].e[i], name_off);
        return args[0];
    }
    char where[MAX_NAME + 8];
    snprintf(where, sizeof where, "%s()", name);
    ExprId x = need_scalar(ps, args[0], offs[0], where);
    if (b->op <= BUILTIN_MAX)
        return scalar_val(switched_call(ps, b->op, name, name_off, args, offs, where));
    /* where a mode can be read (a force, a potential, a define), abs's kink
     * is a switch the run locates; elsewhere (a position, a mass, an event)
     * it is differentiated as |x|' = sign(x) */
    if (b->op == EXPR_ABS && (ps->sc->allow & (DEP_M | DEP_U)) == (DEP_M | DEP_U))
        return scalar_val(switched_call(ps, BUILTIN_ABS, name, name_off, args, offs, where));
    if (b->arity == 1)
        return scalar_val(finite(ps, expr_unary(P, b->op, x), name, x, EXPR_NONE, name_off));
    ExprId y = need_scalar(ps, args[1], offs[1], where);
    return scalar_val(finite(ps, expr_binary(P, b->op, x, y), name, x, y, name_off));
}

/* lambda[NAME]: the multiplier of constraint NAME. */
static ExprId
multiplier(Parser *ps, size_t off)
{
    ParseScope *sc = ps->sc;
    size_t open = ps->tok.off;
    next(ps); /* [ */
    if (ps->tok.kind != T_NAME) {
        char buf[80];
        diag_error(at(ps, ps->tok.off), "expected a constraint's name after 'lambda[', "
                   "found %s", tok_text(ps, &ps->tok, buf, sizeof buf));
    }
    char name[MAX_NAME + 1];
    size_t noff = ps->tok.off;
    memcpy(name, ps->src->text + noff, ps->tok.len);
    name[ps->tok.len] = '\0';
    next(ps);
    expect(ps, T_RBRACKET, "']'", open);
    if (!sc->multiplier || !(sc->allow & DEP_L))
        diag_error(at(ps, off), "%s cannot depend on a multiplier (only a scene's outputs "
                   "have them)", sc->what);
    ExprId e = sc->multiplier(sc, name, at(ps, noff));
    check_deps(ps, e, NULL, off);
    return e;
}

/* FRAME.x: the axis, the name read and the '.' current. */
static Val
frame_axis(Parser *ps, const char *name, size_t off)
{
    ParseScope *sc = ps->sc;
    size_t dot = ps->tok.off;
    if (!sc->K)
        diag_error(at(ps, dot), "unexpected '.'");
    next(ps); /* . */
    int f = sc->frame(sc, name, at(ps, off));
    const char *member = ps->src->text + ps->tok.off;
    if (ps->tok.kind != T_NAME || ps->tok.len != 1 || !strchr("xyz", member[0]))
        diag_error(at(ps, ps->tok.off), "a frame's axes are %s.x, %s.y and %s.z", name, name,
                   name);
    ExprId a[3];
    kin_axis(sc->K, f, member[0] - 'x', a);
    next(ps);
    return vector_val(a);
}

static Val
name_or_call(Parser *ps)
{
    char name[MAX_NAME + 1];
    size_t off = ps->tok.off, len = ps->tok.len;
    memcpy(name, ps->src->text + off, len);
    name[len] = '\0';
    next(ps);
    if (ps->tok.kind == T_LPAREN)
        return call(ps, name, off);
    if (ps->tok.kind == T_DOT)
        return frame_axis(ps, name, off);
    if (ps->tok.kind == T_LBRACKET && !strcmp(name, "lambda"))
        return scalar_val(multiplier(ps, off));
    ParseScope *sc = ps->sc;
    Val v;
    if (!strcmp(name, "t"))
        v = scalar_val(expr_time(sc->P));
    else if (!strcmp(name, "pi"))
        v = scalar_val(expr_const(sc->P, 3.14159265358979323846));
    else
        v = sc->lookup(sc, name, at(ps, off));
    check_val(ps, v, name, off);
    return v;
}

/* primary = NUMBER | NAME | call | FRAME.x | "(" expr ")" */
static Val
primary(Parser *ps)
{
    Token t = ps->tok;
    char buf[80];
    switch (t.kind) {
    case T_NUM:
        next(ps);
        return scalar_val(expr_const(ps->sc->P, t.num));
    case T_NAME:
        return name_or_call(ps);
    case T_LPAREN: {
        next(ps);
        enter(ps, t.off);
        Val e = expr(ps);
        expect(ps, T_RPAREN, "')'", t.off);
        ps->depth--;
        return e;
    }
    default:
        diag_error(at(ps, t.off), "expected a number, a name or '(', found %s",
                   tok_text(ps, &t, buf, sizeof buf));
    }
}

/* postfix = primary "'"* */
static Val
postfix(Parser *ps)
{
    Val e = primary(ps);
    while (ps->tok.kind == T_PRIME) {
        size_t prime = ps->tok.off;
        next(ps);
        e = time_derivative_val(ps, e, prime);
    }
    return e;
}

/* power = postfix ("^" unary)? */
static Val
power(Parser *ps)
{
    size_t base_off = ps->tok.off;
    Val base = postfix(ps);
    if (ps->tok.kind != T_CARET)
        return base;
    size_t caret = ps->tok.off;
    next(ps);
    enter(ps, caret);
    size_t ex_off = ps->tok.off;
    Val ex = unary(ps);
    ps->depth--;
    ExprId b = need_scalar(ps, base, base_off, "'^'");
    ExprId x = need_scalar(ps, ex, ex_off, "'^'");
    return scalar_val(finite(ps, expr_pow(ps->sc->P, b, x), "^", b, x, caret));
}

/* unary = ("-" | "+") unary | power */
static Val
unary(Parser *ps)
{
    if (ps->tok.kind != T_MINUS && ps->tok.kind != T_PLUS)
        return power(ps);
    int neg = ps->tok.kind == T_MINUS;
    size_t sign = ps->tok.off;
    next(ps);
    enter(ps, sign);
    Val e = unary(ps);
    ps->depth--;
    for (int i = 0; neg && i < (e.vec ? 3 : 1); i++)
        e.e[i] = expr_neg(ps->sc->P, e.e[i]);
    return e;
}

/* One more binary operator, at the current token. */
static void
count_operator(Parser *ps)
{
    if (++ps->operators > MAX_OPERATORS)
        diag_error(at(ps, ps->tok.off), "expression has more than %d operators; split it "
                   "into defines", MAX_OPERATORS);
}

/* term = unary (("*" | "/") unary)* */
static Val
term(Parser *ps)
{
    ExprPool *P = ps->sc->P;
    Val e = unary(ps);
    for (;;) {
        if (ps->tok.kind == T_STAR || ps->tok.kind == T_SLASH)
            count_operator(ps);
        size_t op = ps->tok.off;
        if (accept(ps, T_STAR)) {
            Val f = unary(ps);
            if (e.vec && f.vec)
                diag_error(at(ps, op), "'*' of two vectors: write dot(a, b) or cross(a, b)");
            if (!e.vec && !f.vec) {
                e.e[0] = finite(ps, expr_mul(P, e.e[0], f.e[0]), "*", e.e[0], f.e[0], op);
                continue;
            }
            Val r = e.vec ? e : f;
            ExprId k = e.vec ? f.e[0] : e.e[0];
            for (int i = 0; i < 3; i++)
                r.e[i] = expr_mul(P, k, r.e[i]);
            e = r;
        } else if (accept(ps, T_SLASH)) {
            Val d = unary(ps);
            if (d.vec)
                diag_error(at(ps, op), "'/' by a vector: only a scalar divides");
            if (d.e[0] == EXPR_ZERO)
                diag_error(at(ps, op), "division by zero");
            for (int i = 0; i < (e.vec ? 3 : 1); i++)
                e.e[i] = finite(ps, expr_div(P, e.e[i], d.e[0]), "/", e.e[i], d.e[0], op);
        } else {
            return e;
        }
    }
}

/* expr = term (("+" | "-") term)* */
static Val
expr(Parser *ps)
{
    ExprPool *P = ps->sc->P;
    Val e = term(ps);
    for (;;) {
        if (ps->tok.kind == T_PLUS || ps->tok.kind == T_MINUS)
            count_operator(ps);
        size_t op = ps->tok.off;
        int sign = accept(ps, T_PLUS) ? 1 : accept(ps, T_MINUS) ? -1 : 0;
        if (!sign)
            return e;
        Val r = term(ps);
        if (r.vec != e.vec)
            diag_error(at(ps, op), "'%c' of a vector and a scalar", sign > 0 ? '+' : '-');
        for (int i = 0; i < (e.vec ? 3 : 1); i++) {
            ExprId a = e.e[i];
            e.e[i] = finite(ps, sign > 0 ? expr_add(P, a, r.e[i]) : expr_sub(P, a, r.e[i]),
                            sign > 0 ? "+" : "-", a, r.e[i], op);
        }
    }
}

ParseVal
parse_value(ParseScope *sc, const ParseSrc *src)
{
    Parser ps = {sc, src, {T_END, 0, 0, 0.0}, 0, 0};
    ps.tok = lex(src, 0);
    if (ps.tok.kind == T_END)
        diag_error(at(&ps, 0), "empty expression");
    Val e = expr(&ps);
    if (ps.tok.kind != T_END) {
        char buf[80];
        const char *found = tok_text(&ps, &ps.tok, buf, sizeof buf);
        if (ps.tok.kind == T_NAME || ps.tok.kind == T_NUM || ps.tok.kind == T_LPAREN)
            diag_error(at(&ps, ps.tok.off), "expected an operator before %s "
                       "(multiplication is written with '*')", found);
        if (ps.tok.kind == T_RPAREN)
            diag_error(at(&ps, ps.tok.off), "unmatched ')'");
        diag_error(at(&ps, ps.tok.off), "unexpected %s", found);
    }
    for (int i = 0; i < (e.vec ? 3 : 1); i++)
        if (e.e[i] != EXPR_NONE && expr_node(sc->P, e.e[i])->height > MAX_HEIGHT)
            diag_error(at(&ps, 0), "expression is nested more than %d levels deep with the "
                       "defines it uses expanded", MAX_HEIGHT);
    return e;
}

/* Is src, the whole of it, a call vec(F, a, b, c)?  Read from its tokens
 * alone (lexical errors are reported), without parsing. */
static int
is_frame_vector(ParseScope *sc, const ParseSrc *src)
{
    Token t = lex(src, 0);
    if (!sc->K || t.kind != T_NAME || t.len != 3 || memcmp(src->text + t.off, "vec", 3))
        return 0;
    t = lex(src, t.off + t.len);
    if (t.kind != T_LPAREN)
        return 0;
    for (int depth = 0;; t = lex(src, t.off + t.len)) {
        if (t.kind == T_END)
            return 0;
        depth += (t.kind == T_LPAREN) - (t.kind == T_RPAREN);
        if (depth == 0)
            return lex(src, t.off + t.len).kind == T_END;
    }
}

int
parse_frame_vector(ParseScope *sc, const ParseSrc *src, int *frame, ExprId comps[3])
{
    if (!is_frame_vector(sc, src))
        return 0;
    Parser ps = {sc, src, {T_END, 0, 0, 0.0}, 0, 0};
    ps.tok = lex(src, 0);
    next(&ps); /* vec */
    size_t open = ps.tok.off;
    next(&ps); /* ( */
    enter(&ps, open);
    *frame = name_arg(&ps, 'F', "vec");
    size_t offs[3];
    for (int k = 0; k < 3; k++) {
        if (!accept(&ps, T_COMMA)) {
            char buf[80];
            diag_error(at(&ps, ps.tok.off), "expected ',' and more arguments, found %s: "
                       "vec(F, a, b, c), components in F", tok_text(&ps, &ps.tok, buf,
                                                                   sizeof buf));
        }
        offs[k] = ps.tok.off;
        comps[k] = need_scalar(&ps, expr(&ps), offs[k], "a component");
    }
    if (ps.tok.kind == T_COMMA)
        diag_error(at(&ps, ps.tok.off), "too many arguments: vec(F, a, b, c), components "
                   "in F");
    expect(&ps, T_RPAREN, "')'", open);
    for (int k = 0; k < 3; k++) {
        check_deps(&ps, comps[k], NULL, offs[k]);
        if (expr_node(sc->P, comps[k])->height > MAX_HEIGHT)
            diag_error(at(&ps, offs[k]), "expression is nested more than %d levels deep "
                       "with the defines it uses expanded", MAX_HEIGHT);
    }
    return 1;
}

ExprId
parse_expr(ParseScope *sc, const ParseSrc *src)
{
    Val v = parse_value(sc, src);
    if (v.vec)
        diag_error(src->where(src, 0), "%s is a scalar, and this is a vector: a component is "
                   "dot(v, F.x), a length norm(v)", sc->what);
    return v.e[0];
}

void
parse_vector(ParseScope *sc, const ParseSrc *src, ExprId out[3])
{
    Val v = parse_value(sc, src);
    if (!v.vec)
        diag_error(src->where(src, 0), "%s is a vector, and this is a scalar (write a vector "
                   "as [x, y, z], or as pos(P), vec(F, a, b, c), ...)", sc->what);
    for (int i = 0; i < 3; i++)
        out[i] = v.e[i];
}

void
parse_names(const ParseSrc *src,
            void (*fn)(void *ctx, const char *name, size_t len, size_t off), void *ctx)
{
    Token t = lex(src, 0), prev = {T_END, 0, 0, 0.0};
    while (t.kind != T_END) {
        Token n = lex(src, t.off + t.len);
        /* not a function's name, nor a frame's axis after F. */
        if (t.kind == T_NAME && n.kind != T_LPAREN && prev.kind != T_DOT)
            fn(ctx, src->text + t.off, t.len, t.off);
        prev = t;
        t = n;
    }
}
