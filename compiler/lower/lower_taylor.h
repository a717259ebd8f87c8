/*
 * lower_taylor: the program of the model's taylor member, Taylor's
 * method's series (lowered.h's LowTaylor).
 */
#ifndef EOMC_LOWER_TAYLOR_H
#define EOMC_LOWER_TAYLOR_H

#include "lowered.h"

/* The taylor member's program from L's mass_bias and events (or, in
 * ->why, why not: a model it cannot do, or one it was not wanted for):
 * lower_model calls it last. */
LowTaylor *lower_taylor(const Lowered *L, int wanted, ExprPool *P, Arena *A);

#endif
