/*
 * monomial: products as a constant times powers of bases (monomial.h).
 *
 * A node's monomial is c * b_1^e_1 * ... * b_n^e_n: c a node constant in
 * t, each b_i a base (a sum, a leaf, a function's value: anything that is
 * not a product, a quotient, a negation or a power) written again itself,
 * each e_i a nonzero number.  Products add exponents, quotients subtract
 * them, an integer power multiplies them.  A real power (a root) only
 * multiplies the exponent of a lone base that is not an even power, since
 * (b^2)^(1/2) is |b|, not b; otherwise the root is a base of its own.  A
 * monomial of more than MONO_MAX bases is a base too.  Exponents that
 * cancel drop their base (x / x is 1, as expr_div has it).
 *
 * The monomial is then printed as (numerator) / (denominator) with the
 * integer powers by expr_powi and the others by expr_pow, which keeps a
 * real exponent (eomc_tay_powc's recurrence) or writes a half as a root.
 */
#include "monomial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/arena.h"

/* Bases a monomial keeps before it is a base itself: the products of
 * mechanics are short (a mass, lengths, a sine or two, a distance's
 * power), and a longer one gains nothing. */
enum { MONO_MAX = 8 };

typedef struct Factor {
    ExprId base;
    double e;
} Factor;

typedef struct Mono {
    int known; /* computed */
    int n;
    ExprId c;
    Factor f[MONO_MAX];
} Mono;

struct Monomials {
    ExprPool *P;
    unsigned varying;
    size_t cap;    /* entries of done and mono */
    ExprId *done;  /* per node: its rewrite, EXPR_NONE until made */
    unsigned char *real;   /* per node: 1 + mono_real_powers', 0 until counted */
    Mono *mono;    /* per node: its monomial */
};

Monomials *
mono_new(ExprPool *P, unsigned varying)
{
    Monomials *mo = xmalloc(sizeof *mo);
    *mo = (Monomials){.P = P, .varying = varying};
    return mo;
}

void
mono_free(Monomials *mo)
{
    if (!mo)
        return;
    free(mo->done);
    free(mo->real);
    free(mo->mono);
    free(mo);
}

/* Room for node e in the memos (the pool grows as nodes are written). */
static void
room(Monomials *mo, ExprId e)
{
    if ((size_t)e < mo->cap)
        return;
    size_t cap = mo->cap ? mo->cap : 1024;
    while (cap <= (size_t)e)
        cap *= 2;
    mo->done = xrealloc(mo->done, cap * sizeof *mo->done);
    mo->real = xrealloc(mo->real, cap);
    mo->mono = xrealloc(mo->mono, cap * sizeof *mo->mono);
    for (size_t i = mo->cap; i < cap; i++) {
        mo->done[i] = EXPR_NONE;
        mo->real[i] = 0;
        mo->mono[i].known = 0;
    }
    mo->cap = cap;
}

static int
constant(const Monomials *mo, ExprId e)
{
    return !(expr_node(mo->P, e)->deps & mo->varying);
}

static int
is_even(double e)
{
    return e == rint(e) && fmod(e, 2) == 0;
}

/* b^e times m, in place; 0 when it would pass MONO_MAX bases. */
static int
times_factor(Mono *m, ExprId base, double e)
{
    for (int i = 0; i < m->n; i++) {
        if (m->f[i].base != base)
            continue;
        m->f[i].e += e;
        if (m->f[i].e == 0) { /* cancelled: the base goes */
            m->f[i] = m->f[--m->n];
        }
        return 1;
    }
    if (m->n == MONO_MAX)
        return 0;
    m->f[m->n++] = (Factor){base, e};
    return 1;
}

static Mono monomial(Monomials *mo, ExprId e);

/* e's operator on its operands written again (e itself where they are
 * the same). */
static ExprId
rebuilt(Monomials *mo, ExprId e)
{
    ExprPool *P = mo->P;
    const ExprNode nd = *expr_node(P, e); /* (a copy: the pool grows below) */
    int ar = expr_op_arity[nd.op];
    if (ar == 0)
        return e;
    ExprId a = mono_rewrite(mo, nd.a);
    if (nd.op == EXPR_POWI)
        return a == nd.a ? e : expr_powi(P, a, (int32_t)nd.b);
    if (ar == 1)
        return a == nd.a ? e : expr_unary(P, nd.op, a);
    ExprId b = mono_rewrite(mo, nd.b);
    if (a == nd.a && b == nd.b)
        return e;
    return nd.op == EXPR_SELECT ? expr_select(P, (int)nd.value, a, b)
                                : expr_binary(P, nd.op, a, b);
}

/* e as a base of its own: c = 1, e rebuilt, to the power 1. */
static Mono
whole(Monomials *mo, ExprId e)
{
    Mono m = {.known = 1, .n = 1, .c = EXPR_ONE};
    m.f[0] = (Factor){rebuilt(mo, e), 1};
    return m;
}

/* x * y^s (s = 1 or -1); 0 when it has too many bases. */
static int
product(Monomials *mo, Mono *x, const Mono *y, int s)
{
    for (int i = 0; i < y->n; i++)
        if (!times_factor(x, y->f[i].base, s * y->f[i].e))
            return 0;
    x->c = s > 0 ? expr_mul(mo->P, x->c, y->c) : expr_div(mo->P, x->c, y->c);
    return 1;
}

/* m^a: 0 where it is not a monomial (a root of a product or of an even
 * power). */
static int
power(Monomials *mo, Mono *m, double a)
{
    int integer = a == rint(a) && fabs(a) <= INT32_MAX;
    if (!integer && (m->c != EXPR_ONE || m->n != 1 || is_even(m->f[0].e)))
        return 0;
    for (int i = 0; i < m->n; i++)
        m->f[i].e *= a;
    if (integer)
        m->c = expr_powi(mo->P, m->c, (int)a);
    return 1;
}

static Mono
compute(Monomials *mo, ExprId e)
{
    const ExprNode node = *expr_node(mo->P, e), *nd = &node; /* (the pool grows below) */
    if (constant(mo, e))
        return (Mono){.known = 1, .n = 0, .c = e};
    Mono m, y;
    double a;
    switch (nd->op) {
    case EXPR_MUL:
    case EXPR_DIV:
        m = monomial(mo, nd->a);
        y = monomial(mo, nd->b);
        if (product(mo, &m, &y, nd->op == EXPR_MUL ? 1 : -1))
            return m;
        break;
    case EXPR_NEG:
        m = monomial(mo, nd->a);
        m.c = expr_neg(mo->P, m.c);
        return m;
    case EXPR_POWI:
    case EXPR_SQRT:
    case EXPR_POW:
        a = nd->op == EXPR_POWI ? (double)(int32_t)nd->b : nd->op == EXPR_SQRT ? 0.5 : NAN;
        if (nd->op == EXPR_POW && expr_node(mo->P, nd->b)->op == EXPR_CONST)
            a = expr_node(mo->P, nd->b)->value;
        if (isnan(a))
            break;
        m = monomial(mo, nd->a);
        if (power(mo, &m, a))
            return m;
        break;
    default:
        break;
    }
    return whole(mo, e);
}

static Mono
monomial(Monomials *mo, ExprId e)
{
    room(mo, e);
    if (!mo->mono[e].known) {
        Mono m = compute(mo, e);
        room(mo, e); /* (compute may have grown the memos) */
        mo->mono[e] = m;
    }
    return mo->mono[e];
}

static int
by_base(const void *x, const void *y)
{
    ExprId a = ((const Factor *)x)->base, b = ((const Factor *)y)->base;
    return (a > b) - (a < b);
}

/* The monomial as a node: c * (numerator / denominator), the bases in id
 * order, so that the same monomial is the same node. */
static ExprId
print(Monomials *mo, Mono m)
{
    ExprPool *P = mo->P;
    qsort(m.f, (size_t)m.n, sizeof *m.f, by_base);
    ExprId num = EXPR_ONE, den = EXPR_ONE;
    for (int i = 0; i < m.n; i++) {
        double e = m.f[i].e;
        if (e == rint(e) && fabs(e) <= INT32_MAX) {
            ExprId t = expr_powi(P, m.f[i].base, (int)fabs(e));
            if (e > 0)
                num = expr_mul(P, num, t);
            else
                den = expr_mul(P, den, t);
        } else {
            num = expr_mul(P, num, expr_pow(P, m.f[i].base, expr_const(P, e)));
        }
    }
    return expr_mul(P, m.c, expr_div(P, num, den));
}

/* A product, a quotient, a negation or a power: what the monomial is
 * made of. */
static int
product_like(const ExprPool *P, const ExprNode *nd)
{
    return nd->op == EXPR_MUL || nd->op == EXPR_DIV || nd->op == EXPR_NEG ||
           nd->op == EXPR_POWI || nd->op == EXPR_SQRT ||
           (nd->op == EXPR_POW && expr_node(P, nd->b)->op == EXPR_CONST);
}

ExprId
mono_rewrite(Monomials *mo, ExprId e)
{
    room(mo, e);
    if (mo->done[e] != EXPR_NONE)
        return mo->done[e];
    ExprId r = e;
    if (constant(mo, e))
        r = e;
    else if (product_like(mo->P, expr_node(mo->P, e)))
        r = print(mo, monomial(mo, e));
    else
        r = rebuilt(mo, e);
    room(mo, e);
    mo->done[e] = r;
    return r;
}

int
mono_real_powers(Monomials *mo, ExprId e)
{
    room(mo, e);
    if (mo->real[e]) /* (1 + the count) */
        return mo->real[e] - 1;
    const ExprNode nd = *expr_node(mo->P, e);
    int ar = expr_op_arity[nd.op], n = 0;
    if (nd.op == EXPR_POW && expr_node(mo->P, nd.b)->op == EXPR_CONST &&
        expr_node(mo->P, nd.b)->value != rint(expr_node(mo->P, nd.b)->value))
        n = 1;
    else if (nd.op == EXPR_SQRT)
        n = 1;
    if (ar > 0)
        n += mono_real_powers(mo, nd.a);
    if (ar > 1)
        n += mono_real_powers(mo, nd.b);
    n = n > 254 ? 254 : n;
    room(mo, e);
    mo->real[e] = (unsigned char)(n + 1);
    return n;
}
