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

/* The bracket is settled when it is this many units of rounding of t wide:
 * no representable time between its ends decides anything more. */
#define SETTLED_ULPS 4

double
ev_root(ev_fn g, void *ctx, double a, double ga, double b, double gb, double guess,
        int *evals)
{
    *evals = 0;
    if (gb == 0)
        guess = NAN; /* nothing to refine below b... */
    int side = 0; /* which end stayed last time (Illinois halves its g) */
    while (gb != 0 && *evals < EV_MAX_EVALS) {
        double width = fabs(b - a), scale = fmax(fabs(a), fabs(b));
        if (width <= SETTLED_ULPS * DBL_EPSILON * scale)
            break;
        double t;
        if (*evals == 0 && guess > fmin(a, b) && guess < fmax(a, b))
            t = guess;
        else
            t = b - gb * (b - a) / (gb - ga); /* the secant through the bracket */
        if (!(t > fmin(a, b) && t < fmax(a, b))) /* rounding: bisect */
            t = 0.5 * (a + b);
        double gt = g(ctx, t);
        (*evals)++;
        if (isnan(gt))
            return NAN;
        if (gt == 0) {
            b = t, gb = 0;
            break;
        }
        if (sign(gt) == sign(gb)) { /* the root is in [a, t] */
            b = t, gb = gt;
            if (side == -1)
                ga *= 0.5;
            side = -1;
        } else { /* in [t, b] */
            a = t, ga = gt;
            if (side == 1)
                gb *= 0.5;
            side = 1;
        }
    }
    return b;
}
