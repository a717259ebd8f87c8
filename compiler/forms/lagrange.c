/*
 * Lagrange's equations of the second kind:
 *     E_i = d/dt (dT/dq_i') - dT/dq_i + dV/dq_i - Q_i
 * dT/dq and dT/dq' come from one reverse sweep over T; d/dt is the
 * forward-mode total derivative.
 */
#include "forms.h"
#include "form_util.h"

static ExprId *
lagrange(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    (void)why; /* this form applies to every model */
    int n = m->n;
    ExprId *leaves = arena_new_array(A, ExprId, 2 * n);
    ExprId *grad = arena_new_array(A, ExprId, 2 * n);
    for (int i = 0; i < n; i++) {
        leaves[i] = m->q[0][i];
        leaves[n + i] = m->q[1][i];
    }
    diff_gradient(D, m->T, 2 * n, leaves, grad);
    ExprId *E = form_applied(m, A, P, D);
    for (int i = 0; i < n; i++) {
        ExprId dpdt = diff_time(D, grad[n + i]);
        E[i] = expr_add(P, expr_sub(P, dpdt, grad[i]), E[i]);
    }
    return E;
}

const Form form_lagrange = {
    .name = "lagrange",
    .formula = "d/dt(dT/dq') - dT/dq + dV/dq - Q",
    .residual = lagrange,
};

/* Maggi's equations: the same residual, constraints eliminated. */
const Form form_maggi = {
    .name = "maggi",
    .formula = "d/dt(dT/dq') - dT/dq + dV/dq - Q, constraints eliminated (C^T E = 0)",
    .residual = lagrange,
    .eliminate = 1,
};
