/*
 * printer: the state of the C file being printed and the line-level
 * helpers that emit.c, emit_func.c and emit_taylor.c share (the stream,
 * the fence around what is compiled in double only, the second
 * translation unit, declarations wrapped, constants), so that none of
 * them calls another for them.
 */
#ifndef EOMC_PRINTER_H
#define EOMC_PRINTER_H

#include <stdio.h>

#include "lower/lowered.h"

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

#endif
