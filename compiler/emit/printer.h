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
    /* The file is units 1 and 3 (emit.h), each with a second half (2
     * and 4) where its functions are cut into enough parts
     * (SPLIT_MIN_PARTS): a part goes to the half behind, with its own
     * fence.  Unit 3 holds what a simulator may go without (E's Jacobian,
     * Taylor's series), the tables and the model's struct, so that units
     * 1 and 2 are the same C whatever the build adds to unit 3 (the
     * object cache then compiles them once for a simulator and a
     * library).  unit2, fenced2, nunit2 and nodes are those of the pair
     * being printed: (1, 2), or (3, 4) between emit_unit3_begin and
     * emit_unit3_end, which swap them with the other pair's (others). */
    FILE *unit2;   /* the second half, or NULL: none */
    int fenced2;
    int nunit2;    /* parts printed to the second half */
    long nodes[2]; /* temporaries printed to each half: a part goes to the one behind */
    int in3;       /* printing the pair (3, 4) */
    struct PrinterPair {
        FILE *f, *unit2;
        int fenced, fenced2, nunit2;
        long nodes[2];
    } others;
    /* The members of eomc_model defined in unit 1 or 2 (emit_entry_head),
     * declared again in unit 3, whose struct names them. */
    struct PrinterEntry {
        char *decl;
        int double_only;
    } *entry;
    int nentry;
} Printer;

/* Lines of generated code are wrapped before this column. */
enum { WRAP = 80 };

/* A line of C (printf's FMT, then a newline). */
void emit_line(Printer *pr, const char *fmt, ...);
/* What follows is compiled in double only (1: the functions the
 * reference solution does not need), or in both precisions (0). */
void emit_fence(Printer *pr, int double_only);
/* The half a part of this weight goes to, counted there (nodes): 1, the
 * second, where there is one, the part may go there (movable) and it is
 * behind; else 0. */
int emit_part_half(Printer *pr, long weight, int movable);
/* Print a part into the second half (fenced double_only), and back. */
void emit_unit2_begin(Printer *pr, int double_only);
void emit_unit2_end(Printer *pr);
/* Close the fences of both halves of the pair being printed: each unit
 * ends unfenced. */
void emit_unfence_pair(Printer *pr);
/* Print into the pair (3, 4) from here, and back to (1, 2). */
void emit_unit3_begin(Printer *pr);
void emit_unit3_end(Printer *pr);
/* The head of a member of eomc_model: "EOMC_ENTRY TYPE" (hidden linkage
 * when the file is split, static in one unit) outside unit 3, where it is
 * also recorded for emit_entry_decls; "static TYPE" in unit 3. */
void emit_entry_head(Printer *pr, const char *type, const char *name, const char *params);
/* The recorded members' declarations, each in its fence (then forgotten). */
void emit_entry_decls(Printer *pr);
/* "TYPE\nNAME(PARAMS)" then TAIL, the parameters wrapped; emit_head's
 * tail is "\n{". */
void emit_decl(Printer *pr, const char *type, const char *name, const char *params,
               const char *tail);
void emit_head(Printer *pr, const char *type, const char *name, const char *params);
/* The shortest text that reads back as the same double, as C's double. */
void emit_const(char *buf, size_t len, double v);

#endif
