/*
 * mech: the mechanical quantities of a spec's scene, as expressions:
 * kinetic energy T, potential energy V, acceleration energy S and the
 * generalized forces Q of the enabled effects.  The forms (forms/) derive
 * their residuals from these and nothing else.
 */
#ifndef EOMC_MECH_H
#define EOMC_MECH_H

#include "contact.h"
#include "expr/diff.h"
#include "spec/spec.h"
#include "tree.h"

typedef struct Mech {
    /* n velocity slots (Spec.nv: the coordinates' rates, or a
     * quaternion's speeds in place of its Euler parameters' rates) and nq
     * coordinates; without speeds (speeds 0) n = nq.  q[0] has nq leaves,
     * q[1], q[2], q[3] and Q n: q[k][j] is slot j's (k-1)-th rate. */
    int n, nq, speeds;
    ExprId *rate;  /* [nq] q_i' as an expression of the slots (q[1][i] without speeds) */
    ExprId T, V;   /* kinetic and potential energy */
    /* The part of T that no mass carries: the spec's kinetic terms and
     * those of the effects that are on, and 1/2 c (e.e')^2 per frame
     * turned by a quaternion (mech.c).  Where the recursive forms apply,
     * each moves with one joint's rates (tree.c), and they add its
     * Lagrange terms to theirs, its inertia in that joint's block. */
    ExprId T_joint;
    ExprId S;      /* acceleration energy 1/2 sum m |r''|^2, EXPR_NONE if
                    * the spec or an effect that is on has kinetic terms
                    * (no S for them) */
    ExprId *Q;     /* [n] generalized non-potential forces, by the slots' virtual speeds */
    /* [nq] 1 where coordinate i or its rate is in a kinetic-energy term
     * of the spec's or an effect's own (not a mass's) */
    unsigned char *in_kinetic;
    /* V is V_rest plus the potential of a uniform gravity field (world
     * components, constant in time) on every mass; gravity[0] is
     * EXPR_NONE where there is no such split (V_rest = V). */
    ExprId gravity[3], V_rest;
    ExprId *q[EXPR_MAX_ORDER + 1]; /* q[k][i]: the leaf for q_i^(k) (above) */
    ContactFrics fric; /* the friction items of the contacts that are on */
    Tree *tree;    /* the masses as a tree of turning joints (tree.h), or */
    const char *tree_why; /* NULL and why not */
} Mech;

Mech *mech_build(const Spec *s, Arena *A, ExprPool *P, Diff *D);

#endif
