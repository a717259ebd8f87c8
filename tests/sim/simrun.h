/*
 * simrun.h: run a built simulator as a user would (a command line), and
 * read back what it printed: `--accel` lines or the CSV.
 */
#ifndef EOMC_SIMRUN_H
#define EOMC_SIMRUN_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Run `cmd` through the shell; its stdout into a malloc'd string. */
static inline char *
sim_capture(const char *cmd, int *status)
{
    FILE *f = popen(cmd, "r");
    if (!f) {
        perror("popen");
        exit(1);
    }
    size_t cap = 1 << 16, n = 0, k;
    char *buf = malloc(cap);
    while ((k = fread(buf + n, 1, cap - n - 1, f)) > 0)
        if ((n += k) == cap - 1)
            buf = realloc(buf, cap *= 2);
    buf[n] = '\0';
    int st = pclose(f);
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return buf;
}

/* The value printed by --accel on the line "NAME VALUE", or NAN. */
static inline double
sim_accel_value(const char *out, const char *name)
{
    size_t len = strlen(name);
    for (const char *p = out; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
        if (strncmp(p, name, len) == 0 && p[len] == ' ')
            return strtod(p + len + 1, NULL);
    return 0.0 / 0.0;
}

/* A CSV table: header names and rows of numbers. */
typedef struct SimTable {
    int ncol, nrow;
    char **col;
    double *v; /* v[row * ncol + col] */
} SimTable;

static inline int
sim_column(const SimTable *t, const char *name)
{
    for (int j = 0; j < t->ncol; j++)
        if (strcmp(t->col[j], name) == 0)
            return j;
    fprintf(stderr, "no column '%s'\n", name);
    exit(1);
}

static inline SimTable
sim_parse_csv(char *text)
{
    SimTable t = {0, 0, NULL, NULL};
    char *save = NULL, *line = strtok_r(text, "\n", &save);
    if (!line)
        return t;
    t.col = malloc(256 * sizeof *t.col);
    for (char *s2 = NULL, *c = strtok_r(line, ",", &s2); c; c = strtok_r(NULL, ",", &s2))
        t.col[t.ncol++] = strdup(c);
    size_t cap = 1024;
    t.v = malloc(cap * (size_t)t.ncol * sizeof *t.v);
    while ((line = strtok_r(NULL, "\n", &save))) {
        if ((size_t)t.nrow == cap)
            t.v = realloc(t.v, (cap *= 2) * (size_t)t.ncol * sizeof *t.v);
        char *p = line;
        for (int j = 0; j < t.ncol; j++) {
            t.v[(size_t)t.nrow * (size_t)t.ncol + (size_t)j] = strtod(p, &p);
            if (*p == ',')
                p++;
        }
        t.nrow++;
    }
    return t;
}

static inline void
sim_table_free(SimTable *t)
{
    for (int j = 0; j < t->ncol; j++)
        free(t->col[j]);
    free(t->col);
    free(t->v);
}

static inline double
sim_at(const SimTable *t, int row, int col)
{
    return t->v[(size_t)row * (size_t)t->ncol + (size_t)col];
}

#endif
