/*
 * One model written two ways gives the same motion (tests/sim/meson.build
 * builds this once per pair, each spec compiled and renamed
 * same_a_model, the model written out by hand, and same_b_model, written
 * with frames and points, with their extended-precision twins
 * same_a_model_ext and same_b_model_ext).  At 100 random states near the
 * initial one (coordinates and velocities moved by up to 0.3 (1 + |x|),
 * time in [0, 1]), projected onto the constraints:
 *  - in extended precision (each model's M, h, B and b in long double,
 *    [M B^T; B 0] [q''; lambda] = [-h; -b] solved by the runtime's
 *    extended-precision LU), q'' and the multipliers agree to 1e-13,
 *    each component relative to itself (plus a hundredth of its own
 *    largest over the states, for one passing near zero): the derivations
 *    are the same, not only close;
 *  - through the runtime in double, to 1e-12: two different roundings of
 *    the same equations, amplified by the mass matrix's condition (the
 *    bicycle's frame is 2000 times heavier than its fork's inertia).
 * Neither is derived from the other: the hand-written one has its
 * rotation matrices, angular velocities and contact velocities worked
 * out on paper.
 */
#include "../unit/check.h"
#include "eomc.h"
#include "model/linalg.h"

#include <stdlib.h>

extern const eomc_model same_a_model, same_b_model;
extern const eomc_model_ext same_a_model_ext, same_b_model_ext;
enum { NSTATES = 100, MAXN = 64 };
#define TOL_EXT 1e-13
#define TOL_DOUBLE 1e-12

/* [M B^T; B 0] [a; lam] = [-h; -b] at (t, q, v) in long double, by the
 * runtime's extended-precision LU (linalg.h, the reference solution's):
 * out[n + nc]; 0, or -1 when the system is singular. */
static int
solve_ext(const eomc_model_ext *x, int n, int nc, const long double *p, double t,
          const double *q, const double *v, long double *out)
{
    int N = n + nc, perm[MAXN];
    long double Q[MAXN], V[MAXN], A0[MAXN] = {0}, M[MAXN * MAXN], h[MAXN], f[MAXN], B[MAXN * MAXN] = {0};
    long double K[MAXN * MAXN], d[MAXN], scale[2 * MAXN];
    for (int i = 0; i < n; i++)
        Q[i] = q[i], V[i] = v[i];
    x->mass_bias(t, Q, V, p, NULL, M, h);
    if (nc)
        x->constraint(t, Q, V, A0, p, NULL, f, B);
    for (int i = 0; i < N; i++) {
        for (int j = 0; j < N; j++)
            K[i * N + j] = i < n && j < n ? M[i * n + j]
                         : i < n && j >= n ? B[(j - n) * n + i]
                         : i >= n && j < n ? B[(i - n) * n + j] : 0;
        out[i] = i < n ? -h[i] : -f[i - n];
    }
    la_ext_kkt_scaling(K, n, nc, d);
    if (la_ext_lu_factor(K, N, perm, scale, d) != 0)
        return -1;
    la_ext_lu_solve(K, N, perm, scale, out);
    return 0;
}

/* The worst per-component difference of B from A over the states. */
static void
worst(const double *A, const double *B, const unsigned char *ok, int N, int n, double *wa,
      double *wl)
{
    *wa = *wl = 0;
    for (int i = 0; i < N; i++) {
        double scale = 0;
        for (int s = 0; s < NSTATES; s++)
            if (ok[s])
                scale = fmax(scale, fabs(A[s * N + i]));
        for (int s = 0; s < NSTATES; s++) {
            if (!ok[s])
                continue;
            double e = fabs(B[s * N + i] - A[s * N + i]) /
                       fmax(fabs(A[s * N + i]) + 1e-2 * scale, 1e-300);
            if (i < n)
                *wa = fmax(*wa, e);
            else
                *wl = fmax(*wl, e);
        }
    }
}

int
main(void)
{
    const eomc_model *ma = &same_a_model, *mb = &same_b_model;
    CHECK(ma->nq == mb->nq && ma->nc == mb->nc && ma->np == mb->np,
          "%s and %s: the same coordinates, constraints and parameters", ma->name, mb->name);
    if (ma->nq != mb->nq || ma->nc != mb->nc)
        return check_done();
    int n = ma->nq, nc = ma->nc, N = n + nc, bad = 0;
    eomc_sim *sa = eomc_sim_alloc(ma), *sb = eomc_sim_alloc(mb);
    double q0[MAXN], v0[MAXN], q[MAXN], v[MAXN], aa[MAXN], ab[MAXN];
    double *A = calloc((size_t)(NSTATES * N), sizeof *A), *B = calloc((size_t)(NSTATES * N), sizeof *B);
    double *AX = calloc((size_t)(NSTATES * N), sizeof *AX), *BX = calloc((size_t)(NSTATES * N), sizeof *BX);
    unsigned char ok[NSTATES] = {0};
    /* the parameters' defaults, and each model's derived values, in long double */
    long double *pa = calloc((size_t)(ma->np + ma->nd + 1), sizeof *pa);
    long double *pb = calloc((size_t)(mb->np + mb->nd + 1), sizeof *pb);
    for (int i = 0; i < ma->np; i++)
        pa[i] = pb[i] = eomc_sim_params(sa)[i];
    if (same_a_model_ext.derive)
        same_a_model_ext.derive(pa, pa + ma->np);
    if (same_b_model_ext.derive)
        same_b_model_ext.derive(pb, pb + mb->np);
    eomc_sim_initial(sa, q0, v0);
    for (int s = 0; s < NSTATES; s++) {
        double t = check_rand(0, 1);
        for (int i = 0; i < n; i++) {
            q[i] = q0[i] + 0.3 * (1 + fabs(q0[i])) * check_rand(-1, 1);
            v[i] = v0[i] + 0.3 * (1 + fabs(v0[i])) * check_rand(-1, 1);
        }
        if (eomc_sim_project(sa, t, q, v) != EOMC_OK || eomc_sim_accel(sa, t, q, v, aa) != EOMC_OK ||
            eomc_sim_accel(sb, t, q, v, ab) != EOMC_OK) {
            printf("# state %d: %s%s\n", s, eomc_sim_error(sa), eomc_sim_error(sb));
            bad++;
            continue;
        }
        long double xa[MAXN], xb[MAXN];
        if (solve_ext(&same_a_model_ext, n, nc, pa, t, q, v, xa) != 0 ||
            solve_ext(&same_b_model_ext, n, nc, pb, t, q, v, xb) != 0) {
            printf("# state %d: a zero pivot in long double\n", s);
            bad++;
            continue;
        }
        ok[s] = 1;
        for (int i = 0; i < N; i++)
            AX[s * N + i] = (double)xa[i], BX[s * N + i] = (double)xb[i];
        for (int i = 0; i < n; i++)
            A[s * N + i] = aa[i], B[s * N + i] = ab[i];
        for (int c = 0; c < nc; c++) {
            A[s * N + n + c] = eomc_sim_multipliers(sa)[c];
            B[s * N + n + c] = eomc_sim_multipliers(sb)[c];
        }
    }
    double xa_worst, xl_worst, da_worst, dl_worst;
    worst(AX, BX, ok, N, n, &xa_worst, &xl_worst);
    worst(A, B, ok, N, n, &da_worst, &dl_worst);
    CHECK(bad == 0, "%s: %d random states projected and solved", ma->name, NSTATES - bad);
    CHECK(xa_worst <= TOL_EXT, "%s with frames: q'' the same to %.2g relative (long double)",
          mb->name, xa_worst);
    if (nc)
        CHECK(xl_worst <= TOL_EXT, "%s with frames: multipliers the same to %.2g relative "
              "(long double)", mb->name, xl_worst);
    CHECK(da_worst <= TOL_DOUBLE, "%s with frames: the runtime's q'' the same to %.2g relative",
          mb->name, da_worst);
    if (nc)
        CHECK(dl_worst <= TOL_DOUBLE, "%s with frames: the runtime's multipliers the same to "
              "%.2g relative", mb->name, dl_worst);
    eomc_sim_free(sa);
    eomc_sim_free(sb);
    free(A);
    free(B);
    free(AX);
    free(BX);
    free(pa);
    free(pb);
    return check_done();
}
