/*
 * linearize: a model's linearization and its equilibria (eomc.h).
 *
 * A = dz'/dz and B = dz'/du come from the generated residual Jacobians,
 * exactly: the simulator's own Jacobian (eomc_sim_jacobian) for A, and
 * for B the accelerations' response to the inputs, -M^-1 dE/du, or for a
 * constrained model the KKT system's (its time column with a unit input
 * rate: the column is linear in the rates).
 *
 * z is the state's tangent space: one position component and one speed
 * for each speed.  Where the speeds are the coordinates' rates z is x
 * itself.  A unit quaternion e is no vector space: its four parameters on
 * |e| = 1 have three directions, the small rotation dtheta in its body's
 * axes, e = e0 (x) (1, dtheta/2) + O(dtheta^2), whose speeds are the
 * angular velocity w.  Measured from the motion through x0 (e0' = 1/2 e0
 * (x) (0, w0)), dtheta' = dw - w0 x dtheta: the frame P, Q, K below.
 *
 * A constrained model's state moves on the constraints' manifold, so its
 * linearization is given in the independent components of the
 * elimination: a holonomic constraint removes its dependent position and
 * speed, a first-order one its dependent speed.  The full perturbation
 * follows from the reduced one through the linearized constraints (T
 * below), and the reduced rows are read off A T.
 */
#include "model/simimpl.h"
#include "model/kkt.h"
#include "model/linalg.h"
#include "model/state.h"
#include "base/numfmt.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

/* Whether component j of z = (position [nv], speed [nv]) is determined by
 * the constraints: the dependent position and speed of a holonomic
 * constraint, the dependent speed of a first-order one (c_dependent is a
 * speed, and position j is the one speed j moves). */
static int
dependent(const eomc_model *m, int j)
{
    int n = eomc_nv(m), i = j % n, vel = j >= n;
    for (int k = 0; k < m->nc; k++)
        if (m->c_dependent[k] == i && (m->c_order[k] == 0 || (m->c_order[k] == 1 && vel)))
            return 1;
    return 0;
}

int
eomc_sim_linear_size(const eomc_sim *s)
{
    const eomc_model *m = eomc_sim_model(s);
    int Z = 2 * eomc_nv(m), size = 0;
    for (int j = 0; j < Z; j++)
        size += !dependent(m, j);
    return size;
}

void
eomc_sim_linear_state(const eomc_sim *s, int k, int *coord, int *order)
{
    const eomc_model *m = eomc_sim_model(s);
    int nv = eomc_nv(m), Z = 2 * nv;
    *coord = *order = -1;
    for (int j = 0; j < Z; j++)
        if (!dependent(m, j) && k-- == 0) {
            int i = j % nv, *slot = malloc((size_t)nv * sizeof *slot);
            if (j >= nv) /* a speed */
                *coord = i, *order = 1;
            else if (slot && state_tangent(m, slot) == 0)
                *coord = slot[i] >= 0 ? slot[i] : i, *order = slot[i] >= 0 ? 0 : 2;
            free(slot);
            return;
        }
}

/* ---- the tangent space ---- */

/* e (x) p = L(e) p: L's row r, column c. */
static double
lmat(const double *e, int r, int c)
{
    static const int sign[4][4] = {{1, -1, -1, -1}, {1, 1, -1, 1}, {1, 1, 1, -1},
                                   {1, -1, 1, 1}};
    static const int which[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
    return sign[r][c] * e[which[r][c]];
}

/* The linearization's work: x = (q [nq], v [nv]) of N components, z of nz
 * = 2 nv; dx = P dz [N x nz] and dz = Q dx [nz x N] at x0 (Q P = I), K
 * [nz x nz] the rotations' own term (the reference turning), Af the
 * simulator's dx'/dx [N x N], Az = dz'/dz = Q Af P + K, T [nz x nl] the
 * full perturbation of the reduced one (tangent). */
typedef struct Lin {
    const eomc_model *m;
    int nq, nv, N, nz, nl;
    int *slot;           /* [nv] state_tangent's */
    double *P, *Q, *K, *Af, *Az, *T, *e, *ed; /* e, ed [4] a quaternion and its rate */
    double *qd;          /* [nq] q' at x0 */
} Lin;

static void
lin_free(Lin *L)
{
    free(L->slot);
    free(L->P);
    free(L->qd);
}

/* 0, or -1 out of memory; L->slot is checked by lin_frame's caller. */
static int
lin_alloc(eomc_sim *s, Lin *L)
{
    const eomc_model *m = eomc_sim_model(s);
    memset(L, 0, sizeof *L);
    L->m = m;
    L->nq = m->nq, L->nv = eomc_nv(m), L->N = L->nq + L->nv, L->nz = 2 * L->nv;
    L->nl = eomc_sim_linear_size(s);
    size_t N = (size_t)L->N, nz = (size_t)L->nz, nl = L->nl > 0 ? (size_t)L->nl : 1;
    L->slot = malloc((size_t)L->nv * sizeof *L->slot);
    L->P = calloc(2 * N * nz + 2 * nz * nz + N * N + nz * nl + 8, sizeof *L->P);
    L->qd = calloc(N, sizeof *L->qd);
    if (!L->slot || !L->P || !L->qd) {
        lin_free(L);
        return -1;
    }
    L->Q = L->P + N * nz, L->K = L->Q + nz * N, L->Af = L->K + nz * nz;
    L->Az = L->Af + N * N, L->T = L->Az + nz * nz, L->e = L->T + nz * nl, L->ed = L->e + 4;
    return 0;
}

/* EOMC_OK, or EOMC_EUSAGE naming what the speeds lack. */
static int
lin_check(eomc_sim *s, Lin *L, const char *what)
{
    if (state_tangent(L->m, L->slot) == 0)
        return EOMC_OK;
    return sim_usage_error(s, "%s of %s is not available: its kinematic equation q' = W(q) v "
                           "is not that of coordinates' rates and unit quaternions' angular "
                           "velocities in their bodies' axes (each speed one coordinate's "
                           "rate or one axis of one quaternion's w), the only tangent space "
                           "the runtime knows", what, L->m->name);
}

/* P, Q and K at x (L->slot set). */
static void
lin_frame(Lin *L, const double *x)
{
    int nq = L->nq, nv = L->nv, N = L->N, nz = L->nz;
    memset(L->P, 0, (size_t)N * (size_t)nz * sizeof *L->P);
    memset(L->Q, 0, (size_t)nz * (size_t)N * sizeof *L->Q);
    memset(L->K, 0, (size_t)nz * (size_t)nz * sizeof *L->K);
    if (L->m->nv > 0)
        state_qdot(L->m, x, x + nq, L->qd);
    for (int k = 0; k < nv; k++) {
        L->P[(nq + k) * nz + nv + k] = L->Q[(nv + k) * N + nq + k] = 1;
        if (L->slot[k] >= 0) {
            L->P[L->slot[k] * nz + k] = L->Q[k * N + L->slot[k]] = 1;
            continue;
        }
        /* de = 1/2 e (x) (0, dtheta) and dtheta = 2 vec(e* (x) de): column
         * a + 1 of L(e), halved and doubled */
        const int *c = L->m->quat + 4 * STATE_ROT_QUAT(L->slot[k]);
        int a = STATE_ROT_AXIS(L->slot[k]);
        for (int r = 0; r < 4; r++)
            L->e[r] = x[c[r]], L->ed[r] = r ? -L->qd[c[r]] : L->qd[c[r]]; /* ed = e'* */
        for (int r = 0; r < 4; r++) {
            L->P[c[r] * nz + k] = 0.5 * lmat(L->e, r, a + 1);
            L->Q[k * N + c[r]] = 2 * lmat(L->e, r, a + 1);
        }
        /* the reference turns: dtheta = 2 vec(e0(t)* (x) e) moves by
         * 2 vec(e0'* (x) de) too, vec(e0'* (x) e0 (x) (0, eps_b)) along
         * the rotation b of the same quaternion */
        for (int j = 0; j < nv; j++) {
            if (L->slot[j] >= 0 || STATE_ROT_QUAT(L->slot[j]) != STATE_ROT_QUAT(L->slot[k]))
                continue;
            int b = STATE_ROT_AXIS(L->slot[j]);
            double f[4], g = 0;
            for (int r = 0; r < 4; r++)
                f[r] = lmat(L->e, r, b + 1);
            for (int r = 0; r < 4; r++)
                g += lmat(L->ed, a + 1, r) * f[r];
            L->K[k * nz + j] = g;
        }
    }
}

/* Y [rows x nz] = X [rows x N] P, or X itself where z is x; an entry no
 * larger than the rounding of its sum is 0 (as A's, in linearize). */
static void
lin_right(const Lin *L, const double *X, int rows, double *Y)
{
    int N = L->N, nz = L->nz;
    if (L->m->nv == 0) {
        memcpy(Y, X, (size_t)rows * (size_t)N * sizeof *Y);
        return;
    }
    for (int i = 0; i < rows; i++)
        for (int c = 0; c < nz; c++) {
            double sum = 0, mag = 0;
            for (int j = 0; j < N; j++)
                if (L->P[j * nz + c] != 0) {
                    sum += X[i * N + j] * L->P[j * nz + c];
                    mag += fabs(X[i * N + j] * L->P[j * nz + c]);
                }
            Y[i * nz + c] = fabs(sum) <= N * DBL_EPSILON * mag ? 0 : sum;
        }
}

/* Y [nz x cols] = Q X [N x cols] (+ K when X is Af P, cols = nz). */
static void
lin_left(const Lin *L, const double *X, int cols, int with_k, double *Y)
{
    int N = L->N, nz = L->nz;
    if (L->m->nv == 0) {
        memcpy(Y, X, (size_t)N * (size_t)cols * sizeof *Y);
        return;
    }
    for (int r = 0; r < nz; r++)
        for (int c = 0; c < cols; c++) {
            double sum = with_k ? L->K[r * nz + c] : 0, mag = fabs(sum);
            for (int j = 0; j < N; j++)
                if (L->Q[r * N + j] != 0) {
                    sum += L->Q[r * N + j] * X[j * cols + c];
                    mag += fabs(L->Q[r * N + j] * X[j * cols + c]);
                }
            Y[r * cols + c] = fabs(sum) <= N * DBL_EPSILON * mag ? 0 : sum;
        }
}

/* Az = dz'/dz at x: the simulator's Jacobian in the tangent space. */
static int
lin_jacobian(eomc_sim *s, Lin *L, double t, const double *x)
{
    int rc = eomc_sim_jacobian(s, t, x, L->Af, NULL);
    if (rc != EOMC_OK)
        return rc;
    lin_frame(L, x);
    if (L->m->nv == 0) {
        memcpy(L->Az, L->Af, (size_t)L->N * (size_t)L->N * sizeof *L->Az);
        return EOMC_OK;
    }
    double *AP = malloc((size_t)L->N * (size_t)L->nz * sizeof *AP);
    if (!AP)
        return sim_usage_error(s, "out of memory linearizing %s", L->m->name);
    lin_right(L, L->Af, L->N, AP);
    lin_left(L, AP, L->nz, 1, L->Az);
    free(AP);
    return EOMC_OK;
}

/* Position component k's size, what its rounding is relative to: its
 * coordinate's value, or for a rotation 1 (a unit quaternion's
 * parameters are rounded to DBL_EPSILON, and so is the angle). */
static double
lin_size(const Lin *L, const double *x, int k)
{
    return L->slot[k] >= 0 ? fabs(x[L->slot[k]]) : 1;
}

/* Position component k's value: its coordinate's, or the rotation from
 * the start x0's quaternion to x's, component a of its rotation vector. */
static double
lin_value(const Lin *L, const double *x, const double *x0, int k)
{
    if (L->slot[k] >= 0)
        return x[L->slot[k]];
    const int *c = L->m->quat + 4 * STATE_ROT_QUAT(L->slot[k]);
    double e0[4], d[4];
    for (int r = 0; r < 4; r++)
        e0[r] = r ? -x0[c[r]] : x0[c[r]];
    for (int r = 0; r < 4; r++) {
        d[r] = 0;
        for (int i = 0; i < 4; i++)
            d[r] += lmat(e0, r, i) * x[c[i]];
    }
    if (d[0] < 0) /* -d is the same rotation, by the shorter way */
        for (int r = 0; r < 4; r++)
            d[r] = -d[r];
    double sv = sqrt(d[1] * d[1] + d[2] * d[2] + d[3] * d[3]);
    double angle = 2 * atan2(sv, d[0]);
    return sv > 0 ? angle * d[1 + STATE_ROT_AXIS(L->slot[k])] / sv : 0;
}

/* x moved by dz [nv] in position: a coordinate by its component, a unit
 * quaternion turned by its rotation, e <- e (x) exp(dtheta/2), kept of
 * length 1. */
static void
lin_move(const Lin *L, double *x, const double *dz)
{
    const eomc_model *m = L->m;
    for (int k = 0; k < L->nv; k++)
        if (L->slot[k] >= 0 && dz[k] != 0)
            x[L->slot[k]] += dz[k];
    for (int j = 0; j < m->nquat; j++) {
        double th[3] = {0, 0, 0}, e[4], r[4];
        for (int k = 0; k < L->nv; k++)
            if (L->slot[k] < 0 && STATE_ROT_QUAT(L->slot[k]) == j)
                th[STATE_ROT_AXIS(L->slot[k])] = dz[k];
        double angle = sqrt(th[0] * th[0] + th[1] * th[1] + th[2] * th[2]);
        if (angle == 0)
            continue;
        const int *c = m->quat + 4 * j;
        for (int i = 0; i < 4; i++)
            e[i] = x[c[i]];
        r[0] = cos(angle / 2);
        for (int i = 0; i < 3; i++)
            r[i + 1] = sin(angle / 2) * th[i] / angle;
        for (int i = 0; i < 4; i++) {
            x[c[i]] = 0;
            for (int a = 0; a < 4; a++)
                x[c[i]] += lmat(e, i, a) * r[a];
        }
        state_normalize_quat(m, x, j);
    }
}

/* The name of position component k: its coordinate's, or its rotation's
 * (state_rotation_name). */
static const char *
lin_name(const Lin *L, int k, char *buf, size_t len)
{
    if (L->slot[k] >= 0)
        return L->m->q_names[L->slot[k]];
    return state_rotation_name(L->m, k, buf, len);
}

/* The linearized constraints C dz = 0 at (t, x), C [nr x nz]: holonomic
 * g (dg/dq) and g' (dg'/dq, dg'/dv), first order phi (dphi/dq, dphi/dv),
 * taken along P; nr is the number of dependent components. */
static int
constraint_rows(eomc_sim *s, Lin *L, double t, const double *x, double *C)
{
    const eomc_model *m = L->m;
    int n = m->nq, nv = L->nv, nc = m->nc, nu = m->nu, N = L->N, r = 0;
    if (nc == 0)
        return 0;
    size_t nn = (size_t)nc * (size_t)n;
    double *w = calloc(3 * nn + 2 * (size_t)(nc * nu) + 2 * (size_t)nc + 1, sizeof *w);
    double *Cx = m->nv > 0 ? calloc((size_t)(2 * nc) * (size_t)N, sizeof *Cx) : C;
    if (!w || !Cx) {
        free(w);
        if (Cx != C)
            free(Cx);
        return -1;
    }
    double *dposdq = w, *dveldq = w + nn, *dveldv = w + 2 * nn;
    double *dposdu = w + 3 * nn, *dveldu = dposdu + nc * nu, *dposdt = dveldu + nc * nu;
    double *dveldt = dposdt + nc;
    const double *u = sim_inputs_at(s, t, x, x + n);
    m->c_levels_jacobian(t, x, x + n, sim_p(s), u, dposdq, dveldq, dveldv, dposdu, dveldu,
                         dposdt, dveldt);
    for (int k = 0; k < nc; k++) {
        if (m->c_order[k] == 0) {
            for (int j = 0; j < N; j++)
                Cx[r * N + j] = j < n ? dposdq[k * n + j] : 0;
            r++;
        }
        if (m->c_order[k] <= 1) {
            for (int j = 0; j < N; j++)
                Cx[r * N + j] = j < n ? dveldq[k * n + j] : dveldv[k * nv + j - n];
            r++;
        }
    }
    if (Cx != C) {
        lin_frame(L, x);
        lin_right(L, Cx, r, C);
        free(Cx);
    }
    free(w);
    return r;
}

/* The componentwise backward error of y as a solution of C y = b [nd]
 * (Oettli and Prager): the least relative change of C's entries and b's
 * that makes it exact, max_i |b - C y|_i / (|C| |y| + |b|)_i; 0 for an
 * exact one.  Free of the rows' and the unknowns' scales. */
static double
backward_error(const double *C, int nd, const double *y, const double *b)
{
    double worst = 0;
    for (int i = 0; i < nd; i++) {
        double r = b[i], mag = fabs(b[i]);
        for (int j = 0; j < nd; j++)
            r -= C[i * nd + j] * y[j], mag += fabs(C[i * nd + j] * y[j]);
        if (r != 0)
            worst = fmax(worst, mag > 0 ? fabs(r) / mag : HUGE_VAL);
    }
    return worst;
}

/* An entry of a solve's result that is 0 to the solve's accuracy is made
 * 0: one whose zeroing leaves the solution's componentwise backward error
 * at rounding (ZERO_BACKWARD units of it on every row, about LU's own).
 * A cyclic coordinate's influence on a dependent velocity cancels exactly
 * (a bicycle's heading turns its rolling constraints and their solution
 * alike), and its rounding, left in T, would couple the coordinate's
 * zero eigenvalue to the others. */
#define ZERO_BACKWARD 8
static void
clean_zeros(const double *C, int nd, double *y, const double *b, double *trial)
{
    double bound = ZERO_BACKWARD * nd * DBL_EPSILON;
    if (backward_error(C, nd, y, b) > bound)
        return; /* not a solve accurate to rounding: nothing to tell from 0 */
    memcpy(trial, y, (size_t)nd * sizeof *y);
    for (int r = 0; r < nd; r++) {
        if (y[r] == 0)
            continue;
        trial[r] = 0;
        if (backward_error(C, nd, trial, b) <= bound)
            y[r] = 0;
        else
            trial[r] = y[r];
    }
}

/* T [nz x nl]: the full perturbation of each reduced one: dz_i = dy for
 * the independent components, dz_d = -C_d^-1 C_i dy for the dependent. */
static int
tangent(eomc_sim *s, Lin *L, double t, const double *x)
{
    const eomc_model *m = L->m;
    int N = L->nz, nl = L->nl, nd = N - nl;
    double *T = L->T;
    double *C = calloc((size_t)(nd ? nd : 1) * (size_t)N, sizeof *C);
    double *Cd = calloc((size_t)(nd ? nd * nd : 1), sizeof *Cd);
    double *col = calloc(3 * (size_t)(nd ? nd : 1), sizeof *col);
    double *rhs = col + (nd ? nd : 1), *trial = rhs + (nd ? nd : 1);
    int *dep = calloc((size_t)N, sizeof *dep), *ind = calloc((size_t)N, sizeof *ind);
    LaLu *lu = la_lu_alloc(nd ? nd : 1);
    int rc = -1;
    if (!C || !Cd || !col || !dep || !ind || !lu || constraint_rows(s, L, t, x, C) != nd)
        goto done;
    int a = 0, b = 0;
    for (int j = 0; j < N; j++) {
        if (dependent(m, j))
            dep[a++] = j;
        else
            ind[b++] = j;
    }
    for (int r = 0; r < nd; r++)
        for (int c = 0; c < nd; c++)
            Cd[r * nd + c] = C[r * N + dep[c]];
    if (nd && la_lu_factor(lu, Cd) != 0)
        goto done;
    memset(T, 0, (size_t)N * (size_t)nl * sizeof *T);
    for (int k = 0; k < nl; k++) {
        T[ind[k] * nl + k] = 1;
        for (int r = 0; r < nd; r++)
            rhs[r] = col[r] = -C[r * N + ind[k]];
        if (nd) {
            la_lu_solve(lu, col);
            clean_zeros(Cd, nd, col, rhs, trial);
        }
        for (int r = 0; r < nd; r++)
            T[dep[r] * nl + k] = col[r];
    }
    rc = 0;
done:
    free(C);
    free(Cd);
    free(col);
    free(dep);
    free(ind);
    la_lu_free(lu);
    return rc;
}

static int
linearize(eomc_sim *s, double t, const double *x, double *A, double *B)
{
    const eomc_model *m = eomc_sim_model(s);
    if (!m->jacobian)
        return sim_no_jacobian(s, "the linearization");
    Lin L;
    if (lin_alloc(s, &L) != 0)
        return sim_usage_error(s, "out of memory linearizing %s", m->name);
    int n = m->nq, nu = m->nu, N = L.N, nz = L.nz, nl = L.nl;
    int rc = lin_check(s, &L, "the linearization");
    /* off the constraints, the linearization describes no motion of the
     * model, and its eigenvalues nothing the model does */
    if (rc == EOMC_OK)
        rc = sim_off_constraints(s, t, x, x + n, "the linearization");
    if (rc == EOMC_OK)
        rc = sim_choose_rows(s, t, x, x + n);
    if (rc != EOMC_OK) {
        lin_free(&L);
        return rc;
    }
    /* the state it keeps leaves out one coordinate for each constraint
     * (its dependent one): a row left out determines none */
    if (sim_dropped_rows(s)) {
        lin_free(&L);
        return sim_usage_error(s, "the linearization needs independent constraints, and "
                               "these are dependent (%s; the simulations leave the dependent "
                               "rows out): write the model without them",
                               sim_dropped_note(s));
    }
    double *Bf = calloc((size_t)N * (size_t)(nu ? nu : 1), sizeof *Bf);
    double *Bz = calloc((size_t)nz * (size_t)(nu ? nu : 1), sizeof *Bz);
    int *ind = calloc((size_t)nz, sizeof *ind);
    if (!Bf || !Bz || !ind) {
        rc = sim_usage_error(s, "out of memory linearizing %s", m->name);
        goto done;
    }
    if ((rc = lin_jacobian(s, &L, t, x)) != EOMC_OK)
        goto done;
    if (sim_input_jacobian(s, t, x, Bf) != 0) {
        rc = sim_numeric_error(s, t, x, x + n, "the response to the inputs could not be "
                               "solved");
        goto done;
    }
    lin_left(&L, Bf, nu, 0, Bz);
    if (tangent(s, &L, t, x) != 0) {
        rc = sim_numeric_error(s, t, x, x + n, "the constraints cannot be solved for their "
                               "dependent coordinates here (their rows are singular)");
        goto done;
    }
    for (int j = 0, k = 0; j < nz; j++)
        if (!dependent(m, j))
            ind[k++] = j;
    /* the reduced rows of A T and of B.  An entry no larger than the
     * rounding of its own sum (nz units of it on the sum of the terms'
     * magnitudes) is 0 to the accuracy it has, and 0 it is: a cyclic
     * coordinate's column (a bicycle's heading) then stays exactly 0, and
     * its eigenvalue exactly 0 (eomc_sim_eigenvalues) */
    for (int r = 0; r < nl; r++) {
        for (int c = 0; c < nl; c++) {
            double sum = 0, mag = 0;
            for (int j = 0; j < nz; j++) {
                sum += L.Az[ind[r] * nz + j] * L.T[j * nl + c];
                mag += fabs(L.Az[ind[r] * nz + j] * L.T[j * nl + c]);
            }
            A[r * nl + c] = fabs(sum) <= nz * DBL_EPSILON * mag ? 0 : sum;
        }
        for (int k = 0; k < nu; k++)
            B[r * nu + k] = Bz[ind[r] * nu + k];
    }
done:
    lin_free(&L);
    free(Bf);
    free(Bz);
    free(ind);
    return rc;
}

/* Isolate the eigenvalues that rows or columns of zeros give exactly, as
 * LAPACK's balancing does by permutation (GSL's balancing only scales):
 * a component k whose column (or row) is 0 off the diagonal among those
 * left has the eigenvalue A_kk, and the others are those of A without
 * row and column k (expand det(A - s I) along it).  A cyclic coordinate
 * (a bicycle's position, heading, wheel angles) is such a column; left in
 * the QR iteration, the zeros of such a chain form a Jordan block, which
 * rounding splits into +-1e-8 where the true eigenvalues are 0.
 * keep [nl] marks those left; returns how many were isolated, their
 * eigenvalues into re, im [nl] from the end. */
static int
isolate(const double *A, int nl, unsigned char *keep, double *re, double *im)
{
    int found = 0;
    memset(keep, 1, (size_t)nl);
    for (int again = 1; again;) {
        again = 0;
        for (int k = 0; k < nl; k++) {
            if (!keep[k])
                continue;
            int col = 1, row = 1;
            for (int i = 0; i < nl && (col || row); i++)
                if (keep[i] && i != k) {
                    col &= A[i * nl + k] == 0;
                    row &= A[k * nl + i] == 0;
                }
            if (col || row) {
                keep[k] = 0;
                found++;
                re[nl - found] = A[k * nl + k], im[nl - found] = 0;
                again = 1;
            }
        }
    }
    return found;
}

int
eomc_sim_eigenvalues(eomc_sim *s, const double *A, int nl, double *re, double *im)
{
    unsigned char *keep = malloc((size_t)nl + 1);
    /* QR iteration takes a NaN for a number and fails on an infinity
     * through GSL's error handler: neither reaches it */
    for (size_t k = 0; k < (size_t)nl * (size_t)nl; k++)
        if (!isfinite(A[k])) {
            free(keep);
            return sim_usage_error(s, "the matrix has a non-finite entry (row %zu, column "
                                   "%zu): no eigenvalues", k / (size_t)nl + 1,
                                   k % (size_t)nl + 1);
        }
    if (!keep)
        return sim_usage_error(s, "out of memory for the eigenvalues");
    int nr = nl - isolate(A, nl, keep, re, im);
    if (nr == 0) {
        free(keep);
        return EOMC_OK;
    }
    gsl_matrix *M = gsl_matrix_alloc((size_t)nr, (size_t)nr);
    gsl_vector_complex *ev = gsl_vector_complex_alloc((size_t)nr);
    gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc((size_t)nr);
    int rc = EOMC_OK;
    if (!M || !ev || !w) {
        rc = sim_usage_error(s, "out of memory for the eigenvalues");
    } else {
        for (int i = 0, a = 0; i < nl; i++) {
            if (!keep[i])
                continue;
            for (int j = 0, b = 0; j < nl; j++)
                if (keep[j])
                    gsl_matrix_set(M, (size_t)a, (size_t)b++, A[i * nl + j]);
            a++;
        }
        gsl_eigen_nonsymm_params(0, 1, w); /* balanced: A mixes units */
        if (gsl_eigen_nonsymm(M, ev, w) != GSL_SUCCESS)
            rc = sim_usage_error(s, "the eigenvalues did not converge (QR iteration)");
        for (int k = 0; k < nr && !rc; k++) {
            re[k] = GSL_REAL(gsl_vector_complex_get(ev, (size_t)k));
            im[k] = GSL_IMAG(gsl_vector_complex_get(ev, (size_t)k));
        }
    }
    gsl_eigen_nonsymm_free(w);
    gsl_vector_complex_free(ev);
    gsl_matrix_free(M);
    free(keep);
    return rc;
}

/* ---- how far a state is from rest ---- */

/* Jz [nv x nl] = dv'/dy at (t, x), y the linearization's reduced state:
 * the speeds' rows of dz'/dz along T (L's Az and T set). */
static int
accel_jacobian(eomc_sim *s, Lin *L, double t, const double *x, double *Jz)
{
    int nv = L->nv, nz = L->nz, nl = L->nl, rc = lin_jacobian(s, L, t, x);
    if (rc != EOMC_OK)
        return rc;
    if (tangent(s, L, t, x) != 0)
        return sim_numeric_error(s, t, x, x + L->nq, "the constraints' rows are singular "
                                 "here");
    for (int i = 0; i < nv; i++)
        for (int k = 0; k < nl; k++) {
            double sum = 0;
            for (int j = 0; j < nz; j++)
                sum += L->Az[(nv + i) * nz + j] * L->T[j * nl + k];
            Jz[i * nl + k] = sum;
        }
    return EOMC_OK;
}

/* reach [n]: sum_k |Jz_ik| w_k, what q''_i would change by if every z_k
 * moved by w_k [nl]. */
static void
accel_reach(int n, int nl, const double *Jz, const double *w, double *reach)
{
    for (int i = 0; i < n; i++) {
        reach[i] = 0;
        for (int k = 0; k < nl; k++)
            reach[i] += fabs(Jz[i * nl + k]) * w[k];
    }
}

/* The largest |acc_i| / floor_i [n] (0 where acc_i is 0, infinite where
 * only floor_i is), its i into *worst. */
static double
accel_ratio(int n, const double *acc, const double *reach, int *worst)
{
    double big = 0;
    *worst = 0;
    for (int i = 0; i < n; i++) {
        double r = acc[i] == 0 ? 0 : reach[i] > 0 ? fabs(acc[i]) / reach[i] : HUGE_VAL;
        if (r > big)
            big = r, *worst = i;
    }
    return big;
}

static double
accel_residual(eomc_sim *s, double t, const double *x, double *acc, int *worst)
{
    const eomc_model *m = eomc_sim_model(s);
    *worst = -1;
    if (!m->jacobian) {
        sim_no_jacobian(s, "the test for rest");
        return NAN;
    }
    Lin L;
    if (lin_alloc(s, &L) != 0) {
        sim_usage_error(s, "out of memory testing %s for rest", m->name);
        return NAN;
    }
    int n = m->nq, nv = L.nv, nl = L.nl;
    size_t snl = nl > 0 ? (size_t)nl : 1;
    double *Jz = calloc((size_t)nv * snl, sizeof *Jz);
    double *w = calloc(snl, sizeof *w), *reach = calloc((size_t)nv, sizeof *reach);
    double r = NAN;
    if (!Jz || !w || !reach)
        sim_usage_error(s, "out of memory testing %s for rest", m->name);
    else if (lin_check(s, &L, "the test for rest") == EOMC_OK &&
             eomc_sim_accel(s, t, x, x + n, acc) == EOMC_OK &&
             accel_jacobian(s, &L, t, x, Jz) == EOMC_OK) {
        for (int k = 0, j = 0; j < L.nz; j++) {
            if (dependent(m, j))
                continue;
            /* each component by its own size: a speed's, a coordinate's
             * value, a rotation's 1 (lin_size) */
            w[k++] = j >= nv ? fabs(x[n + j - nv]) : lin_size(&L, x, j);
        }
        accel_reach(nv, nl, Jz, w, reach);
        r = accel_ratio(nv, acc, reach, worst);
    }
    lin_free(&L);
    free(Jz);
    free(w);
    free(reach);
    return r;
}

/* ---- equilibria ---- */

/* Newton's method stops when its step is this many units of rounding of
 * the coordinate (or of the coordinate's scale, for one near 0), or when
 * steps below 1e-8 of that stop shrinking; it gives up after EQ_MAX_ITER
 * iterations.  Where it stops, q'' must be 0 (EOMC_ACCEL_ZERO, eomc.h)
 * for what it found to be an equilibrium. */
enum { EQ_MAX_ITER = 100, EQ_HALVINGS = 40 };
#define EQ_SETTLED (16 * DBL_EPSILON)
#define EQ_STALL 1e-8
/* Newton's method runs away when its full step has not shrunk in
 * EQ_RUNAWAY steps running, each taking it farther from the start: it
 * then follows q'' down a slope that reaches 0 only at infinity (on
 * f ~ 1/z Newton's step doubles z; on f ~ exp(-z) it adds 1), where near
 * a root its steps shrink.  Eight: on f ~ 1/z, 256 times as far out as
 * where the run began.  Not shrinking means by less than EQ_SHRUNK: at a
 * root of multiplicity m the steps shrink by (m - 1)/m each, so only a
 * root of multiplicity above 100 is taken for a runaway.  Damped steps
 * (which may crawl round to a root far from the start) are not counted;
 * EQ_MAX_ITER steps, the last EQ_RUNAWAY of them or more each farther
 * out, are a runaway too. */
enum { EQ_RUNAWAY = 8 };
#define EQ_SHRUNK 0.99

/* Put the dependent coordinates of the holonomic constraints back on
 * g(q) = 0 (the independent ones held): Newton on the dependent columns
 * of the tangent space (a rotation's turns its quaternion, lin_move). */
static int
hold_on_constraints(eomc_sim *s, Lin *L, double t, double *x)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, nc = m->nc, nh = 0, nz = L->nz;
    for (int k = 0; k < nc; k++)
        nh += m->c_order[k] == 0;
    if (nh == 0)
        return 0;
    double *pos = calloc((size_t)nc, sizeof *pos), *vel = calloc((size_t)nc, sizeof *vel);
    double *C = calloc((size_t)(2 * nc + 1) * (size_t)nz, sizeof *C);
    double *dz = calloc((size_t)L->nv, sizeof *dz);
    double *G = calloc((size_t)(nh * nh), sizeof *G), *r = calloc((size_t)nh, sizeof *r);
    double *first = calloc((size_t)nh, sizeof *first);
    int *dep = calloc((size_t)nh, sizeof *dep), *row = calloc((size_t)nh, sizeof *row);
    LaLu *lu = la_lu_alloc(nh);
    int rc = -1;
    if (!pos || !vel || !C || !dz || !G || !r || !first || !dep || !row || !lu)
        goto done;
    for (int k = 0, h = 0, rr = 0; k < nc; k++) {
        if (m->c_order[k] == 0)
            dep[h] = m->c_dependent[k], row[h++] = rr;
        rr += m->c_order[k] == 0 ? 2 : m->c_order[k] == 1;
    }
    double prev = HUGE_VAL;
    for (int it = 0; it < EQ_MAX_ITER; it++) {
        m->c_levels(t, x, x + n, sim_p(s), sim_inputs_at(s, t, x, x + n), pos, vel);
        if (constraint_rows(s, L, t, x, C) < 0)
            goto done;
        double worst = 0;
        for (int a = 0, h = 0; a < nc; a++)
            if (m->c_order[a] == 0)
                r[h++] = -pos[a];
        for (int a = 0; a < nh; a++)
            for (int b = 0; b < nh; b++)
                G[a * nh + b] = C[row[a] * nz + dep[b]];
        if (la_lu_factor(lu, G) != 0)
            goto done;
        la_lu_solve(lu, r);
        for (int a = 0; a < nh; a++)
            dz[dep[a]] = r[a];
        lin_move(L, x, dz);
        for (int a = 0; a < nh; a++) {
            dz[dep[a]] = 0;
            if (it == 0) /* a coordinate at 0 is measured by the first correction */
                first[a] = fabs(r[a]);
            worst = fmax(worst, fabs(r[a]) / fmax(fmax(lin_size(L, x, dep[a]), first[a]),
                                                  DBL_MIN));
        }
        if (worst <= EQ_SETTLED || (worst <= EQ_STALL && worst >= prev)) {
            rc = 0;
            break;
        }
        prev = worst;
    }
done:
    free(pos);
    free(vel);
    free(C);
    free(dz);
    free(G);
    free(r);
    free(first);
    free(dep);
    free(row);
    la_lu_free(lu);
    return rc;
}

/* The weights of the accelerations at (t, x), whatever the units of the
 * coordinates: wt [n] gets sqrt(M_ii), the diagonal of the mass matrix
 * (M_ii q''_i^2 is a power per time whatever coordinate i measures; a
 * coordinate without inertia, which a constrained model may have, weighs
 * nothing).  M [n x n] and h [n] are workspace. */
static void
weights(eomc_sim *s, double t, const double *x, double *M, double *h, double *wt)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = eomc_nv(m);
    m->mass_bias(t, x, x + m->nq, sim_p(s), sim_inputs_at(s, t, x, x + m->nq), M, h);
    for (int i = 0; i < n; i++)
        wt[i] = M[i * n + i] > 0 ? sqrt(M[i * n + i]) : 0;
}

/* sqrt(sum_i (wt_i acc_i)^2). */
static double
weighed(int n, const double *acc, const double *wt)
{
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += (wt[i] * acc[i]) * (wt[i] * acc[i]);
    return sqrt(sum);
}

/* The message of a runaway, how as it says, naming the position
 * component (qc [nzq], lin_value from the start xs) that has gone
 * farthest from the start relative to its scale. */
static int
runaway_error(eomc_sim *s, const Lin *L, double t, double *x, const double *xs,
              const double *z0, const double *S, const int *qc, int nzq, const char *how)
{
    const eomc_model *m = eomc_sim_model(s);
    int far = 0;
    double most = -1;
    for (int cq = 0; cq < nzq; cq++) {
        double d = S[cq] > 0 ? fabs(lin_value(L, x, xs, qc[cq]) - z0[cq]) / S[cq] : 0;
        if (d > most)
            most = d, far = cq;
    }
    char a[NUM_MAX], b[NUM_MAX], name[STATE_NAME_MAX];
    return sim_numeric_error(s, t, x, x + m->nq, "Newton's method runs away: %s (%s from %s "
                             "to %s), and q'' does not reach 0 that way: no equilibrium was "
                             "found there (try another --init)", how,
                             lin_name(L, qc[far], name, sizeof name), num_shortest(a, z0[far]),
                             num_shortest(b, lin_value(L, x, xs, qc[far])));
}

static int
equilibrium(eomc_sim *s, double t, double *x, int *iterations)
{
    const eomc_model *m = eomc_sim_model(s);
    *iterations = 0;
    if (!m->jacobian)
        return sim_no_jacobian(s, "the equilibrium search");
    Lin L;
    if (lin_alloc(s, &L) != 0)
        return sim_usage_error(s, "out of memory searching for an equilibrium");
    int rc = lin_check(s, &L, "the equilibrium search");
    if (rc != EOMC_OK) {
        lin_free(&L);
        return rc;
    }
    /* n accelerations (one per speed), N components of x; the independent
     * position components: their place k among the reduced states, and
     * which component of z's position each is */
    int n = L.nv, N = L.N, nl = L.nl, nz = L.nz;
    int nzq = 0, nzv = 0, *qk = calloc((size_t)nz, sizeof *qk), *qc = calloc((size_t)nz, sizeof *qc);
    for (int j = 0, k = 0; j < nz && qk && qc; j++) {
        if (dependent(m, j))
            continue;
        if (j >= n)
            nzv++;
        else
            qk[nzq] = k, qc[nzq++] = j;
        k++;
    }
    size_t snl = nl > 0 ? (size_t)nl : 1, szq = nzq > 0 ? (size_t)nzq : 1;
    double *Jz = calloc((size_t)n * snl, sizeof *Jz);
    double *x0 = calloc((size_t)N, sizeof *x0), *xs = calloc((size_t)N, sizeof *xs);
    double *w = calloc(snl, sizeof *w), *dzq = calloc((size_t)n, sizeof *dzq);
    /* scales from the start, none from the iterate (which a runaway
     * inflates): z0 [nzq] the independent components there (a rotation's
     * 0: it is measured from there, xs), S [nzq] each one's scale (the
     * larger of its value there and its first Newton step; a component
     * with neither takes its first nonzero step), R0 [n] each
     * acceleration's (its value there, and what the components' sizes
     * there would change it by) */
    double *S = calloc(szq, sizeof *S), *z0 = calloc(szq, sizeof *z0);
    double *R0 = calloc((size_t)n, sizeof *R0);
    double *reach = calloc((size_t)n, sizeof *reach);
    double *acc = calloc((size_t)n, sizeof *acc); /* v' at x */
    double *M = calloc((size_t)n * (size_t)n, sizeof *M), *h = calloc((size_t)n, sizeof *h);
    double *wt = calloc((size_t)n, sizeof *wt); /* the rows' weights (weights) */
    gsl_matrix *J = gsl_matrix_alloc((size_t)n, szq);
    gsl_matrix *V = gsl_matrix_alloc(szq, szq);
    gsl_vector *Sv = gsl_vector_alloc(szq), *work = gsl_vector_alloc(szq);
    gsl_vector *F = gsl_vector_alloc((size_t)n), *dz = gsl_vector_alloc(szq);
    double *T = L.T;
    if (!qk || !qc || !Jz || !x0 || !xs || !w || !dzq || !S || !z0 || !R0 || !reach || !acc ||
        !M || !h || !wt || !J || !V || !Sv || !work || !F || !dz) {
        rc = sim_usage_error(s, "out of memory searching for an equilibrium");
        goto done;
    }
    if (nzv != nzq || nzq == 0) {
        rc = sim_usage_error(s, "%s has %d independent coordinate%s but %d independent "
                             "%s: its equilibria are not isolated points (a "
                             "nonholonomic model rests anywhere its forces allow), so "
                             "Newton's method has no single answer to find", m->name, nzq,
                             nzq == 1 ? "" : "s", nzv, state_speed_word(m, nzv != 1));
        goto done;
    }
    memset(x + m->nq, 0, (size_t)n * sizeof *x);
    state_normalize(m, x, NULL);
    if (hold_on_constraints(s, &L, t, x) != 0) {
        rc = sim_numeric_error(s, t, x, x + m->nq, "the start is too far from the "
                               "constraints to put it on them");
        goto done;
    }
    memcpy(xs, x, (size_t)N * sizeof *x);
    for (int cq = 0; cq < nzq; cq++)
        z0[cq] = lin_value(&L, x, xs, qc[cq]);
    double prev = HUGE_VAL, prev_full = HUGE_VAL, prev_far = 0;
    int growing = 0, outward = 0;
    char how[160];
    for (int it = 1;; it++) {
        *iterations = it;
        if (it > EQ_MAX_ITER && outward >= EQ_RUNAWAY) {
            snprintf(how, sizeof how, "in %d iterations it found no equilibrium, and each of "
                     "its last %d steps took it farther from the start", EQ_MAX_ITER, outward);
            rc = runaway_error(s, &L, t, x, xs, z0, S, qc, nzq, how);
            goto done;
        }
        if (it > EQ_MAX_ITER) {
            rc = sim_numeric_error(s, t, x, x + m->nq, "Newton's method found no equilibrium "
                                   "in %d iterations from the start given (try another "
                                   "--init)", EQ_MAX_ITER);
            goto done;
        }
        if ((rc = accel_jacobian(s, &L, t, x, Jz)) != EOMC_OK)
            goto done;
        if ((rc = eomc_sim_accel(s, t, x, x + m->nq, acc)) != EOMC_OK)
            goto done;
        if (it == 1) {
            for (int k = 0; k < nl; k++)
                w[k] = 0;
            for (int cq = 0; cq < nzq; cq++)
                w[qk[cq]] = L.slot[qc[cq]] >= 0 ? fabs(z0[cq]) : lin_size(&L, x, qc[cq]);
            accel_reach(n, nl, Jz, w, R0);
            for (int i = 0; i < n; i++)
                R0[i] += fabs(acc[i]);
        }
        /* F = every acceleration (a dependent coordinate's too: a reduced
         * coordinate may stand still where the motion does not); J = their
         * derivative along the independent coordinates, (dv'/dz) T.  Each
         * row weighted by sqrt(M_ii), each column in the units of its
         * coordinate's scale once it has one: the least-squares step, and
         * the directions it drops, are then the same in any units */
        weights(s, t, x, M, h, wt);
        double f0 = weighed(n, acc, wt);
        for (int i = 0; i < n; i++) {
            gsl_vector_set(F, (size_t)i, -wt[i] * acc[i]);
            for (int cq = 0; cq < nzq; cq++)
                gsl_matrix_set(J, (size_t)i, (size_t)cq,
                               wt[i] * Jz[i * nl + qk[cq]] * (S[cq] > 0 ? S[cq] : 1));
        }
        /* the least-squares step: robust where J is nearly singular (a
         * flat direction) */
        if (gsl_linalg_SV_decomp(J, V, Sv, work) != GSL_SUCCESS ||
            !(gsl_vector_get(Sv, 0) > 0)) {
            rc = sim_numeric_error(s, t, x, x + m->nq, "the accelerations do not depend on "
                                   "the coordinates here: no Newton step (a body that nothing "
                                   "holds falls the same wherever it is: no equilibrium)");
            goto done;
        }
        for (size_t k = 1; k < Sv->size; k++) /* drop what rounding cannot resolve */
            if (gsl_vector_get(Sv, k) < 1e3 * DBL_EPSILON * gsl_vector_get(Sv, 0))
                gsl_vector_set(Sv, k, 0);
        gsl_linalg_SV_solve(J, V, Sv, F, dz);
        for (int cq = 0; cq < nzq; cq++)
            if (S[cq] > 0)
                gsl_vector_set(dz, (size_t)cq, gsl_vector_get(dz, (size_t)cq) * S[cq]);
        /* the full step's size, relative to the coordinates' scales */
        double full = 0;
        for (int cq = 0; cq < nzq; cq++) {
            double step = fabs(gsl_vector_get(dz, (size_t)cq));
            if (S[cq] == 0)
                S[cq] = fmax(fabs(z0[cq]), step);
            if (step > 0)
                full = fmax(full, S[cq] > 0 ? step / S[cq] : HUGE_VAL);
        }
        /* damped: the full step, or halves of it, until the accelerations
         * shrink, weighed as here (a step past a fold of the constraints,
         * or overshooting a maximum, comes back) */
        double worst = 0, lambda = 1;
        memcpy(x0, x, (size_t)N * sizeof *x);
        for (int tries = 0;; tries++, lambda *= 0.5) {
            memcpy(x, x0, (size_t)N * sizeof *x);
            worst = 0;
            for (int j = 0; j < n; j++)
                dzq[j] = 0;
            /* the coordinates one step at a time, in that order (as the
             * steps were always taken); the rotations then at once */
            for (int cq = 0; cq < nzq; cq++) {
                double step = lambda * gsl_vector_get(dz, (size_t)cq);
                for (int j = 0; j < n; j++) {
                    if (L.slot[j] >= 0)
                        x[L.slot[j]] += T[j * nl + qk[cq]] * step;
                    else
                        dzq[j] += T[j * nl + qk[cq]] * step;
                }
                double size = L.slot[qc[cq]] >= 0 ? fabs(x[L.slot[qc[cq]]]) : 0;
                worst = fmax(worst, fabs(step) / fmax(fmax(size, S[cq]), DBL_MIN));
            }
            for (int j = 0; j < n; j++)
                if (L.slot[j] >= 0)
                    dzq[j] = 0;
            lin_move(&L, x, dzq);
            for (int cq = 0; cq < nzq; cq++) /* a rotation's rounding is of size 1 */
                if (L.slot[qc[cq]] < 0)
                    worst = fmax(worst, fabs(lambda * gsl_vector_get(dz, (size_t)cq)) /
                                            fmax(lin_size(&L, x, qc[cq]), S[cq]));
            int ok = hold_on_constraints(s, &L, t, x) == 0 &&
                     eomc_sim_accel(s, t, x, x + m->nq, acc) == EOMC_OK;
            double f1 = ok ? weighed(n, acc, wt) : HUGE_VAL;
            if (ok && (f1 < f0 || worst <= EQ_STALL))
                break;
            if (tries == EQ_HALVINGS) {
                memcpy(x, x0, (size_t)N * sizeof *x);
                rc = sim_numeric_error(s, t, x, x + m->nq, "Newton's method cannot reduce the "
                                       "accelerations from here (no step along its "
                                       "direction does; try another --init)");
                goto done;
            }
        }
        /* a runaway (EQ_RUNAWAY): full steps that do not shrink, each
         * farther out */
        double far = 0;
        for (int cq = 0; cq < nzq; cq++)
            if (S[cq] > 0)
                far = fmax(far, fabs(lin_value(&L, x, xs, qc[cq]) - z0[cq]) / S[cq]);
        outward = far > prev_far ? outward + 1 : 0;
        growing = outward && lambda == 1 && full >= EQ_SHRUNK * prev_full ? growing + 1 : 0;
        prev_full = full, prev_far = far;
        if (growing >= EQ_RUNAWAY) {
            snprintf(how, sizeof how, "%d full Newton steps running did not shrink, each "
                     "taking it farther from the start", growing);
            rc = runaway_error(s, &L, t, x, xs, z0, S, qc, nzq, how);
            goto done;
        }
        if (worst <= EQ_SETTLED || (worst <= EQ_STALL && worst >= prev))
            break;
        prev = worst;
    }
    /* found only where v' is 0: each v'_i within EOMC_ACCEL_ZERO of the
     * larger of its scale at the start, R0_i, and what the components'
     * sizes here would change it by (their rounding reaches that far).
     * Steps stop shrinking also at a minimum of |v'| that is not 0 (the
     * least-squares step drops the direction that would reduce it), and
     * far out where v' only falls as a coordinate grows (a force on a
     * longer lever, divided by an inertia that grows as its square). */
    if ((rc = accel_jacobian(s, &L, t, x, Jz)) != EOMC_OK ||
        (rc = eomc_sim_accel(s, t, x, x + m->nq, acc)) != EOMC_OK)
        goto done;
    for (int k = 0; k < nl; k++)
        w[k] = 0;
    for (int cq = 0; cq < nzq; cq++)
        w[qk[cq]] = lin_size(&L, x, qc[cq]);
    accel_reach(n, nl, Jz, w, reach);
    for (int i = 0; i < n; i++)
        reach[i] = fmax(reach[i], R0[i]);
    int bad;
    double ratio = accel_ratio(n, acc, reach, &bad);
    if (ratio > EOMC_ACCEL_ZERO) {
        char a[NUM_MAX], name[STATE_NAME_MAX];
        rc = sim_numeric_error(s, t, x, x + m->nq, "Newton's method stopped making progress "
                               "after %d steps where q'' is not 0 (%s = %s, where rounding "
                               "would leave at most %.2g): no equilibrium there (try another "
                               "--init)", *iterations, state_rate(m, bad, name, sizeof name),
                               num_shortest(a, acc[bad]), EOMC_ACCEL_ZERO * reach[bad]);
    }
done:
    lin_free(&L);
    free(qk);
    free(qc);
    free(Jz);
    free(x0);
    free(xs);
    free(w);
    free(dzq);
    free(S);
    free(z0);
    free(R0);
    free(reach);
    free(acc);
    free(M);
    free(h);
    free(wt);
    gsl_matrix_free(J);
    gsl_matrix_free(V);
    gsl_vector_free(Sv);
    gsl_vector_free(work);
    gsl_vector_free(F);
    gsl_vector_free(dz);
    return rc;
}

/* ---- the analyses, on the dense solve ----
 * Each differentiates q'' and reads exact zeros in it (a cyclic
 * coordinate's row, a steady motion's q''), so each runs on the dense
 * KKT solve, whose zeros are the equations' own: unit loads give the same
 * q''(x) to the rounding of its terms, which is all a zero there would
 * read as (a_f - Y lambda: 1.7e-15 where the bicycle's x'' is 0). */

/* A switch function counts as 0 within KINK_ULPS units of rounding of
 * its scale, sum_j |ds/dx_j| size_j (and t's term), size_j the larger of
 * |x_j| and what the caller says x_j is known to: what the rounding of the
 * state's values would change it by.  A state given to the last digit, or
 * one a run stopped at, is within a few units of the kink it is on; an
 * equilibrium, within EQ_SETTLED of its start's scale; the rest is room
 * for the rounding of s itself. */
#define KINK_ULPS 64
static const double KINK_STEP = 0x1p-20;

int
eomc_sim_kinks(eomc_sim *s, double t, const double *x, const double *size, unsigned char *on)
{
    const eomc_model *m = eomc_sim_model(s);
    int nm = m->nmode, N = eomc_nx(m), n = m->nq, found = 0;
    if (nm == 0)
        return 0;
    double *s0 = calloc((size_t)nm, sizeof *s0), *s1 = calloc((size_t)nm, sizeof *s1);
    double *scale = calloc((size_t)nm, sizeof *scale), *y = malloc((size_t)N * sizeof *y);
    if (s0 && s1 && scale && y) {
        memcpy(y, x, (size_t)N * sizeof *y);
        sim_set_modes(s, t, x, x + n); /* the state's own, as its q'' takes them */
        sim_switches(s, t, y, y + n, s0);
        for (int j = 0; j <= N; j++) { /* each component, then t */
            double *at = j < N ? &y[j] : &t, keep = *at;
            double h = fmax(fabs(keep), j < N && size ? fabs(size[j]) : 0) * KINK_STEP;
            if (h == 0)
                continue; /* no rounding there */
            *at = keep + h;
            sim_switches(s, t, y, y + n, s1);
            *at = keep;
            for (int k = 0; k < nm; k++)
                scale[k] += fabs(s1[k] - s0[k]) / KINK_STEP;
        }
        for (int k = 0; k < nm; k++) {
            int kink = fabs(s0[k]) <= KINK_ULPS * DBL_EPSILON * scale[k];
            found += kink;
            if (on)
                on[k] = (unsigned char)kink;
        }
    } else {
        found = -1;
    }
    free(s0);
    free(s1);
    free(scale);
    free(y);
    return found;
}

int
eomc_sim_linearize(eomc_sim *s, double t, const double *x, double *A, double *B)
{
    sim_set_dense(s, 1);
    int rc = linearize(s, t, x, A, B);
    sim_set_dense(s, 0);
    return rc;
}

double
eomc_sim_accel_residual(eomc_sim *s, double t, const double *x, double *acc, int *worst)
{
    sim_set_dense(s, 1);
    double r = accel_residual(s, t, x, acc, worst);
    sim_set_dense(s, 0);
    return r;
}

int
eomc_sim_equilibrium(eomc_sim *s, double t, double *x, int *iterations)
{
    sim_set_dense(s, 1);
    int rc = equilibrium(s, t, x, iterations);
    sim_set_dense(s, 0);
    return rc;
}
