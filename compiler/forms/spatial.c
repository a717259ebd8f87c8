/*
 * spatial: spatial vector algebra on expressions (spatial.h).
 */
#include "spatial.h"

#include "../kin.h"

void
sv_zero(Sv *x)
{
    for (int i = 0; i < 3; i++)
        x->w[i] = x->v[i] = EXPR_ZERO;
}

/* x += s y */
void
sv_axpy(ExprPool *P, Sv *x, ExprId s, const Sv *y)
{
    for (int i = 0; i < 3; i++) {
        x->w[i] = expr_add(P, x->w[i], expr_mul(P, s, y->w[i]));
        x->v[i] = expr_add(P, x->v[i], expr_mul(P, s, y->v[i]));
    }
}

void
sv_add(ExprPool *P, Sv *x, const Sv *y)
{
    for (int i = 0; i < 3; i++) {
        x->w[i] = expr_add(P, x->w[i], y->w[i]);
        x->v[i] = expr_add(P, x->v[i], y->v[i]);
    }
}

/* x cross y for motions: (w x w2, w x v2 + v x w2) */
void
sv_cross_motion(ExprPool *P, const Sv *x, const Sv *y, Sv *out)
{
    ExprId a[3], b[3];
    Sv r;
    kin_cross(P, x->w, y->w, r.w);
    kin_cross(P, x->w, y->v, a);
    kin_cross(P, x->v, y->w, b);
    for (int i = 0; i < 3; i++)
        r.v[i] = expr_add(P, a[i], b[i]);
    *out = r;
}

/* x cross* f for a force f = (n, f): (w x n + v x f, w x f) */
void
sv_cross_force(ExprPool *P, const Sv *x, const Sv *f, Sv *out)
{
    ExprId a[3], b[3];
    Sv r;
    kin_cross(P, x->w, f->w, a);
    kin_cross(P, x->v, f->v, b);
    for (int i = 0; i < 3; i++)
        r.w[i] = expr_add(P, a[i], b[i]);
    kin_cross(P, x->w, f->v, r.v);
    *out = r;
}

/* The spatial inertia (m, h, I) times a motion: (I w + h x v, m v - h x w). */
void
sv_inertia_times(ExprPool *P, ExprId m, const ExprId *h, const ExprId *I, const Sv *x, Sv *out)
{
    ExprId hv[3], hw[3];
    Sv r;
    kin_cross(P, h, x->v, hv);
    kin_cross(P, h, x->w, hw);
    for (int i = 0; i < 3; i++) {
        r.w[i] = expr_add(P, kin_dot(P, &I[3 * i], x->w), hv[i]);
        r.v[i] = expr_sub(P, expr_mul(P, m, x->v[i]), hw[i]);
    }
    *out = r;
}

/* S = (a, p x a) */
void
sv_turn_axis(ExprPool *P, const TreeFrame *f, const TreeTurn *t, Sv *S)
{
    for (int i = 0; i < 3; i++)
        S->w[i] = t->a[i];
    kin_cross(P, f->pivot, t->a, S->v);
}


ExprId
sv_dot(ExprPool *P, const Sv *x, const Sv *y)
{
    ExprId w = kin_dot(P, x->w, y->w);
    return expr_add(P, w, kin_dot(P, x->v, y->v));
}
