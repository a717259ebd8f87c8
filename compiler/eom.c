/*
 * eom: derive M, h and the residual Jacobians from a form's residual.
 *
 * M_ij = dE_i/dq_j'' by forward partials (measured: about 10% less code
 * for the chain benchmark than taking M from the reverse sweep); the
 * partials with respect to q, q', u and t come from one reverse sweep per
 * row.  Only the lower triangle of M is derived: M is symmetric for every
 * form here (tests/unit/test_forms.c checks the upper triangle against the
 * residual).
 */
#include "eom.h"

static void
derive_row(Eom *e, Diff *D, const ExprId *accel, const ExprId *leaves,
           ExprId *grad, int i)
{
    int n = e->n, nu = e->nu, nl = 2 * n + nu + 1;
    for (int j = 0; j <= i; j++)
        e->M[i * n + j] = e->M[j * n + i] = diff_partial(D, e->E[i], accel[j]);
    diff_gradient(D, e->E[i], nl, leaves, grad);
    for (int j = 0; j < n; j++) {
        e->dEdq[i * n + j] = grad[j];
        e->dEdv[i * n + j] = grad[n + j];
    }
    for (int k = 0; k < nu; k++)
        e->dEdu[i * nu + k] = grad[2 * n + k];
    e->dEdt[i] = grad[2 * n + nu];
}

Eom *
eom_derive(const Spec *s, const Mech *m, const Form *f, Arena *A,
           ExprPool *P, Diff *D, const char **why)
{
    ExprId *E = f->residual(m, A, P, D, why);
    if (!E)
        return NULL;
    int n = m->n, nu = s->nu, nl = 2 * n + nu + 1;
    Eom *e = arena_alloc(A, sizeof *e);
    e->n = n;
    e->nu = nu;
    e->form = f;
    e->E = E;
    e->M = arena_new_array(A, ExprId, n * n);
    e->h = arena_new_array(A, ExprId, n);
    e->dEdq = arena_new_array(A, ExprId, n * n);
    e->dEdv = arena_new_array(A, ExprId, n * n);
    e->dEdu = arena_new_array(A, ExprId, n * nu + 1);
    e->dEdt = arena_new_array(A, ExprId, n);
    ExprId *leaves = arena_new_array(A, ExprId, nl);
    ExprId *grad = arena_new_array(A, ExprId, nl);
    for (int j = 0; j < n; j++) {
        leaves[j] = m->q[0][j];
        leaves[n + j] = m->q[1][j];
    }
    for (int k = 0; k < nu; k++)
        leaves[2 * n + k] = expr_input(P, k);
    leaves[2 * n + nu] = expr_time(P);
    for (int i = 0; i < n; i++)
        derive_row(e, D, m->q[2], leaves, grad, i);
    /* h = E at q'' = 0: substitution rebuilds only what depends on q'' */
    ExprId *zeros = arena_new_array(A, ExprId, n);
    for (int j = 0; j < n; j++)
        zeros[j] = EXPR_ZERO;
    for (int i = 0; i < n; i++)
        e->h[i] = expr_subst(P, E[i], n, m->q[2], zeros);
    return e;
}
