/*
 * taylor.h: Taylor's method (--method taylor), for the step layer
 * (evolve.c): the series of the solution through a state, to an order
 * the tolerance sets, from the model's generated `taylor` function (the
 * series of M and h, eomc_model.h) and one factorization of M per step;
 * the step from the decay of the last coefficients (Jorba and Zou); the
 * step's polynomial as its dense output.  Not installed.
 */
#ifndef EOMC_TAYLOR_STEP_H
#define EOMC_TAYLOR_STEP_H

#include "eomc.h"

typedef struct Taylor Taylor;

/* The highest order: rtol 1e-16 asks for 20; this leaves room for the
 * extended-precision reference's tighter tolerances (reftaylor.c) ... */
enum { TAYLOR_MAX_ORDER = 40 };
/* ... and the lowest: a polynomial of degree 1 is Euler's method, whose
 * step rule would have no second coefficient to compare. */
enum { TAYLOR_MIN_ORDER = 2 };
/* Jorba and Zou's safety factor, exp(-0.7 / (p - 1)), has this 0.7. */
#define TAYLOR_SAFETY 0.7
/* Rounds of the step and the components' scales over it settling each
 * other (each moves the step by a p-th root of the round before's
 * change). */
enum { TAYLOR_SCALE_ROUNDS = 2 };
/* The order for the relative tolerance rtol > 0 (Jorba and Zou's
 * ceil(-ln(rtol)/2 + 1), within those bounds). */
int taylor_order_for(double rtol);

/* Whether s's model can run Taylor's method with o: EOMC_OK, or
 * EOMC_EUSAGE with the message saying why not (no generated series and
 * why, an input that is not held constant, rtol not positive). */
int taylor_check(eomc_sim *s, const eomc_run_opts *o);
/* For o's tolerances (taylor_check passed); NULL when memory runs out. */
Taylor *taylor_alloc(eomc_sim *s, const eomc_run_opts *o);
void taylor_free(Taylor *tp);
/* The series of the motion through (t0, x) [2nq], to the order the
 * tolerance sets, and the step it allows (at most hmax): *h.  The
 * polynomial stays until the next call (taylor_eval).  0, or -1 when M
 * at x is not safely positive definite or a coefficient is not finite
 * (the caller says so: eomc_sim_accel at x names the cause of the
 * first). */
int taylor_series(Taylor *tp, double t0, const double *x, double hmax, double *h);
/* The last series' value at t0 + tau into x [2nq]: Horner's rule on the
 * change, added to the start with what the additions of the steps before
 * lost (taylor_advance). */
void taylor_eval(const Taylor *tp, double tau, double *x);
/* The same for the step's end, which the next series starts from: the
 * rounding of this addition is kept (Kahan's compensated summation), so
 * that a long run's state does not drift by half an ulp a step; it holds
 * while the next series starts from x. */
void taylor_advance(Taylor *tp, double tau, double *x);
/* An estimate of the error of the last series' value at t0 + h, per
 * component, into err [2nq]: its last term, |x_p| h^p, which bounds the
 * ones left out where the step rule holds (they shrink by e^-2 or more
 * each). */
void taylor_error(const Taylor *tp, double h, double *err);
/* Where a step of h from the last series' start must end so that no
 * event's g crosses zero twice in it: before the second root of g's
 * series in (0, h] (polyroots.h), of any event; h when none has two.
 * Both crossings of a pair that fit in one step leave g with the same
 * sign at its ends, where the events of the steps (stepevents.h) look. */
double taylor_event_cut(const Taylor *tp, double h);
/* EOMC_LANES runs' series by one call of the model's taylor_run4 (a
 * sweep's batch, integrate.c): lane l's through (t0[l], x[l]) for tp[l]
 * (NULL: an idle lane), which taylor_series takes where it is asked for
 * that very series (the same t0 and x, to the bit; else it computes its
 * own), with its step where the series continues the last one's motion
 * (step_size's, the lanes side by side).  The bits are those
 * taylor_series would compute.  For one set of
 * run options (one order), NULL where the model has no taylor_run4 for
 * it or memory runs out. */
typedef struct TaylorLanes TaylorLanes;
TaylorLanes *taylor_lanes_alloc(const eomc_model *m, const eomc_run_opts *o);
void taylor_lanes_free(TaylorLanes *b);
/* 0; -1 where nothing was filled (the order is above those taylor_run4
 * writes out, a lane of another model or order, memory ran out): each
 * lane then computes its own, and the next fills would fail as well. */
int taylor_lanes_fill(TaylorLanes *b, Taylor *const *tp, const double *t0,
                      const double *const *x);
/* The last series' start and order. */
double taylor_start(const Taylor *tp);
int taylor_order(const Taylor *tp);

#endif
