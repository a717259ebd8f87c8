/*
 * reftaylor.h: Taylor's method in extended precision, the reference's
 * second way (reference.c, --reference-method taylor): the series of the
 * model's twin (eomc_model_ext's taylor member), with taylor.c's order and
 * step rule, the accelerations' series by one LU a step of M, or of the
 * KKT matrix, in extended precision.  Not installed.
 */
#ifndef EOMC_REFTAYLOR_H
#define EOMC_REFTAYLOR_H

#include "eomc_model.h"

typedef struct RefTaylor RefTaylor;

/* For the twin x of a model of n coordinates, nv speeds (n when they are
 * the rates) and nc constraints (every one affine in q'': x->taylor_a
 * NULL), qd [n] the slots of q' = W(q) v (the model's taylor_qd; NULL when
 * the speeds are the rates), drop [nc] the rows the doubles' solves leave
 * out (sim_dropped_rows; NULL: none); NULL when memory runs out. */
RefTaylor *reftaylor_alloc(const eomc_model_ext *x, const int *qd, int n, int nv, int nc,
                           const unsigned char *drop);
void reftaylor_free(RefTaylor *rt);
/* The series through (t0, x) [n + nv], parameters p and inputs u held, to
 * the order the relative tolerance rtol sets, and the step it allows (at
 * most hmax) into *h; sc [n + nv] is each component's least scale (the
 * reference's error tests').  0, or -1 when M (the KKT matrix) is
 * singular or a coefficient is not finite. */
int reftaylor_series(RefTaylor *rt, eomc_ext t0, const eomc_ext *x, const eomc_ext *p,
                     const eomc_ext *u, eomc_ext rtol, const eomc_ext *sc, eomc_ext hmax,
                     eomc_ext *h);
/* The last series' value at t0 + tau into x [n + nv], by Horner's rule on
 * the change. */
void reftaylor_eval(const RefTaylor *rt, eomc_ext tau, eomc_ext *x);
/* The last series' order. */
int reftaylor_order(const RefTaylor *rt);

#endif
