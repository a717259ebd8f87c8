/*
 * stick.h: dry friction's modes and its stuck coordinates (eomc_model.h's
 * fric_ members), written once for two number types: double in the runs
 * (friction.c) and eomc_ext in the reference solution (reffric.c), so
 * that both decide alike where a coordinate sticks and where it slips.
 *
 * The includer defines STICK_REAL (the number type), STICK_MODEL (whose
 * mass_bias and fric_bound take it: eomc_model or eomc_model_ext),
 * STICK_(name) (the names' prefix) and STICK_API (the functions'
 * linkage), then includes this file.  Modes are the model's, u[nu + k].
 *
 * While items are stuck, their speeds' accelerations are 0 and the others
 * come from the rows of the free speeds F: M_FF a_F = -h_F (M_FF is M's
 * block, positive definite as M is, factored by LDL^T here).  The force
 * that holds stuck speed s is then phi_s = (M a + h)_s: E's residual
 * there, the generalized force the stuck coordinate must be given (h has
 * no friction of its own: a stuck item puts none).  It holds while
 * |phi_s| <= F_s: the stick switch's function is F_s - |phi_s|.  Let go,
 * it slips the way the rest drives it, -phi_s, against a friction of F_s.
 */
#include <math.h>
#include <stdlib.h>

#ifndef STICK_STATUS_DEFINED /* (friction.h declares them for its callers) */
enum { STICK_OK, STICK_PIVOT, STICK_NEGATIVE, STICK_START };
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
} STICK_(Work);

#define STICK_ABS(r) ((r) < 0 ? -(r) : (r))

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
    if (!w->M || !w->L || !w->h || !w->acc || !w->F || !w->phi || !w->free_of || !w->held) {
        free(w->M), free(w->L), free(w->h), free(w->acc), free(w->F), free(w->phi);
        free(w->free_of), free(w->held);
        free(w);
        return NULL;
    }
    return w;
}

STICK_API void
STICK_(free)(STICK_(Work) *w)
{
    if (!w)
        return;
    free(w->M), free(w->L), free(w->h), free(w->acc), free(w->F), free(w->phi);
    free(w->free_of), free(w->held);
    free(w);
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

/* The bounds F at (t, q, v); STICK_NEGATIVE (bad: the item) where one
 * is below 0 or not a number. */
STICK_API int
STICK_(bounds)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
               const STICK_REAL *p, const STICK_REAL *u)
{
    w->x->fric_bound(t, q, v, p, u, w->F);
    for (int j = 0; j < w->nf; j++)
        if (!(w->F[j] >= 0)) {
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

/* b = -M^-1 b with the stuck speeds held: b_F = -M_FF^-1 b_F, b_S = 0,
 * M_FF as the last solve factored it. */
STICK_API void
STICK_(solve_neg)(const STICK_(Work) *w, STICK_REAL *b)
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

/* q'' at (t, q, v) in the modes u, the stuck items' speeds held at 0
 * (none stuck: M a = -h): a [nv], and each stuck item's holding force
 * and every bound (w->phi, w->F).  STICK_OK, STICK_PIVOT (bad: the speed
 * whose pivot failed) or STICK_NEGATIVE. */
STICK_API int
STICK_(solve)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
              const STICK_REAL *p, const STICK_REAL *u, STICK_REAL *a)
{
    const eomc_model *m = w->m;
    int nv = w->nv;
    int rc = STICK_(bounds)(w, t, q, v, p, u);
    if (rc != STICK_OK)
        return rc;
    w->x->mass_bias(t, q, v, p, u, w->M, w->h);
    for (int i = 0; i < nv; i++)
        w->held[i] = 0;
    for (int j = 0; j < w->nf; j++)
        w->held[m->fric_speed[j]] |= STICK_(stuck)(w, u, j);
    w->nfree = 0;
    for (int i = 0; i < nv; i++)
        if (!w->held[i])
            w->free_of[w->nfree++] = i;
    int k = STICK_(factor)(w);
    if (k) {
        w->bad = w->free_of[k - 1];
        return STICK_PIVOT;
    }
    for (int i = 0; i < nv; i++)
        a[i] = w->h[i];
    STICK_(solve_neg)(w, a);
    for (int j = 0; j < w->nf; j++) {
        int s = m->fric_speed[j];
        STICK_REAL r = w->h[s];
        for (int i = 0; STICK_(stuck)(w, u, j) && i < nv; i++)
            r += w->M[s * nv + i] * a[i];
        w->phi[j] = STICK_(stuck)(w, u, j) ? r : 0;
    }
    return STICK_OK;
}

/* The stick switches' functions at (t, q, v) in the modes u into sw
 * [nmode]: F - |phi| where stuck, else -1 (it cannot stick by this
 * switch: slipping, its slip switch's crossing decides).  A solve's
 * failure is returned, the functions then NAN. */
STICK_API int
STICK_(functions)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
                  const STICK_REAL *p, const STICK_REAL *u, STICK_REAL *sw)
{
    int rc = STICK_(any)(w, u) ? STICK_(solve)(w, t, q, v, p, u, w->acc) : STICK_OK;
    if (rc != STICK_OK) {
        for (int j = 0; j < w->nf; j++)
            sw[w->m->fric_stick[j]] = NAN;
        return rc;
    }
    for (int j = 0; j < w->nf; j++)
        sw[w->m->fric_stick[j]] = STICK_(stuck)(w, u, j)
                                      ? w->F[j] - STICK_ABS(w->phi[j]) : -1;
    return STICK_OK;
}

static void
STICK_(set)(const STICK_(Work) *w, STICK_REAL *u, int mode, int on)
{
    u[w->nu + mode] = on ? 1 : 0;
}

/* The modes at a state (t, q, v) alone, a run's start or a value outside
 * a run: an item slipping has its mode from its speed's sign, already in
 * u; one at rest (its speed exactly 0) is stuck if it can be.  All at
 * rest are held first; while one would need more than its bound, the
 * one needing most (for its bound) is let go, slipping the way the rest
 * drives it.  Then each let go must accelerate the way it slips, else no
 * choice of modes follows the motion (STICK_START, bad: the item). */
STICK_API int
STICK_(settle)(STICK_(Work) *w, STICK_REAL t, const STICK_REAL *q, const STICK_REAL *v,
               const STICK_REAL *p, STICK_REAL *u)
{
    const eomc_model *m = w->m;
    STICK_REAL *a = w->acc;
    for (int j = 0; j < w->nf; j++)
        STICK_(set)(w, u, m->fric_stick[j], v[m->fric_speed[j]] == 0);
    for (int pass = 0; pass <= w->nf; pass++) {
        int rc = STICK_(solve)(w, t, q, v, p, u, a), worst = -1;
        if (rc != STICK_OK)
            return rc;
        for (int j = 0; j < w->nf; j++) {
            STICK_REAL need = STICK_ABS(w->phi[j]);
            /* need / F the largest, compared without dividing by a bound of 0 */
            if (STICK_(stuck)(w, u, j) && need > w->F[j] &&
                (worst < 0 || need * w->F[worst] > STICK_ABS(w->phi[worst]) * w->F[j]))
                worst = j;
        }
        if (worst < 0)
            break;
        STICK_(set)(w, u, m->fric_slip[worst], w->phi[worst] < 0);
        STICK_(set)(w, u, m->fric_stick[worst], 0);
    }
    for (int j = 0; j < w->nf; j++) {
        int s = m->fric_speed[j];
        if (v[s] != 0 || STICK_(stuck)(w, u, j))
            continue;
        int up = u[w->nu + m->fric_slip[j]] != 0;
        if (up ? !(a[s] > 0) : !(a[s] < 0)) {
            w->bad = j;
            return STICK_START;
        }
    }
    return STICK_OK;
}

/* Mode k's flip to on at (t, q, v) in a run (its switch crossed there):
 * an item's slip switch, its speed crossing 0, sticks where the force
 * that holds it is within its bound (its speed set to exactly 0 in v,
 * *stuck its stick switch's mode), else slips on the way the rest drives
 * it; an item's stick switch letting go slips that way; any other mode
 * is set.  STICK_OK, or a solve's failure. */
STICK_API int
STICK_(flip)(STICK_(Work) *w, int k, int on, STICK_REAL t, const STICK_REAL *q,
             STICK_REAL *v, const STICK_REAL *p, STICK_REAL *u, int *stuck)
{
    const eomc_model *m = w->m;
    STICK_REAL *a = w->acc;
    int j = STICK_(item_of)(w, w->m->fric_slip, k), rc;
    *stuck = -1;
    if (j >= 0 && !STICK_(stuck)(w, u, j)) {
        int s = m->fric_speed[j];
        STICK_REAL was = v[s];
        v[s] = 0;
        STICK_(set)(w, u, m->fric_stick[j], 1);
        if ((rc = STICK_(solve)(w, t, q, v, p, u, a)) != STICK_OK)
            return rc;
        if (STICK_ABS(w->phi[j]) <= w->F[j]) {
            *stuck = m->fric_stick[j];
            return STICK_OK;
        }
        v[s] = was;
        STICK_(set)(w, u, m->fric_stick[j], 0);
        STICK_(set)(w, u, k, w->phi[j] < 0);
        return STICK_OK;
    }
    j = STICK_(item_stick)(w, k);
    if (j >= 0 && !on && STICK_(stuck)(w, u, j)) {
        if ((rc = STICK_(solve)(w, t, q, v, p, u, a)) != STICK_OK)
            return rc;
        STICK_(set)(w, u, m->fric_slip[j], w->phi[j] < 0);
    }
    STICK_(set)(w, u, k, on);
    return STICK_OK;
}

#undef STICK_ABS
