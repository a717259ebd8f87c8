/*
 * emit: print a derived model as straight-line C implementing
 * runtime/include/eomc_model.h.  One `const double` temporary per shared DAG node
 * reachable from a function's outputs (dead nodes are never printed),
 * numbered in emission order; leaves get named locals (q_x, v_x, a_x,
 * p_x, u_x); constants print in the shortest form that reads back
 * exactly.  Output depends only on the input, byte for byte.
 */
#ifndef EOMC_EMIT_H
#define EOMC_EMIT_H

#include <stdio.h>

#include "lower/lower.h"

typedef struct EmitInfo {
    const char *version;  /* eomc's */
    const char *options;  /* generator options for the banner, "" if none */
    int eliminate;        /* constraints by elimination (Maggi), else multipliers */
    const char *form_why; /* how the form was picked; NULL: --form chose it */
} EmitInfo;

/* Operation counts of each emitted function. */
typedef struct EmitStats {
    const char *function;
    ExprCount count;
} EmitStats;
enum { EMIT_NFUNCS = 16 };

/* Print the lowered model L (lower.h), which holds all it prints but the
 * expressions (in P) and what info says of the run.  The functions are
 * written in eomc_real (eomc_model.h); those the reference solution needs
 * are also compiled with -DEOMC_EXTENDED, the others are fenced off from
 * it.  The file compiles as one translation unit, or as units
 * -DEOMC_UNIT=1 to 4 linked together: 1 the model's functions, 3 E's
 * Jacobian, Taylor's series, the tables and the model's struct, and 2 and
 * 4, where a large model has them, the second halves of 1 and 3.  Units 1
 * and 2 are the same C whatever the Jacobian and the series, so that a
 * simulator and a library share their objects.  Returns the units there
 * are (EMIT_UNIT1 | ...). */
enum { EMIT_UNIT1 = 1, EMIT_UNIT2 = 2, EMIT_UNIT3 = 4, EMIT_UNIT4 = 8 };
int emit_model(FILE *out, const Lowered *L, ExprPool *P, const EmitInfo *info,
               EmitStats stats[EMIT_NFUNCS]);

#endif
