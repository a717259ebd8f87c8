/*
 * constraint: a spec's constraints brought to acceleration level.
 *
 * Each constraint is classified by the highest derivative of a coordinate
 * in it (order 0 holonomic g(t, q), 1 first order phi(t, q, q'), 2 second
 * order f(t, q, q', q'')) and differentiated 2, 1 or 0 times to
 *     f_a(t, q, q', q'') = 0.
 * Its virtual-displacement row is B_a = df_a/dq'' (Chetaev / Appell rule:
 * dg/dq for holonomic, dphi/dq' for first order).  When every f_a is
 * affine in q'' (always for orders 0 and 1), f = B q'' + b.
 */
#ifndef EOMC_CONSTRAINT_H
#define EOMC_CONSTRAINT_H

#include "mech.h"

#include <stdio.h>

typedef struct Constraints {
    int nc, n;
    const SpecConstraint *spec; /* [nc] names, orders, locations */
    ExprId *f;        /* [nc] acceleration level */
    ExprId *B;        /* [nc*n] df/dq'' */
    ExprId *b;        /* [nc] f at q'' = 0 (meaningful when affine) */
    ExprId *pos;      /* [nc] holonomic: g; otherwise EXPR_NONE */
    ExprId *vel;      /* [nc] holonomic: g'; first order: phi; else EXPR_NONE */
    int affine;       /* every f_a affine in q'' */
    unsigned char *linear; /* [nc] first order: linear in q'; second order:
                            * affine in q''; holonomic: 1 */
    int *dependent;   /* [nc] coordinate eliminated by each constraint */
} Constraints;

/* NULL when the spec has no constraints.  Errors (a constraint that does
 * not restrict the accelerations, an input under d/dt, a dependent
 * coordinate the constraint does not involve) are diagnostics at the
 * constraint's source location. */
Constraints *constraints_build(const Spec *s, const Mech *m, Arena *A, ExprPool *P,
                               Diff *D);

/* Whether a form that solves for q'' by its own recursion can take the
 * constraints by unit loads (runtime/model/kkt.c): there are some, each affine
 * in q'', and they have multipliers (not eliminated). */
int constraints_by_loads(const Constraints *c, int eliminate);

/* "holonomic", "first-order", "second-order". */
const char *constraint_order_name(int order);

/* What --explain says about the constraints: one line each. */
void constraints_explain(FILE *f, const Constraints *c, const Spec *s, int eliminate);

#endif
