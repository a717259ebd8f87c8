/*
 * contact: the normal forces of a contact effect's pairs of shapes
 * (SpecForce.pair), as generalized forces: each contact's gap d in closed
 * form (d > 0 where the shapes overlap), and the force
 * N = where(d, max(0, k d + c d'), 0) along the contact's normal, at the
 * material points that touch, whose switches the runtime locates.
 */
#ifndef EOMC_CONTACT_H
#define EOMC_CONTACT_H

#include "base/arena.h"
#include "expr/diff.h"
#include "spec/spec.h"

/* A friction item of a point that touches a plane, along one of the
 * plane's two axes (the runtime's stuck rows): its name EFFECT.A.B.x
 * (EFFECT.A.B.POINT.x where a pair has several points, .y the other
 * axis), its switches (the pool's: slip's function is speed), its bound
 * mu N, and speed, the tangential speed of the touching points, linear in
 * the velocity slots. */
typedef struct ContactFric {
    const char *name;
    int slip, stick;
    ExprId bound, speed;
} ContactFric;

typedef struct ContactFrics {
    int n, cap;
    ContactFric *item;
} ContactFrics;

/* Where the forces go (mech.h's Mech, which includes this): by the nq
 * coordinates, whose leaves are q and generalized forces Qq, and by the n
 * velocity slots, leaves v and forces Q; the friction items into fric
 * (from A). */
typedef struct ContactQ {
    int nq, n;
    const ExprId *q, *v;
    ExprId *Qq, *Q;
    Arena *A;
    ContactFrics *fric;
} ContactQ;

/* Adds f's forces to out, as mech.c's other effects add theirs; names
 * its switches EFFECT.A.B.touch, .push, ... (e: the effect). */
void contact_add(const Spec *s, const SpecEffect *e, const SpecForce *f, ExprPool *P, Diff *D,
                 const ContactQ *out);

#endif
