/*
 * events: zero crossings of a scene's event functions, found and located.
 *
 * The events of the steps (stepevents.c) evaluate g at every step end.  An
 * event fires in a step where its g crossed zero in its direction; the
 * time is located first on a cheap model of the step (the interpolant),
 * then refined on the true solution (a step from the step's start to the
 * trial time) to within a few units of rounding of t.  Nothing here knows
 * the model: g is a callback.
 */
#ifndef EOMC_EVENTS_H
#define EOMC_EVENTS_H

/* Whether g went from g0 to g1 across zero in direction dir (+1 up, -1
 * down, 0 either): g0 on one side, g1 on the other or exactly 0.  A g0
 * of exactly 0 is never a crossing: it is an event that has just fired
 * (a reset sets it so, stepevents.c), which must leave zero before it
 * can fire again. */
int ev_crossed(int dir, double g0, double g1);

/* A bracket is settled when it is this many units of rounding of t wide:
 * no time between its ends is worth telling apart any more. */
#define EV_SETTLED_ULPS 4

/* g(t) of one event; NAN when it cannot be evaluated there. */
typedef double (*ev_fn)(void *ctx, double t);

/* The time in [a, b] where g crosses zero, given g(a) = ga and g(b) = gb
 * of opposite signs or gb = 0, by the Anderson-Bjorck variant of regula
 * falsi (superlinear, and the bracket always holds the root; bisection
 * when it stalls), starting from the trial time guess when it lies
 * inside (a, b).  It stops when the
 * bracket is within a few units of rounding of t, or after EV_MAX_EVALS
 * evaluations.  Returns the end of the bracket on the far side of the
 * crossing (g there is 0 or of gb's sign: at or just past it), or NAN
 * when g failed; *evals counts the evaluations. */
enum { EV_MAX_EVALS = 100 };
double ev_root(ev_fn g, void *ctx, double a, double ga, double b, double gb, double guess,
               int *evals);

#endif
