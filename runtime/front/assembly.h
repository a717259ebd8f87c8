/*
 * assembly: the initial state and the constraints, as the command line
 * sees them: --assemble's projection with what it moved, the warning of a
 * start off the constraints, and the --assemble --hold a refused
 * linearization would need.
 */
#ifndef EOMC_ASSEMBLY_H
#define EOMC_ASSEMBLY_H

#include "options.h"

/* Whether the model has a constraint below acceleration level. */
int assembly_has_levels(const eomc_model *m);
/* Project the initial state x [nq + nv] onto the constraints (c->held
 * kept) and say what moved. */
int assembly_run(Options *c, eomc_sim *sim, double *x);
/* The initial state's unit quaternions divided by their lengths, with a
 * warning (unless quiet) for one whose length was not 1 to
 * EOMC_INCONSISTENT; EOMC_EUSAGE, said unless quiet, for one of length 0
 * or not finite (no rotation). */
int assembly_unit(const Options *c, const eomc_model *m, double *x, int quiet);
/* A warning, once, when x is off its constraints. */
void assembly_check(const Options *c, eomc_sim *sim, const double *x);
/* After --linearize refused a state x off the constraints: the
 * --assemble --hold that would put it on them. */
void assembly_suggest(Options *c, eomc_sim *sim, const double *x);

#endif
