/*
 * eomc_tree.h: Featherstone's recursions over a tree of turning joints, as
 * loops over a model's tables, for the models too large to be compiled
 * quickly as straight-line code (eomc compile --code tables; docs/forms.md).
 *
 * The straight-line articulated-body form unrolls the same algorithms into
 * expressions, where every constant folds; these loops read the constants
 * from tables instead, so the C compiler sees a few hundred lines whatever
 * the model's size.  The generated file includes this header after
 * eomc_model.h; every function is static and written in eomc_real, so the
 * extended-precision compilation (-DEOMC_EXTENDED) gets its own copy.
 *
 * Each turn has its own coordinates: origin at its frame's pivot, axes
 * those of its frame just after the turn.  There its axis is a constant
 * (one of its own x, y, z, or a unit vector), and it sits in the turn
 * above it ("up") by the rotation Q = Qf Ra(angle) (Qf constant, Ra the
 * turn about its axis) and the constant offset r of its origin, in up's
 * axes.  A spatial vector is (angular, linear) about the origin, in the
 * axes, of the turn it belongs to.  The world is the turn above the
 * roots; it accelerates by a0 (Featherstone's a_0 = -g stands for a
 * uniform gravity field).
 */
#ifndef EOMC_TREE_HEADER
#define EOMC_TREE_HEADER

#include "eomc_model.h"

/* The small helpers are inlined, and the hot ones specialized to a
 * coordinate axis known at compile time (each called as F(0), F(1), F(2)
 * from a switch), so that their index arithmetic folds. */
#if defined(__GNUC__)
#define EOMC_TREE_INLINE static inline __attribute__((always_inline))
/* a constrained model's extended-precision twin has no accel to call it */
#define EOMC_TREE_MAYBE_UNUSED static __attribute__((unused))
#else
#define EOMC_TREE_INLINE static inline
#define EOMC_TREE_MAYBE_UNUSED static
#endif

/* A joint: a turn, or a slide (the offset of its origin from up's is
 * then r + Qf d q, and Q = Qf). */
typedef struct eomc_tree_turn {
    int up;    /* the joint above (a lower index), -1: the world */
    int coord; /* the coordinate that is its angle or length */
    int axis;  /* 0, 1, 2: a turn about its own x, y or z axis; 3: along or about
                * the vector in its numbers */
    int fixed; /* Qf is not the identity */
    int slide; /* a slide, along the vector (axis 3) */
} eomc_tree_turn;

/* A joint's numbers, EOMC_TREE_STRIDE of them per joint, then a0 [6]. */
enum {
    EOMC_TREE_QF = 0,    /* [9] Qf, row-major (columns: its axes in up's) */
    EOMC_TREE_R = 9,     /* [3] r (a slide's at length 0) */
    EOMC_TREE_AXIS = 12, /* [3] the unit axis of a turn, d of a slide (axis 3) */
    EOMC_TREE_M = 15,    /* the mass the turn carries last (0 inside a frame) */
    EOMC_TREE_H = 16,    /* [3] its first moment about the origin */
    EOMC_TREE_I = 19,    /* [6] its inertia about the origin: xx yy zz xy xz yz */
    EOMC_TREE_STRIDE = 25
};

/* Work space per turn, in eomc_real (the caller's array, nt of them). */
enum { EOMC_TREE_WORK = 96 };

/* ---- 3-vectors and 3 x 3 blocks (row-major) ---- */

EOMC_TREE_INLINE void
eomc_tree_cross(const eomc_real *a, const eomc_real *b, eomc_real *out)
{
    eomc_real x = a[1] * b[2] - a[2] * b[1];
    eomc_real y = a[2] * b[0] - a[0] * b[2];
    eomc_real z = a[0] * b[1] - a[1] * b[0];
    out[0] = x, out[1] = y, out[2] = z;
}

/* y = Q x (up = 1) or Q^T x (up = 0) */
EOMC_TREE_INLINE void
eomc_tree_rot(const eomc_real *Q, int up, const eomc_real *x, eomc_real *y)
{
    eomc_real a = x[0], b = x[1], c = x[2];
    if (up) {
        y[0] = Q[0] * a + Q[1] * b + Q[2] * c;
        y[1] = Q[3] * a + Q[4] * b + Q[5] * c;
        y[2] = Q[6] * a + Q[7] * b + Q[8] * c;
    } else {
        y[0] = Q[0] * a + Q[3] * b + Q[6] * c;
        y[1] = Q[1] * a + Q[4] * b + Q[7] * c;
        y[2] = Q[2] * a + Q[5] * b + Q[8] * c;
    }
}

/* X = Q X Q^T in place (sym: X symmetric, kept so to the bit). */
static void
eomc_tree_rot_block(const eomc_real *Q, eomc_real *X, int sym)
{
    eomc_real T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            T[3 * i + j] = Q[3 * i] * X[j] + Q[3 * i + 1] * X[3 + j] + Q[3 * i + 2] * X[6 + j];
    for (int i = 0; i < 3; i++)
        for (int j = sym ? i : 0; j < 3; j++) {
            X[3 * i + j] = T[3 * i] * Q[3 * j] + T[3 * i + 1] * Q[3 * j + 1] +
                           T[3 * i + 2] * Q[3 * j + 2];
            if (sym)
                X[3 * j + i] = X[3 * i + j];
        }
}

/* X = Ra X Ra^T in place for the turn Ra by (c, s) about coordinate axis
 * k: only the other two rows and columns mix. */
EOMC_TREE_INLINE void
eomc_tree_turn_block_k(int k, eomc_real c, eomc_real s, eomc_real *X, int sym)
{
    int i = (k + 1) % 3, j = (k + 2) % 3; /* e_i turns toward e_j */
    if (sym) { /* six entries, from their old values in registers */
        eomc_real a = X[4 * i], b = X[4 * j], o = X[3 * i + j];
        eomc_real p = X[3 * k + i], r = X[3 * k + j];
        eomc_real cc = c * c, ss = s * s, cs = c * s, cso = 2 * cs * o;
        X[4 * i] = cc * a - cso + ss * b;
        X[4 * j] = ss * a + cso + cc * b;
        X[3 * i + j] = X[3 * j + i] = cs * (a - b) + (cc - ss) * o;
        X[3 * k + i] = X[3 * i + k] = c * p - s * r;
        X[3 * k + j] = X[3 * j + k] = s * p + c * r;
        return;
    }
    for (int col = 0; col < 3; col++) { /* rows: Ra X */
        eomc_real xi = X[3 * i + col], xj = X[3 * j + col];
        X[3 * i + col] = c * xi - s * xj;
        X[3 * j + col] = s * xi + c * xj;
    }
    for (int row = 0; row < 3; row++) { /* columns: (Ra X) Ra^T */
        eomc_real xi = X[3 * row + i], xj = X[3 * row + j];
        X[3 * row + i] = c * xi - s * xj;
        X[3 * row + j] = s * xi + c * xj;
    }
}

EOMC_TREE_INLINE void
eomc_tree_turn_block(int k, eomc_real c, eomc_real s, eomc_real *X, int sym)
{
    switch (k) {
    case 0: eomc_tree_turn_block_k(0, c, s, X, sym); break;
    case 1: eomc_tree_turn_block_k(1, c, s, X, sym); break;
    default: eomc_tree_turn_block_k(2, c, s, X, sym); break;
    }
}

/* Work layout, per turn */
enum {
    EOMC_TW_Q = 0,    /* [9] */
    EOMC_TW_CS = 9,   /* [2] */
    EOMC_TW_V = 11,   /* [6] velocity */
    EOMC_TW_C = 17,   /* [6] velocity-product acceleration */
    EOMC_TW_P = 23,   /* [6] bias force pA */
    EOMC_TW_A = 29,   /* [9] IA's blocks A, B, C */
    EOMC_TW_B = 38,   /* [9] */
    EOMC_TW_CC = 47,  /* [9] */
    EOMC_TW_U = 56,   /* [6] */
    EOMC_TW_DINV = 62,
    EOMC_TW_SU = 63,  /* u */
    EOMC_TW_ACC = 64, /* [6] acceleration */
    EOMC_TW_IC = 70,  /* [13] composite rigid inertia: m, h[3], I[9] */
    EOMC_TW_R = 83,   /* [3] a slide's offset from up */
};

/* ---- per turn ---- */

/* Every turn's (cos, sin) of its angle into its work's (c, s), by one
 * call of eomc_sincos per EOMC_TREE_ANGLES turns (several at once where
 * the machine has vector instructions: eomc_model.h). */
enum { EOMC_TREE_ANGLES = 16 };

EOMC_TREE_MAYBE_UNUSED void
eomc_tree_angles(const eomc_tree_turn *T, int nt, const eomc_real *q, eomc_real *w)
{
    eomc_real x[EOMC_TREE_ANGLES], s[EOMC_TREE_ANGLES], c[EOMC_TREE_ANGLES];
    int turn[EOMC_TREE_ANGLES];
    for (int k = 0; k < nt;) {
        int m = 0;
        for (; k < nt && m < EOMC_TREE_ANGLES; k++)
            if (!T[k].slide)
                turn[m] = k, x[m++] = q[T[k].coord];
        eomc_sincos(m, x, s, c);
        for (int j = 0; j < m; j++) {
            eomc_real *cs = w + EOMC_TREE_WORK * turn[j] + EOMC_TW_CS;
            cs[0] = c[j], cs[1] = s[j];
        }
    }
}

/* The turn's place in up: Q (dense) from its angle, whose (c, s) a turn
 * finds in *cs (eomc_tree_angles); a slide sets *cs = (1, 0). */
static void
eomc_tree_place(const eomc_tree_turn *t, const eomc_real *d, eomc_real angle, eomc_real *Q,
                eomc_real *cs)
{
    if (t->slide) { /* Q = Qf, and the offset r + Qf d q into the work */
        const eomc_real *F = d + EOMC_TREE_QF, *a = d + EOMC_TREE_AXIS;
        eomc_real *r = Q + EOMC_TW_R - EOMC_TW_Q;
        cs[0] = 1, cs[1] = 0;
        for (int e = 0; e < 9; e++)
            Q[e] = t->fixed ? F[e] : (eomc_real)(e % 4 == 0);
        for (int i = 0; i < 3; i++)
            r[i] = d[EOMC_TREE_R + i] +
                   (Q[3 * i] * a[0] + Q[3 * i + 1] * a[1] + Q[3 * i + 2] * a[2]) * angle;
        return;
    }
    eomc_real c = cs[0], s = cs[1], R[9];
    if (t->axis < 3 && !t->fixed) /* Q is not needed: (c, s) say it all */
        return;
    if (t->axis < 3) {
        int k = t->axis, i = (k + 1) % 3, j = (k + 2) % 3;
        for (int e = 0; e < 9; e++)
            R[e] = 0;
        R[4 * k] = 1;
        R[4 * i] = R[4 * j] = c;
        R[3 * j + i] = s, R[3 * i + j] = -s;
    } else { /* Rodrigues: c 1 + s [a]x + (1 - c) a a^T */
        const eomc_real *a = d + EOMC_TREE_AXIS;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                R[3 * i + j] = (1 - c) * a[i] * a[j] + (i == j ? c : 0);
        R[1] -= s * a[2], R[2] += s * a[1], R[3] += s * a[2];
        R[5] -= s * a[0], R[6] -= s * a[1], R[7] += s * a[0];
    }
    if (!t->fixed) {
        for (int e = 0; e < 9; e++)
            Q[e] = R[e];
        return;
    }
    const eomc_real *F = d + EOMC_TREE_QF;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Q[3 * i + j] = F[3 * i] * R[j] + F[3 * i + 1] * R[3 + j] + F[3 * i + 2] * R[6 + j];
}

/* y = Q x (up = 1) or Q^T x, Q the turn's (w: its work, with Q and
 * (c, s)): about a coordinate axis with no constant rotation only two
 * components mix. */
EOMC_TREE_INLINE void
eomc_tree_rot_k(int k, eomc_real c, eomc_real s, const eomc_real *x, eomc_real *y)
{
    int i = (k + 1) % 3, j = (k + 2) % 3;
    eomc_real xi = x[i], xj = x[j];
    y[k] = x[k];
    y[i] = c * xi - s * xj;
    y[j] = s * xi + c * xj;
}

EOMC_TREE_INLINE void
eomc_tree_rot_turn(const eomc_tree_turn *t, const eomc_real *w, int up, const eomc_real *x,
                   eomc_real *y)
{
    eomc_real c = w[9], s = up ? w[10] : -w[10];
    if (t->fixed || t->axis == 3) {
        eomc_tree_rot(w, up, x, y);
        return;
    }
    switch (t->axis) {
    case 0: eomc_tree_rot_k(0, c, s, x, y); break;
    case 1: eomc_tree_rot_k(1, c, s, x, y); break;
    default: eomc_tree_rot_k(2, c, s, x, y); break;
    }
}

EOMC_TREE_INLINE int
eomc_tree_offset(const eomc_real *r)
{
    return r[0] != 0 || r[1] != 0 || r[2] != 0;
}

/* A motion x in up's coordinates, in the turn's: w' = Q^T w,
 * v' = Q^T (v - r x w). */
EOMC_TREE_INLINE void
eomc_tree_motion_down(const eomc_tree_turn *t, const eomc_real *w, const eomc_real *r,
                      const eomc_real *x, eomc_real *y)
{
    eomc_real rw[3], v[3];
    eomc_tree_rot_turn(t, w, 0, x, y);
    if (!eomc_tree_offset(r)) {
        eomc_tree_rot_turn(t, w, 0, x + 3, y + 3);
        return;
    }
    eomc_tree_cross(r, x, rw);
    for (int i = 0; i < 3; i++)
        v[i] = x[3 + i] - rw[i];
    eomc_tree_rot_turn(t, w, 0, v, y + 3);
}

/* f += a force x in the turn's coordinates, carried into up's:
 * f' = Q f, n' = Q n + r x f'. */
EOMC_TREE_INLINE void
eomc_tree_force_up(const eomc_tree_turn *t, const eomc_real *w, const eomc_real *r,
                   const eomc_real *x, eomc_real *f)
{
    eomc_real n[3], g[3], rg[3] = {0, 0, 0};
    eomc_tree_rot_turn(t, w, 1, x, n);
    eomc_tree_rot_turn(t, w, 1, x + 3, g);
    if (eomc_tree_offset(r))
        eomc_tree_cross(r, g, rg);
    for (int i = 0; i < 3; i++)
        f[i] += n[i] + rg[i], f[3 + i] += g[i];
}

/* The rigid inertia's blocks: A = I, B = [h]x, C = m 1. */
static void
eomc_tree_rigid(const eomc_real *d, eomc_real *A, eomc_real *B, eomc_real *C)
{
    /* not I: <complex.h>, which <tgmath.h> includes, defines it */
    const eomc_real *J = d + EOMC_TREE_I, *h = d + EOMC_TREE_H, m = d[EOMC_TREE_M];
    A[0] = J[0], A[4] = J[1], A[8] = J[2];
    A[1] = A[3] = J[3], A[2] = A[6] = J[4], A[5] = A[7] = J[5];
    B[0] = B[4] = B[8] = 0;
    B[1] = -h[2], B[2] = h[1], B[3] = h[2], B[5] = -h[0], B[6] = -h[1], B[7] = h[0];
    for (int e = 0; e < 9; e++)
        C[e] = e % 4 == 0 ? m : 0;
}

/* y = [[A, B], [B^T, C]] x */
EOMC_TREE_INLINE void
eomc_tree_inertia_times(const eomc_real *A, const eomc_real *B, const eomc_real *C,
                        const eomc_real *x, eomc_real *y)
{
    for (int i = 0; i < 3; i++) {
        y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2] +
               B[3 * i] * x[3] + B[3 * i + 1] * x[4] + B[3 * i + 2] * x[5];
        y[3 + i] = B[i] * x[0] + B[3 + i] * x[1] + B[6 + i] * x[2] + C[3 * i] * x[3] +
                   C[3 * i + 1] * x[4] + C[3 * i + 2] * x[5];
    }
}

/* f = v x* (I v) + I a for the rigid inertia in d (a may be NULL) */
static void
eomc_tree_body_force(const eomc_real *d, const eomc_real *v, const eomc_real *a,
                     eomc_real *f)
{
    eomc_real A[9], B[9], C[9], Iv[6], t[3];
    eomc_tree_rigid(d, A, B, C);
    eomc_tree_inertia_times(A, B, C, v, Iv);
    /* (w x n + u x g, w x g) for v = (w, u), Iv = (n, g) */
    eomc_tree_cross(v, Iv, f);
    eomc_tree_cross(v + 3, Iv + 3, t);
    for (int i = 0; i < 3; i++)
        f[i] += t[i];
    eomc_tree_cross(v, Iv + 3, f + 3);
    if (a) {
        eomc_tree_inertia_times(A, B, C, a, Iv);
        for (int i = 0; i < 6; i++)
            f[i] += Iv[i];
    }
}

/* The joint's spatial axis S: (a, 0) for a turn, (0, d) for a slide */
static void
eomc_tree_axis(const eomc_tree_turn *t, const eomc_real *d, eomc_real *S)
{
    for (int i = 0; i < 3; i++) {
        eomc_real a = t->axis < 3 ? (eomc_real)(i == t->axis) : d[EOMC_TREE_AXIS + i];
        S[i] = t->slide ? 0 : a;
        S[3 + i] = t->slide ? a : 0;
    }
}

/* The joint's offset from up: constant for a turn, in the work for a slide */
EOMC_TREE_INLINE const eomc_real *
eomc_tree_r(const eomc_tree_turn *t, const eomc_real *d, const eomc_real *wk)
{
    return t->slide ? wk + EOMC_TW_R : d + EOMC_TREE_R;
}

/* S . x for a joint's S and a 6-vector: its nonzero half only */
EOMC_TREE_INLINE eomc_real
eomc_tree_sdot(const eomc_tree_turn *t, const eomc_real *S, const eomc_real *x)
{
    int o = 3 * t->slide;
    return S[o] * x[o] + S[o + 1] * x[o + 1] + S[o + 2] * x[o + 2];
}


/* The composite rigid inertia Ic (m, h, I) of the turn (in its work)
 * added to up's, Icp: h' = Q h + m r, I' = J + 2 (r.g) 1 - (g r^T + r
 * g^T) + m (|r|^2 1 - r r^T) with g = Q h, J = Q I Q^T. */
static void
eomc_tree_composite_up(const eomc_tree_turn *t, const eomc_real *wk, const eomc_real *r,
                       eomc_real *Icp)
{
    const eomc_real *Ic = wk + EOMC_TW_IC;
    eomc_real m = Ic[0], g[3], J[9];
    eomc_tree_rot_turn(t, wk, 1, Ic + 1, g);
    for (int e = 0; e < 9; e++)
        J[e] = Ic[4 + e];
    if (t->axis < 3 && !t->fixed)
        eomc_tree_turn_block(t->axis, wk[EOMC_TW_CS], wk[EOMC_TW_CS + 1], J, 1);
    else
        eomc_tree_rot_block(wk + EOMC_TW_Q, J, 1);
    Icp[0] += m;
    if (!eomc_tree_offset(r)) {
        for (int e = 0; e < 9; e++)
            Icp[4 + e] += J[e];
        for (int i = 0; i < 3; i++)
            Icp[1 + i] += g[i];
        return;
    }
    eomc_real rg = r[0] * g[0] + r[1] * g[1] + r[2] * g[2];
    eomc_real rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Icp[4 + 3 * i + j] += J[3 * i + j] - (g[i] * r[j] + r[i] * g[j]) -
                                  m * r[i] * r[j] + (i == j ? 2 * rg + m * rr : 0);
    for (int i = 0; i < 3; i++)
        Icp[1 + i] += g[i] + m * r[i];
}

/* q'' by the articulated-body algorithm, its pivots piv[coord] and
 * mkk[coord] = M's diagonal (by the composite-rigid-body inertias), given
 * tau: the generalized forces other than the uniform gravity that a0
 * stands for.  a0: the world's acceleration, NULL for the tables' own (a
 * zero one with v = 0 gives q'' = M^-1 tau: a unit-load pass). */
EOMC_TREE_MAYBE_UNUSED void
eomc_tree_aba(const eomc_tree_turn *T, int nt, const eomc_real *d, const eomc_real *a0,
              const eomc_real *q, const eomc_real *v, const eomc_real *tau, eomc_real *w,
              eomc_real *qdd, eomc_real *piv, eomc_real *mkk)
{
    if (!a0)
        a0 = d + EOMC_TREE_STRIDE * nt;
    eomc_tree_angles(T, nt, q, w);
    for (int k = 0; k < nt; k++) {
        const eomc_tree_turn *t = &T[k];
        const eomc_real *dk = d + EOMC_TREE_STRIDE * k;
        eomc_real *wk = w + EOMC_TREE_WORK * k, *V = wk + EOMC_TW_V, *C = wk + EOMC_TW_C;
        eomc_real ax[6], rate = v[t->coord];
        eomc_tree_place(t, dk, q[t->coord], wk + EOMC_TW_Q, wk + EOMC_TW_CS);
        eomc_tree_axis(t, dk, ax);
        if (t->up >= 0) {
            eomc_tree_motion_down(t, wk, eomc_tree_r(t, dk, wk),
                                  w + EOMC_TREE_WORK * t->up + EOMC_TW_V, V);
            /* V x S rate, V before its own rate: (w x a, v x a) for a turn,
             * (0, w x d) for a slide */
            eomc_tree_cross(V, t->slide ? ax + 3 : ax, t->slide ? C + 3 : C);
            if (t->slide)
                C[0] = C[1] = C[2] = 0;
            else
                eomc_tree_cross(V + 3, ax, C + 3);
            for (int i = 0; i < 6; i++)
                C[i] *= rate;
        } else {
            for (int i = 0; i < 6; i++)
                V[i] = C[i] = 0;
        }
        for (int i = 3 * t->slide; i < 3 + 3 * t->slide; i++) /* S's nonzero half */
            V[i] += ax[i] * rate;
        eomc_tree_rigid(dk, wk + EOMC_TW_A, wk + EOMC_TW_B, wk + EOMC_TW_CC);
        if (dk[EOMC_TREE_M] != 0 || dk[EOMC_TREE_I] != 0 || dk[EOMC_TREE_I + 1] != 0 ||
            dk[EOMC_TREE_I + 2] != 0)
            eomc_tree_body_force(dk, V, NULL, wk + EOMC_TW_P);
        else
            for (int i = 0; i < 6; i++)
                wk[EOMC_TW_P + i] = 0;
        eomc_real *Ic = wk + EOMC_TW_IC;
        Ic[0] = dk[EOMC_TREE_M];
        for (int i = 0; i < 3; i++)
            Ic[1 + i] = dk[EOMC_TREE_H + i];
        for (int i = 0; i < 9; i++)
            Ic[4 + i] = wk[EOMC_TW_A + i];
    }
    for (int k = nt - 1; k >= 0; k--) {
        const eomc_tree_turn *t = &T[k];
        const eomc_real *dk = d + EOMC_TREE_STRIDE * k, *r = eomc_tree_r(t, dk, w + EOMC_TREE_WORK * k);
        eomc_real *wk = w + EOMC_TREE_WORK * k, *Q = wk + EOMC_TW_Q;
        eomc_real *A = wk + EOMC_TW_A, *B = wk + EOMC_TW_B, *Cb = wk + EOMC_TW_CC;
        eomc_real *U = wk + EOMC_TW_U, *pA = wk + EOMC_TW_P, ax[6];
        eomc_tree_axis(t, dk, ax);
        /* M_kk = S . Ic S, and Ic carried up (the parallel-axis rule) */
        eomc_real *Ic = wk + EOMC_TW_IC, Ia3[3];
        if (t->slide) { /* Ic (0, d) = (h x d, m d) */
            eomc_real dd = ax[3] * ax[3] + ax[4] * ax[4] + ax[5] * ax[5];
            mkk[t->coord] = Ic[0] * dd;
        } else {
            eomc_tree_rot(Ic + 4, 1, ax, Ia3);
            mkk[t->coord] = ax[0] * Ia3[0] + ax[1] * Ia3[1] + ax[2] * Ia3[2];
        }
        /* U = IA S, D = S . U, u = tau - S . pA */
        if (t->slide) {
            eomc_tree_inertia_times(A, B, Cb, ax, U);
        } else {
            for (int i = 0; i < 3; i++) {
                U[i] = A[3 * i] * ax[0] + A[3 * i + 1] * ax[1] + A[3 * i + 2] * ax[2];
                U[3 + i] = B[i] * ax[0] + B[3 + i] * ax[1] + B[6 + i] * ax[2];
            }
        }
        eomc_real D = eomc_tree_sdot(t, ax, U);
        piv[t->coord] = D;
        wk[EOMC_TW_DINV] = 1 / D;
        wk[EOMC_TW_SU] = tau[t->coord] - eomc_tree_sdot(t, ax, pA);
        if (t->up < 0)
            continue;
        eomc_real *wp = w + EOMC_TREE_WORK * t->up;
        eomc_tree_composite_up(t, wk, r, wp + EOMC_TW_IC);
        /* Ia = IA - U U^T / D, pa = pA + Ia c + U u / D */
        eomc_real Dinv = wk[EOMC_TW_DINV], uD = wk[EOMC_TW_SU] * Dinv, W[6], pa[6];
        for (int i = 0; i < 6; i++)
            W[i] = U[i] * Dinv;
        for (int i = 0; i < 3; i++) { /* A and C symmetric: one triangle, mirrored */
            for (int j = 0; j < 3; j++)
                B[3 * i + j] -= U[i] * W[3 + j];
            for (int j = i; j < 3; j++) {
                A[3 * i + j] -= U[i] * W[j];
                Cb[3 * i + j] -= U[3 + i] * W[3 + j];
                A[3 * j + i] = A[3 * i + j];
                Cb[3 * j + i] = Cb[3 * i + j];
            }
        }
        if (t->axis < 3 && !t->slide) { /* Ia S = 0: a zero row and column, to the bit */
            int a = t->axis;
            for (int i = 0; i < 3; i++)
                A[3 * a + i] = A[3 * i + a] = B[3 * a + i] = 0;
        }
        eomc_tree_inertia_times(A, B, Cb, wk + EOMC_TW_C, pa);
        for (int i = 0; i < 6; i++)
            pa[i] += pA[i] + U[i] * uD;
        eomc_tree_force_up(t, wk, r, pa, wp + EOMC_TW_P);
        /* IA_up += X^T Ia X: the blocks turned (A = Q A Q^T, ...), then
         * moved by r: C' = C, B' = B + [r]x C, A' = A + [r]x B^T - B' [r]x */
        if (t->slide && !t->fixed) {
            /* no turn */
        } else if (t->axis < 3 && !t->fixed) {
            eomc_real c = wk[EOMC_TW_CS], s = wk[EOMC_TW_CS + 1];
            eomc_tree_turn_block(t->axis, c, s, A, 1);
            eomc_tree_turn_block(t->axis, c, s, B, 0);
            eomc_tree_turn_block(t->axis, c, s, Cb, 1);
        } else {
            eomc_tree_rot_block(Q, A, 1);
            eomc_tree_rot_block(Q, B, 0);
            eomc_tree_rot_block(Q, Cb, 1);
        }
        eomc_real *Ap = wp + EOMC_TW_A, *Bp = wp + EOMC_TW_B, *Cp = wp + EOMC_TW_CC;
        if (!eomc_tree_offset(r)) {
            for (int e = 0; e < 9; e++)
                Ap[e] += A[e], Bp[e] += B[e], Cp[e] += Cb[e];
            continue;
        }
        eomc_real Rx[9] = {0, -r[2], r[1], r[2], 0, -r[0], -r[1], r[0], 0}, B2[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                B2[3 * i + j] = B[3 * i + j] + Rx[3 * i] * Cb[j] + Rx[3 * i + 1] * Cb[3 + j] +
                                Rx[3 * i + 2] * Cb[6 + j];
        for (int i = 0; i < 3; i++)
            for (int j = i; j < 3; j++) {
                eomc_real rbt = Rx[3 * i] * B[3 * j] + Rx[3 * i + 1] * B[3 * j + 1] +
                                Rx[3 * i + 2] * B[3 * j + 2];
                eomc_real brx = B2[3 * i] * Rx[j] + B2[3 * i + 1] * Rx[3 + j] +
                                B2[3 * i + 2] * Rx[6 + j];
                eomc_real e = A[3 * i + j] + rbt - brx;
                Ap[3 * i + j] += e;
                if (j != i)
                    Ap[3 * j + i] += e;
            }
        for (int e = 0; e < 9; e++)
            Bp[e] += B2[e], Cp[e] += Cb[e];
    }
    for (int k = 0; k < nt; k++) {
        const eomc_tree_turn *t = &T[k];
        const eomc_real *dk = d + EOMC_TREE_STRIDE * k;
        eomc_real *wk = w + EOMC_TREE_WORK * k, *acc = wk + EOMC_TW_ACC, ax[6];
        eomc_tree_axis(t, dk, ax);
        eomc_tree_motion_down(t, wk, eomc_tree_r(t, dk, wk),
                              t->up >= 0 ? w + EOMC_TREE_WORK * t->up + EOMC_TW_ACC : a0, acc);
        eomc_real ua = 0;
        for (int i = 0; i < 6; i++) {
            acc[i] += wk[EOMC_TW_C + i];
            ua += wk[EOMC_TW_U + i] * acc[i];
        }
        eomc_real x = (wk[EOMC_TW_SU] - ua) * wk[EOMC_TW_DINV];
        qdd[t->coord] = x;
        for (int i = 3 * t->slide; i < 3 + 3 * t->slide; i++)
            acc[i] += ax[i] * x;
    }
}

/* The inverse dynamics: out[coord] = S . F, F the net force the turn
 * transmits, at (q, v, a); the world accelerates by a0 unless NULL
 * (then zero).  E = out - tau. */
static void
eomc_tree_rnea(const eomc_tree_turn *T, int nt, const eomc_real *d, const eomc_real *a0,
               const eomc_real *q, const eomc_real *v, const eomc_real *a, eomc_real *w,
               eomc_real *out)
{
    static const eomc_real still[6] = {0, 0, 0, 0, 0, 0};
    eomc_tree_angles(T, nt, q, w);
    for (int k = 0; k < nt; k++) {
        const eomc_tree_turn *t = &T[k];
        const eomc_real *dk = d + EOMC_TREE_STRIDE * k;
        eomc_real *wk = w + EOMC_TREE_WORK * k, *Q = wk + EOMC_TW_Q;
        eomc_real *V = wk + EOMC_TW_V, *acc = wk + EOMC_TW_ACC, ax[6], rate = v[t->coord];
        eomc_tree_place(t, dk, q[t->coord], Q, wk + EOMC_TW_CS);
        const eomc_real *r = eomc_tree_r(t, dk, wk);
        eomc_tree_axis(t, dk, ax);
        const eomc_real *wu = t->up >= 0 ? w + EOMC_TREE_WORK * t->up : NULL;
        eomc_tree_motion_down(t, wk, r, wu ? wu + EOMC_TW_ACC : a0 ? a0 : still, acc);
        if (wu) {
            eomc_real c[6];
            eomc_tree_motion_down(t, wk, r, wu + EOMC_TW_V, V);
            eomc_tree_cross(V, t->slide ? ax + 3 : ax, t->slide ? c + 3 : c);
            if (t->slide)
                c[0] = c[1] = c[2] = 0;
            else
                eomc_tree_cross(V + 3, ax, c + 3);
            for (int i = 0; i < 6; i++)
                acc[i] += c[i] * rate;
        } else {
            for (int i = 0; i < 6; i++)
                V[i] = 0;
        }
        for (int i = 3 * t->slide; i < 3 + 3 * t->slide; i++) {
            V[i] += ax[i] * rate;
            acc[i] += ax[i] * a[t->coord];
        }
        eomc_tree_body_force(dk, V, acc, wk + EOMC_TW_P);
    }
    for (int k = nt - 1; k >= 0; k--) {
        const eomc_tree_turn *t = &T[k];
        const eomc_real *dk = d + EOMC_TREE_STRIDE * k;
        eomc_real *wk = w + EOMC_TREE_WORK * k, *F = wk + EOMC_TW_P, ax[6];
        eomc_tree_axis(t, dk, ax);
        out[t->coord] = eomc_tree_sdot(t, ax, F);
        if (t->up >= 0)
            eomc_tree_force_up(t, wk, eomc_tree_r(t, dk, wk), F,
                               w + EOMC_TREE_WORK * t->up + EOMC_TW_P);
    }
}

#endif
