/*
 * fold: fixed parameters (a scene's `fix:`, --fix) become constants in
 * every expression of the spec (spec_foreach_expr, spec.h).
 */
#ifndef EOMC_SPEC_FOLD_H
#define EOMC_SPEC_FOLD_H

#include "loader.h"

/* Fold the fixed parameters; drop the checks no parameter can change. */
void spec_fold_fixed(Loader *L);

#endif
