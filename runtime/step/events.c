/*
 * events: crossings and their location (events.h).
 */
#include "events.h"

#include <float.h>
#include <math.h>

static int sign(double x) { return (x > 0) - (x < 0); }

int
ev_crossed(int dir, double g0, double g1)
{
    if (g0 == 0 || isnan(g0) || isnan(g1))
        return 0;
    if (sign(g1) == sign(g0))
        return 0;
    return dir == 0 || dir == (g0 < 0 ? 1 : -1);
}


double
ev_root(ev_fn g, void *ctx, double a, double ga, double b, double gb, double guess,
        int *evals)
{
    *evals = 0;
    int post = sign(gb); /* the side the crossing goes to (0: b is the root) */
    if (gb == 0)
        return b;
    /* Anderson-Bjorck: secant steps on a bracket whose latest point is b;
     * when the new point falls on b's side again, the other end's g is
     * scaled down so that the next secant reaches across.  A bisection
     * whenever three steps did not halve the bracket keeps it safe. */
    double width0 = fabs(b - a);
    int since = 0;
    while (*evals < EV_MAX_EVALS) {
        double lo = fmin(a, b), hi = fmax(a, b);
        if (hi - lo <= EV_SETTLED_ULPS * DBL_EPSILON * fmax(fabs(lo), fabs(hi)))
            break;
        double t;
        if (*evals == 0 && guess > lo && guess < hi)
            t = guess;
        else if (since >= 3 && hi - lo > 0.5 * width0)
            t = 0.5 * (lo + hi), since = 0, width0 = hi - lo;
        else
            t = b - gb * (b - a) / (gb - ga);
        /* never closer to an end than the bracket is to settling: a point
         * next to the root at one end is followed by one just across it,
         * not by a crawl from the other end (Brent's minimum step) */
        double step = EV_SETTLED_ULPS * DBL_EPSILON * fmax(fabs(lo), fabs(hi));
        if (isnan(t))
            t = 0.5 * (lo + hi);
        else if (t - lo < step)
            t = fmin(lo + step, 0.5 * (lo + hi));
        else if (hi - t < step)
            t = fmax(hi - step, 0.5 * (lo + hi));
        double gt = g(ctx, t);
        (*evals)++;
        if (isnan(gt))
            return NAN;
        if (gt == 0)
            return t;
        if (sign(gt) == sign(gb)) {
            double m = 1 - gt / gb;
            ga *= m > 0 ? m : 0.5;
        } else {
            a = b, ga = gb;
        }
        b = t, gb = gt;
        if (++since >= 3 && fabs(b - a) <= 0.5 * width0)
            since = 0, width0 = fabs(b - a);
    }
    return sign(gb) == post ? b : a;
}
