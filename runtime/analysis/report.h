/*
 * report: what accuracy costs in time.  One model run with many methods,
 * tolerances and fixed steps, each measured against a reference solution
 * (its error at the output times), timed, and shown as a table, a CSV, a
 * work-precision plot (gnuplot) and the cheapest setting for a target
 * error.  The simulator's --work-precision, and so `eomc accuracy`.
 */
#ifndef EOMC_REPORT_H
#define EOMC_REPORT_H

#include "eomc.h"

typedef struct Report {
    eomc_sim *sim;
    eomc_run_opts base;          /* span, rows, rtol/atol of fixed-step Newton
                                  * iterations, max_steps (0: REPORT_MAX_STEPS) */
    const double *x0;            /* the initial state [nq + nv] */
    const eomc_reference *ref;
    const char *const *methods;  /* NULL-terminated */
    const double *tolerances;    /* rtol = atol of the adaptive runs */
    int ntolerances;
    const double *steps;         /* fixed steps */
    int nsteps;
    int steps_given;             /* --steps: fixed runs of every one-step method,
                                  * not only of those usually run so */
    const char *csv, *plot;      /* files, or NULL */
    const char *errors;          /* --errors FILE (each run's errors by component), or NULL */
    double target;               /* error_max wanted, or NAN */
    const char *prog;            /* for messages */
    const char *setting;         /* how the runs are set up, for the title */
} Report;

/* Steps of one run at most, unless --max-steps says otherwise: a run
 * needing more says so in its row, and the method's tighter tolerances
 * are not tried. */
#define REPORT_MAX_STEPS 100000

/* The whole report: the table on stdout, then the files.  Returns 0, or
 * an exit status (2: a file could not be written, 3: no run succeeded). */
int report_run(const Report *r);

#endif
