/*
 * stick.h: dry friction's modes and its stuck coordinates (eomc_model.h's
 * fric_ members), written once for two number types: double in the runs
 * (friction.c) and eomc_ext in the reference solution (reffric.c), so
 * that both decide alike where a coordinate sticks and where it slips.
 *
 * The includer defines STICK_REAL (the number type), STICK_EPS (its
 * rounding unit), STICK_MODEL (whose mass_bias, fric_bound and fric_rows
 * take it: eomc_model or eomc_model_ext), STICK_(name) (the names'
 * prefix) and STICK_API (the functions' linkage), then includes this
 * file.  Modes are the model's, u[nu + k].
 *
 * While items are stuck, their speeds' accelerations are 0 and the others
 * come from the rows of the free speeds F: M_FF a_F = -h_F (M_FF is M's
 * block, positive definite as M is, factored by LDL^T here).  The force
 * that holds stuck speed s is then phi_s = (M a + h)_s: E's residual
 * there, the generalized force the stuck coordinate must be given (h has
 * no friction of its own: a stuck item puts none).  It holds while
 * |phi_s| <= F_s: the stick switch's function is F_s - |phi_s|.  Let go,
 * it slips the way the rest drives it, -phi_s, against a friction of F_s.
 *
 * An item of a contact (fric_speed -1) acts along a row J_j of the
 * speeds (its speed J_j v, whose rate is J_j a + b_j: fric_rows).  While
 * the stuck rows R hold, M_FF a_F + h_F = J_RF^T phi_R and J_RF a_F +
 * b_R = 0.  Rows may be redundant (a box's four corners on a floor: eight
 * rows of rank 3): the accelerations are unique but phi is not.  With
 * phi = W psi (W = diag F), the accelerations come from the least-norm
 * psi of G psi = c, G = W J M_FF^-1 J^T W (symmetric, semidefinite),
 * solved by G's eigenvectors, the rank decided relative to its largest
 * eigenvalue (STICK_RANK_ULPS); the stick switches and the flips read the
 * psi whose largest |psi_j| is least (spread), so that a point reaches
 * its bound only where the group cannot hold (rows alike: all at once).  An item whose bound is 0 (its point not touching)
 * has a zero column there: it holds nothing, and it does not stick.
 *
 * Which rows stick where several are at speed 0 at once (a slip
 * crossing joins stuck ones, or one lets go and leaves the rest) is
 * Coulomb's choice, made for all of them together: the box problem
 * (box), whose answer is the modes' only consistent one.  Where a group
 * reaches its limit as its load grows, the choice at that instant is on
 * its edge (every share within its bound, the rates 0) and is made a
 * little ahead along the motion (ahead).  Coordinates held still are let
 * go one at a time, the one needing most first.
 */
#include <math.h>
#include <stdlib.h>

#ifndef STICK_STATUS_DEFINED /* (friction.h declares them for its callers) */
enum { STICK_OK, STICK_PIVOT, STICK_NEGATIVE, STICK_START, STICK_SPANNED };
#endif

typedef struct STICK_(Work) {
    const eomc_model *m;      /* the tables */
    const STICK_MODEL *x;     /* the functions in STICK_REAL */
    int nv, nu, nf;           /* speeds, inputs, items */
    STICK_REAL *M, *h, *L;    /* [nv nv], [nv], [nv nv]: M_FF factored */
    STICK_REAL *F, *phi;      /* [nf] bounds, holding forces (0 where slipping) */
    STICK_REAL *acc;          /* [nv] q'' of the solves settle, flip and
                               * refresh make */
    int *free_of;             /* [nv] the free speeds, nfree of them */
    int nfree;
    unsigned char *held;      /* [nv] the stuck speeds */
    int bad;                  /* STICK_PIVOT's speed, _NEGATIVE's and _START's item */
    STICK_REAL pivot;         /* the last factorization's least pivot / M_kk */
    /* the contacts' rows (nrowitem > 0: fric_rows) */
    int nrowitem;             /* items with a row of their own */
    STICK_REAL *J, *b;        /* [nf nv], [nf]: rows and biases at the last build */
    int *R, nR;               /* [nf] the stuck rows of the last build */
    STICK_REAL *X;            /* [nf nv] column r: M_FF^-1 J_r^T F_r (held speeds 0) */
    STICK_REAL *G, *V, *lam;  /* [nf nf] G, its eigenvectors (columns), [nf] values */
    STICK_REAL top;           /* G's largest eigenvalue */
    int rank;                 /* G's */
    STICK_REAL *c, *psi, *vec;/* [nf], [nf], [nv] scratch */
    unsigned char *live;      /* [nmode] keep_slip's: a slip switch an item slips by */
    STICK_REAL *lp;           /* [nf nf] spread's null space */
    int *lpb;                 /* [2 nf] lexi's simplex basis */
    STICK_REAL ahead;         /* unstick_rows' look ahead (a time; 0: none) */
    STICK_REAL *qa, *va;      /* [nq], [nv] the state there */
    STICK_REAL *lx;           /* [STICK_LEXI_SCRATCH(nf)] lexi's scratch */
    int *lxi;                 /* [nf] lexi's rows left */
} STICK_(Work);

/* An eigenvalue of G counts where it is above STICK_RANK_ULPS rounding
 * units of the largest (times G's order): rows that are combinations of
 * others give eigenvalues of G's rounding, which is that size. */
#define STICK_RANK_ULPS 1024
/* A stuck item's holding force is at its bound where it is within
 * STICK_BOUND_ULPS rounding units (times the items' count) of it: the
 * least-norm solve's rounding. */
#define STICK_BOUND_ULPS 1024
/* The box problem's active set changes at most this many times per row
 * (each pass fixes a row at a bound or frees one; cycling, possible only
 * where rows are degenerate, ends there with the psi reached).  cheb's
 * simplex method (under lexi's passes) pivots at most this many times
 * per row and column of its tableau, for the same reason: Bland's rule
 * cannot cycle, but rounding can make it wander where rows are alike. */
#define STICK_BOX_PASSES 8
/* unstick_rows looks this share of the run's span ahead where the choice
 * of who slips sits on its edge: short of other events (a step is seldom
 * that short), long enough that the rates it brings (that share of the
 * span over the motion's own time) stand far above the box's rounding
 * (STICK_BOUND_ULPS rounding units).  The same in the run and the
 * reference, which decide alike. */
#define STICK_AHEAD_REL 1e-8

/* lexi's scratch for n rows: cheb's tableau, four n x n, three n */
#define STICK_LEXI_SCRATCH(n) \
    ((size_t)(2 * (n) + 1) * (4 * (n) + 3) + 4 * (size_t)(n) * (n) + 3 * (size_t)(n))

#define STICK_ABS(r) ((r) < 0 ? -(r) : (r))

STICK_API void
STICK_(free)(STICK_(Work) *w)
{
    if (!w)
        return;
    free(w->M), free(w->L), free(w->h), free(w->acc), free(w->F), free(w->phi);
    free(w->free_of), free(w->held);
    free(w->J), free(w->b), free(w->R), free(w->X), free(w->G), free(w->V), free(w->lam);
    free(w->c), free(w->psi), free(w->vec), free(w->live), free(w->lp), free(w->lpb);
    free(w->qa), free(w->va);
    free(w->lx), free(w->lxi);
    free(w);
}

STICK_API STICK_(Work) *
STICK_(alloc)(const eomc_model *m, const STICK_MODEL *x)
{
    STICK_(Work) *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    int nv = eomc_nv(m), nf = m->nfric;
    *w = (STICK_(Work)){.m = m, .x = x, .nv = nv, .nu = m->nu, .nf = nf};
    size_t n = (size_t)nv;
    w->M = calloc(n * n + 1, sizeof *w->M);
    w->L = calloc(n * n + 1, sizeof *w->L);
    w->h = calloc(n + 1, sizeof *w->h);
    w->acc = calloc(n + 1, sizeof *w->acc);
    w->F = calloc((size_t)nf + 1, sizeof *w->F);
    w->phi = calloc((size_t)nf + 1, sizeof *w->phi);
    w->free_of = calloc(n + 1, sizeof *w->free_of);
    w->held = calloc(n + 1, 1);
    for (int j = 0; j < nf; j++)
        w->nrowitem += m->fric_speed[j] < 0;
    size_t f = (size_t)(w->nrowitem ? nf : 0);
    w->J = calloc(f * n + 1, sizeof *w->J);
    w->b = calloc(f + 1, sizeof *w->b);
    w->R = calloc(f + 1, sizeof *w->R);
    w->X = calloc(f * n + 1, sizeof *w->X);
    w->G = calloc(f * f + 1, sizeof *w->G);
    w->V = calloc(f * f + 1, sizeof *w->V);
    w->lam = calloc(f + 1, sizeof *w->lam);
    w->c = calloc(f + 1, sizeof *w->c);
    w->psi = calloc(f + 1, sizeof *w->psi);
    w->vec = calloc(n + 1, sizeof *w->vec);
    w->live = calloc((size_t)m->nmode + 1, 1);
    w->lp = calloc(f * f + 1, sizeof *w->lp);
    w->lpb = calloc(2 * f + 1, sizeof *w->lpb);
    w->qa = calloc((size_t)m->nq + 1, sizeof *w->qa);
    w->va = calloc(n + 1, sizeof *w->va);
    w->lx = calloc(STICK_LEXI_SCRATCH(f) + 1, sizeof *w->lx);
    w->lxi = calloc(f + 1, sizeof *w->lxi);
    if (!w->M || !w->L || !w->h || !w->acc || !w->F || !w->phi || !w->free_of || !w->held ||
        !w->J || !w->b || !w->R || !w->X || !w->G || !w->V || !w->lam || !w->c || !w->psi ||
        !w->vec || !w->live || !w->lp || !w->lpb || !w->qa || !w->va || !w->lx ||
        !w->lxi ||
        (w->nrowitem && !x->fric_rows)) {
        STICK_(free)(w);
        return NULL;
    }
    return w;
}

/* The run's span (t_end - t0), for unstick_rows' look ahead. */
STICK_API void
STICK_(span)(STICK_(Work) *w, STICK_REAL span)
{
    w->ahead = STICK_AHEAD_REL * span;
}

static int
STICK_(stuck)(const STICK_(Work) *w, const STICK_REAL *u, int j)
{
    return u[w->nu + w->m->fric_stick[j]] != 0;
}

STICK_API int
STICK_(any)(const STICK_(Work) *w, const STICK_REAL *u)
{
    for (int j = 0; j < w->nf; j++)
        if (STICK_(stuck)(w, u, j))
            return 1;
    return 0;
}

/* The item whose switch of the list modes (fric_stick, fric_slip) is
 * mode k, or -1. */
static int
STICK_(item_of)(const STICK_(Work) *w, const int *modes, int k)
{
    for (int j = 0; j < w->nf; j++)
        if (modes[j] == k)
            return j;
    return -1;
}

/* The item whose stick switch is mode k, or -1. */
STICK_API int
STICK_(item_stick)(const STICK_(Work) *w, int k)
{
    return STICK_(item_of)(w, w->m->fric_stick, k);
}

static int STICK_(is_row)(const STICK_(Work) *w, int j);

/* The bounds F at (t, q, v); STICK_NEGATIVE (bad: the item) where one
 * is not a number, or a coordinate's is below 0.  A contact's bound,
 * mu N, is below 0 only where its push's switch has not yet flipped off:
 * at a trial stage past that switch's crossing (the step is then cut at
 * the crossing) or at the crossing itself, by the rounding of where it
 * was located.  There it is the continuation of the mode's function, as
 * every other term of a step past a crossing is; once the switch flips,
 * N is 0. */
STICK_API int
STICK_(bounds)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
               const STICK_REAL *p, const STICK_REAL *u)
{
    w->x->fric_bound(t, q, v, p, u, w->F);
    for (int j = 0; j < w->nf; j++)
        if (!(w->F[j] >= 0) && (w->F[j] != w->F[j] || !STICK_(is_row)(w, j))) {
            w->bad = j;
            return STICK_NEGATIVE;
        }
    return STICK_OK;
}

/* M_FF = L D L^T in place in w->L (the nfree x nfree block, no pivoting:
 * positive definite), D on the diagonal; 0, or the block's row k + 1
 * whose pivot is d_k <= EOMC_PIVOT_TOL M_kk. */
static int
STICK_(factor)(STICK_(Work) *w)
{
    int n = w->nfree, nv = w->nv;
    STICK_REAL *L = w->L;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            L[i * n + j] = w->M[w->free_of[i] * nv + w->free_of[j]];
    w->pivot = 1;
    for (int k = 0; k < n; k++) {
        STICK_REAL mkk = L[k * n + k], d = mkk;
        for (int j = 0; j < k; j++)
            d -= L[k * n + j] * L[k * n + j] * L[j * n + j];
        if (!(d > EOMC_PIVOT_TOL * mkk))
            return k + 1;
        if (d / mkk < w->pivot)
            w->pivot = d / mkk;
        L[k * n + k] = d;
        for (int i = k + 1; i < n; i++) {
            STICK_REAL s = L[i * n + k];
            for (int j = 0; j < k; j++)
                s -= L[i * n + j] * L[k * n + j] * L[j * n + j];
            L[i * n + k] = s / d;
        }
    }
    return 0;
}

/* b = -M^-1 b with the stuck coordinates' speeds held: b_F = -M_FF^-1
 * b_F, b_S = 0, M_FF as the last build factored it (no rows). */
static void
STICK_(block_neg)(const STICK_(Work) *w, STICK_REAL *b)
{
    int n = w->nfree;
    const STICK_REAL *L = w->L;
    /* gather b_F at the front, in place (free_of ascends) */
    for (int i = 0; i < n; i++)
        b[i] = b[w->free_of[i]];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < i; j++)
            b[i] -= L[i * n + j] * b[j];
    for (int i = 0; i < n; i++)
        b[i] /= L[i * n + i];
    for (int i = n - 1; i >= 0; i--)
        for (int j = i + 1; j < n; j++)
            b[i] -= L[j * n + i] * b[j];
    /* scatter back, the last first (free_of[i] >= i), the held ones 0 */
    for (int i = w->nv - 1, k = n - 1; i >= 0; i--)
        b[i] = k >= 0 && w->free_of[k] == i ? -b[k--] : 0;
}

static int
STICK_(is_row)(const STICK_(Work) *w, int j)
{
    return w->m->fric_speed[j] < 0;
}

/* Symmetric A (n x n, destroyed) diagonalized by cyclic Jacobi
 * rotations: its eigenvalues into lam, its eigenvectors into V's
 * columns. */
static void
STICK_(jacobi)(STICK_REAL *A, STICK_REAL *V, STICK_REAL *lam, int n)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            V[i * n + j] = i == j;
    STICK_REAL all = 0;
    for (int i = 0; i < n * n; i++)
        all += A[i] * A[i];
    /* a sweep at least halves the off-diagonal part's digits: 64 are plenty */
    for (int sweep = 0; sweep < 64; sweep++) {
        STICK_REAL off = 0;
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++)
                off += 2 * A[i * n + j] * A[i * n + j];
        if (!(off > STICK_EPS * STICK_EPS * all))
            break;
        for (int p = 0; p < n; p++)
            for (int q = p + 1; q < n; q++) {
                STICK_REAL apq = A[p * n + q];
                if (apq == 0)
                    continue;
                STICK_REAL theta = (A[q * n + q] - A[p * n + p]) / (2 * apq), t;
                if (STICK_ABS(theta) > 1 / STICK_EPS) /* t = 1/(2 theta) to rounding */
                    t = 1 / (2 * theta);
                else
                    t = (theta >= 0 ? 1 : -1) /
                        (STICK_ABS(theta) + (STICK_REAL)sqrtl((long double)(theta * theta + 1)));
                STICK_REAL co = (STICK_REAL)(1 / sqrtl((long double)(t * t + 1))), si = t * co;
                for (int k = 0; k < n; k++) { /* A = A Rot */
                    STICK_REAL akp = A[k * n + p], akq = A[k * n + q];
                    A[k * n + p] = co * akp - si * akq;
                    A[k * n + q] = si * akp + co * akq;
                }
                for (int k = 0; k < n; k++) { /* A = Rot^T A */
                    STICK_REAL apk = A[p * n + k], aqk = A[q * n + k];
                    A[p * n + k] = co * apk - si * aqk;
                    A[q * n + k] = si * apk + co * aqk;
                }
                for (int k = 0; k < n; k++) {
                    STICK_REAL vkp = V[k * n + p], vkq = V[k * n + q];
                    V[k * n + p] = co * vkp - si * vkq;
                    V[k * n + q] = si * vkp + co * vkq;
                }
            }
    }
    for (int i = 0; i < n; i++)
        lam[i] = A[i * n + i];
}

/* Whether an eigenvalue counts: above STICK_RANK_ULPS rounding units,
 * times the order n, of top (the largest). */
static int
STICK_(counts)(STICK_REAL lam, STICK_REAL top, int n)
{
    return lam > STICK_RANK_ULPS * n * STICK_EPS * top;
}

/* G's eigenvalues and eigenvectors (G, n x n, is destroyed), then its
 * rank. */
static void
STICK_(eigen)(STICK_(Work) *w, int n)
{
    STICK_(jacobi)(w->G, w->V, w->lam, n);
    w->top = 0;
    for (int i = 0; i < n; i++)
        if (w->lam[i] > w->top)
            w->top = w->lam[i];
    w->rank = 0;
    for (int i = 0; i < n; i++)
        w->rank += STICK_(counts)(w->lam[i], w->top, n);
}

/* How much of the direction of eigenvalue lam the solve takes: none
 * where it does not count, all of it from twice that threshold, and
 * between them a smooth step.  Rows that part as the motion goes (a box's
 * two corners on one edge as it starts to turn: one row at psi = 0) have
 * an eigenvalue that rises from rounding, and the forces that hold them
 * rise as its inverse: taken all at once where it first counts, they
 * jumped there, from a share within the bounds to 1e4 times them, a
 * crossing that no root finder brackets well (the run stopped, its side
 * step past the jump failing).  Where they let go is still set by the
 * threshold, not by the motion (which cannot hold them once they part):
 * the run warns of it (fric_condition). */
static STICK_REAL
STICK_(weight)(STICK_REAL lam, STICK_REAL top, int n)
{
    STICK_REAL edge = STICK_RANK_ULPS * n * STICK_EPS * top;
    if (!(lam > edge))
        return 0;
    if (lam >= 2 * edge)
        return 1;
    STICK_REAL x = lam / edge - 1;
    return x * x * (3 - 2 * x);
}

/* psi = G^+ c: along the eigenvectors that count, 0 along the others
 * (the least-norm solution), eased in where they first count (weight). */
static void
STICK_(pseudo)(const STICK_(Work) *w, const STICK_REAL *c, STICK_REAL *psi)
{
    int n = w->nR;
    for (int r = 0; r < n; r++)
        psi[r] = 0;
    for (int i = 0; i < n; i++) {
        if (!STICK_(counts)(w->lam[i], w->top, n))
            continue;
        STICK_REAL y = 0;
        for (int r = 0; r < n; r++)
            y += w->V[r * n + i] * c[r];
        y *= STICK_(weight)(w->lam[i], w->top, n) / w->lam[i];
        for (int r = 0; r < n; r++)
            psi[r] += w->V[r * n + i] * y;
    }
}

/* y += sum_r X_r psi_r over the stuck rows. */
static void
STICK_(add_rows)(const STICK_(Work) *w, const STICK_REAL *psi, STICK_REAL *y)
{
    for (int r = 0; r < w->nR; r++)
        for (int i = 0; i < w->nv; i++)
            y[i] += w->X[r * w->nv + i] * psi[r];
}

/* c_r = -F_r (J_r y + b_r), b counted where with_b. */
static void
STICK_(residual)(const STICK_(Work) *w, const STICK_REAL *y, int with_b, STICK_REAL *c)
{
    int nv = w->nv;
    for (int r = 0; r < w->nR; r++) {
        int j = w->R[r];
        STICK_REAL e = with_b ? w->b[j] : 0;
        for (int i = 0; i < nv; i++)
            e += w->J[j * nv + i] * y[i];
        c[r] = -w->F[j] * e;
    }
}

/* b = -M^-1 b with the stuck speeds held and the stuck rows' forces
 * keeping J_R M^-1 b's part at 0, as the last build set them up (the
 * Jacobian's solves). */
STICK_API void
STICK_(solve_neg)(const STICK_(Work) *w, STICK_REAL *b)
{
    STICK_(block_neg)(w, b);
    if (!w->nR)
        return;
    STICK_REAL *c = w->c, *psi = w->psi;
    for (int i = 0; i < w->nv; i++) /* M^-1 b */
        b[i] = -b[i];
    STICK_(residual)(w, b, 0, c);
    STICK_(pseudo)(w, c, psi);
    STICK_(add_rows)(w, psi, b);
    for (int i = 0; i < w->nv; i++)
        b[i] = -b[i];
}

/* G = W J_R M_FF^-1 J_R^T W [nR nR] from the last build's X. */
static void
STICK_(gram)(const STICK_(Work) *w, STICK_REAL *G)
{
    int n = w->nR, nv = w->nv;
    for (int r = 0; r < n; r++)
        for (int s = 0; s <= r; s++) {
            STICK_REAL g = 0;
            for (int i = 0; i < nv; i++)
                g += w->J[w->R[r] * nv + i] * w->X[s * nv + i];
            G[r * n + s] = G[s * n + r] = w->F[w->R[r]] * g;
        }
}

/* Everything a solve at (t, q, v) in the modes u needs but h: the
 * bounds, M and h, the held speeds, M_FF factored, and the stuck rows'
 * X and G with G's eigenvectors.  STICK_OK, STICK_PIVOT or
 * STICK_NEGATIVE. */
static int
STICK_(build)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
              const STICK_REAL *p, const STICK_REAL *u)
{
    const eomc_model *m = w->m;
    int nv = w->nv;
    int rc = STICK_(bounds)(w, t, q, v, p, u);
    if (rc != STICK_OK)
        return rc;
    w->x->mass_bias(t, q, v, p, u, w->M, w->h);
    for (int i = 0; i < nv; i++)
        w->held[i] = 0;
    w->nR = 0;
    for (int j = 0; j < w->nf; j++)
        if (!STICK_(stuck)(w, u, j))
            continue;
        else if (STICK_(is_row)(w, j))
            w->R[w->nR++] = j;
        else
            w->held[m->fric_speed[j]] = 1;
    w->nfree = 0;
    for (int i = 0; i < nv; i++)
        if (!w->held[i])
            w->free_of[w->nfree++] = i;
    int k = STICK_(factor)(w);
    if (k) {
        w->bad = w->free_of[k - 1];
        return STICK_PIVOT;
    }
    if (w->nrowitem)
        w->x->fric_rows(t, q, v, p, u, w->J, w->b);
    int n = w->nR;
    for (int r = 0; r < n; r++) { /* X_r = M_FF^-1 J_r^T F_r, the held speeds' 0 */
        int j = w->R[r];
        STICK_REAL *x = &w->X[r * nv];
        for (int i = 0; i < nv; i++)
            x[i] = w->held[i] ? 0 : w->J[j * nv + i];
        STICK_(block_neg)(w, x);
        for (int i = 0; i < nv; i++)
            x[i] *= -w->F[j];
    }
    STICK_(gram)(w, w->G);
    if (n)
        STICK_(eigen)(w, n);
    return STICK_OK;
}

/* The held coordinates' holding forces phi, (M a + h)_s less what the
 * stuck rows' phi put there, at q'' a of the last build. */
static void
STICK_(holding)(STICK_(Work) *w, const STICK_REAL *a)
{
    const eomc_model *m = w->m;
    int nv = w->nv;
    for (int j = 0; j < w->nf; j++) {
        if (STICK_(is_row)(w, j) || !w->held[m->fric_speed[j]])
            continue;
        int s = m->fric_speed[j];
        STICK_REAL r = w->h[s];
        for (int i = 0; i < nv; i++)
            r += w->M[s * nv + i] * a[i];
        for (int k = 0; k < w->nR; k++) /* (what the rows hold is theirs) */
            r -= w->J[w->R[k] * nv + s] * w->phi[w->R[k]];
        w->phi[j] = r;
    }
}

/* q'' from the last build at its state: M_FF a_F = -h_F, plus the stuck
 * rows' forces; the holding forces phi. */
static void
STICK_(accel)(STICK_(Work) *w, STICK_REAL *a)
{
    int nv = w->nv;
    for (int i = 0; i < nv; i++)
        a[i] = w->h[i];
    STICK_(block_neg)(w, a);
    for (int j = 0; j < w->nf; j++)
        w->phi[j] = 0;
    if (w->nR) {
        STICK_(residual)(w, a, 1, w->c);
        STICK_(pseudo)(w, w->c, w->psi);
        STICK_(add_rows)(w, w->psi, a);
        for (int r = 0; r < w->nR; r++)
            w->phi[w->R[r]] = w->F[w->R[r]] * w->psi[r];
    }
    STICK_(holding)(w, a);
}

/* q'' at (t, q, v) in the modes u, the stuck items' speeds held at 0
 * (none stuck: M a = -h): a [nv], and each stuck item's holding force
 * and every bound (w->phi, w->F).  STICK_OK, STICK_PIVOT (bad: the speed
 * whose pivot failed) or STICK_NEGATIVE. */
STICK_API int
STICK_(solve)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
              const STICK_REAL *p, const STICK_REAL *u, STICK_REAL *a)
{
    int rc = STICK_(build)(w, t, q, v, p, u);
    if (rc != STICK_OK)
        return rc;
    STICK_(accel)(w, a);
    return STICK_OK;
}

/* The least largest share: min over z of max_r |a_r + (N z)_r| (n rows,
 * N [n d] with orthonormal columns), by the simplex method on a tableau
 * T [(2 n + 1) (2 d + 2 n + 3)] with Bland's rule (no cycling), from z =
 * 0 and the largest |a_r| (a vertex of the problem shifted by it: every
 * slack in the basis).  The shares are of their bounds, numbers near 1,
 * so the pivots' test is in rounding units.  z out; the least largest. */
static STICK_REAL
STICK_(cheb)(const STICK_REAL *a, const STICK_REAL *N, int n, int d, STICK_REAL *z,
             STICK_REAL *T, int *basis)
{
    int rows = 2 * n, cols = 2 * d + 2 + 2 * n, W = cols + 1, tp = 2 * d, tm = 2 * d + 1;
    STICK_REAL top = 0, tol = STICK_BOUND_ULPS * rows * STICK_EPS;
    for (int r = 0; r < n; r++)
        if (STICK_ABS(a[r]) > top)
            top = STICK_ABS(a[r]);
    for (int i = 0; i < (rows + 1) * W; i++)
        T[i] = 0;
    /* a_r + N_r z <= top + T and -(a_r + N_r z) <= top + T, T = T+ - T- */
    for (int r = 0; r < n; r++)
        for (int side = 0; side < 2; side++) {
            int i = side * n + r;
            STICK_REAL sg = side ? -1 : 1, *row = T + (size_t)i * W;
            for (int k = 0; k < d; k++)
                row[k] = sg * N[r * d + k], row[d + k] = -sg * N[r * d + k];
            row[tp] = -1, row[tm] = 1, row[tm + 1 + i] = 1;
            row[cols] = top - sg * a[r];
            basis[i] = tm + 1 + i;
        }
    STICK_REAL *obj = T + (size_t)rows * W; /* min T+ - T- */
    obj[tp] = 1, obj[tm] = -1;
    for (int it = 0; it < STICK_BOX_PASSES * (rows + cols); it++) {
        int in = -1, out = -1;
        for (int j = 0; j < cols && in < 0; j++)
            if (obj[j] < -tol)
                in = j;
        if (in < 0)
            break;
        STICK_REAL best = 0;
        for (int i = 0; i < rows; i++) {
            STICK_REAL e = T[(size_t)i * W + in];
            if (!(e > tol))
                continue;
            STICK_REAL ratio = T[(size_t)i * W + cols] / e;
            if (out < 0 || ratio < best || (ratio == best && basis[i] < basis[out]))
                best = ratio, out = i;
        }
        if (out < 0)
            break; /* (unbounded: cannot be, the shares bound T from below) */
        STICK_REAL *pr = T + (size_t)out * W, pv = pr[in];
        for (int j = 0; j < W; j++)
            pr[j] /= pv;
        for (int i = 0; i <= rows; i++) {
            STICK_REAL *ri = T + (size_t)i * W, f = ri[in];
            if (i == out || f == 0)
                continue;
            for (int j = 0; j < W; j++)
                ri[j] -= f * pr[j];
        }
        basis[out] = in;
    }
    STICK_REAL val[2] = {0, 0}; /* T+, T- */
    for (int k = 0; k < d; k++)
        z[k] = 0;
    for (int i = 0; i < rows; i++) {
        int b = basis[i];
        STICK_REAL x = T[(size_t)i * W + cols];
        if (b < d)
            z[b] += x;
        else if (b < 2 * d)
            z[b - d] -= x;
        else if (b == tp || b == tm)
            val[b - tp] = x;
    }
    return top + val[0] - val[1];
}

/* The shares whose largest is least, then the largest of the rest least,
 * and so on (the lexicographic least: the nucleolus of game theory, here
 * of the 2 n shares +-psi_r, linear in z, so it is unique): psi [n] in,
 * a share of each row (a + N z for some z), out.  N [n d], orthonormal
 * columns, is destroyed.  The least largest alone leaves the shares below
 * it free within a set, and which of them a simplex method returns turns
 * on N's basis, which is G's null space's: its eigenvalues are all 0 to
 * rounding, so an eigensolver picks its vectors by rounding, and a stick
 * switch's function read there would jump from one state to the next.
 * Each pass solves cheb for the rows not yet fixed and fixes those every
 * least largest has at it (a dual above rounding: the reduced cost of
 * their slack), then goes on in the directions that leave them be (the
 * null space of their N rows, which keeps N's columns orthonormal on the
 * rows left): at most n passes.  Scratch s: STICK_LEXI_SCRATCH(n) reals,
 * live: n ints, basis: 2 n ints. */
static void
STICK_(lexi)(STICK_REAL *psi, STICK_REAL *N, int n, int d, STICK_REAL *s, int *live, int *basis)
{
    STICK_REAL *T = s, *NN = T + (size_t)(2 * n + 1) * (4 * n + 3), *M2 = NN + (size_t)n * n,
               *EV = M2 + (size_t)n * n, *NK = EV + (size_t)n * n, *aa = NK + (size_t)n * n,
               *ev = aa + n, *z = ev + n;
    int m = n;
    for (int r = 0; r < n; r++)
        live[r] = r;
    while (m > 0 && d > 0) {
        for (int i = 0; i < m; i++) {
            aa[i] = psi[live[i]];
            for (int k = 0; k < d; k++)
                NN[i * d + k] = N[live[i] * d + k];
        }
        STICK_(cheb)(aa, NN, m, d, z, T, basis);
        for (int i = 0; i < m; i++)
            for (int k = 0; k < d; k++)
                psi[live[i]] += NN[i * d + k] * z[k];
        /* cheb's tableau: row 2 m the reduced costs, constraint i's slack
         * in column 2 d + 2 + i (rows r, then -r) */
        int W = 2 * d + 2 * m + 3, fixed = 0, kept = 0;
        const STICK_REAL *obj = T + (size_t)2 * m * W;
        STICK_REAL tol = STICK_BOUND_ULPS * 2 * m * STICK_EPS;
        for (int k = 0; k < d * d; k++)
            M2[k] = 0;
        for (int i = 0; i < m; i++) {
            int r = live[i];
            if (!(obj[2 * d + 2 + i] > tol || obj[2 * d + 2 + m + i] > tol)) {
                live[kept++] = r;
                continue;
            }
            fixed++;
            for (int a = 0; a < d; a++)
                for (int b = 0; b < d; b++)
                    M2[a * d + b] += N[r * d + a] * N[r * d + b];
        }
        if (!fixed) /* (cannot be: the largest has a dual; rounding) */
            break;
        m = kept;
        /* a direction moves the fixed rows where N_B^T N_B's eigenvalue
         * along it is above rounding of N's own scale, 1 (its columns are
         * unit vectors), not of that matrix's largest: a row that no
         * direction moves but for rounding (N_r of 1e-17) must not take
         * the directions from the rest */
        STICK_(jacobi)(M2, EV, ev, d);
        int d2 = 0;
        for (int k = 0; k < d; k++)
            d2 += !STICK_(counts)(ev[k], 1, d);
        /* (only the rows left are read from here on) */
        for (int i = 0; i < m; i++)
            for (int k = 0, c = 0, r = live[i]; k < d; k++) {
                if (STICK_(counts)(ev[k], 1, d))
                    continue;
                STICK_REAL e = 0;
                for (int a = 0; a < d; a++)
                    e += N[r * d + a] * EV[a * d + k];
                NK[r * d2 + c++] = e;
            }
        d = d2;
        for (int i = 0; i < m; i++)
            for (int k = 0; k < d; k++)
                N[live[i] * d + k] = NK[live[i] * d + k];
    }
}

/* Where the stuck rows are redundant (G's rank below their count: a
 * foot's ends, a leg's points), the holding forces are not unique, and
 * least-norm shares (accel's) can put one point at its bound while the
 * others could take more: letting it go is no choice of Coulomb's (its
 * row is held still by theirs), and holding it a force beyond its
 * bound.  The shares the stick switches read (and the choices at a flip)
 * are then the ones whose largest is least: a point reaches its bound
 * only where no sharing keeps all of them within theirs, the group
 * cannot hold, and the points that reach it are those that must give
 * (cheb, in the null space of G, from accel's least-norm psi).  q'' is
 * the same whatever the shares. */
static void
STICK_(spread)(STICK_(Work) *w, const STICK_REAL *a)
{
    int n = w->nR, d = n - w->rank;
    if (n == 0 || d <= 0)
        return;
    STICK_REAL *N = w->lp;
    for (int i = 0, k = 0; i < n; i++) {
        if (STICK_(counts)(w->lam[i], w->top, n))
            continue;
        for (int r = 0; r < n; r++)
            N[r * d + k] = w->V[r * n + i];
        k++;
    }
    STICK_(lexi)(w->psi, N, n, d, w->lx, w->lxi, w->lpb);
    for (int r = 0; r < n; r++)
        w->phi[w->R[r]] = w->F[w->R[r]] * w->psi[r];
    STICK_(holding)(w, a);
}

/* solve, the shares spread (the stick switches' and the flips'). */
static int
STICK_(solve_shared)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
                     const STICK_REAL *p, const STICK_REAL *u, STICK_REAL *a)
{
    int rc = STICK_(solve)(w, t, q, v, p, u, a);
    if (rc == STICK_OK)
        STICK_(spread)(w, a);
    return rc;
}

/* The slip switch of a stuck row item keeps its side: its speed is 0 to
 * rounding there, whose sign says nothing (a coordinate's is exactly 0).
 * So does a row item's whose bound is 0 (w->F: its point apart, or its
 * pair's push ended), unless an item slipping with a bound shares the
 * switch (the same speed: a box's upper and lower corners where it does
 * not turn): it exerts nothing either way, and its speed, 0 to rounding
 * where the rest holds the point still (a stuck box's upper corners),
 * would flip it back and forth on the rounding; it takes its speed's
 * sign when its pair touches (flip). */
static void
STICK_(keep_slip)(const STICK_(Work) *w, const STICK_REAL *u, STICK_REAL *sw)
{
    const int *slip = w->m->fric_slip;
    for (int j = 0; j < w->nf; j++)
        w->live[slip[j]] = 0;
    for (int j = 0; j < w->nf; j++)
        w->live[slip[j]] |= !STICK_(stuck)(w, u, j) && w->F[j] > 0;
    for (int j = 0; j < w->nf; j++)
        if (STICK_(is_row)(w, j) &&
            (STICK_(stuck)(w, u, j) || (!(w->F[j] > 0) && !w->live[slip[j]])))
            sw[slip[j]] = u[w->nu + slip[j]] != 0 ? 1 : -1;
}

/* The stick switches' functions at (t, q, v) in the modes u into sw
 * [nmode]: F - |phi| where stuck, else -1 (it cannot stick by this
 * switch: slipping, its slip switch's crossing decides).  A solve's
 * failure is returned, the functions then NAN. */
STICK_API int
STICK_(functions)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
                  const STICK_REAL *p, const STICK_REAL *u, STICK_REAL *sw)
{
    int rc = STICK_(any)(w, u)  ? STICK_(solve_shared)(w, t, q, v, p, u, w->acc)
             : w->nrowitem      ? STICK_(bounds)(w, t, q, v, p, u) /* (keep_slip's) */
                                : STICK_OK;
    if (rc != STICK_OK) {
        for (int j = 0; j < w->nf; j++)
            sw[w->m->fric_stick[j]] = NAN;
        return rc;
    }
    for (int j = 0; j < w->nf; j++)
        sw[w->m->fric_stick[j]] = STICK_(stuck)(w, u, j)
                                      ? w->F[j] - STICK_ABS(w->phi[j]) : -1;
    STICK_(keep_slip)(w, u, sw);
    return STICK_OK;
}

static void
STICK_(set)(const STICK_(Work) *w, STICK_REAL *u, int mode, int on)
{
    u[w->nu + mode] = on ? 1 : 0;
}

/* Item j's speed J_j v, and its rate J_j a + b_j (a row's), at the last
 * build. */
static STICK_REAL
STICK_(speed)(const STICK_(Work) *w, int j, const STICK_REAL *v, const STICK_REAL *a)
{
    if (!STICK_(is_row)(w, j))
        return a ? a[w->m->fric_speed[j]] : v[w->m->fric_speed[j]];
    STICK_REAL e = a ? w->b[j] : 0;
    for (int i = 0; i < w->nv; i++)
        e += w->J[j * w->nv + i] * (a ? a[i] : v[i]);
    return e;
}

/* Item j's speed's sign at the last build: +1, -1, or 0 where it is 0
 * but for rounding (of its terms |J_ji v_i|, STICK_BOUND_ULPS of them:
 * a foot's new point, whose row its stuck points span, moves at 0 but
 * for rounding).  Such a 0 has no sign: its sign here and a switch
 * function's, two roundings of one 0, may differ, and the run's doubles
 * and the reference's long doubles would choose apart.  A coordinate's
 * speed is a component of the state, 0 only where it is set so. */
static int
STICK_(sign)(const STICK_(Work) *w, int j, const STICK_REAL *v)
{
    STICK_REAL e = 0, terms = 0;
    if (!STICK_(is_row)(w, j))
        e = v[w->m->fric_speed[j]];
    else /* (speed's sum, its terms' sizes beside it) */
        for (int i = 0; i < w->nv; i++) {
            e += w->J[j * w->nv + i] * v[i];
            terms += STICK_ABS(w->J[j * w->nv + i] * v[i]);
        }
    if (STICK_ABS(e) <= STICK_BOUND_ULPS * w->nv * STICK_EPS * terms)
        return 0;
    return e > 0 ? 1 : -1;
}

/* After a solve: the stuck item that needs most beyond its bound (|phi|
 * / F the largest, compared without dividing by a bound of 0; beyond by
 * more than the solve's rounding, STICK_BOUND_ULPS: one at its bound
 * holds, as the stick switch's function at 0 says) let go,
 * slipping the way the rest drives it; the item, or -1 where every stuck
 * one holds. */
static int
STICK_(release_worst)(STICK_(Work) *w, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    int worst = -1;
    for (int j = 0; j < w->nf; j++) {
        STICK_REAL need = STICK_ABS(w->phi[j]);
        if (STICK_(stuck)(w, u, j) &&
            need - w->F[j] > STICK_BOUND_ULPS * w->nf * STICK_EPS * w->F[j] &&
            (worst < 0 || need * w->F[worst] > STICK_ABS(w->phi[worst]) * w->F[j]))
            worst = j;
    }
    if (worst >= 0) {
        STICK_(set)(w, u, m->fric_slip[worst], w->phi[worst] < 0);
        STICK_(set)(w, u, m->fric_stick[worst], 0);
    }
    return worst;
}

/* The stuck rows' shares psi (phi = F psi) where holding all of them
 * asks more than their bounds give: the psi in the box |psi_r| <= 1
 * minimizing psi^T G psi / 2 - c^T psi (G, c as accel's: G psi - c is
 * the rows' rates of speed, times F).  Its conditions are Coulomb's at
 * a speed of 0: a row inside the box has rate 0 (it holds), one at +1
 * has rate <= 0 (its force pushes up as it slides down), one at -1 rate
 * >= 0.  G is semidefinite (M is definite), so the problem is convex and
 * has a solution, with the rates unique, for any rows and bounds: the
 * choice of who slips is not a guess (as letting go of the one needing
 * most for its bound is, which can let go of one that the rest then
 * drive back).  A primal active set (Nocedal and Wright's 16.3) from
 * psi = 0: on the face where the rows at[r] != 0 sit at their bounds,
 * the least-norm step to the face's least (G's pseudo-inverse on the
 * free rows), or down a direction of no curvature to the box's edge,
 * stopping at the first bound in the way; at the face's least, the row
 * at a bound with its rate the wrong way leaves it.  g gets the rates;
 * returns the size of a rate of rounding (g's terms').  Scratch s:
 * 2 n^2 + 3 n reals, fr: n ints. */
static STICK_REAL
STICK_(box)(const STICK_REAL *G, const STICK_REAL *c, int n, STICK_REAL *psi,
            signed char *at, STICK_REAL *g, STICK_REAL *s, int *fr)
{
    STICK_REAL *A = s, *V = A + (size_t)n * n, *lam = V + (size_t)n * n, *d = lam + n,
               *rhs = d + n;
    STICK_REAL top = 0, scale = 0;
    for (int r = 0; r < n; r++) {
        STICK_REAL row = STICK_ABS(c[r]);
        for (int k = 0; k < n; k++)
            row += STICK_ABS(G[r * n + k]);
        if (row > scale)
            scale = row;
        if (G[r * n + r] > top)
            top = G[r * n + r];
        psi[r] = 0, at[r] = 0;
    }
    /* rates of rounding: their terms' size, as the bounds' test takes */
    STICK_REAL tol = STICK_BOUND_ULPS * n * STICK_EPS * scale;
    for (int it = 0; it < STICK_BOX_PASSES * (n + 1); it++) {
        for (int r = 0; r < n; r++) {
            g[r] = -c[r];
            for (int k = 0; k < n; k++)
                g[r] += G[r * n + k] * psi[k];
        }
        int f = 0;
        for (int r = 0; r < n; r++)
            if (!at[r])
                fr[f++] = r;
        for (int a = 0; a < f; a++) {
            for (int b = 0; b < f; b++)
                A[a * f + b] = G[fr[a] * n + fr[b]];
            rhs[a] = -g[fr[a]];
        }
        STICK_(jacobi)(A, V, lam, f);
        for (int a = 0; a < f; a++)
            d[a] = 0;
        for (int k = 0; k < f; k++) { /* the step along the directions that count */
            if (!STICK_(counts)(lam[k], top, n))
                continue;
            STICK_REAL y = 0;
            for (int a = 0; a < f; a++)
                y += V[a * f + k] * rhs[a];
            for (int a = 0; a < f; a++) {
                d[a] += V[a * f + k] * (y / lam[k]);
                rhs[a] -= V[a * f + k] * y;
            }
        }
        int flat = 0; /* what is left of -g: along directions of no curvature */
        for (int a = 0; a < f; a++)
            flat |= STICK_ABS(rhs[a]) > tol;
        if (flat)
            for (int a = 0; a < f; a++)
                d[a] = rhs[a];
        STICK_REAL most = 0;
        for (int a = 0; a < f; a++)
            if (STICK_ABS(d[a]) > most)
                most = STICK_ABS(d[a]);
        if (!flat && most <= STICK_BOUND_ULPS * n * STICK_EPS) {
            /* the face's least: the row at a bound pulled off it most */
            int off = -1;
            STICK_REAL worst = tol;
            for (int r = 0; r < n; r++)
                if (at[r] && at[r] * -g[r] < -worst)
                    worst = at[r] * g[r], off = r;
            if (off < 0)
                return tol;
            at[off] = 0;
            continue;
        }
        STICK_REAL step = 1;
        int stop = -1;
        for (int a = 0; a < f; a++) { /* (a flat direction goes on to an edge) */
            if (d[a] == 0)
                continue;
            STICK_REAL edge = d[a] > 0 ? 1 : -1, to = (edge - psi[fr[a]]) / d[a];
            if ((flat && stop < 0) || to < step)
                step = to, stop = a;
        }
        for (int a = 0; a < f; a++)
            psi[fr[a]] += step * d[a];
        if (stop >= 0) {
            at[fr[stop]] = d[stop] > 0 ? 1 : -1;
            psi[fr[stop]] = at[fr[stop]];
        }
    }
    for (int r = 0; r < n; r++) { /* (the passes ran out: the rates of where it got) */
        g[r] = -c[r];
        for (int k = 0; k < n; k++)
            g[r] += G[r * n + k] * psi[k];
    }
    return tol;
}

/* The stuck rows of the modes u at (t, q, v) decided together (box):
 * each at its bound whose rate takes it off 0 lets go, slipping that
 * way (gone[j] = 1 where gone); the others stay stuck. */
static int
STICK_(decide_rows)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
                    const STICK_REAL *p, STICK_REAL *u, unsigned char *gone)
{
    const eomc_model *m = w->m;
    int rc = STICK_(build)(w, t, q, v, p, u), n = w->nR;
    if (rc != STICK_OK || !n)
        return rc;
    size_t nn = (size_t)n * n;
    STICK_REAL *G = malloc((3 * nn + 5 * (size_t)n) * sizeof *G);
    int *fr = malloc((size_t)n * sizeof *fr);
    signed char *at = malloc((size_t)n);
    if (!G || !fr || !at) {
        free(G), free(fr), free(at);
        w->bad = w->R[0];
        return STICK_PIVOT;
    }
    STICK_REAL *psi = G + nn, *g = psi + n, *s = g + n;
    STICK_(gram)(w, G);
    STICK_REAL *y = w->vec; /* the rates with the rows free: -M_FF^-1 h */
    for (int i = 0; i < w->nv; i++)
        y[i] = w->h[i];
    STICK_(block_neg)(w, y);
    STICK_(residual)(w, y, 1, w->c);
    STICK_REAL tol = STICK_(box)(G, w->c, n, psi, at, g, s, fr);
    for (int r = 0; r < n; r++) {
        int j = w->R[r];
        if (!at[r] || !(at[r] * g[r] < -tol))
            continue;
        STICK_(set)(w, u, m->fric_slip[j], at[r] < 0); /* (phi = F at: slips against it) */
        STICK_(set)(w, u, m->fric_stick[j], 0);
        if (gone)
            gone[j] = 1;
    }
    free(G), free(fr), free(at);
    return STICK_OK;
}

/* Lets go of the stuck items that cannot hold: the rows Coulomb's
 * choice lets go (decide_rows), then, while one needs more than its
 * bound, the one needing most for it, each slipping the way the rest
 * drives it; the solve at (t, q, v) of the modes left in w->acc.  Let
 * go, a row item gets gone[j] = 1. */
static int
STICK_(let_go)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
               const STICK_REAL *p, STICK_REAL *u, unsigned char *gone)
{
    for (int pass = 0; pass <= w->nf; pass++) {
        int rc = w->nrowitem ? STICK_(decide_rows)(w, t, q, v, p, u, gone) : STICK_OK, worst;
        if (rc != STICK_OK || (rc = STICK_(solve_shared)(w, t, q, v, p, u, w->acc)) != STICK_OK)
            return rc;
        if ((worst = STICK_(release_worst)(w, u)) < 0)
            return STICK_OK;
        if (gone)
            gone[worst] = 1;
    }
    return STICK_OK;
}

/* Whether row item j, not stuck, can move with the stuck rows held: its
 * row adds to their rank (0: their rows span it, its speed is held at 0
 * whatever its mode).  Builds at (t, q, v) with j stuck, then as u is. */
static int
STICK_(free_row)(STICK_(Work) *w, int j, STICK_REAL t, const STICK_REAL *q,
                 const STICK_REAL *v, const STICK_REAL *p, STICK_REAL *u, int *rc)
{
    const eomc_model *m = w->m;
    STICK_REAL F = 1;
    if ((*rc = STICK_(build)(w, t, q, v, p, u)) != STICK_OK)
        return 0;
    int before = w->nR ? w->rank : 0;
    STICK_(set)(w, u, m->fric_stick[j], 1);
    *rc = STICK_(build)(w, t, q, v, p, u);
    STICK_(set)(w, u, m->fric_stick[j], 0);
    for (int r = 0; r < w->nR; r++)
        if (w->R[r] == j)
            F = w->F[j];
    return *rc == STICK_OK && (w->rank > before || !(F > 0));
}

/* v made consistent with the stuck rows, the least change in the kinetic
 * metric that stops them: v += M_FF^-1 J_R^T F psi with J_R v = 0 (a
 * coordinate's speed is set to 0 by its own flip). */
static int
STICK_(project)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, STICK_REAL *v,
                const STICK_REAL *p, const STICK_REAL *u)
{
    int rc = STICK_(build)(w, t, q, v, p, u);
    if (rc != STICK_OK || !w->nR)
        return rc;
    STICK_(residual)(w, v, 0, w->c);
    STICK_(pseudo)(w, w->c, w->psi);
    STICK_(add_rows)(w, w->psi, v);
    return STICK_OK;
}

/* The modes at a state (t, q, v) alone, a run's start or a value outside
 * a run: an item slipping has its mode from its speed's sign, already in
 * u; one at rest (its speed 0, a row's 0 but for rounding: sign; a row
 * item's with a bound above 0) is stuck if it can be.  All at rest are
 * held first; while one would need more than its bound, the one needing
 * most (for its bound) is let go, slipping the way the rest drives it.
 * Then each let go must accelerate the way it slips, else no choice of
 * modes follows the motion (STICK_START, bad: the item; a row item whose
 * bound is 0 exerts nothing either way). */
STICK_API int
STICK_(settle)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
               const STICK_REAL *p, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    STICK_REAL *a = w->acc;
    int rc;
    if (w->nrowitem) { /* the rows' speeds and bounds at the state */
        for (int j = 0; j < w->nf; j++)
            STICK_(set)(w, u, m->fric_stick[j], 0);
        if ((rc = STICK_(build)(w, t, q, v, p, u)) != STICK_OK)
            return rc;
        /* a row's slip from its speed's sign (a function that kept the
         * side of a stuck item's may have kept a side from before) */
        for (int j = 0; j < w->nf; j++) {
            int sign = STICK_(sign)(w, j, v);
            if (STICK_(is_row)(w, j) && sign)
                STICK_(set)(w, u, m->fric_slip[j], sign > 0);
        }
    }
    for (int j = 0; j < w->nf; j++)
        STICK_(set)(w, u, m->fric_stick[j],
                    !STICK_(sign)(w, j, v) && (!STICK_(is_row)(w, j) || w->F[j] > 0));
    if ((rc = STICK_(let_go)(w, t, q, v, p, u, NULL)) != STICK_OK)
        return rc;
    for (int j = 0; j < w->nf; j++) {
        if (STICK_(stuck)(w, u, j) || STICK_(sign)(w, j, v) ||
            (STICK_(is_row)(w, j) && !(w->F[j] > 0)))
            continue;
        int up = u[w->nu + m->fric_slip[j]] != 0;
        STICK_REAL rate = STICK_(speed)(w, j, v, a);
        if (up ? !(rate > 0) : !(rate < 0)) {
            w->bad = j;
            return STICK_START;
        }
    }
    return STICK_OK;
}

/* A row item's slip switch k crossing at (t, q, v): every item of that
 * switch sticks where it can, with every other whose row the stuck rows
 * then span (its speed is 0 with theirs), v made consistent with all of
 * them (their speeds 0); then the items that cannot hold let go
 * (let_go), at speed 0 and leaving it the way they slip.  Where none of
 * this switch's holds, v is as it was and they slip on the way the rest
 * drives them. */
static int
STICK_(stick_rows)(STICK_(Work) *w, int k, STICK_REAL t, const STICK_REAL *q, STICK_REAL *v,
                   const STICK_REAL *p, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    int nv = w->nv, rc, any = 0;
    if ((rc = STICK_(bounds)(w, t, q, v, p, u)) != STICK_OK)
        return rc;
    unsigned char *mine = calloc((size_t)w->nf + 1, 1);
    STICK_REAL *was = malloc(((size_t)nv + 1) * sizeof *was);
    if (!mine || !was) {
        free(mine), free(was);
        w->bad = 0;
        return STICK_PIVOT;
    }
    for (int i = 0; i < nv; i++)
        was[i] = v[i];
    for (int j = 0; j < w->nf; j++)
        if (m->fric_slip[j] == k && !STICK_(stuck)(w, u, j) && w->F[j] > 0) {
            STICK_(set)(w, u, m->fric_stick[j], 1);
            mine[j] = 1, any = 1;
        }
    for (int j = 0; any && j < w->nf; j++) { /* those the stuck rows span */
        if (mine[j] || STICK_(stuck)(w, u, j) || !STICK_(is_row)(w, j) || !(w->F[j] > 0))
            continue;
        int spans = !STICK_(free_row)(w, j, t, q, v, p, u, &rc);
        if (rc != STICK_OK)
            goto out;
        if (spans) {
            STICK_(set)(w, u, m->fric_stick[j], 1);
            mine[j] = 1;
        }
    }
    if (any && ((rc = STICK_(project)(w, t, q, v, p, u)) != STICK_OK ||
                (rc = STICK_(let_go)(w, t, q, v, p, u, NULL)) != STICK_OK))
        goto out;
    any = 0;
    for (int j = 0; j < w->nf; j++)
        any |= mine[j] && STICK_(stuck)(w, u, j);
    if (!any) /* none held: on as before, the way the rest drives each */
        for (int i = 0; i < nv; i++)
            v[i] = was[i];
    if (!any && !STICK_(any)(w, u)) /* (the modes' own solve: nothing of the rows) */
        w->nR = 0;
    rc = STICK_OK;
out:
    free(mine), free(was);
    return rc;
}

/* Coulomb's choice (decide_rows) a little ahead (w->ahead) along the
 * motion of the modes u, where at (t, q, v) it sits on its edge: a group
 * of stuck rows at its limit, whose shares have reached their bounds with
 * rates of 0, so that which of them slip is told by where the rates go
 * next.  The state there, q + dt q', v + dt q'', is the motion's to
 * first order (q'' the caller's solve at (t, q, v) in u, in w->acc); the
 * modes the choice sets are u's, at (t, q, v). */
static int
STICK_(ahead)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
              const STICK_REAL *p, STICK_REAL *u, unsigned char *gone)
{
    int nq = w->m->nq;
    if (!(w->ahead > 0))
        return STICK_OK;
    if (w->x->qdot)
        w->x->qdot(q, v, w->qa);
    else
        for (int i = 0; i < nq; i++)
            w->qa[i] = v[i];
    for (int i = 0; i < nq; i++)
        w->qa[i] = q[i] + w->ahead * w->qa[i];
    for (int i = 0; i < w->nv; i++)
        w->va[i] = v[i] + w->ahead * w->acc[i];
    return STICK_(decide_rows)(w, t + w->ahead, w->qa, w->va, p, u, gone);
}

/* Row item j's stick switch letting go at (t, q, v): Coulomb's choice
 * for the stuck rows, j among them, says who slips (j or others: below),
 * and then so does every stuck item that needs more than its bound (the
 * group that held with it, by the proportional share: all at once).  Each let go must be free to move: where the rows
 * still stuck span its row, it cannot, and no choice of modes follows
 * (STICK_SPANNED, bad: the item). */
static int
STICK_(unstick_rows)(STICK_(Work) *w, int j, STICK_REAL t, const STICK_REAL *q,
                     const STICK_REAL *v, const STICK_REAL *p, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    int rc;
    if ((rc = STICK_(solve_shared)(w, t, q, v, p, u, w->acc)) != STICK_OK)
        return rc;
    int side = w->phi[j] < 0; /* (the way the rest drives it) */
    unsigned char *gone = calloc((size_t)w->nf + 1, 1);
    if (!gone) {
        w->bad = j;
        return STICK_PIVOT;
    }
    /* Coulomb's choice for all the stuck rows, j among them (decide_rows):
     * where the load came at once (a limit or a contact made at this
     * instant, its damper's force), it names who slips, j or not.  Where
     * it lets none go, j's share reached its bound as the load grew (its
     * crossing located): the choice is on its edge (shares at their
     * bounds, rates 0), and is made a little ahead (ahead).  Where that
     * lets none go either, j goes, the way the rest drives it, unless
     * the rows still stuck span its row (it cannot move: it holds with
     * them, at its bound to rounding). */
    if ((rc = STICK_(decide_rows)(w, t, q, v, p, u, gone)) != STICK_OK)
        goto out;
    int any = 0;
    for (int i = 0; i < w->nf; i++)
        any |= gone[i];
    if (!any) { /* (on its edge: where the rates go next; w->acc is the first solve's) */
        if ((rc = STICK_(ahead)(w, t, q, v, p, u, gone)) != STICK_OK)
            goto out;
        for (int i = 0; i < w->nf; i++)
            any |= gone[i];
    }
    if (!any) { /* none ahead either: j goes, unless the others hold its row */
        STICK_(set)(w, u, m->fric_stick[j], 0);
        int spanned = STICK_(any)(w, u) && !STICK_(free_row)(w, j, t, q, v, p, u, &rc);
        if (rc != STICK_OK)
            goto out;
        if (spanned) {
            STICK_(set)(w, u, m->fric_stick[j], 1);
            rc = STICK_(solve_shared)(w, t, q, v, p, u, w->acc);
            goto out;
        }
        STICK_(set)(w, u, m->fric_slip[j], side);
        gone[j] = 1;
    }
    for (int pass = 0; pass <= w->nf; pass++) {
        if ((rc = STICK_(let_go)(w, t, q, v, p, u, gone)) != STICK_OK)
            goto out;
        int held = -1; /* a let-go item the stuck rows hold still */
        for (int i = 0; i < w->nf && held < 0; i++)
            if (gone[i] && STICK_(is_row)(w, i) && STICK_(any)(w, u)) {
                if (!STICK_(free_row)(w, i, t, q, v, p, u, &rc))
                    held = i;
                if (rc != STICK_OK)
                    goto out;
            }
        if (held < 0)
            break;
        /* those at their bound to rounding let go with it (a group whose
         * rows are alike shares alike: its items reach their bounds at
         * once, and only the first one's crossing is located) */
        if ((rc = STICK_(solve_shared)(w, t, q, v, p, u, w->acc)) != STICK_OK)
            goto out;
        int more = 0;
        for (int i = 0; i < w->nf; i++)
            if (STICK_(stuck)(w, u, i) && STICK_(is_row)(w, i) && w->F[i] > 0 &&
                w->F[i] - STICK_ABS(w->phi[i]) <= STICK_BOUND_ULPS * w->nf * STICK_EPS * w->F[i]) {
                STICK_(set)(w, u, m->fric_slip[i], w->phi[i] < 0);
                STICK_(set)(w, u, m->fric_stick[i], 0);
                gone[i] = 1, more = 1;
            }
        if (!more) {
            w->bad = held;
            rc = STICK_SPANNED;
            goto out;
        }
    }
    /* (the build of the modes as they are, for the Jacobian) */
    rc = STICK_(solve_shared)(w, t, q, v, p, u, w->acc);
out:
    free(gone);
    return rc;
}

/* Mode k's flip to on at (t, q, v) in a run (its switch crossed there):
 * an item's slip switch, its speed crossing 0, sticks where the force
 * that holds it is within its bound (its speed set to exactly 0 in v),
 * else slips on the way the rest drives
 * it; an item's stick switch letting go slips that way; any other mode
 * is set.  A row item's (stick_rows, unstick_rows) take the items whose
 * rows the stuck ones span with it.  STICK_OK, or a solve's failure. */
STICK_API int
STICK_(flip)(STICK_(Work) *w, int k, int on, STICK_REAL t, const STICK_REAL *q,
             STICK_REAL *v, const STICK_REAL *p, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    STICK_REAL *a = w->acc;
    int j = STICK_(item_of)(w, w->m->fric_slip, k), rc;
    if (j >= 0 && STICK_(is_row)(w, j)) {
        int held = 0;
        for (int i = 0; i < w->nf; i++)
            held |= m->fric_slip[i] == k && STICK_(stuck)(w, u, i);
        if (held) /* (its side is kept while stuck: keep_slip) */
            return STICK_OK;
        STICK_(set)(w, u, k, on);
        return STICK_(stick_rows)(w, k, t, q, v, p, u);
    }
    if (j >= 0 && !STICK_(stuck)(w, u, j)) {
        int s = m->fric_speed[j];
        STICK_REAL was = v[s];
        v[s] = 0;
        STICK_(set)(w, u, m->fric_stick[j], 1);
        if ((rc = STICK_(solve_shared)(w, t, q, v, p, u, a)) != STICK_OK)
            return rc;
        if (STICK_ABS(w->phi[j]) <= w->F[j])
            return STICK_OK;
        v[s] = was;
        STICK_(set)(w, u, m->fric_stick[j], 0);
        STICK_(set)(w, u, k, w->phi[j] < 0);
        return STICK_OK;
    }
    j = STICK_(item_stick)(w, k);
    if (j >= 0 && !on && STICK_(stuck)(w, u, j) && STICK_(is_row)(w, j))
        return STICK_(unstick_rows)(w, j, t, q, v, p, u);
    if (j >= 0 && !on && STICK_(stuck)(w, u, j)) {
        if ((rc = STICK_(solve_shared)(w, t, q, v, p, u, a)) != STICK_OK)
            return rc;
        STICK_(set)(w, u, m->fric_slip[j], w->phi[j] < 0);
    }
    STICK_(set)(w, u, k, on);
    if (j >= 0 || !w->nrowitem)
        return STICK_OK;
    /* a contact's push ended (or its near or touch switch flipped): a
     * stuck point whose bound is now 0 holds nothing, and lets go, its
     * slip switch on its speed's side (its side kept where that is 0 but
     * for rounding: it was held at 0); it slips by its speed's sign when
     * it touches again */
    if ((rc = STICK_(build)(w, t, q, v, p, u)) != STICK_OK)
        return rc;
    for (int i = 0; i < w->nf; i++)
        if (STICK_(is_row)(w, i) && STICK_(stuck)(w, u, i) && !(w->F[i] > 0)) {
            int sign = STICK_(sign)(w, i, v);
            STICK_(set)(w, u, m->fric_stick[i], 0);
            if (sign)
                STICK_(set)(w, u, m->fric_slip[i], sign > 0);
        }
    /* a point that touches slips by its speed's sign (its slip switch
     * kept its side while its bound was 0: keep_slip).  One that touches
     * with its speed exactly 0 (a ball dropped straight down) has no sign
     * to slip by: its slip switch keeps its side, on its kink, and the
     * friction of that side moves it off 0 the other way at once, where
     * the run locates the departure as a crossing (stepevents.c's
     * leaves_kink) and it sticks, as one touching with a speed that is 0
     * but for rounding (of its terms, STICK_BOUND_ULPS of them) does: the
     * same flips whether rounding left its speed 0 or not (in the run's
     * doubles and the reference's long doubles alike).  Where the
     * switch's function is across from its kept side by rounding, the
     * instant's pass flips it there (stepevents.c's together): the speed
     * crosses 0 at once. */
    for (int i = 0; i < w->nf; i++) {
        if (!STICK_(is_row)(w, i) || STICK_(stuck)(w, u, i) || !(w->F[i] > 0))
            continue;
        int sign = STICK_(sign)(w, i, v);
        if (sign)
            STICK_(set)(w, u, m->fric_slip[i], sign > 0);
    }
    return STICK_OK;
}

#undef STICK_ABS
