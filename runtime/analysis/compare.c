/*
 * compare: a run's rows against the reference, component by component
 * (compare.h).
 */
#include "compare.h"
#include "base/numfmt.h"
#include "model/state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int
compare_init(Compare *c, const eomc_reference *ref, int n)
{
    int nx = ref->nx;
    size_t N = (size_t)(nx > 0 ? nx : 1);
    *c = (Compare){.ref = ref, .nx = nx};
    c->scale = calloc(3 * N, sizeof *c->scale);
    if (!c->scale)
        return -1;
    c->max = c->scale + N;
    c->end = c->max + N;
    for (long k = 0; k < ref->nrows; k++)
        for (int i = 0; i < nx; i++)
            c->scale[i] = fmax(c->scale[i], fabs(ref->x[(size_t)k * N + (size_t)i]));
    double group[2] = {0, 0};
    for (int i = 0; i < nx; i++)
        group[i >= n] = fmax(group[i >= n], c->scale[i]);
    for (int i = 0; i < nx; i++) /* a group all 0 (a model at rest): the whole state's */
        c->scale[i] = fmax(c->scale[i],
                           COMPARE_FLOOR * (group[i >= n] > 0 ? group[i >= n] : ref->scale));
    return 0;
}

void
compare_free(Compare *c)
{
    free(c->scale);
    c->scale = c->max = c->end = NULL;
}

void
compare_reset(Compare *c)
{
    c->k = 0;
    c->err_max = c->err_end = 0;
    for (int i = 0; i < c->nx; i++)
        c->max[i] = c->end[i] = 0;
}

void
compare_row(Compare *c, const double *x)
{
    if (c->k >= c->ref->nrows)
        return;
    const double *xr = c->ref->x + (size_t)c->k * (size_t)c->nx;
    c->err_end = 0;
    for (int i = 0; i < c->nx; i++) {
        double e = fabs(x[i] - xr[i]);
        if (isnan(e))
            e = INFINITY;
        c->end[i] = e;
        c->max[i] = fmax(c->max[i], e);
        c->err_end = fmax(c->err_end, e);
    }
    c->err_max = fmax(c->err_max, c->err_end);
    c->k++;
}

double
compare_digits(double error, double scale)
{
    if (error == 0)
        return INFINITY;
    return scale > 0 ? -log10(error / scale) : -INFINITY;
}

int
compare_worst(const Compare *c, double *digits)
{
    int worst = 0;
    *digits = INFINITY;
    for (int i = 0; i < c->nx; i++) {
        double d = compare_digits(c->max[i], c->scale[i]);
        if (d < *digits)
            *digits = d, worst = i;
    }
    return worst;
}

void
compare_csv_header(FILE *f)
{
    fprintf(f, "method,tolerance,fixed_step,component,scale,error_end,error_max,digits\n");
}

static void
cell(FILE *f, double x)
{
    fputc(',', f);
    num_put(f, x);
}

void
compare_csv_run(FILE *f, const eomc_model *m, const double *scale, const double *end,
                const double *max, const char *method, double tol, double h)
{
    char name[STATE_NAME_MAX];
    for (int i = 0; i < eomc_nx(m); i++) {
        fprintf(f, "%s", method);
        if (h > 0) {
            fputc(',', f);
            cell(f, h);
        } else {
            cell(f, tol);
            fputc(',', f);
        }
        fprintf(f, ",%s", state_name(m, i, name, sizeof name));
        cell(f, scale[i]);
        if (end && max) {
            cell(f, end[i]);
            cell(f, max[i]);
            cell(f, compare_digits(max[i], scale[i]));
        } else {
            fprintf(f, ",,,");
        }
        fputc('\n', f);
    }
}
