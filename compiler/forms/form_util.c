/*
 * form_util: what the forms' residuals share (form_util.h).
 */
#include "form_util.h"

ExprId *
form_gradient(const Mech *m, ExprId f, int order, Arena *A, Diff *D)
{
    ExprId *g = arena_new_array(A, ExprId, m->n);
    diff_gradient(D, f, m->n, m->q[order], g);
    return g;
}

ExprId *
form_applied(const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    ExprId *G = form_gradient(m, m->V, 0, A, D);
    for (int i = 0; i < m->n; i++)
        G[i] = expr_sub(P, G[i], m->Q[i]);
    return G;
}
