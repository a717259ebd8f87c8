/*
 * tree: recognize a tree of rigid bodies on turning joints in a spec's
 * frames and points (tree.h), and gather each frame's spatial inertia.
 *
 * Why the pivot is all that is needed: a mass at point P hangs from the
 * origin through links d_1 ... d_L (each fixed in its frame), so
 *     v_P = sum_links w_f(link) x d_link,   w_f = sum_{turns above f} a th'.
 * A turn of frame g moves the links in g's subtree.  When those are the
 * last links of the chain, from the point p where the chain enters the
 * subtree, its part of the spatial velocity about the world origin,
 * (w, v_P - w x P), is th' (a, a x (P - p) - a x P) = th' (a, p x a):
 * the same for every mass below g exactly when they all enter the
 * subtree at p.
 */
#include "tree.h"

#include "kin.h"

#include <string.h>

/* A place among the turns: kin's frame f after its first n turns (the
 * fixed ones counted). */
typedef struct Place {
    int f, n;
} Place;

/* One mass: a body (I its inertia about its centre in its frame's axes)
 * or a particle (I NULL). */
typedef struct Mass {
    const char *name;
    int frame, point;
    ExprId m;
    const ExprId *I;
} Mass;

static int
constant_in_time(Diff *D, ExprId e)
{
    return diff_time(D, e) == EXPR_ZERO;
}

/* Whether frame g turns at all (a turn by a constant angle does not). */
static int
turns(const Kin *K, int g)
{
    ExprId rate, a[3];
    for (int k = 0; kin_turn_of(K, g, k, &rate, a); k++)
        if (rate != EXPR_ZERO)
            return 1;
    return 0;
}

/* The number of frames from the world down to f (the world: 0). */
static int
depth(const Kin *K, int f)
{
    int d = 0;
    for (; f > KIN_WORLD; f = kin_parent(K, f))
        d++;
    return d;
}

/* Check the chain of m's point, mark the frames above it in used[] and
 * set the pivots of those that turn (pivot[g][0] == EXPR_NONE: not yet
 * set), and a point there (pivot_pt[g]).  Returns the reason it does not fit, or NULL. */
static const char *
hang(const Kin *K, Arena *A, Diff *D, Mass *ms, ExprId (*pivot)[3], int *pivot_pt, int *used)
{
    /* the chain is kept on the stack; a longer one is refused, and
     * Lagrange's form derives the model as before */
    enum { CHAIN_MAX = 256 };
    int from[CHAIN_MAX], fr[CHAIN_MAX], n = 0;
    for (int p = ms->point; p > KIN_ORIGIN; n++) {
        if (n == CHAIN_MAX)
            return arena_printf(A, "'%s' hangs from more than %d points", ms->name, CHAIN_MAX);
        ExprId at[3], off[3];
        from[n] = kin_point_link(K, p, &fr[n], at, off);
        for (int k = 0; k < 3; k++)
            if (!constant_in_time(D, at[k]))
                return arena_printf(A, "the position of '%s' slides in a frame (an offset "
                                    "moves with the coordinates or time)", ms->name);
        p = from[n] < 0 ? KIN_ORIGIN : from[n];
    }
    /* link 0 ends at the mass, link n - 1 starts at the origin; link k
     * starts at from[k] and is fixed in frame fr[k] */
    if (ms->frame < 0) { /* a particle: it moves with its deepest link's frame */
        ms->frame = KIN_WORLD;
        for (int k = 0; k < n; k++)
            if (kin_is_ancestor(K, ms->frame, fr[k]))
                ms->frame = fr[k];
    }
    for (int k = 0; k < n; k++)
        if (!kin_is_ancestor(K, fr[k], ms->frame))
            return arena_printf(A, "the position of '%s' goes through a frame it does not "
                                "turn with", ms->name);
    /* the links' frames and g below are all on the way from the world to
     * the mass's frame: one is an ancestor of another when it is no deeper */
    int dep[CHAIN_MAX], dg = depth(K, ms->frame);
    for (int k = 0; k < n; k++)
        dep[k] = depth(K, fr[k]);
    for (int g = ms->frame; g > KIN_WORLD; g = kin_parent(K, g), dg--) {
        used[g] = 1;
        /* the links in g's subtree must be the outermost ones */
        int k = 0;
        while (k < n && dep[k] >= dg)
            k++;
        for (int j = k; j < n; j++)
            if (dep[j] >= dg)
                return arena_printf(A, "the position of '%s' leaves a turning frame and "
                                    "enters it again", ms->name);
        if (!turns(K, g))
            continue;
        ExprId p[3];
        int pt = k == 0 ? ms->point : from[k - 1];
        kin_pos(K, pt, p);
        if (pivot[g][0] == EXPR_NONE) {
            memcpy(pivot[g], p, sizeof p);
            pivot_pt[g] = pt;
        } else if (memcmp(pivot[g], p, sizeof p)) {
            return arena_printf(A, "a frame turns '%s' about another point than the other "
                                "masses it turns", ms->name);
        }
    }
    return NULL;
}

static int
nturns_of(const Kin *K, int f)
{
    ExprId rate, a[3];
    int k = 0;
    while (kin_turn_of(K, f, k, &rate, a))
        k++;
    return k;
}

/* C = A B, 3 x 3 row-major (C may be A or B). */
static void
mat3_mul(ExprPool *P, const ExprId *X, const ExprId *Y, ExprId *C)
{
    ExprId out[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            ExprId sum = EXPR_ZERO;
            for (int k = 0; k < 3; k++)
                sum = expr_add(P, sum, expr_mul(P, X[3 * i + k], Y[3 * k + j]));
            out[3 * i + j] = sum;
        }
    memcpy(C, out, sizeof out);
}

/* Q: the axes at place b in the axes at place a, when a's frame is an
 * ancestor of b's (or b's, with a.n <= b.n): the product of the turns
 * from a to b. */
static void
axes_between(const Kin *K, Arena *A, ExprPool *P, Place a, Place b, ExprId Q[9])
{
    for (int i = 0; i < 9; i++)
        Q[i] = i % 4 == 0 ? EXPR_ONE : EXPR_ZERO;
    int depth = 0;
    for (int h = b.f; h != a.f; h = kin_parent(K, h))
        depth++;
    int *path = arena_new_array(A, int, depth + 1); /* b's frame up to a's */
    depth = 0;
    for (int h = b.f; h != a.f; h = kin_parent(K, h))
        path[depth++] = h;
    for (int d = depth; d >= 0; d--) {
        int f = d == depth ? a.f : path[d];
        int from = d == depth ? a.n : 0, to = d == 0 ? b.n : nturns_of(K, f);
        for (int k = from; k < to; k++) {
            ExprId angle, axis[3], Rk[9];
            kin_turn_local(K, f, k, &angle, axis, Rk);
            mat3_mul(P, Q, Rk, Q);
        }
    }
}

/* The offset of point p from the point at world position o (where p's
 * chain of links passes), in the axes at place x: the sum of the links
 * between them, each turned into those axes.  0 if the chain misses o or
 * a link's frame is on another branch than x's. */
static int
offset_in(const Kin *K, Arena *A, ExprPool *P, int p, const ExprId o[3], Place x,
          ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = EXPR_ZERO;
    for (;;) {
        ExprId pos[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
        if (p > KIN_ORIGIN)
            kin_pos(K, p, pos);
        if (pos[0] == o[0] && pos[1] == o[1] && pos[2] == o[2])
            return 1;
        if (p <= KIN_ORIGIN)
            return 0;
        int f;
        ExprId at[3], off[3], Q[9];
        int from = kin_point_link(K, p, &f, at, off);
        Place pf = {f, nturns_of(K, f)};
        int down = kin_is_ancestor(K, x.f, f);
        if (down)
            axes_between(K, A, P, x, pf, Q); /* at's axes in x's */
        else if (kin_is_ancestor(K, f, x.f))
            axes_between(K, A, P, pf, x, Q); /* x's in at's */
        else
            return 0;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                out[i] = expr_add(P, out[i], expr_mul(P, down ? Q[3 * i + k] : Q[3 * k + i], at[k]));
        p = from < 0 ? KIN_ORIGIN : from;
    }
}

/* The turns' and masses' local coordinates (tree.h).  kid: each tree
 * frame's frame in kin; at: each turn's place. */
static const char *
localize(const Kin *K, Arena *A, ExprPool *P, Diff *D, Tree *t, const int *kid,
         const Place *at, ExprId (*pivot)[3], const int *pivot_pt, const Mass *ms, int nm,
         const int *index)
{
    static const char *const moves = "a turn's local offset or inertia moves (a tree "
                                     "eomc cannot yet put in local coordinates)";
    int nf = t->nframes;
    typedef ExprId Point3[3];
    Point3 *o = arena_new_array(A, Point3, nf + 1); /* each frame's origin, world */
    for (int fi = 0; fi < nf; fi++) {
        TreeFrame *f = &t->frame[fi];
        for (int i = 0; i < 3; i++)
            o[fi][i] = f->nturns ? pivot[kid[fi]][i] : f->parent >= 0 ? o[f->parent][i]
                                                                      : EXPR_ZERO;
        f->carrier = f->nturns ? f->first + f->nturns - 1
                               : f->parent >= 0 ? t->frame[f->parent].carrier : -1;
        for (int k = f->first; k < f->first + f->nturns; k++) {
            TreeTurn *tk = &t->turn[k];
            tk->up = k > f->first ? k - 1 : f->parent >= 0 ? t->frame[f->parent].carrier : -1;
            Place up = tk->up >= 0 ? at[tk->up] : (Place){KIN_WORLD, 0};
            axes_between(K, A, P, up, at[k], tk->Q);
            axes_between(K, A, P, up, (Place){at[k].f, at[k].n - 1}, tk->Qf);
            ExprId Rk[9];
            kin_turn_local(K, at[k].f, at[k].n - 1, &tk->angle, tk->al, Rk);
            if (k > f->first) {
                tk->r[0] = tk->r[1] = tk->r[2] = EXPR_ZERO;
                continue;
            }
            /* the origin of the frame that holds the turn above */
            int fu = f->parent;
            while (fu >= 0 && t->frame[fu].nturns == 0)
                fu = t->frame[fu].parent;
            const ExprId zero[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
            if (!offset_in(K, A, P, pivot_pt[kid[fi]], fu >= 0 ? o[fu] : zero, up, tk->r))
                return moves;
            for (int i = 0; i < 3; i++)
                if (!constant_in_time(D, tk->r[i]))
                    return moves;
        }
        f->m = f->h[0] = f->h[1] = f->h[2] = EXPR_ZERO;
        for (int i = 0; i < 9; i++)
            f->I[i] = EXPR_ZERO;
    }
    for (int k = 0; k < nm; k++) {
        if (ms[k].frame <= KIN_WORLD)
            continue;
        int fi = index[ms[k].frame], c = t->frame[fi].carrier;
        if (c < 0)
            continue;
        TreeFrame *f = &t->frame[fi];
        int fc = 0; /* the tree frame of the carrier */
        while (!(t->frame[fc].first <= c && c < t->frame[fc].first + t->frame[fc].nturns))
            fc++;
        ExprId d[3], Q[9], J[9];
        if (!offset_in(K, A, P, ms[k].point, o[fc], at[c], d))
            return moves;
        axes_between(K, A, P, at[c], (Place){ms[k].frame, nturns_of(K, ms[k].frame)}, Q);
        for (int i = 0; i < 9; i++)
            J[i] = EXPR_ZERO;
        if (ms[k].I) { /* Q I Q^T */
            ExprId QI[9], Qt[9];
            mat3_mul(P, Q, ms[k].I, QI);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    Qt[3 * i + j] = Q[3 * j + i];
            mat3_mul(P, QI, Qt, J);
            for (int i = 0; i < 3; i++) /* symmetric to the bit */
                for (int j = 0; j < i; j++)
                    J[3 * j + i] = J[3 * i + j];
        }
        /* about the carrier's origin: J + m (|d|^2 1 - d d^T) */
        ExprId h[3];
        for (int i = 0; i < 3; i++)
            h[i] = expr_mul(P, ms[k].m, d[i]);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                ExprId e;
                if (i == j) {
                    int a = (i + 1) % 3, b = (i + 2) % 3;
                    ExprId hb = expr_mul(P, h[b], d[b]);
                    e = expr_add(P, expr_mul(P, h[a], d[a]), hb);
                } else {
                    e = expr_neg(P, expr_mul(P, h[i], d[j]));
                }
                J[3 * i + j] = expr_add(P, J[3 * i + j], e);
            }
        f->m = expr_add(P, f->m, ms[k].m);
        for (int i = 0; i < 3; i++)
            f->h[i] = expr_add(P, f->h[i], h[i]);
        for (int i = 0; i < 9; i++)
            f->I[i] = expr_add(P, f->I[i], J[i]);
    }
    for (int fi = 0; fi < nf; fi++) {
        const TreeFrame *f = &t->frame[fi];
        for (int i = 0; i < 9; i++)
            if (!constant_in_time(D, f->I[i]) || (i < 3 && !constant_in_time(D, f->h[i])))
                return moves;
    }
    return NULL;
}

Tree *
tree_build(const Spec *s, const ExprId *q1, Arena *A, ExprPool *P, Diff *D,
           const char **why)
{
    const Kin *K = s->kin;
    if (s->nkinetic > 0) {
        *why = "the spec has explicit kinetic-energy terms";
        return NULL;
    }
    if (!K || s->nbody + s->npart == 0) {
        *why = "the spec places no mass by frames";
        return NULL;
    }
    int nm = s->nbody + s->npart, nf = kin_nframes(K);
    Mass *ms = arena_new_array(A, Mass, nm);
    for (int k = 0; k < s->nbody; k++) {
        const SpecBody *b = &s->body[k];
        if (b->frame < 0 || b->point < 0) {
            *why = arena_printf(A, "body '%s' is not placed by a frame with its centre at "
                                "a point", b->name);
            return NULL;
        }
        ms[k] = (Mass){b->name, b->frame, b->point, b->mass, b->inertia};
    }
    for (int k = 0; k < s->npart; k++) {
        const SpecParticle *pt = &s->part[k];
        if (pt->point < 0) {
            *why = arena_printf(A, "particle '%s' is not at a point", pt->name);
            return NULL;
        }
        ms[s->nbody + k] = (Mass){pt->name, -1, pt->point, pt->mass, NULL};
    }
    for (int k = 0; k < nm; k++) {
        int varies = !constant_in_time(D, ms[k].m);
        for (int i = 0; ms[k].I && i < 9; i++)
            varies |= !constant_in_time(D, ms[k].I[i]);
        if (varies) {
            *why = arena_printf(A, "the mass or inertia of '%s' changes with time",
                                ms[k].name);
            return NULL;
        }
    }
    typedef ExprId Point3[3];
    Point3 *pivot = arena_new_array(A, Point3, nf);
    int *above = arena_new_array(A, int, nf); /* the frame is above a mass */
    int *pivot_pt = arena_new_array(A, int, nf);
    for (int g = 0; g < nf; g++)
        pivot[g][0] = EXPR_NONE, above[g] = 0;
    for (int k = 0; k < nm; k++)
        if ((*why = hang(K, A, D, &ms[k], pivot, pivot_pt, above)))
            return NULL;
    /* the frames that turn a mass, numbered in kin's order (parents first) */
    int *index = arena_new_array(A, int, nf);
    Tree *t = arena_alloc(A, sizeof *t);
    t->nframes = t->nturns = 0;
    for (int g = 1; g < nf; g++) {
        index[g] = -1;
        if (above[g]) {
            index[g] = t->nframes++;
            ExprId rate, a[3];
            for (int k = 0; kin_turn_of(K, g, k, &rate, a); k++)
                t->nturns++;
        }
    }
    t->frame = arena_new_array(A, TreeFrame, t->nframes + 1);
    t->turn = arena_new_array(A, TreeTurn, t->nturns + 1);
    int *used = arena_new_array(A, int, s->nq + 1);
    for (int i = 0; i < s->nq; i++)
        used[i] = 0;
    int *kid = arena_new_array(A, int, t->nframes + 1); /* kin's frame */
    Place *at = arena_new_array(A, Place, t->nturns + 1); /* each turn's place */
    int nt = 0;
    for (int g = 1; g < nf; g++) {
        if (index[g] < 0)
            continue;
        TreeFrame *f = &t->frame[index[g]];
        kid[index[g]] = g;
        int pg = kin_parent(K, g);
        f->parent = pg > KIN_WORLD ? index[pg] : -1;
        f->first = nt;
        ExprId rate, a[3];
        for (int k = 0; kin_turn_of(K, g, k, &rate, a); k++) {
            if (rate == EXPR_ZERO) /* a fixed angle: part of the frame's shape */
                continue;
            if (rate == EXPR_NONE) {
                *why = "a frame turns by a quaternion, not by the angle of a turn";
                return NULL;
            }
            int i = 0;
            while (i < s->nq && q1[i] != rate)
                i++;
            if (i == s->nq) {
                *why = "a turn's angle is not a coordinate";
                return NULL;
            }
            if (used[i]++) {
                *why = arena_printf(A, "coordinate '%s' is the angle of two turns",
                                    s->coord[i].name);
                return NULL;
            }
            t->turn[nt].coord = i;
            at[nt] = (Place){g, k + 1};
            nt++;
        }
        f->nturns = nt - f->first;
    }
    t->nturns = nt;
    for (int i = 0; i < s->nq; i++)
        if (!used[i]) {
            *why = arena_printf(A, "coordinate '%s' is not the angle of a turn",
                                s->coord[i].name);
            return NULL;
        }
    if ((*why = localize(K, A, P, D, t, kid, at, pivot, pivot_pt, ms, nm, index)))
        return NULL;
    return t;
}
