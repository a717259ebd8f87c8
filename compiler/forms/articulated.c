/*
 * The articulated-body form, for a tree of rigid bodies on turning joints
 * (tree.h): Featherstone's articulated-body algorithm, unrolled into the
 * DAG so that axes, offsets, inertias and structural zeros fold.
 *
 * Its residual and mass matrix are the recursive Newton-Euler form's (so
 * the Jacobian, the linearization and the constrained solves are the
 * same); what differs is the accelerations, which it never gets by
 * factoring M.  Each turn is a joint of one degree of freedom; the turns
 * of one frame are joints in a row with massless bodies between them.
 * With everything in world components about the world origin no
 * coordinate transforms are needed (Featherstone, Rigid Body Dynamics
 * Algorithms, 2008, sec. 7.3, in absolute coordinates):
 *
 *   outward:  v_i = v_p + S_i q_i',   c_i = (v_p x S_i) q_i'
 *             IA_i = I_i,  pA_i = v_i x* I_i v_i   (I_i: the masses the
 *             turn carries last; 0 for a turn inside a frame)
 *   inward:   U_i = IA_i S_i,  D_i = S_i . U_i,  u_i = tau_i - S_i . pA_i
 *             IA_p += IA_i - U_i U_i^T / D_i
 *             pA_p += pA_i + (IA_i - U_i U_i^T / D_i) c_i + U_i u_i / D_i
 *   outward:  a' = a_p + c_i,  q_i'' = (u_i - U_i . a') / D_i,
 *             a_i = a' + S_i q_i''
 *
 * with tau = Q - dV/dq the generalized forces every form shares (gravity
 * among them, so the world does not accelerate).  Cost and code grow
 * linearly with the number of turns.
 *
 * D_i is the pivot that eliminating the turns below i leaves for i: the
 * LDL^T factorization of M that eliminates leaves first.  So piv = D and
 * mkk = diag M keep the meaning the unrolled solve gives them (eom.h).
 */
#include "forms.h"

#include "spatial.h"

/* A symmetric 6 x 6 spatial inertia, motion to force, as a full array:
 * row r, column c at [6 r + c], rows and columns (w, v). */
typedef struct Si {
    ExprId e[36];
} Si;

static ExprId *
sv_at(Sv *x, int r)
{
    return r < 3 ? &x->w[r] : &x->v[r - 3];
}

static ExprId
sv_get(const Sv *x, int r)
{
    return r < 3 ? x->w[r] : x->v[r - 3];
}

static void
si_zero(Si *X)
{
    for (int i = 0; i < 36; i++)
        X->e[i] = EXPR_ZERO;
}

/* The rigid inertia (m, h, I) as a matrix: [[I, [h]x], [-[h]x, m 1]]. */
static void
si_rigid(ExprPool *P, Si *X, ExprId m, const ExprId *h, const ExprId *I)
{
    si_zero(X);
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++)
            X->e[6 * r + c] = I[3 * r + c];
        X->e[6 * (r + 3) + r + 3] = m;
    }
    /* h x v = [h]x v, [h]x = [[0, -h2, h1], [h2, 0, -h0], [-h1, h0, 0]] */
    ExprId n0 = expr_neg(P, h[0]), n1 = expr_neg(P, h[1]), n2 = expr_neg(P, h[2]);
    ExprId hx[9] = {EXPR_ZERO, n2, h[1], h[2], EXPR_ZERO, n0, n1, h[0], EXPR_ZERO};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            X->e[6 * r + c + 3] = hx[3 * r + c];
            X->e[6 * (c + 3) + r] = hx[3 * r + c]; /* the transpose of -[h]x */
        }
}

static void
si_times(ExprPool *P, const Si *X, const Sv *x, Sv *out)
{
    for (int r = 0; r < 6; r++) {
        ExprId s = EXPR_ZERO;
        for (int c = 0; c < 6; c++)
            s = expr_add(P, s, expr_mul(P, X->e[6 * r + c], sv_get(x, c)));
        *sv_at(out, r) = s;
    }
}

/* Y += X - U W^T, only the upper triangle computed (X is symmetric). */
static void
si_add_update(ExprPool *P, Si *Y, const Si *X, const Sv *U, const Sv *W)
{
    for (int r = 0; r < 6; r++)
        for (int c = r; c < 6; c++) {
            ExprId x = expr_sub(P, X->e[6 * r + c], expr_mul(P, sv_get(U, r), sv_get(W, c)));
            Y->e[6 * r + c] = expr_add(P, Y->e[6 * r + c], x);
            Y->e[6 * c + r] = Y->e[6 * r + c];
        }
}

static void
articulated(const Mech *m, const ExprId *M, Arena *A, ExprPool *P, Diff *D, ExprId *acc,
            ExprId *piv, ExprId *mkk)
{
    const Tree *t = m->tree;
    int nf = t->nframes, nt = t->nturns, n = m->n;
    /* body[g]: the turn that carries frame g's masses, the last turn at or
     * above it (-1: none, the masses do not move) */
    int *body = arena_new_array(A, int, nf + 1);
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        body[g] = f->nturns ? f->first + f->nturns - 1 : f->parent >= 0 ? body[f->parent] : -1;
    }
    /* up[k]: the turn just above turn k, -1 for the world */
    int *up = arena_new_array(A, int, nt + 1);
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        for (int k = f->first; k < f->first + f->nturns; k++)
            up[k] = k > f->first ? k - 1 : f->parent >= 0 ? body[f->parent] : -1;
    }
    Sv *S = arena_new_array(A, Sv, nt + 1), *V = arena_new_array(A, Sv, nt + 1);
    Sv *C = arena_new_array(A, Sv, nt + 1), *pA = arena_new_array(A, Sv, nt + 1);
    Sv *U = arena_new_array(A, Sv, nt + 1), *Acc = arena_new_array(A, Sv, nt + 1);
    Si *IA = arena_new_array(A, Si, nt + 1);
    ExprId *Dinv = arena_new_array(A, ExprId, nt + 1), *u = arena_new_array(A, ExprId, nt + 1);
    ExprId *tau = form_applied(m, A, P, D);
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        for (int k = f->first; k < f->first + f->nturns; k++) {
            int i = t->turn[k].coord;
            sv_turn_axis(P, f, &t->turn[k], &S[k]);
            if (up[k] >= 0) {
                V[k] = V[up[k]];
                sv_cross_motion(P, &V[k], &S[k], &C[k]);
                for (int r = 0; r < 6; r++)
                    *sv_at(&C[k], r) = expr_mul(P, sv_get(&C[k], r), m->q[1][i]);
            } else {
                sv_zero(&V[k]);
                sv_zero(&C[k]);
            }
            sv_axpy(P, &V[k], m->q[1][i], &S[k]);
            si_zero(&IA[k]);
            sv_zero(&pA[k]);
        }
    }
    /* each frame's masses on the turn that carries them, their velocity
     * product force at that turn's velocity */
    for (int g = 0; g < nf; g++) {
        const TreeFrame *f = &t->frame[g];
        int k = body[g];
        if (k < 0)
            continue;
        Si X;
        Sv IV, F;
        si_rigid(P, &X, f->m, f->h, f->I);
        for (int i = 0; i < 36; i++)
            IA[k].e[i] = expr_add(P, IA[k].e[i], X.e[i]);
        sv_inertia_times(P, f->m, f->h, f->I, &V[k], &IV);
        sv_cross_force(P, &V[k], &IV, &F);
        sv_add(P, &pA[k], &F);
    }
    for (int k = nt - 1; k >= 0; k--) {
        int i = t->turn[k].coord;
        si_times(P, &IA[k], &S[k], &U[k]);
        ExprId d = sv_dot(P, &S[k], &U[k]);
        piv[i] = d;
        Dinv[k] = expr_div(P, EXPR_ONE, d);
        ExprId force = expr_neg(P, tau[i]);
        u[k] = expr_sub(P, force, sv_dot(P, &S[k], &pA[k]));
        int p = up[k];
        if (p < 0)
            continue;
        Sv W, Ic, pa;
        for (int r = 0; r < 6; r++)
            *sv_at(&W, r) = expr_mul(P, sv_get(&U[k], r), Dinv[k]);
        Si Ia;
        si_zero(&Ia);
        si_add_update(P, &Ia, &IA[k], &U[k], &W);
        si_times(P, &Ia, &C[k], &Ic);
        pa = pA[k];
        sv_add(P, &pa, &Ic);
        sv_axpy(P, &pa, u[k], &W);
        for (int e = 0; e < 36; e++)
            IA[p].e[e] = expr_add(P, IA[p].e[e], Ia.e[e]);
        sv_add(P, &pA[p], &pa);
    }
    for (int k = 0; k < nt; k++) {
        int i = t->turn[k].coord;
        Sv a = C[k];
        if (up[k] >= 0)
            sv_add(P, &a, &Acc[up[k]]);
        ExprId qdd = expr_mul(P, expr_sub(P, u[k], sv_dot(P, &a, &U[k])), Dinv[k]);
        acc[i] = qdd;
        sv_axpy(P, &a, qdd, &S[k]);
        Acc[k] = a;
    }
    for (int i = 0; i < n; i++)
        mkk[i] = M[i * n + i];
}

const Form form_articulated = {
    .name = "articulated-body",
    .formula = "q'' by Featherstone's articulated-body recursion; E as newton-euler",
    .residual = rne_residual,
    .mass = crb_mass,
    .solve = articulated,
};
