/*
 * rtest.h: helpers of the runtime tests: a row recorder for
 * eomc_sim_integrate and run options built from a model's defaults.
 */
#ifndef EOMC_RTEST_H
#define EOMC_RTEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eomc.h"
#include "models.h"

/* Every row passed to the row callback; stops with stop_status at row
 * number stop_at (0-based) when stop_at >= 0. */
typedef struct Rows {
    int n, cap, nx;
    double *t, *x; /* t[n], x[n * nx] */
    int stop_at, stop_status;
} Rows;

static inline void
rows_init(Rows *r, int nq)
{
    *r = (Rows){0, 0, 2 * nq, NULL, NULL, -1, 0};
}

/* The same for a model's states of nq + nv entries. */
static inline void
rows_init_model(Rows *r, const eomc_model *m)
{
    *r = (Rows){0, 0, eomc_nx(m), NULL, NULL, -1, 0};
}

static inline void
rows_free(Rows *r)
{
    free(r->t);
    free(r->x);
    r->t = r->x = NULL;
    r->n = r->cap = 0;
}

static inline int
rows_add(void *ctx, double t, const double *x)
{
    Rows *r = ctx;
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 64;
        r->t = realloc(r->t, (size_t)r->cap * sizeof *r->t);
        r->x = realloc(r->x, (size_t)r->cap * (size_t)r->nx * sizeof *r->x);
        if (!r->t || !r->x) {
            fprintf(stderr, "out of memory\n");
            exit(1);
        }
    }
    r->t[r->n] = t;
    memcpy(r->x + (size_t)r->n * (size_t)r->nx, x, (size_t)r->nx * sizeof *x);
    return r->n++ == r->stop_at ? r->stop_status : 0;
}

/* A whole file as a malloc'd string ("" if it cannot be read). */
static inline char *
slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    size_t n = 0, cap = 4096, k;
    char *buf = malloc(cap);
    if (!buf)
        exit(1);
    while (f && (k = fread(buf + n, 1, cap - n - 1, f)) > 0)
        if ((n += k) == cap - 1 && !(buf = realloc(buf, cap *= 2)))
            exit(1);
    buf[n] = '\0';
    if (f)
        fclose(f);
    return buf;
}

/* Row i's state. */
static inline const double *
rows_x(const Rows *r, int i)
{
    return r->x + (size_t)i * (size_t)r->nx;
}

/* A simulator, or exit: nothing can be tested without one. */
static inline eomc_sim *
sim_new(const eomc_model *m)
{
    eomc_sim *s = eomc_sim_alloc(m);
    if (!s) {
        printf("Bail out! eomc_sim_alloc(%s) returned NULL\n", m->name);
        exit(1);
    }
    return s;
}

/* The model's initial state as x = (q, v). */
static inline void
sim_x0(const eomc_sim *s, double *x)
{
    int n = eomc_sim_model(s)->nq;
    eomc_sim_initial(s, x, x + n);
}

/* Options: the model's defaults with this span, interval and method. */
static inline eomc_run_opts
opts_for(const eomc_model *m, double t_end, double dt, const char *method,
         double rtol, double atol)
{
    eomc_run_opts o = eomc_run_defaults(m);
    o.t0 = 0.0;
    o.t_end = t_end;
    o.dt = dt;
    o.method = method;
    o.rtol = rtol;
    o.atol = atol;
    o.h_fixed = 0.0;
    o.max_steps = 0;
    o.on_progress = NULL;
    return o;
}

/* Is every number of every row finite? */
static inline int
rows_finite(const Rows *r)
{
    for (int i = 0; i < r->n; i++) {
        if (!isfinite(r->t[i]))
            return 0;
        for (int j = 0; j < r->nx; j++)
            if (!isfinite(rows_x(r, i)[j]))
                return 0;
    }
    return 1;
}

#endif
