/*
 * csv_table.h: what the simulator's command-line tests read back from its
 * output (test_cli.c, test_speeds_cli.c): a CSV's rows of numbers, and the
 * value of one "NAME VALUE" line of --accel.
 */
#ifndef EOMC_TEST_CSV_TABLE_H
#define EOMC_TEST_CSV_TABLE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A CSV: its header line and rows of numbers (ok = 0 if any field is not
 * a number or a row has another width). */
typedef struct Table {
    char header[1024];
    int ncol, nrow, ok;
    double *v; /* v[row * ncol + col] */
} Table;

static inline Table
parse_csv(const char *text)
{
    Table t = {{0}, 1, 0, 1, NULL};
    size_t len = strcspn(text, "\n");
    snprintf(t.header, sizeof t.header, "%.*s", (int)len, text);
    for (const char *c = t.header; *c; c++)
        t.ncol += *c == ',';
    const char *p = text + len;
    size_t cap = 0;
    while (*p == '\n' && p[1]) {
        p++;
        if ((size_t)t.nrow == cap) {
            cap = cap ? 2 * cap : 256;
            if (!(t.v = realloc(t.v, cap * (size_t)t.ncol * sizeof *t.v)))
                exit(1);
        }
        for (int j = 0; j < t.ncol; j++) {
            char *end;
            t.v[(size_t)t.nrow * (size_t)t.ncol + (size_t)j] = strtod(p, &end);
            t.ok &= end != p && (*end == (j + 1 < t.ncol ? ',' : '\n') || *end == '\0');
            p = *end == ',' ? end + 1 : end;
        }
        p += strcspn(p, "\n");
        t.nrow++;
    }
    return t;
}

/* The value on the line "NAME VALUE" of text (--accel's output), or NAN. */
static inline double
accel_value(const char *text, const char *name)
{
    size_t len = strlen(name);
    for (const char *p = text; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
        if (strncmp(p, name, len) == 0 && p[len] == ' ')
            return strtod(p + len + 1, NULL);
    return NAN;
}

#endif
