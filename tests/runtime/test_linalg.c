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
 *    6 (coordinate 5, the first bad pivot from the leaves up);
 *  - la_ltdl_solve_cols_neg, several right-hand sides at once, gives each the
 *    one-column solve's bits, and leaves the columns past them alone;
 *  - la_ldlt_solve_rows_neg, 7 right-hand sides at once after GSL's pivoted
 *    LDL^T (la_ldlt_factor), equals GSL's LU solution of each, to 1e-12.
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
    static double F2[N * N];
    memcpy(F2, F, sizeof F);
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
    /* every column at once, in a wider array: each column as the one above */
    enum { C = 5, LD = 9 };
    static double Xc[N * LD];
    for (int i = 0; i < N; i++)
        for (int c = 0; c < LD; c++)
            Xc[i * LD + c] = c == 2 ? b[i] : check_rand(-1, 1);
    static double Xs[N * LD];
    memcpy(Xs, Xc, sizeof Xc);
    la_ltdl_solve_cols_neg(F2, N, parent, Xc, C, LD);
    int same = 1;
    for (int c = 0; c < LD && same; c++) {
        double col[N];
        for (int i = 0; i < N; i++)
            col[i] = Xs[i * LD + c];
        if (c < C)
            la_ltdl_solve_neg(F2, N, parent, col);
        for (int i = 0; i < N; i++)
            same &= memcmp(&col[i], &Xc[i * LD + c], sizeof col[i]) == 0;
    }
    CHECK(same, "%d columns at once (rows %d apart): each column the one-column solve's to "
          "the bit, the columns past them untouched", C, LD);
    gsl_vector_free(y);
    gsl_permutation_free(p);
    /* many right-hand sides at once, by the pivoted LDL^T: rows of X */
    enum { K = 7 };
    static double X[K * N], B[K * N];
    for (int i = 0; i < K * N; i++)
        X[i] = B[i] = check_rand(-1, 1);
    static size_t perm[N];
    memcpy(F, M, sizeof M);
    rc = la_ldlt_factor(F, N, rel, perm);
    rc |= la_ldlt_solve_rows_neg(F, N, perm, X, K);
    memcpy(F, M, sizeof M);
    gsl_permutation *p2 = gsl_permutation_alloc(N);
    gsl_vector *y2 = gsl_vector_alloc(N);
    gsl_linalg_LU_decomp(&Mv.matrix, p2, &sign);
    worst = big = 0;
    for (int r = 0; r < K; r++) {
        gsl_vector_view br = gsl_vector_view_array(B + r * N, N);
        gsl_linalg_LU_solve(&Mv.matrix, p2, &br.vector, y2);
        for (int i = 0; i < N; i++) {
            worst = fmax(worst, fabs(X[r * N + i] + gsl_vector_get(y2, i)));
            big = fmax(big, fabs(gsl_vector_get(y2, i)));
        }
    }
    CHECK(rc == 0 && worst < 1e-12 * big, "-M^-1 b of %d right-hand sides at once by the "
          "pivoted LDL^T = GSL's LU, to %.2g of max |x|", K, worst / big);
    gsl_vector_free(y2);
    gsl_permutation_free(p2);
    D[5] = -1;
    build(parent, Lr, D, M);
    rc = la_ltdl_factor(M, N, parent, rel);
    CHECK(rc == 6, "with d_5 < 0 it stops at coordinate 5 (rc %d)", rc);
    return check_done();
}
