/*
 * depend: which constraint rows the solves use.  Rows dependent on the
 * others at the start are left out of them, and watched; where the kept
 * rows are singular, the ones that are dependent are named.  Pure
 * functions of the rows B = df/dq'' and the mass matrix that return a
 * status; sim.c says what it means.  The reasoning is in depend.c.
 */
#ifndef EOMC_DEPEND_H
#define EOMC_DEPEND_H

#include "eomc_model.h"

typedef struct Depend Depend;

/* NULL when memory runs out; depend_free is NULL-safe. */
Depend *depend_alloc(const eomc_model *m);
void depend_free(Depend *w);

enum {
    DEPEND_NONE,       /* the rows are independent: none dropped */
    DEPEND_DROPPED,    /* some are dropped (depend_dropped) */
    DEPEND_SECOND,     /* a dependent row is of a second-order constraint:
                        * none dropped (depend_involved names them) */
};
/* The rows to leave out, chosen at B [nc*n] (at any q'': every f affine in
 * q'') and M [n*n] (its diagonal scales the coordinates): DEPEND_*. */
int depend_choose(Depend *w, const double *B, const double *M);
/* The rows left out, drop [nc] (1: left out), or NULL when none are. */
const unsigned char *depend_dropped(const Depend *w);
/* None left out (the parameters changed: chosen again at the next start). */
void depend_clear(Depend *w);

/* The rows of the dependencies depend_choose found (dropped or not):
 * "loop_z, dependent on loop_x, loop_y"; "" when none. */
const char *depend_note(const Depend *w);
/* Of the rows rows [nr] at B and M (NULL: unscaled), those that are
 * dependent, and those their combinations use: "rod, pin"; their rank
 * into *rank.  "" when they are independent (*rank == nr). */
const char *depend_involved(Depend *w, const double *B, const double *M, const int *rows,
                            int nr, int *rank);

/* After a step: each [nc], each row's residual relative to its terms
 * (eomc_sim_inconsistencies).  The dropped row furthest from its
 * constraint, or -1 while every dropped row stays within DEPEND_FOLLOW
 * times the kept rows' largest (*kept) or EOMC_INCONSISTENT, whichever is
 * larger: a dependent row's residual follows those of the rows it is a
 * combination of, by the combination's coefficients (pivoted QR keeps
 * them near 1); one that does not is no longer dependent on them. */
#define DEPEND_FOLLOW 1e3
int depend_watch(const Depend *w, const double *each, double *kept);

#endif
