/*
 * repeat: one copy's code and a loop, where a lowered function's outputs
 * are identical copies of one subtree (repeat.h).
 *
 * Why it is safe: copy c's outputs are accepted only where, with its
 * coordinates q_{j+d} and inputs u_{i+du} renamed to the first copy's q_j
 * and u_i, each is the node the first copy stores at its slot shifted by
 * d.  Then the first copy's expressions, evaluated on arrays shifted by
 * d (coordinates, their rates and seeds) and du (inputs), are copy c's,
 * stored at copy c's slots; parameters and time are not renamed and are
 * read unshifted.
 */
#include "repeat.h"

#include <stdlib.h>
#include <string.h>

/* union-find over the keys: coordinates 0..n-1, then (with speeds) the
 * velocity slots n..n+nv-1, then inputs */
static int
find(int *up, int x)
{
    while (up[x] != x)
        x = up[x] = up[up[x]];
    return x;
}

static void
unite(int *up, int a, int b)
{
    a = find(up, a), b = find(up, b);
    if (a != b)
        up[a < b ? b : a] = a < b ? a : b;
}

/* The coordinates, inputs (as keys, n + index) and outputs of the
 * outputs' group rooted at a key; ok: a contiguous run of each, so a shift is the whole renaming. */
typedef struct Group {
    int qmin, qmax, nq, umin, umax, nu;
    int vmin, vmax, nv; /* with speeds: the velocity slots (keys n + slot) */
    int nout, ops; /* ops: operations below its outputs and no other group's */
    int ok;
} Group;

/* Could group g be a copy of group b: a run of as many coordinates,
 * inputs and outputs? */
static int
alike(const Group *G, int b, int g)
{
    return G[g].ok && G[g].nq == G[b].nq && G[g].nv == G[b].nv && G[g].nu == G[b].nu &&
           G[g].nout == G[b].nout;
}

/* Can f's arrays be shifted at all: inputs of the state, the parameters
 * and the seeds only (no values from another function, no multipliers),
 * no output that may be NULL or that is zero-filled first. */
static int
shiftable(const LowFunc *f)
{
    static const char *const known[] = {"t", "q", "v", "a", "p", "u", "dq", "dv", "da"};
    if (f->shared || f->zeroed || strchr(f->sig->args, '?'))
        return 0;
    /* the signature's inputs: the names before '>' (lowered.h) */
    for (const char *c = f->sig->args; *c && *c != '>';) {
        size_t len = strcspn(c, " >"), i = 0;
        while (len && i < sizeof known / sizeof *known &&
               !(strlen(known[i]) == len && !strncmp(c, known[i], len)))
            i++;
        if (i == sizeof known / sizeof *known)
            return 0;
        c += len;
        c += strspn(c, " ");
    }
    for (int k = 0; k < LOW_MAX_ARGS; k++)
        if (f->fill[k])
            return 0;
    return 1;
}

/* The speeds of a model whose velocity slots are not its coordinates
 * (NULL: v = q', a leaf's key is its coordinate at every order). */
typedef struct Slots {
    int nv;
    const int *vslot, *vcoord; /* lowered.h */
} Slots;

/* Does group g's copy of base b (shifted by d, du) store, at each slot,
 * the node base stores there?  gk: each output's group.  With speeds, the
 * coordinates shift by the q run, the speeds (rates, seeds dv, da) and
 * the outputs (by slot) by the v run. */
static int
verify(const LowFunc *f, const int *gk, int b, int g, const Group *G, int n, const Slots *sp,
       const ExprId *base_e, Arena *A, ExprPool *P)
{
    int nq = G[b].nq, nv = G[b].nv, nu = G[b].nu, sv = sp != NULL;
    int d = sv ? G[g].vmin - G[b].vmin : G[g].qmin - G[b].qmin, lo = sv ? G[b].vmin : G[b].qmin;
    int nout = sv ? nv : nq; /* the outputs' run */
    int nl = (nq + nv) * (EXPR_MAX_ORDER + 1 + 3) + nu, k = 0;
    ExprId *from = arena_new_array(A, ExprId, nl), *to = arena_new_array(A, ExprId, nl);
    for (int j = 0; j < nq; j++) {
        int jc = G[g].qmin + j, j0 = G[b].qmin + j;
        for (int o = 0; o <= (sv ? 0 : EXPR_MAX_ORDER); o++)
            from[k] = expr_var(P, jc, o), to[k++] = expr_var(P, j0, o);
        for (int s = 0; s < (sv ? 1 : 3); s++)
            from[k] = expr_seed(P, jc, s), to[k++] = expr_seed(P, j0, s);
    }
    for (int j = 0; j < nv; j++) { /* slots: their leaves' rates, seeds by slot */
        int jc = G[g].vmin - n + j, j0 = G[b].vmin - n + j;
        for (int o = 1; o <= EXPR_MAX_ORDER; o++)
            from[k] = expr_var(P, sp->vcoord[jc], o), to[k++] = expr_var(P, sp->vcoord[j0], o);
        for (int s = 1; s < 3; s++)
            from[k] = expr_seed(P, jc, s), to[k++] = expr_seed(P, j0, s);
    }
    int u0 = n + (sv ? sp->nv : 0);
    for (int i = 0; i < nu; i++)
        from[k] = expr_input(P, G[g].umin - u0 + i), to[k++] = expr_input(P, G[b].umin - u0 + i);
    int nr = G[g].nout, r = 0;
    ExprId *roots = arena_new_array(A, ExprId, nr), *mapped = arena_new_array(A, ExprId, nr);
    int *slot = arena_new_array(A, int, nr);
    for (int o = 0; o < f->nout; o++)
        if (gk[o] == g)
            slot[r] = o, roots[r++] = f->out[o].e;
    expr_subst_many(P, nr, roots, k, from, to, mapped);
    for (int i = 0; i < nr; i++) {
        const LowSlot *s = &f->out[slot[i]];
        int at = s->index - d - (lo - (sv ? n : 0)); /* the base's slot, in base_e's rows */
        if (at < 0 || at >= nout || base_e[s->arg * nout + at] != mapped[i])
            return 0;
    }
    return 1;
}

/* Does every output of c vanish where its seeds (coordinates q0 ..
 * q0+nq-1; with speeds, the slots from v0) are all 0, as expressions (a
 * unit load's recursion: no load, no motion)?  Then a copy whose seeds are zero may store zeros instead
 * of running (repeat.h). */
static int
vanishes(const LowFunc *c, int q0, int nq, int v0, Arena *A, ExprPool *P)
{
    int any = 0;
    for (int k = 0; k < c->nout; k++)
        any |= (expr_node(P, c->out[k].e)->deps & DEP_S) != 0;
    if (!any || c->nout == 0)
        return 0;
    ExprId *from = arena_new_array(A, ExprId, 3 * nq), *to = arena_new_array(A, ExprId, 3 * nq);
    ExprId *roots = arena_new_array(A, ExprId, c->nout), *got = arena_new_array(A, ExprId, c->nout);
    for (int j = 0; j < nq; j++) /* dq by coordinate, dv and da by slot (from v0) */
        for (int s = 0; s < 3; s++)
            from[3 * j + s] = expr_seed(P, (s ? v0 : q0) + j, s), to[3 * j + s] = EXPR_ZERO;
    for (int k = 0; k < c->nout; k++)
        roots[k] = c->out[k].e;
    expr_subst_many(P, c->nout, roots, 3 * nq, from, to, got);
    for (int k = 0; k < c->nout; k++)
        if (got[k] != EXPR_ZERO)
            return 0;
    return 1;
}

static int
split(LowFunc *f, int n, int nu, const Slots *sp, long min_saved, Arena *A, ExprPool *P)
{
    if (!shiftable(f) || f->nout < 2)
        return 0;
    size_t size = expr_pool_size(P);
    unsigned char *mark = calloc(size, 1);
    int nv = sp ? sp->nv : 0; /* keys: coordinates, then slots (with speeds), then inputs */
    int *key = malloc(size * sizeof *key), nk = n + nv + nu;
    int *up = malloc(((size_t)nk + 1) * sizeof *up);
    unsigned char *seen = calloc((size_t)nk + 1, 1);
    ExprId *roots = malloc(((size_t)f->nout + 1) * sizeof *roots);
    int *gk = malloc(((size_t)f->nout + 1) * sizeof *gk);
    Group *G = calloc((size_t)nk + 1, sizeof *G);
    int split = 0;
    for (int o = 0; o < f->nout; o++)
        roots[o] = f->out[o].e;
    expr_mark(P, f->nout, roots, mark);
    for (int i = 0; i < nk; i++)
        up[i] = i;
    /* each node's key: a leaf's own; an operation joins its operands' */
    for (size_t i = 0; i < size; i++) {
        key[i] = -1;
        if (!mark[i])
            continue;
        const ExprNode *nd = expr_node(P, (ExprId)i);
        int ar = expr_op_arity[nd->op];
        /* a mode is read at u[nu + k], which no copy's shift of u renames */
        if (nd->op == EXPR_MULT || nd->op == EXPR_SELECT)
            goto done;
        if (nd->op == EXPR_VAR || nd->op == EXPR_SEED || nd->op == EXPR_INPUT) {
            if (nd->op == EXPR_INPUT)
                key[i] = n + nv + (int)nd->a;
            else if (!sp || nd->b == 0) /* a coordinate, dq */
                key[i] = (int)nd->a;
            else /* a slot: a rate's by its leaf, dv and da by their index */
                key[i] = n + (nd->op == EXPR_VAR ? sp->vslot[nd->a] : (int)nd->a);
            seen[key[i]] = 1;
        } else if (ar > 0) {
            int ka = key[nd->a], kb = ar == 2 ? key[nd->b] : -1;
            if (ka >= 0 && kb >= 0)
                unite(up, ka, kb);
            key[i] = ka >= 0 ? ka : kb;
        }
    }
    for (int g = 0; g < nk; g++)
        G[g] = (Group){.qmin = n, .qmax = -1, .vmin = n + nv, .vmax = -1, .umin = nk,
                       .umax = -1, .ok = 1};
    for (int x = 0; x < nk; x++) {
        if (!seen[x])
            continue;
        Group *g = &G[find(up, x)];
        if (x < n)
            g->nq++, g->qmin = x < g->qmin ? x : g->qmin, g->qmax = x > g->qmax ? x : g->qmax;
        else if (x < n + nv)
            g->nv++, g->vmin = x < g->vmin ? x : g->vmin, g->vmax = x > g->vmax ? x : g->vmax;
        else
            g->nu++, g->umin = x < g->umin ? x : g->umin, g->umax = x > g->umax ? x : g->umax;
    }
    for (size_t i = 0; i < size; i++)
        if (key[i] >= 0 && expr_op_arity[expr_node(P, (ExprId)i)->op] > 0)
            G[find(up, key[i])].ops++;
    for (int o = 0; o < f->nout; o++) {
        int k = key[f->out[o].e];
        gk[o] = k >= 0 ? find(up, k) : -1;
        if (gk[o] >= 0)
            G[gk[o]].nout++;
    }
    for (int g = 0; g < nk; g++) /* runs that a shift renames */
        G[g].ok = G[g].nout > 0 && G[g].nq > 0 && G[g].qmax - G[g].qmin + 1 == G[g].nq &&
                  (G[g].nv == 0 || G[g].vmax - G[g].vmin + 1 == G[g].nv) &&
                  (!sp || G[g].nv > 0) &&
                  (G[g].nu == 0 || G[g].umax - G[g].umin + 1 == G[g].nu);
    /* the base: the group whose copies would save the most code (groups
     * are rooted at their least key, so in coordinate order) */
    int best = -1;
    long best_saved = 0;
    for (int b = 0; b < nk; b++) {
        if (!G[b].ok)
            continue;
        int like = 0;
        for (int g = b + 1; g < nk; g++)
            like += alike(G, b, g);
        long saved = (long)like * G[b].ops;
        if (saved > best_saved)
            best = b, best_saved = saved;
    }
    if (best < 0 || best_saved < min_saved)
        goto done;
    int b = best;
    /* the outputs' run: the coordinates', or with speeds the slots' */
    int nq = sp ? G[b].nv : G[b].nq, lo = sp ? G[b].vmin - n : G[b].qmin;
    /* the base's node at each slot, by output argument and coordinate */
    ExprId *base_e = arena_new_array(A, ExprId, LOW_MAX_ARGS * nq);
    for (int i = 0; i < LOW_MAX_ARGS * nq; i++)
        base_e[i] = EXPR_NONE;
    for (int o = 0; o < f->nout; o++) {
        const LowSlot *s = &f->out[o];
        if (gk[o] != b)
            continue;
        if (s->index < lo || s->index >= lo + nq)
            goto done; /* not one slot per coordinate: no shift maps it */
        base_e[s->arg * nq + s->index - lo] = s->e;
    }
    int *in = calloc((size_t)nk + 1, sizeof *in), ncopy = 1;
    long saved = 0;
    in[b] = 1;
    for (int g = b + 1; g < nk; g++)
        if (alike(G, b, g) && verify(f, gk, b, g, G, n, sp, base_e, A, P))
            in[g] = 1, ncopy++, saved += G[b].ops;
    if (ncopy > 1 && saved >= min_saved) {
        LowFunc *c = arena_new_array(A, LowFunc, 1);
        LowSig *sig = arena_new_array(A, LowSig, 1);
        *c = *f;
        sig->name = arena_printf(A, "%s_copy", f->sig->name);
        sig->comment = "One copy of a subtree that repeats (repeat.c), in the first copy's\n"
                       " * names: the function after it runs it for each, its arrays shifted.";
        sig->args = f->sig->args;
        c->sig = sig;
        c->out = arena_new_array(A, LowSlot, G[b].nout);
        c->nout = c->cap = 0;
        f->ncopy = ncopy;
        f->dq = arena_new_array(A, int, ncopy);
        f->du = arena_new_array(A, int, ncopy);
        f->dv = sp ? arena_new_array(A, int, ncopy) : NULL;
        LowSlot *rest = arena_new_array(A, LowSlot, f->nout);
        int nrest = 0;
        for (int o = 0; o < f->nout; o++) {
            if (gk[o] == b)
                c->out[c->nout++] = f->out[o];
            else if (gk[o] < 0 || !in[gk[o]])
                rest[nrest++] = f->out[o];
        }
        c->cap = c->nout;
        for (int g = b, k = 0; g < nk; g++)
            if (in[g]) {
                f->dq[k] = G[g].qmin - G[b].qmin;
                if (sp)
                    f->dv[k] = G[g].vmin - G[b].vmin;
                f->du[k++] = G[b].nu ? G[g].umin - G[b].umin : 0;
            }
        f->out = rest;
        f->nout = f->cap = nrest;
        f->copy = c;
        f->span0 = lo, f->span = nq;
        /* (with speeds, where its seeds are dv and da alone: by slot) */
        f->zero_skip = (!sp || !strstr(f->sig->args, "dq")) &&
                       vanishes(c, sp ? G[b].qmin : lo, nq, lo, A, P);
        split = 1;
    }
    free(in);
done:
    free(mark);
    free(key);
    free(up);
    free(seen);
    free(roots);
    free(gk);
    free(G);
    return split;
}

int
repeat_split(LowFunc *f, int n, int nu, long min_saved, Arena *A, ExprPool *P)
{
    return split(f, n, nu, NULL, min_saved, A, P);
}

int
repeat_split_speeds(LowFunc *f, int nq, int nv, const int *vslot, const int *vcoord, int nu,
                    long min_saved, Arena *A, ExprPool *P)
{
    Slots sp = {nv, vslot, vcoord};
    return split(f, nq, nu, &sp, min_saved, A, P);
}
