/*
 * hard.h: what the tests of tests/hard share (TAP from tests/unit/check.h).
 * A case runs a model through the runtime's API as the simulator would
 * and keeps the rows, so that the test can hold them against a reference
 * obtained without eomc: a closed form, another model of the same motion,
 * a published value.
 */
#ifndef EOMC_HARD_H
#define EOMC_HARD_H

#include "../unit/check.h"
#include "eomc.h"

#include <stdlib.h>
#include <string.h>

/* The rows of one run: t [nrows], x [nrows * nx]. */
typedef struct Rows {
    long nrows, cap;
    int nx;
    double *t, *x;
    eomc_stats st;
    int rc;
    char error[512];
} Rows;

static int
hard_keep_row(void *ctx, double t, const double *x)
{
    Rows *r = ctx;
    if (r->nrows == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 256;
        r->t = realloc(r->t, (size_t)r->cap * sizeof *r->t);
        r->x = realloc(r->x, (size_t)r->cap * (size_t)r->nx * sizeof *r->x);
        if (!r->t || !r->x)
            return 1;
    }
    r->t[r->nrows] = t;
    memcpy(r->x + r->nrows * r->nx, x, (size_t)r->nx * sizeof *x);
    r->nrows++;
    return 0;
}

/* Run s with o from x0 [2 nq] (the model's initial state when NULL). */
static Rows
hard_run(eomc_sim *s, const eomc_run_opts *o, const double *x0)
{
    const eomc_model *m = eomc_sim_model(s);
    Rows r = {.nx = 2 * m->nq};
    double *x = calloc((size_t)r.nx, sizeof *x);
    if (x0)
        memcpy(x, x0, (size_t)r.nx * sizeof *x);
    else
        eomc_sim_initial(s, x, x + m->nq);
    r.rc = eomc_sim_integrate(s, o, x, hard_keep_row, &r, &r.st);
    if (r.rc != EOMC_OK)
        snprintf(r.error, sizeof r.error, "%s", eomc_sim_error(s));
    free(x);
    return r;
}

static void
hard_free(Rows *r)
{
    free(r->t);
    free(r->x);
    r->t = r->x = NULL;
}

#endif
