/*
 * option_table: a simulator's options described once (options.c reads
 * them): each one's name, value and help, and --help written from them.
 */
#ifndef EOMC_OPTION_TABLE_H
#define EOMC_OPTION_TABLE_H

#include "eomc.h"

#include <stddef.h>

/* What parsing needs of an option: which one it is.  The options from
 * FIRST_FLAG on take no value; O_METHODS to O_TARGET belong to the
 * --work-precision report (Options.report_given's bits follow them). */
enum Option {
    /* with a value */
    O_T0, O_T_END, O_DT, O_METHOD, O_RTOL, O_ATOL, O_FIXED_STEP, O_MAX_STEPS, O_SET, O_INIT,
    O_OUT, O_STABILIZE, O_BAUMGARTE, O_REFERENCE, O_REFERENCE_OUT, O_EVENTS, O_SWEEP,
    O_SWEEP_FILE, O_THREADS, O_BATCH, O_HOLD, O_ERRORS, O_ANIMATE, O_REFERENCE_METHOD,
    O_METHODS, O_TOLERANCES, O_STEPS, O_CSV, O_PLOT, O_TARGET, /* report only */
    /* flags */
    O_STATS, O_SUMMARY, O_ACCEL, O_ASSEMBLE, O_NO_ASSEMBLE, O_WORK_PRECISION, O_ERROR,
    O_LINEARIZE, O_EQUILIBRIUM, O_ACCEL_EXTENDED, O_HELP, O_VERSION, NOPTIONS,
    FIRST_FLAG = O_STATS,
};

/* Baumgarte's rates when --baumgarte is not given (1/time units). */
#define OPTION_DEFAULT_RATE 10.0

/* The option arg[0..len) names, or -1. */
int option_find(const char *arg, size_t len);
/* Whether its row gives it a value (1) or it is a flag (0); -1: no row.
 * Parsing goes by the enum (FIRST_FLAG), --help by the row: the runtime
 * test option_table holds the two to agree. */
int option_takes_value(int option);
/* Its name as the user writes it ("--t-end", "-o"). */
const char *option_name(int option);
/* --help: the usage, every option the model m has a use for, and the
 * model's names; self is how the user runs the simulator. */
void option_help(const char *self, const eomc_model *m);

#endif
