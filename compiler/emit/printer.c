/*
 * printer: the lines of the C file, for every printer of emit/ (printer.h).
 */
#include "printer.h"
#include "base/arena.h"
#include "runtime/base/numfmt.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void
emit_line(Printer *pr, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(pr->f, fmt, ap);
    va_end(ap);
    fputc('\n', pr->f);
}

/* What follows is compiled in double only (1: the functions the
 * reference solution does not need), or in both precisions (0). */
void
emit_fence(Printer *pr, int double_only)
{
    if (double_only && !pr->fenced)
        emit_line(pr, "#ifndef EOMC_EXTENDED");
    else if (!double_only && pr->fenced)
        emit_line(pr, "#endif /* EOMC_EXTENDED */\n");
    pr->fenced = double_only;
}

/* Swap the stream and fence being printed with the second half's. */
static void
unit2_swap(Printer *pr)
{
    FILE *f = pr->f;
    pr->f = pr->unit2, pr->unit2 = f;
    int fenced = pr->fenced;
    pr->fenced = pr->fenced2, pr->fenced2 = fenced;
}

int
emit_part_half(Printer *pr, long weight, int movable)
{
    int second = movable && pr->unit2 && pr->nodes[1] < pr->nodes[0];
    pr->nodes[second] += weight;
    return second;
}

void
emit_unit2_begin(Printer *pr, int double_only)
{
    unit2_swap(pr);
    emit_fence(pr, double_only);
    pr->nunit2++;
}

void
emit_unit2_end(Printer *pr)
{
    unit2_swap(pr);
}

void
emit_unfence_pair(Printer *pr)
{
    emit_fence(pr, 0);
    if (pr->unit2) {
        unit2_swap(pr);
        emit_fence(pr, 0);
        unit2_swap(pr);
    }
}

/* Swap the pair being printed with the other. */
static void
pair_swap(Printer *pr)
{
    struct PrinterPair now = {pr->f, pr->unit2, pr->fenced, pr->fenced2, pr->nunit2,
                              {pr->nodes[0], pr->nodes[1]}};
    pr->f = pr->others.f, pr->unit2 = pr->others.unit2;
    pr->fenced = pr->others.fenced, pr->fenced2 = pr->others.fenced2;
    pr->nunit2 = pr->others.nunit2;
    pr->nodes[0] = pr->others.nodes[0], pr->nodes[1] = pr->others.nodes[1];
    pr->others = now;
}

void
emit_unit3_begin(Printer *pr)
{
    pair_swap(pr);
    pr->in3 = 1;
}

void
emit_unit3_end(Printer *pr)
{
    pair_swap(pr);
    pr->in3 = 0;
}

void
emit_entry_head(Printer *pr, const char *type, const char *name, const char *params)
{
    char head[32];
    snprintf(head, sizeof head, "%s %s", pr->in3 ? "static" : "EOMC_ENTRY", type);
    if (!pr->in3) {
        char *decl = NULL;
        size_t len = 0;
        FILE *f = pr->f, *m = xmemstream(&decl, &len);
        pr->f = m;
        emit_decl(pr, head, name, params, ";");
        pr->f = f;
        fclose(m);
        pr->entry = xrealloc(pr->entry, (size_t)(pr->nentry + 1) * sizeof *pr->entry);
        pr->entry[pr->nentry++] = (struct PrinterEntry){decl, pr->fenced};
    }
    emit_head(pr, head, name, params);
}

void
emit_entry_decls(Printer *pr)
{
    for (int k = 0; k < pr->nentry; k++) {
        emit_fence(pr, pr->entry[k].double_only);
        fputs(pr->entry[k].decl, pr->f);
        free(pr->entry[k].decl);
    }
    free(pr->entry);
    pr->entry = NULL;
    pr->nentry = 0;
}

/* "TYPE\nNAME(PARAMS)" then tail, the comma-separated parameters wrapped. */
void
emit_decl(Printer *pr, const char *type, const char *name, const char *params,
           const char *tail)
{
    fprintf(pr->f, "%s\n%s(", type, name);
    int col = (int)strlen(name) + 1;
    for (const char *p = params; *p;) {
        int len = (int)strcspn(p, ",");
        if (p != params && col + 2 + len + 1 > WRAP) {
            fputs(",\n    ", pr->f);
            col = 4;
        } else if (p != params) {
            fputs(", ", pr->f);
            col += 2;
        }
        fprintf(pr->f, "%.*s", len, p);
        col += len;
        p += len;
        p += strspn(p, ", ");
    }
    fprintf(pr->f, ")%s\n", tail);
}

/* "TYPE\nNAME(PARAMS)\n{" */
void
emit_head(Printer *pr, const char *type, const char *name, const char *params)
{
    emit_decl(pr, type, name, params, "\n{");
}

/* The shortest text that reads back as the same double (runtime/base/numfmt.h:
 * 9.81, not 9.8100000000000005; 10, not 1e+01), made to look like a
 * double to C. */
void
emit_const(char *buf, size_t len, double v)
{
    char num[NUM_MAX];
    snprintf(buf, len, "%s", num_shortest(num, v));
    if (!strpbrk(buf, ".eEn"))
        strncat(buf, ".0", len - strlen(buf) - 1);
}
