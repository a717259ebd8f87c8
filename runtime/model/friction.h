/*
 * friction: dry friction's modes and stuck coordinates in doubles
 * (stick.h's functions, fric_ here): q'' with the stuck items' speeds
 * held, the forces that hold them, the stick switches' functions, the
 * modes at a state and at a flip.  Knows the model, not the simulator:
 * statuses here, messages in sim.c.
 */
#ifndef EOMC_FRICTION_H
#define EOMC_FRICTION_H

#include "eomc.h"

/* stick.h's statuses: what a solve or a choice of modes came to */
#define STICK_STATUS_DEFINED
enum { STICK_OK, STICK_PIVOT, STICK_NEGATIVE, STICK_START, STICK_SPANNED };

typedef struct fric_Work Fric;

/* For a model with nfric > 0; NULL when memory runs out. */
Fric *fric_alloc(const eomc_model *m, const eomc_model *x);
void fric_free(Fric *w);
/* Whether an item is stuck in the modes of u (the model's u, modes after
 * the inputs). */
int fric_any(const Fric *w, const double *u);
/* The item whose stick switch is mode k, or -1. */
int fric_item_stick(const Fric *w, int k);
/* The bounds F at (t, q, v) (fric_bound_of); STICK_NEGATIVE where one is
 * below 0. */
int fric_bounds(Fric *w, double t, const double *q, const double *v, const double *p,
                const double *u);
/* q'' [nv] at (t, q, v), the stuck speeds held at 0; STICK_OK,
 * STICK_PIVOT or STICK_NEGATIVE (fric_bad says which). */
int fric_solve(Fric *w, double t, const double *q, const double *v, const double *p,
               const double *u, double *a);
/* b = -M^-1 b [nv] with the stuck speeds held, after fric_solve. */
void fric_solve_neg(const Fric *w, double *b);
/* The stick switches' functions at (t, q, v) into sw [nmode] (NAN,
 * and the failure returned, where the holding forces cannot be solved). */
int fric_functions(Fric *w, double t, const double *q, const double *v, const double *p,
                   const double *u, double *sw);
/* The modes of the items at (t, q, v) alone (stick.h's settle).
 * STICK_OK or a failure (STICK_START: no modes follow). */
int fric_settle(Fric *w, double t, const double *q, const double *v, const double *p,
                double *u);
/* Mode k flips to on at (t, q, v) in a run (stick.h's flip): v's stuck
 * speed set to 0 where an item sticks. */
int fric_flip(Fric *w, int k, int on, double t, const double *q, double *v, const double *p,
              double *u);
/* The run's span (t_end - t0): how far a choice on its edge looks ahead
 * (stick.h's unstick_rows). */
void fric_span(Fric *w, double span);
/* What the last failure names (a speed, an item), the last solve's
 * bounds, holding forces and least relative pivot. */
int fric_bad(const Fric *w);
double fric_bound_of(const Fric *w, int j);
double fric_phi(const Fric *w, int j);
double fric_pivot(const Fric *w);
/* The condition of the stuck rows' system at the last solve (G balanced by
 * its diagonal: the rows' directions alone; its largest eigenvalue over
 * the least the solve counts), 1 where fewer than two rows count; near
 * [nf]: each item's part in the least direction, of the largest part (0
 * where not stuck).  Rows that part by little more than rounding (a box's
 * two corners on one edge as it starts to turn) give a large one: their
 * holding forces grow as it does, and they let go where their rank first
 * counts them apart, a place rounding sets. */
double fric_condition(Fric *w, double *near);

#endif
