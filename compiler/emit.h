/*
 * emit: print a derived model as straight-line C implementing
 * runtime/eomc_model.h.  One `const double` temporary per shared DAG node
 * reachable from a function's outputs (dead nodes are never printed),
 * numbered in emission order; leaves get named locals (q_x, v_x, a_x,
 * p_x, u_x); constants print with %.17g.  Output depends only on the
 * input, byte for byte.
 */
#ifndef EOMC_EMIT_H
#define EOMC_EMIT_H

#include <stdio.h>

#include "eom.h"

typedef struct EmitInfo {
    const char *version;  /* eomc's */
    const char *options;  /* generator options for the banner, "" if none */
} EmitInfo;

/* Operation counts of each emitted function. */
typedef struct EmitStats {
    const char *function;
    ExprCount count;
} EmitStats;
enum { EMIT_NFUNCS = 6 };

void emit_model(FILE *out, const Spec *s, const Mech *m, const Eom *e,
                ExprPool *P, Diff *D, const EmitInfo *info,
                EmitStats stats[EMIT_NFUNCS]);

#endif
