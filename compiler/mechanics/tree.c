/*
 * tree: recognize a tree of rigid bodies on turning and sliding joints in
 * a spec's frames and points (tree.h), and place each joint and mass in
 * its own coordinates.
 *
 * Why the pivot is all that is needed: a mass at point P hangs from the
 * origin through links d_1 ... d_L (each fixed in its frame, or sliding
 * along a constant direction in it), so
 *     v_P = sum_links (w_f(link) x d_link + d_link'),
 *     w_f = sum_{turns above f} a th'.
 * A turn of frame g moves the links in g's subtree.  When those are the
 * last links of the chain, from the point p where the chain enters the
 * subtree, its part of the velocity of P is th' a x (P - p): the same
 * rigid motion for every mass below g exactly when they all enter the
 * subtree at p.  A sliding link moves everything after it on the chain by
 * d q', along its direction in its frame's axes; a link affine in several
 * coordinates, c + d_1 q_1 + ... + d_k q_k, is k slides in a row (a
 * floating base's translation, a rolling wheel's contact point), by
 * coordinate index, with massless bodies between.  Walking a mass's chain
 * from the world outward gives its joints in order: at each link, the
 * turns of the frames it enters (top down), then the link's slides; each
 * joint's parent is the one before it, the same for every mass.
 */
#include "tree.h"

#include "expr/kin.h"

#include <stdlib.h>
#include <string.h>

/* A place among the turns: kin's frame f after its first n turns (the
 * fixed ones counted). */
typedef struct Place {
    int f, n;
} Place;

/* One mass: a body (I its inertia about its centre in its frame's axes)
 * or a particle (I NULL), and the chain of links it hangs from (link 0
 * ends at the mass; link k starts at from[k], -1 the origin, lies in
 * frame fr[k], and slides as slides sl[k], sl[k] + 1, ... (those of its
 * point), or not: -1). */
typedef struct Mass {
    const char *name;
    int frame, point;
    ExprId m;
    const ExprId *I;
    int n, *from, *fr, *sl;
} Mass;

/* A slide of a link: the link ends at point `point`, lies in kin's frame
 * `frame`, and its offset is c + sum d q over its slides (q coordinate
 * `coord`, c and d constant), which follow each other in the list. */
typedef struct Slide {
    int point, frame, coord;
    ExprId d[3];
} Slide;

/* What the search finds, by kin's frames. */
typedef struct Found {
    ExprId (*pivot)[3]; /* each frame's pivot (EXPR_NONE: not set) */
    int *pivot_pt;      /* a point there */
    int *above;         /* the frame is above a mass */
    Slide *slide;
    int nslide;
} Found;

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

/* A link's offset at = c + sum_k d_k q_k with c and the d_k constant:
 * the number of coordinates k (with coord[k] by index and d[k] set; at
 * most nmax, else -1), 0 when at depends on no coordinate, -1 when it is
 * not affine so. */
static int
affine(const Spec *s, ExprPool *P, Diff *D, const ExprId at[3], int nmax, int *coord,
       ExprId (*d)[3])
{
    int found = 0;
    ExprId c[3] = {at[0], at[1], at[2]};
    for (int i = 0; i < s->nq; i++) {
        ExprId qi = expr_var(P, i, 0), di[3];
        int any = 0;
        for (int k = 0; k < 3; k++)
            any |= (di[k] = diff_partial(D, at[k], qi)) != EXPR_ZERO;
        if (!any)
            continue;
        if (found == nmax)
            return -1;
        coord[found] = i;
        for (int k = 0; k < 3; k++) {
            if (!constant_in_time(D, di[k]))
                return -1;
            d[found][k] = di[k];
            c[k] = expr_sub(P, c[k], expr_mul(P, di[k], qi));
        }
        found++;
    }
    for (int k = 0; k < 3; k++)
        if (!constant_in_time(D, c[k]))
            return -1;
    return found;
}

/* Check the chain of m's point and keep it, mark the frames above it in
 * found->above, set the pivots of those that turn, and gather its sliding
 * links.  Returns the reason it does not fit, or NULL. */
static const char *
hang(const Spec *s, const Kin *K, Arena *A, ExprPool *P, Diff *D, Mass *ms, Found *fd)
{
    /* the chain is kept on the stack; a longer one is refused, and
     * Lagrange's form derives the model as before */
    enum { CHAIN_MAX = 256 };
    /* a link slides along at most the three directions of space */
    enum { SLIDES_MAX = 3 };
    int from[CHAIN_MAX], fr[CHAIN_MAX], sl[CHAIN_MAX], n = 0;
    for (int p = ms->point; p > KIN_ORIGIN; n++) {
        if (n == CHAIN_MAX)
            return arena_printf(A, "'%s' hangs from more than %d points", ms->name, CHAIN_MAX);
        ExprId at[3], off[3], d[SLIDES_MAX][3];
        from[n] = kin_point_link(K, p, &fr[n], at, off);
        sl[n] = -1;
        int varies = 0, coord[SLIDES_MAX], ns;
        for (int k = 0; k < 3; k++)
            varies |= !constant_in_time(D, at[k]);
        if (varies) {
            if ((ns = affine(s, P, D, at, SLIDES_MAX, coord, d)) <= 0)
                return arena_printf(A, "the position of '%s' moves in a frame other than "
                                    "along constant directions by its coordinates (an "
                                    "offset c + d1 q1 + ... + d%d q%d)", ms->name,
                                    SLIDES_MAX, SLIDES_MAX);
            int j = 0;
            while (j < fd->nslide && fd->slide[j].point != p)
                j++;
            if (j == fd->nslide) /* the point's first mass: its slides */
                for (int k = 0; k < ns; k++)
                    fd->slide[fd->nslide++] = (Slide){p, fr[n], coord[k], {d[k][0], d[k][1], d[k][2]}};
            sl[n] = j;
        }
        p = from[n] < 0 ? KIN_ORIGIN : from[n];
    }
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
        fd->above[g] = 1;
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
        if (fd->pivot[g][0] == EXPR_NONE) {
            memcpy(fd->pivot[g], p, sizeof p);
            fd->pivot_pt[g] = pt;
        } else if (memcmp(fd->pivot[g], p, sizeof p)) {
            return arena_printf(A, "a frame turns '%s' about another point than the other "
                                "masses it turns", ms->name);
        }
    }
    ms->n = n;
    ms->from = arena_new_array(A, int, n + 1);
    ms->fr = arena_new_array(A, int, n + 1);
    ms->sl = arena_new_array(A, int, n + 1);
    memcpy(ms->from, from, (size_t)n * sizeof *from);
    memcpy(ms->fr, fr, (size_t)n * sizeof *fr);
    memcpy(ms->sl, sl, (size_t)n * sizeof *sl);
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
            kin_mat3_mul(P, Q, Rk, Q);
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

/* The joints as they are found: turn ids first (by kin's frames, then
 * their turns), then the slides. */
typedef struct Joints {
    int nturn, n, nslide;
    const Slide *slide; /* [nslide]: joint nturn + k is slide k */
    int *first;     /* per kin frame: the id of its first coordinate turn */
    int *nct;       /* per kin frame: how many */
    Place *place;   /* per id: its axes */
    int *origin;    /* per id: a point at its origin (0: the world's) */
    int *coord;     /* per id */
    int *ndof;      /* per id: 1, or 4 (3) for a turn by a quaternion (with speeds) */
    int (*qc)[4];   /* per id: its velocity slots (Spec.vcoord) */
    int *up;        /* per id: the joint before it (-1 the world; -2 not yet seen) */
} Joints;

/* up[j] = prev, or the reason two masses disagree. */
static const char *
link_joint(Joints *J, Arena *A, const Mass *ms, int prev, int j)
{
    if (J->up[j] == -2)
        J->up[j] = prev;
    else if (J->up[j] != prev)
        return arena_printf(A, "the joints above '%s' come in another order than above the "
                            "other masses they move", ms->name);
    return NULL;
}

/* Walk ms's chain from the world outward: each joint's parent, and the
 * last one (its carrier) in *carrier (-1: none, it does not move). */
static const char *
sequence(const Kin *K, Arena *A, Joints *J, const Mass *ms, int *carrier)
{
    int prev = -1, dmax = 0;
    const char *why;
    for (int k = ms->n; k >= 0; k--) { /* k = -1: the mass's own frame, at its point */
        int f = k > 0 ? ms->fr[k - 1] : ms->frame, d = depth(K, f);
        if (d > dmax) { /* the frames entered: depths dmax + 1 .. d, top down */
            int *path = arena_new_array(A, int, d - dmax + 1), np = 0;
            for (int g = f; depth(K, g) > dmax; g = kin_parent(K, g))
                path[np++] = g;
            for (int i = np - 1; i >= 0; i--)
                for (int t = 0; t < J->nct[path[i]]; t++) {
                    int j = J->first[path[i]] + t;
                    if ((why = link_joint(J, A, ms, prev, j)))
                        return why;
                    prev = j;
                }
            dmax = d;
        }
        int first = k > 0 ? ms->sl[k - 1] : -1; /* the link's slides, in a row */
        for (int j = first; j >= 0 && j < J->nslide && J->slide[j].point == J->slide[first].point;
             j++) {
            if ((why = link_joint(J, A, ms, prev, J->nturn + j)))
                return why;
            prev = J->nturn + j;
        }
    }
    *carrier = prev;
    return NULL;
}

/* A wheel: a turn about a coordinate axis of its own that carries a mass
 * symmetric about that axis (I diagonal with the other two moments the
 * same expression, h along the axis) and nothing else.  Turning it leaves
 * its mass where it was, so its coordinates may as well be the axes just
 * before the turn (Q = Qf): its angle then appears nowhere, and the
 * derivatives along it are structurally 0 (a rolling wheel's angle is a
 * symmetry; rounding noise in dE/dangle would split the linearization's
 * double zero eigenvalue by sqrt(epsilon)). */
static void
spin_in_place(Tree *t, int k)
{
    TreeTurn *tk = &t->turn[k];
    int a = -1;
    for (int j = 0; j < 3; j++)
        if (tk->al[j] == EXPR_ONE && tk->al[(j + 1) % 3] == EXPR_ZERO &&
            tk->al[(j + 2) % 3] == EXPR_ZERO)
            a = j;
    if (tk->slide || a < 0)
        return;
    for (int j = 0; j < t->nturns; j++)
        if (t->turn[j].up == k)
            return;
    int b = (a + 1) % 3, c = (a + 2) % 3;
    if (tk->h[b] != EXPR_ZERO || tk->h[c] != EXPR_ZERO || tk->I[4 * b] != tk->I[4 * c])
        return;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (i != j && tk->I[3 * i + j] != EXPR_ZERO)
                return;
    memcpy(tk->Q, tk->Qf, sizeof tk->Q);
}

/* Each joint's and mass's local coordinates (tree.h), in `order`. */
static const char *
localize(const Kin *K, Arena *A, ExprPool *P, Diff *D, Tree *t,
         const Joints *J, const int *order, const int *pos, const Mass *ms, int nm,
         const int *carrier, const ExprId *q1)
{
    static const char *const moves = "a joint's local offset or inertia moves (a tree "
                                     "eomc cannot yet put in local coordinates)";
    const ExprId zero[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    for (int k = 0; k < J->n; k++) {
        int j = order[k], u = J->up[j];
        TreeTurn *tk = &t->turn[k];
        tk->coord = J->coord[j];
        tk->ndof = J->ndof[j];
        memcpy(tk->qc, J->qc[j], sizeof tk->qc);
        tk->up = u >= 0 ? pos[u] : -1;
        tk->slide = j >= J->nturn;
        Place up = u >= 0 ? J->place[u] : (Place){KIN_WORLD, 0}, at = J->place[j];
        axes_between(K, A, P, up, at, tk->Q);
        ExprId uo[3];
        memcpy(uo, zero, sizeof uo);
        if (u >= 0 && J->origin[u] > KIN_ORIGIN)
            kin_pos(K, J->origin[u], uo);
        const Slide *sd = tk->slide ? &J->slide[j - J->nturn] : NULL;
        if (sd && sd > J->slide && sd[-1].point == sd->point) {
            /* a link's later slide: its offset from the one before, in the
             * same axes (Q = 1), is d q alone */
            memcpy(tk->Qf, tk->Q, sizeof tk->Q);
            tk->angle = EXPR_NONE;
            for (int i = 0; i < 3; i++)
                tk->al[i] = sd->d[i], tk->r[i] = expr_mul(P, sd->d[i], expr_var(P, sd->coord, 0));
            continue;
        }
        if (!offset_in(K, A, P, J->origin[j], uo, up, tk->r))
            return moves;
        if (sd) {
            /* the first: the link's offset but for the later slides' */
            memcpy(tk->Qf, tk->Q, sizeof tk->Q);
            tk->angle = EXPR_NONE;
            for (int i = 0; i < 3; i++)
                tk->al[i] = sd->d[i];
            for (const Slide *x = sd + 1; x < J->slide + J->nslide && x->point == sd->point; x++) {
                ExprId qx = expr_var(P, x->coord, 0), zero0 = EXPR_ZERO, r[3];
                expr_subst_many(P, 3, tk->r, 1, &qx, &zero0, r);
                memcpy(tk->r, r, sizeof r);
            }
            continue;
        }
        axes_between(K, A, P, up, (Place){at.f, at.n - 1}, tk->Qf);
        ExprId Rk[9], wa[3];
        kin_turn_local(K, at.f, at.n - 1, &tk->angle, tk->al, Rk);
        kin_turn_omega(K, at.f, at.n - 1, wa);
        for (int d = 0; tk->ndof > 1 && d < tk->ndof; d++) /* a ball's axes */
            for (int i = 0; i < 3; i++)
                tk->Sw[d][i] = diff_partial(D, wa[i], q1[tk->qc[d]]);
        for (int i = 0; i < 3; i++)
            if (!constant_in_time(D, tk->r[i]))
                return moves;
    }
    for (int k = 0; k < J->n; k++) {
        TreeTurn *tk = &t->turn[k];
        tk->m = tk->h[0] = tk->h[1] = tk->h[2] = EXPR_ZERO;
        for (int i = 0; i < 9; i++)
            tk->I[i] = EXPR_ZERO;
    }
    for (int k = 0; k < nm; k++) {
        int c = carrier[k];
        if (c < 0) /* no joint moves it */
            continue;
        TreeTurn *tc = &t->turn[pos[c]];
        ExprId o[3], d[3], Q[9], Jm[9];
        memcpy(o, zero, sizeof o);
        if (J->origin[c] > KIN_ORIGIN)
            kin_pos(K, J->origin[c], o);
        if (!offset_in(K, A, P, ms[k].point, o, J->place[c], d))
            return moves;
        axes_between(K, A, P, J->place[c], (Place){ms[k].frame, nturns_of(K, ms[k].frame)}, Q);
        for (int i = 0; i < 9; i++)
            Jm[i] = EXPR_ZERO;
        if (ms[k].I) { /* Q I Q^T */
            ExprId QI[9], Qt[9];
            kin_mat3_mul(P, Q, ms[k].I, QI);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    Qt[3 * i + j] = Q[3 * j + i];
            kin_mat3_mul(P, QI, Qt, Jm);
            for (int i = 0; i < 3; i++) /* symmetric to the bit */
                for (int j = 0; j < i; j++)
                    Jm[3 * j + i] = Jm[3 * i + j];
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
                Jm[3 * i + j] = expr_add(P, Jm[3 * i + j], e);
            }
        tc->m = expr_add(P, tc->m, ms[k].m);
        for (int i = 0; i < 3; i++)
            tc->h[i] = expr_add(P, tc->h[i], h[i]);
        for (int i = 0; i < 9; i++)
            tc->I[i] = expr_add(P, tc->I[i], Jm[i]);
    }
    for (int k = 0; k < J->n; k++) {
        const TreeTurn *tk = &t->turn[k];
        for (int i = 0; i < 9; i++)
            if (!constant_in_time(D, tk->I[i]) || (i < 3 && !constant_in_time(D, tk->h[i])))
                return moves;
    }
    for (int k = 0; k < J->n; k++)
        spin_in_place(t, k);
    return NULL;
}

/* The name of velocity slot j: its coordinate's, or its speed's. */
static const char *
slot_name(const Spec *s, int j)
{
    int c = s->vcoord[j];
    return c < s->nq ? s->coord[c].name : s->speed[c - s->nq].name;
}

/* Each kinetic-energy term no mass carries must move with one joint's
 * rates alone, so that its inertia lies in that joint's own block of M
 * (a rotor's 1/2 a q'^2): the recursions add it there.  NULL, or why
 * not. */
static const char *
joint_local(const Spec *s, Arena *A, ExprPool *P, const Tree *t, const ExprId *q1, int nkin,
            const ExprId *kin)
{
    if (nkin == 0)
        return NULL;
    int *joint = arena_new_array(A, int, s->nv);
    for (int k = 0; k < t->nturns; k++)
        for (int d = 0; d < t->turn[k].ndof; d++)
            joint[t->turn[k].qc[d]] = k;
    size_t npool = expr_pool_size(P);
    unsigned char *mark = calloc(npool, 1);
    const char *why = NULL;
    for (int k = 0; !why && k < nkin; k++) {
        memset(mark, 0, npool);
        expr_mark(P, 1, &kin[k], mark);
        int first = -1;
        for (int i = 0; !why && i < s->nv; i++)
            if ((size_t)q1[i] < npool && mark[q1[i]]) {
                if (first < 0)
                    first = i;
                else if (joint[i] != joint[first])
                    why = arena_printf(A, "a kinetic-energy term moves with the rates of '%s' "
                                       "and '%s', two joints", slot_name(s, first),
                                       slot_name(s, i));
            }
        for (int i = 0; !why && s->nspeed && i < s->nq; i++)
            if (s->vslot[i] < 0 && (size_t)expr_var(P, i, 0) < npool &&
                mark[expr_var(P, i, 0)])
                why = arena_printf(A, "a kinetic-energy term depends on '%s', an Euler "
                                   "parameter turned by speeds", s->coord[i].name);
    }
    free(mark);
    return why;
}

Tree *
tree_build(const Spec *s, const ExprId *q1, int nkin, const ExprId *kin, Arena *A,
           ExprPool *P, Diff *D, const char **why)
{
    const Kin *K = s->kin;
    if (!K || s->nbody + s->npart == 0) {
        *why = "the spec places no mass by frames";
        return NULL;
    }
    int nm = s->nbody + s->npart, nf = kin_nframes(K), np = kin_npoints(K);
    Mass *ms = arena_new_array(A, Mass, nm);
    for (int k = 0; k < s->nbody; k++) {
        const SpecBody *b = &s->body[k];
        if (b->frame < 0 || b->point < 0) {
            *why = arena_printf(A, "body '%s' is not placed by a frame with its centre at "
                                "a point", b->name);
            return NULL;
        }
        ms[k] = (Mass){b->name, b->frame, b->point, b->mass, b->inertia, 0, NULL, NULL, NULL};
    }
    for (int k = 0; k < s->npart; k++) {
        const SpecParticle *pt = &s->part[k];
        if (pt->point < 0) {
            *why = arena_printf(A, "particle '%s' is not at a point", pt->name);
            return NULL;
        }
        ms[s->nbody + k] = (Mass){pt->name, -1, pt->point, pt->mass, NULL, 0, NULL, NULL, NULL};
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
    Found fd = {arena_new_array(A, Point3, nf), arena_new_array(A, int, nf),
                arena_new_array(A, int, nf), arena_new_array(A, Slide, 3 * np + 1), 0};
    for (int g = 0; g < nf; g++)
        fd.pivot[g][0] = EXPR_NONE, fd.above[g] = 0;
    for (int k = 0; k < nm; k++)
        if ((*why = hang(s, K, A, P, D, &ms[k], &fd)))
            return NULL;
    /* the coordinate turns of the frames above a mass, in kin's order */
    Joints J = {0};
    J.first = arena_new_array(A, int, nf);
    J.nct = arena_new_array(A, int, nf);
    int *used = arena_new_array(A, int, s->nv + 1);
    for (int i = 0; i < s->nv; i++)
        used[i] = 0;
    int cap = fd.nslide + 1;
    for (int g = 0; g < nf; g++) {
        ExprId rate, a[3];
        for (int k = 0; kin_turn_of(K, g, k, &rate, a); k++)
            cap++;
    }
    J.place = arena_new_array(A, Place, cap);
    J.origin = arena_new_array(A, int, cap);
    J.coord = arena_new_array(A, int, cap);
    J.ndof = arena_new_array(A, int, cap);
    J.qc = arena_alloc(A, (size_t)cap * sizeof *J.qc);
    J.up = arena_new_array(A, int, cap);
    for (int g = 0; g < nf; g++) {
        J.first[g] = J.nturn, J.nct[g] = 0;
        if (g == KIN_WORLD || !fd.above[g])
            continue;
        ExprId rate, a[3];
        for (int k = 0; kin_turn_of(K, g, k, &rate, a); k++) {
            if (rate == EXPR_ZERO) /* a fixed angle: part of the frame's shape */
                continue;
            int j = J.nturn, nd = 0;
            if (rate == EXPR_NONE) { /* a ball: the parameters its rate is made of */
                ExprId wa[3];
                kin_turn_omega(K, g, k, wa);
                for (int i = 0; i < s->nv; i++) {
                    int in = 0;
                    for (int r = 0; r < 3; r++)
                        in |= diff_partial(D, wa[r], q1[i]) != EXPR_ZERO;
                    if (in && nd < 4)
                        J.qc[j][nd] = i;
                    nd += in;
                }
            } else {
                while (nd < s->nv && q1[nd] != rate)
                    nd++;
                if (nd == s->nv) {
                    *why = "a turn's angle is not a coordinate";
                    return NULL;
                }
                J.qc[j][0] = nd, nd = 1;
            }
            int speeds = nd == 3 && s->vcoord[J.qc[j][0]] >= s->nq;
            if (nd != 1 && nd != 4 && !speeds) {
                *why = "a quaternion's turn does not move by four Euler parameters";
                return NULL;
            }
            for (int d = 0; d < nd; d++)
                if (used[J.qc[j][d]]++) {
                    *why = arena_printf(A, nd == 1 ? "coordinate '%s' is the angle of two turns"
                                                   : "'%s' moves two joints",
                                        slot_name(s, J.qc[j][d]));
                    return NULL;
                }
            J.nturn++;
            J.place[j] = (Place){g, k + 1}, J.origin[j] = fd.pivot_pt[g];
            J.coord[j] = nd == 1 ? s->vcoord[J.qc[j][0]] : -1;
            J.ndof[j] = nd;
            J.nct[g]++;
        }
    }
    J.n = J.nturn + fd.nslide;
    J.nslide = fd.nslide, J.slide = fd.slide;
    for (int k = 0; k < fd.nslide; k++) {
        const Slide *sd = &fd.slide[k];
        int j = J.nturn + k;
        if (s->vslot[sd->coord] < 0 || used[s->vslot[sd->coord]]++) {
            *why = arena_printf(A, "coordinate '%s' moves two joints", s->coord[sd->coord].name);
            return NULL;
        }
        J.place[j] = (Place){sd->frame, nturns_of(K, sd->frame)};
        J.origin[j] = sd->point, J.coord[j] = sd->coord, J.qc[j][0] = s->vslot[sd->coord];
        J.ndof[j] = 1;
    }
    for (int i = 0; i < s->nv; i++)
        if (!used[i]) {
            *why = arena_printf(A, "'%s' is not the rate of a turn, a slide or a ball joint",
                                slot_name(s, i));
            return NULL;
        }
    for (int j = 0; j < J.n; j++)
        J.up[j] = -2;
    int *carrier = arena_new_array(A, int, nm);
    for (int k = 0; k < nm; k++)
        if ((*why = sequence(K, A, &J, &ms[k], &carrier[k])))
            return NULL;
    /* parents first: the smallest id whose parent is placed, each time
     * (the found order itself when there are no slides) */
    int *order = arena_new_array(A, int, J.n + 1), *pos = arena_new_array(A, int, J.n + 1);
    for (int j = 0; j < J.n; j++)
        pos[j] = -1;
    for (int placed = 0; placed < J.n;) {
        int before = placed;
        for (int j = 0; j < J.n; j++)
            if (pos[j] < 0 && (J.up[j] == -1 || (J.up[j] >= 0 && pos[J.up[j]] >= 0))) {
                pos[j] = placed, order[placed++] = j;
                break;
            }
        if (placed == before) {
            *why = "a joint moves no mass";
            return NULL;
        }
    }
    Tree *t = arena_alloc(A, sizeof *t);
    t->nturns = J.n;
    t->turn = arena_new_array(A, TreeTurn, J.n + 1);
    if ((*why = localize(K, A, P, D, t, &J, order, pos, ms, nm, carrier, q1)))
        return NULL;
    if ((*why = joint_local(s, A, P, t, q1, nkin, kin)))
        return NULL;
    return t;
}
