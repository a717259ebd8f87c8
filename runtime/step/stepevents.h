/*
 * stepevents.h: the scene's events in the steps, for the step layer
 * above (evolve.c).  After each accepted step, the events that fired in
 * it are located (events.h) and reported through on_event, and the first
 * `stop` or `set` among them ends the step; a `set` event's reset is
 * applied here, and watched (an event held at g = 0 until it leaves it,
 * events that accumulate).  The events' state (g at the step's ends, the
 * held events, the resets so far) is stepevents.c's alone; the step's
 * state stays evolve.c's, which hands this layer a step's ends
 * (StepevSpan) and the two things it needs of the motion as callbacks
 * (StepevMotion), so that the calls go one way.  Not installed, and
 * nothing of it leaves the library (runtime/meson.build).
 */
#ifndef EOMC_STEPEVENTS_H
#define EOMC_STEPEVENTS_H

#include "eomc.h"

/* Failure statuses of stepev_check and stepev_reset besides GSL's, in
 * the step layer's range (evolve.h), which passes them on; stepev_error
 * says what they mean. */
enum { STEPEV_ACCUMULATE = -1003, STEPEV_RETURNED = -1005 };

/* Events accumulate (a bouncing ball coming to rest, Zeno's paradox) when
 * a `set` event fires within STEPEV_ACCUMULATE_REL of the time span of
 * the one before: their times are no longer resolved (the steps between
 * them would be below the collapse limit of any run), and the next ones
 * come ever faster.  A switch chatters (Zeno) when STEPEV_CHATTER_FLIPS
 * of its flips in a row each come within that share of the span after
 * the one before.  One that close can be two events' doing, located apart
 * by rounding (a body's mirror images touching at once, each moving the
 * loads a group of stuck points shares); a chatter goes on without end.
 * The reference (analysis/refswitch.c) stops where the run does. */
#define STEPEV_ACCUMULATE_REL 1e-9
#define STEPEV_CHATTER_FLIPS 4

/* The action of index k (stepev_action): the scene's EOMC_EVENT_... for
 * k < nevent, else a switch of the model's (nevent + j: switch j), which
 * ends the step as a `set` does and flips mode j (stepev_reset). */
enum { STEPEV_SWITCH = 100 };

/* The motion, from the step layer. */
typedef struct StepevMotion {
    /* x' at (t, x) into f (gsl_odeiv2_system's function): GSL_SUCCESS or
     * a failure status */
    int (*rate)(double t, const double *x, double *f, void *ctx);
    /* The state at t into x by a step of its own from (tk, xk, fk)
     * (evolve_side): GSL_SUCCESS or a failure status */
    int (*side)(void *ctx, double tk, const double *xk, const double *fk, double t,
                double *x);
    void *ctx;
    /* the steps already end between any two crossings of an event
     * (Taylor's method cuts them at the roots of g's series): no pair
     * of crossings can hide inside one, and none is looked for */
    int steps_split_pairs;
} StepevMotion;

/* An accepted step: the state x and x' at t0 and at t1. */
typedef struct StepevSpan {
    double t0, t1;
    const double *x0, *f0, *x1, *f1;
} StepevSpan;

/* What ends a step (stepev_check). */
typedef struct StepevHit {
    int k;               /* the `stop` or `set` event that ends it at t, or -1 */
    int status;          /* on_event's nonzero status, which stops the run at
                          * (t, x) instead; else EOMC_OK */
    double t;
    const double *x;     /* [nx] the state there: this layer's, valid until
                          * its next call */
} StepevHit;

typedef struct StepEvents StepEvents;

int stepev_action(const StepEvents *v, int k);

/* The events of s's model for a run of o, counted in st (o and st are
 * kept); NULL when memory runs out. */
StepEvents *stepev_alloc(eomc_sim *s, const eomc_run_opts *o, eomc_stats *st,
                         StepevMotion motion);
void stepev_free(StepEvents *v);
/* g at the run's start (t, x): an event at exactly 0 there waits to
 * leave it. */
void stepev_start(StepEvents *v, double t, const double *x);
/* After the step sp (its arrays are read during the call only): the
 * events that fired in it, in time order, each reported with the state
 * there.  An event whose g has one sign at both ends of a step may still
 * have crossed twice, there and back: where g heads for 0 at the step's
 * start and away at its end, g on the solution where it turns decides,
 * and each crossing found fires as any other (unless the motion says its
 * steps split such pairs already).  The first `stop` or `set` event, or an on_event that returned
 * nonzero, ends the step: *hit says which and where; a `record` event
 * after it in the same step never happened.  GSL_SUCCESS or a failure
 * status. */
int stepev_check(StepEvents *v, const StepevSpan *sp, StepevHit *hit);
/* Event k's reset at t, of x [nx] in place, after the rows up to it were
 * written; f [nx] is x' there before it and becomes x' after.  The event
 * is held until its g leaves zero, unless the reset passes through it.
 * GSL_SUCCESS or a failure status. */
int stepev_reset(StepEvents *v, int k, double t, double *x, double *f);
/* The inputs jumped at t (a sampled controller's sample), x [nx] as it
 * is: f [nx] gets x' with the new inputs, and the switches whose
 * functions they moved across their kinks flip at t (told as any flip,
 * settled as after one); g at the next step's start is taken here.  An
 * event of the scene whose function reads an input sees the new value
 * from here on, but is not fired by the jump itself.  GSL_SUCCESS or a
 * failure status. */
int stepev_jump(StepEvents *v, double t, double *x, double *f);
/* The time from the `set` event before the last one to the last. */
double stepev_gap(const StepEvents *v);
/* The message of STEPEV_ACCUMULATE or STEPEV_RETURNED, the run having
 * stopped at (t, x); returns EOMC_ENUMERIC. */
int stepev_error(const StepEvents *v, int status, double t, const double *x);

#endif
