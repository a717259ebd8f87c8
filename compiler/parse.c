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
    T_LPAREN, T_RPAREN, T_COMMA, T_PRIME, T_LBRACKET, T_RBRACKET,
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
    int op;    /* EXPR_ op, or BUILTIN_DOT, BUILTIN_DELTA */
    int arity;
} Builtin;

enum { BUILTIN_DOT = -1, BUILTIN_DELTA = -2 };

static const Builtin builtins[] = {
    {"sin", EXPR_SIN, 1},   {"cos", EXPR_COS, 1},     {"tan", EXPR_TAN, 1},
    {"asin", EXPR_ASIN, 1}, {"acos", EXPR_ACOS, 1},   {"atan", EXPR_ATAN, 1},
    {"atan2", EXPR_ATAN2, 2}, {"sinh", EXPR_SINH, 1}, {"cosh", EXPR_COSH, 1},
    {"tanh", EXPR_TANH, 1}, {"exp", EXPR_EXP, 1},     {"log", EXPR_LOG, 1},
    {"sqrt", EXPR_SQRT, 1}, {"abs", EXPR_ABS, 1},     {"pow", EXPR_POW, 2},
    {"dot", BUILTIN_DOT, 1}, {"delta", BUILTIN_DELTA, 1},
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

int
parse_is_reserved(const char *name)
{
    return !strcmp(name, "t") || !strcmp(name, "pi") || find_builtin(name) != NULL;
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
    char what[200];
    describe_leaf(sc, leaf, what, sizeof what);
    if (name && expr_op_arity[expr_node(sc->P, e)->op] != 0)
        diag_error(at(ps, off), "%s cannot depend on %s (through '%s')", sc->what, what, name);
    diag_error(at(ps, off), "%s cannot depend on %s", sc->what, what);
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

/* delta(e): the virtual displacement of e at fixed time,
 *     delta(e) = sum_i de/dq_i delta(q_i),
 * with the variations delta(q_i) as EXPR_SEED leaves (kind 0), or an
 * error at off saying why e has none. */
static ExprId
variation(Parser *ps, ExprId e, size_t off)
{
    ParseScope *sc = ps->sc;
    ExprPool *P = sc->P;
    unsigned deps = expr_deps(P, e);
    if (deps & DEP_S)
        diag_error(at(ps, off), "delta() of an expression that holds a variation: virtual "
                   "work is linear in the variations, so write each as delta(e) of a position e");
    unsigned moving = DEP_ANY_Q & ~DEP_ORDER(0);
    if (deps & moving) {
        char what[200];
        describe_leaf(sc, expr_find_leaf(P, e, moving), what, sizeof what);
        diag_error(at(ps, off), "delta() varies positions at a fixed time, and this "
                   "expression depends on %s: write the force's factor outside, as in "
                   "-c*r'*delta(r)", what);
    }
    ExprId r = EXPR_ZERO;
    for (int i = 0; i < sc->ncoord; i++)
        r = expr_add(P, r, expr_mul(P, diff_partial(sc->D, e, expr_var(P, i, 0)),
                                    expr_seed(P, i, 0)));
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

static ExprId expr(Parser *ps);
static ExprId unary(Parser *ps);

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
    const char *names[NBUILTINS];
    char list[256] = "";
    for (int i = 0; i < NBUILTINS; i++) {
        names[i] = builtins[i].name;
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                 names[i]);
    }
    const char *near = diag_nearest(name, names, NBUILTINS);
    if (near)
        diag_error(at(ps, off), "unknown function '%s'; did you mean '%s'?", name, near);
    diag_error(at(ps, off), "unknown function '%s' (the functions are %s)", name, list);
}

/* NAME "(" expr ("," expr)* ")" with the name already read. */
static ExprId
call(Parser *ps, const char *name, size_t name_off)
{
    const Builtin *b = find_builtin(name);
    if (!b)
        unknown_function(ps, name, name_off);
    size_t open = ps->tok.off;
    next(ps); /* ( */
    enter(ps, open);
    ExprId args[2];
    int n = 0;
    if (ps->tok.kind != T_RPAREN) {
        do {
            size_t arg_off = ps->tok.off;
            ExprId a = expr(ps);
            if (n == b->arity)
                diag_error(at(ps, arg_off), "too many arguments: %s takes %d", name, b->arity);
            args[n++] = a;
        } while (accept(ps, T_COMMA));
    }
    expect(ps, T_RPAREN, "')'", open);
    ps->depth--;
    if (n != b->arity)
        diag_error(at(ps, name_off), "%s takes %d argument%s, not %d", name, b->arity,
                   b->arity == 1 ? "" : "s", n);
    ExprPool *P = ps->sc->P;
    if (b->op == BUILTIN_DOT)
        return time_derivative(ps, args[0], name_off);
    if (b->op == BUILTIN_DELTA)
        return variation(ps, args[0], name_off);
    if (b->arity == 1)
        return finite(ps, expr_unary(P, b->op, args[0]), name, args[0], EXPR_NONE, name_off);
    return finite(ps, expr_binary(P, b->op, args[0], args[1]), name, args[0], args[1], name_off);
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

static ExprId
name_or_call(Parser *ps)
{
    char name[MAX_NAME + 1];
    size_t off = ps->tok.off, len = ps->tok.len;
    memcpy(name, ps->src->text + off, len);
    name[len] = '\0';
    next(ps);
    if (ps->tok.kind == T_LPAREN)
        return call(ps, name, off);
    if (ps->tok.kind == T_LBRACKET && !strcmp(name, "lambda"))
        return multiplier(ps, off);
    if (find_builtin(name))
        diag_error(at(ps, off), "'%s' is a function: write %s(...)", name, name);
    ParseScope *sc = ps->sc;
    ExprId e;
    if (!strcmp(name, "t"))
        e = expr_time(sc->P);
    else if (!strcmp(name, "pi"))
        e = expr_const(sc->P, 3.14159265358979323846);
    else
        e = sc->lookup(sc, name, at(ps, off));
    check_deps(ps, e, name, off);
    return e;
}

/* primary = NUMBER | NAME | call | "(" expr ")" */
static ExprId
primary(Parser *ps)
{
    Token t = ps->tok;
    char buf[80];
    switch (t.kind) {
    case T_NUM:
        next(ps);
        return expr_const(ps->sc->P, t.num);
    case T_NAME:
        return name_or_call(ps);
    case T_LPAREN: {
        next(ps);
        enter(ps, t.off);
        ExprId e = expr(ps);
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
static ExprId
postfix(Parser *ps)
{
    ExprId e = primary(ps);
    while (ps->tok.kind == T_PRIME) {
        size_t prime = ps->tok.off;
        next(ps);
        e = time_derivative(ps, e, prime);
    }
    return e;
}

/* power = postfix ("^" unary)? */
static ExprId
power(Parser *ps)
{
    ExprId base = postfix(ps);
    if (ps->tok.kind != T_CARET)
        return base;
    size_t caret = ps->tok.off;
    next(ps);
    enter(ps, caret);
    ExprId ex = unary(ps);
    ps->depth--;
    return finite(ps, expr_pow(ps->sc->P, base, ex), "^", base, ex, caret);
}

/* unary = ("-" | "+") unary | power */
static ExprId
unary(Parser *ps)
{
    if (ps->tok.kind != T_MINUS && ps->tok.kind != T_PLUS)
        return power(ps);
    int neg = ps->tok.kind == T_MINUS;
    size_t sign = ps->tok.off;
    next(ps);
    enter(ps, sign);
    ExprId e = unary(ps);
    ps->depth--;
    return neg ? expr_neg(ps->sc->P, e) : e;
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
static ExprId
term(Parser *ps)
{
    ExprPool *P = ps->sc->P;
    ExprId e = unary(ps);
    for (;;) {
        if (ps->tok.kind == T_STAR || ps->tok.kind == T_SLASH)
            count_operator(ps);
        size_t op = ps->tok.off;
        if (accept(ps, T_STAR)) {
            ExprId f = unary(ps);
            e = finite(ps, expr_mul(P, e, f), "*", e, f, op);
        } else if (accept(ps, T_SLASH)) {
            ExprId d = unary(ps);
            if (d == EXPR_ZERO)
                diag_error(at(ps, op), "division by zero");
            e = finite(ps, expr_div(P, e, d), "/", e, d, op);
        } else {
            return e;
        }
    }
}

/* expr = term (("+" | "-") term)* */
static ExprId
expr(Parser *ps)
{
    ExprPool *P = ps->sc->P;
    ExprId e = term(ps);
    for (;;) {
        if (ps->tok.kind == T_PLUS || ps->tok.kind == T_MINUS)
            count_operator(ps);
        size_t op = ps->tok.off;
        ExprId r;
        if (accept(ps, T_PLUS))
            r = term(ps), e = finite(ps, expr_add(P, e, r), "+", e, r, op);
        else if (accept(ps, T_MINUS))
            r = term(ps), e = finite(ps, expr_sub(P, e, r), "-", e, r, op);
        else
            return e;
    }
}

ExprId
parse_expr(ParseScope *sc, const ParseSrc *src)
{
    Parser ps = {sc, src, {T_END, 0, 0, 0.0}, 0, 0};
    ps.tok = lex(src, 0);
    if (ps.tok.kind == T_END)
        diag_error(at(&ps, 0), "empty expression");
    ExprId e = expr(&ps);
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
    if (e != EXPR_NONE && expr_node(sc->P, e)->height > MAX_HEIGHT)
        diag_error(at(&ps, 0), "expression is nested more than %d levels deep with the "
                   "defines it uses expanded", MAX_HEIGHT);
    return e;
}

void
parse_names(const ParseSrc *src,
            void (*fn)(void *ctx, const char *name, size_t len, size_t off), void *ctx)
{
    Token t = lex(src, 0);
    while (t.kind != T_END) {
        Token n = lex(src, t.off + t.len);
        if (t.kind == T_NAME && n.kind != T_LPAREN)
            fn(ctx, src->text + t.off, t.len, t.off);
        t = n;
    }
}
