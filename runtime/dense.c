/*
 * dense: Hermite interpolation through the last step ends (dense.h).
 *
 * The polynomial is kept in Newton form over the confluent nodes
 * z = (t_a, t_a, t_a, t_b, t_b, t_b, ...), each node repeated three times
 * for its value, first and second derivative: the divided differences
 * f[z_i..z_i+l] over one repeated node are q, q' and q''/2.  Its
 * coefficients are computed once per window of nodes and coordinate and
 * reused for every output time in the window's interval.
 */
#include "dense.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    WINDOW = 4,          /* nodes per interpolant: k - 1 .. k + 2 */
    KEEP = WINDOW + 1,   /* nodes stored: a window and the next node */
    COEFFS = 3 * WINDOW, /* conditions per coordinate */
};

struct Dense {
    int n;               /* coordinates; states have 2n entries */
    long count;          /* nodes pushed; node i is slot i % KEEP */
    double t[KEEP];
    double *x[KEEP], *f[KEEP];  /* [2n] each */
    long win_lo;         /* the window whose coefficients are in coef, or -1 */
    int win_m;           /* its number of nodes */
    double z[COEFFS];
    double *coef;        /* [n * COEFFS] */
};

Dense *
dense_alloc(int n)
{
    Dense *d = calloc(1, sizeof *d);
    if (!d)
        return NULL;
    d->n = n;
    int ok = (d->coef = calloc((size_t)n * COEFFS, sizeof(double))) != NULL;
    for (int k = 0; k < KEEP; k++) {
        ok &= (d->x[k] = calloc(2 * (size_t)n, sizeof(double))) != NULL;
        ok &= (d->f[k] = calloc(2 * (size_t)n, sizeof(double))) != NULL;
    }
    if (!ok) {
        dense_free(d);
        return NULL;
    }
    dense_clear(d);
    return d;
}

void
dense_free(Dense *d)
{
    if (!d)
        return;
    for (int k = 0; k < KEEP; k++)
        free(d->x[k]), free(d->f[k]);
    free(d->coef);
    free(d);
}

void
dense_clear(Dense *d)
{
    d->count = 0;
    d->win_lo = -1;
}

void
dense_push(Dense *d, double t, const double *x, const double *dxdt)
{
    int slot = (int)(d->count % KEEP);
    d->t[slot] = t;
    memcpy(d->x[slot], x, 2 * (size_t)d->n * sizeof *x);
    memcpy(d->f[slot], dxdt, 2 * (size_t)d->n * sizeof *dxdt);
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
    *lo = k > first ? k - 1 : first;
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

/* Newton coefficients of coordinate i's polynomial over the window. */
static void
fit(Dense *d, long lo, int m)
{
    int n = d->n, N = 3 * m;
    for (int j = 0; j < N; j++)
        d->z[j] = node_t(d, lo + j / 3);
    for (int i = 0; i < n; i++) {
        double *c = d->coef + (size_t)i * COEFFS;
        for (int j = 0; j < N; j++)
            c[j] = d->x[(lo + j / 3) % KEEP][i];
        for (int l = 1; l < N; l++)
            for (int j = N - 1; j >= l; j--) {
                const double *f = d->f[(lo + j / 3) % KEEP];
                if (d->z[j] == d->z[j - l]) /* one node: q' or q''/2 */
                    c[j] = l == 1 ? f[i] : 0.5 * f[n + i];
                else
                    c[j] = (c[j] - c[j - 1]) / (d->z[j] - d->z[j - l]);
            }
    }
    d->win_lo = lo;
    d->win_m = m;
}

void
dense_eval(Dense *d, double t, int final, double *x)
{
    int n = d->n;
    long k = interval(d, t), lo;
    int m;
    for (long i = k; i <= k + 1 && i < d->count; i++)
        if (node_t(d, i) == t) {
            memcpy(x, d->x[i % KEEP], 2 * (size_t)n * sizeof *x);
            return;
        }
    window(d, k, final, &lo, &m);
    if (lo != d->win_lo || m != d->win_m)
        fit(d, lo, m);
    int N = 3 * m;
    for (int i = 0; i < n; i++) {
        const double *c = d->coef + (size_t)i * COEFFS;
        double p = c[N - 1], dp = 0;
        for (int j = N - 2; j >= 0; j--) {
            dp = dp * (t - d->z[j]) + p;
            p = p * (t - d->z[j]) + c[j];
        }
        x[i] = p;
        x[n + i] = dp;
    }
}
