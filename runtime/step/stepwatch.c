/*
 * stepwatch: the watch over the adaptive steps (stepwatch.h).
 */
#include "stepwatch.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Steps have collapsed when an accepted step is below COLLAPSE_REL of the
 * run's typical step (the geometric mean of its accepted steps, once it
 * has COLLAPSE_AFTER of them): seven orders of magnitude is more than a
 * smooth motion asks (Kepler's orbit at e = 0.9999 runs 100 time units
 * with every method without coming near), and a run that went on at such
 * steps would take ten million times its steps so far to cover as much
 * time again.  A stiff motion's fast phases are brief and take their
 * share of the steps: msbdf on Van der Pol's oscillator at mu = 1e4 and
 * 3e4 (its steps up to ten billion times shorter in a jump than between)
 * comes to 3e-6 of typical at worst. */
#define COLLAPSE_REL 1e-7
enum { COLLAPSE_AFTER = 100 };
/* The steps grind when GRIND_WINDOWS windows of GRIND_WINDOW attempts in
 * a row each rejected more than GRIND_REJECTED of them and advanced the
 * run by less than GRIND_REL of the step at a typical instant of it (the
 * geometric mean of its steps, each weighted by the time it covers) per
 * attempt: the step control no longer finds the step its error model
 * predicts, and the run crawls.  (The pace, not the steps' mean: bsimp
 * alternates long steps and many short ones, and makes its way.)
 * One-step methods grinding reject more than half (rk8pd's steps
 * alternate between one that fails and one that passes); the multistep
 * methods cut their order with the step after a rejection, and reject a
 * third (msbdf on a top in z-x-z angles at theta = 0: 16% to 44% a
 * window, at 1e-5 of the typical instant's step, for 12 million steps).
 * Smooth motion rejects a fifth of its attempts for at most 7 such
 * windows in a row (Kepler's orbit at e = 0.9999 through periapsis).
 * Weighted by steps instead of time, the typical step sank with the steps
 * of the very trouble it was to measure: the top's ten million short
 * steps became typical.  A window that grinds does not count toward the
 * collapse's typical step, which would otherwise sink with it. */
enum { GRIND_WINDOW = 100, GRIND_WINDOWS = 20 };
#define GRIND_REL 1e-3
#define GRIND_REJECTED 0.2

struct StepWatch {
    double log_h;                 /* sum of log(h) over the accepted steps ... */
    long nh;                      /* ... not cut short by t_end, of windows that
                                   * did not grind */
    double sum_h, sum_hlog;       /* sums of h and h log(h) over all of them */
    double h_last;                /* the last such step */
    long tries, fails;            /* attempts and rejections in this window */
    double w_log_h;               /* sum of log(h) over its accepted steps ... */
    long w_nh;                    /* ... how many */
    double w_t0;                  /* the time it started at */
    int grinding;                 /* windows in a row that ground */
};

StepWatch *
stepwatch_alloc(double t0)
{
    StepWatch *w = calloc(1, sizeof *w);
    if (w)
        w->w_t0 = t0;
    return w;
}

void
stepwatch_free(StepWatch *w)
{
    free(w);
}

void
stepwatch_tried(StepWatch *w, int rejected)
{
    w->tries++;
    if (rejected)
        w->fails++;
}

void
stepwatch_accepted(StepWatch *w, double h)
{
    double lh = log(h); /* once: libm's log may set errno, so the compiler calls it each time */
    w->sum_h += h, w->sum_hlog += h * lh;
    w->w_log_h += lh, w->w_nh++, w->h_last = h;
}

/* The run's typical step (COLLAPSE_REL): the geometric mean of its
 * accepted steps. */
static double
typical_step(const StepWatch *w)
{
    if (w->nh > 0)
        return exp(w->log_h / (double)w->nh);
    return w->w_nh ? exp(w->w_log_h / (double)w->w_nh) : 0; /* the first window */
}

/* The step at a typical instant of the run (GRIND_REL): the geometric mean
 * of its accepted steps, each weighted by the time it covers. */
static double
instant_step(const StepWatch *w)
{
    return w->sum_h > 0 ? exp(w->sum_hlog / w->sum_h) : 0;
}

int
stepwatch_check(StepWatch *w, double t, int restarting)
{
    double typ = typical_step(w);
    if (w->nh + w->w_nh >= COLLAPSE_AFTER && w->h_last < COLLAPSE_REL * typ && !restarting)
        return STEPWATCH_COLLAPSE;
    if (w->tries < GRIND_WINDOW)
        return 0;
    double pace = (t - w->w_t0) / (double)w->tries;
    if ((double)w->fails > GRIND_REJECTED * (double)w->tries &&
        pace < GRIND_REL * instant_step(w)) {
        w->grinding++;
    } else {
        w->log_h += w->w_log_h, w->nh += w->w_nh;
        w->grinding = 0;
    }
    w->tries = w->fails = 0, w->w_log_h = 0, w->w_nh = 0, w->w_t0 = t;
    return w->grinding >= GRIND_WINDOWS ? STEPWATCH_GRIND : 0;
}

void
stepwatch_what(const StepWatch *w, int status, char *buf, size_t len)
{
    if (status == STEPWATCH_COLLAPSE)
        snprintf(buf, len, "the steps collapsed to %.3g, %.2g of the run's typical step "
                 "%.3g: the motion is near a singularity, and the likely cause: ",
                 w->h_last, w->h_last / typical_step(w), typical_step(w));
    else
        snprintf(buf, len, "the steps grind: in each of the last %d windows of %d "
                 "attempts more than %g of them were rejected, and the run advanced by "
                 "less than %g of the step at a typical instant of it (%.3g) per attempt "
                 "(steps of %.3g lately); the likely cause: ", GRIND_WINDOWS, GRIND_WINDOW,
                 GRIND_REJECTED, GRIND_REL, instant_step(w), w->h_last);
}
