/*
 * emit_func: print one lowered function (lowered.h) as C, step by step
 * as its schedule (lower_schedule) lists them, for emit.c, which prints
 * the model file around the functions.  The rest of the compiler calls
 * emit.h.
 */
#ifndef EOMC_EMIT_FUNC_H
#define EOMC_EMIT_FUNC_H

#include "printer.h"

/* The arrays leaves are read from, in the order their locals are
 * declared and unused ones are (void)ed: a function reads only those
 * among its inputs. */
enum { SRC_Q, SRC_V, SRC_A, SRC_P, SRC_U, SRC_T, SRC_DQ, SRC_DV, SRC_DA, SRC_LAM, NSRC };

/* A function being printed: its list and its signature. */
typedef struct Func {
    const LowFunc *low;
    LowArgs args;
    char params[600]; /* the C parameter list */
    char names[300];  /* the parameter names, comma-separated */
    int has[NSRC];    /* which sources are among the inputs */
} Func;

/* The C parameter list and names of a function's signature. */
void emit_func_of(Func *fn, const LowFunc *lf);
/* Print a lowered function (and, first, the one its copies call); its
 * operation counts, each copy's included. */
ExprCount emit_function(Printer *pr, const LowFunc *lf);

#endif
