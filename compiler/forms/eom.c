/*
 * eom: derive M, h and the residual Jacobians from a form's residual.
 *
 * M_ij = dE_i/dq_j'' by forward partials (measured: about 10% less code
 * for the chain benchmark than taking M from the reverse sweep); the
 * partials with respect to q, q', u and t come from one reverse sweep per
 * row.  Only the lower triangle of M is derived: M is symmetric for every
 * form here (tests/unit/test_forms.c checks the upper triangle against the
 * residual).
 *
 * The same partials also come as directional derivatives along symbolic
 * seeds (diff_jvp): one forward sweep over E for q and one for q'.
 */
#include "eom.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void
derive_row(Eom *e, Diff *D, const ExprId *leaves, ExprId *grad, int i)
{
    int n = e->n, nq = e->nq, nu = e->nu, nl = nq + n + nu + 1;
    diff_gradient(D, e->E[i], nl, leaves, grad);
    for (int j = 0; j < nq; j++)
        e->dEdq[i * nq + j] = grad[j];
    for (int j = 0; j < n; j++)
        e->dEdv[i * n + j] = grad[nq + j];
    for (int k = 0; k < nu; k++)
        e->dEdu[i * nu + k] = grad[nq + n + k];
    e->dEdt[i] = grad[nq + n + nu];
}

/* x - (t[0] + ... + t[k-1]), the operands combined as they become ready:
 * the two with the least height (expr.h) first, x with a sum of terms by
 * a subtraction, until one is left (Huffman's merge, with the greater
 * height for the sum of weights).  The solve is a chain of dependent
 * steps, and each step then waits only one operation for its latest term
 * (the last pivot's), where a balanced tree waited log k and a chain k:
 * latency, not operation count, is what the unrolled solve costs.  Ties
 * keep the terms' order, so the result is deterministic.  t is reordered. */
typedef struct Ready {
    ExprId e;
    uint32_t height;
    int sign; /* +1 for x and what x is in, -1 for a sum of terms */
} Ready;

static Ready
ready(ExprPool *P, ExprId e, int sign)
{
    return (Ready){e, expr_node(P, e)->height, sign};
}

static int
ready_cmp(const void *pa, const void *pb)
{
    const Ready *a = pa, *b = pb;
    if (a->height != b->height)
        return a->height < b->height ? -1 : 1;
    return a->e < b->e ? -1 : a->e > b->e; /* ids: a total, deterministic order */
}

static ExprId
minus_sum(ExprPool *P, ExprId x, ExprId *t, int k)
{
    if (k == 0)
        return x;
    /* the operands sorted by height in q[0..k], the merged ones in m[]:
     * a merge is at least as high as the one before it, so the lower of
     * the two fronts is always the lowest left */
    Ready *q = xmalloc(2 * ((size_t)k + 1) * sizeof *q), *m = q + k + 1;
    for (int i = 0; i < k; i++)
        q[i] = ready(P, t[i], -1);
    q[k] = ready(P, x, 1);
    qsort(q, (size_t)k + 1, sizeof *q, ready_cmp);
    int qi = 0, mi = 0, mn = 0;
    for (int left = k + 1; left > 1; left--) {
        Ready r[2];
        for (int j = 0; j < 2; j++)
            r[j] = qi <= k && (mi == mn || q[qi].height <= m[mi].height) ? q[qi++] : m[mi++];
        if (r[0].sign < 0 && r[1].sign < 0)
            m[mn++] = ready(P, expr_add(P, r[0].e, r[1].e), -1);
        else if (r[0].sign > 0)
            m[mn++] = ready(P, expr_sub(P, r[0].e, r[1].e), 1);
        else
            m[mn++] = ready(P, expr_sub(P, r[1].e, r[0].e), 1);
    }
    ExprId sum = m[mn - 1].e;
    free(q);
    return sum;
}

/* LDL^T of the symmetric M, then a = -L^-T D^-1 L^-1 h:
 *   d_j = M_jj - sum_k<j e_jk^2 / d_k,   e_ik = L_ik d_k
 *   L_ij = (M_ij - sum_k<j L_ik e_jk) / d_j          (i > j)
 * One reciprocal per pivot; everything else multiplies.  Row and column j
 * of the factored matrix are coordinate ord[j] = n-1-j: the last
 * coordinates of a chain or tree have the simplest entries (for a chain
 * M_nn is a constant), so the first pivots are ready early. */
static void ldl_solve(const Eom *e, Arena *A, ExprPool *P, const ExprId *b, int neg, ExprId *x);

static void
derive_solve(Eom *e, Arena *A, ExprPool *P)
{
    int n = e->n;
    ExprId *L = arena_new_array(A, ExprId, n * n), *E = arena_new_array(A, ExprId, n * n);
    ExprId *inv = arena_new_array(A, ExprId, n), *t = arena_new_array(A, ExprId, n);
    int *ord = arena_new_array(A, int, n);
    for (int j = 0; j < n; j++)
        ord[j] = n - 1 - j;
#define MO(i, j) e->M[ord[i] * n + ord[j]]
    e->acc = arena_new_array(A, ExprId, n);
    e->piv = arena_new_array(A, ExprId, n);
    e->mkk = arena_new_array(A, ExprId, n);
    for (int j = 0; j < n; j++) {
        /* L_jk e_jk as e_jk^2 / d_k: the square is ready before the
         * reciprocal, and the pivots' chain, the longest in the solve,
         * waits one multiplication after each division, not two */
        for (int k = 0; k < j; k++)
            t[k] = expr_mul(P, expr_mul(P, E[j * n + k], E[j * n + k]), inv[k]);
        ExprId d = minus_sum(P, MO(j, j), t, j);
        e->piv[ord[j]] = d;
        e->mkk[ord[j]] = MO(j, j);
        inv[j] = expr_div(P, EXPR_ONE, d);
        for (int i = j + 1; i < n; i++) {
            for (int k = 0; k < j; k++)
                t[k] = expr_mul(P, L[i * n + k], E[j * n + k]);
            ExprId s = minus_sum(P, MO(i, j), t, j);
            E[i * n + j] = s; /* = L_ij d_j */
            L[i * n + j] = expr_mul(P, s, inv[j]);
        }
    }
#undef MO
    e->ldl_L = L, e->ldl_inv = inv, e->ldl_ord = ord;
    ldl_solve(e, A, P, e->h, 1, e->acc);
}

/* x = M^-1 b (neg: -b) by derive_solve's factors: L y = b, then L^T x =
 * D^-1 y, in the factorization's order; b and x by coordinate. */
static void
ldl_solve(const Eom *e, Arena *A, ExprPool *P, const ExprId *b, int neg, ExprId *x)
{
    int n = e->n;
    const ExprId *L = e->ldl_L, *inv = e->ldl_inv;
    const int *ord = e->ldl_ord;
    ExprId *y = arena_new_array(A, ExprId, n), *z = arena_new_array(A, ExprId, n);
    ExprId *t = arena_new_array(A, ExprId, n);
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < i; k++)
            t[k] = expr_mul(P, L[i * n + k], y[k]);
        ExprId bi = b[ord[i]];
        y[i] = minus_sum(P, neg ? expr_neg(P, bi) : bi, t, i);
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int k = i + 1; k < n; k++)
            t[k - i - 1] = expr_mul(P, L[k * n + i], z[k]);
        z[i] = minus_sum(P, expr_mul(P, y[i], inv[i]), t, n - 1 - i);
        x[ord[i]] = z[i];
    }
}

/* What derive_solve would print, from M's structural zeros: the
 * multiplications of the factorization and the two solves, fill-in
 * included (an upper bound: the DAG may cancel more).  In derive_solve's
 * order, leaves first, a tree's M (M_ij = 0 unless one turn is above the
 * other) has no fill-in: this is the branch-induced sparsity of
 * Featherstone's LTDL factorization.  on_ij[i * n + j]: M_ij may be
 * nonzero; nz is scratch for n * words. */
static long
solve_ops(int n, const unsigned char *on_ij, uint64_t *nz)
{
    int words = (n + 63) / 64;
    long ops = 0;
#define NZ(i, k) (nz[(size_t)(i) * (size_t)words + (size_t)(k) / 64] >> ((k) % 64) & 1)
    memset(nz, 0, (size_t)n * (size_t)words * sizeof *nz);
    for (int i = 0; i < n; i++) /* row i of L, in elimination order: column j < i */
        for (int j = 0; j < i; j++) {
            int on = on_ij[(n - 1 - i) * n + (n - 1 - j)];
            for (int w = 0; w <= j / 64; w++) { /* k < j (row j has no other) */
                uint64_t both = nz[(size_t)i * words + w] & nz[(size_t)j * words + w];
                on |= both != 0;
                for (; both; both &= both - 1) /* one multiplication per k */
                    ops++;
            }
            if (on)
                nz[(size_t)i * words + j / 64] |= 1ull << (j % 64);
        }
    for (int i = 0; i < n; i++) /* the pivots' sums and the two solves */
        for (int k = 0; k < i; k++)
            ops += 3 * (int)NZ(i, k);
#undef NZ
    return ops;
}

/* M's structural nonzeros as a tree, for LTDL (which eliminates the last
 * coordinate first): parent[i] = the last j < i with M_ij not
 * structurally 0 once the elimination's fill-in is counted (eliminating i
 * couples every pair of the j < i it is coupled to: a free body's
 * translations, uncoupled among themselves but each coupled to its
 * rotations, become a chain).  Then every j < i that row i holds is on
 * the way from i to its root, and LTDL keeps to that pattern.  The tree
 * when LTDL's work (about half the sum of the squared depths) is at most
 * half a dense factorization's (n^3/6); else NULL. */
static int *
mass_tree(const Eom *e, Arena *A)
{
    int n = e->n;
    int *parent = arena_new_array(A, int, n), *depth = arena_new_array(A, int, n);
    unsigned char *on = xmalloc((size_t)n * (size_t)n); /* [i * n + j], j < i */
    for (int i = 0; i < n; i++)
        for (int j = 0; j < i; j++)
            on[i * n + j] = e->M[i * n + j] != EXPR_ZERO;
    for (int i = n - 1; i >= 0; i--) /* the fill of eliminating i */
        for (int a = 0; a < i; a++)
            for (int b = 0; on[i * n + a] && b < a; b++)
                on[a * n + b] |= on[i * n + b];
    long work = 0;
    for (int i = 0; i < n; i++) {
        parent[i] = -1;
        for (int j = i - 1; j >= 0 && parent[i] < 0; j--)
            if (on[i * n + j])
                parent[i] = j;
        depth[i] = parent[i] < 0 ? 0 : depth[parent[i]] + 1;
        work += (long)depth[i] * depth[i];
    }
    free(on);
    return work <= (long)n * n * n / 6 ? parent : NULL;
}

Eom *
eom_derive(const Spec *s, const Mech *m, const Form *f, Arena *A,
           ExprPool *P, Diff *D, const char **why)
{
    if (m->speeds && !f->speeds) {
        *why = "its equations are in the coordinates' rates, and a quaternion here has speeds "
               "(its angular velocity); gibbs-appell and the recursive forms take them";
        return NULL;
    }
    ExprId *E = f->residual(m, A, P, D, why);
    if (!E)
        return NULL;
    int n = m->n;
    Eom *e = arena_alloc(A, sizeof *e);
    *e = (Eom){.n = n, .nq = m->nq, .nu = s->nu, .form = f, .E = E, .ldl_loads = 1};
    for (int k = 0; k < s->nfquat; k++) /* (lower.c's held_rows: the recursion's alone) */
        e->ldl_loads &= s->fquat[k].speed >= 0;
    if (!f->solve) /* else only on demand (eom_mass): a recursion never needs it */
        eom_mass(e, m, A, P, D);
    /* h = E at q'' = 0: substitution rebuilds only what depends on q'' */
    e->h = arena_new_array(A, ExprId, n);
    ExprId *zeros = arena_new_array(A, ExprId, n);
    for (int j = 0; j < n; j++)
        zeros[j] = EXPR_ZERO;
    expr_subst_many(P, n, E, n, m->q[2], zeros, e->h);
    if (f->solve) {
        e->acc = arena_new_array(A, ExprId, n);
        e->piv = arena_new_array(A, ExprId, n);
        e->mkk = arena_new_array(A, ExprId, n);
        f->solve(m, A, P, D, NULL, e->acc, e->piv, e->mkk);
    } else if (n <= EOM_SOLVE_MAX) {
        derive_solve(e, A, P);
    } else {
        uint64_t *nz = xmalloc((size_t)n * (size_t)((n + 63) / 64) * sizeof *nz);
        unsigned char *on = xmalloc((size_t)n * (size_t)n);
        for (int i = 0; i < n * n; i++)
            on[i] = e->M[i] != EXPR_ZERO;
        if (solve_ops(n, on, nz) <= EOM_SPARSE_SOLVE_MAX)
            derive_solve(e, A, P);
        free(on);
        free(nz);
    }
    /* M's tree, where it has one: the runtime's own factorizations of M
     * (the solve where accel is not generated, and the Jacobian's columns
     * always) keep its sparsity */
    if (!f->solve)
        e->mass_parent = mass_tree(e, A);
    return e;
}

void
eom_derive_jacobian(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    if (e->dEdq)
        return;
    int n = e->n, nq = e->nq, nu = e->nu, nl = nq + n + nu + 1;
    e->dEdq = arena_new_array(A, ExprId, n * nq);
    e->dEdv = arena_new_array(A, ExprId, n * n);
    e->dEdu = arena_new_array(A, ExprId, n * nu + 1);
    e->dEdt = arena_new_array(A, ExprId, n);
    ExprId *leaves = arena_new_array(A, ExprId, nl);
    ExprId *grad = arena_new_array(A, ExprId, nl);
    for (int j = 0; j < nq; j++)
        leaves[j] = m->q[0][j];
    for (int j = 0; j < n; j++)
        leaves[nq + j] = m->q[1][j];
    for (int k = 0; k < nu; k++)
        leaves[nq + n + k] = expr_input(P, k);
    leaves[nq + n + nu] = expr_time(P);
    for (int i = 0; i < n; i++)
        derive_row(e, D, leaves, grad, i);
    ExprId *seed = arena_new_array(A, ExprId, nq > n ? nq : n);
    e->jvp_q = arena_new_array(A, ExprId, n);
    e->jvp_v = arena_new_array(A, ExprId, n);
    for (int j = 0; j < nq; j++)
        seed[j] = expr_seed(P, j, 0);
    diff_jvp(D, n, e->E, nq, m->q[0], seed, e->jvp_q);
    for (int j = 0; j < n; j++)
        seed[j] = expr_seed(P, j, 1);
    diff_jvp(D, n, e->E, n, m->q[1], seed, e->jvp_v);
}

/* The default form: the one whose right-hand side costs the fewest
 * operations (eom_cost) among those that apply (eom.h), the first in --form's
 * order on a tie.  Elimination (maggi) is a way of handling constraints,
 * not a form, so it is not a candidate.  On a tree of more than
 * EOM_SOLVE_MAX coordinates only the recursive forms are: the energy
 * forms' M and h alone already cost more than the articulated-body solve
 * there (measured on specs/gen_tree.sh 5 to 30: tree 10's Lagrange M and
 * h 17 299 operations, its whole articulated-body solve 13 633), and the
 * runtime would factor their M besides.  Writes the reason to why. */
Eom *
eom_derive_cheapest(const Spec *s, const Mech *m, int nc, int loads, int series, Arena *A,
                    ExprPool *P, Diff *D, char *why, size_t len)
{
    enum { NFORMS_MAX = 16 };
    Eom *e[NFORMS_MAX];
    long cost[NFORMS_MAX];
    int nf = 0, best = -1, n = m->n;
    /* On a large tree a form that factors M pays at least the dense
     * factorization, unless M's tree pattern (M_ij != 0 only where one
     * joint is above the other) makes the unrolled solve short: priced
     * from the tree, it is not derived where the articulated-body solve
     * already costs less (deriving Newton-Euler's M of a 600-coordinate
     * tree takes seconds and hundreds of megabytes, for nothing). */
    long dense = EOM_DENSE_WEIGHT * ((long)n * n * n / 3 + 2L * n * n), ab = -1;
    const char *priced = NULL;
    Eom *x = NULL; /* the articulated-body form, derived first here */
    if (!nc && m->tree && n > EOM_SOLVE_MAX) {
        const char *no;
        x = eom_derive(s, m, &form_articulated, A, P, D, &no);
        ab = x ? eom_cost(x, m, nc, loads, A, P, D) : -1;
        if (ab >= 0 && dense > ab) {
            const Tree *t = m->tree;
            unsigned char *on = xmalloc((size_t)n * (size_t)n);
            uint64_t *nz = xmalloc((size_t)n * (size_t)((n + 63) / 64) * sizeof *nz);
            memset(on, 0, (size_t)n * (size_t)n);
            for (int k = 0; k < t->nturns; k++)
                for (int a = k; a >= 0; a = t->turn[a].up)
                    for (int dk = 0; dk < t->turn[k].ndof; dk++)
                        for (int da = 0; da < t->turn[a].ndof; da++) {
                            int i = t->turn[k].qc[dk], j = t->turn[a].qc[da];
                            on[i * n + j] = on[j * n + i] = 1;
                        }
            if (solve_ops(n, on, nz) > EOM_SPARSE_SOLVE_MAX)
                priced = "newton-euler";
            free(nz);
            free(on);
        }
    }
    for (int k = 0; form_at(k) && nf < NFORMS_MAX; k++) {
        const Form *f = form_at(k);
        const char *no;
        if (f->eliminate || (m->tree && m->n > EOM_SOLVE_MAX && !f->mass))
            continue;
        if (priced && !strcmp(f->name, priced))
            continue;
        if (f == &form_articulated && x) {
            e[nf] = x, cost[nf] = ab;
            nf++;
            continue;
        }
        if (!(e[nf] = eom_derive(s, m, f, A, P, D, &no)))
            continue;
        cost[nf] = eom_cost(e[nf], m, nc, loads, A, P, D);
        nf++;
    }
    /* a form with a recursion of its own computes M by columns: it has no
     * series, so where Taylor's are asked the cheapest with them is taken,
     * if one applies */
    int with = -1;
    for (int k = 0; k < nf; k++) {
        if (best < 0 || cost[k] < cost[best])
            best = k;
        if (!e[k]->form->solve && (with < 0 || cost[k] < cost[with]))
            with = k;
    }
    int skip = series && with >= 0 && with != best;
    if (skip)
        best = with;
    if (best < 0)
        return NULL;
    size_t at = (size_t)snprintf(why, len, "the cheapest that applies: %ld operation%s per "
                                 "right-hand side", cost[best], cost[best] == 1 ? "" : "s");
    for (int k = 0, first = 1; k < nf && at < len; k++)
        if (k != best) {
            at += (size_t)snprintf(why + at, len - at, "%s%s %ld", first ? " (" : ", ",
                                   e[k]->form->name, cost[k]);
            first = 0;
        }
    if (priced && at < len)
        at += (size_t)snprintf(why + at, len - at, "%s%s more than %ld, its dense "
                               "factorization alone", nf > 1 ? ", " : " (", priced, dense);
    if ((nf > 1 || priced) && at < len)
        at += (size_t)snprintf(why + at, len - at, ")");
    if (skip && at < len)
        snprintf(why + at, len - at, "; Taylor's series asked for, which a form that computes M "
                 "by columns of its recursion does not have");
    return e[best];
}

ExprId *
eom_mass(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    if (e->M)
        return e->M;
    int n = e->n;
    const Form *f = e->form;
    e->M = f->mass ? f->mass(m, A, P, D) : arena_new_array(A, ExprId, n * n);
    for (int i = 0; !f->mass && i < n; i++)
        for (int j = 0; j <= i; j++)
            e->M[i * n + j] = e->M[j * n + i] = diff_partial(D, e->E[i], m->q[2][j]);
    return e->M;
}

static long
ops(ExprPool *P, int n, const ExprId *roots)
{
    ExprCount c = expr_count_ops(P, n, roots);
    return c.adds + c.muls + c.divs + c.calls;
}

/* The operations below roots that depend on the seeds: what a load's
 * pass computes when the rest is shared. */
static long
seeded_ops(ExprPool *P, int n, const ExprId *roots)
{
    size_t size = expr_pool_size(P), k = 0;
    unsigned char *mark = xmalloc(size);
    ExprId *nodes = xmalloc(size * sizeof *nodes);
    memset(mark, 0, size);
    expr_mark(P, n, roots, mark);
    for (size_t id = 0; id < size; id++)
        if (mark[id] && expr_op_arity[expr_node(P, (ExprId)id)->op] &&
            (expr_deps(P, (ExprId)id) & DEP_S))
            nodes[k++] = (ExprId)id;
    ExprCount c = expr_count_list(P, k, nodes);
    free(nodes);
    free(mark);
    return c.adds + c.muls + c.divs + c.calls;
}

int
eom_loads(const Eom *e)
{
    return e->acc && (e->form->solve || (e->ldl_L && e->ldl_loads));
}

ExprId *
eom_minv(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    if (e->minv || !eom_loads(e))
        return e->minv;
    int n = e->n;
    ExprId *load = arena_new_array(A, ExprId, n), *piv = arena_new_array(A, ExprId, n);
    ExprId *mkk = arena_new_array(A, ExprId, n);
    e->minv = arena_new_array(A, ExprId, n);
    for (int j = 0; j < n; j++)
        load[j] = expr_seed(P, j, 2);
    if (e->form->solve)
        e->form->solve(m, A, P, D, load, e->minv, piv, mkk);
    else
        ldl_solve(e, A, P, load, 0, e->minv);
    return e->minv;
}

long
eom_cost(Eom *e, const Mech *m, int nc, int loads, Arena *A, ExprPool *P, Diff *D)
{
    int n = e->n;
    ExprId *roots = xmalloc((size_t)(n * n + 3 * n + 1) * sizeof *roots);
    long cost;
    if (e->acc && (!nc || (loads && eom_loads(e)))) {
        for (int i = 0; i < n; i++)
            roots[i] = e->acc[i], roots[n + i] = e->piv[i], roots[2 * n + i] = e->mkk[i];
        cost = ops(P, 3 * n, roots);
        if (nc) {
            /* the solve and what minv reads of it (computed once, lower.c's
             * lower_loads_shared), then per row the load's own operations,
             * B M^-1 B^T, its LU, q'' = a - Y lambda */
            ExprId *y = eom_minv(e, m, A, P, D);
            memcpy(roots + 3 * n, y, (size_t)n * sizeof *y);
            cost = ops(P, 4 * n, roots) + (nc - 1) * seeded_ops(P, n, y) +
                   EOM_DENSE_WEIGHT * ((long)nc * nc * n + (long)nc * nc * nc / 3 + 2L * nc * n);
        }
    } else {
        int k = 0;
        eom_mass(e, m, A, P, D);
        for (int i = 0; i < n; i++)
            for (int j = 0; j <= i; j++)
                roots[k++] = e->M[i * n + j];
        for (int i = 0; i < n; i++)
            roots[k++] = e->h[i];
        cost = ops(P, k, roots);
        long N = n + nc; /* LDL^T of M, or LU of the KKT matrix */
        cost += EOM_DENSE_WEIGHT * (nc ? N * N * N / 3 + 2 * N * N : (long)n * n * n / 3 + 2L * n * n);
    }
    free(roots);
    return cost;
}
