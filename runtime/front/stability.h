/*
 * stability: what --linearize and --equilibrium print: the equilibrium
 * found, A = dz'/dz and B = dz'/du labelled, A's eigenvalues (the largest
 * real part first) and the stability verdict, and --csv's rows of them;
 * and a sweep of --linearize's cells, the eigenvalues of each run.
 */
#ifndef EOMC_STABILITY_H
#define EOMC_STABILITY_H

#include "options.h"

/* --linearize or --equilibrium from the initial state x [2nq]. */
int stab_print(Options *c, eomc_sim *sim, double *x);
/* A sweep's cells of one run (Sweep.cells, ctx an Options): its
 * eigenvalues, the largest real part first, as ",re1,im1,re2,im2,...". */
int stab_cells(void *ctx, eomc_sim *sim, double *x, char **text);
/* "re1,im1,re2,im2,...": the columns of stab_cells (malloc'd, NULL when
 * memory runs out). */
char *stab_columns(int nl);

#endif
