/*
 * diff: symbolic derivatives on the hash-consed DAG.
 *
 * All three derivatives are built from one table of local rules,
 * diff_local: the partial of a node with respect to one operand, written
 * as an expression over the node's operands (and the node itself where
 * that saves work, as CasADi does: d(exp x) = exp x).  Forward mode walks
 * operand-first with memo tables; reverse mode walks ids downward, which
 * is a reverse topological order because operands have smaller ids.
 */
#include "diff.h"
#include "base/arena.h"

#include <stdlib.h>
#include <string.h>

#define UNSET ((ExprId)0xfffffffeu) /* memo slot not computed yet */

/* Open-addressing map from (node, leaf) to the partial derivative. */
typedef struct Memo {
    uint64_t *key; /* 0 = empty; else ((node+1) << 32 | leaf) */
    ExprId *val;
    size_t n, cap;
} Memo;

struct Diff {
    ExprPool *P;
    Memo partial;
    ExprId *dt; /* time-derivative memo by node id, UNSET if not computed */
    size_t ndt;
};

Diff *
diff_new(ExprPool *P)
{
    Diff *D = xmalloc(sizeof *D);
    memset(D, 0, sizeof *D);
    D->P = P;
    return D;
}

void
diff_free(Diff *D)
{
    if (!D)
        return;
    free(D->partial.key);
    free(D->partial.val);
    free(D->dt);
    free(D);
}

static uint64_t
mix(uint64_t k)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return k;
}

static void memo_put(Memo *m, uint64_t key, ExprId val);

static void
memo_grow(Memo *m)
{
    Memo old = *m;
    m->cap = old.cap ? old.cap * 2 : 4096;
    m->n = 0;
    m->key = xmalloc(m->cap * sizeof *m->key);
    m->val = xmalloc(m->cap * sizeof *m->val);
    memset(m->key, 0, m->cap * sizeof *m->key);
    for (size_t i = 0; i < old.cap; i++)
        if (old.key[i])
            memo_put(m, old.key[i], old.val[i]);
    free(old.key);
    free(old.val);
}

static void
memo_put(Memo *m, uint64_t key, ExprId val)
{
    if ((m->n + 1) * 2 > m->cap)
        memo_grow(m);
    size_t i = mix(key) & (m->cap - 1);
    while (m->key[i] && m->key[i] != key)
        i = (i + 1) & (m->cap - 1);
    if (!m->key[i])
        m->n++;
    m->key[i] = key;
    m->val[i] = val;
}

static int
memo_get(const Memo *m, uint64_t key, ExprId *val)
{
    if (!m->cap)
        return 0;
    size_t i = mix(key) & (m->cap - 1);
    while (m->key[i]) {
        if (m->key[i] == key) {
            *val = m->val[i];
            return 1;
        }
        i = (i + 1) & (m->cap - 1);
    }
    return 0;
}

/* The local rules, one per operator; f is the node itself, x and y its
 * operands, k which operand. */
ExprId
diff_local(ExprPool *P, ExprId f, int k)
{
    const ExprNode nd = *expr_node(P, f);
    ExprId x = nd.a, y = nd.b;
    switch (nd.op) {
    case EXPR_ADD: /* d(x+y) = dx + dy */
        return EXPR_ONE;
    case EXPR_SUB: /* d(x-y) = dx - dy */
        return k == 0 ? EXPR_ONE : expr_const(P, -1.0);
    case EXPR_MUL: /* d(xy) = y dx + x dy */
        return k == 0 ? y : x;
    case EXPR_DIV: /* d(x/y) = dx/y - (x/y) dy/y */
        return k == 0 ? expr_div(P, EXPR_ONE, y)
                      : expr_neg(P, expr_div(P, f, y));
    case EXPR_NEG:
        return expr_const(P, -1.0);
    case EXPR_POWI: { /* d(x^n) = n x^(n-1) dx */
        int n = (int32_t)nd.b;
        ExprId xn1 = expr_powi(P, x, n - 1);
        return expr_mul(P, expr_const(P, n), xn1);
    }
    case EXPR_POW: /* d(x^y) = y x^(y-1) dx + x^y log(x) dy */
        if (k == 0)
            return expr_mul(P, y, expr_pow(P, x, expr_sub(P, y, EXPR_ONE)));
        return expr_mul(P, f, expr_unary(P, EXPR_LOG, x));
    case EXPR_ATAN2: { /* d atan2(x, y) = (y dx - x dy) / (x^2 + y^2) */
        ExprId y2 = expr_powi(P, y, 2);
        ExprId r2 = expr_add(P, expr_powi(P, x, 2), y2);
        return k == 0 ? expr_div(P, y, r2) : expr_neg(P, expr_div(P, x, r2));
    }
    case EXPR_SIN: /* d sin x = cos x dx */
        return expr_unary(P, EXPR_COS, x);
    case EXPR_COS: /* d cos x = -sin x dx */
        return expr_neg(P, expr_unary(P, EXPR_SIN, x));
    case EXPR_TAN: /* d tan x = (1 + tan^2 x) dx */
        return expr_add(P, EXPR_ONE, expr_powi(P, f, 2));
    case EXPR_ASIN: /* d asin x = dx / sqrt(1 - x^2) */
        return expr_div(P, EXPR_ONE, expr_unary(P, EXPR_SQRT,
                        expr_sub(P, EXPR_ONE, expr_powi(P, x, 2))));
    case EXPR_ACOS: /* d acos x = -dx / sqrt(1 - x^2) */
        return expr_neg(P, expr_div(P, EXPR_ONE, expr_unary(P, EXPR_SQRT,
                        expr_sub(P, EXPR_ONE, expr_powi(P, x, 2)))));
    case EXPR_ATAN: /* d atan x = dx / (1 + x^2) */
        return expr_div(P, EXPR_ONE, expr_add(P, EXPR_ONE, expr_powi(P, x, 2)));
    case EXPR_SINH: /* d sinh x = cosh x dx */
        return expr_unary(P, EXPR_COSH, x);
    case EXPR_COSH: /* d cosh x = sinh x dx */
        return expr_unary(P, EXPR_SINH, x);
    case EXPR_TANH: /* d tanh x = (1 - tanh^2 x) dx */
        return expr_sub(P, EXPR_ONE, expr_powi(P, f, 2));
    case EXPR_EXP: /* d exp x = exp x dx */
        return f;
    case EXPR_LOG: /* d log x = dx / x */
        return expr_div(P, EXPR_ONE, x);
    case EXPR_SQRT: /* d sqrt x = dx / (2 sqrt x) */
        return expr_div(P, expr_const(P, 0.5), f);
    case EXPR_ABS: /* d |x| = sign(x) dx */
        return expr_unary(P, EXPR_SIGN, x);
    case EXPR_SIGN: /* piecewise constant */
        return EXPR_ZERO;
    case EXPR_SELECT: /* the branch's own derivative in its mode (chain, below) */
        return k == 0 ? expr_select(P, (int)nd.value, EXPR_ONE, EXPR_ZERO)
                      : expr_select(P, (int)nd.value, EXPR_ZERO, EXPR_ONE);
    }
    return EXPR_ZERO; /* leaves have no operands */
}

/* Chain rule over the operands: sum_k local(f, k) * d(operand_k). */
static ExprId
chain(ExprPool *P, ExprId f, const ExprId *dargs, int nargs)
{
    const ExprNode *nd = expr_node(P, f);
    if (nd->op == EXPR_SELECT) /* d SELECT(k, a, b) = SELECT(k, da, db), not a sum of products */
        return dargs[0] == EXPR_NONE || dargs[1] == EXPR_NONE
                   ? EXPR_NONE
                   : expr_select(P, (int)nd->value, dargs[0], dargs[1]);
    ExprId sum = EXPR_ZERO;
    for (int k = 0; k < nargs; k++) {
        if (dargs[k] == EXPR_NONE)
            return EXPR_NONE;
        if (dargs[k] != EXPR_ZERO)
            sum = expr_add(P, sum, expr_mul(P, diff_local(P, f, k), dargs[k]));
    }
    return sum;
}

static int
nargs_of(const ExprNode *nd)
{
    return nd->op == EXPR_POWI ? 1 : expr_op_arity[nd->op];
}

ExprId
diff_partial(Diff *D, ExprId e, ExprId leaf)
{
    if (e == leaf)
        return EXPR_ONE;
    const ExprNode nd = *expr_node(D->P, e);
    int n = nargs_of(&nd);
    if (n == 0 || leaf > e) /* operands are older than their node */
        return EXPR_ZERO;
    uint64_t key = ((uint64_t)e + 1) << 32 | leaf;
    ExprId r;
    if (memo_get(&D->partial, key, &r))
        return r;
    ExprId d[2] = {diff_partial(D, nd.a, leaf), EXPR_ZERO};
    if (n == 2)
        d[1] = diff_partial(D, nd.b, leaf);
    r = chain(D->P, e, d, n);
    memo_put(&D->partial, key, r);
    return r;
}

static ExprId
time_leaf(ExprPool *P, const ExprNode *nd)
{
    switch (nd->op) {
    case EXPR_TIME:
        return EXPR_ONE;
    case EXPR_VAR: /* d/dt q^(k) = q^(k+1), or the rate of a coordinate that has one */
        if (nd->b == 0 && expr_rate(P, (int)nd->a) != EXPR_NONE)
            return expr_rate(P, (int)nd->a);
        if (nd->b + 1 > EXPR_MAX_ORDER)
            return EXPR_NONE;
        return expr_var(P, (int)nd->a, (int)nd->b + 1);
    case EXPR_INPUT: /* a signal's derivative is not known symbolically */
    case EXPR_MULT:  /* nor a multiplier's */
        return EXPR_NONE;
    }
    return EXPR_ZERO;
}

ExprPool *
diff_pool(const Diff *D)
{
    return D->P;
}

ExprId
diff_time(Diff *D, ExprId e)
{
    size_t need = expr_pool_size(D->P);
    if (D->ndt < need) {
        size_t cap = need * 2;
        D->dt = xrealloc(D->dt, cap * sizeof *D->dt);
        for (size_t i = D->ndt; i < cap; i++)
            D->dt[i] = UNSET;
        D->ndt = cap;
    }
    if (D->dt[e] != UNSET)
        return D->dt[e];
    const ExprNode nd = *expr_node(D->P, e);
    int n = nargs_of(&nd);
    ExprId r;
    if (n == 0) {
        r = time_leaf(D->P, &nd);
    } else {
        ExprId d[2] = {diff_time(D, nd.a), EXPR_ZERO};
        if (n == 2)
            d[1] = diff_time(D, nd.b);
        r = chain(D->P, e, d, n);
    }
    /* the recursion may have grown the pool, but not below e */
    D->dt[e] = r;
    return r;
}

void
diff_gradient(Diff *D, ExprId f, int n, const ExprId *leaves, ExprId *out)
{
    ExprPool *P = D->P;
    size_t size = (size_t)f + 1;
    unsigned char *mark = xmalloc(size);
    memset(mark, 0, size);
    expr_mark(P, 1, &f, mark);
    ExprId *adj = xmalloc(size * sizeof *adj);
    for (size_t i = 0; i < size; i++)
        adj[i] = EXPR_ZERO;
    adj[f] = EXPR_ONE;
    for (int i = 0; i < n; i++)
        out[i] = EXPR_ZERO;
    for (ExprId id = f + 1; id-- > 0;) {
        if (!mark[id] || adj[id] == EXPR_ZERO)
            continue;
        const ExprNode nd = *expr_node(P, id);
        if (nd.op == EXPR_SELECT) {
            /* adj SELECT(k, da, db): each branch's partials (forward,
             * memoized) in its own mode, not adj SELECT(k, 1, 0) carried
             * into the branch, a product outside it that every mode
             * would compute (lower_schedule.h: lazy branches) */
            for (int i = 0; i < n; i++) {
                ExprId da = diff_partial(D, nd.a, leaves[i]), db = diff_partial(D, nd.b, leaves[i]);
                if (da == EXPR_ZERO && db == EXPR_ZERO)
                    continue;
                ExprId on = expr_mul(P, adj[id], da), off = expr_mul(P, adj[id], db);
                out[i] = expr_add(P, out[i], expr_select(P, (int)nd.value, on, off));
            }
            continue;
        }
        int na = nargs_of(&nd);
        for (int k = 0; k < na; k++) {
            ExprId arg = k == 0 ? nd.a : nd.b;
            ExprId contrib = expr_mul(P, adj[id], diff_local(P, id, k));
            adj[arg] = expr_add(P, adj[arg], contrib);
        }
    }
    for (int i = 0; i < n; i++)
        if (leaves[i] <= f)
            out[i] = expr_add(P, adj[leaves[i]], out[i]);
    free(adj);
    free(mark);
}

void
diff_jvp(Diff *D, int nroots, const ExprId *roots, int n, const ExprId *leaves,
         const ExprId *seeds, ExprId *out)
{
    ExprPool *P = D->P;
    ExprId top = 0;
    for (int i = 0; i < nroots; i++)
        if (roots[i] != EXPR_NONE && roots[i] > top)
            top = roots[i];
    size_t size = (size_t)top + 1;
    unsigned char *mark = xmalloc(expr_pool_size(P));
    memset(mark, 0, expr_pool_size(P));
    expr_mark(P, nroots, roots, mark);
    ExprId *tan = xmalloc(size * sizeof *tan); /* tangent by node id */
    for (ExprId id = 0; id < size; id++) { /* operands first: ids ascend */
        tan[id] = EXPR_ZERO;
        if (!mark[id])
            continue;
        const ExprNode nd = *expr_node(P, id);
        int na = nargs_of(&nd);
        if (na == 0) {
            for (int k = 0; k < n; k++)
                if (leaves[k] == id)
                    tan[id] = seeds[k];
            continue;
        }
        ExprId d[2] = {tan[nd.a], na == 2 ? tan[nd.b] : EXPR_ZERO};
        tan[id] = chain(P, id, d, na);
    }
    for (int i = 0; i < nroots; i++)
        out[i] = roots[i] == EXPR_NONE ? EXPR_NONE : tan[roots[i]];
    free(tan);
    free(mark);
}
