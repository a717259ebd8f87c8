/*
 * reffric: dry friction in the reference solution, in extended precision
 * (model/stick.h's functions over the twin, reffric_ here, as friction.h's
 * are over the doubles): the same choices of modes, so that the reference
 * sticks and slips where a run does.  Statuses are stick.h's (STICK_OK
 * and the failures, friction.h).  Not installed.
 */
#ifndef EOMC_REFFRIC_H
#define EOMC_REFFRIC_H

#include "eomc.h"
#include "model/friction.h"

typedef struct reffric_Work RefFric;

RefFric *reffric_alloc(const eomc_model *m, const eomc_model_ext *x);
void reffric_free(RefFric *w);
int reffric_any(const RefFric *w, const eomc_ext *u);
int reffric_item_stick(const RefFric *w, int k);
int reffric_bounds(RefFric *w, eomc_ext t, const eomc_ext *q, const eomc_ext *v,
                   const eomc_ext *p, const eomc_ext *u);
int reffric_solve(RefFric *w, eomc_ext t, const eomc_ext *q, const eomc_ext *v,
                  const eomc_ext *p, const eomc_ext *u, eomc_ext *a);
int reffric_functions(RefFric *w, eomc_ext t, const eomc_ext *q, const eomc_ext *v,
                      const eomc_ext *p, const eomc_ext *u, eomc_ext *sw);
int reffric_settle(RefFric *w, eomc_ext t, const eomc_ext *q, const eomc_ext *v,
                   const eomc_ext *p, eomc_ext *u);
void reffric_span(RefFric *w, eomc_ext span);
int reffric_flip(RefFric *w, int k, int on, eomc_ext t, const eomc_ext *q, eomc_ext *v,
                 const eomc_ext *p, eomc_ext *u);

#endif
