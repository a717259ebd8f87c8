/*
 * reftaylor: Taylor's method in extended precision (reftaylor.h).
 *
 * The same method as taylor.c, carried in eomc_ext, for a reference that
 * shares nothing with extrapolation but the model's twin: the series of
 * M, h (and of B and f = B q'' + b with constraints) from the twin's
 * taylor member; the accelerations' coefficients order by order from
 *     M_0 a_k = -(h_k + sum_{j=1..k} M_j a_{k-j})
 * or, with constraints, from the KKT system
 *     [M_0 B_0^T; B_0 0] [a_k; lambda_k]
 *         = -[h_k + sum_{j=1..k} (M_j a_{k-j} + B_j^T lambda_{k-j});
 *             b_k + sum_{j=1..k} B_j a_{k-j}],
 * factored once a step (linalg.c's la_ext_lu, the KKT matrix scaled by
 * la_ext_kkt_scaling); Jorba and Zou's order ceil(-ln(rtol)/2 + 1) and
 * step rho e^-2 exp(-0.7/(p - 1)), rho from the last two coefficients of
 * each component against its size over the step, at least its least
 * scale (sc).  No stabilization: the reference follows the constraints'
 * own motion.  With speeds of their own (nv > 0) as taylor.c: M, h, a
 * and B in the speeds, and q's coefficients from the series of q' = W(q)
 * v (the model's taylor_qd, the twin's slots being the same).
 */
#include "reftaylor.h"
#include "step/taylor.h"
#include "model/linalg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct RefTaylor {
    const eomc_model_ext *x;
    const int *qd;     /* [nq] the slots of q' = W(q) v, or NULL (q' = v) */
    int n, nv, N, nc, nk, p; /* nq, nv (nq without speeds), nq + nv, nc, nv + nc */
    eomc_ext *T;       /* [nslot (TAYLOR_MAX_ORDER + 1)] the twin's series, stride p + 1 */
    eomc_ext *X;       /* [(p + 1) N] the state's, X[j N + i] */
    eomc_ext *A, *L;   /* [nv (p + 1)], [nc (p + 1)]: the accelerations', the multipliers' */
    eomc_ext *K, *r;   /* [nk nk] M_0 or the KKT matrix, factored; [nk] a right-hand side */
    eomc_ext *eq, *dK; /* [2 nk] its equilibration, [nk] its KKT scaling */
    int *perm;         /* [nk] */
    eomc_ext *S;       /* [N] the scales of the step rule */
    const unsigned char *drop; /* [nc] rows left out, as the doubles' solves do, or NULL */
};

static eomc_ext *
zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(eomc_ext));
}

RefTaylor *
reftaylor_alloc(const eomc_model_ext *x, const int *qd, int n, int nv, int nc,
                const unsigned char *drop)
{
    RefTaylor *rt = calloc(1, sizeof *rt);
    if (!rt)
        return NULL;
    size_t K1 = TAYLOR_MAX_ORDER + 1, nk = (size_t)(nv + nc), N = (size_t)(n + nv);
    *rt = (RefTaylor){.x = x, .qd = qd, .n = n, .nv = nv, .N = n + nv, .nc = nc,
                      .nk = nv + nc, .drop = drop};
    rt->T = zeros((size_t)x->taylor_nslot * K1);
    rt->X = zeros(K1 * N);
    rt->A = zeros(K1 * (size_t)nv);
    rt->L = zeros(K1 * (size_t)nc);
    rt->K = zeros(nk * nk);
    rt->r = zeros(nk);
    rt->eq = zeros(2 * nk);
    rt->dK = zeros(nk);
    rt->S = zeros(N);
    rt->perm = calloc(nk + 1, sizeof *rt->perm);
    if (!rt->T || !rt->X || !rt->A || !rt->L || !rt->K || !rt->r || !rt->eq || !rt->dK ||
        !rt->S || !rt->perm) {
        reftaylor_free(rt);
        return NULL;
    }
    return rt;
}

void
reftaylor_free(RefTaylor *rt)
{
    if (!rt)
        return;
    free(rt->T);
    free(rt->X);
    free(rt->A);
    free(rt->L);
    free(rt->K);
    free(rt->r);
    free(rt->eq);
    free(rt->dK);
    free(rt->S);
    free(rt->perm);
    free(rt);
}

static eomc_ext
coef(const RefTaylor *rt, int slot, int k)
{
    return slot < 0 ? 0 : rt->T[(size_t)slot * (size_t)(rt->p + 1) + (size_t)k];
}

/* sum_{j=1..k} a_j b_{k-j} of two series of stride p + 1 (a: a slot's). */
static eomc_ext
conv(const RefTaylor *rt, int slot, const eomc_ext *b, int k)
{
    if (slot < 0)
        return 0;
    const eomc_ext *a = rt->T + (size_t)slot * (size_t)(rt->p + 1);
    eomc_ext s = 0;
    for (int j = 1; j <= k; j++)
        s += a[j] * b[k - j];
    return s;
}

/* Coefficient k of the accelerations (and multipliers) into r: the
 * system above, factored at k = 0.  0, or -1 when it is singular. */
static int
order(RefTaylor *rt, int k)
{
    const eomc_model_ext *x = rt->x;
    int n = rt->nv, nc = rt->nc, nk = rt->nk, p1 = rt->p + 1;
    if (k == 0) {
        memset(rt->K, 0, (size_t)nk * (size_t)nk * sizeof *rt->K);
        for (int i = 0; i < n; i++)
            for (int l = 0; l < n; l++)
                rt->K[i * nk + l] = coef(rt, x->taylor_M[i * n + l], 0);
        for (int c = 0; c < nc; c++) /* a row left out: as kkt.c */
            for (int i = 0; i < n; i++)
                rt->K[(n + c) * nk + i] = rt->K[i * nk + n + c] =
                    rt->drop && rt->drop[c] ? 0 : coef(rt, x->taylor_B[c * n + i], 0);
        for (int c = 0; rt->drop && c < nc; c++)
            rt->K[(n + c) * nk + n + c] = rt->drop[c];
        if (nc)
            la_ext_kkt_scaling(rt->K, n, nc, rt->dK);
        if (la_ext_lu_factor(rt->K, nk, rt->perm, rt->eq, nc ? rt->dK : NULL) != 0)
            return -1;
    }
    for (int i = 0; i < n; i++) {
        eomc_ext s = coef(rt, x->taylor_h[i], k);
        for (int l = 0; l < n; l++)
            s += conv(rt, x->taylor_M[i * n + l], rt->A + (size_t)l * p1, k);
        for (int c = 0; c < nc; c++)
            s += conv(rt, x->taylor_B[c * n + i], rt->L + (size_t)c * p1, k);
        rt->r[i] = s;
    }
    for (int c = 0; c < nc; c++) {
        eomc_ext s = coef(rt, x->taylor_f[c], k);
        for (int i = 0; i < n; i++)
            s += conv(rt, x->taylor_B[c * n + i], rt->A + (size_t)i * p1, k);
        rt->r[n + c] = rt->drop && rt->drop[c] ? 0 : s;
    }
    la_ext_lu_solve(rt->K, nk, rt->perm, rt->eq, rt->r);
    return 0;
}

/* The least over the components and the last two orders of
 * (S_i / |x_ij|)^(1/j), or, for S NULL, of (|x_im| / |x_ij|)^(1/(j - m))
 * with x_im the component's first coefficient that is not 0 (taylor.c's
 * radius). */
static eomc_ext
radius(const RefTaylor *rt, const eomc_ext *S)
{
    int p = rt->p, N = rt->N;
    eomc_ext rho = INFINITY;
    for (int i = 0; i < N; i++) {
        int m = 0;
        while (!S && m < p - 1 && rt->X[(size_t)m * N + i] == 0)
            m++;
        eomc_ext scale = S ? S[i] : fabsl(rt->X[(size_t)m * N + i]);
        if (!(scale > 0))
            continue;
        for (int j = p - 1; j <= p; j++) {
            eomc_ext c = fabsl(rt->X[(size_t)j * N + i]);
            if (c > 0 && j > m)
                rho = fminl(rho, powl(scale / c, 1.0L / (j - m)));
        }
    }
    return rho;
}

int
reftaylor_series(RefTaylor *rt, eomc_ext t0, const eomc_ext *x, const eomc_ext *p,
                 const eomc_ext *u, eomc_ext rtol, const eomc_ext *sc, eomc_ext hmax,
                 eomc_ext *h)
{
    const eomc_model_ext *tw = rt->x;
    int n = rt->n, nv = rt->nv, N = rt->N;
    rt->p = taylor_order_for((double)rtol);
    int P = rt->p, p1 = P + 1;
    memcpy(rt->X, x, (size_t)N * sizeof *x);
    for (int k = 0; k < P; k++) {
        const eomc_ext *cur = rt->X + (size_t)k * N;
        for (int i = 0; i < n; i++)
            if (tw->taylor_q[i] >= 0)
                rt->T[(size_t)tw->taylor_q[i] * p1 + k] = cur[i];
        for (int j = 0; j < nv; j++)
            if (tw->taylor_v[j] >= 0)
                rt->T[(size_t)tw->taylor_v[j] * p1 + k] = cur[n + j];
        tw->taylor(k, P, t0, p, u, rt->T);
        if (order(rt, k) != 0)
            return -1;
        eomc_ext *next = rt->X + (size_t)(k + 1) * N;
        for (int j = 0; j < nv; j++) {
            rt->A[(size_t)j * p1 + k] = -rt->r[j];
            next[n + j] = -rt->r[j] / (k + 1);
        }
        for (int i = 0; i < n; i++) /* q' = v, or W(q) v's series */
            next[i] = (rt->qd ? coef(rt, rt->qd[i], k) : cur[n + i]) / (k + 1);
        for (int c = 0; c < rt->nc; c++)
            rt->L[(size_t)c * p1 + k] = -rt->r[nv + c];
        for (int i = 0; i < N; i++)
            if (!isfinite(next[i]))
                return -1;
    }
    /* the step: each component against its size over it, at least sc */
    eomc_ext factor = expl(-2.0L - (eomc_ext)TAYLOR_SAFETY / (P - 1));
    eomc_ext step = radius(rt, NULL) * factor;
    for (int round = 0; round < TAYLOR_SCALE_ROUNDS && isfinite(step); round++) {
        for (int i = 0; i < N; i++) {
            eomc_ext big = sc[i], hj = 1;
            for (int j = 0; j <= P; j++, hj *= step)
                big = fmaxl(big, fabsl(rt->X[(size_t)j * N + i]) * hj);
            rt->S[i] = big;
        }
        step = radius(rt, rt->S) * factor;
    }
    *h = step < hmax ? step : hmax;
    return 0;
}

void
reftaylor_eval(const RefTaylor *rt, eomc_ext tau, eomc_ext *x)
{
    int N = rt->N;
    for (int i = 0; i < N; i++) {
        eomc_ext d = rt->X[(size_t)rt->p * N + i];
        for (int j = rt->p - 1; j >= 1; j--)
            d = d * tau + rt->X[(size_t)j * N + i];
        x[i] = rt->X[i] + d * tau;
    }
}

int
reftaylor_order(const RefTaylor *rt)
{
    return rt->p;
}
