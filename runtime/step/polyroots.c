/*
 * polyroots: the first real roots of a polynomial on (0, 1], by Collins
 * and Akritas' bisection with Descartes' rule of signs (as heyoka finds
 * events on its Taylor polynomials).
 *
 * For q on (0, 1), the number of sign changes in the coefficients of
 * (x + 1)^d q(1 / (x + 1)) (q's coefficients reversed, then shifted by
 * one) bounds the number of roots of q in (0, 1), and has its parity:
 * 0 means none, 1 exactly one.  Otherwise the interval is halved: q(x/2)
 * on the left half, and that shifted by one on the right, the left first,
 * so that the roots come out in order and the search stops at the second.
 * Coefficients that round to noise only cost more halvings: a sign change
 * that is not a root vanishes in the halves.
 */
#include "polyroots.h"

#include <string.h>

/* q(x) := q(x + 1), in place: Ruffini-Horner's Taylor shift, O(d^2). */
static void
shift_one(double *q, int d)
{
    for (int i = 0; i < d; i++)
        for (int j = d - 1; j >= i; j--)
            q[j] += q[j + 1];
}

/* The sign changes of the coefficients of (x + 1)^d q(1 / (x + 1)). */
static int
variations(const double *q, int d)
{
    double m[POLY_MAX_DEGREE + 1];
    for (int j = 0; j <= d; j++)
        m[j] = q[d - j];
    shift_one(m, d);
    int v = 0, last = 0;
    for (int j = 0; j <= d; j++) {
        int s = (m[j] > 0) - (m[j] < 0);
        if (s && last && s != last)
            v++;
        if (s)
            last = s;
    }
    return v;
}

typedef struct Found {
    int n;          /* roots so far */
    double end1;    /* where the first one's interval ends */
    double cut;     /* past the first, before the second */
} Found;

static void
found(Found *f, double lo, double hi)
{
    if (f->n++ == 0)
        f->end1 = hi;
    else if (f->n == 2)
        f->cut = 0.5 * (f->end1 + lo);
}

/* The roots of q, given on (0, 1), in (a, a + w), in order. */
static void
isolate(const double *q, int d, double a, double w, int depth, Found *f)
{
    if (f->n >= 2)
        return;
    int v = variations(q, d);
    if (v == 0)
        return;
    if (v == 1 || depth >= POLY_MAX_DEPTH) {
        found(f, a, a + w);
        return;
    }
    double half[POLY_MAX_DEGREE + 1], scale = 1;
    for (int j = 0; j <= d; j++, scale *= 0.5) /* q(x/2): the left half */
        half[j] = q[j] * scale;
    isolate(half, d, a, 0.5 * w, depth + 1, f);
    shift_one(half, d); /* q(x/2 + 1/2): the right half */
    if (half[0] == 0) /* a root at the middle */
        found(f, a + 0.5 * w, a + 0.5 * w);
    isolate(half, d, a + 0.5 * w, 0.5 * w, depth + 1, f);
}

int
poly_first_roots(const double *c, int d, double *cut)
{
    double q[POLY_MAX_DEGREE + 1];
    int lo = 0;
    while (lo < d && c[lo] == 0) /* a root at 0 is not one of (0, 1] */
        lo++;
    d -= lo;
    memcpy(q, c + lo, (size_t)(d + 1) * sizeof *q);
    while (d > 0 && q[d] == 0)
        d--;
    Found f = {0};
    if (d > 0) {
        double at1 = 0;
        for (int j = d; j >= 0; j--)
            at1 += q[j];
        isolate(q, d, 0, 1, 0, &f);
        if (f.n < 2 && at1 == 0) /* 1 itself, which the open interval left out */
            found(&f, 1, 1);
    }
    *cut = f.n >= 2 ? f.cut : 1;
    return f.n < 2 ? f.n : 2;
}
