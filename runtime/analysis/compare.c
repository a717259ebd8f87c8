/*
 * compare: a run's rows against the reference, component by component
 * (compare.h).
 */
#include "compare.h"
#include "base/numfmt.h"
#include "model/state.h"

#include <float.h>
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
    c->row_err = calloc((size_t)(ref->nrows > 0 ? ref->nrows : 1), sizeof *c->row_err);
    if (!c->scale || !c->row_err)
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
    free(c->row_err);
    free(c->flip_t);
    free(c->flip_k);
    free(c->flip_eps);
    free(c->flip_x);
    c->scale = c->max = c->end = c->row_err = c->flip_t = c->flip_eps = c->flip_x = NULL;
    c->flip_k = NULL;
    c->nflip = c->flip_cap = 0;
}

void
compare_reset(Compare *c)
{
    c->k = 0;
    c->err_max = c->err_end = 0;
    c->nflip = c->flip_open = 0;
    c->parted = 0;
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
    c->row_err[c->k] = c->err_end;
    /* the flips up to this row have their errors to it */
    for (; c->flip_open < c->nflip && c->flip_t[c->flip_open] <= c->ref->t[c->k];
         c->flip_open++)
        memcpy(c->flip_eps + (2 * (size_t)c->flip_open + 1) * (size_t)c->nx, c->max,
               (size_t)c->nx * sizeof *c->max);
    c->k++;
}

int
compare_flip(Compare *c, int k, double t, const double *x)
{
    size_t nx = (size_t)c->nx;
    if (c->nflip == c->flip_cap) {
        long cap = c->flip_cap ? 2 * c->flip_cap : 16;
        double *ft = realloc(c->flip_t, (size_t)cap * sizeof *ft);
        if (ft)
            c->flip_t = ft;
        int *fk = realloc(c->flip_k, (size_t)cap * sizeof *fk);
        if (fk)
            c->flip_k = fk;
        double *fe = realloc(c->flip_eps, 2 * (size_t)cap * nx * sizeof *fe);
        if (fe)
            c->flip_eps = fe;
        double *fx = realloc(c->flip_x, (size_t)cap * nx * sizeof *fx);
        if (fx)
            c->flip_x = fx;
        if (!ft || !fk || !fe || !fx)
            return -1;
        c->flip_cap = cap;
    }
    c->flip_t[c->nflip] = t;
    c->flip_k[c->nflip] = k;
    memcpy(c->flip_x + (size_t)c->nflip * nx, x, nx * sizeof *x);
    /* the rows before it are in (a run's rows come after the step they
     * lie in, and a flip ends its step) */
    memcpy(c->flip_eps + 2 * (size_t)c->nflip * nx, c->max, nx * sizeof *c->max);
    c->nflip++;
    return 0;
}

/* How far apart the reference's flip i and the run's may be (compare.h). */
static double
allowed(const Compare *c, long i, double rtol, double atol, double floor)
{
    const double *sens = c->ref->sw_sens + (size_t)i * (size_t)c->nx;
    const double *eps = c->flip_eps + 2 * (size_t)i * (size_t)c->nx;
    const double *xr = c->ref->sw_x ? c->ref->sw_x + (size_t)i * (size_t)c->nx : NULL;
    const double *fr = c->ref->sw_f ? c->ref->sw_f + (size_t)i * (size_t)c->nx : NULL;
    const double *x = c->flip_x + (size_t)i * (size_t)c->nx;
    double dt = c->flip_t[i] - c->ref->sw_t[i];
    int fixed = rtol == 0 && atol == 0;
    double sum = 0;
    for (int j = 0; j < c->nx; j++) {
        double e = fixed ? eps[c->nx + j] : fmax(eps[j], atol + rtol * c->scale[j]);
        if (xr && fr) /* the error at the flip, on the branch before it */
            e = fmax(e, fabs(x[j] - (xr[j] + fr[j] * dt)));
        if (sens[j] > 0 && e > 0)
            sum += sens[j] * e;
    }
    return COMPARE_TIME_SLACK * sum + floor;
}

/* The run's flips i and j swapped. */
static void
swap_flips(Compare *c, long i, long j)
{
    double t = c->flip_t[i];
    int k = c->flip_k[i];
    c->flip_t[i] = c->flip_t[j], c->flip_k[i] = c->flip_k[j];
    c->flip_t[j] = t, c->flip_k[j] = k;
    double *a = c->flip_eps + 2 * (size_t)i * (size_t)c->nx;
    double *b = c->flip_eps + 2 * (size_t)j * (size_t)c->nx;
    for (int n = 0; n < 2 * c->nx; n++) {
        double e = a[n];
        a[n] = b[n], b[n] = e;
    }
    a = c->flip_x + (size_t)i * (size_t)c->nx;
    b = c->flip_x + (size_t)j * (size_t)c->nx;
    for (int n = 0; n < c->nx; n++) {
        double e = a[n];
        a[n] = b[n], b[n] = e;
    }
}

int
compare_switches(Compare *c, double rtol, double atol, double t0, double t_end)
{
    const eomc_reference *ref = c->ref;
    c->parted = 0;
    if (ref->nswitch < 0)
        return 0;
    for (; c->flip_open < c->nflip; c->flip_open++) /* after the last row */
        memcpy(c->flip_eps + (2 * (size_t)c->flip_open + 1) * (size_t)c->nx, c->max,
               (size_t)c->nx * sizeof *c->max);
    double floor = COMPARE_TIME_ULPS * DBL_EPSILON *
                   fmax(fmax(fabs(t0), fabs(t_end)), t_end - t0);
    ComparePart *p = &c->part;
    for (long i = 0; i < ref->nswitch || i < c->nflip; i++) {
        int has_ref = i < ref->nswitch, has_run = i < c->nflip;
        *p = (ComparePart){.ref_k = has_ref ? ref->sw_k[i] : -1,
                           .run_k = has_run ? c->flip_k[i] : -1,
                           .t_ref = has_ref ? ref->sw_t[i] : NAN,
                           .t_run = has_run ? c->flip_t[i] : NAN, .allowed = NAN};
        if (has_ref && has_run) {
            p->allowed = allowed(c, i, rtol, atol, floor);
            /* flips at one instant, to what the error explains, in any order */
            for (long j = i + 1; p->run_k != p->ref_k && j < c->nflip; j++)
                if (c->flip_k[j] == p->ref_k && fabs(c->flip_t[j] - p->t_ref) <= p->allowed &&
                    fabs(c->flip_t[j] - p->t_run) <= p->allowed) {
                    swap_flips(c, i, j);
                    p->run_k = c->flip_k[i];
                    p->t_run = c->flip_t[i];
                }
            if (p->run_k == p->ref_k && fabs(p->t_run - p->t_ref) <= p->allowed)
                continue;
        }
        p->t = !has_run ? p->t_ref : !has_ref ? p->t_run : fmin(p->t_ref, p->t_run);
        p->err_before = 0;
        for (long k = 0; k < c->k && ref->t[k] < p->t; k++)
            p->err_before = fmax(p->err_before, c->row_err[k]);
        c->parted = 1;
        return 1;
    }
    return 0;
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
