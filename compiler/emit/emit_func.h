/*
 * emit_func: print one lowered function (lower.h) as C, step by step
 * as its schedule (lower_schedule) lists them, for emit.c, which prints
 * the model file around the functions.  The rest of the compiler calls
 * emit.h.
 */
#ifndef EOMC_EMIT_FUNC_H
#define EOMC_EMIT_FUNC_H

#include "emit.h"

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

typedef struct Printer {
    FILE *f;
    ExprPool *P;
    const LowModel *md; /* L's: the names */
    const Lowered *L;
    const LowFunc *lf; /* the function being printed */
    /* per node id, for the function being printed */
    int *temp;  /* temporary number, -1 if not scheduled */
    int *part;  /* the part that computes it */
    int *slot;  /* index in s[], -1 if only its own part uses it */
    const int *ext; /* NULL, or per node its index in an input array shared[]
                     * (-1: not there): values computed once by another function */
    const int *derived; /* NULL, or per node its index in pd[] (-1: not there):
                         * values of the parameters alone, read from p[np + k] */
    int cur;    /* the part being printed */
    unsigned used; /* bit k: source k is read in this part */
    int fenced;    /* inside #ifndef EOMC_EXTENDED */
    /* A large model is two translation units (SPLIT_MIN_PARTS): the even
     * parts of each cut function go to unit2, with its own fence. */
    FILE *unit2;   /* NULL: one unit */
    int fenced2;
    int nunit2;    /* parts printed to unit2 */
    long nodes[2]; /* temporaries printed to each unit: a part goes to the one behind */
} Printer;

/* Lines of generated code are wrapped before this column. */
enum { WRAP = 80 };

/* A line of C (printf's FMT, then a newline). */
void emit_line(Printer *pr, const char *fmt, ...);
/* What follows is compiled in double only (1: the functions the
 * reference solution does not need), or in both precisions (0). */
void emit_fence(Printer *pr, int double_only);
/* Swap the stream and fence being printed with the second unit's. */
void emit_unit2_swap(Printer *pr);
/* "TYPE\nNAME(PARAMS)" then TAIL, the parameters wrapped; emit_head's
 * tail is "\n{". */
void emit_decl(Printer *pr, const char *type, const char *name, const char *params,
               const char *tail);
void emit_head(Printer *pr, const char *type, const char *name, const char *params);
/* The shortest text that reads back as the same double, as C's double. */
void emit_const(char *buf, size_t len, double v);
/* The C parameter list and names of a function's signature. */
void emit_func_of(Func *fn, const LowFunc *lf);
/* Print a lowered function (and, first, the one its copies call); its
 * operation counts, each copy's included. */
ExprCount emit_function(Printer *pr, const LowFunc *lf);
/* The taylor member and its tables (emit_taylor.c), in double only;
 * nothing when ty->why says why there is none. */
void emit_taylor(Printer *pr, const LowTaylor *ty);

#endif
