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
/* A turn's axis S = (a, p x a), p the pivot of its frame. */
void sv_turn_axis(ExprPool *P, const TreeFrame *f, const TreeTurn *t, Sv *S);

/* The recursive Newton-Euler residual and the composite-rigid-body mass
 * matrix of m->tree (forms/newton_euler.c), which the articulated-body
 * form shares. */
ExprId *rne_residual(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why);
ExprId *crb_mass(const Mech *m, Arena *A, ExprPool *P);

#endif
