/*
 * invariant: the quantity a model's motion conserves, decided from the
 * spec.  The energy function
 *     h = q' . dL/dq' - L,   L = T - V,
 * changes as dh/dt = -dL/dt|explicit + q' . (Q - B^T lambda), so it is
 * conserved when T, V and the constraints are free of t (and of inputs,
 * which are signals of t), no effect gives a generalized force Q (every
 * effect on is a potential), and the constraint forces do no work:
 * B q' = 0 on the constraints, which holds for a holonomic g(q) (B q' is
 * g') and for a first-order phi(q, q') homogeneous in q' (by Euler's
 * theorem B q' = k phi for degree k).  Second-order constraints are not
 * credited with it.  Split by degree in q', T = T2 + T1 + T0 and
 * h = T2 - T0 + V, which is T + V exactly when T is a quadratic form.
 * Free of t means by structure (no t left once simplified), or, where t
 * is written but cancels through an identity the simplifier does not
 * apply, by a numerical zero test of the partial derivatives in t in long
 * double at random states (invariant.c); Invariant.test says which.
 * docs/mechanics.md has the derivation and the test's criterion.
 */
#ifndef EOMC_INVARIANT_H
#define EOMC_INVARIANT_H

#include "constraint.h"

typedef struct Invariant {
    ExprId h;          /* the conserved quantity, EXPR_NONE if none */
    const char *name;  /* "E" (h = T + V) or "h"; NULL if none */
    const char *note;  /* one sentence: what is conserved and why, or why not */
    const char *test;  /* for --explain: which test decided whether T, V and the
                        * constraints are free of t (the structure, or the
                        * numerical zero test and what it saw) */
} Invariant;

/* c: the constraints, or NULL. */
Invariant *invariant_derive(const Spec *s, const Mech *m, const Constraints *c, Arena *A,
                            ExprPool *P, Diff *D);

/* The degree k of e in the velocities q' (e(q, s q') = s^k e(q, q') for
 * every s > 0), as far as the structure of e shows it; NAN when e is not
 * homogeneous or contains accelerations. */
double invariant_velocity_degree(ExprPool *P, ExprId e);

#endif
