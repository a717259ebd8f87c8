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
 * linearly with the number of turns.  A free joint (three slides and a
 * ball) is one joint of six degrees of freedom (Free, below).
 *
 * D_i is the pivot that eliminating the turns below i leaves for i: the
 * LDL^T factorization of M that eliminates leaves first.  So piv = D and
 * mkk = diag M keep the meaning the unrolled solve gives them (eom.h).
 */
#include "forms.h"

#include "spatial.h"

#include "expr/kin.h"

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

/* The 3 x 3 block of X at (row r0, column c0). */
static void
si_block(const Si *X, int r0, int c0, ExprId *B)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            B[3 * r + c] = X->e[6 * (r0 + r) + c0 + c];
}

/* C = X Y with X or Y transposed as asked, 3 x 3. */
static void
m3_mul(ExprPool *P, const ExprId *X, int xt, const ExprId *Y, int yt, ExprId *C)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            ExprId s = EXPR_ZERO;
            for (int k = 0; k < 3; k++) {
                ExprId x = xt ? X[3 * k + i] : X[3 * i + k];
                ExprId y = yt ? Y[3 * j + k] : Y[3 * k + j];
                s = expr_add(P, s, expr_mul(P, x, y));
            }
            C[3 * i + j] = s;
        }
}

/* Q X Q^T for a 3 x 3 X, symmetric to the bit when X is (sym). */
static void
m3_rotate(ExprPool *P, const ExprId *Q, const ExprId *X, int sym, ExprId *out)
{
    ExprId QX[9];
    m3_mul(P, Q, 0, X, 0, QX);
    m3_mul(P, QX, 0, Q, 1, out);
    for (int i = 0; sym && i < 3; i++)
        for (int j = 0; j < i; j++)
            out[3 * j + i] = out[3 * i + j];
}

/* [r]x, the cross product r x . as a matrix */
static void
m3_cross(ExprPool *P, const ExprId *r, ExprId *Rx)
{
    Rx[0] = Rx[4] = Rx[8] = EXPR_ZERO;
    Rx[1] = expr_neg(P, r[2]), Rx[2] = r[1];
    Rx[3] = r[2], Rx[5] = expr_neg(P, r[0]);
    Rx[6] = expr_neg(P, r[1]), Rx[7] = r[0];
}

/* Y += X^T Ia X, Ia in turn t's coordinates, Y in up's: the blocks
 * [[A, B], [B^T, C]] turned, A = Q A Q^T ..., then moved by r:
 *   C' = C,  B' = B + [r]x C,  A' = A + [r]x B^T - B' [r]x. */
static void
inertia_up(ExprPool *P, const TreeTurn *t, const Si *Ia, Si *Y)
{
    ExprId a[9], b[9], c[9], A[9], B[9], C[9], Rx[9], T[9], U[9];
    si_block(Ia, 0, 0, a);
    si_block(Ia, 0, 3, b);
    si_block(Ia, 3, 3, c);
    m3_rotate(P, t->Q, a, 1, A);
    m3_rotate(P, t->Q, b, 0, B);
    m3_rotate(P, t->Q, c, 1, C);
    m3_cross(P, t->r, Rx);
    m3_mul(P, Rx, 0, B, 1, T); /* [r]x B^T */
    m3_mul(P, Rx, 0, C, 0, U);
    for (int i = 0; i < 9; i++)
        B[i] = expr_add(P, B[i], U[i]);
    m3_mul(P, B, 0, Rx, 0, U); /* B' [r]x */
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
            ExprId e = expr_add(P, A[3 * i + j], T[3 * i + j]);
            A[3 * i + j] = A[3 * j + i] = expr_sub(P, e, U[3 * i + j]);
        }
    for (int r = 0; r < 3; r++)
        for (int c2 = 0; c2 < 3; c2++) {
            ExprId *y = &Y->e[6 * r + c2];
            *y = expr_add(P, *y, A[3 * r + c2]);
            y = &Y->e[6 * r + c2 + 3];
            *y = expr_add(P, *y, B[3 * r + c2]);
            y = &Y->e[6 * (c2 + 3) + r];
            *y = expr_add(P, *y, B[3 * r + c2]);
            y = &Y->e[6 * (r + 3) + c2 + 3];
            *y = expr_add(P, *y, C[3 * r + c2]);
        }
}

/* j when a is the coordinate axis e_j, else -1 */
static int
axis_index(const ExprId *a)
{
    for (int j = 0; j < 3; j++)
        if (a[j] == EXPR_ONE && a[(j + 1) % 3] == EXPR_ZERO && a[(j + 2) % 3] == EXPR_ZERO)
            return j;
    return -1;
}

/* A joint's part of the recursion: its axes, U = IA S, the joint-space
 * inertia D = S^T IA S (plus what T_joint adds) as L diag(d) L^T (L unit
 * lower, only for a ball's 4 x 4), and u = tau - S . pA. */
typedef struct Jt {
    int nd;
    Sv S[4], U[4];
    ExprId u[4], L[16], dinv[4];
} Jt;

/* x = X^-1 b for X = L diag(d) L^T of nd rows (L unit lower, row i at
 * L[stride i]; dinv = 1/d): a joint's D, or a free joint's IA */
static void
ldl_solve(ExprPool *P, int nd, int stride, const ExprId *L, const ExprId *dinv,
          const ExprId *b, ExprId *x)
{
    ExprId y[6];
    for (int i = 0; i < nd; i++) {
        y[i] = b[i];
        for (int k = 0; k < i; k++)
            y[i] = expr_sub(P, y[i], expr_mul(P, L[stride * i + k], y[k]));
    }
    for (int i = nd - 1; i >= 0; i--) {
        x[i] = expr_mul(P, y[i], dinv[i]);
        for (int k = i + 1; k < nd; k++)
            x[i] = expr_sub(P, x[i], expr_mul(P, L[stride * k + i], x[k]));
    }
}

/* x = D^-1 b by the joint's L diag(d) L^T (nd = 1: b / d) */
static void
jt_solve(ExprPool *P, const Jt *j, const ExprId *b, ExprId *x)
{
    ldl_solve(P, j->nd, 4, j->L, j->dinv, b, x);
}

/* X = L diag(d) L^T for a symmetric 6 x 6 X (L unit lower, at [6 i + j]),
 * eliminating rows 0, 1, ... in turn; LD[i j] = L[i j] d[j] saves a
 * product per term. */
static void
si_ldl(ExprPool *P, const Si *X, ExprId *L, ExprId *d, ExprId *dinv)
{
    ExprId LD[36];
    for (int j = 0; j < 6; j++) {
        ExprId x = X->e[7 * j];
        for (int k = 0; k < j; k++)
            x = expr_sub(P, x, expr_mul(P, LD[6 * j + k], L[6 * j + k]));
        d[j] = x;
        dinv[j] = expr_div(P, EXPR_ONE, x);
        for (int i = j + 1; i < 6; i++) {
            ExprId y = X->e[6 * i + j];
            for (int k = 0; k < j; k++)
                y = expr_sub(P, y, expr_mul(P, LD[6 * i + k], L[6 * j + k]));
            LD[6 * i + j] = y;
            L[6 * i + j] = expr_mul(P, y, dinv[j]);
        }
    }
}

/* x = X^-1 b by si_ldl's factors */
static void
si_ldl_solve(ExprPool *P, const ExprId *L, const ExprId *dinv, const Sv *b, Sv *x)
{
    ExprId bb[6], xx[6];
    for (int i = 0; i < 3; i++)
        bb[i] = b->w[i], bb[3 + i] = b->v[i];
    ldl_solve(P, 6, 6, L, dinv, bb, xx);
    for (int i = 0; i < 3; i++)
        x->w[i] = xx[i], x->v[i] = xx[3 + i];
}

/* A free joint (spatial.h's SvFree) in the recursion, one joint of six
 * degrees of freedom as the articulated-body libraries run a floating
 * base.  Its axes in the ball's coordinates, S = [[0, 1], [Q^T G, 0]], are
 * invertible, so D q'' = u - U^T a' (D = S^T IA S, u = tau - S^T pA,
 * U = IA S) is
 *     IA a = S^-T tau - pA,   q'' = S^-1 (a - a'),
 * a the body's acceleration: one 6 x 6 solve of the articulated inertia
 * in place of three slides' and a ball's eliminations, and of the
 * transforms of IA through the massless bodies between them.  Its pivots
 * are IA's, balanced by IA's own diagonal (mkk): how nearly singular D is
 * shows in IA as well, S being invertible.  Not with a rotor's inertia on
 * these coordinates, which IA misses. */
typedef struct Free {
    const SvFree *j;
    ExprId L[36], dinv[6]; /* IA = L diag(d) L^T */
} Free;


/* A free joint's q'' (its ball turn k) from a' (the parent's acceleration
 * carried down, with c): IA a = S^-T tau - pA, q'' = S^-1 (a - a'), with
 * S^-T tau = (tau_w, Q^T G^-T tau_v) and S^-1 r = (r_w, G^-1 Q r_v);
 * *out = a. */
static void
free_accel(ExprPool *P, const Tree *t, int k, const Free *f, const ExprId *tau, const Sv *pA,
           const Sv *ap, ExprId *acc, Sv *out)
{
    const TreeTurn *tk = &t->turn[k];
    const ExprId *Q = tk->Q, *Gi = f->j->Gi;
    int cv[3];
    for (int i = 0; i < 3; i++)
        cv[i] = t->turn[f->j->slide[i]].qc[0];
    ExprId y[3];
    Sv b, a;
    for (int i = 0; i < 3; i++) {
        y[i] = EXPR_ZERO;
        for (int j = 0; j < 3; j++)
            y[i] = expr_add(P, y[i], expr_mul(P, Gi[3 * j + i], tau[cv[j]]));
    }
    for (int i = 0; i < 3; i++) {
        ExprId x = EXPR_ZERO;
        for (int j = 0; j < 3; j++)
            x = expr_add(P, x, expr_mul(P, Q[3 * j + i], y[j]));
        b.w[i] = expr_sub(P, tau[tk->qc[i]], pA->w[i]);
        b.v[i] = expr_sub(P, x, pA->v[i]);
    }
    si_ldl_solve(P, f->L, f->dinv, &b, &a);
    ExprId r[3], z[3];
    for (int i = 0; i < 3; i++) {
        acc[tk->qc[i]] = expr_sub(P, a.w[i], ap->w[i]);
        r[i] = expr_sub(P, a.v[i], ap->v[i]);
    }
    for (int i = 0; i < 3; i++) {
        z[i] = EXPR_ZERO;
        for (int j = 0; j < 3; j++)
            z[i] = expr_add(P, z[i], expr_mul(P, Q[3 * i + j], r[j]));
    }
    for (int i = 0; i < 3; i++) {
        ExprId x = EXPR_ZERO;
        for (int j = 0; j < 3; j++)
            x = expr_add(P, x, expr_mul(P, Gi[3 * i + j], z[j]));
        acc[cv[i]] = x;
    }
    *out = a;
}

static void
articulated(const Mech *m, Arena *A, ExprPool *P, Diff *D, const ExprId *load, ExprId *acc,
            ExprId *piv, ExprId *mkk)
{
    const Tree *t = m->tree;
    int nt = t->nturns, n = m->n;
    Rigid *body = sv_bodies(P, A, t), *comp = arena_new_array(A, Rigid, nt + 1);
    Sv *V = arena_new_array(A, Sv, nt + 1);
    Sv *C = arena_new_array(A, Sv, nt + 1), *pA = arena_new_array(A, Sv, nt + 1);
    Sv *Acc = arena_new_array(A, Sv, nt + 1);
    Si *IA = arena_new_array(A, Si, nt + 1);
    Jt *J = arena_new_array(A, Jt, nt + 1);
    /* gravity as the world's acceleration upward (Featherstone's a_0 =
     * -g), where it is uniform: its potential's gradient is not needed */
    Sv a0;
    const ExprId *tau = load; /* a load: at rest, the world still */
    /* T_joint (mech.h) is no mass's: its M (in each joint's own block)
     * joins D, and the rest of its terms tau */
    ExprId *Eq = sv_joint_terms(m, A, P, D), *hq = NULL;
    if (Eq) {
        ExprId *zeros = arena_new_array(A, ExprId, n);
        hq = arena_new_array(A, ExprId, n);
        for (int i = 0; i < n; i++)
            zeros[i] = EXPR_ZERO;
        expr_subst_many(P, n, Eq, n, m->q[2], zeros, hq);
    }
    if (load) {
        sv_zero(&a0);
    } else {
        ExprId *applied = sv_applied(m, A, P, D, &a0);
        for (int i = 0; i < n; i++)
            applied[i] = expr_neg(P, applied[i]);
        for (int i = 0; hq && i < n; i++)
            applied[i] = expr_sub(P, applied[i], hq[i]);
        tau = applied;
    }
    /* free joints: fr[k] for the ball, its slides skipped */
    SvFree **fj = sv_free_joints(m, A, P, D, Eq);
    Free **fr = arena_new_array(A, Free *, nt + 1);
    int *skip = arena_new_array(A, int, nt + 1);
    for (int k = 0; k < nt; k++)
        skip[k] = 0, fr[k] = NULL;
    for (int k = 0; k < nt; k++)
        if (fj[k]) {
            fr[k] = arena_alloc(A, sizeof *fr[k]);
            fr[k]->j = fj[k];
            for (int i = 0; i < 3; i++)
                skip[fj[k]->slide[i]] = 1;
        }
    for (int k = 0; k < nt; k++) {
        const TreeTurn *tk = &t->turn[k];
        Jt *jk = &J[k];
        jk->nd = sv_joint_axes(tk, jk->S);
        sv_zero(&C[k]);
        if (tk->up >= 0) {
            Sv vp;
            sv_motion_down(P, tk, &V[tk->up], &vp);
            for (int d = 0; d < jk->nd; d++) {
                ExprId rate = load ? EXPR_ZERO : m->q[1][tk->qc[d]];
                Sv x;
                sv_cross_motion(P, &vp, &jk->S[d], &x);
                for (int r = 0; r < 6; r++)
                    *sv_at(&x, r) = expr_mul(P, sv_get(&x, r), rate);
                if (d == 0)
                    C[k] = x;
                else
                    sv_add(P, &C[k], &x);
            }
            V[k] = vp;
        } else {
            sv_zero(&V[k]);
        }
        /* a ball's S' e' = 2 L(e') e' = 0: no term of its own */
        for (int d = 0; d < jk->nd; d++)
            sv_axpy(P, &V[k], load ? EXPR_ZERO : m->q[1][tk->qc[d]], &jk->S[d]);
        const Rigid *b = &body[k];
        Sv IV;
        si_rigid(P, &IA[k], b->m, b->h, b->I);
        sv_inertia_times(P, b->m, b->h, b->I, &V[k], &IV);
        sv_cross_force(P, &V[k], &IV, &pA[k]);
        comp[k] = *b;
    }
    for (int k = nt - 1; k >= 0; k--) {
        const TreeTurn *tk = &t->turn[k];
        Jt *jk = &J[k];
        int nd = jk->nd, p = tk->up;
        if (skip[k])
            continue;
        if (fr[k]) {
            Free *f = fr[k];
            ExprId d[6];
            si_ldl(P, &IA[k], f->L, d, f->dinv);
            for (int i = 0; i < 6; i++) {
                int c = i < 3 ? tk->qc[i] : t->turn[f->j->slide[i - 3]].qc[0];
                piv[c] = d[i], mkk[c] = IA[k].e[7 * i];
            }
            continue;
        }
        /* M_ii = S^T Ic S, Ic the composite inertia of all the joint moves */
        for (int d = 0; d < nd; d++) {
            Sv IcS;
            int i = tk->qc[d];
            sv_inertia_times(P, comp[k].m, comp[k].h, comp[k].I, &jk->S[d], &IcS);
            mkk[i] = sv_dot(P, &jk->S[d], &IcS);
            if (Eq)
                mkk[i] = expr_add(P, mkk[i], diff_partial(D, Eq[i], m->q[2][i]));
        }
        if (p >= 0)
            sv_rigid_up(P, tk, &comp[k], &comp[p]);
        for (int d = 0; d < nd; d++)
            si_times(P, &IA[k], &jk->S[d], &jk->U[d]);
        /* D = L diag(d) L^T, its pivots those of coordinates qc[0], qc[1], ... */
        int rotor = 0; /* T_joint adds inertia to D beyond S^T IA S */
        for (int i = 0; i < nd; i++)
            for (int j = 0; j <= i; j++) {
                ExprId x = sv_dot(P, &jk->S[i], &jk->U[j]);
                ExprId xq = Eq ? diff_partial(D, Eq[tk->qc[i]], m->q[2][tk->qc[j]]) : EXPR_ZERO;
                x = expr_add(P, x, xq);
                rotor |= xq != EXPR_ZERO;
                for (int l = 0; l < j; l++) {
                    ExprId ll = expr_mul(P, jk->L[4 * i + l], jk->L[4 * j + l]);
                    x = expr_sub(P, x, expr_mul(P, ll, piv[tk->qc[l]]));
                }
                if (i == j) {
                    piv[tk->qc[i]] = x;
                    jk->dinv[i] = expr_div(P, EXPR_ONE, x);
                } else {
                    jk->L[4 * i + j] = expr_mul(P, x, jk->dinv[j]);
                }
            }
        for (int d = 0; d < nd; d++)
            jk->u[d] = expr_sub(P, tau[tk->qc[d]], sv_dot(P, &jk->S[d], &pA[k]));
        if (p < 0)
            continue;
        /* W = U D^-1, row by row */
        Sv W[4], Ic, pa, up;
        for (int r = 0; r < 6; r++) {
            ExprId ur[4], wr[4];
            for (int d = 0; d < nd; d++)
                ur[d] = sv_get(&jk->U[d], r);
            if (nd == 1)
                wr[0] = expr_mul(P, ur[0], jk->dinv[0]);
            else
                jt_solve(P, jk, ur, wr);
            for (int d = 0; d < nd; d++)
                *sv_at(&W[d], r) = wr[d];
        }
        Si Ia;
        si_zero(&Ia);
        si_add_update(P, &Ia, &IA[k], &jk->U[0], &W[0]);
        for (int d = 1; d < nd; d++) {
            Si zero;
            si_zero(&zero);
            si_add_update(P, &Ia, &zero, &jk->U[d], &W[d]);
        }
        /* Ia S = U - U (S.U) / D = 0: about a coordinate axis that is a
         * row and a column of exact zeros, which the rounding of the
         * update would only blur, and which fold through the transforms.
         * Not with a rotor's inertia in D: then Ia S = U arm / D. */
        int j = nd == 1 && !rotor ? axis_index(tk->al) : -1; /* S's row among (w, v) */
        j += j >= 0 && tk->slide ? 3 : 0;
        for (int c = 0; j >= 0 && c < 6; c++)
            Ia.e[6 * j + c] = Ia.e[6 * c + j] = EXPR_ZERO;
        si_times(P, &Ia, &C[k], &Ic);
        pa = pA[k];
        sv_add(P, &pa, &Ic);
        for (int d = 0; d < nd; d++)
            sv_axpy(P, &pa, jk->u[d], &W[d]);
        inertia_up(P, tk, &Ia, &IA[p]);
        sv_force_up(P, tk, &pa, &up);
        sv_add(P, &pA[p], &up);
    }
    for (int k = 0; k < nt; k++) {
        const TreeTurn *tk = &t->turn[k];
        const Jt *jk = &J[k];
        Sv a;
        sv_motion_down(P, tk, tk->up >= 0 ? &Acc[tk->up] : &a0, &a);
        sv_add(P, &a, &C[k]);
        if (skip[k]) { /* a free joint's slide: its q'' comes with the ball's */
            Acc[k] = a;
            continue;
        }
        if (fr[k]) {
            free_accel(P, t, k, fr[k], tau, &pA[k], &a, acc, &Acc[k]);
            continue;
        }
        ExprId b[4], qdd[4];
        for (int d = 0; d < jk->nd; d++)
            b[d] = expr_sub(P, jk->u[d], sv_dot(P, &a, &jk->U[d]));
        if (jk->nd == 1)
            qdd[0] = expr_mul(P, b[0], jk->dinv[0]);
        else
            jt_solve(P, jk, b, qdd);
        for (int d = 0; d < jk->nd; d++) {
            acc[tk->qc[d]] = qdd[d];
            sv_axpy(P, &a, qdd[d], &jk->S[d]);
        }
        Acc[k] = a;
    }
}

const Form form_articulated = {
    .name = "articulated-body",
    .formula = "q'' by Featherstone's articulated-body recursion; E as newton-euler",
    .residual = rne_residual,
    .mass = crb_mass,
    .solve = articulated,
    .speeds = 1,
};

FormTables *
form_tables(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why)
{
    const Tree *t = m->tree;
    if (!t) {
        *why = m->tree_why;
        return NULL;
    }
    if (m->speeds) { /* the tables index q and v alike */
        *why = "the tables have no ball joints (turns by a quaternion)";
        return NULL;
    }
    int nt = t->nturns;
    for (int k = 0; k < nt; k++)
        if (t->turn[k].ndof > 1) {
            *why = "the tables have no ball joints (turns by a quaternion)";
            return NULL;
        } else if (!t->turn[k].slide && t->turn[k].angle != m->q[0][t->turn[k].coord]) {
            *why = "a turn's angle is not its coordinate itself";
            return NULL;
        }
    if (m->T_joint != EXPR_ZERO) { /* the balls' own terms are refused above */
        *why = "the tables have no kinetic-energy terms of the spec's own (a rotor's inertia)";
        return NULL;
    }
    FormTables *tb = arena_alloc(A, sizeof *tb);
    tb->nt = nt;
    tb->turn = arena_new_array(A, int, FORM_TABLE_INTS * nt + 1);
    tb->num = arena_new_array(A, ExprId, FORM_TABLE_STRIDE * nt + 6);
    Rigid *body = sv_bodies(P, A, t);
    for (int k = 0; k < nt; k++) {
        const TreeTurn *tk = &t->turn[k];
        int ax = axis_index(tk->al), fixed = 0;
        for (int i = 0; i < 9; i++)
            fixed |= tk->Qf[i] != (i % 4 == 0 ? EXPR_ONE : EXPR_ZERO);
        int *ti = tb->turn + FORM_TABLE_INTS * k;
        /* a slide: its vector in the numbers (axis 3); its offset at q = 0 */
        ti[0] = tk->up, ti[1] = tk->coord, ti[2] = ax < 0 || tk->slide ? 3 : ax, ti[3] = fixed;
        ti[4] = tk->slide;
        ExprId *x = tb->num + FORM_TABLE_STRIDE * k, r0[3];
        const Rigid *b = &body[k];
        ExprId zero = EXPR_ZERO;
        if (tk->slide)
            expr_subst_many(P, 3, tk->r, 1, &m->q[0][tk->coord], &zero, r0);
        for (int i = 0; i < 9; i++)
            x[i] = tk->Qf[i];
        for (int i = 0; i < 3; i++)
            x[9 + i] = tk->slide ? r0[i] : tk->r[i], x[12 + i] = tk->al[i], x[16 + i] = b->h[i];
        x[15] = b->m;
        x[19] = b->I[0], x[20] = b->I[4], x[21] = b->I[8];
        x[22] = b->I[1], x[23] = b->I[2], x[24] = b->I[5];
    }
    Sv a0;
    tb->tau = sv_applied(m, A, P, D, &a0);
    for (int i = 0; i < m->n; i++)
        tb->tau[i] = expr_neg(P, tb->tau[i]);
    for (int i = 0; i < 3; i++)
        tb->num[FORM_TABLE_STRIDE * nt + i] = a0.w[i],
        tb->num[FORM_TABLE_STRIDE * nt + 3 + i] = a0.v[i];
    return tb;
}
