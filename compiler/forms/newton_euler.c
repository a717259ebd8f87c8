/*
 * The recursive Newton-Euler form, for a tree of rigid bodies on turning
 * joints (tree.h):
 *     E_i = S_i . F(frame of turn i) + dV/dq_i - Q_i
 * where F_i is the net spatial force the masses turn i moves need,
 *     F_i = sum over the turns below i of  I_k A_k + V_k x* I_k V_k,
 * V and A the turns' spatial velocities and accelerations, built from
 * the world outward (V = X V_up + S th', A = X A_up + S th'' + (X V_up x
 * S) th'), and the sum taken from the leaves inward (F_up += X^T F).
 * Everything is in each turn's own coordinates (tree.h): S = (axis, 0)
 * is a constant there, and X (a rotation by the turn's angle after a
 * constant one, and a constant offset) folds with it.  A uniform gravity
 * field is the world accelerating upward (A_0 = -g), not a gradient.
 *
 * Its mass matrix is not differentiated out of E: it is the composite-
 * rigid-body sum M_ij = S_i . X Ic_j S_j for turn i at or above turn j,
 * Ic_j the inertia of all turn j moves.  That it is dE/dq'', Lagrange's
 * M, and that E is Lagrange's residual is what tests/unit/test_forms.c
 * and test_tree.c check.
 */
#include "forms.h"

#include "spatial.h"

#include "expr/kin.h"

ExprId *
rne_residual(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    const Tree *t = m->tree;
    if (!t) {
        *why = m->tree_why;
        return NULL;
    }
    int nt = t->nturns;
    Rigid *body = sv_bodies(P, A, t);
    Sv *V = arena_new_array(A, Sv, nt + 1), *Acc = arena_new_array(A, Sv, nt + 1);
    Sv *F = arena_new_array(A, Sv, nt + 1), a0;
    ExprId *E = sv_applied(m, A, P, D, &a0), *Eq = sv_joint_terms(m, A, P, D);
    for (int i = 0; Eq && i < m->n; i++)
        E[i] = expr_add(P, E[i], Eq[i]);
    for (int k = 0; k < nt; k++) {
        const TreeTurn *tk = &t->turn[k];
        Sv S[4], VS, IV, IA;
        int nd = sv_joint_axes(tk, S);
        sv_motion_down(P, tk, tk->up >= 0 ? &Acc[tk->up] : &a0, &Acc[k]);
        if (tk->up >= 0) {
            sv_motion_down(P, tk, &V[tk->up], &V[k]);
            for (int d = 0; d < nd; d++) { /* before the joint's own rates */
                sv_cross_motion(P, &V[k], &S[d], &VS);
                sv_axpy(P, &Acc[k], m->q[1][tk->qc[d]], &VS);
            }
        } else {
            sv_zero(&V[k]);
        }
        /* a ball's S' e' = 2 L(e') e' = 0: no term of its own */
        for (int d = 0; d < nd; d++)
            sv_axpy(P, &Acc[k], m->q[2][tk->qc[d]], &S[d]);
        for (int d = 0; d < nd; d++)
            sv_axpy(P, &V[k], m->q[1][tk->qc[d]], &S[d]);
        const Rigid *b = &body[k];
        sv_inertia_times(P, b->m, b->h, b->I, &V[k], &IV);
        sv_inertia_times(P, b->m, b->h, b->I, &Acc[k], &IA);
        sv_cross_force(P, &V[k], &IV, &F[k]);
        sv_add(P, &F[k], &IA);
    }
    for (int k = nt - 1; k >= 0; k--) {
        const TreeTurn *tk = &t->turn[k];
        Sv up, S[4];
        int nd = sv_joint_axes(tk, S);
        for (int d = 0; d < nd; d++) {
            int i = tk->qc[d];
            E[i] = expr_add(P, sv_dot(P, &S[d], &F[k]), E[i]);
        }
        if (tk->up < 0)
            continue;
        sv_force_up(P, tk, &F[k], &up);
        sv_add(P, &F[tk->up], &up);
    }
    return E;
}

/* M_ij = S_i . Ic_j S_j for turn i at or above turn j (Ic_j the
 * composite inertia of all turn j moves, S_j's force carried up the
 * turns to i's coordinates); 0 for turns on different branches. */
ExprId *
crb_mass(const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    const Tree *t = m->tree;
    int n = m->n, nt = t->nturns;
    ExprId *M = arena_new_array(A, ExprId, n * n);
    for (int i = 0; i < n * n; i++)
        M[i] = EXPR_ZERO;
    Rigid *Ic = sv_bodies(P, A, t);
    for (int k = nt - 1; k >= 0; k--)
        if (t->turn[k].up >= 0)
            sv_rigid_up(P, &t->turn[k], &Ic[k], &Ic[t->turn[k].up]);
    for (int kj = 0; kj < nt; kj++) {
        const TreeTurn *tj = &t->turn[kj];
        Sv S[4], Si[4];
        int nj = sv_joint_axes(tj, S);
        for (int dj = 0; dj < nj; dj++) {
            Sv F;
            int j = tj->qc[dj];
            sv_inertia_times(P, Ic[kj].m, Ic[kj].h, Ic[kj].I, &S[dj], &F);
            for (int ki = kj;;) { /* F in turn ki's coordinates */
                int ni = sv_joint_axes(&t->turn[ki], Si);
                for (int di = 0; di < ni; di++) {
                    int i = t->turn[ki].qc[di];
                    if (ki != kj || di >= dj) /* a ball's own block: its lower triangle */
                        M[i * n + j] = M[j * n + i] = sv_dot(P, &Si[di], &F);
                }
                if (t->turn[ki].up < 0)
                    break;
                Sv up;
                sv_force_up(P, &t->turn[ki], &F, &up);
                F = up;
                ki = t->turn[ki].up;
            }
        }
    }
    /* and the inertia of T_joint, in each joint's own block: a rotor's, and
     * e' along e for a ball */
    ExprId *Eq = sv_joint_terms(m, A, P, D);
    for (int k = 0; Eq && k < nt; k++)
        for (int di = 0; di < t->turn[k].ndof; di++)
            for (int dj = 0; dj < t->turn[k].ndof; dj++) {
                int i = t->turn[k].qc[di], j = t->turn[k].qc[dj];
                M[i * n + j] = expr_add(P, M[i * n + j], diff_partial(D, Eq[i], m->q[2][j]));
            }
    return M;
}

const Form form_newton_euler = {
    .name = "newton-euler",
    .formula = "S . sum(I A + V x* I V) over the subtree + dV/dq - Q (recursive)",
    .residual = rne_residual,
    .mass = crb_mass,
    .speeds = 1,
};
