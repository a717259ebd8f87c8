/*
 * extrap: one step of an extrapolation method for x' = f(t, x) in
 * extended precision (eomc_ext), and what choosing between the methods
 * needs.  The reference solution (reference.c) owns the step-size
 * control, the output rows and the model's f; this knows neither.
 *
 *  - EXTRAP_GBS: Gragg-Bulirsch-Stoer, the explicit midpoint rule
 *    extrapolated in h^2, order 2 EXTRAP_GBS_LEVELS.  For problems that
 *    are not stiff.
 *  - EXTRAP_LINEARLY_IMPLICIT: the linearly implicit Euler method
 *    extrapolated in h (Deuflhard's EULSIM, Hairer and Wanner's SEULEX),
 *    order EXTRAP_LI_LEVELS, with the Jacobian of the last
 *    extrap_jacobian.  For stiff problems: its base method damps the
 *    modes far faster than the motion instead of needing steps that
 *    resolve them.
 *
 * A step's error estimate is the difference of the tableau's last two
 * values, by component: the caller judges it against the sizes it
 * chooses (the reference, against the magnitudes of the solution's
 * components and groups, the step's end included).
 */
#ifndef EOMC_EXTRAP_H
#define EOMC_EXTRAP_H

#include "eomc_model.h"

/* f(t, x) into dx [N]; 0, or nonzero when the model fails there. */
typedef int (*ExtrapRhs)(void *ctx, eomc_ext t, const eomc_ext *x, eomc_ext *dx);

enum { EXTRAP_GBS, EXTRAP_LINEARLY_IMPLICIT };
enum {
    EXTRAP_GBS_LEVELS = 8, /* order 16 */
    EXTRAP_LI_LEVELS = 8,  /* order 8 */
};

/* A GBS step of size H whose H rho (rho the spectral radius of df/dx)
 * is this or more is held by stability, not accuracy (extrap.c says why):
 * the problem is stiff for it. */
#define EXTRAP_GBS_STIFF 4.0

typedef struct Extrap Extrap;

/* For states of N components; NULL when memory runs out. */
Extrap *extrap_alloc(int N, ExtrapRhs f, void *ctx);
void extrap_free(Extrap *e);

/* One step of method from (t, X), F = f(t, X), of size H: the
 * extrapolated value into out (which may be X), its error estimate by
 * component into est [N] (not out).  0, or -1 when f fails at a stage or
 * (linearly implicit) the iteration matrix is singular: a smaller step
 * may do. */
int extrap_step(Extrap *e, int method, eomc_ext t, eomc_ext H, const eomc_ext *X,
                const eomc_ext *F, eomc_ext *out, eomc_ext *est);
/* The order of the error estimate in H (the local error of the lower of
 * the two values it compares), for the step-size control. */
int extrap_error_order(int method);

/* J = df/dx at (t, X), F = f(t, X), by forward differences (increments
 * sqrt(eps) scale_j), for the linearly implicit steps that follow.  0, or
 * -1 when f fails. */
int extrap_jacobian(Extrap *e, eomc_ext t, const eomc_ext *X, const eomc_ext *F,
                    const eomc_ext *scale);

/* An estimate of the spectral radius of df/dx at (t, X): two steps of the
 * power iteration by difference quotients, going on from the direction
 * the last call left (so repeated calls along a solution converge), in
 * the components' scales.  0, or -1 when f fails. */
int extrap_spectral_radius(Extrap *e, eomc_ext t, const eomc_ext *X, const eomc_ext *F,
                           const eomc_ext *scale, double *rho);

#endif
