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
 * it.  Returns the number of translation units the file makes: 1, or 2
 * for a large model, whose C compiles as one unit or, with -DEOMC_UNIT=1
 * and -DEOMC_UNIT=2, as two halves linked together. */
int emit_model(FILE *out, const Lowered *L, ExprPool *P, const EmitInfo *info,
               EmitStats stats[EMIT_NFUNCS]);

#endif
