/*
 * simimpl.h: the inside of an eomc_sim, for the layers above sim.c
 * (integrate.c, reference.c, report.c).  Not installed.
 */
#ifndef EOMC_SIMIMPL_H
#define EOMC_SIMIMPL_H

#include "eomc.h"
#include "kkt.h"
#include "linalg.h"
#include "project.h"

#include <stddef.h>

/* The generated solve reports its smallest balanced pivot at every
 * PIVOT_EVERY-th call (a power of 2): several per step of any method. */
enum { PIVOT_EVERY = 4 };

struct eomc_sim {
    const eomc_model *m;
    int n, nu;
    double *p;               /* [np + nd] parameter values, then derive's */
    double *u, *dudt;        /* [nu] inputs at the last time asked */
    double *u_const;         /* [nu] held values, where u_held */
    unsigned char *u_held;   /* [nu] */
    double *M, *h, *a, *Mrel;             /* [n*n], [n], [n], [n] pivots / M_kk */
    size_t *Mperm;           /* [n] M's pivot order (la_ldlt_factor) */
    double *arow;            /* [n] the accelerations of a row (eomc_sim_outputs) */
    double *dEdq, *dEdv, *dEdu, *dEdt;    /* residual Jacobians */
    double *col;             /* [n] one right-hand side of M y = b */
    double *fk;              /* [nc] f (scratch) */
    LaLu *mlu;               /* M, balanced, for its condition (sim_condition) */
    double *cy, *cd;         /* [n + nc] its near-null direction, [n] the balance */
    char *cwhat;             /* sim_condition_what's text */
    double pivot;            /* the smallest balanced pivot since sim_take_pivot */
    unsigned solves;         /* generated solves so far (PIVOT_EVERY) */
    size_t errlen;
    char *err;               /* the last error message */
    Kkt *kkt;                /* constrained models: the solve and multipliers */
    Proj *proj;              /* constrained models: projection */
    int stabilize;           /* EOMC_STABILIZE_... */
    double alpha, beta;      /* Baumgarte's rates */
};

/* A zeroed array of n doubles (at least one), or NULL. */
double *sim_zeros(size_t n);
/* Whether every x[i] is finite. */
int sim_all_finite(const double *x, int n);
/* Seconds of the process's CPU time (cpu), or of a monotonic wall clock. */
double sim_seconds(int cpu);
/* "t = T: CAUSE; state: q1 = .., q1' = .."; returns EOMC_ENUMERIC. */
int sim_numeric_error(eomc_sim *s, double t, const double *q, const double *v,
                      const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* The message of a usage error; returns EOMC_EUSAGE. */
int sim_usage_error(eomc_sim *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* The usage error of `what` (a method, --linearize) on a model built
 * without its Jacobian; returns EOMC_EUSAGE. */
int sim_no_jacobian(eomc_sim *s, const char *what);
/* u and du/dt at t into s->u, s->dudt (held inputs constant). */
void sim_inputs_at(eomc_sim *s, double t);
/* Whether the model has a holonomic or first-order constraint. */
int sim_has_levels(const eomc_sim *s);
/* The rows of B = df/dq'' at (t, x) into B [nc*n]; -1 when x is not
 * finite or the accelerations (needed when f is not affine) fail. */
int sim_constraint_rows(eomc_sim *s, double t, const double *x, double *B);
/* The largest |g|, |g'| or |phi| at (t, q, v), 0 without such
 * constraints. */
double sim_level_residual(eomc_sim *s, double t, const double *q, const double *v);
/* EOMC_OK when (q, v) is on its holonomic and velocity-level constraints
 * (eomc_sim_inconsistency at most EOMC_INCONSISTENT), else EOMC_ENUMERIC
 * with the message "t = T: WHAT: the state is off 2 constraints, worst
 * first: c1 (velocities: its residual is 1 of the size of its terms), c2
 * (positions: 0.3); state: ...", every one it violates. */
int sim_off_constraints(eomc_sim *s, double t, const double *q, const double *v,
                        const char *what);
/* The condition number of the linear system whose solution is q'' at
 * (t, q, v): the mass matrix balanced by its diagonal (which makes it free
 * of the coordinates' units), or the scaled KKT or elimination matrix;
 * NAN when it cannot be had (the solve failed). */
double sim_condition(eomc_sim *s, double t, const double *q, const double *v);
/* What the nearly singular direction of the system sim_condition last
 * factored mixes: "the mass matrix (coordinates th1, th2)"; valid until
 * the next call. */
const char *sim_condition_what(eomc_sim *s);
/* The smallest pivot of the solves for q'' since the last call, balanced
 * as sim_condition balances (1 when none): its inverse is about a lower
 * bound on their condition, had for free from their factorizations. */
double sim_take_pivot(eomc_sim *s);

#endif
