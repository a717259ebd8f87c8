/*
 * form_util: what the forms' residuals share (form_util.h).
 */
#include "form_util.h"

ExprId *
form_gradient(const Mech *m, ExprId f, int order, Arena *A, Diff *D)
{
    ExprId *g = arena_new_array(A, ExprId, m->n);
    if (order > 0 || !m->speeds) {
        diff_gradient(D, f, m->n, m->q[order], g);
        return g;
    }
    /* by the slots' virtual displacements: df/dq_i dq_i'/dv_j summed */
    ExprPool *P = diff_pool(D);
    ExprId *gq = arena_new_array(A, ExprId, m->nq);
    diff_gradient(D, f, m->nq, m->q[0], gq);
    for (int j = 0; j < m->n; j++) {
        g[j] = EXPR_ZERO;
        for (int i = 0; i < m->nq; i++)
            if (gq[i] != EXPR_ZERO)
                g[j] = expr_add(P, g[j], expr_mul(P, gq[i], diff_partial(D, m->rate[i],
                                                                         m->q[1][j])));
    }
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
