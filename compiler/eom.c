/*
 * eom: derive M, h and the residual Jacobians from a form's residual.
 */
#include "eom.h"

/* Row i of every derivative of E_i in one reverse sweep: leaves are
 * q'' (for M), q, q', u and t. */
static void
derive_row(Eom *e, Diff *D, ExprId *leaves,
           ExprId *grad, int i)
{
    int n = e->n, nu = e->nu, nl = 3 * n + nu + 1;
    diff_gradient(D, e->E[i], nl, leaves, grad);
    for (int j = 0; j <= i; j++)
        e->M[i * n + j] = e->M[j * n + i] = grad[j];
    for (int j = 0; j < n; j++) {
        e->dEdq[i * n + j] = grad[n + j];
        e->dEdv[i * n + j] = grad[2 * n + j];
    }
    for (int k = 0; k < nu; k++)
        e->dEdu[i * nu + k] = grad[3 * n + k];
    e->dEdt[i] = grad[3 * n + nu];
}

Eom *
eom_derive(const Spec *s, const Mech *m, const Form *f, Arena *A,
           ExprPool *P, Diff *D, const char **why)
{
    ExprId *E = f->residual(m, A, P, D, why);
    if (!E)
        return NULL;
    int n = m->n, nu = s->nu, nl = 3 * n + nu + 1;
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
        leaves[j] = m->q[2][j];
        leaves[n + j] = m->q[0][j];
        leaves[2 * n + j] = m->q[1][j];
    }
    for (int k = 0; k < nu; k++)
        leaves[3 * n + k] = expr_input(P, k);
    leaves[3 * n + nu] = expr_time(P);
    for (int i = 0; i < n; i++)
        derive_row(e, D, leaves, grad, i);
    /* h = E at q'' = 0: substitution rebuilds only what depends on q'' */
    ExprId *zeros = arena_new_array(A, ExprId, n);
    for (int j = 0; j < n; j++)
        zeros[j] = EXPR_ZERO;
    for (int i = 0; i < n; i++)
        e->h[i] = expr_subst(P, E[i], n, m->q[2], zeros);
    return e;
}
