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

/* Check the chain of m's point, mark the frames above it in used[] and
 * set the pivots of those that turn (pivot[g][0] == EXPR_NONE: not yet
 * set).  Returns the reason it does not fit, or NULL. */
static const char *
hang(const Kin *K, Arena *A, Diff *D, Mass *ms, ExprId (*pivot)[3], int *used)
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
    for (int g = ms->frame; g > KIN_WORLD; g = kin_parent(K, g)) {
        used[g] = 1;
        /* the links in g's subtree must be the outermost ones */
        int k = 0;
        while (k < n && kin_is_ancestor(K, g, fr[k]))
            k++;
        for (int j = k; j < n; j++)
            if (kin_is_ancestor(K, g, fr[j]))
                return arena_printf(A, "the position of '%s' leaves a turning frame and "
                                    "enters it again", ms->name);
        if (!turns(K, g))
            continue;
        ExprId p[3];
        kin_pos(K, k == 0 ? ms->point : from[k - 1], p);
        if (pivot[g][0] == EXPR_NONE) {
            memcpy(pivot[g], p, sizeof p);
        } else if (memcmp(pivot[g], p, sizeof p)) {
            return arena_printf(A, "a frame turns '%s' about another point than the other "
                                "masses it turns", ms->name);
        }
    }
    return NULL;
}

/* The spatial inertia of ms about the world origin, added to f. */
static void
add_inertia(const Kin *K, ExprPool *P, const Mass *ms, TreeFrame *f)
{
    ExprId c[3], R[9], J[9];
    kin_pos(K, ms->point, c);
    for (int i = 0; i < 9; i++)
        J[i] = EXPR_ZERO;
    if (ms->I) { /* J = R I R^T: the inertia about the centre in world axes */
        kin_rotation(K, ms->frame, R);
        ExprId RI[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                ExprId s = EXPR_ZERO;
                for (int k = 0; k < 3; k++)
                    s = expr_add(P, s, expr_mul(P, R[3 * i + k], ms->I[3 * k + j]));
                RI[3 * i + j] = s;
            }
        for (int i = 0; i < 3; i++)
            for (int j = 0; j <= i; j++) {
                ExprId s = EXPR_ZERO;
                for (int k = 0; k < 3; k++)
                    s = expr_add(P, s, expr_mul(P, RI[3 * i + k], R[3 * j + k]));
                J[3 * i + j] = J[3 * j + i] = s;
            }
    }
    /* about the origin: J + m (|c|^2 1 - c c^T), the parallel-axis term */
    ExprId h[3];
    for (int i = 0; i < 3; i++)
        h[i] = expr_mul(P, ms->m, c[i]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j <= i; j++) {
            ExprId t;
            if (i == j) {
                int a = (i + 1) % 3, b = (i + 2) % 3;
                ExprId hb = expr_mul(P, h[b], c[b]);
                t = expr_add(P, expr_mul(P, h[a], c[a]), hb);
            } else {
                t = expr_neg(P, expr_mul(P, h[i], c[j]));
            }
            J[3 * i + j] = J[3 * j + i] = expr_add(P, J[3 * i + j], t);
        }
    f->m = expr_add(P, f->m, ms->m);
    for (int i = 0; i < 3; i++)
        f->h[i] = expr_add(P, f->h[i], h[i]);
    for (int i = 0; i < 9; i++)
        f->I[i] = expr_add(P, f->I[i], J[i]);
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
    for (int g = 0; g < nf; g++)
        pivot[g][0] = EXPR_NONE, above[g] = 0;
    for (int k = 0; k < nm; k++)
        if ((*why = hang(K, A, D, &ms[k], pivot, above)))
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
    int nt = 0;
    for (int g = 1; g < nf; g++) {
        if (index[g] < 0)
            continue;
        TreeFrame *f = &t->frame[index[g]];
        int pg = kin_parent(K, g);
        f->parent = pg > KIN_WORLD ? index[pg] : -1;
        memcpy(f->pivot, pivot[g], sizeof f->pivot);
        f->m = f->h[0] = f->h[1] = f->h[2] = EXPR_ZERO;
        for (int i = 0; i < 9; i++)
            f->I[i] = EXPR_ZERO;
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
            memcpy(t->turn[nt].a, a, sizeof a);
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
    for (int k = 0; k < nm; k++)
        if (ms[k].frame > KIN_WORLD)
            add_inertia(K, P, &ms[k], &t->frame[index[ms[k].frame]]);
    return t;
}
