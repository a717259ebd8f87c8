/*
 * plan: the runs of a sweep (plan.h).  A swept name is a parameter, not
 * fixed and not swept twice.
 */
#include "plan.h"
#include "base/numfmt.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A swept name: a parameter, not fixed, not swept twice. */
static int
sweep_name(Options *c, const eomc_model *m, const Plan *pl, const char *name, const char *where)
{
    int k = -1;
    for (int i = 0; i < m->np && k < 0; i++)
        if (!strcmp(m->p_names[i], name))
            k = i;
    if (k < 0) {
        const char *hint = opt_nearest(name, m->p_names, m->np, "");
        return opt_usage(c, "%s: '%s' is not a parameter%s", where, name, hint);
    }
    if (m->p_fixed[k])
        return opt_usage(c, "%s: parameter '%s' is fixed in %s%s%s (folded into the code): "
                     "it cannot be swept", where, name, *m->scene ? "scene '" : "the spec's "
                     "scene", m->scene, *m->scene ? "'" : "");
    for (int j = 0; j < pl->nparam; j++)
        if (!strcmp(pl->names[j], name))
            return opt_usage(c, "%s: '%s' is swept twice", where, name);
    return EOMC_OK;
}

/* --sweep NAME=START:STOP:COUNT ...: the grid, the first sweep slowest. */
static int
plan_grid(Options *c, const eomc_model *m, Plan *pl)
{
    double *start = calloc((size_t)c->nsweep, sizeof *start);
    double *stop = calloc((size_t)c->nsweep, sizeof *stop);
    long *count = calloc((size_t)c->nsweep, sizeof *count);
    pl->names = calloc((size_t)c->nsweep, sizeof *pl->names);
    int rc = start && stop && count && pl->names ? EOMC_OK : opt_usage(c, "out of memory");
    pl->nruns = 1;
    for (int j = 0; j < c->nsweep && rc == EOMC_OK; j++) {
        char *arg = c->sweep[j], *eq = strchr(arg, '='), *end;
        if (!eq || eq == arg)
            rc = opt_usage(c, "--sweep: expected NAME=START:STOP:COUNT, not '%s'", arg);
        else {
            /* the name copied out, argv left as it is: the caller's, maybe
             * read-only or shared by threads (eomc_main_mem) */
            char *name = strndup(arg, (size_t)(eq - arg));
            rc = name ? sweep_name(c, m, pl, name, "--sweep") : opt_usage(c, "out of memory");
            pl->names[pl->nparam++] = name;
            errno = 0;
            start[j] = strtod(eq + 1, &end);
            if (rc == EOMC_OK && *end == ':')
                stop[j] = strtod(end + 1, &end);
            if (rc == EOMC_OK && *end == ':')
                count[j] = strtol(end + 1, &end, 10);
            if (rc == EOMC_OK && (*end || errno || !isfinite(start[j]) || !isfinite(stop[j]) ||
                                  count[j] < 1 || count[j] > 1000000))
                rc = opt_usage(c, "--sweep %s=%s: expected START:STOP:COUNT, two finite numbers "
                           "and a count from 1 to 1000000", name, eq + 1);
            if (rc == EOMC_OK && pl->nruns > 10000000 / count[j])
                rc = opt_usage(c, "--sweep: more than 10000000 runs");
            if (rc == EOMC_OK) /* a bad count is not multiplied in */
                pl->nruns *= count[j];
        }
    }
    if (rc == EOMC_OK && !(pl->values = calloc((size_t)(pl->nruns * pl->nparam), sizeof(double))))
        rc = opt_usage(c, "out of memory");
    for (long r = 0; rc == EOMC_OK && r < pl->nruns; r++) {
        long rest = r;
        for (int j = pl->nparam - 1; j >= 0; j--) { /* the last sweep fastest */
            long i = rest % count[j];
            rest /= count[j];
            pl->values[r * pl->nparam + j] =
                count[j] == 1 ? start[j]
                              : start[j] + (stop[j] - start[j]) * (double)i / (double)(count[j] - 1);
        }
    }
    free(start);
    free(stop);
    free(count);
    return rc;
}

/* --sweep-file FILE: a header of parameter names, then one set per row. */
static int
plan_file(Options *c, const eomc_model *m, Plan *pl)
{
    FILE *f = fopen(c->sweep_file, "r");
    if (!f)
        return opt_usage(c, "--sweep-file: cannot read '%s': %s", c->sweep_file, strerror(errno));
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0, capv = 0;
    int rc = EOMC_OK;
    ssize_t got;
    while (rc == EOMC_OK && (got = getline(&line, &cap, f)) >= 0) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (!*line)
            continue;
        if (!pl->names) { /* the header: a name in every column */
            int cols = 1;
            for (char *p = line; *p; p++)
                cols += *p == ',';
            if (!(pl->names = calloc((size_t)cols, sizeof *pl->names)))
                rc = opt_usage(c, "out of memory");
            for (char *tok = line, *next; tok && rc == EOMC_OK; tok = next) {
                if ((next = strchr(tok, ',')))
                    *next++ = '\0';
                char where[4200];
                snprintf(where, sizeof where, "%s:%ld:%ld", c->sweep_file, lineno,
                         (long)(tok - line) + 1);
                rc = *tok ? sweep_name(c, m, pl, tok, where)
                          : opt_usage(c, "%s: an empty name: the header names the parameter of "
                                  "every column", where);
                pl->names[pl->nparam++] = strdup(tok);
            }
            continue; /* the names are copies: the line is reused */
        }
        if (pl->nruns == capv) {
            capv = capv ? 2 * capv : 64;
            double *v = realloc(pl->values, (size_t)(capv * pl->nparam) * sizeof *v);
            if (!v) {
                rc = opt_usage(c, "out of memory");
                break;
            }
            pl->values = v;
        }
        char *p = line;
        for (int j = 0; j < pl->nparam && rc == EOMC_OK; j++) {
            char *end;
            errno = 0;
            double v = strtod(p, &end);
            if (end == p || errno || !isfinite(v) || (*end != ',' && *end) ||
                (j < pl->nparam - 1 && *end != ',') || (j == pl->nparam - 1 && *end))
                rc = opt_usage(c, "%s:%ld:%ld: expected %d finite number%s separated by commas "
                           "(the value of %s here)", c->sweep_file, lineno,
                           (long)(p - line) + 1, pl->nparam, num_plural(pl->nparam),
                           pl->names[j]);
            pl->values[pl->nruns * pl->nparam + j] = v;
            p = end + (*end == ',');
        }
        pl->nruns++;
    }
    free(line);
    fclose(f);
    if (rc == EOMC_OK && (!pl->names || pl->nruns == 0))
        rc = opt_usage(c, "%s: no parameter sets (a header of names, then one row per run)",
                   c->sweep_file);
    return rc;
}

int
plan_make(Options *c, const eomc_model *m, Plan *pl)
{
    *pl = (Plan){0};
    return c->sweep_file ? plan_file(c, m, pl) : plan_grid(c, m, pl);
}

void
plan_free(Plan *pl)
{
    for (int j = 0; j < pl->nparam; j++)
        free((char *)pl->names[j]);
    free(pl->names);
    free(pl->values);
}
