/*
 * Unit tests of kin.c against plain double arithmetic done here:
 *  - a frame turned by a chain of turns (about x, y, z and fixed axes,
 *    under a parent) has R = the product of the turns' matrices (Rodrigues'
 *    formula evaluated here), orthonormal with det +1;
 *  - its angular velocity, in the world's and its own components, is the
 *    vee of R' R^T (world) and R^T R' (own), R' by extrapolated central
 *    differences of R along q(t) = q0 + v t: nothing of kin.c is reused;
 *  - a point's position is from + R at;
 *  - vel(P, F), the velocity of the point of F at P, through the parser,
 *    both ways it is formed (P offset from F's origin through a sliding
 *    link; the same place as a point of its own), against v_O + w_F x
 *    (r_P - r_O) with v_O and w_F by differences here;
 *  - along q(t) = q0 + v0 t + a0 t^2 / 2: acc(P) and acc(P, B) against
 *    second differences of P's position and of the point fixed in B at P
 *    (r_O(t) + R_B(t) R_B(0)^T (r_P(0) - r_O(0))), alpha(B) against first
 *    differences of B's angular velocity written out here (q0' z + q1'
 *    R_z x + q2' R_A y), and omega(B, A), alpha(B, A) against q2' R_A y
 *    and q2'' R_A y (B turns about A's y alone);
 *  - the vector operations (axes, vec, cross, dot, norm, sums and
 *    scaling) against the same arithmetic on R_B and r_P done here.
 */
#include "check.h"
#include "expr/kin.h"
#include "expr/parse.h"

#include <string.h>

enum { NQ = 4 };
/* the step of the differences along the motion (and half of it) */
#define DIFF_H 2e-3

static ExprPool *P;
static Diff *D;

/* Rodrigues: the matrix turning by th about unit axis a. */
static void
rodrigues(const double a[3], double th, double Rk[9])
{
    double c = cos(th), s = sin(th);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            Rk[3 * i + j] = (1 - c) * a[i] * a[j] + (i == j ? c : 0);
    Rk[1] -= s * a[2], Rk[3] += s * a[2];
    Rk[2] += s * a[1], Rk[6] -= s * a[1];
    Rk[5] -= s * a[0], Rk[7] += s * a[0];
}

static void
matmul(const double *A, const double *B, double *C)
{
    double T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            T[3 * i + j] = 0;
            for (int k = 0; k < 3; k++)
                T[3 * i + j] += A[3 * i + k] * B[3 * k + j];
        }
    memcpy(C, T, sizeof T);
}

/* The turns: parent frame turns about z by q0 then x by q1; the child
 * turns about y by q2, about the fixed axis (1, 2, 2)/3 by q3, and about
 * x by q0 + q3 (a rate shared with the parent). */
static const double axis[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};

static void
child_R(const double *q, double R[9])
{
    static const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    double Rk[9];
    rodrigues(ez, q[0], R);
    rodrigues(ex, q[1], Rk), matmul(R, Rk, R);
    rodrigues(ey, q[2], Rk), matmul(R, Rk, R);
    rodrigues(axis, q[3], Rk), matmul(R, Rk, R);
    rodrigues(ex, q[0] + q[3], Rk), matmul(R, Rk, R);
}

/* vel(P, F): frames B (the child of A below), points O (B's origin), P
 * (from O, sliding with q3) and Q (P's place, from the world's origin). */
static int frame_a, frame_b, point_o, point_p, point_q;

static int
frame_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    (void)sc, (void)at;
    return name[0] == 'A' ? frame_a : frame_b;
}

static int
point_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    (void)sc, (void)at;
    return name[0] == 'P' ? point_p : point_q;
}

static ParseVal
no_names(ParseScope *sc, const char *name, SrcLoc at)
{
    (void)sc;
    diag_error(at, "unknown name '%s'", name);
}

static const char *
no_leaf(ParseScope *sc, ExprId leaf)
{
    (void)sc, (void)leaf;
    return "?";
}

static SrcLoc
where(const ParseSrc *src, size_t off)
{
    (void)src;
    return (SrcLoc){"test", 1, (int)off + 1};
}

/* The test's own positions: O = R_A [0, 0, 1], P = O + R_A [0.5, q3, 0]. */
static void
positions(const double *q, double rO[3], double rP[3], double RB[9])
{
    static const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    double RA[9], Rk[9];
    rodrigues(ez, q[0], RA);
    rodrigues(ex, q[1], Rk), matmul(RA, Rk, RA);
    rodrigues(ey, q[2], Rk), matmul(RA, Rk, RB);
    for (int i = 0; i < 3; i++) {
        rO[i] = RA[3 * i + 2];
        rP[i] = rO[i] + 0.5 * RA[3 * i] + q[3] * RA[3 * i + 1];
    }
}

/* B's angular velocity written out: q0' about z, q1' about A's x after
 * the turn about z, q2' about A's y. */
static void
omega_b(const double *q, const double *v, double w[3])
{
    double RA[9], Rk[9];
    static const double ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0};
    rodrigues(ez, q[0], RA);
    rodrigues(ex, q[1], Rk), matmul(RA, Rk, RA);
    w[0] = v[1] * cos(q[0]) + v[2] * RA[1];
    w[1] = v[1] * sin(q[0]) + v[2] * RA[4];
    w[2] = v[0] + v[2] * RA[7];
}

/* The state at time t along q0 + v0 t + a0 t^2 / 2. */
static void
along(const double *q0, const double *v0, const double *a0, double t, double *q, double *v)
{
    for (int i = 0; i < NQ; i++)
        q[i] = q0[i] + t * v0[i] + 0.5 * t * t * a0[i], v[i] = v0[i] + t * a0[i];
}

/* Differences over h and h/2 extrapolated (Richardson), the first
 * derivative of omega_b and the second of P's position and of the point
 * fixed in B at P: d[0..3) acc(P), d[3..6) acc(P, B), d[6..9) alpha(B). */
static void
differences(const double *q0, const double *v0, const double *a0, double d[9])
{
    double rO0[3], rP0[3], RB0[9], r0[3], Dh[2][9];
    positions(q0, rO0, rP0, RB0);
    for (int i = 0; i < 3; i++) { /* r_P - r_O in B's axes at t = 0 */
        r0[i] = 0;
        for (int k = 0; k < 3; k++)
            r0[i] += RB0[3 * k + i] * (rP0[k] - rO0[k]);
    }
    for (int pass = 0; pass < 2; pass++) {
        double h = pass ? DIFF_H / 2 : DIFF_H, f[3][6], wp[3], wm[3];
        for (int side = 0; side < 3; side++) { /* t = -h, 0, h */
            double q[NQ], v[NQ], rO[3], rP[3], RB[9];
            along(q0, v0, a0, (side - 1) * h, q, v);
            positions(q, rO, rP, RB);
            for (int i = 0; i < 3; i++) {
                f[side][i] = rP[i];
                f[side][3 + i] = rO[i];
                for (int k = 0; k < 3; k++)
                    f[side][3 + i] += RB[3 * i + k] * r0[k];
            }
            if (side == 0)
                omega_b(q, v, wm);
            else if (side == 2)
                omega_b(q, v, wp);
        }
        for (int i = 0; i < 6; i++)
            Dh[pass][i] = (f[2][i] - 2 * f[1][i] + f[0][i]) / (h * h);
        for (int i = 0; i < 3; i++)
            Dh[pass][6 + i] = (wp[i] - wm[i]) / (2 * h);
    }
    for (int i = 0; i < 9; i++)
        d[i] = (4 * Dh[1][i] - Dh[0][i]) / 3;
}

static void
test_accelerations(ParseScope *sc)
{
    static const char *const text[] = {"acc(P)", "acc(P, B)", "alpha(B)", "omega(B, A)",
                                       "alpha(B, A)"};
    enum { NV = sizeof text / sizeof *text };
    ExprId e[NV][3];
    for (int k = 0; k < NV; k++) {
        ParseSrc src = {text[k], strlen(text[k]), where, NULL};
        parse_vector(sc, &src, e[k]);
    }
    double worst[NV] = {0};
    for (int trial = 0; trial < 50; trial++) {
        double q0[NQ], v0[NQ], a0[NQ];
        for (int i = 0; i < NQ; i++)
            q0[i] = check_rand(-3, 3), v0[i] = check_rand(-2, 2), a0[i] = check_rand(-2, 2);
        ExprEnv env = {.q = {q0, v0, a0}};
        double want[NV][3], d[9], rO[3], rP[3], RB[9];
        differences(q0, v0, a0, d);
        memcpy(want, d, sizeof d); /* acc(P), acc(P, B), alpha(B) */
        positions(q0, rO, rP, RB);
        for (int i = 0; i < 3; i++) { /* R_A y is R_B y: B turns about it */
            want[3][i] = v0[2] * RB[3 * i + 1];
            want[4][i] = a0[2] * RB[3 * i + 1];
        }
        for (int k = 0; k < NV; k++)
            for (int i = 0; i < 3; i++)
                worst[k] = fmax(worst[k], fabs(expr_eval(P, e[k][i], &env) - want[k][i]));
    }
    /* second differences: the rounding of |r| ~ 3 over (h/2)^2 = 1e-6,
     * times 5/3 by the extrapolation, ~ 1e-9; first differences: the
     * extrapolated truncation h^4 |w^(5)| / 480 ~ 1e-11; closed forms:
     * rounding */
    static const double tol[NV] = {1e-8, 1e-8, 1e-9, 1e-14, 1e-14};
    for (int k = 0; k < NV; k++)
        CHECK(worst[k] <= tol[k], "%s against %s (to %.2g)", text[k],
              k < 2 ? "second differences of positions" : k == 2
              ? "differences of omega written out" : "its closed form", worst[k]);
}

static void
test_vector_operations(ParseScope *sc)
{
    static const char *const vtext[] = {"cross(B.x, B.y)", "vec(B, 1, -2, 3)",
                                        "-pos(P)/2 + 3*B.z", "cross(omega(B), vec(B, 0, 0, 1))"};
    static const char *const stext[] = {"norm(vec(B, 3, 0, 4))", "dot(pos(P), B.y)"};
    enum { NV = sizeof vtext / sizeof *vtext, NS = sizeof stext / sizeof *stext };
    ExprId ev[NV][3], es[NS];
    for (int k = 0; k < NV; k++) {
        ParseSrc src = {vtext[k], strlen(vtext[k]), where, NULL};
        parse_vector(sc, &src, ev[k]);
    }
    for (int k = 0; k < NS; k++) {
        ParseSrc src = {stext[k], strlen(stext[k]), where, NULL};
        es[k] = parse_expr(sc, &src);
    }
    double worst = 0;
    for (int trial = 0; trial < 50; trial++) {
        double q0[NQ], v0[NQ], zero[NQ] = {0};
        for (int i = 0; i < NQ; i++)
            q0[i] = check_rand(-3, 3), v0[i] = check_rand(-2, 2);
        ExprEnv env = {.q = {q0, v0, zero}};
        double rO[3], rP[3], R[9], w[3], want[NV][3], swant[NS] = {5, 0};
        positions(q0, rO, rP, R);
        omega_b(q0, v0, w);
        for (int i = 0; i < 3; i++) {
            int j = (i + 1) % 3, k = (i + 2) % 3;
            want[0][i] = R[3 * i + 2];
            want[1][i] = R[3 * i] - 2 * R[3 * i + 1] + 3 * R[3 * i + 2];
            want[2][i] = -rP[i] / 2 + 3 * R[3 * i + 2];
            want[3][i] = w[j] * R[3 * k + 2] - w[k] * R[3 * j + 2];
            swant[1] += rP[i] * R[3 * i + 1];
        }
        for (int k = 0; k < NV; k++)
            for (int i = 0; i < 3; i++)
                worst = fmax(worst, fabs(expr_eval(P, ev[k][i], &env) - want[k][i]));
        for (int k = 0; k < NS; k++)
            worst = fmax(worst, fabs(expr_eval(P, es[k], &env) - swant[k]));
    }
    CHECK(worst <= 1e-14, "axes, vec, cross, dot, norm, sums and scaling: the arithmetic "
          "done here (to %.2g)", worst);
}

static void
test_material_velocity(Arena *A)
{
    Kin *K = kin_new(A, P, D, 2, 3);
    ExprId q[NQ];
    for (int i = 0; i < NQ; i++)
        q[i] = expr_var(P, i, 0);
    int fa = frame_a = kin_frame(K, KIN_WORLD);
    kin_turn_axis(K, fa, 2, q[0]);
    kin_turn_axis(K, fa, 0, q[1]);
    frame_b = kin_frame(K, fa);
    kin_turn_axis(K, frame_b, 1, q[2]);
    ExprId ato[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ONE}, atp[3] = {expr_const(P, 0.5), q[3], EXPR_ZERO};
    point_o = kin_point(K, KIN_ORIGIN, fa, ato);
    point_p = kin_point(K, point_o, fa, atp);
    ExprId rp[3];
    kin_pos(K, point_p, rp);
    point_q = kin_point(K, KIN_ORIGIN, KIN_WORLD, rp);
    kin_set_origin(K, frame_b, point_o);
    ParseScope sc = {P, D, no_names, NULL, no_leaf, 0xff, "a velocity", NQ, frame_arg,
                     point_arg, K, NULL};
    ParseSrc sp = {"vel(P, B)", 9, where, NULL}, sq = {"vel(Q, B)", 9, where, NULL};
    ExprId vp[3], vq[3], kv[3];
    parse_vector(&sc, &sp, vp);
    parse_vector(&sc, &sq, vq);
    kin_vel(K, point_p, kv);
    double worst_p = 0, worst_q = 0, worst_v = 0;
    for (int trial = 0; trial < 50; trial++) {
        double q0[NQ], v0[NQ], zero[NQ] = {0};
        for (int i = 0; i < NQ; i++)
            q0[i] = check_rand(-3, 3), v0[i] = check_rand(-2, 2);
        ExprEnv env = {.q = {q0, v0, zero}};
        /* v_O and R_B' by extrapolated central differences (as above) */
        double vO[3], vP[3], dRB[9], Dh[2][15];
        for (int pass = 0; pass < 2; pass++) {
            double h = pass ? 5e-4 : 1e-3, qp[NQ], qm[NQ], Op[3], Om[3], Pp[3], Pm[3], Rp[9],
                   Rm[9];
            for (int i = 0; i < NQ; i++)
                qp[i] = q0[i] + h * v0[i], qm[i] = q0[i] - h * v0[i];
            positions(qp, Op, Pp, Rp);
            positions(qm, Om, Pm, Rm);
            for (int i = 0; i < 3; i++)
                Dh[pass][i] = (Op[i] - Om[i]) / (2 * h);
            for (int i = 0; i < 9; i++)
                Dh[pass][3 + i] = (Rp[i] - Rm[i]) / (2 * h);
            for (int i = 0; i < 3; i++)
                Dh[pass][12 + i] = (Pp[i] - Pm[i]) / (2 * h);
        }
        for (int i = 0; i < 3; i++)
            vP[i] = (4 * Dh[1][12 + i] - Dh[0][12 + i]) / 3;
        for (int i = 0; i < 3; i++)
            vO[i] = (4 * Dh[1][i] - Dh[0][i]) / 3;
        for (int i = 0; i < 9; i++)
            dRB[i] = (4 * Dh[1][3 + i] - Dh[0][3 + i]) / 3;
        double rO[3], rP[3], RB[9], W[9] = {0};
        positions(q0, rO, rP, RB);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    W[3 * i + j] += dRB[3 * i + k] * RB[3 * j + k];
        double w[3] = {W[7], W[2], W[3]}, r[3], want[3];
        for (int i = 0; i < 3; i++)
            r[i] = rP[i] - rO[i];
        for (int i = 0; i < 3; i++)
            want[i] = vO[i] + w[(i + 1) % 3] * r[(i + 2) % 3] - w[(i + 2) % 3] * r[(i + 1) % 3];
        for (int i = 0; i < 3; i++) {
            worst_p = fmax(worst_p, fabs(expr_eval(P, vp[i], &env) - want[i]));
            worst_q = fmax(worst_q, fabs(expr_eval(P, vq[i], &env) - want[i]));
            worst_v = fmax(worst_v, fabs(expr_eval(P, kv[i], &env) - vP[i]));
        }
    }
    CHECK(worst_p <= 1e-10, "vel(P, B), P linked from B's origin (sliding): v_O + w_B x r "
          "(to %.2g)", worst_p);
    CHECK(worst_v <= 1e-10, "a point's velocity by its links (kin_vel): the rate of its "
          "position (to %.2g)", worst_v);
    CHECK(worst_q <= 1e-10, "vel(Q, B), Q at P's place from the world's origin: the same "
          "(to %.2g)", worst_q);
    test_accelerations(&sc);
    test_vector_operations(&sc);
}

int
main(void)
{
    Arena *A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    Kin *K = kin_new(A, P, D, 2, 1);
    ExprId q[NQ];
    for (int i = 0; i < NQ; i++)
        q[i] = expr_var(P, i, 0);
    int parent = kin_frame(K, KIN_WORLD);
    kin_turn_axis(K, parent, 2, q[0]);
    kin_turn_axis(K, parent, 0, q[1]);
    int f = kin_frame(K, parent);
    kin_turn_axis(K, f, 1, q[2]);
    ExprId a[3] = {expr_const(P, axis[0]), expr_const(P, axis[1]), expr_const(P, axis[2])};
    kin_turn(K, f, a, q[3]);
    kin_turn_axis(K, f, 0, expr_add(P, q[0], q[3]));
    ExprId at[3] = {expr_const(P, 0.3), q[1], expr_const(P, -1.1)};
    int pt = kin_point(K, KIN_ORIGIN, f, at);

    ExprId Rx[9], w[3], wl[3], r[3];
    for (int k = 0; k < 3; k++) {
        ExprId col[3];
        kin_axis(K, f, k, col);
        for (int i = 0; i < 3; i++)
            Rx[3 * i + k] = col[i];
    }
    kin_omega(K, f, w);
    kin_omega_local(K, f, wl);
    kin_pos(K, pt, r);

    double worst_R = 0, worst_orth = 0, worst_w = 0, worst_wl = 0, worst_r = 0;
    for (int trial = 0; trial < 50; trial++) {
        double q0[NQ], v0[NQ], zero[NQ] = {0};
        for (int i = 0; i < NQ; i++)
            q0[i] = check_rand(-3, 3), v0[i] = check_rand(-2, 2);
        ExprEnv env = {.q = {q0, v0, zero}};
        double R[9], Rn[9];
        for (int i = 0; i < 9; i++)
            R[i] = expr_eval(P, Rx[i], &env);
        child_R(q0, Rn);
        for (int i = 0; i < 9; i++)
            worst_R = fmax(worst_R, fabs(R[i] - Rn[i]));
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double d = (i == j) ? -1 : 0;
                for (int k = 0; k < 3; k++)
                    d += R[3 * k + i] * R[3 * k + j];
                worst_orth = fmax(worst_orth, fabs(d));
            }
        /* R' by central differences along q0 + v0 t, of the test's R, with
         * h and h/2 extrapolated (Richardson): error O(h^4) */
        double dR[9], Dh[2][9];
        for (int pass = 0; pass < 2; pass++) {
            double h = pass ? 5e-4 : 1e-3, qp[NQ], qm[NQ], Rp[9], Rm[9];
            for (int i = 0; i < NQ; i++)
                qp[i] = q0[i] + h * v0[i], qm[i] = q0[i] - h * v0[i];
            child_R(qp, Rp);
            child_R(qm, Rm);
            for (int i = 0; i < 9; i++)
                Dh[pass][i] = (Rp[i] - Rm[i]) / (2 * h);
        }
        for (int i = 0; i < 9; i++)
            dR[i] = (4 * Dh[1][i] - Dh[0][i]) / 3;
        double W[9] = {0}, Wl[9] = {0}; /* R' R^T and R^T R' */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) {
                    W[3 * i + j] += dR[3 * i + k] * Rn[3 * j + k];
                    Wl[3 * i + j] += Rn[3 * k + i] * dR[3 * k + j];
                }
        double vee[3] = {W[7], W[2], W[3]}, veel[3] = {Wl[7], Wl[2], Wl[3]};
        for (int i = 0; i < 3; i++) {
            worst_w = fmax(worst_w, fabs(expr_eval(P, w[i], &env) - vee[i]));
            worst_wl = fmax(worst_wl, fabs(expr_eval(P, wl[i], &env) - veel[i]));
        }
        double atn[3] = {0.3, q0[1], -1.1};
        for (int i = 0; i < 3; i++) {
            double ri = 0;
            for (int k = 0; k < 3; k++)
                ri += Rn[3 * i + k] * atn[k];
            worst_r = fmax(worst_r, fabs(expr_eval(P, r[i], &env) - ri));
        }
    }
    CHECK(worst_R <= 1e-14, "R is the product of the turns' Rodrigues matrices (to %.2g)",
          worst_R);
    CHECK(worst_orth <= 1e-14, "R^T R = I (to %.2g)", worst_orth);
    /* extrapolated differences: h^4 |R^(5)| / 480 ~ 1e-12, rounding
     * eps / h ~ 1e-13 */
    CHECK(worst_w <= 1e-10, "omega (world) is the vee of R' R^T (to %.2g)", worst_w);
    CHECK(worst_wl <= 1e-10, "omega (own axes) is the vee of R^T R' (to %.2g)", worst_wl);
    CHECK(worst_r <= 1e-14, "a point is from + R at (to %.2g)", worst_r);
    test_material_velocity(A);
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}
