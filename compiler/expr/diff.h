/*
 * diff: derivatives on the expression DAG.
 *
 *  - diff_partial: d e / d x for a leaf x (VAR, PARAM, INPUT or TIME),
 *    forward chain rule, memoized on (e, x) for the life of the Diff.
 *  - diff_time: the total time derivative, a forward-mode directional
 *    derivative along (1, q', q'', q''', ...):
 *        de/dt = de/dt|explicit + sum_i,k de/dq_i^(k) q_i^(k+1)
 *    Inputs are signals of unknown derivative: differentiating an
 *    expression that contains one gives EXPR_NONE, as does a derivative
 *    order beyond EXPR_MAX_ORDER.
 *  - diff_gradient: reverse mode: the partials of one scalar with respect
 *    to many leaves in one sweep over the DAG.
 *  - diff_jvp: forward mode along a symbolic direction: the derivatives
 *    of many roots along sum_k seed_k d/dleaf_k in one sweep.  With
 *    EXPR_SEED leaves as the seeds the result is one expression, about the
 *    size of the roots, that gives any column of the Jacobian once the
 *    seeds get values.
 */
#ifndef EOMC_DIFF_H
#define EOMC_DIFF_H

#include "expr.h"

typedef struct Diff Diff;

Diff *diff_new(ExprPool *P);
void diff_free(Diff *D);
ExprPool *diff_pool(const Diff *D);

ExprId diff_partial(Diff *D, ExprId e, ExprId leaf);
ExprId diff_time(Diff *D, ExprId e);
void diff_gradient(Diff *D, ExprId f, int n, const ExprId *leaves, ExprId *out);
void diff_jvp(Diff *D, int nroots, const ExprId *roots, int n,
              const ExprId *leaves, const ExprId *seeds, ExprId *out);

/* The partial derivative of node e with respect to its k-th operand
 * (k = 0 or 1), as an expression: the local rule of each operator. */
ExprId diff_local(ExprPool *P, ExprId e, int k);

#endif
