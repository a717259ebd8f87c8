/*
 * The recursive Newton-Euler form, for a tree of rigid bodies on turning
 * joints (tree.h):
 *     E_i = S_i . F(frame of turn i) + dV/dq_i - Q_i
 * where F(g) is the net spatial force the masses g turns need,
 *     F(g) = sum over g's subtree of  I_k A_k + V_k x* I_k V_k,
 * V and A the frames' spatial velocities and accelerations, built from
 * the world outward (V += S th', A += S th'' + (V x S) th', V before the
 * turn), and the sum taken from the leaves inward.  Spatial vectors are
 * (angular, linear) in world components about the world origin.
 *
 * Its mass matrix is not differentiated out of E: it is the composite-
 * rigid-body sum M_ij = S_i . Ic(g_j) S_j for turn i at or above turn j,
 * Ic(g) the inertia of g's subtree, with S_i . F taken as the moment of
 * F about turn i's pivot along its axis.  The residual and M come from
 * the same inertias, so M = dE/dq'' holds term by term; that it is also
 * Lagrange's M and that E is Lagrange's residual is what
 * tests/unit/test_forms.c checks.
 */
#include "forms.h"

#include "spatial.h"

#include "../kin.h"

/* a . (n - p x f): the moment of the force F about the pivot p along a */
static ExprId
moment(ExprPool *P, const ExprId *a, const ExprId *p, const Sv *F)
{
    ExprId pf[3], d[3];
    kin_cross(P, p, F->v, pf);
    for (int i = 0; i < 3; i++)
        d[i] = expr_sub(P, F->w[i], pf[i]);
    return kin_dot(P, a, d);
}

ExprId *
rne_residual(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    const Tree *t = m->tree;
    if (!t) {
        *why = m->tree_why;
        return NULL;
    }
    int nf = t->nframes;
    Sv *V = arena_new_array(A, Sv, nf + 1), *Acc = arena_new_array(A, Sv, nf + 1);
    Sv *F = arena_new_array(A, Sv, nf + 1);
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        if (f->parent >= 0) {
            V[g] = V[f->parent], Acc[g] = Acc[f->parent];
        } else {
            sv_zero(&V[g]);
            sv_zero(&Acc[g]);
        }
        for (int k = f->first; k < f->first + f->nturns; k++) {
            int i = t->turn[k].coord;
            Sv S, VS;
            sv_turn_axis(P, f, &t->turn[k], &S);
            sv_cross_motion(P, &V[g], &S, &VS);
            sv_axpy(P, &Acc[g], m->q[1][i], &VS);
            sv_axpy(P, &Acc[g], m->q[2][i], &S);
            sv_axpy(P, &V[g], m->q[1][i], &S);
        }
        Sv IV, IA;
        sv_inertia_times(P, f->m, f->h, f->I, &V[g], &IV);
        sv_inertia_times(P, f->m, f->h, f->I, &Acc[g], &IA);
        sv_cross_force(P, &V[g], &IV, &F[g]);
        sv_add(P, &F[g], &IA);
    }
    for (int g = nf - 1; g >= 0; g--)
        if (t->frame[g].parent >= 0)
            sv_add(P, &F[t->frame[g].parent], &F[g]);
    ExprId *E = form_applied(m, A, P, D);
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        for (int k = f->first; k < f->first + f->nturns; k++) {
            int i = t->turn[k].coord;
            E[i] = expr_add(P, moment(P, t->turn[k].a, f->pivot, &F[g]), E[i]);
        }
    }
    return E;
}

/* M_ij = S_i . Ic(g_j) S_j for turn i at or above turn j; 0 for turns
 * on different branches. */
ExprId *
crb_mass(const Mech *m, Arena *A, ExprPool *P)
{
    const Tree *t = m->tree;
    int n = m->n, nf = t->nframes;
    ExprId *M = arena_new_array(A, ExprId, n * n);
    for (int i = 0; i < n * n; i++)
        M[i] = EXPR_ZERO;
    TreeFrame *Ic = arena_new_array(A, TreeFrame, nf + 1);
    for (int g = 0; g < nf; g++)
        Ic[g] = t->frame[g];
    for (int g = nf - 1; g >= 0; g--) {
        int p = t->frame[g].parent;
        if (p < 0)
            continue;
        Ic[p].m = expr_add(P, Ic[p].m, Ic[g].m);
        for (int i = 0; i < 3; i++)
            Ic[p].h[i] = expr_add(P, Ic[p].h[i], Ic[g].h[i]);
        for (int i = 0; i < 9; i++)
            Ic[p].I[i] = expr_add(P, Ic[p].I[i], Ic[g].I[i]);
    }
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        for (int kj = f->first; kj < f->first + f->nturns; kj++) {
            int j = t->turn[kj].coord;
            Sv S, F;
            sv_turn_axis(P, f, &t->turn[kj], &S);
            sv_inertia_times(P, Ic[g].m, Ic[g].h, Ic[g].I, &S, &F);
            for (int a = g; a >= 0; a = t->frame[a].parent) {
                const TreeFrame *fa = &t->frame[a];
                int last = a == g ? kj : fa->first + fa->nturns - 1;
                for (int ki = fa->first; ki <= last; ki++) {
                    int i = t->turn[ki].coord;
                    M[i * n + j] = M[j * n + i] = moment(P, t->turn[ki].a, fa->pivot, &F);
                }
            }
        }
    }
    return M;
}

const Form form_newton_euler = {
    .name = "newton-euler",
    .formula = "S . sum(I A + V x* I V) over the subtree + dV/dq - Q (recursive)",
    .residual = rne_residual,
    .mass = crb_mass,
};
