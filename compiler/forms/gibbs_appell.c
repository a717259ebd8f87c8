/*
 * The Gibbs–Appell form (the paper's (1.6) without constraints):
 *     E_i = dS/dq_i'' + dV/dq_i - Q_i,   S = 1/2 sum_k m_k |r_k''|^2
 * S is only defined here for masses: explicit kinetic-energy terms have
 * no acceleration energy, so such models are refused.
 */
#include "forms.h"
#include "form_util.h"

static ExprId *
gibbs_appell(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    if (m->S == EXPR_NONE) {
        *why = "the spec has explicit kinetic-energy terms (its own, or an effect's that is "
               "on), which define no acceleration energy S";
        return NULL;
    }
    ExprId *dS = form_gradient(m, m->S, 2, A, D);
    ExprId *E = form_applied(m, A, P, D);
    for (int i = 0; i < m->n; i++)
        E[i] = expr_add(P, dS[i], E[i]);
    return E;
}

const Form form_gibbs_appell = {
    .name = "gibbs-appell",
    .formula = "dS/dq'' + dV/dq - Q",
    .residual = gibbs_appell,
    .speeds = 1,
};
