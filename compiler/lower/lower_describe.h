/*
 * lower_describe: the lowered model's own copy of the names, sizes, the
 * scene's choices and the banner's facts (lowered.h's LowModel).
 */
#ifndef EOMC_LOWER_DESCRIBE_H
#define EOMC_LOWER_DESCRIBE_H

#include "lowered.h"
#include "forms/eom.h"
#include "mechanics/invariant.h"

/* Fill L->model, its strings and arrays in A (lower_model calls it). */
void lower_describe(Lowered *L, const Spec *s, const Eom *e, const Constraints *c,
                    const Invariant *inv, Arena *A);

#endif
