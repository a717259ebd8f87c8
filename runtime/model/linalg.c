/*
 * linalg: dense factorizations and small vector helpers (see linalg.h).
 */
#include "linalg.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_permute_matrix.h>
#include <gsl/gsl_permute_vector.h>
#include <math.h>
#include <stdlib.h>

struct LaLu {
    int n;
    double *A;            /* [n*n] the equilibrated matrix, then its LU */
    double *row, *col;    /* [n] A_eq = diag(row) A diag(col), powers of 2 */
    double norm1;         /* ||A_eq||_1, for the condition estimate */
    int ok;               /* the last factorization succeeded */
    double pivot;         /* its smallest |U_ii| / max |A_eq| */
    gsl_permutation perm; /* its data in mem */
    gsl_vector_view work; /* [3n] for gsl_linalg_invnorm1 */
    double mem[];
};

LaLu *
la_lu_alloc(int n)
{
    size_t N = (size_t)(n > 0 ? n : 1);
    /* doubles: A, row, col, work; then the permutation's size_t */
    size_t doubles = N * N + 5 * N;
    LaLu *lu = calloc(1, sizeof *lu + doubles * sizeof(double) + N * sizeof(size_t));
    if (!lu)
        return NULL;
    lu->n = n;
    lu->A = lu->mem;
    lu->row = lu->A + N * N;
    lu->col = lu->row + N;
    lu->work = gsl_vector_view_array(lu->col + N, 3 * N);
    lu->perm.size = N;
    lu->perm.data = (size_t *)(lu->mem + doubles);
    return lu;
}

void
la_lu_free(LaLu *lu)
{
    free(lu);
}

/* 2^-e with 2^e <= x < 2^(e+1): the power of 2 that brings x into [1, 2). */
static double
inverse_power(double x)
{
    return ldexp(1.0, -ilogb(x));
}

int
la_lu_factor(LaLu *lu, const double *A)
{
    return la_lu_factor_scaled(lu, A, NULL);
}

int
la_lu_factor_scaled(LaLu *lu, const double *A, const double *d)
{
    int n = lu->n;
    double *E = lu->A;
    lu->ok = 0;
    for (int i = 0; i < n; i++) {
        double di = d ? d[i] : 1, big = 0;
        for (int j = 0; j < n; j++)
            big = fmax(big, fabs(di * A[i * n + j] * (d ? d[j] : 1)));
        if (!(big > 0) || !isfinite(big))
            return -1;
        lu->row[i] = di * inverse_power(big);
    }
    for (int j = 0; j < n; j++) {
        double big = 0, dj = d ? d[j] : 1;
        for (int i = 0; i < n; i++)
            big = fmax(big, fabs(lu->row[i] * A[i * n + j] * dj));
        if (!(big > 0))
            return -1;
        lu->col[j] = dj * inverse_power(big);
    }
    lu->norm1 = 0;
    for (int j = 0; j < n; j++) {
        double sum = 0;
        for (int i = 0; i < n; i++)
            sum += fabs(E[i * n + j] = lu->row[i] * A[i * n + j] * lu->col[j]);
        lu->norm1 = fmax(lu->norm1, sum);
    }
    double scale = la_max_abs(E, n * n);
    gsl_matrix_view Av = gsl_matrix_view_array(E, (size_t)n, (size_t)n);
    int sign;
    gsl_linalg_LU_decomp(&Av.matrix, &lu->perm, &sign);
    lu->pivot = HUGE_VAL;
    for (int i = 0; i < n; i++) {
        lu->pivot = fmin(lu->pivot, fabs(E[i * n + i]) / scale);
        if (!(fabs(E[i * n + i]) > LA_SINGULAR_TOL * scale))
            return -1;
    }
    lu->ok = 1;
    return 0;
}

void
la_lu_solve(LaLu *lu, double *b)
{
    int n = lu->n;
    gsl_matrix_view Av = gsl_matrix_view_array(lu->A, (size_t)n, (size_t)n);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)n);
    for (int i = 0; i < n; i++)
        b[i] *= lu->row[i];
    gsl_linalg_LU_svx(&Av.matrix, &lu->perm, &bv.vector);
    for (int j = 0; j < n; j++)
        b[j] *= lu->col[j];
}

void
la_lu_near_null(LaLu *lu, double *y)
{
    int n = lu->n;
    gsl_matrix_view Av = gsl_matrix_view_array(lu->A, (size_t)n, (size_t)n);
    gsl_vector_view yv = gsl_vector_view_array(y, (size_t)n);
    /* a start with no symmetry the matrix could be orthogonal to */
    for (int i = 0; i < n; i++)
        y[i] = 1.0 + 0.1 * (double)i / (double)n;
    for (int it = 0; it < 2 && lu->ok; it++) {
        gsl_linalg_LU_svx(&Av.matrix, &lu->perm, &yv.vector);
        double big = la_max_abs(y, n);
        for (int i = 0; i < n && big > 0 && isfinite(big); i++)
            y[i] /= big;
    }
}

void
la_kkt_scaling(const double *K, int n, int nc, double *d)
{
    int N = n + nc;
    for (int i = 0; i < n; i++) {
        double h = K[i * N + i];
        d[i] = h > 0 && isfinite(h) ? inverse_power(sqrt(h)) : 1;
    }
    for (int c = 0; c < nc; c++) {
        double big = 0;
        for (int i = 0; i < n; i++)
            big = fmax(big, fabs(K[(n + c) * N + i] * d[i]));
        d[n + c] = big > 0 && isfinite(big) ? inverse_power(big) : 1;
    }
}

/* x = A_eq^-1 x or A_eq^-T x, for gsl_linalg_invnorm1.  P A = L U, so
 * A^T = U^T L^T P. */
static int
equilibrated_solve(CBLAS_TRANSPOSE_t trans, gsl_vector *x, void *params)
{
    LaLu *lu = params;
    gsl_matrix_view Av = gsl_matrix_view_array(lu->A, (size_t)lu->n, (size_t)lu->n);
    if (trans == CblasNoTrans)
        return gsl_linalg_LU_svx(&Av.matrix, &lu->perm, x);
    gsl_blas_dtrsv(CblasUpper, CblasTrans, CblasNonUnit, &Av.matrix, x);
    gsl_blas_dtrsv(CblasLower, CblasTrans, CblasUnit, &Av.matrix, x);
    return gsl_permute_vector_inverse(&lu->perm, x);
}

double
la_lu_pivot(const LaLu *lu)
{
    return lu->ok ? lu->pivot : 0;
}

double
la_lu_condition(LaLu *lu)
{
    double inv = 0;
    if (!lu->ok)
        return NAN;
    if (gsl_linalg_invnorm1((size_t)lu->n, equilibrated_solve, lu, &inv, &lu->work.vector) !=
            GSL_SUCCESS || !isfinite(inv))
        return HUGE_VAL;
    return lu->norm1 * inv;
}

struct LaRank {
    int nr, n;
    gsl_matrix *A;        /* [n x nr] the scaled rows as columns, then QR */
    gsl_vector *tau, *norm, *w; /* [min(n, nr)], [nr], [nr] */
    gsl_permutation *perm; /* [nr] */
};

LaRank *
la_rank_alloc(int nr, int n)
{
    LaRank *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    size_t R = (size_t)(nr > 0 ? nr : 1), N = (size_t)(n > 0 ? n : 1);
    w->nr = nr, w->n = n;
    w->A = gsl_matrix_alloc(N, R);
    w->tau = gsl_vector_alloc(R < N ? R : N);
    w->norm = gsl_vector_alloc(R);
    w->w = gsl_vector_alloc(R);
    w->perm = gsl_permutation_alloc(R);
    if (!w->A || !w->tau || !w->norm || !w->w || !w->perm) {
        la_rank_free(w);
        return NULL;
    }
    return w;
}

void
la_rank_free(LaRank *w)
{
    if (!w)
        return;
    if (w->A)
        gsl_matrix_free(w->A);
    if (w->tau)
        gsl_vector_free(w->tau);
    if (w->norm)
        gsl_vector_free(w->norm);
    if (w->w)
        gsl_vector_free(w->w);
    if (w->perm)
        gsl_permutation_free(w->perm);
    free(w);
}

int
la_rank_rows(LaRank *w, const double *B, int n, const int *rows, int nr, const double *d,
             unsigned char *keep, unsigned char *involved)
{
    if (nr <= 0)
        return 0;
    /* views of the workspace at this size (nr <= w->nr, n == w->n) */
    gsl_matrix_view Av = gsl_matrix_submatrix(w->A, 0, 0, (size_t)n, (size_t)nr);
    gsl_matrix *A = &Av.matrix;
    size_t m = (size_t)(nr < n ? nr : n);
    gsl_vector_view tau = gsl_vector_subvector(w->tau, 0, m);
    gsl_vector_view norm = gsl_vector_subvector(w->norm, 0, (size_t)nr);
    gsl_permutation perm = {(size_t)nr, w->perm->data};
    for (int r = 0; r < nr; r++) {
        const double *b = B + (size_t)rows[r] * n;
        double len = 0;
        for (int i = 0; i < n; i++)
            len = hypot(len, b[i] * (d ? d[i] : 1));
        for (int i = 0; i < n; i++)
            gsl_matrix_set(A, (size_t)i, (size_t)r, len > 0 ? b[i] * (d ? d[i] : 1) / len : 0);
    }
    int sign, rank = 0;
    gsl_linalg_QRPT_decomp(A, &tau.vector, &perm, &sign, &norm.vector);
    while ((size_t)rank < m && fabs(gsl_matrix_get(A, (size_t)rank, (size_t)rank)) > LA_DEPENDENT)
        rank++;
    for (int k = 0; k < nr; k++) {
        int row = rows[perm.data[k]];
        if (keep)
            keep[row] = k < rank;
        if (involved)
            involved[row] = k >= rank;
    }
    /* dependent column k: A_k = (kept columns) R11^-1 R[0 .. rank, k] */
    double *c = w->w->data;
    for (int k = rank; involved && k < nr; k++) {
        double big = 0;
        for (int i = rank - 1; i >= 0; i--) {
            double x = gsl_matrix_get(A, (size_t)i, (size_t)k);
            for (int j = i + 1; j < rank; j++)
                x -= gsl_matrix_get(A, (size_t)i, (size_t)j) * c[j];
            c[i] = x / gsl_matrix_get(A, (size_t)i, (size_t)i);
            big = fmax(big, fabs(c[i]));
        }
        for (int i = 0; i < rank; i++)
            if (fabs(c[i]) > LA_INVOLVED * big)
                involved[rows[perm.data[i]]] = 1;
    }
    return rank;
}

/* GSL's pivoted LDL^T (pcholesky), not ldlt_decomp or cholesky_decomp1:
 * those report a singular or indefinite matrix through GSL's error
 * handler, which aborts the program unless the program turned it off; the
 * handler is the program's to choose, not ours.  pcholesky only computes,
 * and its pivots are tested here, relative to M's own diagonal.  perm is
 * a bijection, so rel[k] is read as M_kk and overwritten once. */
int
la_ldlt_factor(double *M, int n, double *rel, size_t *perm)
{
    if (n == 1) { /* the same test, without GSL's setup: a unit-load system of one
                   * row (one equality) costs more in it than in the recursion */
        perm[0] = 0;
        if (!(M[0] > EOMC_PIVOT_TOL * M[0]))
            return 1;
        rel[0] = 1;
        return 0;
    }
    for (int i = 0; i < n; i++)
        rel[i] = M[i * n + i];
    gsl_matrix_view Mv = gsl_matrix_view_array(M, (size_t)n, (size_t)n);
    gsl_permutation p = {(size_t)n, perm};
    gsl_linalg_pcholesky_decomp(&Mv.matrix, &p);
    for (int i = 0; i < n; i++) { /* in pivot order: the first bad one is to blame */
        size_t k = perm[i];
        double d = M[i * n + i];
        if (!(d > EOMC_PIVOT_TOL * rel[k]))
            return (int)k + 1;
        rel[k] = d / rel[k];
    }
    return 0;
}

int
la_ltdl_factor(double *M, int n, const int *parent, double *rel)
{
    for (int k = 0; k < n; k++)
        rel[k] = M[k * n + k];
    for (int k = n - 1; k >= 0; k--) {
        double d = M[k * n + k];
        if (!(d > EOMC_PIVOT_TOL * rel[k]))
            return k + 1;
        for (int i = parent[k]; i >= 0; i = parent[i]) {
            double a = M[k * n + i] / d;
            for (int j = i; j >= 0; j = parent[j])
                M[i * n + j] -= a * M[k * n + j];
            M[k * n + i] = a;
        }
        rel[k] = d / rel[k];
    }
    return 0;
}

/* Both solves in two passes: up the tree (L^T y = b), then down it with
 * D's division and the sign in the same pass.  Each row is negated when
 * its own division is done, and the rows below subtract the negated
 * values: negation is exact, so the result is -(M^-1 b) to the bit of
 * solving first and negating after. */
void
la_ltdl_solve_neg(const double *LDL, int n, const int *parent, double *b)
{
    for (int i = n - 1; i >= 0; i--) /* L^T y = b */
        for (int j = parent[i]; j >= 0; j = parent[j])
            b[j] -= LDL[i * n + j] * b[i];
    for (int i = 0; i < n; i++) { /* -(D^-1 y) - L x, x the rows above, negated */
        double x = -(b[i] / LDL[i * n + i]);
        for (int j = parent[i]; j >= 0; j = parent[j])
            x -= LDL[i * n + j] * b[j];
        b[i] = x;
    }
}

/* always inlined: into each version below, compiled for its width */
static inline __attribute__((always_inline)) void
ltdl_cols_neg(const double *LDL, int n, const int *parent, double *X, int k, int ld)
{
    for (int i = n - 1; i >= 0; i--) { /* L^T Y = B */
        const double *xi = X + (size_t)i * ld;
        for (int j = parent[i]; j >= 0; j = parent[j]) {
            double l = LDL[i * n + j], *xj = X + (size_t)j * ld;
            for (int c = 0; c < k; c++)
                xj[c] -= l * xi[c];
        }
    }
    for (int i = 0; i < n; i++) { /* -(D^-1 Y) - L X, X's rows above negated */
        double d = LDL[i * n + i], *xi = X + (size_t)i * ld;
        for (int c = 0; c < k; c++)
            xi[c] = -(xi[c] / d);
        for (int j = parent[i]; j >= 0; j = parent[j]) {
            double l = LDL[i * n + j];
            const double *xj = X + (size_t)j * ld;
            for (int c = 0; c < k; c++)
                xi[c] -= l * xj[c];
        }
    }
}

/* The row operations are vector loops: on x86-64 a second version for
 * AVX2, taken where the CPU has it, runs them at twice the portable
 * build's SSE2 width (the humanoid's 76 columns of accel_derivatives: 3.5
 * us less of 51).  The same arithmetic to the bit: AVX2 brings no fused
 * multiply-adds, and each lane rounds as a scalar would.  A call, not GNU
 * ifunc's target_clones, whose resolver clang exports. */
#if defined(__x86_64__) && (defined(__clang__) ? __clang_major__ >= 6 : __GNUC__ >= 6)
#define LA_AVX2 1
__attribute__((target("avx2"))) static void
ltdl_cols_neg_avx2(const double *LDL, int n, const int *parent, double *X, int k, int ld)
{
    ltdl_cols_neg(LDL, n, parent, X, k, ld);
}
#endif

void
la_ltdl_solve_cols_neg(const double *LDL, int n, const int *parent, double *X, int k, int ld)
{
#ifdef LA_AVX2
    if (__builtin_cpu_supports("avx2")) {
        ltdl_cols_neg_avx2(LDL, n, parent, X, k, ld);
        return;
    }
#endif
    ltdl_cols_neg(LDL, n, parent, X, k, ld);
}

void
la_ldlt_solve(double *LDL, int n, size_t *perm, double *b)
{
    if (n == 1) { /* la_ldlt_factor's one pivot */
        b[0] /= LDL[0];
        return;
    }
    gsl_matrix_view L = gsl_matrix_view_array(LDL, (size_t)n, (size_t)n);
    gsl_permutation p = {(size_t)n, perm};
    gsl_vector_view x = gsl_vector_view_array(b, (size_t)n);
    gsl_linalg_pcholesky_svx(&L.matrix, &p, &x.vector);
}

void
la_ldlt_solve_neg(double *LDL, int n, size_t *perm, double *b)
{
    la_ldlt_solve(LDL, n, perm, b);
    for (int i = 0; i < n; i++)
        b[i] = -b[i];
}

int
la_ldlt_solve_rows_neg(double *LDL, int n, size_t *perm, double *X, int k)
{
    if (k == 0)
        return 0;
    size_t *inv = malloc((size_t)n * sizeof *inv);
    if (!inv)
        return -1;
    /* P M P^T = L D L^T, so M^-1 = P^T L^-T D^-1 L^-1 P; a row x^T of X
     * becomes x^T P^T L^-T D^-1 L^-1 P: the columns permuted by p, two
     * triangular solves from the right with D between, the columns put
     * back by p's inverse (as gsl_linalg_pcholesky_svx does a vector) */
    gsl_permutation p = {(size_t)n, perm}, pi = {(size_t)n, inv};
    gsl_permutation_inverse(&pi, &p);
    gsl_matrix_view L = gsl_matrix_view_array(LDL, (size_t)n, (size_t)n);
    gsl_matrix_view Xv = gsl_matrix_view_array(X, (size_t)k, (size_t)n);
    gsl_permute_matrix(&p, &Xv.matrix);
    gsl_blas_dtrsm(CblasRight, CblasLower, CblasTrans, CblasUnit, 1.0, &L.matrix,
                   &Xv.matrix);
    for (int r = 0; r < k; r++)
        for (int i = 0; i < n; i++)
            X[(size_t)r * n + i] /= -LDL[(size_t)i * n + i];
    gsl_blas_dtrsm(CblasRight, CblasLower, CblasNoTrans, CblasUnit, 1.0, &L.matrix,
                   &Xv.matrix);
    gsl_permute_matrix(&pi, &Xv.matrix);
    free(inv);
    return 0;
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
la_quadratic(const double *M, const double *v, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += v[i] * la_dot(M + (size_t)i * n, v, n);
    return s;
}

double
la_max_abs(const double *x, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(x[i]));
    return m;
}

/* 2^-e bringing x into [1, 2), in extended precision. */
static eomc_ext
ext_inverse_power(eomc_ext x)
{
    return ldexpl(1.0L, -ilogbl(x));
}

void
la_ext_kkt_scaling(const eomc_ext *K, int n, int nc, eomc_ext *d)
{
    int N = n + nc;
    for (int i = 0; i < n; i++) {
        eomc_ext h = K[i * N + i];
        d[i] = h > 0 && isfinite(h) ? ext_inverse_power(sqrtl(h)) : 1;
    }
    for (int c = 0; c < nc; c++) {
        eomc_ext big = 0;
        for (int i = 0; i < n; i++)
            big = fmaxl(big, fabsl(K[(n + c) * N + i] * d[i]));
        d[n + c] = big > 0 && isfinite(big) ? ext_inverse_power(big) : 1;
    }
}

int
la_ext_lu_factor(eomc_ext *A, int n, int *perm, eomc_ext *scale, const eomc_ext *d)
{
    eomc_ext *row = scale, *col = scale + n;
    for (int i = 0; i < n * n && d; i++)
        A[i] *= d[i / n] * d[i % n];
    for (int i = 0; i < n; i++) {
        eomc_ext big = 0;
        for (int j = 0; j < n; j++)
            big = fmaxl(big, fabsl(A[i * n + j]));
        if (!(big > 0) || !isfinite(big))
            return -1;
        row[i] = ext_inverse_power(big);
        for (int j = 0; j < n; j++)
            A[i * n + j] *= row[i];
        row[i] *= d ? d[i] : 1;
    }
    for (int j = 0; j < n; j++) {
        eomc_ext big = 0;
        for (int i = 0; i < n; i++)
            big = fmaxl(big, fabsl(A[i * n + j]));
        if (!(big > 0))
            return -1;
        col[j] = ext_inverse_power(big);
        for (int i = 0; i < n; i++)
            A[i * n + j] *= col[j];
        col[j] *= d ? d[j] : 1;
    }
    eomc_ext big = 0;
    for (int i = 0; i < n * n; i++)
        big = fmaxl(big, fabsl(A[i]));
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
        if (!(fabsl(piv) > LA_SINGULAR_TOL * big))
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
la_ext_lu_solve(const eomc_ext *LU, int n, const int *perm, const eomc_ext *scale,
                eomc_ext *b)
{
    for (int i = 0; i < n; i++)
        b[i] *= scale[i];
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
    for (int j = 0; j < n; j++)
        b[j] *= scale[n + j];
}
