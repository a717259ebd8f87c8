/*
 * expr: hash-consed expression DAG with simplifying constructors.
 *
 * The pool is an array of nodes indexed by id plus an open-addressing hash
 * table of ids keyed on (op, a, b, value bits).  Interning a node has the
 * shape of Lua's internshrstr: hash, probe, return the existing id or
 * append.  Commutative operands are put in canonical order (constants
 * first, then by id) before interning, so a+b and b+a are one node.
 *
 * One file past the project's ~800 lines because it is one concept: the
 * constructors' simplifications (like terms, powers, constant folding,
 * sin/cos of a sum) decide which nodes are equal, and so what interning
 * finds; apart, a change to one could silently undo another's sharing.
 */
#include "expr.h"
#include "base/arena.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct ExprPool {
    ExprNode *node;
    uint8_t *trig; /* per node: its TRIG_ bits (derived, see trig_bits) */
    size_t n, cap;
    uint32_t *table; /* ids + 1; 0 = empty slot */
    size_t tcap;
    ExprId *rate;    /* per coordinate: its rate where it is not a speed (expr_set_rate) */
    int nrate;
    ExprId *sw;      /* per switch: its function s_k (expr_max) */
    char **swname;   /* per switch: its name (expr_name_switch), or NULL */
    int nsw, capsw;
};

const char *const expr_op_spelling[EXPR_NOPS] = {
#define OP(name, arity, spell, kind) spell,
#include "ops.def"
#undef OP
};
const char *const expr_op_name[EXPR_NOPS] = {
#define OP(name, arity, spell, kind) #name,
#include "ops.def"
#undef OP
};
const int expr_op_arity[EXPR_NOPS] = {
#define OP(name, arity, spell, kind) arity,
#include "ops.def"
#undef OP
};
const int expr_op_kind[EXPR_NOPS] = {
#define OP(name, arity, spell, kind) OPK_##kind,
#include "ops.def"
#undef OP
};

static uint64_t
hash_node(const ExprNode *n)
{
    uint64_t bits;
    memcpy(&bits, &n->value, sizeof bits);
    uint64_t h = 1469598103934665603ull; /* FNV-1a over the fields */
    uint64_t words[4] = {n->op, n->a, n->b, bits};
    for (int i = 0; i < 4; i++) {
        h ^= words[i];
        h *= 1099511628211ull;
        h ^= h >> 29;
    }
    /* MurmurHash3's finalizer: the table takes the low bits, and without
     * it nodes made in sequence (ids a, a + 1, ...) fall in runs that
     * linear probing walks */
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

static int
same_node(const ExprNode *x, const ExprNode *y)
{
    return x->op == y->op && x->a == y->a && x->b == y->b &&
           memcmp(&x->value, &y->value, sizeof x->value) == 0;
}

static void
rehash(ExprPool *P)
{
    size_t cap = P->tcap ? P->tcap * 2 : 1024;
    uint32_t *t = xmalloc(cap * sizeof *t);
    memset(t, 0, cap * sizeof *t);
    for (size_t id = 0; id < P->n; id++) {
        size_t i = hash_node(&P->node[id]) & (cap - 1);
        while (t[i])
            i = (i + 1) & (cap - 1);
        t[i] = (uint32_t)id + 1;
    }
    free(P->table);
    P->table = t;
    P->tcap = cap;
}

/* What the Pythagorean identity (pythagoras, below) looks for, as bits
 * each node derives from its operands when it is built, so that a sum
 * with nothing to find costs one test.  Seen as a monomial (a product of
 * powers, through MUL, POWI and NEG): */
enum {
    TRIG_FACTOR = 1, /* it has a factor sin(x) or cos(x) */
    TRIG_SQUARE = 2, /* it has a factor sin(x)^k or cos(x)^k, k >= 2 */
    TRIG_SUM = 4,    /* a sum (ADD, SUB, NEG) with such a term */
};

static uint8_t
trig_bits(const ExprPool *P, const ExprNode *nd)
{
    switch (nd->op) {
    case EXPR_SIN:
    case EXPR_COS:
        return TRIG_FACTOR;
    case EXPR_MUL:
        return (P->trig[nd->a] | P->trig[nd->b]) & (TRIG_FACTOR | TRIG_SQUARE);
    case EXPR_NEG:
        return P->trig[nd->a];
    case EXPR_POWI: {
        int n = (int32_t)nd->b;
        uint8_t t = P->trig[nd->a] & (TRIG_FACTOR | TRIG_SQUARE);
        return n < 1 ? 0 : n >= 2 && (t & TRIG_FACTOR) ? t | TRIG_SQUARE : t;
    }
    case EXPR_ADD:
    case EXPR_SUB:
        return (P->trig[nd->a] | P->trig[nd->b]) & (TRIG_SQUARE | TRIG_SUM) ? TRIG_SUM : 0;
    }
    return 0;
}

static ExprId
intern(ExprPool *P, ExprNode nd)
{
    if (P->n * 2 >= P->tcap)
        rehash(P);
    size_t i = hash_node(&nd) & (P->tcap - 1);
    while (P->table[i]) {
        ExprId id = P->table[i] - 1;
        if (same_node(&P->node[id], &nd))
            return id;
        i = (i + 1) & (P->tcap - 1);
    }
    if (P->n == P->cap) {
        P->cap = P->cap ? P->cap * 2 : 1024;
        P->node = xrealloc(P->node, P->cap * sizeof *P->node);
        P->trig = xrealloc(P->trig, P->cap * sizeof *P->trig);
    }
    ExprId id = (ExprId)P->n++;
    P->node[id] = nd;
    P->trig[id] = trig_bits(P, &nd);
    P->table[i] = id + 1;
    return id;
}

ExprPool *
expr_pool_new(void)
{
    ExprPool *P = xmalloc(sizeof *P);
    memset(P, 0, sizeof *P);
    expr_const(P, 0.0); /* EXPR_ZERO */
    expr_const(P, 1.0); /* EXPR_ONE */
    return P;
}

void
expr_pool_free(ExprPool *P)
{
    if (!P)
        return;
    free(P->node);
    free(P->trig);
    free(P->table);
    free(P->rate);
    expr_clear_switches(P);
    free(P->sw);
    free(P->swname);
    free(P);
}

void
expr_set_rate(ExprPool *P, int coord, ExprId rate)
{
    if (coord >= P->nrate) {
        int cap = 2 * coord + 8;
        P->rate = xrealloc(P->rate, (size_t)cap * sizeof *P->rate);
        for (int i = P->nrate; i < cap; i++)
            P->rate[i] = EXPR_NONE;
        P->nrate = cap;
    }
    P->rate[coord] = rate;
}

void
expr_clear_rates(ExprPool *P)
{
    for (int i = 0; i < P->nrate; i++)
        P->rate[i] = EXPR_NONE;
}

void
expr_clear_switches(ExprPool *P)
{
    for (int k = 0; k < P->nsw; k++)
        free(P->swname[k]);
    P->nsw = 0;
}

ExprId
expr_rate(const ExprPool *P, int coord)
{
    return coord < P->nrate ? P->rate[coord] : EXPR_NONE;
}

size_t expr_pool_size(const ExprPool *P) { return P->n; }

const ExprNode *expr_node(const ExprPool *P, ExprId e) { return &P->node[e]; }

static ExprId
mk(ExprPool *P, int op, ExprId a, ExprId b)
{
    ExprNode nd = {.op = (uint8_t)op, .a = a, .b = b, .value = 0.0};
    int ar = expr_op_arity[op];
    switch (op) {
    case EXPR_VAR: nd.deps = (uint16_t)DEP_ORDER(b); break;
    case EXPR_MULT: nd.deps = DEP_L; break;
    case EXPR_PARAM: nd.deps = DEP_P; break;
    case EXPR_INPUT: nd.deps = DEP_U; break;
    case EXPR_TIME: nd.deps = DEP_T; break;
    case EXPR_SEED: nd.deps = DEP_S; break;
    default:
        nd.deps = P->node[a].deps | (ar == 2 ? P->node[b].deps : 0);
        nd.height = P->node[a].height;
        if (ar == 2 && P->node[b].height > nd.height)
            nd.height = P->node[b].height;
        nd.height++;
    }
    nd.coeff = (nd.deps & ~DEP_P) == 0;
    return intern(P, nd);
}

ExprId
expr_const(ExprPool *P, double v)
{
    if (v == 0.0)
        v = 0.0; /* one zero: -0.0 folds to +0.0 */
    ExprNode nd = {.op = EXPR_CONST, .coeff = 1, .a = 0, .b = 0, .value = v};
    return intern(P, nd);
}

ExprId expr_var(ExprPool *P, int coord, int order)
{
    return mk(P, EXPR_VAR, (uint32_t)coord, (uint32_t)order);
}
ExprId expr_param(ExprPool *P, int i) { return mk(P, EXPR_PARAM, (uint32_t)i, 0); }
ExprId expr_input(ExprPool *P, int i) { return mk(P, EXPR_INPUT, (uint32_t)i, 0); }
ExprId expr_mult(ExprPool *P, int c) { return mk(P, EXPR_MULT, (uint32_t)c, 0); }
ExprId expr_time(ExprPool *P) { return mk(P, EXPR_TIME, 0, 0); }
ExprId
expr_seed(ExprPool *P, int coord, int kind)
{
    return mk(P, EXPR_SEED, (uint32_t)coord, (uint32_t)kind);
}

int
expr_is_const(const ExprPool *P, ExprId e, double *value)
{
    if (P->node[e].op != EXPR_CONST)
        return 0;
    if (value)
        *value = P->node[e].value;
    return 1;
}

static int
is_value(const ExprPool *P, ExprId e, double v)
{
    double c;
    return expr_is_const(P, e, &c) && c == v;
}

static int op_of(const ExprPool *P, ExprId e) { return P->node[e].op; }

int expr_is_coeff(const ExprPool *P, ExprId e) { return P->node[e].coeff; }

/* e = c*x with c a coefficient: *c and *x, else 0. */
static int
scaled(const ExprPool *P, ExprId e, ExprId *c, ExprId *x)
{
    const ExprNode *n = &P->node[e];
    if (n->op != EXPR_MUL || !P->node[n->a].coeff || P->node[n->b].coeff)
        return 0;
    *c = n->a;
    *x = n->b;
    return 1;
}

/* e as c*x with c a coefficient (1 when e is not scaled) and x not: the
 * terms of like-term collection.  0 when e is itself a coefficient. */
static int
term(const ExprPool *P, ExprId e, ExprId *c, ExprId *x)
{
    if (scaled(P, e, c, x))
        return 1;
    if (P->node[e].coeff)
        return 0;
    *c = EXPR_ONE;
    *x = e;
    return 1;
}

/* e as k*r with k a number: a constant is k*1, a product whose first
 * factor is a constant is split, anything else is 1*e. */
static void
numeric(const ExprPool *P, ExprId e, double *k, ExprId *r)
{
    const ExprNode *n = &P->node[e];
    if (n->op == EXPR_CONST) {
        *k = n->value, *r = EXPR_ONE;
    } else if (n->op == EXPR_MUL && P->node[n->a].op == EXPR_CONST) {
        *k = P->node[n->a].value, *r = n->b;
    } else {
        *k = 1.0, *r = e;
    }
}

/* Fold to a constant only when the result is finite: 1/0 or log(-1) stay
 * symbolic so that the checker upstream can report them. */
static int
foldable(double r)
{
    return isfinite(r);
}

/* Canonical order of commutative operands: constants first, then other
 * coefficients, then by id. */
static int
rank(const ExprPool *P, ExprId e)
{
    return op_of(P, e) == EXPR_CONST ? 0 : P->node[e].coeff ? 1 : 2;
}

static void
order2(const ExprPool *P, ExprId *a, ExprId *b)
{
    int ra = rank(P, *a), rb = rank(P, *b);
    if (rb < ra || (ra == rb && *b < *a)) {
        ExprId t = *a;
        *a = *b;
        *b = t;
    }
}

ExprId
expr_neg(ExprPool *P, ExprId a)
{
    const ExprNode nv = P->node[a], *n = &nv;
    switch (n->op) {
    case EXPR_CONST:
        return expr_const(P, -n->value);
    case EXPR_NEG:
        return n->a;
    case EXPR_SUB:
        return expr_sub(P, n->b, n->a);
    case EXPR_MUL:
        if (op_of(P, n->a) == EXPR_CONST) /* -(c*x) = (-c)*x */
            return expr_mul(P, expr_const(P, -P->node[n->a].value), n->b);
        break;
    }
    return mk(P, EXPR_NEG, a, 0);
}

/* ---- sin(x)^2 + cos(x)^2 = 1 ----
 *
 * Mechanics meets the identity in the square of a velocity: a point at
 * l (sin q, -cos q) has |r'|^2 = (l cos q q')^2 + (l sin q q')^2, which is
 * l^2 q'^2.  Folding it by structure keeps t out of a kinetic energy where
 * it cancels (the invariant then needs no numerical test), and spares the
 * code the sum.  Two terms of a sum, seen as monomials k * prod b_i^n_i
 * (k a number, through MUL, POWI and NEG, so (l cos q q')^2 is
 * l^2 cos(q)^2 q'^2), are partners when they have the same k and differ
 * only in sin(x)^(p+2) cos(x)^q against sin(x)^p cos(x)^(q+2), for one
 * argument node x: their sum is k prod b_i^min(n_i, m_i).  The trig bits
 * keep every other sum to one test; a sum is searched only as far as
 * PYTH_TERMS terms (the nearest to its root first), a monomial only as far
 * as PYTH_FACTORS factors. */
enum { PYTH_TERMS = 32, PYTH_FACTORS = 32 };

typedef struct PythFactor {
    ExprId base;
    int n;
} PythFactor;

typedef struct PythMono {
    double k;
    int nf;
    PythFactor f[PYTH_FACTORS];
} PythMono;

/* A term of a sum, with the sign it is added with. */
typedef struct PythTerm {
    ExprId e;
    int sign;
} PythTerm;

/* Append e^n (e within a monomial) to m: 0 when there are too many
 * factors.  A number to the first power goes to k; to another power it
 * stays a factor, so that k is exact. */
static int
pyth_gather(const ExprPool *P, ExprId e, int n, PythMono *m)
{
    const ExprNode *nd = &P->node[e];
    switch (nd->op) {
    case EXPR_NEG:
        if (n % 2)
            m->k = -m->k;
        return pyth_gather(P, nd->a, n, m);
    case EXPR_MUL:
        return pyth_gather(P, nd->a, n, m) && pyth_gather(P, nd->b, n, m);
    case EXPR_POWI: {
        long k = (long)n * (int32_t)nd->b;
        return k >= -PYTH_FACTORS && k <= PYTH_FACTORS && pyth_gather(P, nd->a, (int)k, m);
    }
    case EXPR_CONST:
        if (n == 1) {
            m->k *= nd->value;
            return 1;
        }
        break;
    }
    if (m->nf == PYTH_FACTORS)
        return 0;
    m->f[m->nf++] = (PythFactor){e, n};
    return 1;
}

/* e as a monomial, its factors sorted by base and merged; 0 if too long. */
static int
pyth_mono(const ExprPool *P, ExprId e, int sign, PythMono *m)
{
    m->k = sign;
    m->nf = 0;
    if (!pyth_gather(P, e, 1, m))
        return 0;
    for (int i = 1; i < m->nf; i++) { /* insertion sort: monomials are short */
        PythFactor x = m->f[i];
        int j = i;
        for (; j > 0 && m->f[j - 1].base > x.base; j--)
            m->f[j] = m->f[j - 1];
        m->f[j] = x;
    }
    int k = 0;
    for (int i = 0; i < m->nf; i++) {
        if (k && m->f[k - 1].base == m->f[i].base)
            m->f[k - 1].n += m->f[i].n;
        else
            m->f[k++] = m->f[i];
        if (m->f[k - 1].n == 0)
            k--;
    }
    m->nf = k;
    return 1;
}

/* Are x and y partners (see above)?  Their factors are compared in order;
 * exactly two bases may differ, sin(z) and cos(z) of one z, by 2 each in
 * opposite directions. */
static int
pyth_partners(const ExprPool *P, const PythMono *x, const PythMono *y)
{
    if (x->k != y->k)
        return 0;
    ExprId base[2];
    int diff[2], nd = 0, i = 0, j = 0;
    while (i < x->nf || j < y->nf) {
        ExprId bx = i < x->nf ? x->f[i].base : EXPR_NONE;
        ExprId by = j < y->nf ? y->f[j].base : EXPR_NONE;
        ExprId b = bx < by ? bx : by;
        int nx = bx == b ? x->f[i++].n : 0, ny = by == b ? y->f[j++].n : 0;
        if (nx == ny)
            continue;
        if (nd == 2)
            return 0;
        base[nd] = b;
        diff[nd++] = nx - ny;
    }
    if (nd != 2 || diff[0] + diff[1] != 0 || (diff[0] != 2 && diff[0] != -2))
        return 0;
    const ExprNode *u = &P->node[base[0]], *v = &P->node[base[1]];
    return u->a == v->a && ((u->op == EXPR_SIN && v->op == EXPR_COS) ||
                            (u->op == EXPR_COS && v->op == EXPR_SIN));
}

/* The terms of e (added with `sign`) appended to t[*n]: sums that hold a
 * square (TRIG_SUM) are opened breadth first while there is room; the
 * rest are terms as they stand. */
static void
pyth_terms(const ExprPool *P, ExprId e, int sign, PythTerm *t, int *n, int cap)
{
    int first = *n;
    t[(*n)++] = (PythTerm){e, sign};
    for (int open = 1; open;) {
        open = 0;
        for (int i = first; i < *n; i++) {
            const ExprNode *nd = &P->node[t[i].e];
            if (!(P->trig[t[i].e] & TRIG_SUM))
                continue;
            if (nd->op == EXPR_NEG) {
                t[i] = (PythTerm){nd->a, -t[i].sign};
                open = 1;
            } else if ((nd->op == EXPR_ADD || nd->op == EXPR_SUB) && *n < cap) {
                memmove(&t[i + 2], &t[i + 1], (size_t)(*n - i - 1) * sizeof *t);
                (*n)++;
                t[i + 1] = (PythTerm){nd->b, nd->op == EXPR_SUB ? -t[i].sign : t[i].sign};
                t[i] = (PythTerm){nd->a, t[i].sign};
                open = 1;
                i++;
            }
        }
    }
}

/* a + sign*b with one pair of partners (one term from each side) added
 * into one term, or EXPR_NONE when there is none.  The other terms are
 * added again in order, which finds any further pairs. */
static ExprId
pyth_search(ExprPool *P, ExprId a, ExprId b, int sign)
{
    PythTerm t[2 * PYTH_TERMS];
    int n = 0;
    pyth_terms(P, a, 1, t, &n, PYTH_TERMS);
    int na = n;
    pyth_terms(P, b, sign, t, &n, na + PYTH_TERMS);
    PythMono x, y;
    int hit = -1, with = -1;
    for (int j = na; j < n && hit < 0; j++) {
        if (!(P->trig[t[j].e] & TRIG_SQUARE) || !pyth_mono(P, t[j].e, t[j].sign, &y))
            continue;
        for (int i = 0; i < na && hit < 0; i++)
            if ((P->trig[t[i].e] & TRIG_SQUARE) && pyth_mono(P, t[i].e, t[i].sign, &x) &&
                pyth_partners(P, &x, &y))
                hit = i, with = j;
    }
    if (hit < 0)
        return EXPR_NONE;
    ExprId sum = EXPR_ZERO, term = EXPR_ONE;
    for (int i = 0, j = 0; i < x.nf; i++) { /* prod b^min(n, m) */
        while (j < y.nf && y.f[j].base < x.f[i].base)
            j++;
        if (j < y.nf && y.f[j].base == x.f[i].base) {
            int m = x.f[i].n < y.f[j].n ? x.f[i].n : y.f[j].n;
            term = expr_mul(P, term, expr_powi(P, x.f[i].base, m));
        }
    }
    term = expr_mul(P, expr_const(P, x.k), term);
    for (int i = 0; i < n; i++)
        if (i != hit && i != with)
            sum = t[i].sign > 0 ? expr_add(P, sum, t[i].e) : expr_sub(P, sum, t[i].e);
    return expr_add(P, sum, term);
}

/* The trig bits first: most sums have no square on one side at least. */
static inline ExprId
pythagoras(ExprPool *P, ExprId a, ExprId b, int sign)
{
    const uint8_t any = TRIG_SQUARE | TRIG_SUM;
    if (!(P->trig[a] & any) || !(P->trig[b] & any))
        return EXPR_NONE;
    return pyth_search(P, a, b, sign);
}

/* Cancellation by structure.  A term of one operand that the other
 * takes away again, (x - y) - x + y or (a + b*c) - b*c, or the same
 * product grouped differently, (x y) s - x (y s), leaves work that is
 * exactly 0 but rounds to noise.  The signed terms of both operands
 * are gathered through +, - and unary -, a few of them (sums are not
 * flattened in general: that would rebuild shared partial sums), and when
 * a term of one is the negated term of the other both go and the sum is
 * rebuilt from what is left, in its order.  When nothing cancels the sum
 * is left as it was built. */
enum { CANCEL_TERMS_MAX = 8 };

typedef struct SignedTerm {
    ExprId x;
    int neg;
} SignedTerm;

/* Append the signed terms of e (negated if neg) to t[*n]; 0 when there
 * are more than CANCEL_TERMS_MAX. */
static int
signed_terms(const ExprPool *P, ExprId e, int neg, SignedTerm *t, int *n)
{
    const ExprNode *nd = &P->node[e];
    switch (nd->op) {
    case EXPR_ADD:
        return signed_terms(P, nd->a, neg, t, n) && signed_terms(P, nd->b, neg, t, n);
    case EXPR_SUB:
        return signed_terms(P, nd->a, neg, t, n) && signed_terms(P, nd->b, !neg, t, n);
    case EXPR_NEG:
        return signed_terms(P, nd->a, !neg, t, n);
    default:
        if (*n == CANCEL_TERMS_MAX)
            return 0;
        t[(*n)++] = (SignedTerm){e, neg};
        return 1;
    }
}

/* The factors of e through products of any kind, sorted by id: a
 * product's value whatever its grouping.  0 past CANCEL_FACTORS_MAX. */
enum { CANCEL_FACTORS_MAX = 16 };

static int
product_factors(const ExprPool *P, ExprId e, ExprId *f, int *n)
{
    const ExprNode *nd = &P->node[e];
    if (nd->op == EXPR_MUL)
        return product_factors(P, nd->a, f, n) && product_factors(P, nd->b, f, n);
    if (*n == CANCEL_FACTORS_MAX)
        return 0;
    int k = (*n)++;
    for (; k > 0 && f[k - 1] > e; k--) /* insertion: products are short */
        f[k] = f[k - 1];
    f[k] = e;
    return 1;
}

/* x and y are one node, or products of the same factors grouped
 * differently ((a b) c and a (b c) with a sum among them, which the
 * canonical product leaves binary). */
static int
same_product(const ExprPool *P, ExprId x, ExprId y)
{
    if (x == y)
        return 1;
    if (P->node[x].op != EXPR_MUL || P->node[y].op != EXPR_MUL)
        return 0;
    ExprId fx[CANCEL_FACTORS_MAX], fy[CANCEL_FACTORS_MAX];
    int nx = 0, ny = 0;
    if (!product_factors(P, x, fx, &nx) || !product_factors(P, y, fy, &ny) || nx != ny)
        return 0;
    for (int i = 0; i < nx; i++)
        if (fx[i] != fy[i])
            return 0;
    return 1;
}

static int
is_sum(const ExprPool *P, ExprId e)
{
    int op = P->node[e].op;
    return op == EXPR_ADD || op == EXPR_SUB || op == EXPR_NEG;
}

/* a + b (sign 1) or a - b (sign -1) with the terms that cancel taken
 * out, or EXPR_NONE when none do. */
static ExprId
cancel_terms(ExprPool *P, ExprId a, ExprId b, int sign)
{
    if (!is_sum(P, a) && !is_sum(P, b))
        return EXPR_NONE;
    SignedTerm t[2 * CANCEL_TERMS_MAX];
    int na = 0, nb = 0;
    if (!signed_terms(P, a, 0, t, &na))
        return EXPR_NONE;
    if (!signed_terms(P, b, sign < 0, t + na, &nb))
        return EXPR_NONE;
    int n = na + nb, gone = 0;
    for (int i = 0; i < na; i++)
        for (int j = na; j < n; j++)
            if (t[i].x != EXPR_NONE && t[j].x != EXPR_NONE && t[i].neg != t[j].neg &&
                same_product(P, t[i].x, t[j].x)) {
                t[i].x = t[j].x = EXPR_NONE;
                gone = 1;
                break;
            }
    if (!gone)
        return EXPR_NONE;
    ExprId r = EXPR_ZERO;
    for (int i = 0; i < n; i++)
        if (t[i].x != EXPR_NONE)
            r = t[i].neg ? expr_sub(P, r, t[i].x) : expr_add(P, r, t[i].x);
    return r;
}

ExprId
expr_add(ExprPool *P, ExprId a, ExprId b)
{
    double x, y;
    if (expr_is_const(P, a, &x) && expr_is_const(P, b, &y) && foldable(x + y))
        return expr_const(P, x + y);
    if (is_value(P, a, 0.0))
        return b;
    if (is_value(P, b, 0.0))
        return a;
    if (op_of(P, b) == EXPR_NEG)
        return expr_sub(P, a, P->node[b].a);
    if (op_of(P, a) == EXPR_NEG)
        return expr_sub(P, b, P->node[a].a);
    if (a == b)
        return expr_mul(P, expr_const(P, 2.0), a);
    ExprId r = pythagoras(P, a, b, 1);
    if (r != EXPR_NONE)
        return r;
    /* (x - a) + a = x: a point offset and brought back (kin.h).  A case
     * of cancel_terms below, kept because it returns x's own node where
     * cancel_terms would rebuild x's sum in another grouping */
    if (op_of(P, a) == EXPR_SUB && P->node[a].b == b)
        return P->node[a].a;
    if (op_of(P, b) == EXPR_SUB && P->node[b].b == a)
        return P->node[b].a;
    ExprId c1, x1, c2, x2;
    double k1, k2;
    if (P->node[a].coeff && P->node[b].coeff) { /* 4 m l - 2 m l = 2 m l */
        numeric(P, a, &k1, &x1);
        numeric(P, b, &k2, &x2);
        if (x1 == x2 && foldable(k1 + k2))
            return expr_mul(P, expr_const(P, k1 + k2), x1);
    }
    if (term(P, a, &c1, &x1) && term(P, b, &c2, &x2) && x1 == x2)
        return expr_mul(P, expr_add(P, c1, c2), x1); /* c x + d x = (c + d) x */
    if (scaled(P, a, &c1, &x1) && scaled(P, b, &c2, &x2) && c1 == c2)
        return expr_mul(P, c1, expr_add(P, x1, x2)); /* c x + c y = c (x + y) */
    if ((r = cancel_terms(P, a, b, 1)) != EXPR_NONE)
        return r;
    order2(P, &a, &b);
    return mk(P, EXPR_ADD, a, b);
}

ExprId
expr_sub(ExprPool *P, ExprId a, ExprId b)
{
    double x, y;
    if (expr_is_const(P, a, &x) && expr_is_const(P, b, &y) && foldable(x - y))
        return expr_const(P, x - y);
    if (a == b)
        return EXPR_ZERO;
    if (is_value(P, b, 0.0))
        return a;
    if (is_value(P, a, 0.0))
        return expr_neg(P, b);
    if (op_of(P, b) == EXPR_NEG)
        return expr_add(P, a, P->node[b].a);
    if (op_of(P, a) == EXPR_NEG) /* -x - y = -(x + y) */
        return expr_neg(P, expr_add(P, P->node[a].a, b));
    ExprId r = pythagoras(P, a, b, -1);
    if (r != EXPR_NONE)
        return r;
    /* (x + y) - y = x, (x + y) - x = y, x - (x - y) = y: a point's
     * position less the point it is offset from (kin.h); cases of
     * cancel_terms kept for the same reason as in expr_add */
    if (op_of(P, a) == EXPR_ADD && P->node[a].b == b)
        return P->node[a].a;
    if (op_of(P, a) == EXPR_ADD && P->node[a].a == b)
        return P->node[a].b;
    if (op_of(P, b) == EXPR_SUB && P->node[b].a == a)
        return P->node[b].b;
    ExprId c1, x1, c2, x2;
    double k1, k2;
    if (P->node[a].coeff && P->node[b].coeff) {
        numeric(P, a, &k1, &x1);
        numeric(P, b, &k2, &x2);
        if (x1 == x2 && foldable(k1 - k2))
            return expr_mul(P, expr_const(P, k1 - k2), x1);
    }
    if (term(P, a, &c1, &x1) && term(P, b, &c2, &x2) && x1 == x2)
        return expr_mul(P, expr_sub(P, c1, c2), x1); /* c x - d x = (c - d) x */
    if (scaled(P, a, &c1, &x1) && scaled(P, b, &c2, &x2) && c1 == c2)
        return expr_mul(P, c1, expr_sub(P, x1, x2)); /* c x - c y = c (x - y) */
    if ((r = cancel_terms(P, a, b, -1)) != EXPR_NONE)
        return r;
    return mk(P, EXPR_SUB, a, b);
}

/* x^m * x^n = x^(m+n) where one side is x or an integer power of x. */
static int
power_parts(const ExprPool *P, ExprId e, ExprId *base)
{
    if (op_of(P, e) == EXPR_POWI) {
        *base = P->node[e].a;
        return (int32_t)P->node[e].b;
    }
    *base = e;
    return 1;
}

/* A product of non-coefficient factors is kept in one canonical shape: a
 * left-deep chain ((f1*f2)*f3)*... of its factors sorted by base id, equal
 * bases merged into integer powers.  So x*y*z is one node however it was
 * built, and x*(y*x) is x^2*y.  Only monomials are flattened (factors that
 * are leaves or function calls, such as sin q1 * v2): a product with a
 * sum or quotient factor stays binary, so that intermediate products that
 * are shared (the solve is full of them) are not rebuilt in another
 * order. */
enum { MAX_FACTORS = 32 };

typedef struct Factor {
    ExprId base;
    int n;
} Factor;

/* Append the factors of e (a canonical product, a power or anything else)
 * to f; 0 if there are more than MAX_FACTORS.  A chain of products deeper
 * than MAX_FACTORS has more factors than that, so the walk stops there:
 * long products cost constant time here, and no deep recursion. */
static int
gather_factors(const ExprPool *P, ExprId e, Factor *f, int *nf, int depth)
{
    const ExprNode *nd = &P->node[e];
    if (nd->op == EXPR_MUL && !P->node[nd->a].coeff && !P->node[nd->b].coeff)
        return depth < MAX_FACTORS && gather_factors(P, nd->a, f, nf, depth + 1) &&
               gather_factors(P, nd->b, f, nf, depth + 1);
    if (*nf == MAX_FACTORS)
        return 0;
    f[*nf].n = power_parts(P, e, &f[*nf].base);
    int k = expr_op_kind[op_of(P, f[*nf].base)];
    (*nf)++;
    return k == OPK_LEAF || k == OPK_CALL;
}

static ExprId
canonical_product(ExprPool *P, ExprId a, ExprId b)
{
    Factor f[MAX_FACTORS];
    int nf = 0;
    if (!gather_factors(P, a, f, &nf, 0) || !gather_factors(P, b, f, &nf, 0)) {
        order2(P, &a, &b);
        return mk(P, EXPR_MUL, a, b);
    }
    for (int i = 1; i < nf; i++) { /* insertion sort: products are short */
        Factor x = f[i];
        int j = i;
        for (; j > 0 && f[j - 1].base > x.base; j--)
            f[j] = f[j - 1];
        f[j] = x;
    }
    int m = 0;
    for (int i = 0; i < nf; i++) {
        if (m && f[m - 1].base == f[i].base)
            f[m - 1].n += f[i].n;
        else
            f[m++] = f[i];
    }
    ExprId r = EXPR_NONE;
    for (int i = 0; i < m; i++) {
        ExprId x = expr_powi(P, f[i].base, f[i].n);
        r = r == EXPR_NONE ? x : mk(P, EXPR_MUL, r, x);
    }
    return r;
}

ExprId
expr_mul(ExprPool *P, ExprId a, ExprId b)
{
    /* set only where expr_is_const says so: initialized for gcc -O3, which
     * cannot see that every read is behind its flag */
    double x = 0, y = 0;
    order2(P, &a, &b);
    int ca = expr_is_const(P, a, &x), cb = expr_is_const(P, b, &y);
    if (ca && cb && foldable(x * y))
        return expr_const(P, x * y);
    if (ca) {
        if (x == 0.0)
            return EXPR_ZERO;
        if (x == 1.0)
            return b;
        if (x == -1.0)
            return expr_neg(P, b);
        if (op_of(P, b) == EXPR_NEG)
            return expr_mul(P, expr_const(P, -x), P->node[b].a);
    }
    /* numbers gather in front across products of parameters:
     * 2*(0.5*m) = m, (2*m)*(3*l) = 6*(m*l) */
    double k1, k2;
    ExprId r1, r2;
    numeric(P, a, &k1, &r1);
    numeric(P, b, &k2, &r2);
    if (!ca && !cb && (k1 != 1.0 || k2 != 1.0) && P->node[a].coeff && P->node[b].coeff &&
        foldable(k1 * k2)) {
        ExprId r = expr_mul(P, r1, r2);
        return expr_mul(P, expr_const(P, k1 * k2), r);
    }
    if (ca && !cb && k2 != 1.0 && foldable(x * k2))
        return expr_mul(P, expr_const(P, x * k2), r2);
    if (!ca && op_of(P, a) == EXPR_NEG)
        return expr_neg(P, expr_mul(P, P->node[a].a, b));
    if (!ca && op_of(P, b) == EXPR_NEG)
        return expr_neg(P, expr_mul(P, a, P->node[b].a));
    /* Coefficient factors float to the front and gather there:
     * c*(d*y) = (c d)*y, (c*x)*y = c*(x*y), x*(c*y) = c*(x*y). */
    ExprId cf, rest;
    if (P->node[a].coeff && scaled(P, b, &cf, &rest))
        return expr_mul(P, expr_mul(P, a, cf), rest);
    if (!P->node[a].coeff && scaled(P, a, &cf, &rest))
        return expr_mul(P, cf, expr_mul(P, rest, b));
    if (!P->node[a].coeff && scaled(P, b, &cf, &rest))
        return expr_mul(P, cf, expr_mul(P, a, rest));
    ExprId ba, bb;
    int ma = power_parts(P, a, &ba), mb = power_parts(P, b, &bb);
    if (ba == bb && op_of(P, ba) != EXPR_CONST)
        return expr_powi(P, ba, ma + mb);
    if (!P->node[a].coeff && !P->node[b].coeff)
        return canonical_product(P, a, b);
    return mk(P, EXPR_MUL, a, b);
}

static int
is_pow2(double c)
{
    int e;
    return c != 0.0 && fabs(frexp(c, &e)) == 0.5;
}

ExprId
expr_div(ExprPool *P, ExprId a, ExprId b)
{
    double x = 0, y = 0;
    int ca = expr_is_const(P, a, &x), cb = expr_is_const(P, b, &y);
    if (ca && cb && y != 0.0 && foldable(x / y))
        return expr_const(P, x / y);
    if (cb && y == 1.0)
        return a;
    if (cb && y == -1.0)
        return expr_neg(P, a);
    if (cb && is_pow2(y)) /* exact: x/4 = 0.25*x */
        return expr_mul(P, expr_const(P, 1.0 / y), a);
    if (ca && x == 0.0 && !(cb && y == 0.0))
        return EXPR_ZERO;
    if (a == b && !cb) /* x/x = 1 symbolically; 0/0 stays */
        return EXPR_ONE;
    if (op_of(P, a) == EXPR_NEG)
        return expr_neg(P, expr_div(P, P->node[a].a, b));
    if (op_of(P, b) == EXPR_NEG)
        return expr_neg(P, expr_div(P, a, P->node[b].a));
    /* (c*x)/y = c*(x/y), keeping coefficients outermost */
    ExprId cf, rest;
    if (!P->node[b].coeff && scaled(P, a, &cf, &rest))
        return expr_mul(P, cf, expr_div(P, rest, b));
    return mk(P, EXPR_DIV, a, b);
}

ExprId
expr_powi(ExprPool *P, ExprId a, int n)
{
    double x;
    if (n == 0)
        return EXPR_ONE;
    if (n == 1)
        return a;
    if (n == -1)
        return expr_div(P, EXPR_ONE, a);
    if (expr_is_const(P, a, &x)) {
        double r = pow(x, n);
        if (foldable(r))
            return expr_const(P, r);
    }
    const ExprNode nav = P->node[a], *na = &nav;
    if (na->op == EXPR_POWI) {
        long m = (long)(int32_t)na->b * n;
        if (m >= INT32_MIN && m <= INT32_MAX)
            return expr_powi(P, na->a, (int)m);
    }
    if (na->op == EXPR_NEG) {
        ExprId r = expr_powi(P, na->a, n);
        return n % 2 ? expr_neg(P, r) : r;
    }
    if (n < 0)
        return expr_div(P, EXPR_ONE, expr_powi(P, a, -n));
    return mk(P, EXPR_POWI, a, (uint32_t)(int32_t)n);
}

ExprId
expr_pow(ExprPool *P, ExprId a, ExprId b)
{
    double x, y;
    if (expr_is_const(P, b, &y)) {
        if (y == rint(y) && fabs(y) <= 64)
            return expr_powi(P, a, (int)y);
        if (y == 0.5)
            return expr_unary(P, EXPR_SQRT, a);
        if (y == -0.5)
            return expr_div(P, EXPR_ONE, expr_unary(P, EXPR_SQRT, a));
        if (expr_is_const(P, a, &x) && foldable(pow(x, y)))
            return expr_const(P, pow(x, y));
    }
    return mk(P, EXPR_POW, a, b);
}

static double
sign(double x)
{
    return (x > 0) - (x < 0);
}

static double
apply1(int op, double x)
{
    switch (op) {
    case EXPR_NEG: return -x;
    case EXPR_SIN: return sin(x);
    case EXPR_COS: return cos(x);
    case EXPR_TAN: return tan(x);
    case EXPR_ASIN: return asin(x);
    case EXPR_ACOS: return acos(x);
    case EXPR_ATAN: return atan(x);
    case EXPR_SINH: return sinh(x);
    case EXPR_COSH: return cosh(x);
    case EXPR_TANH: return tanh(x);
    case EXPR_EXP: return exp(x);
    case EXPR_LOG: return log(x);
    case EXPR_SQRT: return sqrt(x);
    case EXPR_ABS: return fabs(x);
    case EXPR_SIGN: return sign(x);
    }
    return NAN;
}

ExprId
expr_unary(ExprPool *P, int op, ExprId a)
{
    double x;
    if (op == EXPR_NEG)
        return expr_neg(P, a);
    if (expr_is_const(P, a, &x) && foldable(apply1(op, x)))
        return expr_const(P, apply1(op, x));
    if (op_of(P, a) == EXPR_NEG) {
        ExprId in = P->node[a].a;
        switch (op) { /* odd and even functions */
        case EXPR_SIN: case EXPR_TAN: case EXPR_ASIN: case EXPR_ATAN:
        case EXPR_SINH: case EXPR_TANH: case EXPR_SIGN:
            return expr_neg(P, expr_unary(P, op, in));
        case EXPR_COS: case EXPR_COSH: case EXPR_ABS:
            return expr_unary(P, op, in);
        }
    }
    return mk(P, op, a, 0);
}

ExprId
expr_binary(ExprPool *P, int op, ExprId a, ExprId b)
{
    double x, y;
    switch (op) {
    case EXPR_ADD: return expr_add(P, a, b);
    case EXPR_SUB: return expr_sub(P, a, b);
    case EXPR_MUL: return expr_mul(P, a, b);
    case EXPR_DIV: return expr_div(P, a, b);
    case EXPR_POW: return expr_pow(P, a, b);
    case EXPR_ATAN2:
        if (expr_is_const(P, a, &x) && expr_is_const(P, b, &y))
            return expr_const(P, atan2(x, y));
        return mk(P, EXPR_ATAN2, a, b);
    }
    return EXPR_NONE;
}

/* ---- switched expressions ---- */

ExprId
expr_select(ExprPool *P, int mode, ExprId a, ExprId b)
{
    if (a == b)
        return a;
    /* within mode k, a SELECT on k below is already decided */
    if (op_of(P, a) == EXPR_SELECT && expr_select_mode(P, a) == mode)
        a = P->node[a].a;
    if (op_of(P, b) == EXPR_SELECT && expr_select_mode(P, b) == mode)
        b = P->node[b].b;
    if (a == b)
        return a;
    ExprNode nd = {.op = EXPR_SELECT, .a = a, .b = b, .value = mode};
    nd.deps = P->node[a].deps | P->node[b].deps | DEP_U | DEP_M;
    nd.height = 1 + (P->node[a].height > P->node[b].height ? P->node[a].height
                                                            : P->node[b].height);
    nd.coeff = 0; /* a mode is not a parameter: never folded into derived ones */
    return intern(P, nd);
}

int expr_nswitch(const ExprPool *P) { return P->nsw; }
ExprId expr_switch(const ExprPool *P, int k) { return P->sw[k]; }
int expr_select_mode(const ExprPool *P, ExprId e) { return (int)P->node[e].value; }
const char *expr_switch_name(const ExprPool *P, int k) { return P->swname[k]; }

/* The first name a switch is given is its own; another of the pool's
 * gets a suffix .2, .3, ... */
void
expr_name_switch(ExprPool *P, int k, const char *name)
{
    if (P->swname[k])
        return;
    size_t len = strlen(name) + 16; /* room for the suffix */
    char *s = xmalloc(len);
    snprintf(s, len, "%s", name);
    for (int n = 2;; n++) {
        int taken = 0;
        for (int j = 0; j < P->nsw && !taken; j++)
            taken = P->swname[j] && !strcmp(P->swname[j], s);
        if (!taken)
            break;
        snprintf(s, len, "%s.%d", name, n);
    }
    P->swname[k] = s;
}

/* A new switch, k = nsw, whose function is s. */
static void
add_switch(ExprPool *P, ExprId s)
{
    if (P->nsw == P->capsw) {
        P->capsw = P->capsw ? 2 * P->capsw : 8;
        P->sw = xrealloc(P->sw, (size_t)P->capsw * sizeof *P->sw);
        P->swname = xrealloc(P->swname, (size_t)P->capsw * sizeof *P->swname);
    }
    P->swname[P->nsw] = NULL;
    P->sw[P->nsw++] = s;
}

/* SELECT(k, a, b) on s's switch k (s met before: the same k), or the
 * branch s's constant sign chooses now. */
ExprId
expr_where(ExprPool *P, ExprId s, ExprId a, ExprId b)
{
    double v;
    if (expr_is_const(P, s, &v))
        return v > 0 ? a : b;
    int k = 0;
    while (k < P->nsw && P->sw[k] != s)
        k++;
    if (k == P->nsw)
        add_switch(P, s);
    return expr_select(P, k, a, b);
}

int
expr_switch_held(ExprPool *P)
{
    add_switch(P, expr_const(P, -1));
    return P->nsw - 1;
}

ExprId
expr_max(ExprPool *P, ExprId a, ExprId b)
{
    return a == b ? a : expr_where(P, expr_sub(P, a, b), a, b);
}

ExprId
expr_min(ExprPool *P, ExprId a, ExprId b)
{
    return a == b ? a : expr_where(P, expr_sub(P, a, b), b, a);
}

ExprId
expr_clamp(ExprPool *P, ExprId x, ExprId lo, ExprId hi)
{
    ExprId s_hi = expr_sub(P, x, hi); /* built first: ids do not depend on C's order */
    ExprId below = expr_where(P, expr_sub(P, x, lo), x, lo);
    return expr_where(P, s_hi, hi, below);
}

/* ---- traversals ---- */

void
expr_magnitude_many(ExprPool *P, int nroots, const ExprId *roots, ExprId *out)
{
    size_t n = P->n;
    unsigned char *mark = calloc(n, 1);
    ExprId *mag = xmalloc(n * sizeof *mag);
    expr_mark(P, nroots, roots, mark);
    /* operands have smaller ids than the nodes built from them */
    for (size_t id = 0; id < n; id++) {
        if (!mark[id])
            continue;
        const ExprNode nd = P->node[id];
        ExprId e = (ExprId)id, m;
        switch (nd.op) {
        case EXPR_CONST:
            m = expr_const(P, fabs(nd.value));
            break;
        case EXPR_ADD:
        case EXPR_SUB:
            m = expr_add(P, mag[nd.a], mag[nd.b]);
            break;
        case EXPR_MUL:
            m = expr_mul(P, mag[nd.a], mag[nd.b]);
            break;
        case EXPR_DIV:
            m = expr_div(P, mag[nd.a], expr_unary(P, EXPR_ABS, nd.b));
            break;
        case EXPR_NEG:
            m = mag[nd.a];
            break;
        case EXPR_SELECT: /* the branch's */
            m = expr_select(P, (int)nd.value, mag[nd.a], mag[nd.b]);
            break;
        case EXPR_POWI: /* a reciprocal's size is that of 1/|a| */
            m = (int32_t)nd.b > 0 ? expr_powi(P, mag[nd.a], (int)(int32_t)nd.b)
                                  : expr_powi(P, expr_unary(P, EXPR_ABS, nd.a),
                                              (int)(int32_t)nd.b);
            break;
        default: /* a leaf or a function: its own size */
            m = expr_unary(P, EXPR_ABS, e);
            break;
        }
        mag[id] = m;
    }
    for (int i = 0; i < nroots; i++)
        out[i] = roots[i] == EXPR_NONE ? EXPR_NONE : mag[roots[i]];
    free(mark);
    free(mag);
}

void
expr_mark(ExprPool *P, int n, const ExprId *roots, unsigned char *mark)
{
    size_t cap = 64, sp = 0;
    ExprId *stack = xmalloc(cap * sizeof *stack);
    for (int i = 0; i < n; i++)
        if (roots[i] != EXPR_NONE)
            stack[sp++] = roots[i], sp == cap ? (cap *= 2, stack = xrealloc(stack, cap * sizeof *stack)) : 0;
    while (sp) {
        ExprId e = stack[--sp];
        if (mark[e])
            continue;
        mark[e] = 1;
        const ExprNode *nd = &P->node[e];
        int ar = expr_op_arity[nd->op];
        if (sp + 2 >= cap) {
            cap *= 2;
            stack = xrealloc(stack, cap * sizeof *stack);
        }
        if (ar >= 1)
            stack[sp++] = nd->a;
        if (ar >= 2)
            stack[sp++] = nd->b;
    }
    free(stack);
}

static unsigned char *
marked(ExprPool *P, int n, const ExprId *roots)
{
    unsigned char *mark = xmalloc(P->n);
    memset(mark, 0, P->n);
    expr_mark(P, n, roots, mark);
    return mark;
}

int
expr_max_order(const ExprPool *P, ExprId e)
{
    for (int k = EXPR_MAX_ORDER; k >= 0; k--)
        if (P->node[e].deps & DEP_ORDER(k))
            return k;
    return -1;
}

unsigned expr_deps(const ExprPool *P, ExprId e) { return P->node[e].deps; }

ExprId
expr_find_leaf(ExprPool *P, ExprId e, unsigned deps)
{
    if (!(P->node[e].deps & deps))
        return EXPR_NONE;
    unsigned char *mark = marked(P, 1, &e);
    ExprId found = EXPR_NONE;
    for (ExprId i = 0; i <= e && found == EXPR_NONE; i++)
        if (mark[i] && expr_op_arity[P->node[i].op] == 0 && (P->node[i].deps & deps))
            found = i;
    free(mark);
    return found;
}

int
expr_depends(ExprPool *P, ExprId e, ExprId leaf)
{
    if (leaf > e)
        return 0;
    unsigned char *mark = marked(P, 1, &e);
    int r = mark[leaf];
    free(mark);
    return r;
}

/* x^n as the generated C computes it (emit_func.c's print_powi): a
 * product of n factors left to right, rounded at each, up to
 * EXPR_POWI_MUL_MAX, else pow, so that an evaluation here is the C's to
 * the last bit. */
static double
powi(double x, int n)
{
    if (n > EXPR_POWI_MUL_MAX)
        return pow(x, n);
    double r = x;
    for (int k = 1; k < n; k++)
        r *= x;
    return r;
}

/* One node from its operands' values x (a's) and y (b's), a leaf from
 * env: the one place the evaluators compute an operator. */
static double
apply(const ExprNode *nd, double x, double y, const ExprEnv *env)
{
    switch (nd->op) {
    case EXPR_CONST: return nd->value;
    case EXPR_VAR: return env->q[nd->b][nd->a];
    case EXPR_PARAM: return env->p[nd->a];
    case EXPR_INPUT: return env->u[nd->a];
    case EXPR_TIME: return env->t;
    case EXPR_SEED: return env->seed[nd->b] ? env->seed[nd->b][nd->a] : 0.0;
    case EXPR_MULT: return env->lam ? env->lam[nd->a] : 0.0;
    case EXPR_ADD: return x + y;
    case EXPR_SUB: return x - y;
    case EXPR_MUL: return x * y;
    case EXPR_DIV: return x / y;
    case EXPR_POWI: return powi(x, (int32_t)nd->b);
    case EXPR_POW: return pow(x, y);
    case EXPR_ATAN2: return atan2(x, y);
    case EXPR_SELECT:
        if (!env->mode)
            return NAN;
        return env->mode[(int)nd->value] != 0.0 ? x : y;
    }
    return apply1(nd->op, x);
}

double
expr_eval_node(const ExprPool *P, ExprId e, const double *operand, const ExprEnv *env)
{
    const ExprNode *nd = &P->node[e];
    int ar = expr_op_arity[nd->op];
    return apply(nd, ar >= 1 ? operand[0] : 0.0, ar >= 2 ? operand[1] : 0.0, env);
}

static double
eval_node(const ExprNode *nd, const double *v, const ExprEnv *env)
{
    int ar = expr_op_arity[nd->op];
    return apply(nd, ar >= 1 ? v[nd->a] : 0.0, ar >= 2 ? v[nd->b] : 0.0, env);
}

void
expr_eval_many(ExprPool *P, int n, const ExprId *roots, const ExprEnv *env,
               double *out)
{
    unsigned char *mark = marked(P, n, roots);
    double *v = xmalloc(P->n * sizeof *v);
    for (size_t i = 0; i < P->n; i++)
        if (mark[i])
            v[i] = eval_node(&P->node[i], v, env);
    for (int i = 0; i < n; i++)
        out[i] = roots[i] == EXPR_NONE ? 0.0 : v[roots[i]];
    free(v);
    free(mark);
}

double
expr_eval(ExprPool *P, ExprId e, const ExprEnv *env)
{
    double r;
    expr_eval_many(P, 1, &e, env, &r);
    return r;
}

/* ---- evaluation with a rounding bound ---- */

/* An error a long double libm function may make, in units of its
 * result's LDBL_EPSILON: glibc's documented worst cases on x86-64 are 1
 * to 3 ulps (libm-test-ulps), and a bound that is a little loose only
 * costs a zero test its margin, never its soundness. */
enum { CALL_ULPS = 4 };

typedef struct Bounded {
    long double v, err, mag;
} Bounded;

/* One node: its value, the bound on its error (first order, Higham's
 * running error analysis: each operation's rounding plus the operands'
 * errors carried by its partial derivatives, and their product where the
 * second order is cheap to keep), and the magnitude of what it is made
 * of (|x| + |y| for x + y, |x| |y| for x y: the scale at which a sum
 * that cancels is zero).  err = INFINITY where the first order cannot be
 * trusted: a branch (sign, atan2's cut) or a singularity within reach. */
static Bounded
bound_node(const ExprNode *nd, const Bounded *v, const ExprEnv *env)
{
    const long double u = LDBL_EPSILON / 2, call = CALL_ULPS * LDBL_EPSILON;
    Bounded x = {0, 0, 0}, y = {0, 0, 0}, r = {0, 0, 0};
    int ar = expr_op_arity[nd->op];
    if (ar >= 1)
        x = v[nd->a];
    if (ar >= 2)
        y = v[nd->b];
    long double ax = fabsl(x.v), dfdx = 0;
    switch (nd->op) {
    case EXPR_CONST:
    case EXPR_VAR:
    case EXPR_PARAM:
    case EXPR_INPUT:
    case EXPR_TIME:
    case EXPR_SEED:
    case EXPR_MULT:
        r.v = eval_node(nd, NULL, env); /* doubles: exact in long double */
        r.mag = fabsl(r.v);
        return r;
    case EXPR_ADD:
    case EXPR_SUB:
        r.v = nd->op == EXPR_ADD ? x.v + y.v : x.v - y.v;
        r.err = x.err + y.err + u * fabsl(r.v);
        r.mag = x.mag + y.mag;
        return r;
    case EXPR_MUL:
        r.v = x.v * y.v;
        r.err = fabsl(y.v) * x.err + ax * y.err + x.err * y.err + u * fabsl(r.v);
        r.mag = x.mag * y.mag;
        return r;
    case EXPR_DIV:
        r.v = x.v / y.v;
        r.err = y.err < fabsl(y.v) ? (x.err + fabsl(r.v) * y.err) / (fabsl(y.v) - y.err) +
                                         u * fabsl(r.v)
                                   : INFINITY;
        r.mag = x.mag / fabsl(y.v);
        return r;
    case EXPR_NEG:
        x.v = -x.v;
        return x;
    case EXPR_SELECT: /* the branch the mode takes, with its error */
        if (!env->mode)
            return (Bounded){NAN, INFINITY, NAN};
        return env->mode[(int)nd->value] != 0.0 ? x : y;
    case EXPR_POWI: {
        int n = (int32_t)nd->b;
        r.v = powl(x.v, n);
        /* |d x^n / dx| = |n x^(n-1)|, taken at the end of x's interval
         * farther from 0; powl rounds once or a few times */
        r.err = fabsl((long double)n) * powl(ax + x.err, n - 1) * x.err + call * fabsl(r.v);
        r.mag = powl(x.mag, n);
        return r;
    }
    case EXPR_POW:
        r.v = powl(x.v, y.v);
        r.err = fabsl(y.v * powl(x.v, y.v - 1)) * x.err + fabsl(logl(ax) * r.v) * y.err +
                call * fabsl(r.v);
        r.mag = fabsl(r.v);
        return r;
    case EXPR_ATAN2: {
        long double rr = x.v * x.v + y.v * y.v;
        r.v = atan2l(x.v, y.v);
        /* across the cut (y < 0, x = 0) the value jumps by 2 pi */
        r.err = y.v < 0 && fabsl(x.v) <= x.err ? INFINITY
                : (fabsl(y.v) * x.err + ax * y.err) / rr + call * fabsl(r.v);
        r.mag = fabsl(r.v);
        return r;
    }
    case EXPR_SIN: r.v = sinl(x.v); dfdx = fabsl(cosl(x.v)); break;
    case EXPR_COS: r.v = cosl(x.v); dfdx = fabsl(sinl(x.v)); break;
    case EXPR_TAN: r.v = tanl(x.v); dfdx = 1 + r.v * r.v; break;
    case EXPR_ASIN: r.v = asinl(x.v); dfdx = 1 / sqrtl(1 - x.v * x.v); break;
    case EXPR_ACOS: r.v = acosl(x.v); dfdx = 1 / sqrtl(1 - x.v * x.v); break;
    case EXPR_ATAN: r.v = atanl(x.v); dfdx = 1 / (1 + x.v * x.v); break;
    case EXPR_SINH: r.v = sinhl(x.v); dfdx = coshl(x.v); break;
    case EXPR_COSH: r.v = coshl(x.v); dfdx = fabsl(sinhl(x.v)); break;
    case EXPR_TANH: r.v = tanhl(x.v); dfdx = 1 - r.v * r.v; break;
    case EXPR_EXP: r.v = expl(x.v); dfdx = r.v; break;
    case EXPR_LOG: r.v = logl(x.v); dfdx = 1 / ax; break;
    case EXPR_SQRT: r.v = sqrtl(x.v); dfdx = 1 / (2 * r.v); break;
    case EXPR_ABS: r.v = ax; dfdx = 1; break;
    case EXPR_SIGN:
        r.v = (x.v > 0) - (x.v < 0);
        r.err = ax <= x.err ? INFINITY : 0; /* the sign is not known */
        r.mag = fabsl(r.v);
        return r;
    }
    /* a function: first order holds while the error of its argument is
     * small against the scale its derivative changes on, which a bound
     * beyond 1 (radians, or relative for exp and log) no longer says */
    if (x.err > 0 && !(x.err * dfdx < 1 && x.err < 1))
        r.err = INFINITY;
    else
        r.err = (x.err > 0 ? dfdx * x.err : 0) + call * fabsl(r.v);
    r.mag = fabsl(r.v);
    return r;
}

void
expr_eval_bound(ExprPool *P, ExprId e, int n, const ExprEnv *env, ExprBound *out)
{
    unsigned char *mark = marked(P, 1, &e);
    size_t count = 0;
    for (size_t i = 0; i <= e; i++)
        count += mark[i];
    ExprId *list = xmalloc(count * sizeof *list);
    count = 0;
    for (ExprId i = 0; i <= e; i++)
        if (mark[i])
            list[count++] = i;
    free(mark);
    Bounded *v = xmalloc(((size_t)e + 1) * sizeof *v);
    for (int k = 0; k < n; k++) {
        for (size_t i = 0; i < count; i++)
            v[list[i]] = bound_node(&P->node[list[i]], v, &env[k]);
        out[k] = (ExprBound){v[e].v, v[e].err, v[e].mag};
        if (!isfinite(out[k].value) || !isfinite(out[k].mag) || isnan(out[k].err))
            out[k].err = INFINITY;
    }
    free(v);
    free(list);
}

/* Rebuild a node over new operands through the simplifying constructors. */
static ExprId
rebuild(ExprPool *P, const ExprNode *nd, ExprId a, ExprId b)
{
    if (nd->op == EXPR_POWI)
        return expr_powi(P, a, (int32_t)nd->b);
    if (expr_op_arity[nd->op] == 1)
        return expr_unary(P, nd->op, a);
    return expr_binary(P, nd->op, a, b);
}

/* A SELECT over substituted operands: its switch function substituted
 * too, so that the mode still says which side of the kink the branches
 * are on (the same switch where s_k does not change). */
static ExprId
rebuild_select(ExprPool *P, const ExprNode *nd, ExprId a, ExprId b, int n, const ExprId *from,
               const ExprId *to)
{
    int k = (int)nd->value;
    ExprId s = expr_subst(P, P->sw[k], n, from, to);
    return s == P->sw[k] ? expr_select(P, k, a, b) : expr_where(P, s, a, b);
}

ExprId
expr_subst(ExprPool *P, ExprId e, int n, const ExprId *from, const ExprId *to)
{
    size_t size = P->n;
    unsigned char *mark = marked(P, 1, &e);
    ExprId *map = xmalloc(size * sizeof *map);
    for (ExprId i = 0; i <= e; i++) {
        if (!mark[i])
            continue;
        map[i] = i;
        for (int k = 0; k < n; k++)
            if (from[k] == i)
                map[i] = to[k];
        ExprNode nd = P->node[i];
        int ar = expr_op_arity[nd.op];
        if (map[i] != i || ar == 0)
            continue;
        ExprId a = map[nd.a], b = ar == 2 ? map[nd.b] : nd.b;
        if (a != nd.a || (ar == 2 && b != nd.b))
            map[i] = nd.op == EXPR_SELECT ? rebuild_select(P, &nd, a, b, n, from, to)
                                          : rebuild(P, &nd, a, b);
    }
    ExprId r = map[e];
    free(map);
    free(mark);
    return r;
}

void
expr_subst_many(ExprPool *P, int nroots, const ExprId *roots, int n, const ExprId *from,
                const ExprId *to, ExprId *out)
{
    size_t size = P->n;
    unsigned char *mark = marked(P, nroots, roots);
    ExprId *map = xmalloc(size * sizeof *map);
    for (size_t i = 0; i < size; i++)
        map[i] = (ExprId)i;
    for (int k = 0; k < n; k++)
        if (from[k] < size)
            map[from[k]] = to[k];
    for (size_t i = 0; i < size; i++) {
        ExprNode nd = P->node[i];
        int ar = expr_op_arity[nd.op];
        if (!mark[i] || map[i] != i || ar == 0)
            continue;
        ExprId a = map[nd.a], b = ar == 2 ? map[nd.b] : nd.b;
        if (a != nd.a || (ar == 2 && b != nd.b))
            map[i] = nd.op == EXPR_SELECT ? rebuild_select(P, &nd, a, b, n, from, to)
                                          : rebuild(P, &nd, a, b);
    }
    for (int i = 0; i < nroots; i++)
        out[i] = map[roots[i]];
    free(map);
    free(mark);
}

static void
count_node(const ExprPool *P, ExprId i, ExprCount *c)
{
    switch (P->node[i].op) {
    case EXPR_ADD: case EXPR_SUB: case EXPR_NEG: c->adds++; break;
    case EXPR_MUL: c->muls++; break;
    case EXPR_DIV: c->divs++; break;
    case EXPR_POWI: {
        /* emitted as repeated multiplication (and 1/x for n < 0) */
        int k = abs((int32_t)P->node[i].b);
        c->muls += k - 1;
        break;
    }
    default:
        if (expr_op_kind[P->node[i].op] == OPK_CALL)
            c->calls++;
    }
}

ExprCount
expr_count_ops(ExprPool *P, int n, const ExprId *roots)
{
    ExprCount c = {0, 0, 0, 0};
    unsigned char *mark = marked(P, n, roots);
    for (size_t i = 0; i < P->n; i++)
        if (mark[i])
            count_node(P, (ExprId)i, &c);
    free(mark);
    return c;
}

ExprCount
expr_count_list(ExprPool *P, size_t n, const ExprId *nodes)
{
    ExprCount c = {0, 0, 0, 0};
    for (size_t i = 0; i < n; i++)
        count_node(P, nodes[i], &c);
    return c;
}
