/*
 * spatial: Featherstone's spatial vectors as expressions, for the
 * recursive forms.  Every vector is in world components about the world
 * origin: a motion (angular w, linear v: the velocity of the body point
 * at the origin) or a force (moment n about the origin, force f).  The
 * plain dot product of a motion and a force is their power.
 */
#ifndef EOMC_SPATIAL_H
#define EOMC_SPATIAL_H

#include "forms.h"

typedef struct Sv {
    ExprId w[3], v[3]; /* angular, linear */
} Sv;

void sv_zero(Sv *x);
/* x += s y */
void sv_axpy(ExprPool *P, Sv *x, ExprId s, const Sv *y);
void sv_add(ExprPool *P, Sv *x, const Sv *y);
/* the power x . y (a motion and a force) */
ExprId sv_dot(ExprPool *P, const Sv *x, const Sv *y);
/* x cross y for motions: (w x w2, w x v2 + v x w2) */
void sv_cross_motion(ExprPool *P, const Sv *x, const Sv *y, Sv *out);
/* x cross* f for a force f = (n, f): (w x n + v x f, w x f) */
void sv_cross_force(ExprPool *P, const Sv *x, const Sv *f, Sv *out);
/* The spatial inertia (m, h = m c, I about the origin) times a motion:
 * (I w + h x v, m v - h x w). */
void sv_inertia_times(ExprPool *P, ExprId m, const ExprId *h, const ExprId *I, const Sv *x,
                      Sv *out);
/* In the turns' own coordinates (tree.h's local frames, the articulated-
 * body form's and the recursive Newton-Euler form's): a motion carried
 * from up's coordinates into turn t's (w' = Q^T w, v' = Q^T (v - r x w)),
 * and a force from t's into up's (f' = Q f, n' = Q n + r x f'). */
void sv_motion_down(ExprPool *P, const TreeTurn *t, const Sv *x, Sv *out);
void sv_force_up(ExprPool *P, const TreeTurn *t, const Sv *x, Sv *out);
/* The rigid inertia (m, first moment h, I) about a turn's origin in its
 * axes. */
typedef struct Rigid {
    ExprId m, h[3], I[9];
} Rigid;
/* Y += X carried from turn t's coordinates into up's: h' = Q h + m r,
 * I' = J + 2 (r.g) 1 - (g r^T + r g^T) + m (|r|^2 1 - r r^T), with
 * g = Q h and J = Q I Q^T (the parallel-axis rule with a first moment). */
void sv_rigid_up(ExprPool *P, const TreeTurn *t, const Rigid *X, Rigid *Y);
/* The masses each joint carries last (zero for a turn inside a frame). */
Rigid *sv_bodies(ExprPool *P, Arena *A, const Tree *t);
/* A joint's axis S in its own coordinates: (a, 0) for a turn, (0, d) for
 * a slide. */
void sv_joint_axis(const TreeTurn *t, Sv *S);
/* Its axes, one per coordinate (t->ndof of them: a ball's four are its
 * angular velocity's derivatives along its Euler parameters' rates, (Sw[d],
 * 0)); returns t->ndof. */
int sv_joint_axes(const TreeTurn *t, Sv S[4]);
/* Lagrange's d/dt(dT_joint/dq') - dT_joint/dq for the part of T no mass
 * carries (mech.h: a rotor's inertia, a quaternion's e' along e), which
 * the recursions over the masses leave out; NULL when there is none. */
ExprId *sv_joint_terms(const Mech *m, Arena *A, ExprPool *P, Diff *D);
/* dV/dq - Q, and the world's acceleration a0 that stands for a uniform
 * gravity field (Featherstone's a_0 = -g; then V's part from it is left
 * out of the gradient), or zero. */
ExprId *sv_applied(const Mech *m, Arena *A, ExprPool *P, Diff *D, Sv *a0);

/* A free joint: a ball with speeds (its axes its own unit axes) on three
 * slides in a row from the world, massless and carrying nothing but the
 * next (how a floating base comes out of tree.h), the slides' directions
 * constants.  In the ball's axes the slides move along the columns of
 * Q^T G (G their directions in the last slide's axes, Q the ball's turn).
 * The recursions take it as one joint of six degrees of freedom. */
typedef struct SvFree {
    int slide[3];     /* the slides' turns, the world's first */
    ExprId G[9], Gi[9]; /* G and G^-1, constants */
} SvFree;
/* [nturns]: at a free joint's ball, the joint, else NULL.  With Eq
 * (sv_joint_terms), not where a rotor's inertia couples its coordinates. */
SvFree **sv_free_joints(const Mech *m, Arena *A, ExprPool *P, Diff *D, const ExprId *Eq);

/* The recursive Newton-Euler residual and the composite-rigid-body mass
 * matrix of m->tree (forms/newton_euler.c), which the articulated-body
 * form shares. */
ExprId *rne_residual(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why);
ExprId *crb_mass(const Mech *m, Arena *A, ExprPool *P, Diff *D);

#endif
