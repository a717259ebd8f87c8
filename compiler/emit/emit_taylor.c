/*
 * emit_taylor: the model's taylor member (eomc_model.h) and its tables,
 * printed from the program lower_taylor made (lowered.h's LowTaylor): one
 * call of runtime/include/eomc_taylor.h per step, slot s being the series at
 * T + s * S.  Compiled in both precisions: the extended-precision twin
 * sums the same series (a reference by Taylor's method, reference.c).
 */
#include "emit_taylor.h"
#include "base/arena.h"
#include "lower/lower_schedule.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A slot's series, "T + s * S". */
static void
print_slot(FILE *f, int s)
{
    if (s == 0)
        fputs("T", f);
    else
        fprintf(f, "T + %d * S", s);
}

/* "static const int NAME[n] = {...};" at file scope, twenty a line, or
 * in a function (in: its indent), sixteen. */
static void
print_ints_in(Printer *pr, const char *in, const char *name, const int *x, int n)
{
    int per = *in ? 16 : 20;
    fprintf(pr->f, "%sstatic const int %s[%d] = {", in, name, n);
    for (int i = 0; i < n; i++) {
        if (i > 0 && i % per)
            fputs(", ", pr->f);
        else if (i > 0)
            fprintf(pr->f, ",\n%s    ", in);
        fprintf(pr->f, "%d", x[i]);
    }
    emit_line(pr, "};");
}

static void
print_ints(Printer *pr, const char *name, const int *x, int n)
{
    print_ints_in(pr, "", name, x, n);
}

/* One call, "PREFIXCALL(T + s * S, ..., [value,] k);" after indent in. */
static void
print_call(Printer *pr, const char *in, const char *prefix, const LowTayStep *st)
{
    FILE *f = pr->f;
    fprintf(f, "%s%s%s(", in, prefix, st->call);
    for (int j = 0; j < st->nslot; j++) {
        if (j)
            fputs(", ", f);
        print_slot(f, st->slot[j]);
    }
    char num[40];
    switch (st->src) {
    case LOW_TAY_SRC_CONST:
        emit_const(num, sizeof num, st->value);
        fprintf(f, ", %s", num);
        break;
    case LOW_TAY_SRC_P:
        fprintf(f, ", p[%d]", st->index);
        break;
    case LOW_TAY_SRC_U:
        fprintf(f, ", u[%d]", st->index);
        break;
    case LOW_TAY_SRC_T:
        fputs(", t0", f);
        break;
    }
    emit_line(pr, ", k);");
}

/* Calls first .. end-1 of the program, after the locals they need. */
static void
print_calls(Printer *pr, const LowTaylor *ty, int first, int end, const char *prefix)
{
    int reads_t = 0, reads_p = 0, reads_u = 0;
    for (int i = first; i < end; i++) {
        reads_t |= ty->step[i].src == LOW_TAY_SRC_T;
        reads_p |= ty->step[i].src == LOW_TAY_SRC_P;
        reads_u |= ty->step[i].src == LOW_TAY_SRC_U;
    }
    emit_line(pr, "    const int S = K + 1;");
    if (first == end)
        emit_line(pr, "    (void)k, (void)S, (void)T;");
    if (!reads_t)
        emit_line(pr, "    (void)t0;");
    if (!reads_p)
        emit_line(pr, "    (void)p;");
    if (!reads_u)
        emit_line(pr, "    (void)u;");
    for (int i = first; i < end; i++)
        print_call(pr, "    ", prefix, &ty->step[i]);
}

/* Each recurrence the program calls as a function of its own, for a
 * program cut into parts: inlined at each of thousands of calls, their
 * loops multiply the C compiler's time (a chain of 50 links, 12 213
 * calls: 16 s of cc -O1 inlined, 7 s through these, 2 s without Taylor). */
static void
print_wrappers(Printer *pr, const LowTaylor *ty, int declare)
{
    if (declare)
        emit_line(pr, "/* The recurrences, in the third unit. */");
    else {
        emit_line(pr, "/* The recurrences the parts below call, each compiled once: inlined at");
        emit_line(pr, " * every call, their loops would multiply the C compiler's time; the");
        emit_line(pr, " * fourth unit's parts call them too. */");
    }
    for (int i = 0; i < ty->nstep; i++) {
        const LowTayStep *st = &ty->step[i];
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = !strcmp(ty->step[j].call, st->call);
        if (seen)
            continue;
        char params[600] = "", args[300] = "";
        size_t pl = 0, al = 0;
        for (int j = 0; j < st->nslot; j++) {
            pl += (size_t)snprintf(params + pl, sizeof params - pl, "%seomc_real *s%d",
                                   j < st->nres ? "" : "const ", j);
            pl += (size_t)snprintf(params + pl, sizeof params - pl, ", ");
            al += (size_t)snprintf(args + al, sizeof args - al, "s%d, ", j);
        }
        if (st->src != LOW_TAY_SRC_NONE) {
            pl += (size_t)snprintf(params + pl, sizeof params - pl, "eomc_real v, ");
            al += (size_t)snprintf(args + al, sizeof args - al, "v, ");
        }
        snprintf(params + pl, sizeof params - pl, "int k");
        char fname[64];
        snprintf(fname, sizeof fname, "tay_%s", st->call);
        if (declare) {
            emit_decl(pr, "EOMC_PART void", fname, params, ";");
            continue;
        }
        emit_head(pr, "EOMC_PART void", fname, params);
        emit_line(pr, "    eomc_tay_%s(%sk);", st->call, args);
        emit_line(pr, "}\n");
    }
    if (declare)
        emit_line(pr, "");
}

/* A line's text, wrapped before a term past this column. */
enum { SERIES_WRAP = 92 };

/* Where a cell lives: the state's (q's and v's slots, in column c with
 * place[c] >= 0) in the caller's X, X[j N + place[c]], so that its series
 * is written where the runtime reads it; every other in the local W. */
typedef struct Cells {
    const int *place; /* [nslot] by column: the state's index, or -1 (LowSeries') */
    int nslot, N;
    int lanes;        /* taylor_run4's: every value a vector of the lanes'
                       * (EOMC_V4), a number spread over them */
} Cells;

/* A line being printed: at column col; in a pack (LowSerLine.pack) of w
 * lanes, an operand that differs in lane 1 (cell1) is its w consecutive
 * cells, EOMC_AT4 or EOMC_AT2, and one the same in every lane a number. */
typedef struct Col {
    FILE *f;
    int col;
    const Cells *cells;
    int w;
} Col;

static void
put(Col *c, const char *fmt, ...)
{
    char buf[160];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    fputs(buf, c->f);
    c->col += n;
}

/* A cell as an operand: W[c] or the state's X[...], or 0 (-1: 0 at
 * every step); in a pack, lane 1's being cell1. */
static void
put_cell(Col *c, int cell, int cell1)
{
    const Cells *m = c->cells;
    int at = cell < 0 ? -1 : m->place[cell % m->nslot];
    int index = at >= 0 ? cell / m->nslot * m->N + at : cell;
    if (cell < 0)
        put(c, m->lanes ? "EOMC_V4C(0.0)" : "0.0");
    else if (c->w && cell1 != cell)
        put(c, "EOMC_AT%d(%s + %d)", c->w, at >= 0 ? "X" : "W", index);
    else
        put(c, "%s[%d]", at >= 0 ? "X" : "W", index);
}

/* Term t, after others (its sign as the operator) or first; t1 lane 1's
 * in a pack. */
static void
put_term(Col *c, const LowSerTerm *t, const LowSerTerm *t1, int first)
{
    double mag = fabs(t->coef);
    if (!first && c->col > SERIES_WRAP) {
        fputs("\n           ", c->f);
        c->col = 11;
    }
    if (first)
        put(c, t->coef < 0 ? "-" : "");
    else
        put(c, t->coef < 0 ? " - " : " + ");
    char num[40];
    emit_const(num, sizeof num, mag);
    if (t->x < 0) {
        put(c, "%s", num);
        return;
    }
    if (mag != 1)
        put(c, "%s * ", num);
    put_cell(c, t->x, t1->x);
    if (t->y >= 0) {
        put(c, " * ");
        put_cell(c, t->y, t1->y);
    }
}

static void
put_value(Col *c, int src, int index, double value)
{
    char num[40];
    if (c->cells->lanes && src != LOW_TAY_SRC_P && src != LOW_TAY_SRC_U &&
        src != LOW_TAY_SRC_T) {
        emit_const(num, sizeof num, value);
        put(c, "EOMC_V4C(%s)", num);
        return;
    }
    switch (src) {
    case LOW_TAY_SRC_P:
        put(c, "p[%d]", index);
        break;
    case LOW_TAY_SRC_U:
        put(c, "u[%d]", index);
        break;
    case LOW_TAY_SRC_T:
        put(c, "t0");
        break;
    default:
        emit_const(num, sizeof num, value);
        put(c, "%s", num);
        break;
    }
}

/* One line of the written-out series (lowered.h's LowSerLine); w > 0:
 * the pack of w lines from l, on vectors. */
static void
print_series_line(Printer *pr, const LowSeries *se, const LowSerLine *l, int w,
                  const Cells *cells)
{
    Col c = {pr->f, 0, cells, w};
    const LowSerLine *l1 = w ? l + 1 : l; /* lane 1's, which tells an operand's kind */
    char num[40];
    if (l->kind == LOW_SER_SOLVE) { /* in place over W's cells from dst */
        if (l->index > 0) {
            emit_line(pr, "    if (solve(ctx, %d, NULL, W + %d))\n        return -1;", l->index,
                      l->dst);
            return;
        }
        put(&c, "    {\n        const eomc_real M0[%d] = {", l->nterm);
        for (int t = 0; t < l->nterm; t++) {
            const LowSerTerm *m = &se->term[l->first + t];
            if (t > 0)
                put(&c, ",");
            if (t > 0 && c.col > SERIES_WRAP) {
                fputs("\n            ", c.f);
                c.col = 12;
            } else if (t > 0) {
                put(&c, " ");
            }
            if (m->x < 0)
                put(&c, "0.0");
            else
                put_cell(&c, m->x, m->x);
        }
        put(&c, "};\n");
        emit_line(pr, "        if (solve(ctx, 0, M0, W + %d))\n            return -1;\n    }",
                  l->dst);
        return;
    }
    put(&c, "    ");
    if (cells->lanes && (l->kind == LOW_SER_CALL || l->kind == LOW_SER_SELECT)) {
        /* a lane at a time, by eomc_taylor.h's helper */
        put(&c, "eomc_v4_%s(&", l->kind == LOW_SER_CALL ? l->fn : "select");
        put_cell(&c, l->dst, l1->dst);
        put(&c, ", ");
        if (l->kind == LOW_SER_SELECT) {
            put(&c, "&");
            put_value(&c, l->src, l->index, 0);
            put(&c, ", ");
        }
        put(&c, "&");
        put_cell(&c, l->x, l->x);
        if (l->kind == LOW_SER_SELECT || !strcmp(l->fn, "pow")) {
            put(&c, ", &");
            put_cell(&c, l->y, l->y);
        }
        fputs(");\n", pr->f);
        return;
    }
    put_cell(&c, l->dst, l1->dst);
    put(&c, " = ");
    switch (l->kind) {
    case LOW_SER_VALUE:
        put_value(&c, l->src, l->index, l->value);
        break;
    case LOW_SER_CALL:
        put(&c, "%s(", l->fn);
        put_cell(&c, l->x, l->x);
        if (!strcmp(l->fn, "pow")) {
            put(&c, ", ");
            put_cell(&c, l->y, l->y);
        }
        put(&c, ")");
        break;
    case LOW_SER_SELECT:
        put_value(&c, l->src, l->index, 0);
        put(&c, " != 0 ? ");
        put_cell(&c, l->x, l->x);
        put(&c, " : ");
        put_cell(&c, l->y, l->y);
        break;
    default: {
        /* Products and quotients associate to the left, so a single term
         * needs no parentheses (x * y / m / 3 is ((x y) / m) / 3); a
         * negation is exact wherever it stands, so it leads.  A sum is
         * parenthesized before what multiplies or divides it.  An empty
         * sum times a number is 0: then the last term alone. */
        int times = l->times != 1 && l->nterm > 0, nsum = l->nterm + (l->last >= 0);
        int wrap = l->nterm > 1 && (times || l->over != 0 || l->after != 0 || l->negate);
        int wrap2 = nsum > 1 && l->last >= 0 && (l->over != 0 || l->after != 0 || l->negate);
        /* a number alone is spread over the lanes (a vector's operator
         * spreads a number beside a vector itself) */
        int number = cells->lanes && l->over == 0;
        for (int t = 0; t < l->nterm && number; t++)
            number = se->term[l->first + t].x < 0;
        number &= l->last < 0 || se->term[l->last].x < 0;
        put(&c, number ? "EOMC_V4C(" : "");
        put(&c, "%s%s%s", l->negate ? (nsum > 1 ? "-(" : "-") : "", wrap2 ? "(" : "",
            wrap ? "(" : "");
        for (int t = 0; t < l->nterm; t++)
            put_term(&c, &se->term[l->first + t], &se->term[l1->first + t], t == 0);
        put(&c, wrap ? ")" : "");
        if (times) {
            emit_const(num, sizeof num, l->times);
            put(&c, " * %s", num);
        }
        if (l->last >= 0)
            put_term(&c, &se->term[l->last], &se->term[l1->last], l->nterm == 0);
        put(&c, wrap2 ? ")" : "");
        if (l->over != 0) {
            emit_const(num, sizeof num, l->over);
            put(&c, l->over != 1 ? " / (%s * " : " / ", num);
            put_cell(&c, l->over_cell, l1->over_cell);
            put(&c, l->over != 1 ? ")" : "");
        }
        if (l->negate && nsum > 1)
            put(&c, ")");
        if (l->after != 0 && l->after != 1) { /* (x / 1 is x) */
            emit_const(num, sizeof num, l->after);
            put(&c, " / %s", num);
        }
        put(&c, number ? ")" : "");
    }
    }
    fputs(";\n", pr->f);
}

/* The cells of ty's written-out series. */
static Cells
series_cells(const LowTaylor *ty, int lanes)
{
    return (Cells){ty->series->place, ty->nslot, ty->nstate, lanes};
}

/* Lines from .. to - 1 of the series: a run of packs (LowSerLine.pack)
 * each as one line on vectors where the C compiler has GCC's vectors
 * (EOMC_PACKS, eomc_taylor.h), else line by line; none in taylor_run4's
 * lanes, already vectors. */
static void
print_lines(Printer *pr, const LowSeries *se, int from, int to, const Cells *cells)
{
    for (int i = from, j; i < to; i = j) {
        const LowSerLine *l = se->line;
        if (cells->lanes || !l[i].pack) {
            print_series_line(pr, se, &l[i], 0, cells);
            j = i + 1;
            continue;
        }
        for (j = i; j < to && l[j].pack;)
            j += l[j].pack;
        emit_line(pr, "#ifdef EOMC_PACKS");
        for (int x = i; x < j; x += l[x].pack)
            print_series_line(pr, se, &l[x], l[x].pack, cells);
        emit_line(pr, "#else");
        for (int x = i; x < j; x++)
            print_series_line(pr, se, &l[x], 0, cells);
        emit_line(pr, "#endif");
    }
}

/* A parted series (LowSeries.parted: past LOW_SERIES_OPTIMIZED_TERMS
 * terms) is cut into parts of at most this many lines, none across an
 * order, each a function of its own on taylor_run's W and X, which
 * taylor_run calls in turn.  The C compiler's optimizer, whose time grows
 * faster than a function's length, then sees short functions.  Measured
 * on the Pleiades (25 000 terms; gcc 12, -Og, the unit that holds them):
 * parts of 10, 20, 40, 80 lines compile in 3.6, 3.5, 3.7, 4.4 s, and its
 * series to order 15 takes 44 700, 42 700, 44 200, 46 700 instructions
 * (longer parts spill more), where the one function compiled without the
 * optimizer took 1.3 s less (that unit 2.2 s, in the same sitting) and
 * 65 700 instructions.  Split over units 3 and 4, compiled at once, the
 * Pleiades builds in 2.3 s, against 2.6 s before. */
enum { SERIES_PART_LINES = 20 };

/* Where ty's parted series' parts begin, [*nparts + 1] (malloc'd): a part
 * holds at most SERIES_PART_LINES lines, a pack (LowSerLine.pack) one
 * line as the C compiler sees it, within one order. */
static int *
series_parts(const LowSeries *se, int *nparts)
{
    int *first = xmalloc(((size_t)se->nline + 2) * sizeof *first), n = 0;
    for (int k = 0; k < LOW_SERIES_ORDERS; k++)
        for (int i = se->start[k]; i < se->start[k + 1];) {
            first[n++] = i;
            for (int lines = 0; i < se->start[k + 1] && lines < SERIES_PART_LINES; lines++)
                i += se->line[i].pack ? se->line[i].pack : 1;
        }
    first[n] = se->start[LOW_SERIES_ORDERS];
    *nparts = n;
    return first;
}

/* taylor_run's values a part may read, in the order it takes them: a
 * part takes those its lines read (series_reads), and no others. */
static const struct {
    const char *param, *arg;
} run_values[] = {{"eomc_real t0", "t0"},
                  {"const eomc_real *p", "p"},
                  {"const eomc_real *u", "u"},
                  {"eomc_real *restrict W", "W"},
                  {"eomc_real *restrict X", "X"},
                  {"eomc_tay_solve solve, void *ctx", "solve, ctx"}};
enum { READS_T0 = 1, READS_P = 2, READS_U = 4, READS_W = 8, READS_X = 16, READS_SOLVE = 32 };

static int
cell_reads(const Cells *cells, int c)
{
    return c < 0 ? 0 : cells->place[c % cells->nslot] >= 0 ? READS_X : READS_W;
}

/* What lines from .. to - 1 read of run_values, a bit each. */
static int
series_reads(const LowSeries *se, int from, int to, const Cells *cells)
{
    int r = 0;
    for (int i = from; i < to; i++) {
        const LowSerLine *l = &se->line[i];
        r |= cell_reads(cells, l->dst) | cell_reads(cells, l->over_cell);
        r |= cell_reads(cells, l->x) | cell_reads(cells, l->y);
        for (int t = l->first; t < l->first + l->nterm; t++)
            r |= cell_reads(cells, se->term[t].x) | cell_reads(cells, se->term[t].y);
        if (l->last >= 0)
            r |= cell_reads(cells, se->term[l->last].x) | cell_reads(cells, se->term[l->last].y);
        if (l->kind == LOW_SER_VALUE || l->kind == LOW_SER_SELECT)
            r |= l->src == LOW_TAY_SRC_T   ? READS_T0
                 : l->src == LOW_TAY_SRC_P ? READS_P
                 : l->src == LOW_TAY_SRC_U ? READS_U
                                           : 0;
        if (l->kind == LOW_SER_SOLVE)
            r |= READS_SOLVE | READS_W;
    }
    return r;
}

/* Part's parameters (params) or its call's arguments, those of run_values
 * that reads has, into buf. */
static void
part_values(char *buf, size_t size, int reads, int params)
{
    size_t n = 0;
    buf[0] = 0;
    for (size_t j = 0; j < sizeof run_values / sizeof run_values[0]; j++)
        if (reads & 1 << j)
            n += (size_t)snprintf(buf + n, n < size ? size - n : 0, "%s%s", n ? ", " : "",
                                  params ? run_values[j].param : run_values[j].arg);
    if (!n)
        snprintf(buf, size, "%s", params ? "void" : "");
}

/* The parts of ty's parted series (first, [nparts + 1]: series_parts),
 * NAME_taylor_run_1, ..., in print_series' order: each in the third unit
 * or the fourth, whichever is behind (as emit_taylor cuts the program; a
 * term counted as a temporary), those of the fourth declared after; each
 * takes what its lines read. */
static void
print_series_parts(Printer *pr, const LowTaylor *ty, const int *first, int nparts)
{
    const LowSeries *se = ty->series;
    Cells cells = series_cells(ty, 0);
    char *in4 = xmalloc((size_t)nparts + 1), fname[160], params[200];
    for (int part = 0, k = 0; part < nparts; part++) {
        int i = first[part], end = first[part + 1];
        while (se->start[k + 1] <= i)
            k++;
        long terms = 0;
        for (int j = i; j < end; j++)
            terms += se->line[j].nterm + 1;
        int second = in4[part] = emit_part_half(pr, terms, 1);
        if (second)
            emit_unit2_begin(pr, 1);
        snprintf(fname, sizeof fname, "%s_taylor_run_%d", pr->md->name, part + 1);
        int reads = series_reads(se, i, end, &cells), solves = reads & READS_SOLVE;
        part_values(params, sizeof params, reads, 1);
        emit_line(pr, "/* Lines %d .. %d of taylor_run's order %d%s. */", i - se->start[k],
                  end - 1 - se->start[k], k, second ? ", in the fourth unit" : "");
        const char *type = second ? (solves ? "EOMC_PART EOMC_UNCHECKED int"
                                            : "EOMC_PART EOMC_UNCHECKED void")
                                  : (solves ? "static EOMC_NOINLINE EOMC_UNCHECKED int"
                                            : "static EOMC_NOINLINE EOMC_UNCHECKED void");
        emit_head(pr, type, fname, params);
        print_lines(pr, se, i, end, &cells);
        emit_line(pr, solves ? "    return 0;\n}\n" : "}\n");
        if (second)
            emit_unit2_end(pr);
    }
    for (int part = 0; part < nparts; part++) { /* called before they are defined */
        snprintf(fname, sizeof fname, "%s_taylor_run_%d", pr->md->name, part + 1);
        int reads = series_reads(se, first[part], first[part + 1], &cells);
        part_values(params, sizeof params, reads, 1);
        if (in4[part])
            emit_decl(pr,
                      reads & READS_SOLVE ? "EOMC_PART EOMC_UNCHECKED int"
                                          : "EOMC_PART EOMC_UNCHECKED void",
                      fname, params, ";");
    }
    free(in4);
}

/* taylor_run written out (lower_series.c): orders 0 .. LOW_SERIES_ORDERS
 * - 1, the state's cells in the caller's X (Cells) and the others in the
 * local W; then what the caller reads of the others copied into T. */
static void
print_series(Printer *pr, const LowTaylor *ty, int lanes, const int *first)
{
    const LowSeries *se = ty->series;
    int ns = ty->nstate, nslot = ty->nslot, parted = first != NULL;
    Cells cells = series_cells(ty, lanes);
    const int *place = cells.place;
    const char *zero = lanes ? "EOMC_V4C(0.0)" : "0.0";
    emit_line(pr, "    %s W[%d]; /* a slot's coefficient j at W[j * %d + its column], but the",
              lanes ? "eomc_v4" : "eomc_real", se->ncell, nslot);
    emit_line(pr, "                   * state's: X[j * %d + i], q's then v's */", ns);
    for (int i = 0, j; i < se->nzero_out; i = j) { /* 0 at every step: W's by runs */
        int c = se->zero_out[i], at = place[c % nslot];
        for (j = i + 1; at < 0 && j < se->nzero_out && se->zero_out[j] == se->zero_out[j - 1] + 1 &&
                        place[se->zero_out[j] % nslot] < 0;)
            j++;
        if (at >= 0) /* (X has the orders to K) */
            emit_line(pr, "    if (K >= %d)\n        X[%d] = %s; /* at every step */",
                      c / nslot, c / nslot * ns + at, zero);
        else if (j - i == 1)
            emit_line(pr, "    W[%d] = %s; /* at every step */", c, zero);
        else
            emit_line(pr, "    for (int c = %d; c <= %d; c++) /* 0 at every step */\n"
                          "        W[c] = %s;", c, se->zero_out[j - 1], zero);
    }
    for (int k = 0, part = 0; k < LOW_SERIES_ORDERS; k++) {
        if (k > 0) {
            emit_line(pr, "    if (K == %d)", k);
            emit_line(pr, "        goto out;");
        }
        emit_line(pr, "    /* order %d */", k);
        if (!parted)
            print_lines(pr, se, se->start[k], se->start[k + 1], &cells);
        for (char args[80]; parted && first[part] < se->start[k + 1]; part++) {
            int reads = series_reads(se, first[part], first[part + 1], &cells);
            part_values(args, sizeof args, reads, 0);
            if (reads & READS_SOLVE) /* (a solve can fail) */
                emit_line(pr, "    if (%s_taylor_run_%d(%s)) {\n        EOMC_ZEROUPPER();\n"
                              "        return -1;\n    }", pr->md->name, part + 1, args);
            else
                emit_line(pr, "    %s_taylor_run_%d(%s);", pr->md->name, part + 1, args);
        }
    }
    emit_line(pr, "out:");
    for (int e = 0; e < ty->nevent + ty->nmode; e++) {
        int g = ty->g_slot[e], seen = 0;
        for (int f = 0; f < e; f++)
            seen |= ty->g_slot[f] == g;
        if (g < 0 || seen)
            continue;
        emit_line(pr, "    for (int j = 0; j < K; j++) /* event function %d */", e);
        int c = se->col[g];
        if (place[c] >= 0)
            emit_line(pr, "        T[%d * S + j] = X[j * %d + %d];", g, ns, place[c]);
        else
            emit_line(pr, "        T[%d * S + j] = W[j * %d + %d];", g, nslot, c);
    }
    int nv = ty->acc_slot ? 0 : pr->md->nv; /* (the hook tests M_0 itself) */
    for (int j = 0; j < nv; j++) {
        int m = ty->M_slot[j * nv + j], seen = 0;
        for (int i = 0; i < j; i++) /* equal masses share a slot */
            seen |= ty->M_slot[i * nv + i] == m;
        if (!seen)
            emit_line(pr, "    T[%d * S] = W[%d]; /* M's diagonal, entry %d */", m, se->col[m], j);
    }
    emit_line(pr, "    EOMC_ZEROUPPER(); /* (eomc_taylor.h) */");
    emit_line(pr, "    return 0;");
}

/* taylor_run (eomc_model.h): each order of the program, then the state's
 * next coefficients, M being constant and diagonal; written out where
 * lower_series could.  Only the doubles': the extended twin's reference
 * sums its series by the runtime's loop. */
static void
print_run(Printer *pr, const LowTaylor *ty)
{
    const char *nm = pr->md->name;
    int general = ty->acc_slot != NULL;
    emit_line(pr, "#ifndef EOMC_EXTENDED");
    emit_line(pr, "/* The whole series to order K in one call (taylor_run): each order k of");
    emit_line(pr, " * the program above, then q's coefficient k + 1 from its rate's k, and");
    if (general) {
        emit_line(pr, " * q''s from a_k = -M_0^-1 (h_k + sum_{i=1..k} M_i a_{k-i}), solved by the");
        emit_line(pr, " * caller's hook (M_0 factored at k = 0), then / (k + 1).  Written out to");
        emit_line(pr, " * order %d, each recurrence's sum with its indices fixed (the same", LOW_SERIES_ORDERS);
        emit_line(pr, " * arithmetic in the same order); above that 1, for the caller's loop. */");
    } else {
        emit_line(pr, " * q''s, M being constant and diagonal, from (h_j / M_jj) / -(k + 1).");
        if (ty->series) {
            emit_line(pr, " * Written out to order %d, each recurrence's sum with its indices fixed",
                      LOW_SERIES_ORDERS);
            emit_line(pr, " * (the same arithmetic in the same order); above that, the loop. */");
        } else {
            emit_line(pr, " */");
        }
    }
    int nparts = 0, *first = NULL;
    if (ty->series && ty->series->parted) {
        first = series_parts(ty->series, &nparts);
        print_series_parts(pr, ty, first, nparts);
    }
    char fname[160];
    snprintf(fname, sizeof fname, "%s_taylor_run", nm);
    emit_head(pr, "static int", fname,
              "int K, eomc_real t0, const eomc_real *p, const eomc_real *u, eomc_real *T, "
              "eomc_real *X, eomc_tay_solve solve, void *ctx");
    emit_line(pr, "    const int S = K + 1;");
    if (general) {
        emit_line(pr, "    if (K > %d)", LOW_SERIES_ORDERS);
        emit_line(pr, "        return 1;");
        emit_line(pr, "    (void)S, (void)T, (void)t0, (void)p, (void)u;");
        print_series(pr, ty, 0, first);
        emit_line(pr, "}");
        emit_line(pr, "#endif\n");
        free(first);
        return;
    }
    emit_line(pr, "    (void)solve, (void)ctx;");
    int ns = ty->nstate; /* the state's slots, q's then v's: X's order */
    const char *in = "    ";
    if (ty->series) {
        emit_line(pr, "    if (K > %d) {", LOW_SERIES_ORDERS);
        in = "        ";
    }
    print_ints_in(pr, in, "state", ty->state_slot, ns);
    emit_line(pr, "%sfor (int i = 0; i < %d; i++)", in, ns);
    emit_line(pr, "%s    T[state[i] * S] = X[i];", in);
    emit_line(pr, "%sfor (int k = 0; k < K; k++) {", in);
    emit_line(pr, "%s    %s_taylor(k, K, t0, p, u, T);", in, nm);
    char in2[16];
    snprintf(in2, sizeof in2, "%s    ", in);
    for (int i = ty->nstep; i < ty->nstep + ty->nrun; i++)
        print_call(pr, in2, "eomc_tay_", &ty->step[i]);
    emit_line(pr, "%s}", in);
    emit_line(pr, "%sfor (int j = 1; j <= K; j++)", in);
    emit_line(pr, "%s    for (int i = 0; i < %d; i++)", in, ns);
    emit_line(pr, "%s        X[j * %d + i] = T[state[i] * S + j];", in, ns);
    emit_line(pr, "%sreturn 0;", in);
    if (ty->series) {
        emit_line(pr, "    }");
        print_series(pr, ty, 0, first);
    }
    emit_line(pr, "}");
    emit_line(pr, "#endif\n");
    free(first);
}

/* taylor_run4 (eomc_model.h): the written-out series once more, each
 * value a vector of the lanes' (print_series with lanes), so that each
 * lane computes its run's bits; a libm function or a mode's choice is
 * taken a lane at a time, by eomc_taylor.h's helpers (eomc_v4_pow, ...). */
static void
print_run4(Printer *pr, const LowTaylor *ty)
{
    const char *nm = pr->md->name;
    emit_line(pr, "#if !defined(EOMC_EXTENDED) && defined(EOMC_V4)");
    emit_line(pr, "/* taylor_run for EOMC_LANES runs at once, a run a lane (eomc_model.h):");
    emit_line(pr, " * the lines above on vectors, each lane's the same arithmetic in the");
    emit_line(pr, " * same order; above order %d 1, for one run at a time. */", LOW_SERIES_ORDERS);
    char fname[160];
    snprintf(fname, sizeof fname, "%s_taylor_run4", nm);
    emit_head(pr, "static int", fname,
              "int K, const double *t0s, const double *ps, const double *us, double *Ts, "
              "double *Xs");
    emit_line(pr, "    const int S = K + 1;");
    emit_line(pr, "    if (K > %d)\n        return 1;", LOW_SERIES_ORDERS);
    emit_line(pr, "    const eomc_v4 t0 = *(const eomc_v4 *)t0s;");
    emit_line(pr, "    const eomc_v4 *p = (const eomc_v4 *)ps, *u = (const eomc_v4 *)us;");
    emit_line(pr, "    eomc_v4 *T = (eomc_v4 *)Ts, *X = (eomc_v4 *)Xs;");
    emit_line(pr, "    (void)S, (void)T, (void)t0, (void)p, (void)u;");
    print_series(pr, ty, 1, NULL);
    emit_line(pr, "}");
    emit_line(pr, "#endif\n");
}

void
emit_taylor(Printer *pr, const LowTaylor *ty)
{
    if (ty->why)
        return;
    const LowModel *md = pr->md;
    int nq = md->nq, nv = md->nv; /* nv = nq without speeds of their own */
    emit_line(pr, "/* Taylor's method (eomc_taylor.h): coefficient k of the series about t0");
    if (ty->nc) {
        emit_line(pr, " * of every value mass_bias, events, constraint (at q'' = 0) and");
        emit_line(pr, " * c_levels compute, slot s's at T[s (K + 1) ...], from their orders");
        emit_line(pr, " * 0 .. k-1 and the caller's coefficient k of q");
    } else {
        emit_line(pr, " * of every value mass_bias and events compute, slot s's at T[s (K + 1)");
        emit_line(pr, " * ...], from their orders 0 .. k-1 and the caller's coefficient k of q");
    }
    if (ty->qd_slot)
        emit_line(pr, " * and of the speeds v (taylor_q, taylor_v), with the kinematic equation's");
    if (ty->qd_slot)
        emit_line(pr, " * q' = W(q) v (taylor_qd): %d slots, %d calls. */", ty->nslot, ty->nstep);
    else
        emit_line(pr, " * and q' (taylor_q, taylor_v): %d slots, %d calls. */", ty->nslot,
                  ty->nstep);
    /* cut as emit_func.c cuts a long function (LOWER_PART_SIZE): each
     * part a C function of its own, taylor calling them in turn */
    int nparts = (ty->nstep + LOWER_PART_SIZE - 1) / LOWER_PART_SIZE;
    if (nparts < 1)
        nparts = 1;
    const char *params = "int k, int K, eomc_real t0, const eomc_real *p, const eomc_real *u, "
                         "eomc_real *T";
    char fname[160];
    if (nparts > 1)
        print_wrappers(pr, ty, 0);
    /* the parts balanced between the third unit and the fourth, a call
     * counted as a temporary of the Jacobian's (each about as much of the
     * C compiler's time) */
    char *in4 = xmalloc((size_t)nparts);
    for (int part = 0, declared = 0; part < nparts; part++) {
        int first = part * LOWER_PART_SIZE, end = first + LOWER_PART_SIZE;
        if (end > ty->nstep)
            end = ty->nstep;
        int second = in4[part] = emit_part_half(pr, end - first, nparts > 1);
        if (second) {
            emit_unit2_begin(pr, 0);
            if (!declared++)
                print_wrappers(pr, ty, 1);
        }
        if (nparts > 1) {
            snprintf(fname, sizeof fname, "%s_taylor_%d", md->name, part + 1);
            emit_line(pr, "/* Calls %d .. %d of taylor%s. */", first, end - 1,
                      second ? ", in the fourth unit" : "");
            emit_head(pr, second ? "EOMC_PART void" : "static EOMC_NOINLINE void", fname, params);
        } else {
            snprintf(fname, sizeof fname, "%s_taylor", md->name);
            emit_head(pr, "static void", fname, params);
        }
        print_calls(pr, ty, first, end, nparts > 1 ? "tay_" : "eomc_tay_");
        emit_line(pr, "}\n");
        if (second)
            emit_unit2_end(pr);
    }
    for (int part = 0; part < nparts; part++) { /* called before they are defined */
        snprintf(fname, sizeof fname, "%s_taylor_%d", md->name, part + 1);
        if (in4[part])
            emit_decl(pr, "EOMC_PART void", fname, params, ";");
    }
    free(in4);
    if (nparts > 1) {
        snprintf(fname, sizeof fname, "%s_taylor", md->name);
        emit_head(pr, "static void", fname, params);
        for (int part = 0; part < nparts; part++)
            emit_line(pr, "    %s_taylor_%d(k, K, t0, p, u, T);", md->name, part + 1);
        emit_line(pr, "}\n");
    }
    if (ty->nrun)
        print_run(pr, ty);
    if (ty->nrun && ty->series && ty->series->lanes)
        print_run4(pr, ty);
    if (ty->qd_slot) {
        emit_line(pr, "/* The slots of q and v the caller writes, those of q' = W(q) v, and");
        emit_line(pr, " * those of M (row-major, in the speeds), h and the event functions g");
        emit_line(pr, " * (-1: none, or zero at every order). */");
    } else {
        emit_line(pr, "/* The slots of q and q' the caller writes, and those of M (row-major),");
        emit_line(pr, " * h and the event functions g (-1: none, or zero at every order). */");
    }
    print_ints(pr, "taylor_q", ty->q_slot, nq);
    print_ints(pr, "taylor_v", ty->v_slot, nv);
    if (ty->qd_slot) { /* eomc_model's alone: the twin's reference reads the doubles' */
        emit_line(pr, "#ifndef EOMC_EXTENDED");
        print_ints(pr, "taylor_qd", ty->qd_slot, nq);
        emit_line(pr, "#endif");
    }
    print_ints(pr, "taylor_M", ty->M_slot, nv * nv);
    print_ints(pr, "taylor_h", ty->h_slot, nv);
    if (ty->nevent + ty->nmode)
        print_ints(pr, "taylor_g", ty->g_slot, ty->nevent + ty->nmode);
    if (ty->nc) {
        if (ty->nonlinear) {
            emit_line(pr, "/* The constraints: the slots of q'' the caller writes, B = df/dq''");
            emit_line(pr, " * (row-major), f at that q'', and their own levels (c_levels' pos");
            emit_line(pr, " * and vel). */");
            print_ints(pr, "taylor_a", ty->a_slot, nv);
        } else {
            emit_line(pr, "/* The constraints' f = B q'' + b: B = df/dq'' (row-major) and b, f at");
            emit_line(pr, " * q'' = 0, and their own levels (c_levels' pos and vel). */");
        }
        print_ints(pr, "taylor_B", ty->B_slot, ty->nc * nv);
        print_ints(pr, "taylor_f", ty->f_slot, ty->nc);
        print_ints(pr, "taylor_pos", ty->pos_slot, ty->nc);
        print_ints(pr, "taylor_vel", ty->vel_slot, ty->nc);
    }
    emit_line(pr, "");
}
