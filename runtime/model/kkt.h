/*
 * kkt: the accelerations of a constrained model and their Jacobian, as
 * pure functions of (t, q, v, p, u) that return a status: what they mean
 * for a user is said by the caller (sim.c), which knows the time and the
 * state.  The mathematics is in kkt.c and docs/mechanics.md.  "q''" is
 * the speeds' rates v' [nv] (eomc.h), n below nv.
 */
#ifndef EOMC_KKT_H
#define EOMC_KKT_H

#include "eomc_model.h"

#include <stddef.h>

typedef struct Kkt Kkt;

enum {
    KKT_OK,
    KKT_SINGULAR,  /* the KKT matrix (or B_h^T) is singular */
    KKT_DEPENDENT, /* elimination: df/dq'' of the dependent coordinates is singular */
    KKT_NEWTON,    /* Newton's method did not converge */
};
/* Newton iterations on a constraint nonlinear in q'', at most. */
enum { KKT_NEWTON_MAX = 50 };

/* NULL when memory runs out; kkt_free is NULL-safe. */
Kkt *kkt_alloc(const eomc_model *m);
void kkt_free(Kkt *k);

/* Rows left out of the solves: drop [nc] (1: dropped; the caller's, read
 * at each solve; NULL: none).  A dropped row's multiplier is 0 and q''
 * solves the kept rows alone (kkt.c); with multipliers only (the
 * simulator refuses to drop rows of an eliminating model). */
void kkt_set_dropped(Kkt *k, const unsigned char *drop);
/* The rows B = df/dq'' [nc*n] of the last solve (its last iterate). */
const double *kkt_rows(const Kkt *k);

/* dense 1: every solve by the KKT system (or elimination), M formed, even
 * where unit loads apply; 0 (the default): by unit loads where they do.
 * The same q''(x) to rounding, but a coordinate whose q'' is 0 reads 0
 * from the dense solve and the rounding of a_f - Y lambda from the loads
 * (sim.c's sim_set_dense, for the analyses). */
void kkt_set_dense(Kkt *k, int dense);
/* Baumgarte's weights: a holonomic constraint's f gets wv_hol g' + wp_hol g
 * and a first-order one's gets wv_first phi.  All zero: off. */
void kkt_set_baumgarte(Kkt *k, double wv_hol, double wp_hol, double wv_first);

/* Constraint c's weights: its f gets *wv vel + *wp pos (0 when off). */
void kkt_baumgarte_weights(const Kkt *k, int c, double *wv, double *wp);

/* q'' into a and the multipliers (kkt_multipliers) at (t, q, v), with
 * u the inputs at t. */
int kkt_accel(Kkt *k, double t, const double *q, const double *v, const double *p,
              const double *u, double *a);
const double *kkt_multipliers(const Kkt *k);

/* The Jacobian of x' = (q', v') at x = (q, v), right after kkt_accel
 * at the same state gave a: its rows of v', rows nq .. nq + n - 1 of dfdx
 * [(nq + n) x (nq + n)] and entries nq .. of dfdt (dudt: the inputs' time
 * derivatives); the caller's the rows of q'.  Either may be NULL. */
int kkt_jacobian(Kkt *k, double t, const double *x, const double *p, const double *u,
                 const double *dudt, const double *a, double *dfdx, double *dfdt);

/* Each constraint at its own level (g, phi, or f at a) into res [nc]. */
void kkt_residuals(Kkt *k, double t, const double *q, const double *v, const double *a,
                   const double *p, const double *u, double *res);

/* Newton's method on a constraint nonlinear in q'' starts from the last
 * solution.  Save it (at a step's start) and go back to it (before each
 * attempt of the step), so that a stage of a rejected attempt, perhaps
 * past a fold where the branch ends, never decides where the next
 * attempt's solves start, nor which root they find. */
void kkt_save_start(Kkt *k);
void kkt_restore_start(Kkt *k);

/* A constraint row B_c = df_c/dq'' has vanished when each of its entries
 * has fallen to this fraction of its largest size in the solves so far:
 * a ratio of like quantities, so it means the same in any units (a row's
 * size at one instant does not: the constraint may be written times any
 * factor). */
#define KKT_VANISHED 1e-6
/* After a failed kkt_accel: the first constraint whose row (as the
 * failed solve left it) has vanished, its largest entry's fraction into
 * *fraction; or -1.  This names the likely cause: two roots of a
 * constraint merging, or a constraint degenerating. */
int kkt_vanished(const Kkt *k, double *fraction);

/* The condition number of the system the last kkt_accel solved (the KKT
 * matrix, or the elimination matrix, as scaled and equilibrated: free of
 * units), estimated from its factorization (la_lu_condition).  (t, q, v,
 * p, u) is that solve's state: after unit loads, which neither form M
 * nor keep a copy of the state, M is formed there and the KKT system
 * factored. */
double kkt_condition(Kkt *k, double t, const double *q, const double *v, const double *p,
                     const double *u);
/* Its near-null direction (la_lu_near_null) into y [n + nc], after
 * kkt_condition with no solve between: over q'' and, with multipliers,
 * lambda (zeros for elimination, and everywhere after a solve by unit
 * loads that kkt_condition has not factored). */
void kkt_near_null(Kkt *k, double *y);
/* The smallest pivot of that factorization (la_lu_pivot): free, and
 * about the inverse of a lower bound on the condition. */
double kkt_pivot(const Kkt *k);

/* "rod (y), cone (z)": the constraints and their dependent coordinates. */
const char *kkt_names(const Kkt *k);
/* The name of constraint c's dependent coordinate (its speed, where the
 * speeds are not the rates) into buf. */
const char *kkt_dependent_name(const eomc_model *m, int c, char *buf, size_t len);

#endif
