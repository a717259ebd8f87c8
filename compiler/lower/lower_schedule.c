/*
 * lower_schedule: a lowered function as the flat list of steps its C runs
 * (lower_schedule.h's LowSched), which the emitter prints and lower_eval evaluates:
 * what is computed is decided once, here, and both follow it.
 *
 * The operator nodes the outputs need are listed depth-first, in output
 * order; the sines and cosines of the angles computed together come
 * first (schedule_angles); then, in a function printed whole, the nodes
 * are reordered by when they could start on a core that runs them out of
 * order (order_by_start).  Each output is stored as soon as its value
 * exists.  Last, the nodes only one branch of a switch needs are moved
 * into blocks that run in that mode alone (guards, flush): a contact's
 * whole share of the forces is computed only while its shapes are near.
 * All cleverness is in the DAG; this is a plain loop.
 */
#include "lower_schedule.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int
lower_computed(ExprPool *P, const LowFunc *f, ExprId e)
{
    return expr_op_arity[expr_node(P, e)->op] > 0 && !(f->shared && f->shared[e] >= 0) &&
           !(f->derived && f->derived[e] >= 0);
}

/* The schedule being built: the operator nodes in order, and per node id
 * its place among them (-1: not scheduled). */
typedef struct Build {
    ExprPool *P;
    const LowFunc *f;
    LowSched *S;
    ExprId *node;
    int n;
    int *place;
    int *after; /* per output: nodes listed before its store */
    int *order; /* the outputs in store order (NULL: as listed) */
} Build;

static int
is_input(const Build *b, ExprId e)
{
    return !lower_computed(b->P, b->f, e);
}

/* Append the unscheduled operator nodes that root needs, operands first. */
static void
schedule_tree(Build *b, ExprId root)
{
    size_t cap = 64, sp = 0;
    struct { ExprId id; int expanded; } *stack = xmalloc(cap * sizeof *stack);
    stack[sp].id = root;
    stack[sp++].expanded = 0;
    while (sp) {
        ExprId e = stack[sp - 1].id;
        const ExprNode *nd = expr_node(b->P, e);
        if (is_input(b, e) || b->place[e] >= 0) {
            sp--;
        } else if (stack[sp - 1].expanded) {
            sp--;
            b->place[e] = b->n;
            b->node[b->n++] = e;
        } else {
            stack[sp - 1].expanded = 1;
            if (sp + 2 >= cap)
                stack = xrealloc(stack, (cap *= 2) * sizeof *stack);
            int ar = expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            for (int k = ar - 1; k >= 0; k--) { /* operand a comes first */
                stack[sp].id = ops[k];
                stack[sp++].expanded = 0;
            }
        }
    }
    free(stack);
}

/* The sines and cosines whose angles need no other sine or cosine (a
 * turn's coordinate, a sum of coordinates) come first, all computed by one
 * call of eomc_sincos (eomc_model.h), which computes several at once
 * where the machine has vector instructions for it: each angle's
 * operations, then the angles' sines and cosines.  Fewer than
 * ANGLES_MIN angles keep their own sin and cos calls. */
enum { ANGLES_MIN = 2 };

static void
schedule_angles(Build *b)
{
    ExprPool *P = b->P;
    LowSched *S = b->S;
    int nout = b->f->nout;
    const LowSlot *out = b->f->out;
    size_t size = expr_pool_size(P);
    /* per node: 0 unseen, 1 seen, no sine or cosine in it, 2 one in it */
    unsigned char *seen = xmalloc(size);
    memset(seen, 0, size);
    /* a node is pushed once per edge into it at most: 2 per node (arity <= 2) */
    ExprId *trig = xmalloc(size * sizeof *trig), *stack = xmalloc((2 * size + 1) * sizeof *stack);
    size_t ntrig = 0;
    for (int i = 0; i < nout; i++) { /* post-order, iteratively: DAGs are deep */
        size_t sp = 0;
        if (!seen[out[i].e])
            stack[sp++] = out[i].e;
        while (sp) {
            ExprId e = stack[sp - 1];
            const ExprNode *nd = expr_node(P, e);
            int ar = is_input(b, e) ? 0 : expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            int pushed = 0;
            for (int k = ar - 1; k >= 0; k--)
                if (!seen[ops[k]])
                    stack[sp++] = ops[k], pushed = 1;
            if (pushed)
                continue;
            sp--;
            if (seen[e])
                continue;
            int below = 0;
            for (int k = 0; k < ar; k++)
                below |= seen[ops[k]] == 2;
            int is_trig = ar && (nd->op == EXPR_SIN || nd->op == EXPR_COS);
            if (is_trig && !below)
                trig[ntrig++] = e;
            seen[e] = below || is_trig ? 2 : 1;
        }
    }
    /* the angles, in order of first use; each one's sine and cosine, */
    S->angle = xmalloc((ntrig + 1) * sizeof *S->angle);
    ExprId(*pair)[2] = xmalloc((ntrig + 1) * sizeof *pair);
    int na = 0;
    for (size_t t = 0; t < ntrig; t++) {
        const ExprNode *nd = expr_node(P, trig[t]);
        int j = 0;
        while (j < na && S->angle[j] != nd->a)
            j++;
        if (j == na) {
            S->angle[na] = nd->a;
            pair[na][0] = pair[na][1] = EXPR_NONE;
            na++;
        }
        pair[j][nd->op == EXPR_COS] = trig[t];
    }
    /* then by height, stably: the vector of the angles ready first does
     * not wait for the last one (a chain's sum of all its coordinates) */
    for (int j = 1; j < na; j++)
        for (int k = j; k > 0 && expr_node(P, S->angle[k - 1])->height >
                                     expr_node(P, S->angle[k])->height; k--) {
            ExprId a = S->angle[k], p0 = pair[k][0], p1 = pair[k][1];
            S->angle[k] = S->angle[k - 1], pair[k][0] = pair[k - 1][0];
            pair[k][1] = pair[k - 1][1];
            S->angle[k - 1] = a, pair[k - 1][0] = p0, pair[k - 1][1] = p1;
        }
    S->nangle = 0;
    S->angles = S->angles_end = b->n;
    S->angle_of = NULL;
    if (na >= ANGLES_MIN) {
        S->nangle = na;
        for (int j = 0; j < na; j++)
            schedule_tree(b, S->angle[j]);
        S->angles = b->n;
        S->angle_of = xmalloc(2 * (size_t)na * sizeof *S->angle_of);
        for (int j = 0; j < na; j++)
            for (int k = 0; k < 2; k++)
                if (pair[j][k] != EXPR_NONE) {
                    S->angle_of[b->n - S->angles] = 2 * j + k;
                    b->place[pair[j][k]] = b->n;
                    b->node[b->n++] = pair[j][k];
                }
        S->angles_end = b->n;
    }
    free(pair);
    free(trig);
    free(stack);
    free(seen);
}

/* Latencies in cycles on a current x86-64 core (an addition or a
 * multiplication 3 to 4, a division 13 to 15, a libm call some 20): only
 * their ratios matter. */
enum { LAT_ADD = 3, LAT_MUL = 3, LAT_DIV = 13, LAT_CALL = 20 };

static int
latency(int op)
{
    switch (op) {
    case EXPR_ADD: case EXPR_SUB: case EXPR_NEG: return LAT_ADD;
    case EXPR_MUL: case EXPR_POWI: return LAT_MUL; /* powi 2: x * x, the most common */
    case EXPR_DIV: return LAT_DIV;
    default: return LAT_CALL;
    }
}

typedef struct Start {
    int at, k; /* the cycle a node could start, its place depth-first */
} Start;

static int
start_cmp(const void *pa, const void *pb)
{
    const Start *a = pa, *b = pb;
    return a->at != b->at ? (a->at > b->at) - (a->at < b->at) : (a->k > b->k) - (a->k < b->k);
}

/* A core runs instructions out of order, but only within a window of a
 * few hundred after the oldest one it waits on.  Depth-first, a solve's
 * chain of dependent pivots comes first and fills that window, and the
 * independent work printed after it (the bias's terms) waits behind it.
 * So the nodes after the angles are listed in the order they could
 * start, by the latencies above, depth-first order breaking ties (a
 * topological order still: a node starts after its operands); each
 * output is stored when its value is done.  The angles' sines and
 * cosines count as ready at the start, as the leaves: counting their
 * call's latency put the work that needs none of them first, which
 * measured slower (chain 5: 80 against 77 ns).  Chain 5's right-hand
 * side: 80 -> 75 ns.  Only for a function printed whole: a cut one keeps
 * its parts depth-first, which keeps the values they share few. */
static void
order_by_start(Build *b)
{
    ExprPool *P = b->P;
    const LowSched *S = b->S;
    int nout = b->f->nout;
    const LowSlot *out = b->f->out;
    int n = b->n, from = S->angles_end;
    int *done = xmalloc(((size_t)n + 1) * sizeof *done);
    Start *st = xmalloc(((size_t)n + 1) * sizeof *st);
    for (int k = 0; k < n; k++) {
        const ExprNode *nd = expr_node(P, b->node[k]);
        int at = 0;
        if (k >= S->angles && k < S->angles_end) {
            done[k] = 0;
        } else {
            int ar = expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            for (int j = 0; j < ar; j++) {
                int t = is_input(b, ops[j]) ? -1 : b->place[ops[j]];
                if (t >= 0 && done[t] > at)
                    at = done[t];
            }
            done[k] = at + latency(nd->op);
        }
        st[k] = (Start){at, k};
    }
    qsort(st + from, (size_t)(n - from), sizeof *st, start_cmp);
    ExprId *node = xmalloc(((size_t)n + 1) * sizeof *node);
    for (int k = from; k < n; k++)
        node[k] = b->node[st[k].k];
    for (int k = from; k < n; k++) {
        b->node[k] = node[k];
        b->place[node[k]] = k;
    }
    /* an output's store when its value is done, by the same order: after
     * the nodes that could start before, its place depth-first breaking
     * ties (a leaf's: done at once) */
    Start *os = xmalloc(((size_t)nout + 1) * sizeof *os);
    for (int i = 0; i < nout; i++) {
        int t = is_input(b, out[i].e) ? -1 : b->place[out[i].e];
        Start key = {t < 0 ? 0 : done[t >= from ? st[t].k : t], b->after[i]};
        int lo = from, hi = n; /* the first node after key */
        while (lo < hi) {
            int mid = lo + (hi - lo) / 2;
            if (start_cmp(&st[mid], &key) < 0)
                lo = mid + 1;
            else
                hi = mid;
        }
        if (t >= 0 && lo <= t)
            lo = t + 1;
        os[i] = (Start){lo < S->angles_end ? S->angles_end : lo, i};
    }
    qsort(os, (size_t)nout, sizeof *os, start_cmp);
    b->order = xmalloc(((size_t)nout + 1) * sizeof *b->order);
    for (int i = 0; i < nout; i++) {
        b->order[i] = os[i].k;
        b->after[os[i].k] = os[i].at;
    }
    free(os);
    free(node);
    free(st);
    free(done);
}

/* (a block's tests are a few steps or many: the list grows) */
static void
add_test(LowSched *S, int kind, ExprId id, int i, int branch)
{
    if (S->nstep == S->cap)
        S->step = xrealloc(S->step, (size_t)(S->cap = 2 * S->cap + 64) * sizeof *S->step);
    S->step[S->nstep++] = (LowStep){kind, id, i, branch};
}

static void
add_step(LowSched *S, int kind, ExprId id, int i)
{
    add_test(S, kind, id, i, 0);
}

/* ---- lazy branches ---- */

/* A node's guard is the set of (switch, branch) under whose SELECTs its
 * uses lie, each written 2 k + branch, sorted: it is computed in a block
 * that runs where any of them holds.  A node read under more than this
 * many is computed in every mode: the block's test reads each mode, and a
 * value that so many switches need (a body's pose, in most of a robot's
 * contact pairs) is needed most of the time anyway.  (Measured on MuJoCo's
 * humanoid, 150 pairs, all apart: 16 run 9 % more instructions than 64.) */
enum { GUARD_MAX = 64 };
enum { G_UNSET = 0, G_TOP = -1 }; /* a guard's size, besides 1 .. GUARD_MAX */

/* A guard: its size and where its switches start in the guards' one
 * array (Guards.k): a node takes its user's guard as it is, and only a
 * union makes a new one. */
typedef struct Guard {
    int n; /* G_UNSET, G_TOP or the size */
    int off;
} Guard;

typedef struct Guards {
    Guard *g; /* by place */
    int *k;
    size_t len, cap;
} Guards;

static Guard
guard_new(Guards *G, const int *k, int n)
{
    if (G->len + (size_t)n > G->cap) {
        G->cap = 2 * (G->len + (size_t)n) + 64;
        G->k = xrealloc(G->k, G->cap * sizeof *G->k);
    }
    memcpy(G->k + G->len, k, (size_t)n * sizeof *k);
    Guard g = {n, (int)G->len};
    G->len += (size_t)n;
    return g;
}

/* The union of guards a and b; G_TOP past GUARD_MAX, or where it holds
 * both modes of one switch (it always holds). */
static Guard
guard_join(Guards *G, Guard a, Guard b)
{
    if (a.n == G_TOP || b.n == G_TOP)
        return (Guard){G_TOP, 0};
    int u[2 * GUARD_MAX], n = 0, i = 0, j = 0;
    const int *x = G->k + a.off, *y = G->k + b.off;
    while (i < a.n || j < b.n) {
        if (j >= b.n || (i < a.n && x[i] < y[j]))
            u[n++] = x[i++];
        else if (i >= a.n || y[j] < x[i])
            u[n++] = y[j++];
        else /* in both */
            u[n++] = x[i++], j++;
    }
    if (n > GUARD_MAX)
        return (Guard){G_TOP, 0};
    for (int i = 1; i < n; i++)
        if (u[i] == (u[i - 1] | 1) && u[i - 1] % 2 == 0) /* both modes of one switch */
            return (Guard){G_TOP, 0};
    if (n == a.n)
        return a;
    if (n == b.n)
        return b;
    return guard_new(G, u, n);
}

static int
guard_same(const Guards *G, Guard a, Guard b)
{
    return a.n == b.n &&
           (a.n <= 0 || a.off == b.off ||
            !memcmp(G->k + a.off, G->k + b.off, (size_t)a.n * sizeof *G->k));
}

/* Each scheduled node's guard (by its place), from its uses: the
 * outputs' and the angles' (computed at once, first) are G_TOP; the
 * operand in branch a (b) of a SELECT on k that is G_TOP is read under
 * {2 k + 1} ({2 k}); any other operand under its user's guard (a
 * SELECT under a guard is its guard's: blocks do not nest).  In reverse
 * order every use of a node is seen before it.  lazy 0: all G_TOP. */
static void
guards(const Build *b, int lazy, Guards *G)
{
    ExprPool *P = b->P;
    Guard *g = G->g = xmalloc(((size_t)b->n + 1) * sizeof *g);
    G->k = NULL, G->len = G->cap = 0;
    for (int k = 0; k < b->n; k++)
        g[k].n = lazy ? G_UNSET : G_TOP;
    for (int i = 0; i < b->f->nout; i++)
        if (!is_input(b, b->f->out[i].e))
            g[b->place[b->f->out[i].e]].n = G_TOP;
    for (int k = b->n - 1; k >= 0; k--) {
        ExprId e = b->node[k];
        const ExprNode *nd = expr_node(P, e);
        if (k < b->S->angles_end || g[k].n == G_UNSET)
            g[k].n = G_TOP;
        ExprId ops[2] = {nd->a, nd->b};
        for (int j = 0; j < expr_op_arity[nd->op]; j++) {
            if (is_input(b, ops[j]))
                continue;
            Guard use = g[k], *o = &g[b->place[ops[j]]];
            if (nd->op == EXPR_SELECT && use.n == G_TOP) {
                int t = 2 * expr_select_mode(P, e) + (j == 0);
                use = guard_new(G, &t, 1);
            }
            *o = o->n == G_UNSET ? use : guard_join(G, *o, use);
        }
    }
}

/* The steps being listed: the guarded nodes, listed per switch in
 * their guard in schedule order, each listed by the first SELECT on
 * one of them that comes once its operands are computed. */
typedef struct Lazy {
    const Build *b;
    Guards G;
    const Guard *g;            /* G.g: by place */
    unsigned char *done;       /* per node id: listed */
    struct Pending {
        int *at; /* places */
        int n, cap;
    } *pend; /* per switch */
    int *taken, *at2;          /* scratch: the places a flush lists, by group */
    int *grp, *cnt;            /* scratch: a flush's groups, their sizes */
    struct Pending *sel;       /* per switch: the places of its G_TOP SELECTs */
    int *stamp, flushes;       /* by place: the flush that could not pull it */
    ExprId *stack;             /* scratch: pull's */
} Lazy;

static int
ready(const Lazy *z, ExprId e)
{
    const ExprNode *nd = expr_node(z->b->P, e);
    ExprId ops[2] = {nd->a, nd->b};
    for (int j = 0; j < expr_op_arity[nd->op]; j++)
        if (!z->done[ops[j]] && !is_input(z->b, ops[j]))
            return 0;
    return 1;
}

static void
add_block(Lazy *z, Guard g, const int *at, int n, int k_else, const int *at2, int n2)
{
    LowSched *S = z->b->S;
    const int *t = z->G.k + g.off;
    for (int c = 0; c < g.n; c++)
        add_test(S, c ? LOW_STEP_OR : LOW_STEP_IF, EXPR_NONE, t[c] / 2, t[c] % 2);
    for (int j = 0; j < n; j++)
        add_step(S, LOW_STEP_NODE, z->b->node[at[j]], 0);
    if (n2) {
        add_step(S, LOW_STEP_ELSE, EXPR_NONE, k_else);
        for (int j = 0; j < n2; j++)
            add_step(S, LOW_STEP_NODE, z->b->node[at2[j]], 0);
    }
    add_step(S, LOW_STEP_END, EXPR_NONE, t[0] / 2);
}

/* G_TOP node e listed now, with the G_TOP operands it needs first:
 * what a block reads that the schedule would reach only later (a body's
 * Jacobian on a coordinate whose turn comes after).  Not a SELECT, nor
 * anything that reads one: a SELECT lists its own blocks first.  1 if
 * e is listed (or needs no listing). */
static int
pull(Lazy *z, ExprId root)
{
    const Build *b = z->b;
    size_t sp = 0;
    z->stack[sp++] = root;
    while (sp) {
        ExprId e = z->stack[sp - 1];
        if (z->done[e] || is_input(b, e)) {
            sp--;
            continue;
        }
        const ExprNode *nd = expr_node(b->P, e);
        if (z->stamp[b->place[e]] == z->flushes || z->g[b->place[e]].n != G_TOP ||
            nd->op == EXPR_SELECT) {
            for (size_t i = 0; i < sp; i++) /* it, and what waits on it, cannot come now */
                z->stamp[b->place[z->stack[i]]] = z->flushes;
            return 0;
        }
        ExprId ops[2] = {nd->a, nd->b};
        int pushed = 0;
        for (int j = expr_op_arity[nd->op] - 1; j >= 0; j--)
            if (!z->done[ops[j]] && !is_input(b, ops[j]))
                z->stack[sp++] = ops[j], pushed = 1;
        if (pushed)
            continue;
        sp--;
        add_step(b->S, LOW_STEP_NODE, e, 0);
        z->done[e] = 1;
    }
    return 1;
}

/* The guarded nodes whose guard holds switch k and that can run now,
 * as blocks, one per guard: all of them, not only those the schedule
 * has reached (a pair's share on each coordinate, in one block); a node
 * whose operands are not all computed yet waits for a later SELECT (the
 * one that needs it comes after them).  The blocks of {k on} and {k
 * off} are one, its two branches. */
static void
flush(Lazy *z, int k)
{
    const Build *b = z->b;
    struct Pending *p = &z->pend[k];
    int n = 0, kept = 0;
    z->flushes++;
    for (int j = 0; j < p->n; j++) { /* the G_TOP values they read, first */
        const ExprNode *nd = expr_node(b->P, b->node[p->at[j]]);
        ExprId ops[2] = {nd->a, nd->b};
        for (int i = 0; !z->done[b->node[p->at[j]]] && i < expr_op_arity[nd->op]; i++)
            if (is_input(b, ops[i]) || z->g[b->place[ops[i]]].n == G_TOP)
                (void)pull(z, ops[i]);
    }
    for (int j = 0; j < p->n; j++) {
        int at = p->at[j];
        ExprId e = b->node[at];
        if (z->done[e])
            continue; /* listed through another switch of its guard */
        if (ready(z, e)) {
            z->taken[n++] = at;
            z->done[e] = 1;
        } else {
            p->at[kept++] = at;
        }
    }
    p->n = kept;
    if (!n)
        return;
    /* one block per guard, the guards' nodes in schedule order; wider
     * guards first: a node reads only nodes whose guards hold its own
     * (a guard is the union of its uses'), so never a narrower one's,
     * and two guards of one width do not read each other */
    int *grp = z->grp, ngrp = 0, *cnt = z->cnt, *at = z->at2;
    for (int i = 0; i < n; i++) {
        int c = 0;
        while (c < ngrp && !guard_same(&z->G, z->g[grp[c]], z->g[z->taken[i]]))
            c++;
        if (c == ngrp)
            grp[ngrp] = z->taken[i], cnt[ngrp++] = 0;
        cnt[c]++;
    }
    for (int i = 1; i < ngrp; i++) /* by width, then first place: stable, few */
        for (int j = i; j > 0 && z->g[grp[j - 1]].n < z->g[grp[j]].n; j--) {
            int t = grp[j], c = cnt[j];
            grp[j] = grp[j - 1], cnt[j] = cnt[j - 1];
            grp[j - 1] = t, cnt[j - 1] = c;
        }
    int c_on = -1, c_off = -1;
    for (int c = 0; c < ngrp; c++) {
        Guard g = z->g[grp[c]];
        if (g.n == 1 && z->G.k[g.off] == 2 * k + 1)
            c_on = c;
        if (g.n == 1 && z->G.k[g.off] == 2 * k)
            c_off = c;
    }
    for (int c = 0, from = 0; c < ngrp; c++) { /* each group's places, in order */
        int m = 0;
        for (int i = 0; i < n; i++)
            if (guard_same(&z->G, z->g[z->taken[i]], z->g[grp[c]]))
                at[from + m++] = z->taken[i];
        grp[c] = from; /* now: where its places start in at */
        from += m;
    }
    for (int c = 0; c < ngrp; c++) {
        Guard g = z->g[at[grp[c]]];
        if (c == c_off && c_on >= 0)
            continue; /* the on block's else */
        if (c == c_on && c_off >= 0)
            add_block(z, g, at + grp[c], cnt[c], k, at + grp[c_off], cnt[c_off]);
        else
            add_block(z, g, at + grp[c], cnt[c], k, NULL, 0);
    }
}

static void
pend_add(struct Pending *p, int at)
{
    if (p->n == p->cap)
        p->at = xrealloc(p->at, (size_t)(p->cap = p->cap ? 2 * p->cap : 16) * sizeof *p->at);
    p->at[p->n++] = at;
}

/* Node e in schedule order: left to a block if guarded, else listed,
 * after the blocks of what it takes if it is a SELECT; and after a
 * block, the SELECTs on its switch that can run now, the emitter's
 * assignments in its two branches (a pair's share on each coordinate:
 * apart, only the test of its mode). */
static void
lazy_node(Lazy *z, int at)
{
    ExprId e = z->b->node[at];
    if (z->done[e] || z->g[at].n > 0) /* listed already, or by a SELECT */
        return;
    const ExprNode *nd = expr_node(z->b->P, e);
    int k = nd->op == EXPR_SELECT ? expr_select_mode(z->b->P, e) : -1, before = z->b->S->nstep;
    if (k >= 0 && z->pend[k].n)
        flush(z, k);
    add_step(z->b->S, LOW_STEP_NODE, e, 0);
    z->done[e] = 1;
    if (k < 0 || z->b->S->nstep == before + 1)
        return;
    struct Pending *p = &z->sel[k];
    int kept = 0;
    for (int j = 0; j < p->n; j++) {
        ExprId s = z->b->node[p->at[j]];
        if (z->done[s])
            continue;
        if (ready(z, s)) {
            add_step(z->b->S, LOW_STEP_NODE, s, 0);
            z->done[s] = 1;
        } else {
            p->at[kept++] = p->at[j];
        }
    }
    p->n = kept;
}

LowSched *
lower_schedule(ExprPool *P, const LowFunc *f, int lazy)
{
    size_t size = expr_pool_size(P);
    int nout = f->nout;
    LowSched *S = xmalloc(sizeof *S);
    memset(S, 0, sizeof *S);
    Build b = {P, f, S, xmalloc(size * sizeof *b.node), 0, xmalloc(size * sizeof *b.place),
               xmalloc(((size_t)nout + 1) * sizeof *b.after), NULL};
    for (size_t i = 0; i < size; i++)
        b.place[i] = -1;
    schedule_angles(&b);
    for (int i = 0; i < nout; i++) {
        schedule_tree(&b, f->out[i].e);
        b.after[i] = b.n;
    }
    S->whole = b.n < LOWER_PART_SIZE;
    if (S->whole)
        order_by_start(&b);
    S->nnode = b.n;
    /* the copies' loop, the fills, then the nodes with each store after
     * the nodes listed before it, and the blocks' steps */
    S->cap = LOW_MAX_ARGS + 1 + b.n + nout;
    S->step = xmalloc((size_t)S->cap * sizeof *S->step);
    if (f->copy)
        add_step(S, LOW_STEP_COPIES, EXPR_NONE, 0);
    LowArgs a;
    lower_args(f->sig, &a);
    for (int k = 0; k < a.n - a.nin; k++)
        if (f->fill[k])
            add_step(S, LOW_STEP_FILL, EXPR_NONE, k);
    int nsw = expr_nswitch(P);
    Lazy z = {&b, {0}, NULL, xmalloc(size), xmalloc(((size_t)nsw + 1) * sizeof *z.pend),
              xmalloc(((size_t)b.n + 1) * sizeof *z.taken),
              xmalloc(((size_t)b.n + 1) * sizeof *z.at2), xmalloc(((size_t)b.n + 1) * sizeof *z.grp),
              xmalloc(((size_t)b.n + 1) * sizeof *z.cnt),
              xmalloc(((size_t)nsw + 1) * sizeof *z.sel),
              xmalloc(((size_t)b.n + 1) * sizeof *z.stamp), 0,
              xmalloc((2 * (size_t)b.n + 1) * sizeof *z.stack)};
    guards(&b, lazy, &z.G);
    z.g = z.G.g;
    for (int i = 0; i < b.n; i++)
        z.stamp[i] = -1;
    memset(z.done, 0, size);
    memset(z.pend, 0, ((size_t)nsw + 1) * sizeof *z.pend);
    memset(z.sel, 0, ((size_t)nsw + 1) * sizeof *z.sel);
    for (int j = 0; j < b.n; j++) {
        for (int c = 0; c < z.g[j].n; c++)
            pend_add(&z.pend[z.G.k[z.g[j].off + c] / 2], j);
        if (z.g[j].n == G_TOP && expr_node(P, b.node[j])->op == EXPR_SELECT)
            pend_add(&z.sel[expr_select_mode(P, b.node[j])], j);
    }
    int k = 0;
    for (int j = 0; j < nout; j++) {
        int i = b.order ? b.order[j] : j;
        for (; k < b.after[i]; k++)
            lazy_node(&z, k);
        add_step(S, LOW_STEP_STORE, EXPR_NONE, i);
    }
    for (; k < b.n; k++)
        lazy_node(&z, k);
    for (int j = 0; j < nsw; j++) {
        for (int i = 0; i < z.pend[j].n; i++)
            if (!z.done[b.node[z.pend[j].at[i]]]) /* deferred, and no SELECT took it */
                diag_unreachable();
        free(z.pend[j].at);
        free(z.sel[j].at);
    }
    free(z.pend);
    free(z.sel);
    free(z.stamp);
    free(z.stack);
    free(z.done);
    free(z.taken);
    free(z.at2);
    free(z.grp);
    free(z.cnt);
    free(z.G.g);
    free(z.G.k);
    free(b.node);
    free(b.place);
    free(b.after);
    free(b.order);
    return S;
}

void
lower_sched_free(LowSched *S)
{
    if (!S)
        return;
    free(S->step);
    free(S->angle);
    free(S->angle_of);
    free(S);
}

/* The copies' loop, as the C runs it (the loop the emitter prints): each
 * copy's function on arrays shifted by its dq[c] (u by du[c]); a copy
 * whose seeds are all 0 stores zeros if zero_skip. */
static void
eval_copies(ExprPool *P, const LowFunc *f, const ExprEnv *env, double *const *outs)
{
    LowArgs a;
    lower_args(f->sig, &a);
    if (f->dv) /* env's rates are by leaf, the copies' by slot: no one shift (tests only) */
        diag_unreachable();
    for (int c = 0; c < f->ncopy; c++) {
        int d = f->dq[c];
        ExprEnv ec = *env;
        for (int k = 0; k <= EXPR_MAX_ORDER; k++)
            ec.q[k] = env->q[k] ? env->q[k] + d : NULL;
        for (int k = 0; k < 3; k++)
            ec.seed[k] = env->seed[k] ? env->seed[k] + d : NULL;
        ec.u = env->u ? env->u + f->du[c] : NULL;
        double *oc[LOW_MAX_ARGS];
        for (int k = 0; k < a.n - a.nin; k++) /* (outs has one per output argument) */
            oc[k] = outs[k] ? outs[k] + d : NULL;
        int loaded = !f->zero_skip;
        for (int k = 0; k < 3 && !loaded; k++)
            for (int i = f->span0; ec.seed[k] && i < f->span0 + f->span && !loaded; i++)
                loaded = ec.seed[k][i] != 0.0;
        if (loaded) {
            lower_eval(P, f->copy, &ec, oc);
            continue;
        }
        for (int k = 0; k < a.n - a.nin; k++) /* a copy without a load: at rest */
            for (int i = f->span0; oc[k] && lower_size(f->copy, k) && i < f->span0 + f->span; i++)
                oc[k][i] = 0.0;
    }
}

/* The values f reads but does not compute, by node id: leaves from env,
 * and the values another function computes (shared[], pd[]), which the C
 * reads and which are evaluated here on the DAG instead (expr_eval_many:
 * the same arithmetic, node by node). */
static void
eval_inputs(ExprPool *P, const LowFunc *f, const LowSched *S, const ExprEnv *env, double *v)
{
    size_t size = expr_pool_size(P);
    unsigned char *seen = xmalloc(size);
    memset(seen, 0, size);
    ExprId *far = xmalloc(size * sizeof *far);
    int nfar = 0;
    for (int k = 0; k < S->nstep; k++) {
        const LowStep *st = &S->step[k];
        ExprId ops[2];
        int nop = 0;
        if (st->kind == LOW_STEP_NODE) {
            const ExprNode *nd = expr_node(P, st->id);
            nop = expr_op_arity[nd->op];
            ops[0] = nd->a, ops[1] = nd->b;
        } else if (st->kind == LOW_STEP_STORE) {
            nop = 1, ops[0] = f->out[st->i].e;
        }
        for (int j = 0; j < nop; j++) {
            ExprId e = ops[j];
            if (seen[e] || lower_computed(P, f, e))
                continue;
            seen[e] = 1;
            if (expr_op_arity[expr_node(P, e)->op] == 0)
                v[e] = expr_eval_node(P, e, NULL, env);
            else
                far[nfar++] = e;
        }
    }
    double *val = xmalloc(((size_t)nfar + 1) * sizeof *val);
    expr_eval_many(P, nfar, far, env, val);
    for (int j = 0; j < nfar; j++)
        v[far[j]] = val[j];
    free(val);
    free(far);
    free(seen);
}

void
lower_eval(ExprPool *P, const LowFunc *f, const ExprEnv *env, double *const *outs)
{
    LowSched *S = lower_schedule(P, f, 1);
    size_t size = expr_pool_size(P);
    double *v = xmalloc(size * sizeof *v); /* by node id; a block not run leaves NaN */
    for (size_t i = 0; i < size; i++)
        v[i] = NAN;
    eval_inputs(P, f, S, env, v);
    int skip = 0; /* inside a block's branch that the mode does not take */
    for (int k = 0; k < S->nstep; k++) {
        const LowStep *st = &S->step[k];
        if (skip && st->kind == LOW_STEP_NODE)
            continue;
        switch (st->kind) {
        case LOW_STEP_IF: /* no modes (NULL): no branch, as SELECT's NaN */
            skip = !env->mode || (env->mode[st->i] != 0.0) != st->branch;
            break;
        case LOW_STEP_OR: /* a block runs where any of its tests holds */
            skip = skip && (!env->mode || (env->mode[st->i] != 0.0) != st->branch);
            break;
        case LOW_STEP_ELSE:
            skip = !env->mode || !skip;
            break;
        case LOW_STEP_END:
            skip = 0;
            break;
        case LOW_STEP_COPIES:
            eval_copies(P, f, env, outs);
            break;
        case LOW_STEP_FILL: /* unless the caller zeroed it, as in the C */
            for (int i = 0; outs[st->i] && !(f->zeroed >> st->i & 1) && i < f->fill[st->i]; i++)
                outs[st->i][i] = 0.0;
            break;
        case LOW_STEP_NODE: {
            const ExprNode *nd = expr_node(P, st->id);
            int ar = expr_op_arity[nd->op];
            double x[2] = {ar >= 1 ? v[nd->a] : 0.0, ar >= 2 ? v[nd->b] : 0.0};
            v[st->id] = expr_eval_node(P, st->id, x, env);
            break;
        }
        case LOW_STEP_STORE: {
            const LowSlot *o = &f->out[st->i];
            if (outs[o->arg])
                outs[o->arg][o->index] = v[o->e];
            break;
        }
        }
    }
    free(v);
    lower_sched_free(S);
}
