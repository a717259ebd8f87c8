/*
 * linalg: dense factorizations and small vector helpers (see linalg.h).
 */
#include "linalg.h"

#include <gsl/gsl_linalg.h>
#include <math.h>

int
la_lu_factor(double *A, int n, gsl_permutation *perm)
{
    double scale = la_max_abs(A, n * n);
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)n, (size_t)n);
    int sign;
    gsl_linalg_LU_decomp(&Av.matrix, perm, &sign);
    for (int i = 0; i < n; i++)
        if (!(fabs(A[i * n + i]) > LA_SINGULAR_TOL * scale))
            return -1;
    return 0;
}

void
la_lu_solve(double *LU, int n, gsl_permutation *perm, double *b)
{
    gsl_matrix_view Av = gsl_matrix_view_array(LU, (size_t)n, (size_t)n);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)n);
    gsl_linalg_LU_svx(&Av.matrix, perm, &bv.vector);
}

int
la_ldlt_factor(double *M, int n, double *diag)
{
    for (int i = 0; i < n; i++)
        diag[i] = M[i * n + i];
    gsl_matrix_view Mv = gsl_matrix_view_array(M, (size_t)n, (size_t)n);
    int rc = gsl_linalg_ldlt_decomp(&Mv.matrix);
    for (int i = 0; i < n; i++)
        if (!(M[i * n + i] > EOMC_PIVOT_TOL * diag[i]))
            return i + 1;
    return rc == GSL_SUCCESS ? 0 : 1;
}

void
la_ldlt_solve_neg(double *LDL, int n, double *b)
{
    gsl_matrix_view L = gsl_matrix_view_array(LDL, (size_t)n, (size_t)n);
    gsl_vector_view x = gsl_vector_view_array(b, (size_t)n);
    gsl_linalg_ldlt_svx(&L.matrix, &x.vector);
    for (int i = 0; i < n; i++)
        b[i] = -b[i];
}

int
la_cholesky_factor(double *A, int n)
{
    gsl_matrix_view L = gsl_matrix_view_array(A, (size_t)n, (size_t)n);
    return gsl_linalg_cholesky_decomp1(&L.matrix) == GSL_SUCCESS ? 0 : -1;
}

void
la_cholesky_solve(double *L, int n, double *b)
{
    gsl_matrix_view Lv = gsl_matrix_view_array(L, (size_t)n, (size_t)n);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)n);
    gsl_linalg_cholesky_svx(&Lv.matrix, &bv.vector);
}

double
la_dot(const double *a, const double *b, int n)
{
    double d = 0;
    for (int i = 0; i < n; i++)
        d += a[i] * b[i];
    return d;
}

double
la_max_abs(const double *x, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(x[i]));
    return m;
}

int
la_ext_lu_factor(eomc_ext *A, int n, int *perm)
{
    eomc_ext scale = 0;
    for (int i = 0; i < n * n; i++)
        scale = fmaxl(scale, fabsl(A[i]));
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabsl(A[i * n + k]) > fabsl(A[p * n + k]))
                p = i;
        perm[k] = p;
        if (p != k)
            for (int j = 0; j < n; j++) {
                eomc_ext x = A[k * n + j];
                A[k * n + j] = A[p * n + j];
                A[p * n + j] = x;
            }
        eomc_ext piv = A[k * n + k];
        if (!(fabsl(piv) > LA_SINGULAR_TOL * scale))
            return -1;
        for (int i = k + 1; i < n; i++) {
            eomc_ext l = A[i * n + k] /= piv;
            for (int j = k + 1; j < n; j++)
                A[i * n + j] -= l * A[k * n + j];
        }
    }
    return 0;
}

void
la_ext_lu_solve(const eomc_ext *LU, int n, const int *perm, eomc_ext *b)
{
    for (int k = 0; k < n; k++) {
        eomc_ext x = b[k];
        b[k] = b[perm[k]];
        b[perm[k]] = x;
    }
    for (int i = 1; i < n; i++)
        for (int j = 0; j < i; j++)
            b[i] -= LU[i * n + j] * b[j];
    for (int i = n - 1; i >= 0; i--) {
        for (int j = i + 1; j < n; j++)
            b[i] -= LU[i * n + j] * b[j];
        b[i] /= LU[i * n + i];
    }
}
