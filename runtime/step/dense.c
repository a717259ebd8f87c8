/*
 * dense: Hermite interpolation through the last step ends (dense.h).
 *
 * The polynomial is kept in Newton form over the confluent nodes
 * z = (t_a, t_a, t_a, t_b, t_b, t_b, ...), each node repeated three times
 * for its value, first and second derivative: the divided differences
 * f[z_i..z_i+l] over one repeated node are q, q' and q''/2.  Its
 * coefficients are computed once per window of nodes and coordinate and
 * reused for every output time in the window's interval.
 *
 * The nodes enter the Newton form nearest first: the interval's two ends,
 * then the others by their distance from it.  Its partial sums are the
 * interpolants through the nearest 1, 2, ... 5 nodes, each of higher
 * degree.  Where steps are long and the motion smooth, each is better
 * than the one before, and the difference of the last two estimates the
 * error of the fourth (and bounds the fifth's): the ratio of successive
 * errors goes as (w d)^3 / 1320 for a motion of frequency w and nodes d
 * apart, so an estimate from the third and fourth would be hundreds of
 * times too large and send most of rk8pd's rows to side steps for
 * nothing.  That is the first look (choose_top): the full interpolant,
 * and the difference of the last two at 0.3 and 0.7 of the interval (two
 * points, in case two interpolants cross at one) as its error.
 *
 * Where steps are short, the node values' own errors (the tolerance,
 * which is not smooth from step to step) dominate, and higher degrees
 * amplify them: there a lower interpolant is better.  When the first look
 * does not satisfy the driver, dense_refine takes, coordinate by
 * coordinate, the higher of the two successive interpolants that differ
 * least at a quarter, a half and three quarters of the interval, and
 * their largest difference there as its error.  A velocity is then the
 * derivative of its coordinate's polynomial, or, where that is estimated
 * worse, the Hermite interpolant of q' and q'' alone (degree up to 9):
 * differentiating amplifies the noise of short steps by 1/h (msbdf at
 * 1e-13 takes steps of 3e-4 on chain5), which the direct interpolant
 * does not.
 *
 * Speeds that are not the coordinates' rates (dense_alloc's nv > 0: a unit
 * quaternion and its body's angular velocity): a coordinate has its rate
 * q' in x' and its second derivative q'' = dq'/dq q' + W(q) v' from the
 * caller (dense_push's qdd), so it is interpolated as above; a speed is
 * not any coordinate's rate, and is interpolated from its value and rate
 * alone, as a velocity's direct interpolant above, with the same first
 * look and the same refinement; or, where that is estimated worse and the
 * caller can turn rates into speeds (dense_set_speeds: v = W(q)^+ q', W
 * of full column rank), from the coordinates' polynomials' derivative, as
 * a velocity is, its estimate the speeds of the derivatives of one node
 * less.  Without q'' (the model has no qdot_jacobian) a coordinate is
 * interpolated from its value and rate too.
 */
#include "dense.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    WINDOW = 5,           /* nodes per interpolant: k - 2 .. k + 2 */
    BEFORE = 2,           /* of which before the interval [k, k + 1] */
    KEEP = WINDOW + 1,    /* nodes stored: a window and the next node */
    COEFFS = 3 * WINDOW,  /* conditions per coordinate */
    VCOEFFS = 2 * WINDOW, /* ... per entry from its value and rate */
};

struct Dense {
    int n;               /* coordinates */
    int nv;              /* speeds: n (their rates), or the model's own nv */
    int N;               /* the state's entries, n + nv */
    int speeds;          /* the speeds are not the rates (nv > 0 given) */
    int second;          /* the coordinates' q'' at the nodes: the rates' v'
                          * (not speeds), or dense_push's qdd */
    long count;          /* nodes pushed; node i is slot i % KEEP */
    double t[KEEP];
    double *x[KEEP], *f[KEEP];  /* [N] each */
    double *s[KEEP];     /* [n] each: the coordinates' q'' */
    long win_lo;         /* the window whose coefficients are in coef, or -1 */
    int win_m;           /* its number of nodes */
    long win_k;          /* the interval it was fitted for */
    int refined;         /* dense_refine has chosen for this window */
    long order[WINDOW];  /* its nodes, nearest the interval first */
    double z[COEFFS];
    double *coef;        /* [n * COEFFS] q's Newton coefficients */
    double *vcoef;       /* [N * VCOEFFS] entry c's from its value and rate
                          * alone: a velocity's from q' and q'' (c = n + i), a
                          * speed's, a coordinate's without q'' */
    /* Rates as speeds: per coordinate and window, the number of nodes of
     * q's interpolant (lev[3i]), of the one whose derivative is q'
     * (lev[3i+1]), of q''s direct one (lev[3i+2], 0 when the derivative
     * is used), and the error estimates of q and q' (est[i], est[n+i]).
     * Speeds of their own: lev[i] and est[i] of entry i, each from its own
     * interpolant. */
    int *lev;            /* [3n], or [N] */
    double *est;         /* [N] */
    /* speeds of their own from the coordinates' derivative (dense_set_speeds) */
    int (*to_speeds)(void *ctx, const double *q, const double *qd, double *v);
    void *to_ctx;
    unsigned char *vsrc; /* [nv] 1: speed k from it, 0: from its value and rate */
    double *esta;        /* [nv] its estimate so */
    double *qt, *dqt, *dql, *vt, *vl; /* [n] [n] [n] [nv] [nv] scratch */
};

Dense *
dense_alloc(int n, int nv)
{
    Dense *d = calloc(1, sizeof *d);
    if (!d)
        return NULL;
    d->n = n;
    d->speeds = nv > 0;
    d->nv = d->speeds ? nv : n;
    d->N = n + d->nv;
    d->second = !d->speeds;
    size_t N = (size_t)d->N;
    int ok = (d->coef = calloc((size_t)n * COEFFS, sizeof(double))) != NULL &&
             (d->vcoef = calloc(N * VCOEFFS, sizeof(double))) != NULL &&
             (d->lev = calloc(3 * (size_t)n + N, sizeof(int))) != NULL &&
             (d->est = calloc(N, sizeof(double))) != NULL &&
             (d->vsrc = calloc((size_t)d->nv, 1)) != NULL &&
             (d->esta = calloc((size_t)d->nv, sizeof(double))) != NULL &&
             (d->qt = calloc(3 * (size_t)n + 2 * (size_t)d->nv, sizeof(double))) != NULL;
    for (int k = 0; k < KEEP; k++) {
        ok &= (d->x[k] = calloc(N, sizeof(double))) != NULL;
        ok &= (d->f[k] = calloc(N, sizeof(double))) != NULL;
        ok &= (d->s[k] = calloc((size_t)n + 1, sizeof(double))) != NULL;
    }
    if (!ok) {
        dense_free(d);
        return NULL;
    }
    d->dqt = d->qt + n, d->dql = d->dqt + n, d->vt = d->dql + n, d->vl = d->vt + d->nv;
    dense_clear(d);
    return d;
}

void
dense_free(Dense *d)
{
    if (!d)
        return;
    for (int k = 0; k < KEEP; k++)
        free(d->x[k]), free(d->f[k]), free(d->s[k]);
    free(d->coef);
    free(d->vcoef);
    free(d->lev);
    free(d->est);
    free(d->vsrc);
    free(d->esta);
    free(d->qt);
    free(d);
}

void
dense_set_speeds(Dense *d, int (*to_speeds)(void *ctx, const double *q, const double *qd,
                                             double *v), void *ctx)
{
    d->to_speeds = to_speeds;
    d->to_ctx = ctx;
}

void
dense_clear(Dense *d)
{
    d->count = 0;
    d->win_lo = -1;
    d->second = !d->speeds;
}

void
dense_push(Dense *d, double t, const double *x, const double *dxdt, const double *qdd)
{
    int slot = (int)(d->count % KEEP);
    d->t[slot] = t;
    memcpy(d->x[slot], x, (size_t)d->N * sizeof *x);
    memcpy(d->f[slot], dxdt, (size_t)d->N * sizeof *dxdt);
    if (!d->speeds) /* q'' is v' */
        memcpy(d->s[slot], dxdt + d->n, (size_t)d->n * sizeof *dxdt);
    else if (qdd)
        memcpy(d->s[slot], qdd, (size_t)d->n * sizeof *qdd);
    /* speeds: q'' at every node, or the coordinates from their rates alone */
    d->second = !d->speeds || (qdd && (d->count == 0 || d->second));
    d->count++;
}

double
dense_last(const Dense *d)
{
    return d->count ? d->t[(d->count - 1) % KEEP] : -INFINITY;
}

static double
node_t(const Dense *d, long i)
{
    return d->t[i % KEEP];
}

/* The interval [node k, node k + 1] holding t, or -1 when t is outside
 * the stored nodes. */
static long
interval(const Dense *d, double t)
{
    long first = d->count > KEEP ? d->count - KEEP : 0, last = d->count - 1;
    if (d->count == 0 || t < node_t(d, first) || t > node_t(d, last))
        return -1;
    long k = first;
    while (k + 1 < last && node_t(d, k + 1) < t)
        k++;
    return k;
}

/* The window of interval k: its first node and node count. */
static void
window(const Dense *d, long k, int final, long *lo, int *m)
{
    long first = d->count > KEEP ? d->count - KEEP : 0, last = d->count - 1;
    *lo = k - BEFORE > first ? k - BEFORE : first;
    if (final && *lo + WINDOW - 1 > last)
        *lo = last - (WINDOW - 1) > first ? last - (WINDOW - 1) : first;
    *m = (int)(last - *lo + 1 < WINDOW ? last - *lo + 1 : WINDOW);
}

int
dense_ready(const Dense *d, double t, int final)
{
    long k = interval(d, t), lo;
    int m;
    if (k < 0)
        return 0;
    if (final)
        return 1;
    window(d, k, 0, &lo, &m);
    return m == WINDOW;
}

/* The end of interval k (k itself for a single node). */
static double
interval_end(const Dense *d, long k)
{
    return node_t(d, k + 1 < d->count ? k + 1 : k);
}

/* The window's nodes for interval k, nearest the interval first. */
static void
order_nodes(Dense *d, long k, long lo, int m)
{
    double mid = 0.5 * (node_t(d, k) + interval_end(d, k));
    for (int j = 0; j < m; j++)
        d->order[j] = lo + j;
    for (int i = 1; i < m; i++) /* insertion sort by distance from mid */
        for (int j = i; j > 0 && fabs(node_t(d, d->order[j]) - mid) <
                                     fabs(node_t(d, d->order[j - 1]) - mid); j--) {
            long x = d->order[j];
            d->order[j] = d->order[j - 1], d->order[j - 1] = x;
        }
}

/* Newton coefficients of each coordinate's polynomial over the window
 * (with its q'' at the nodes: d->second). */
static void
fit(Dense *d, long k, long lo, int m)
{
    int n = d->n, N = 3 * m;
    order_nodes(d, k, lo, m);
    for (int j = 0; j < N; j++)
        d->z[j] = node_t(d, d->order[j / 3]);
    for (int i = 0; i < n && d->second; i++) {
        double *c = d->coef + (size_t)i * COEFFS;
        for (int j = 0; j < N; j++)
            c[j] = d->x[d->order[j / 3] % KEEP][i];
        for (int l = 1; l < N; l++)
            for (int j = N - 1; j >= l; j--) {
                int slot = (int)(d->order[j / 3] % KEEP);
                if (d->z[j] == d->z[j - l]) /* one node: q' or q''/2 */
                    c[j] = l == 1 ? d->f[slot][i] : 0.5 * d->s[slot][i];
                else
                    c[j] = (c[j] - c[j - 1]) / (d->z[j] - d->z[j - l]);
            }
    }
    d->win_lo = lo;
    d->win_m = m;
    d->win_k = k;
    d->refined = 0;
}

/* The same for entries c0 .. c1 - 1 from their values and rates alone,
 * over the nodes z_v = (t_a, t_a, t_b, t_b, ...) (a velocity: q', q''). */
static void
fit_pairs(Dense *d, int m, int c0, int c1)
{
    int N = 2 * m;
    for (int c = c0; c < c1; c++) {
        double *cv = d->vcoef + (size_t)c * VCOEFFS;
        for (int j = 0; j < N; j++)
            cv[j] = d->x[d->order[j / 2] % KEEP][c];
        for (int l = 1; l < N; l++)
            for (int j = N - 1; j >= l; j--) {
                double za = d->z[3 * (j / 2)], zb = d->z[3 * ((j - l) / 2)];
                cv[j] = za == zb ? d->f[d->order[j / 2] % KEEP][c]
                                 : (cv[j] - cv[j - 1]) / (za - zb);
            }
    }
}

/* The interpolants of coordinate i through the nearest 1 .. m nodes at
 * t: p[j] of q and dp[j] its derivative.  Forward sums of the Newton
 * forms, so that they come out on the way. */
static void
partial_sums(const Dense *d, int i, int m, double t, double *p, double *dp)
{
    const double *c = d->coef + (size_t)i * COEFFS;
    double w = 1, dw = 0, sum = 0, dsum = 0;
    for (int j = 0; j < 3 * m; j++) {
        sum += c[j] * w;
        dsum += c[j] * dw;
        dw = dw * (t - d->z[j]) + w;
        w *= t - d->z[j];
        if (j % 3 == 2)
            p[j / 3] = sum, dp[j / 3] = dsum;
    }
}

/* Entry c's interpolants from its values and rates through the nearest 1
 * .. m nodes at t, pv[j]. */
static void
pair_sums(const Dense *d, int c, int m, double t, double *pv)
{
    const double *cv = d->vcoef + (size_t)c * VCOEFFS;
    double w = 1, sum = 0;
    for (int j = 0; j < 2 * m; j++) {
        sum += cv[j] * w;
        w *= t - d->z[3 * (j / 2)];
        if (j % 2 == 1)
            pv[j / 2] = sum;
    }
}

/* Entry c's interpolants at t (with speeds of their own): a coordinate's
 * with its q'', else its value and rate's. */
static void
entry_sums(const Dense *d, int c, int m, double t, double *p)
{
    double dp[WINDOW];
    if (c < d->n && d->second)
        partial_sums(d, c, m, t, p, dp);
    else
        pair_sums(d, c, m, t, p);
}

/* Speeds of their own at t from the coordinates' polynomials of m nodes,
 * W(q)^+ q', into d->vt, and from the derivatives of one node less (same
 * q) into d->vl: 0, or -1 when they cannot be had. */
static int
derived_speeds(Dense *d, int m, double t)
{
    if (!d->to_speeds || !d->second || m < 2)
        return -1;
    for (int i = 0; i < d->n; i++) {
        double p[WINDOW], dp[WINDOW];
        partial_sums(d, i, m, t, p, dp);
        d->qt[i] = p[m - 1], d->dqt[i] = dp[m - 1], d->dql[i] = dp[m - 2];
    }
    return d->to_speeds(d->to_ctx, d->qt, d->dqt, d->vt) ||
                   d->to_speeds(d->to_ctx, d->qt, d->dql, d->vl)
               ? -1
               : 0;
}

/* Each speed's estimate from the derivative, the larger at 0.3 and 0.7 of
 * interval k, into d->esta (infinite where it cannot be had). */
static void
derived_estimates(Dense *d, long k, int m)
{
    double a = node_t(d, k), b = interval_end(d, k);
    for (int j = 0; j < d->nv; j++)
        d->esta[j] = 0;
    for (int s = 0; s < 2; s++) {
        int ok = derived_speeds(d, m, a + (s ? 0.7 : 0.3) * (b - a)) == 0;
        for (int j = 0; j < d->nv; j++)
            d->esta[j] = ok ? fmax(d->esta[j], fabs(d->vt[j] - d->vl[j])) : INFINITY;
    }
}

/* Each speed from whichever of its two interpolants is estimated better. */
static void
choose_speeds(Dense *d)
{
    for (int j = 0; j < d->nv; j++) {
        double *e = d->est + d->n + j;
        d->vsrc[j] = d->esta[j] < *e;
        if (d->vsrc[j])
            *e = d->esta[j];
    }
}

/* The first look: the full interpolant, its error the difference from the
 * one of a node less, the larger at 0.3 and 0.7 of the interval. */
static void
choose_top(Dense *d, long k, int m)
{
    int n = d->n;
    double a = node_t(d, k), b = interval_end(d, k);
    if (d->speeds) { /* entry by entry */
        for (int c = 0; c < d->N; c++) {
            d->lev[c] = m;
            d->est[c] = m > 1 ? 0 : INFINITY;
            for (int s = 0; s < 2 && m > 1; s++) {
                double p[WINDOW];
                entry_sums(d, c, m, a + (s ? 0.7 : 0.3) * (b - a), p);
                d->est[c] = fmax(d->est[c], fabs(p[m - 1] - p[m - 2]));
            }
        }
        derived_estimates(d, k, m);
        choose_speeds(d);
        return;
    }
    for (int i = 0; i < n; i++) {
        d->lev[3 * i] = d->lev[3 * i + 1] = m;
        d->lev[3 * i + 2] = 0;
        d->est[i] = d->est[n + i] = m > 1 ? 0 : INFINITY;
        for (int s = 0; s < 2 && m > 1; s++) {
            double p[WINDOW], dp[WINDOW];
            partial_sums(d, i, m, a + (s ? 0.7 : 0.3) * (b - a), p, dp);
            d->est[i] = fmax(d->est[i], fabs(p[m - 1] - p[m - 2]));
            d->est[n + i] = fmax(d->est[n + i], fabs(dp[m - 1] - dp[m - 2]));
        }
    }
}

/* Of the successive interpolants with 1 .. m nodes, whose differences
 * d[j] = |p[j + 1] - p[j]| are given, the number of nodes of the higher
 * of the two that differ least, and that difference (infinite for a
 * single one) into *err. */
static int
least_pair(const double *d, int m, double *err)
{
    int best = m;
    *err = INFINITY;
    for (int j = 0; j + 1 < m; j++)
        if (d[j] < *err)
            *err = d[j], best = j + 2;
    return best;
}

/* dense_refine with speeds of their own: entry by entry. */
static void
refine_entries(Dense *d)
{
    int m = d->win_m;
    long k = d->win_k;
    double a = node_t(d, k), b = interval_end(d, k);
    for (int c = 0; c < d->N; c++) {
        double dp[WINDOW] = {0};
        for (int s = 1; s <= 3; s++) {
            double p[WINDOW];
            entry_sums(d, c, m, a + 0.25 * s * (b - a), p);
            for (int j = 0; j + 1 < m; j++)
                dp[j] = fmax(dp[j], fabs(p[j + 1] - p[j]));
        }
        d->lev[c] = least_pair(dp, m, &d->est[c]);
    }
    choose_speeds(d); /* the derivative's estimate as the first look made it */
}

void
dense_refine(Dense *d)
{
    int n = d->n, m = d->win_m;
    long k = d->win_k;
    if (d->win_lo < 0 || d->refined)
        return;
    d->refined = 1;
    if (d->speeds) {
        refine_entries(d);
        return;
    }
    fit_pairs(d, m, n, 2 * n);
    double a = node_t(d, k), b = interval_end(d, k);
    for (int i = 0; i < n; i++) {
        double dq[WINDOW] = {0}, ddp[WINDOW] = {0}, dpv[WINDOW] = {0}, edp, epv;
        for (int s = 1; s <= 3; s++) {
            double p[WINDOW], dp[WINDOW], pv[WINDOW];
            double t = a + 0.25 * s * (b - a);
            partial_sums(d, i, m, t, p, dp);
            pair_sums(d, n + i, m, t, pv);
            for (int j = 0; j + 1 < m; j++) {
                dq[j] = fmax(dq[j], fabs(p[j + 1] - p[j]));
                ddp[j] = fmax(ddp[j], fabs(dp[j + 1] - dp[j]));
                dpv[j] = fmax(dpv[j], fabs(pv[j + 1] - pv[j]));
            }
        }
        d->lev[3 * i] = least_pair(dq, m, &d->est[i]);
        d->lev[3 * i + 1] = least_pair(ddp, m, &edp);
        d->lev[3 * i + 2] = least_pair(dpv, m, &epv);
        if (edp <= epv)
            d->lev[3 * i + 2] = 0;
        d->est[n + i] = fmin(edp, epv);
    }
}

void
dense_eval(Dense *d, double t, int final, double *x, double *err)
{
    int n = d->n;
    long k = interval(d, t), lo;
    int m;
    for (long i = k; i <= k + 1 && i < d->count; i++)
        if (node_t(d, i) == t) {
            memcpy(x, d->x[i % KEEP], (size_t)d->N * sizeof *x);
            memset(err, 0, (size_t)d->N * sizeof *err);
            return;
        }
    window(d, k, final, &lo, &m);
    if (lo != d->win_lo || m != d->win_m || k != d->win_k) {
        fit(d, k, lo, m);
        if (d->speeds) /* the speeds, and coordinates without q'' */
            fit_pairs(d, m, d->second ? n : 0, d->N);
        choose_top(d, k, m);
    }
    if (d->speeds) {
        int derived = 0;
        for (int c = 0; c < d->N; c++) {
            double p[WINDOW];
            entry_sums(d, c, m, t, p);
            x[c] = p[d->lev[c] - 1];
            err[c] = d->est[c];
            derived |= c >= n && d->vsrc[c - n];
        }
        if (derived && derived_speeds(d, m, t) == 0)
            for (int j = 0; j < d->nv; j++)
                if (d->vsrc[j])
                    x[n + j] = d->vt[j];
        return;
    }
    for (int i = 0; i < n; i++) {
        double p[WINDOW], dp[WINDOW], pv[WINDOW];
        const int *lev = d->lev + 3 * i;
        partial_sums(d, i, m, t, p, dp);
        if (lev[2])
            pair_sums(d, n + i, m, t, pv);
        x[i] = p[lev[0] - 1];
        x[n + i] = lev[2] ? pv[lev[2] - 1] : dp[lev[1] - 1];
        err[i] = d->est[i];
        err[n + i] = d->est[n + i];
    }
}

double
dense_start(const Dense *d, double t, const double **x, const double **dxdt)
{
    long k = interval(d, t);
    *x = d->x[k % KEEP];
    *dxdt = d->f[k % KEEP];
    return node_t(d, k);
}

void
dense_cubic(double t0, double t1, const double *x0, const double *f0, const double *x1,
            const double *f1, int N, double t, double *x)
{
    double h = t1 - t0, s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    double h01 = 3 * s2 - 2 * s3, h11 = s3 - s2;
    for (int i = 0; i < N; i++)
        x[i] = h00 * x0[i] + h10 * h * f0[i] + h01 * x1[i] + h11 * h * f1[i];
}
