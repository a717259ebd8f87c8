/*
 * linalg: the dense linear algebra of the runtime, on row-major arrays.
 * Knows nothing of models or simulators.
 *
 * Factorizations of doubles are GSL's; the tests that call a matrix
 * singular are ours, and relative to the matrix's own entries.  The
 * reference solution (reference.c) solves in extended precision
 * (eomc_ext), for which GSL has no routines: the la_ext_ functions are
 * a plain LU with partial pivoting and the same test.
 */
#ifndef EOMC_LINALG_H
#define EOMC_LINALG_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#include "eomc_model.h"

/* A pivot is negligible when |U_ii| <= LA_SINGULAR_TOL max|A_ij|, A
 * equilibrated (la_lu) or as given (la_ext_lu). */
#define LA_SINGULAR_TOL 1e-13

/*
 * An LU factorization of a square matrix whose rows and columns may carry
 * different units (a KKT matrix mixes masses and lengths, an iteration
 * matrix positions and velocities).  It first equilibrates, as LAPACK's
 * dgeequb does: each row, then each column, is scaled by a power of 2 to
 * bring its largest entry near 1.  Rescaling a row or column of A by any
 * factor then changes neither the pivots' test nor the solution beyond
 * rounding, and the condition estimate is that of the balanced matrix:
 * what the problem's units do not decide.
 */
typedef struct LaLu LaLu;

/* NULL when memory runs out; la_lu_free is NULL-safe. */
LaLu *la_lu_alloc(int n);
void la_lu_free(LaLu *lu);
/* Factor A [n*n] (left unchanged); 0, or -1 when A has a zero row or
 * column or a pivot is negligible. */
int la_lu_factor(LaLu *lu, const double *A);
/* The same for diag(d) A diag(d), d [n] a symmetric scaling the caller
 * knows better than the entries' sizes can tell (la_kkt_scaling); the
 * solve still solves with A. */
int la_lu_factor_scaled(LaLu *lu, const double *A, const double *d);
/* b = A^-1 b, A as last factored. */
void la_lu_solve(LaLu *lu, double *b);
/* An estimate of cond_1 of the equilibrated A, as last factored (Hager
 * and Higham's, a few solves): HUGE_VAL when it is singular to working
 * precision, NAN when the last la_lu_factor failed. */
double la_lu_condition(LaLu *lu);
/* The smallest |U_ii| of the last factorization, relative to the
 * equilibrated matrix's largest entry (free: the singularity test
 * computes it); its inverse is about a lower bound on the condition. */
double la_lu_pivot(const LaLu *lu);
/* The direction y [n] (max |y_i| = 1) that the equilibrated A, as last
 * factored, most nearly annihilates: two steps of inverse iteration.
 * Its large entries name the unknowns an ill-conditioned system mixes. */
void la_lu_near_null(LaLu *lu, double *y);

/*
 * Which rows of B = df/dq'' are independent: QR with column pivoting
 * (GSL's QRPT) of B^T, B's columns first scaled by d (1/sqrt(M_ii): the
 * kinetic-energy metric, free of the coordinates' units) and each row then
 * brought to unit length (free of the constraint's own factor).  In pivot
 * order each R_kk is the part of a row independent of the rows before it;
 * a row whose part is at most LA_DEPENDENT is dependent on them.  The
 * multipliers' system B M^-1 B^T has about the squares of these as its
 * pivots, so the rows it would call singular (LA_SINGULAR_TOL, EOMC_PIVOT_TOL)
 * are the ones called dependent here.
 */
#define LA_DEPENDENT 3e-7 /* about sqrt(LA_SINGULAR_TOL) */
/* A row takes part in a dependent row's combination of the independent
 * ones when its coefficient there is above this of the largest. */
#define LA_INVOLVED 1e-6
typedef struct LaRank LaRank;
/* Room for up to nr rows of n entries; NULL when memory runs out. */
LaRank *la_rank_alloc(int nr, int n);
void la_rank_free(LaRank *w);
/* The rows rows[0 .. nr) of B [* x n], scaled as above (d [n], or NULL
 * for none): their rank.  keep[rows[i]] (unless NULL) is 1 for the
 * independent rows QR's pivots keep, 0 for the others, each dependent on
 * the kept ones; involved[rows[i]] (unless NULL) is 1 for each row that
 * takes part in a dependency: a dependent row, and the kept rows its
 * combination uses.  A row of zeros is dependent, a combination of none. */
int la_rank_rows(LaRank *w, const double *B, int n, const int *rows, int nr, const double *d,
                 unsigned char *keep, unsigned char *involved);

/* P M P^T = L D L^T in place (GSL's pivoted Cholesky), M symmetric; 0,
 * or k + 1 when the pivot of coordinate k is d <= EOMC_PIVOT_TOL M_kk (M
 * singular or not positive definite; the first such in pivot order).  On
 * success rel[k] [n] is that pivot relative to M_kk, the condition watch's
 * measure; perm [n] is the permutation, for the solves.  Never calls GSL's
 * error handler. */
int la_ldlt_factor(double *M, int n, double *rel, size_t *perm);
/* M = L^T D L in place when M_ij = 0 unless one of i, j is an ancestor
 * of the other in the tree parent[] (parent[i] < i, -1 a root):
 * Featherstone's LTDL (Rigid Body Dynamics Algorithms, sec. 6.5), which
 * has no fill-in, so it costs the sum of the squared depths instead of
 * n^3/6.  Only the lower triangle's ancestor entries are read and written.
 * Returns and rel[] as la_ldlt_factor's, in elimination order (the last
 * coordinate first).  No pivoting: the tree fixes the order, and the
 * pivot check stops a run whose M is not safely positive definite. */
int la_ltdl_factor(double *M, int n, const int *parent, double *rel);
/* b = -M^-1 b with M factored by la_ltdl_factor. */
void la_ltdl_solve_neg(const double *LDL, int n, const int *parent, double *b);
/* The same for the k columns of X [n rows, row i at X + i * ld], each a
 * right-hand side, all at once: each step of the solve is a row operation
 * on k contiguous numbers, the same operations as la_ltdl_solve_neg's on
 * each column. */
void la_ltdl_solve_cols_neg(const double *LDL, int n, const int *parent, double *X, int k,
                            int ld);
/* b = M^-1 b, and b = -M^-1 b, with M factored by la_ldlt_factor. */
void la_ldlt_solve(double *LDL, int n, size_t *perm, double *b);
void la_ldlt_solve_neg(double *LDL, int n, size_t *perm, double *b);
/* X = -X M^-1 for X [k x n] row-major (each row a right-hand side, M
 * symmetric), with M factored by la_ldlt_factor: the solves of many
 * right-hand sides at once, by GSL's BLAS-3 triangular solves; 0, or -1
 * when memory runs out (X as it was). */
int la_ldlt_solve_rows_neg(double *LDL, int n, size_t *perm, double *X, int k);

/*
 * When a Newton-type iteration (kkt.c's, project.c's) may stop.  Each of
 * its equations is measured against the magnitude of its terms, so the
 * test means the same in any units: the iteration stops when the largest
 * such relative residual is LA_SETTLED_TIGHT (rounding: 16 units of it),
 * or when it stopped decreasing below LA_SETTLED_LOOSE: then
 * what is left is the rounding of the equations themselves, which the
 * magnitude of their terms need not bound.  Quadratic convergence makes
 * the second case cost one extra iteration; a step's size is not used, as
 * an ill-conditioned system leaves steps of rounding times its condition
 * long after its equations hold.
 */
#define LA_SETTLED_TIGHT (16 * DBL_EPSILON)
#define LA_SETTLED_LOOSE 1e-8
static inline int
la_settled(double rel, double prev)
{
    return rel <= LA_SETTLED_TIGHT || (rel <= LA_SETTLED_LOOSE && rel >= prev);
}
/* |r| relative to mag, the magnitude of r's terms: 0 when r is exactly
 * 0, infinite when r is not but mag is 0. */
static inline double
la_relative(double r, double mag)
{
    return r == 0 ? 0 : mag > 0 ? fabs(r) / mag : HUGE_VAL;
}

double la_dot(const double *a, const double *b, int n);
/* v^T M v, M n x n row-major */
double la_quadratic(const double *M, const double *v, int n);
/* max_i |x_i| */
double la_max_abs(const double *x, size_t n);

/*
 * A KKT matrix K = [H B^T; B 0] (H the mass matrix, plus the constraints'
 * curvature) needs more than equilibration: when the masses are small
 * against B's entries, every row and column of K already has its largest
 * entry in B, yet the motion along the constraints is decided by H alone.
 * The symmetric scaling d [n + nc] that makes H's diagonal near 1 and then
 * each row of B's largest entry near 1 balances both, whatever the units:
 *     d_i = 1 / sqrt(H_ii),   d_(n+c) = 1 / max_i |B_ci d_i|,
 * as powers of 2; a coordinate without mass keeps d_i = 1 and is left to
 * the equilibration.  K [(n+nc)^2] is row-major.
 */
void la_kkt_scaling(const double *K, int n, int nc, double *d);

/* The same LU, equilibrated the same way, in extended precision, in
 * place: perm [n] and scale [2n] (the rows', then the columns') are filled
 * here for la_ext_lu_solve.  d [n] is a symmetric scaling applied first
 * (la_ext_kkt_scaling), or NULL. */
int la_ext_lu_factor(eomc_ext *A, int n, int *perm, eomc_ext *scale, const eomc_ext *d);
void la_ext_kkt_scaling(const eomc_ext *K, int n, int nc, eomc_ext *d);
void la_ext_lu_solve(const eomc_ext *LU, int n, const int *perm, const eomc_ext *scale,
                     eomc_ext *b);

#endif
