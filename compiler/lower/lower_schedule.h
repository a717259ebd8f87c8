/*
 * lower_schedule: a lowered function as the flat list of steps its C
 * runs, as CasADi's SX functions are: which operator nodes, in which
 * order, where each output is stored.  The emitter prints that list
 * (naming the temporaries, cutting it into C functions), and lower_eval
 * evaluates the same list without any C: what the tests evaluate is what
 * the C computes, step for step, not another walk of the DAG (to the bit,
 * but for sines and cosines: the C's eomc_sincos is runtime/base/sincos.c's,
 * within 1.5 ulp of the libm ones lower_eval calls).
 */
#ifndef EOMC_LOWER_SCHEDULE_H
#define EOMC_LOWER_SCHEDULE_H

#include "lowered.h"

/* Does f compute e (an operator node not read from shared[] or pd[])? */
int lower_computed(ExprPool *P, const LowFunc *f, ExprId e);

/* A function of more operator nodes than this is printed in parts of at
 * most as many (emit_func.c), each a C function of its own: gcc -O2's
 * time per statement grows with the function; on the 30-body tree's
 * articulated-body solve, parts of 6000 took 11.7 s of cc, of 1500 7.6 s
 * (its register allocation alone 4.2 -> 0.6 s), for no loss of speed.
 * The schedule depends on it: only a function printed whole has its
 * nodes in the order they could start. */
enum { LOWER_PART_SIZE = 1500 };

enum {
    LOW_STEP_COPIES, /* run f->copy once per copy (LowFunc.copy), first */
    LOW_STEP_FILL,   /* output argument i's first fill[i] entries = 0
                      * (printed as a comment where f->zeroed says so) */
    LOW_STEP_NODE,   /* compute operator node id from its operands */
    LOW_STEP_STORE,  /* store out[i] (once its value is computed) */
    /* A lazy block: IF, then ORs, each a test that switch i (the
     * pool's) is in mode `branch`; the NODE steps up to its END (or ELSE)
     * run where any test holds.  A block of one test may have an ELSE:
     * the NODE steps after it run where the test fails.  Blocks hold
     * nodes only and do not nest. */
    LOW_STEP_IF,
    LOW_STEP_OR,
    LOW_STEP_ELSE,
    LOW_STEP_END,
};

typedef struct LowStep {
    int kind; /* LOW_STEP_* */
    ExprId id;
    int i;
    int branch; /* LOW_STEP_IF: 1, mode i on, or 0, off */
} LowStep;

/* The one order in which a function's values are computed: the emitter
 * prints it (naming a temporary per node, cutting it into parts) and
 * lower_eval evaluates it.  Operands that f does not compute
 * (lower_computed) are leaves, shared[] or pd[] values, read where used.
 *
 * Lazy branches: a node whose every use, through any path, lies under
 * one branch of a switched expression SELECT(k, a, b) is computed in a
 * block that runs only in that mode of switch k, just before the first
 * SELECT on k that takes it (a SELECT under another one's branch counts
 * as the outer one's: blocks do not nest).  A node under branches of a
 * few switches (a body's pose, which each of its contact pairs reads
 * under its own switch) runs where any of them holds.  The values are
 * the same operations either way; a mode's branch that is not taken
 * costs nothing. */
typedef struct LowSched {
    int nstep, cap;
    LowStep *step;
    int nnode; /* LOW_STEP_NODE steps */
    /* The nodes numbered angles .. angles_end-1, counted among the
     * NODE steps, are sines and cosines computed by one eomc_sincos call
     * from nangle angles: angle_of[k - angles] is 2 j for the sine of
     * angle[j], 2 j + 1 for its cosine.  The angles themselves are
     * computed before. */
    int nangle, angles, angles_end;
    ExprId *angle;
    int *angle_of;
    int whole; /* fewer than LOWER_PART_SIZE nodes: in start order */
} LowSched;

/* f's schedule (lower_sched_free frees it); lazy 0: no lazy blocks,
 * every branch computed (eomc's --branches eager). */
LowSched *lower_schedule(ExprPool *P, const LowFunc *f, int lazy);
void lower_sched_free(LowSched *S);

/* Evaluate f at env by running its schedule (lower_schedule: the list
 * its C is printed from, lazy), each node from its operands' values by
 * expr_eval_node, copies and fills included: out[k] is output argument
 * k's array (NULL: skipped).  Tests use it to check a derivation without
 * compiling C. */
void lower_eval(ExprPool *P, const LowFunc *f, const ExprEnv *env, double *const *out);

#endif
