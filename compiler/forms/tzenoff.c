/*
 * Tzénoff's (Tsenov's) equations of the second kind (the paper, section 3):
 *     E_i = 1/2 d(T'')/dq_i'' - 3/2 dT/dq_i + dV/dq_i - Q_i
 * T'' contains q'''; only its q'' dependence survives d/dq''.
 */
#include "forms.h"
#include "form_util.h"

static ExprId *
tzenoff(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    (void)why; /* this form applies to every model */
    ExprId T2 = diff_time(D, diff_time(D, m->T));
    ExprId *dT2 = form_gradient(m, T2, 2, A, D);
    ExprId *dT = form_gradient(m, m->T, 0, A, D);
    ExprId *E = form_applied(m, A, P, D);
    ExprId half = expr_const(P, 0.5), three_halves = expr_const(P, 1.5);
    for (int i = 0; i < m->n; i++) {
        ExprId b = expr_mul(P, three_halves, dT[i]);
        ExprId a = expr_mul(P, half, dT2[i]);
        ExprId r = expr_sub(P, a, b);
        E[i] = expr_add(P, r, E[i]);
    }
    return E;
}

const Form form_tzenoff = {
    .name = "tzenoff",
    .formula = "1/2 d(T'')/dq'' - 3/2 dT/dq + dV/dq - Q",
    .residual = tzenoff,
};
