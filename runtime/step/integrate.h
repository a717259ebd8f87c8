/*
 * integrate.h: runs one after another EOMC_LANES at a time (a sweep's,
 * runtime/front/sweep.c), each lane a run of eomc_sim_integrate's with
 * its own steps, events and rows, their Taylor series computed together
 * (taylor.h: taylor_lanes_fill).  Not installed.
 */
#ifndef EOMC_INTEGRATE_H
#define EOMC_INTEGRATE_H

#include "eomc.h"

/* A lane's run: what eomc_sim_integrate takes, and then its status. */
typedef struct IntegrateLane {
    eomc_sim *s;
    double *x;
    eomc_row_fn row;
    void *ctx;
    eomc_stats *st;
    int rc;
    void *tag; /* the caller's */
} IntegrateLane;

/* next(ctx, lane) sets up a lane's next run and returns 1, or 0 when
 * none is left; done(ctx, lane) takes it back with lane->rc as
 * eomc_sim_integrate would have returned it. */
typedef struct IntegrateRuns {
    int (*next)(void *ctx, IntegrateLane *lane);
    void (*done)(void *ctx, IntegrateLane *lane);
    void *ctx;
} IntegrateRuns;

/* Every run runs gives, m's under the options o, each lane's rows and
 * state those of eomc_sim_integrate to the bit (with Taylor's method
 * where m has taylor_run4, its series EOMC_LANES at once; else one at a
 * time).  EOMC_OK. */
int integrate_lanes(const eomc_model *m, const eomc_run_opts *o, const IntegrateRuns *runs);

#endif
