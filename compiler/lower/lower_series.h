/*
 * lower_series: taylor_run's program as straight-line code (lowered.h's
 * LowSeries): every call of the Taylor program at every order up to
 * LOW_SERIES_ORDERS, each written out as its sum of products over fixed
 * cells, for the emitter to print.
 */
#ifndef EOMC_LOWER_SERIES_H
#define EOMC_LOWER_SERIES_H

#include "lowered.h"

/* ty's program written out order by order, or NULL where it has a call
 * without a straight form (lowered.h) or would be longer than
 * LOW_SERIES_MAX_TERMS; ty must have a taylor_run (nrun > 0).
 * lower_taylor calls it last. */
LowSeries *lower_series(const LowTaylor *ty, Arena *A);

#endif
