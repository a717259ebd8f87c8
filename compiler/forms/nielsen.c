/*
 * Nielsen's form (the 1973 paper, section 2):
 *     E_i = d(T')/dq_i' - 2 dT/dq_i + dV/dq_i - Q_i,   T' = dT/dt
 */
#include "forms.h"
#include "form_util.h"

static ExprId *
nielsen(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    (void)why; /* this form applies to every model */
    ExprId Tdot = diff_time(D, m->T);
    ExprId *dTdot = form_gradient(m, Tdot, 1, A, D);
    ExprId *dT = form_gradient(m, m->T, 0, A, D);
    ExprId *E = form_applied(m, A, P, D);
    ExprId two = expr_const(P, 2.0);
    for (int i = 0; i < m->n; i++)
        E[i] = expr_add(P, expr_sub(P, dTdot[i], expr_mul(P, two, dT[i])), E[i]);
    return E;
}

const Form form_nielsen = {
    .name = "nielsen",
    .formula = "d(T')/dq' - 2 dT/dq + dV/dq - Q",
    .residual = nielsen,
};
