/*
 * runtime/model/linalg.c's LTDL (la_ltdl_factor, la_ltdl_solve_neg) on a
 * random tree of 40 coordinates: M is built as L^T D L from a unit lower
 * triangular L whose off-diagonal entries sit only between a coordinate
 * and its ancestors, and a positive D, so it has exactly a tree's
 * sparsity and known factors.
 *  - the factorization gives back L and D (to rounding), and rel[k] = d_k /
 *    M_kk;
 *  - -M^-1 b equals GSL's LU solution of the same M, to 1e-12;
 *  - with d_5 < 0, M is not positive definite: the factorization returns
 *    6 (coordinate 5, the first bad pivot from the leaves up).
 */
#include "../unit/check.h"
#include "model/linalg.h"

#include <gsl/gsl_linalg.h>
#include <string.h>

enum { N = 40 };

/* M = L^T D L, L from the tree (unit diagonal, random entries at
 * ancestors), D as given */
static void
build(const int *parent, const double *Lr, const double *D, double *M)
{
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double s = 0; /* sum_k L_ki D_k L_kj */
            for (int k = 0; k < N; k++)
                s += Lr[k * N + i] * D[k] * Lr[k * N + j];
            M[i * N + j] = s;
        }
    (void)parent;
}

int
main(void)
{
    static int parent[N];
    static double Lr[N * N], D[N], M[N * N], F[N * N], rel[N], b[N], x[N];
    for (int i = 0; i < N; i++)
        parent[i] = i == 0 ? -1 : (int)check_rand(0, i - 0.001); /* a parent before it */
    memset(Lr, 0, sizeof Lr);
    for (int i = 0; i < N; i++) {
        Lr[i * N + i] = 1;
        for (int j = parent[i]; j >= 0; j = parent[j])
            Lr[i * N + j] = check_rand(-0.5, 0.5);
        D[i] = check_rand(0.5, 2);
    }
    build(parent, Lr, D, M);
    memcpy(F, M, sizeof M);
    int rc = la_ltdl_factor(F, N, parent, rel);
    double worst_l = 0, worst_d = 0, worst_rel = 0;
    for (int i = 0; i < N; i++) {
        worst_d = fmax(worst_d, fabs(F[i * N + i] - D[i]) / D[i]);
        worst_rel = fmax(worst_rel, fabs(rel[i] - D[i] / M[i * N + i]) / rel[i]);
        for (int j = parent[i]; j >= 0; j = parent[j])
            worst_l = fmax(worst_l, fabs(F[i * N + j] - Lr[i * N + j]));
    }
    CHECK(rc == 0, "LTDL of a positive definite tree-sparse M succeeds (rc %d)", rc);
    CHECK(worst_l < 1e-13 && worst_d < 1e-13 && worst_rel < 1e-13,
          "it gives back L (worst %.2g), D (%.2g) and rel = d/M_kk (%.2g)", worst_l, worst_d,
          worst_rel);
    for (int i = 0; i < N; i++)
        b[i] = x[i] = check_rand(-1, 1);
    la_ltdl_solve_neg(F, N, parent, x);
    gsl_matrix_view Mv = gsl_matrix_view_array(memcpy(F, M, sizeof M), N, N);
    gsl_permutation *p = gsl_permutation_alloc(N);
    int sign;
    gsl_vector *y = gsl_vector_alloc(N);
    gsl_vector_view bv = gsl_vector_view_array(b, N);
    gsl_linalg_LU_decomp(&Mv.matrix, p, &sign);
    gsl_linalg_LU_solve(&Mv.matrix, p, &bv.vector, y);
    double worst = 0, big = 0;
    for (int i = 0; i < N; i++) {
        worst = fmax(worst, fabs(x[i] + gsl_vector_get(y, i)));
        big = fmax(big, fabs(gsl_vector_get(y, i)));
    }
    CHECK(worst < 1e-12 * big, "-M^-1 b by LTDL = GSL's LU, to %.2g of max |x|", worst / big);
    gsl_vector_free(y);
    gsl_permutation_free(p);
    D[5] = -1;
    build(parent, Lr, D, M);
    rc = la_ltdl_factor(M, N, parent, rel);
    CHECK(rc == 6, "with d_5 < 0 it stops at coordinate 5 (rc %d)", rc);
    return check_done();
}
