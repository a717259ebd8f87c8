/*
 * simimpl.h: the inside of an eomc_sim, shared by sim.c (unconstrained
 * models, integration) and kkt.c (constrained ones).  Not installed.
 */
#ifndef EOMC_SIMIMPL_H
#define EOMC_SIMIMPL_H

#include "eomc.h"

#include <gsl/gsl_permutation.h>
#include <stddef.h>

typedef struct Kkt Kkt;
typedef struct Proj Proj;

struct eomc_sim {
    const eomc_model *m;
    int n, nu;
    double *p;               /* [np] parameter values */
    double *u, *dudt;        /* [nu] inputs at the last time asked */
    double *u_const;         /* [nu] held values, where u_held */
    unsigned char *u_held;   /* [nu] */
    double *M, *h, *a, *Mdiag;            /* [n*n], [n], [n], [n] */
    double *dEdq, *dEdv, *dEdu, *dEdt;    /* residual Jacobians */
    double *col;             /* [n] one right-hand side of M y = b */
    eomc_stats *st;          /* counters of the running integration */
    int progress;            /* show progress (a terminal, > 1 s) */
    double t_end, wall0, next_show;
    int shown;
    size_t errlen;
    char *err;               /* the last error message */
    Kkt *kkt;                /* constrained models: work arrays, multipliers */
    Proj *proj;              /* constrained models: projection's work arrays */
    double *B0, *B1, *fk;    /* constrained: rows of B before and after a step,
                              * [nc*n] each, and f [nc] (scratch) */
    double *x0, *xt, *xerr;  /* [2n] the state before a step, trial states */
    double t0;               /* the time before the step */
    int stabilize;           /* EOMC_STABILIZE_... */
    double alpha, beta;      /* Baumgarte's rates */
};


/* A zeroed array of n doubles (at least one), or NULL. */
double *sim_zeros(size_t n);
/* "t = T: CAUSE; state: q1 = .., q1' = .."; returns EOMC_ENUMERIC. */
int sim_numeric_error(eomc_sim *s, double t, const double *q, const double *v,
                      const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* u and du/dt at t into s->u, s->dudt (held inputs constant). */
void sim_inputs_at(eomc_sim *s, double t);

/* kkt.c: LU of the N x N matrix A in place (GSL), -1 when a pivot is
 * negligible: |U_ii| <= KKT_SINGULAR_TOL max|A_ij|; b = A^-1 b with A so
 * factored; a . b; the largest |x_i|. */
#define KKT_SINGULAR_TOL 1e-13
int kkt_lu_factor(double *A, int N, gsl_permutation *perm);
void kkt_lu_solve(double *A, int N, gsl_permutation *perm, double *b);
double kkt_dot(const double *a, const double *b, int n);
double kkt_max_abs(const double *x, int n);

/* kkt.c: NULL-safe; kkt_alloc returns NULL when memory runs out. */
Kkt *kkt_alloc(const eomc_model *m);
void kkt_free(Kkt *k);
/* q'' (and the multipliers, kept in the Kkt) at (t, q, v): inputs already
 * evaluated into s->u. */
int kkt_accel(eomc_sim *s, double t, const double *q, const double *v, double *a);
/* The Jacobian of x' = f(t, x) for a constrained model. */
int kkt_jacobian(eomc_sim *s, double t, const double *x, double *dfdx, double *dfdt);
const double *kkt_multipliers(const Kkt *k);
/* Each constraint at its own level (g, phi, or f at a). */
void kkt_residuals(eomc_sim *s, double t, const double *q, const double *v,
                   const double *a, double *res);


/* project.c: NULL-safe; proj_alloc returns NULL when memory runs out. */
Proj *proj_alloc(const eomc_model *m);
void proj_free(Proj *j);
/* Whether the model has constraints below acceleration level. */
int proj_levels(const Proj *j);
/* The largest |g| and |g'| or |phi| at (t, q, v). */
double proj_residual(eomc_sim *s, double t, const double *q, const double *v);
/* (q, v) onto the holonomic and velocity-level constraints, in place. */
int proj_apply(eomc_sim *s, double t, double *q, double *v);

#endif
