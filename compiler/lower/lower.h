/*
 * lower: a derived model as the list of functions the generated C file
 * defines, each a list of (expression, output slot) (lowered.h).
 *
 * This is the last step that differentiates (input derivatives, the
 * constraints' Jacobians, the seeded Jacobian's split into shared and
 * per-column values).  What comes out is data, and every array size the
 * C needs is read off it (lower_size).  lower_model calls the rest of
 * lower/: lower_describe for the names and the scene, repeat_split for
 * copies of one subtree, lower_taylor for Taylor's program; each function's
 * schedule is lower_schedule's.
 */
#ifndef EOMC_LOWER_H
#define EOMC_LOWER_H

#include "lowered.h"
#include "forms/eom.h"
#include "mechanics/constraint.h"
#include "mechanics/invariant.h"

/* The jacobian member's signature (the seeded Jacobian's driver has it). */
extern const LowSig lower_jacobian_sig;
/* The invariant member's (its sum of energy's T and V has it). */
extern const LowSig lower_invariant_sig;

/* c: the constraints, or NULL; eliminate: they are eliminated (else
 * multipliers).  Derives e's partial derivatives (eom_derive_jacobian)
 * when the Jacobian is printed. */
Lowered *lower_model(const Spec *s, const Mech *m, Eom *e, const Constraints *c,
                     int eliminate, const Invariant *inv, int jacobian, int code, int taylor,
                     Arena *A, ExprPool *P, Diff *D);

#endif
