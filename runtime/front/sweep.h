/*
 * sweep: one simulation per parameter set, for --sweep and --sweep-file,
 * on the threads of one machine and, when the simulator was built with
 * --mpi, on the ranks of an MPI job (eomc_set_parallel).  The summary has
 * one row per run, in sweep order, whatever the threads or ranks: each run
 * is computed alone from its own parameters, and rank 0 writes the rows in
 * order.
 */
#ifndef EOMC_SWEEP_H
#define EOMC_SWEEP_H

#include "eomc.h"

#include <stdio.h>

typedef struct Sweep {
    const eomc_model *m;
    const eomc_run_opts *run;   /* every run's options */
    /* A fresh simulator set up as the command line says (its --set, its
     * --stabilize), before the swept parameters; EOMC_OK or a status. */
    int (*prepare)(void *ctx, eomc_sim *sim);
    /* The run's initial state into x [2nq] (the spec's, with the run's
     * parameters, then --init); EOMC_OK or a status. */
    int (*initial)(void *ctx, eomc_sim *sim, double *x);
    void *ctx;
    int nparam;
    const char *const *names;   /* [nparam] the swept parameters */
    long nruns;
    const double *values;       /* [nruns * nparam], in sweep order */
    int threads;                /* >= 1 */
    int batch;                  /* EOMC_LANES: Taylor's runs that many at a time, where
                                 * the model has the series for it; else 1 */
    const char *prog;           /* for messages */
    /* Instead of integrating (NULL: integrate), each run's own ncells
     * cells, computed from its initial state x: ",a,b,..." into *text
     * (malloc'd), EOMC_OK or a status with the simulator's message.  The
     * header names them after the swept parameters with columns
     * ("re1,im1,..."). */
    int (*cells)(void *ctx, eomc_sim *sim, double *x, char **text);
    const char *columns;
    int ncells;
} Sweep;

/* Every run, and the summary CSV on f (written by rank 0 only): the swept
 * parameters' names, status, t, the coordinates, the velocities as name',
 * the outputs at the end.  A failed run's row has its error as status and
 * empty cells.  With cells, the swept parameters' names and the columns,
 * no status: a failed run's cells are empty, and the warning says why.
 * Returns EOMC_OK (failed runs included), or an exit status when the
 * sweep itself could not run. */
int sweep_run(const Sweep *sw, FILE *f);

/* This process's rank in an MPI job (eomc_set_parallel), else 0: only rank
 * 0 speaks, and only it does a run that is not a sweep. */
int sweep_rank(void);

#endif
