/*
 * plan: the runs of a sweep, from --sweep NAME=START:STOP:COUNT (a grid,
 * the last one fastest) or from --sweep-file's rows (a header of
 * parameter names, then one set of values per row).
 */
#ifndef EOMC_PLAN_H
#define EOMC_PLAN_H

#include "options.h"

typedef struct Plan {
    int nparam;
    const char **names;   /* [nparam] the swept parameters (copies) */
    long nruns;
    double *values;       /* [nruns * nparam], in sweep order */
} Plan;

/* The plan c's --sweep or --sweep-file gives; EOMC_OK or EOMC_EUSAGE
 * (said).  plan_free is safe either way. */
int plan_make(Options *c, const eomc_model *m, Plan *pl);
void plan_free(Plan *pl);

#endif
