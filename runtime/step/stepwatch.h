/*
 * stepwatch.h: the watch over the adaptive steps, for the step layer
 * (evolve.c): whether they collapsed (an accepted step far below the
 * run's typical one) or grind (most attempts rejected, the run crawling).
 * It sees only the attempts and the accepted steps' sizes, which the step
 * layer reports; its sums are stepwatch.c's alone.  Not installed, and
 * nothing of it leaves the library (runtime/meson.build).
 */
#ifndef EOMC_STEPWATCH_H
#define EOMC_STEPWATCH_H

#include <stddef.h>

/* stepwatch_check's statuses, in the step layer's range (evolve.h), which
 * passes them on. */
enum { STEPWATCH_COLLAPSE = -1001, STEPWATCH_GRIND = -1002 };

typedef struct StepWatch StepWatch;

/* The watch of a run from t0; NULL when memory runs out. */
StepWatch *stepwatch_alloc(double t0);
void stepwatch_free(StepWatch *w);
/* An attempt at a step, rejected or not. */
void stepwatch_tried(StepWatch *w, int rejected);
/* An accepted step of h, not cut short by t_end. */
void stepwatch_accepted(StepWatch *w, double h);
/* After an accepted step, the run at t: STEPWATCH_COLLAPSE,
 * STEPWATCH_GRIND, or 0.  The steps after a reset (restarting) are small
 * on purpose, and not watched for a collapse. */
int stepwatch_check(StepWatch *w, double t, int restarting);
/* What STEPWATCH_COLLAPSE or STEPWATCH_GRIND found, into buf: a message
 * up to "the likely cause: ", which the caller completes. */
void stepwatch_what(const StepWatch *w, int status, char *buf, size_t len);

#endif
