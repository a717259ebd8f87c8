/*
 * emit: print a derived model as straight-line C implementing
 * runtime/eomc_model.h.  One `const double` temporary per shared DAG node
 * reachable from a function's outputs (dead nodes are never printed),
 * numbered in emission order; leaves get named locals (q_x, v_x, a_x,
 * p_x, u_x); constants print in the shortest form that reads back
 * exactly.  Output depends only on the input, byte for byte.
 */
#ifndef EOMC_EMIT_H
#define EOMC_EMIT_H

#include <stdio.h>

#include "constraint.h"
#include "eom.h"
#include "invariant.h"

/* How the jacobian member is printed.  UNROLLED: every entry of dE/dq
 * and dE/dq' as its own expression, the fastest to run; code grows as
 * n |E|.  SEEDED: the directional derivatives of E along seeds dq and
 * dq' as two functions (code ~ |E|) that jacobian calls once per column
 * with a unit seed: exact all the same, slower to run, far less for the C
 * compiler.  AUTO: unrolled up to EMIT_UNROLLED_JACOBIAN_MAX operations. */
enum { EMIT_JACOBIAN_AUTO, EMIT_JACOBIAN_UNROLLED, EMIT_JACOBIAN_SEEDED };
/* Measured on the chain benchmark (gcc 12, -O2): cc spends ~0.3 ms per
 * operation, linearly; the seeded Jacobian runs 2-3x slower (N = 20:
 * 4.5 -> 13 us, N = 50: 47 -> 97 us) but is 6x (N = 20) to 16x (N = 50)
 * less code.  Up to here the unrolled one costs < 6 s of cc. */
enum { EMIT_UNROLLED_JACOBIAN_MAX = 20000 };

typedef struct EmitInfo {
    const char *version;  /* eomc's */
    const char *options;  /* generator options for the banner, "" if none */
    int jacobian;         /* EMIT_JACOBIAN_... */
    int eliminate;        /* constraints by elimination (Maggi), else multipliers */
} EmitInfo;

/* Operation counts of each emitted function. */
typedef struct EmitStats {
    const char *function;
    ExprCount count;
} EmitStats;
enum { EMIT_NFUNCS = 11 };

/* c: the constraints, or NULL.  The functions are written in
 * eomc_real (eomc_model.h); those the reference solution needs are also
 * compiled with -DEOMC_EXTENDED, the others are fenced off from it. */
void emit_model(FILE *out, const Spec *s, const Mech *m, const Eom *e,
                const Constraints *c, const Invariant *inv, ExprPool *P, Diff *D,
                const EmitInfo *info, EmitStats stats[EMIT_NFUNCS]);

#endif
