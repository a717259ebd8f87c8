/*
 * spatial: spatial vector algebra on expressions (spatial.h).
 */
#include "spatial.h"
#include "form_util.h"

#include "expr/kin.h"

void
sv_zero(Sv *x)
{
    for (int i = 0; i < 3; i++)
        x->w[i] = x->v[i] = EXPR_ZERO;
}

/* x += s y */
void
sv_axpy(ExprPool *P, Sv *x, ExprId s, const Sv *y)
{
    for (int i = 0; i < 3; i++) {
        x->w[i] = expr_add(P, x->w[i], expr_mul(P, s, y->w[i]));
        x->v[i] = expr_add(P, x->v[i], expr_mul(P, s, y->v[i]));
    }
}

void
sv_add(ExprPool *P, Sv *x, const Sv *y)
{
    for (int i = 0; i < 3; i++) {
        x->w[i] = expr_add(P, x->w[i], y->w[i]);
        x->v[i] = expr_add(P, x->v[i], y->v[i]);
    }
}

/* x cross y for motions: (w x w2, w x v2 + v x w2) */
void
sv_cross_motion(ExprPool *P, const Sv *x, const Sv *y, Sv *out)
{
    ExprId a[3], b[3];
    Sv r;
    kin_cross(P, x->w, y->w, r.w);
    kin_cross(P, x->w, y->v, a);
    kin_cross(P, x->v, y->w, b);
    for (int i = 0; i < 3; i++)
        r.v[i] = expr_add(P, a[i], b[i]);
    *out = r;
}

/* x cross* f for a force f = (n, f): (w x n + v x f, w x f) */
void
sv_cross_force(ExprPool *P, const Sv *x, const Sv *f, Sv *out)
{
    ExprId a[3], b[3];
    Sv r;
    kin_cross(P, x->w, f->w, a);
    kin_cross(P, x->v, f->v, b);
    for (int i = 0; i < 3; i++)
        r.w[i] = expr_add(P, a[i], b[i]);
    kin_cross(P, x->w, f->v, r.v);
    *out = r;
}

/* The spatial inertia (m, h, I) times a motion: (I w + h x v, m v - h x w). */
void
sv_inertia_times(ExprPool *P, ExprId m, const ExprId *h, const ExprId *I, const Sv *x, Sv *out)
{
    ExprId hv[3], hw[3];
    Sv r;
    kin_cross(P, h, x->v, hv);
    kin_cross(P, h, x->w, hw);
    for (int i = 0; i < 3; i++) {
        r.w[i] = expr_add(P, kin_dot(P, &I[3 * i], x->w), hv[i]);
        r.v[i] = expr_sub(P, expr_mul(P, m, x->v[i]), hw[i]);
    }
    *out = r;
}

/* S = (a, p x a) */
ExprId
sv_dot(ExprPool *P, const Sv *x, const Sv *y)
{
    ExprId w = kin_dot(P, x->w, y->w);
    return expr_add(P, w, kin_dot(P, x->v, y->v));
}

void
sv_motion_down(ExprPool *P, const TreeTurn *t, const Sv *x, Sv *out)
{
    ExprId rw[3], v[3];
    kin_cross(P, t->r, x->w, rw);
    for (int i = 0; i < 3; i++)
        v[i] = expr_sub(P, x->v[i], rw[i]);
    for (int i = 0; i < 3; i++) {
        ExprId w = EXPR_ZERO, u = EXPR_ZERO;
        for (int k = 0; k < 3; k++) {
            w = expr_add(P, w, expr_mul(P, t->Q[3 * k + i], x->w[k]));
            u = expr_add(P, u, expr_mul(P, t->Q[3 * k + i], v[k]));
        }
        out->w[i] = w, out->v[i] = u;
    }
}

void
sv_force_up(ExprPool *P, const TreeTurn *t, const Sv *x, Sv *out)
{
    ExprId n[3], f[3], rf[3];
    for (int i = 0; i < 3; i++) {
        n[i] = f[i] = EXPR_ZERO;
        for (int k = 0; k < 3; k++) {
            n[i] = expr_add(P, n[i], expr_mul(P, t->Q[3 * i + k], x->w[k]));
            f[i] = expr_add(P, f[i], expr_mul(P, t->Q[3 * i + k], x->v[k]));
        }
    }
    kin_cross(P, t->r, f, rf);
    for (int i = 0; i < 3; i++)
        out->w[i] = expr_add(P, n[i], rf[i]), out->v[i] = f[i];
}

Rigid *
sv_bodies(ExprPool *P, Arena *A, const Tree *t)
{
    (void)P;
    int nt = t->nturns;
    Rigid *body = arena_new_array(A, Rigid, nt + 1);
    for (int k = 0; k < nt; k++) {
        const TreeTurn *tk = &t->turn[k];
        body[k].m = tk->m;
        for (int i = 0; i < 3; i++)
            body[k].h[i] = tk->h[i];
        for (int i = 0; i < 9; i++)
            body[k].I[i] = tk->I[i];
    }
    return body;
}

void
sv_joint_axis(const TreeTurn *t, Sv *S)
{
    for (int i = 0; i < 3; i++) {
        S->w[i] = t->slide ? EXPR_ZERO : t->al[i];
        S->v[i] = t->slide ? t->al[i] : EXPR_ZERO;
    }
}

int
sv_joint_axes(const TreeTurn *t, Sv S[4])
{
    if (t->ndof == 1) {
        sv_joint_axis(t, &S[0]);
        return 1;
    }
    for (int d = 0; d < t->ndof; d++)
        for (int i = 0; i < 3; i++)
            S[d].w[i] = t->Sw[d][i], S[d].v[i] = EXPR_ZERO;
    return t->ndof;
}

ExprId *
sv_joint_terms(const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    if (m->T_joint == EXPR_ZERO)
        return NULL;
    ExprId *dq = form_gradient(m, m->T_joint, 0, A, D);
    ExprId *dv = form_gradient(m, m->T_joint, 1, A, D);
    for (int i = 0; i < m->n; i++)
        dq[i] = expr_sub(P, diff_time(D, dv[i]), dq[i]);
    return dq;
}

ExprId *
sv_applied(const Mech *m, Arena *A, ExprPool *P, Diff *D, Sv *a0)
{
    int lift = m->gravity[0] != EXPR_NONE;
    ExprId *G = form_gradient(m, lift ? m->V_rest : m->V, 0, A, D);
    for (int i = 0; i < m->n; i++)
        G[i] = expr_sub(P, G[i], m->Q[i]);
    sv_zero(a0);
    for (int i = 0; lift && i < 3; i++)
        a0->v[i] = expr_neg(P, m->gravity[i]);
    return G;
}

void
sv_rigid_up(ExprPool *P, const TreeTurn *t, const Rigid *X, Rigid *Y)
{
    ExprId g[3], J[9];
    for (int i = 0; i < 3; i++) {
        g[i] = EXPR_ZERO;
        for (int k = 0; k < 3; k++)
            g[i] = expr_add(P, g[i], expr_mul(P, t->Q[3 * i + k], X->h[k]));
    }
    for (int i = 0; i < 3; i++) /* J = Q I Q^T */
        for (int j = 0; j <= i; j++) {
            ExprId s = EXPR_ZERO;
            for (int k = 0; k < 3; k++) {
                ExprId row = EXPR_ZERO; /* (Q I)_ik */
                for (int l = 0; l < 3; l++)
                    row = expr_add(P, row, expr_mul(P, t->Q[3 * i + l], X->I[3 * l + k]));
                s = expr_add(P, s, expr_mul(P, row, t->Q[3 * j + k]));
            }
            J[3 * i + j] = J[3 * j + i] = s;
        }
    const ExprId *r = t->r;
    ExprId rg = kin_dot(P, r, g), rr = kin_dot(P, r, r);
    ExprId two = expr_const(P, 2);
    ExprId two_rg = expr_mul(P, two, rg), mrr = expr_mul(P, X->m, rr);
    ExprId diag = expr_add(P, two_rg, mrr);
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
            ExprId mr = expr_mul(P, X->m, r[j]);
            ExprId gr = expr_mul(P, g[i], r[j]), rg2 = expr_mul(P, r[i], g[j]);
            ExprId rmr = expr_mul(P, r[i], mr);
            ExprId off = expr_add(P, expr_add(P, gr, rg2), rmr);
            ExprId e = expr_sub(P, J[3 * i + j], off);
            if (i == j)
                e = expr_add(P, e, diag);
            Y->I[3 * i + j] = expr_add(P, Y->I[3 * i + j], e);
            if (j != i)
                Y->I[3 * j + i] = Y->I[3 * i + j];
        }
    for (int i = 0; i < 3; i++)
        Y->h[i] = expr_add(P, Y->h[i], expr_add(P, g[i], expr_mul(P, X->m, r[i])));
    Y->m = expr_add(P, Y->m, X->m);
}

/* Whether t carries no mass of its own (a body between joints of a row). */
static int
massless(const TreeTurn *t)
{
    int zero = t->m == EXPR_ZERO;
    for (int i = 0; i < 3; i++)
        zero &= t->h[i] == EXPR_ZERO;
    for (int i = 0; i < 9; i++)
        zero &= t->I[i] == EXPR_ZERO;
    return zero;
}

/* Whether turn k is the ball of a free joint, and then its slides, G and
 * G^-1. */
static int
free_joint(const Mech *m, ExprPool *P, Diff *D, const ExprId *Eq, const int *nchild, int k,
           SvFree *f)
{
    const Tree *t = m->tree;
    const TreeTurn *tk = &t->turn[k];
    if (tk->slide || tk->ndof != 3)
        return 0;
    for (int d = 0; d < 3; d++)
        for (int i = 0; i < 3; i++)
            if (tk->Sw[d][i] != (i == d ? EXPR_ONE : EXPR_ZERO))
                return 0;
    int s = tk->up;
    for (int i = 2; i >= 0; i--) {
        if (s < 0 || !t->turn[s].slide || !massless(&t->turn[s]) || nchild[s] != 1)
            return 0;
        f->slide[i] = s;
        s = t->turn[s].up;
    }
    if (s != -1)
        return 0;
    int c[6] = {tk->qc[0], tk->qc[1], tk->qc[2]};
    for (int i = 0; i < 3; i++)
        c[3 + i] = t->turn[f->slide[i]].qc[0];
    for (int i = 0; Eq && i < 6; i++)
        for (int j = 0; j < 6; j++)
            if (diff_partial(D, Eq[c[i]], m->q[2][c[j]]) != EXPR_ZERO)
                return 0;
    /* G's columns: each slide's direction carried into the last's axes */
    ExprId *G = f->G;
    for (int i = 0; i < 3; i++) {
        Sv x, y;
        sv_zero(&x);
        for (int r = 0; r < 3; r++)
            x.v[r] = t->turn[f->slide[i]].al[r];
        for (int j = i + 1; j < 3; j++) {
            sv_motion_down(P, &t->turn[f->slide[j]], &x, &y);
            x = y;
        }
        for (int r = 0; r < 3; r++)
            G[3 * r + i] = x.v[r];
    }
    /* G^-1 = adj(G) / det G, the cofactors taken cyclically; G's entries
     * are numbers, so all of it folds (a free joint's G is 1) */
    ExprId adj[9];
    for (int r = 0; r < 3; r++)
        for (int c2 = 0; c2 < 3; c2++) {
            int r1 = (c2 + 1) % 3, r2 = (c2 + 2) % 3, c1 = (r + 1) % 3, c3 = (r + 2) % 3;
            ExprId x = expr_mul(P, G[3 * r1 + c1], G[3 * r2 + c3]);
            adj[3 * r + c2] = expr_sub(P, x, expr_mul(P, G[3 * r1 + c3], G[3 * r2 + c1]));
        }
    ExprId det = EXPR_ZERO;
    for (int i = 0; i < 3; i++)
        det = expr_add(P, det, expr_mul(P, G[i], adj[3 * i]));
    double dv;
    if (!expr_is_const(P, det, &dv) || dv == 0)
        return 0;
    for (int i = 0; i < 9; i++)
        f->Gi[i] = expr_mul(P, adj[i], expr_const(P, 1 / dv));
    return 1;
}

SvFree **
sv_free_joints(const Mech *m, Arena *A, ExprPool *P, Diff *D, const ExprId *Eq)
{
    const Tree *t = m->tree;
    int nt = t->nturns;
    SvFree **fj = arena_new_array(A, SvFree *, nt + 1);
    int *nchild = arena_new_array(A, int, nt + 1);
    for (int k = 0; k < nt; k++)
        nchild[k] = 0, fj[k] = NULL;
    for (int k = 0; k < nt; k++)
        if (t->turn[k].up >= 0)
            nchild[t->turn[k].up]++;
    for (int k = 0; k < nt; k++) {
        SvFree f;
        if (free_joint(m, P, D, Eq, nchild, k, &f)) {
            fj[k] = arena_alloc(A, sizeof f);
            *fj[k] = f;
        }
    }
    return fj;
}
