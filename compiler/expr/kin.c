/*
 * kin: the orientation and angular velocity of frames, the positions of
 * points (kin.h).
 *
 * Turning a frame by angle th about its unit axis a (its own components)
 * multiplies R on the right by Rodrigues' matrix
 *     Rk = c I + s [a]x + (1 - c) a a^T,    c = cos th, s = sin th,
 * and moves its angular velocity, kept in its own components, to the new
 * axes before adding the new rate:  w = Rk^T w + a th'.  About a
 * coordinate axis, Rk has its zeros and ones written in, so that a chain
 * of such turns builds the products a hand derivation would.
 */
#include "kin.h"

#include "base/diag.h"

/* A path of frames longer than this (a chain of 64 frames between a link
 * and the frame it moves with) takes the general form of vel(P, F)
 * instead of the one in the link's axes: the same value, larger. */
enum { KIN_PATH_MAX = 64 };

/* One turn of a frame: its matrix, unit axis (in the axes before it) and
 * rate, for angular velocities relative to an ancestor in its axes.  A
 * turn by a quaternion has no single axis (rate EXPR_NONE, a and aw zero):
 * its angular velocity, in the axes before it, is wb. */
typedef struct KinTurn {
    ExprId Rk[9], a[3], rate, th; /* th: the angle (EXPR_NONE: a quaternion) */
    ExprId aw[3]; /* the axis in world components */
    ExprId wb[3]; /* the turn's angular velocity in the axes before it */
    ExprId wa[3]; /* and in the axes after it: a th', or 2 L e' */
    struct KinTurn *next;
} KinTurn;

typedef struct KinFrame {
    ExprId R[9]; /* row-major, columns the axes in world components */
    ExprId w[3]; /* angular velocity relative to the world, own components */
    ExprId ww[3]; /* the same in world components */
    ExprId own[3]; /* its own turns' part of ww: ww = parent's ww + own */
    int parent;  /* -1 for the world */
    int origin;  /* a point, or -1 */
    KinTurn *turns, *last; /* its own, in order */
} KinFrame;

typedef struct KinPoint {
    ExprId r[3];   /* position, world components */
    int from, f;   /* the point it is offset from (-1: the origin), in frame f */
    ExprId at[3];  /* the offset in f's axes */
    ExprId off[3]; /* and in the world's: R_f at */
    ExprId v[3];   /* velocity: v_from + R_f (w_f x at + at'), w_f in f's axes */
} KinPoint;

struct Kin {
    Arena *A;
    ExprPool *P;
    Diff *D;
    KinFrame *f;
    KinPoint *pt;
    int nf, np, capf, capp;
};

void
kin_mat3_mul(ExprPool *P, const ExprId *A, const ExprId *B, ExprId *C)
{
    ExprId T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            ExprId s = EXPR_ZERO;
            for (int k = 0; k < 3; k++)
                s = expr_add(P, s, expr_mul(P, A[3 * i + k], B[3 * k + j]));
            T[3 * i + j] = s;
        }
    for (int i = 0; i < 9; i++)
        C[i] = T[i];
}

/* out = R v, or R^T v (transpose); out may be v. */
static void
matvec3(ExprPool *P, const ExprId *R, int transpose, const ExprId *v, ExprId *out)
{
    ExprId r[3];
    for (int i = 0; i < 3; i++) {
        ExprId s = EXPR_ZERO;
        for (int k = 0; k < 3; k++)
            s = expr_add(P, s, expr_mul(P, transpose ? R[3 * k + i] : R[3 * i + k], v[k]));
        r[i] = s;
    }
    for (int i = 0; i < 3; i++)
        out[i] = r[i];
}

void
kin_cross(ExprPool *P, const ExprId *a, const ExprId *b, ExprId *out)
{
    ExprId c[3];
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        ExprId kj = expr_mul(P, a[k], b[j]);
        c[i] = expr_sub(P, expr_mul(P, a[j], b[k]), kj);
    }
    for (int i = 0; i < 3; i++)
        out[i] = c[i];
}

ExprId
kin_dot(ExprPool *P, const ExprId *a, const ExprId *b)
{
    ExprId s = EXPR_ZERO;
    for (int i = 0; i < 3; i++)
        s = expr_add(P, s, expr_mul(P, a[i], b[i]));
    return s;
}

Kin *
kin_new(Arena *A, ExprPool *P, Diff *D, int nframes, int npoints)
{
    Kin *K = arena_alloc(A, sizeof *K);
    K->A = A, K->P = P, K->D = D;
    K->capf = nframes + 1, K->capp = npoints + 1;
    K->f = arena_new_array(A, KinFrame, K->capf);
    K->pt = arena_new_array(A, KinPoint, K->capp);
    for (int i = 0; i < 9; i++)
        K->f[0].R[i] = i % 4 == 0 ? EXPR_ONE : EXPR_ZERO;
    for (int i = 0; i < 3; i++) {
        K->f[0].w[i] = K->f[0].ww[i] = K->f[0].own[i] = EXPR_ZERO;
        K->pt[0].r[i] = K->pt[0].at[i] = K->pt[0].off[i] = K->pt[0].v[i] = EXPR_ZERO;
    }
    K->f[0].origin = KIN_ORIGIN;
    K->f[0].parent = -1;
    K->pt[0].from = -1;
    K->nf = K->np = 1;
    return K;
}

int
kin_frame(Kin *K, int parent)
{
    if (K->nf == K->capf)
        diag_unreachable(); /* sized by the loader from the spec */
    K->f[K->nf] = K->f[parent];
    K->f[K->nf].origin = -1;
    K->f[K->nf].parent = parent;
    K->f[K->nf].turns = K->f[K->nf].last = NULL;
    for (int i = 0; i < 3; i++)
        K->f[K->nf].own[i] = EXPR_ZERO;
    return K->nf++;
}

void kin_set_origin(Kin *K, int f, int p) { K->f[f].origin = p; }
int kin_origin(const Kin *K, int f) { return K->f[f].origin; }

void
kin_rate_turn(ExprPool *P, const ExprId Rk[9], const ExprId own[3], ExprId w[3])
{
    ExprId r[3];
    for (int j = 0; j < 3; j++) {
        ExprId sum = own[j];
        for (int k = 0; k < 3; k++)
            sum = expr_add(P, sum, expr_mul(P, Rk[3 * k + j], w[k]));
        r[j] = sum;
    }
    for (int j = 0; j < 3; j++)
        w[j] = r[j];
}

/* R = R Rk and w = Rk^T w + a th', Rk given.  The world components of
 * the angular velocity are summed the same way, each rate along its axis
 * in the world (R a, before the turn): not R w, whose products of R's
 * entries equal these only through sin^2 + cos^2 = 1, which the DAG does
 * not know; kept apart, velocities such as v_C + w x r cancel term by
 * term where they should (a contact point at rest).  A turn by a
 * quaternion (th EXPR_NONE) has no axis: its own angular velocity is wa in
 * the axes after it and wb in those before, in place of a th'. */
static void
turn_by(Kin *K, int f, const ExprId Rk[9], const ExprId a[3], ExprId th, const ExprId *wa,
        const ExprId *wb)
{
    ExprPool *P = K->P;
    KinFrame *F = &K->f[f];
    ExprId w[3], axis[3], wbw[3];
    kin_to_world(K, f, a, axis);
    if (th == EXPR_NONE)
        kin_to_world(K, f, wb, wbw);
    kin_mat3_mul(P, F->R, Rk, F->R);
    ExprId rate = th == EXPR_NONE ? EXPR_NONE : diff_time(K->D, th);
    KinTurn *turn = arena_alloc(K->A, sizeof *turn);
    for (int i = 0; i < 9; i++)
        turn->Rk[i] = Rk[i];
    for (int i = 0; i < 3; i++)
        turn->a[i] = a[i], turn->aw[i] = axis[i], turn->wb[i] = wb ? wb[i] : EXPR_NONE,
        turn->wa[i] = th == EXPR_NONE ? wa[i] : expr_mul(P, a[i], rate);
    turn->rate = rate;
    turn->th = th;
    turn->next = NULL;
    if (F->last)
        F->last->next = turn;
    else
        F->turns = turn;
    F->last = turn;
    for (int i = 0; i < 3; i++)
        w[i] = F->w[i];
    kin_rate_turn(P, Rk, turn->wa, w); /* a th' + Rk^T w */
    for (int i = 0; i < 3; i++) {
        ExprId own = th == EXPR_NONE ? wbw[i] : expr_mul(P, axis[i], rate);
        F->w[i] = w[i], F->ww[i] = expr_add(P, F->ww[i], own),
        F->own[i] = expr_add(P, F->own[i], own);
    }
}

void
kin_axis_turn(ExprPool *P, int k, ExprId th, ExprId Rk[9], ExprId a[3])
{
    ExprId c = expr_unary(P, EXPR_COS, th), s = expr_unary(P, EXPR_SIN, th);
    int j = (k + 1) % 3, l = (k + 2) % 3;
    for (int i = 0; i < 9; i++)
        Rk[i] = EXPR_ZERO;
    for (int i = 0; i < 3; i++)
        a[i] = EXPR_ZERO;
    a[k] = EXPR_ONE;
    Rk[3 * k + k] = EXPR_ONE;
    Rk[3 * j + j] = c, Rk[3 * l + l] = c;
    Rk[3 * l + j] = s, Rk[3 * j + l] = expr_neg(P, s); /* e_j turns toward e_l */
}

void
kin_turn_axis(Kin *K, int f, int k, ExprId th)
{
    ExprId Rk[9], a[3];
    kin_axis_turn(K->P, k, th, Rk, a);
    turn_by(K, f, Rk, a, th, NULL, NULL);
}

void
kin_turn(Kin *K, int f, const ExprId a[3], ExprId th)
{
    ExprPool *P = K->P;
    ExprId c = expr_unary(P, EXPR_COS, th), s = expr_unary(P, EXPR_SIN, th);
    ExprId v = expr_sub(P, EXPR_ONE, c), Rk[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Rk[3 * i + j] = expr_mul(P, v, expr_mul(P, a[i], a[j]));
    for (int i = 0; i < 3; i++)
        Rk[4 * i] = expr_add(P, Rk[4 * i], c);
    /* [a]x: the cross product a x . as a matrix */
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, l = (i + 2) % 3;
        ExprId sa = expr_mul(P, s, a[i]);
        Rk[3 * l + j] = expr_add(P, Rk[3 * l + j], sa);
        Rk[3 * j + l] = expr_sub(P, Rk[3 * j + l], sa);
    }
    turn_by(K, f, Rk, a, th, NULL, NULL);
}

/* The Euler parameters e = (e0, v), v = (e1, e2, e3):
 *     Rk = (e0^2 - |v|^2) I + 2 v v^T + 2 e0 [v x],
 * and the turn's angular velocity in its own axes 2 L e', in those before
 * it 2 E e' (= Rk 2 L e' on |e| = 1, written without Rk's products), with
 *     L = [-e1  e0  e3 -e2;  -e2 -e3  e0  e1;  -e3  e2 -e1  e0],
 *     E = [-e1  e0 -e3  e2;  -e2  e3  e0 -e1;  -e3 -e2  e1  e0]. */
void
kin_quat_matrix(ExprPool *P, const ExprId e[4], ExprId Rk[9])
{
    ExprId two = expr_const(P, 2), sq = expr_powi(P, e[0], 2);
    for (int k = 1; k < 4; k++)
        sq = expr_sub(P, sq, expr_powi(P, e[k], 2));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Rk[3 * i + j] = expr_mul(P, two, expr_mul(P, e[1 + i], e[1 + j]));
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, l = (i + 2) % 3;
        ExprId c = expr_mul(P, two, expr_mul(P, e[0], e[1 + i])); /* 2 e0 [v x] */
        Rk[4 * i] = expr_add(P, Rk[4 * i], sq);
        Rk[3 * l + j] = expr_add(P, Rk[3 * l + j], c);
        Rk[3 * j + l] = expr_sub(P, Rk[3 * j + l], c);
    }
}

/* L(e) = [-e1 e0 e3 -e2; -e2 -e3 e0 e1; -e3 e2 -e1 e0], w = 2 L e' in the
 * turned axes: (sign, index of e) per entry. */
static const int Lrow[3][4][2] = {
    {{-1, 1}, {1, 0}, {1, 3}, {-1, 2}},
    {{-1, 2}, {-1, 3}, {1, 0}, {1, 1}},
    {{-1, 3}, {1, 2}, {-1, 1}, {1, 0}},
};

void
kin_turn_quaternion(Kin *K, int f, const ExprId e[4])
{
    ExprPool *P = K->P;
    ExprId Rk[9], d[4], wa[3], wb[3], zero[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    ExprId two = expr_const(P, 2);
    kin_quat_matrix(P, e, Rk);
    static const int Erow[3][4][2] = { /* and of E */
        {{-1, 1}, {1, 0}, {-1, 3}, {1, 2}},
        {{-1, 2}, {1, 3}, {1, 0}, {-1, 1}},
        {{-1, 3}, {-1, 2}, {1, 1}, {1, 0}},
    };
    for (int k = 0; k < 4; k++)
        d[k] = diff_time(K->D, e[k]);
    for (int r = 0; r < 3; r++) {
        ExprId a = EXPR_ZERO, b = EXPR_ZERO;
        for (int c = 0; c < 4; c++) {
            ExprId ta = expr_mul(P, e[Lrow[r][c][1]], d[c]);
            ExprId tb = expr_mul(P, e[Erow[r][c][1]], d[c]);
            a = Lrow[r][c][0] > 0 ? expr_add(P, a, ta) : expr_sub(P, a, ta);
            b = Erow[r][c][0] > 0 ? expr_add(P, b, tb) : expr_sub(P, b, tb);
        }
        wa[r] = expr_mul(P, two, a);
        wb[r] = expr_mul(P, two, b);
    }
    turn_by(K, f, Rk, zero, EXPR_NONE, wa, wb);
}

void
kin_quat_rates(ExprPool *P, const ExprId e[4], const ExprId w[3], ExprId ed[4])
{
    ExprId half = expr_const(P, 0.5);
    for (int c = 0; c < 4; c++) {
        ExprId x = EXPR_ZERO;
        for (int r = 0; r < 3; r++) {
            ExprId t = expr_mul(P, e[Lrow[r][c][1]], w[r]);
            x = Lrow[r][c][0] > 0 ? expr_add(P, x, t) : expr_sub(P, x, t);
        }
        ed[c] = expr_mul(P, half, x);
    }
}

void
kin_quat_omega(ExprPool *P, const ExprId e[4], const ExprId ed[4], ExprId w[3])
{
    ExprId two = expr_const(P, 2);
    for (int r = 0; r < 3; r++) {
        ExprId x = EXPR_ZERO;
        for (int c = 0; c < 4; c++) {
            ExprId t = expr_mul(P, e[Lrow[r][c][1]], ed[c]);
            x = Lrow[r][c][0] > 0 ? expr_add(P, x, t) : expr_sub(P, x, t);
        }
        w[r] = expr_mul(P, two, x);
    }
}

void
kin_turn_quaternion_speeds(Kin *K, int f, const ExprId e[4], const ExprId w[3])
{
    ExprPool *P = K->P;
    ExprId Rk[9], wa[3], wb[3], zero[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    kin_quat_matrix(P, e, Rk);
    for (int r = 0; r < 3; r++) {
        wa[r] = w[r];
        wb[r] = EXPR_ZERO;
        for (int c = 0; c < 3; c++)
            wb[r] = expr_add(P, wb[r], expr_mul(P, Rk[3 * r + c], w[c]));
    }
    turn_by(K, f, Rk, zero, EXPR_NONE, wa, wb);
}

int
kin_point(Kin *K, int from, int f, const ExprId at[3])
{
    if (K->np == K->capp)
        diag_unreachable();
    KinPoint *pt = &K->pt[K->np];
    ExprPool *P = K->P;
    kin_to_world(K, f, at, pt->off);
    /* w x (R at) + R at' = R (w_f x at + at'), w_f in f's own axes: the
     * product formed where at is simple, then turned once */
    ExprId local[3], turned[3];
    kin_cross(P, K->f[f].w, at, local);
    for (int i = 0; i < 3; i++)
        local[i] = expr_add(P, local[i], diff_time(K->D, at[i]));
    kin_to_world(K, f, local, turned);
    for (int i = 0; i < 3; i++) {
        pt->r[i] = expr_add(P, K->pt[from].r[i], pt->off[i]), pt->at[i] = at[i];
        pt->v[i] = expr_add(P, K->pt[from].v[i], turned[i]);
    }
    pt->from = from, pt->f = f;
    return K->np++;
}

void
kin_axis(const Kin *K, int f, int k, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = K->f[f].R[3 * i + k];
}

void
kin_omega(const Kin *K, int f, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = K->f[f].ww[i];
}

void
kin_omega_local(const Kin *K, int f, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = K->f[f].w[i];
}

void
kin_pos(const Kin *K, int p, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = K->pt[p].r[i];
}

void
kin_vel(const Kin *K, int p, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = K->pt[p].v[i];
}

int
kin_point_link(const Kin *K, int p, int *f, ExprId at[3], ExprId off[3])
{
    const KinPoint *pt = &K->pt[p];
    *f = pt->f;
    for (int i = 0; i < 3; i++)
        at[i] = pt->at[i], off[i] = pt->off[i];
    return pt->from;
}

/* Sum of own turns from f up to (not including) its ancestor a. */
static void
own_up_to(const Kin *K, int f, int a, ExprId out[3])
{
    for (; f != a && f > KIN_WORLD; f = K->f[f].parent)
        for (int i = 0; i < 3; i++)
            out[i] = expr_add(K->P, out[i], K->f[f].own[i]);
}

int
kin_is_ancestor(const Kin *K, int a, int f)
{
    for (; f >= 0; f = K->f[f].parent)
        if (f == a)
            return 1;
    return 0;
}

int
kin_omega_rel_in(const Kin *K, int f, int g, ExprId out[3])
{
    ExprPool *P = K->P;
    int path[KIN_PATH_MAX], np = 0; /* f's ancestors below g, from f up */
    for (int h = f; h != g; h = K->f[h].parent) {
        if (h <= KIN_WORLD || np == KIN_PATH_MAX)
            return 0; /* g is not an ancestor, or the path is too long */
        path[np++] = h;
    }
    ExprId Q[9], w[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    for (int i = 0; i < 9; i++)
        Q[i] = i % 4 == 0 ? EXPR_ONE : EXPR_ZERO;
    for (int k = np - 1; k >= 0; k--)
        for (const KinTurn *t = K->f[path[k]].turns; t; t = t->next) {
            ExprId axis[3];
            matvec3(P, Q, 0, t->rate == EXPR_NONE ? t->wb : t->a, axis);
            for (int i = 0; i < 3; i++)
                w[i] = expr_add(P, w[i], t->rate == EXPR_NONE ? axis[i]
                                                              : expr_mul(P, axis[i], t->rate));
            kin_mat3_mul(P, Q, t->Rk, Q);
        }
    for (int i = 0; i < 3; i++)
        out[i] = w[i];
    return 1;
}

void
kin_omega_rel(const Kin *K, int f, int g, ExprId out[3])
{
    int a = g; /* the nearest common ancestor */
    while (!kin_is_ancestor(K, a, f))
        a = K->f[a].parent;
    ExprId up[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    ExprId down[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    own_up_to(K, f, a, up);
    own_up_to(K, g, a, down);
    for (int i = 0; i < 3; i++)
        out[i] = expr_sub(K->P, up[i], down[i]);
}

void
kin_to_world(const Kin *K, int f, const ExprId v[3], ExprId out[3])
{
    matvec3(K->P, K->f[f].R, 0, v, out);
}

void
kin_to_frame(const Kin *K, int f, const ExprId w[3], ExprId out[3])
{
    matvec3(K->P, K->f[f].R, 1, w, out);
}

int kin_nframes(const Kin *K) { return K->nf; }
int kin_parent(const Kin *K, int f) { return K->f[f].parent; }
int kin_npoints(const Kin *K) { return K->np; }

/* Frame f's own turn k, or NULL past the last. */
static const KinTurn *
turn_at(const Kin *K, int f, int k)
{
    const KinTurn *t = K->f[f].turns;
    for (; t && k > 0; k--)
        t = t->next;
    return t;
}

int
kin_turn_of(const Kin *K, int f, int k, ExprId *rate, ExprId axis[3])
{
    const KinTurn *t = turn_at(K, f, k);
    if (!t)
        return 0;
    *rate = t->rate;
    for (int i = 0; i < 3; i++)
        axis[i] = t->aw[i];
    return 1;
}

int
kin_turn_local(const Kin *K, int f, int k, ExprId *angle, ExprId a[3], ExprId Rk[9])
{
    const KinTurn *t = turn_at(K, f, k);
    if (!t)
        return 0;
    *angle = t->th;
    for (int i = 0; i < 3; i++)
        a[i] = t->a[i];
    for (int i = 0; i < 9; i++)
        Rk[i] = t->Rk[i];
    return 1;
}

int
kin_turn_omega(const Kin *K, int f, int k, ExprId wa[3])
{
    const KinTurn *t = turn_at(K, f, k);
    if (!t)
        return 0;
    for (int i = 0; i < 3; i++)
        wa[i] = t->wa[i];
    return 1;
}

void
kin_rotation(const Kin *K, int f, ExprId R[9])
{
    for (int i = 0; i < 9; i++)
        R[i] = K->f[f].R[i];
}
