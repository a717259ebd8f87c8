/*
 * dense: the values between steps.  Output rows are not step ends: the
 * driver steps as the tolerance allows and asks this interpolant for the
 * state at each output time.
 *
 * Each accepted step end is a node with the state x = (q, q') and its
 * derivative x' = (q', q'').  Between nodes k and k + 1 the coordinates
 * are a polynomial through q, q' and q'' at the nodes nearest them among
 * k - 2 .. k + 2 (Hermite interpolation of degree up to 14: error
 * O(h^15) for smooth motion; the degree is chosen per coordinate, see
 * dense.c), and the velocities are its derivative.  A cubic through the two ends of a step only would be off
 * by far more than a high-order method's error: on chain5 with rk8pd at
 * 1e-10, 2.7e-6 against 1.3e-10 at the step ends.  Where steps are so long
 * that even this is not good enough (bsimp takes 17 steps for chain5 over
 * 10 s), its error estimate says so, and the driver computes the row by a
 * step of its own instead (integrate.c).
 */
#ifndef EOMC_DENSE_H
#define EOMC_DENSE_H

typedef struct Dense Dense;

/* For states of n coordinates and their rates (x of 2n, nv = 0), or of n
 * coordinates and nv speeds that are not their rates (x of n + nv: each
 * entry is then interpolated from its value and rate alone, dense.c);
 * NULL when memory runs out. */
Dense *dense_alloc(int n, int nv);
void dense_free(Dense *d);
/* With speeds of their own: how to turn the coordinates' rates qd [n] at
 * q into speeds v [nv] (least squares, v = W(q)^+ qd; 0, or nonzero where
 * it cannot), for a speed interpolated as the derivative of the
 * coordinates' polynomials where that is estimated better (dense.c). */
void dense_set_speeds(Dense *d, int (*to_speeds)(void *ctx, const double *q,
                                                  const double *qd, double *v), void *ctx);
/* Forget every node (a new run). */
void dense_clear(Dense *d);
/* A node at t, after the last one: x [N] and x' [N] (N = 2n, or n + nv);
 * with speeds of their own, qdd [n] the coordinates' second derivatives
 * there, or NULL when they cannot be had (then the coordinates too are
 * interpolated from their values and rates alone). */
void dense_push(Dense *d, double t, const double *x, const double *dxdt, const double *qdd);
/* Whether the value at t is settled: t lies between stored nodes and the
 * nodes that decide it are all there (or `final`: no more will come). */
int dense_ready(const Dense *d, double t, int final);
/* The state at t (dense_ready), into x [N]; exactly a node's state at
 * its own time.  err [N]: an estimate of its error, entry by entry (the
 * difference from the interpolant of one node less, which is one order
 * less accurate; infinite with a single node). */
void dense_eval(Dense *d, double t, int final, double *x, double *err);
/* A closer look at the interval of the last dense_eval, for when its
 * estimate was not good enough: the interpolants of fewer nodes too (see
 * dense.c).  dense_eval at the same interval then uses what it found. */
void dense_refine(Dense *d);
/* The node at the start of the interval holding t (dense_ready): its
 * time, state and derivative, for a step from there to t. */
double dense_start(const Dense *d, double t, const double **x, const double **dxdt);
/* The time of the last node (-inf without one). */
double dense_last(const Dense *d);
/* The cubic Hermite interpolant of one step alone, through (x0, f0) at t0
 * and (x1, f1) at t1, at t: x [N].  Cheap, for where a step's own ends
 * are enough (an event's first look, eomc_step_eval). */
void dense_cubic(double t0, double t1, const double *x0, const double *f0,
                 const double *x1, const double *f1, int N, double t, double *x);

#endif
