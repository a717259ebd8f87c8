/*
 * compare: a run's rows against the reference solution, component by
 * component.  The error of component i at a row is |x_i - x_ref,i|; over a
 * run, its largest and its last.  Its digits are -log10 of the largest
 * against the component's own scale: its largest |x_ref,i| over the
 * reference's rows, at least COMPARE_FLOOR of the largest of its group
 * (the coordinates, or the speeds: the units differ between them).
 * A big component then no longer hides a small one's error (a top
 * spinning to 739 rad, its nutation rate wrong by 1.31 out of 1.57, read
 * 2.6 digits against the whole state), and one that stays near 0 is
 * measured against what is small beside its group, not against its own
 * rounding.  Used by the report (report.c) and by one run's --error
 * (cli.c), and for --errors FILE.
 */
#ifndef EOMC_COMPARE_H
#define EOMC_COMPARE_H

#include "eomc.h"

/* The reference's own step control measures a component against the
 * same floor: it is resolved on this scale, no finer. */
#define COMPARE_FLOOR 1e-6

typedef struct Compare {
    const eomc_reference *ref;
    int nx;              /* nq + nv */
    long k;              /* the next row */
    double *scale;       /* [nx] each component's scale (above) */
    double *max, *end;   /* [nx] its largest error over the rows, its last */
    double err_max, err_end; /* the largest over the components */
} Compare;

/* For runs against ref (nx = ref->nx components, the first nq of them
 * the coordinates); 0, or -1 when memory runs out (compare_free is safe
 * either way). */
int compare_init(Compare *c, const eomc_reference *ref, int nq);
void compare_free(Compare *c);
/* Forget the rows measured: a new run. */
void compare_reset(Compare *c);
/* The next row, x [nx] (a NaN entry is an infinite error).  Rows past
 * the reference's are ignored. */
void compare_row(Compare *c, const double *x);
/* The component with the fewest digits, and their number (INFINITY when
 * every error is 0). */
int compare_worst(const Compare *c, double *digits);
/* -log10(error / scale): INFINITY for no error. */
double compare_digits(double error, double scale);

/* --errors FILE: one row per run and component,
 *     method,tolerance,fixed_step,component,scale,error_end,error_max,digits
 * (tolerance for an adaptive run, fixed_step h > 0 for a fixed one), end
 * and max [nx] as a Compare has them, or NULL for a run that failed: its
 * error cells are empty. */
void compare_csv_header(FILE *f);
void compare_csv_run(FILE *f, const eomc_model *m, const double *scale, const double *end,
                     const double *max, const char *method, double tol, double h);

#endif
