/*
 * contact: the normal forces of a contact effect's pairs of shapes
 * (SpecForce.pair), as generalized forces: each contact's gap d in closed
 * form (d > 0 where the shapes overlap), and the force
 * N = where(d, max(0, k d + c d'), 0) along the contact's normal, at the
 * material points that touch, whose switches the runtime locates.
 */
#ifndef EOMC_CONTACT_H
#define EOMC_CONTACT_H

#include "expr/diff.h"
#include "spec/spec.h"

/* Where the forces go (mech.h's Mech, which includes this): by the nq
 * coordinates, whose leaves are q and generalized forces Qq, and by the n
 * velocity slots, leaves v and forces Q. */
typedef struct ContactQ {
    int nq, n;
    const ExprId *q, *v;
    ExprId *Qq, *Q;
} ContactQ;

/* Adds f's forces to out, as mech.c's other effects add theirs; names
 * its switches EFFECT.A.B.touch, .push, ... (e: the effect). */
void contact_add(const Spec *s, const SpecEffect *e, const SpecForce *f, ExprPool *P, Diff *D,
                 const ContactQ *out);

#endif
