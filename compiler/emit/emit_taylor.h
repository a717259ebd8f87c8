/*
 * emit_taylor: the model's taylor member and its tables, printed from
 * the program lower_taylor made.
 */
#ifndef EOMC_EMIT_TAYLOR_H
#define EOMC_EMIT_TAYLOR_H

#include "printer.h"

/* The taylor member and its tables (emit_taylor.c), in double only;
 * nothing when ty->why says why there is none. */
void emit_taylor(Printer *pr, const LowTaylor *ty);

#endif
