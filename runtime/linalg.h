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

#include <gsl/gsl_permutation.h>

#include "eomc_model.h"

/* A pivot is negligible when |U_ii| <= LA_SINGULAR_TOL max|A_ij|. */
#define LA_SINGULAR_TOL 1e-13

/* A = LU in place (partial pivoting); 0, or -1 when a pivot is negligible. */
int la_lu_factor(double *A, int n, gsl_permutation *perm);
/* b = A^-1 b with A factored by la_lu_factor. */
void la_lu_solve(double *LU, int n, gsl_permutation *perm, double *b);

/* M = L D L^T in place, M symmetric; 0, or k + 1 for the first pivot
 * d_k <= EOMC_PIVOT_TOL M_kk (M singular or not positive definite).
 * diag [n] is scratch for M's diagonal. */
int la_ldlt_factor(double *M, int n, double *diag);
/* b = -M^-1 b with M factored by la_ldlt_factor. */
void la_ldlt_solve_neg(double *LDL, int n, double *b);

/* A = L L^T in place; 0, or -1 when A is not positive definite. */
int la_cholesky_factor(double *A, int n);
/* b = A^-1 b with A factored by la_cholesky_factor. */
void la_cholesky_solve(double *L, int n, double *b);

double la_dot(const double *a, const double *b, int n);
/* max_i |x_i| */
double la_max_abs(const double *x, int n);

/* The same LU in extended precision: perm [n] is filled here. */
int la_ext_lu_factor(eomc_ext *A, int n, int *perm);
void la_ext_lu_solve(const eomc_ext *LU, int n, const int *perm, eomc_ext *b);

#endif
