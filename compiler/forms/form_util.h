/*
 * form_util: what the forms' residuals share.  Apart from forms.c, the
 * table of forms, so that no form and the table call each other.
 */
#ifndef EOMC_FORM_UTIL_H
#define EOMC_FORM_UTIL_H

#include "mechanics/mech.h"

/* dV/dq_i - Q_i, the part every form shares. */
ExprId *form_applied(const Mech *m, Arena *A, ExprPool *P, Diff *D);
/* Gradient of f with respect to the leaves q^(order); for order 0 with
 * speeds, by the slots' virtual displacements (df/dq dq'/dv, v held). */
ExprId *form_gradient(const Mech *m, ExprId f, int order, Arena *A, Diff *D);

#endif
