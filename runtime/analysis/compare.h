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
 *
 * A model with switches (max, min, clamp, step) has its run's flips
 * compared with the reference's too: the same switches in the same order
 * (flips at one instant in any order), each pair's times no further
 * apart than the run's error explains.  The flip's time moves by
 * |ds/dx_i| / |ds/dt| per unit error of component i (the reference
 * records it, eomc.h); the run's error of component i there is taken as
 * the largest over the rows before its flip, and at least what its
 * tolerance asks, atol + rtol scale_i (with fixed steps, which ask for
 * none, the largest over the rows up to the first after it: the rows
 * before a flip early in a run may have no error yet), and at least its
 * error at the flip itself: the run's state there against the
 * reference's at its own flip, carried to the run's time along the
 * reference's rate before the flip (both on the branch before it, so
 * that the flips' times apart do not count; where the reference knows
 * its states at flips: not a file's); COMPARE_TIME_SLACK
 * times the sum over the components, and never less than
 * COMPARE_TIME_ULPS units of rounding of the times, is how far apart the
 * two may be.  Where they part, the rows after it compare different
 * branches of the motion.
 */
#ifndef EOMC_COMPARE_H
#define EOMC_COMPARE_H

#include "eomc.h"

/* The reference's own step control measures a component against the
 * same floor: it is resolved on this scale, no finer. */
#define COMPARE_FLOOR 1e-6

/* The slack on the times a switch's flips may differ by (above): the
 * sensitivities are first order, and a file's reference has no states at
 * its flips, whose run's error is then the rows'. */
#define COMPARE_TIME_SLACK 10.0
#define COMPARE_TIME_ULPS 16.0

/* Where a run's flips part from the reference's. */
typedef struct ComparePart {
    double t;            /* the earlier of the two flips there */
    int ref_k, run_k;    /* the switch each flipped there (-1: none) */
    double t_ref, t_run; /* and when (NAN: none) */
    double allowed;      /* how far apart the run's error explains */
    double err_before;   /* the largest error over the rows before t */
} ComparePart;

typedef struct Compare {
    const eomc_reference *ref;
    int nx;              /* nq + nv */
    long k;              /* the next row */
    double *scale;       /* [nx] each component's scale (above) */
    double *max, *end;   /* [nx] its largest error over the rows, its last */
    double err_max, err_end; /* the largest over the components */
    double *row_err;     /* [nrows] each row's largest error */
    long nflip, flip_cap, flip_open; /* the run's flips; the first one whose
                                      * errors are not in yet */
    double *flip_t;      /* [flip_cap] when */
    int *flip_k;         /* [flip_cap] which switch */
    double *flip_eps;    /* [flip_cap 2 nx] the errors before it, and up to the
                          * first row at or after it (above) */
    double *flip_x;      /* [flip_cap nx] the run's state there */
    int parted;          /* compare_switches found them parting, at part */
    ComparePart part;
} Compare;

/* For runs against ref (nx = ref->nx components, the first nq of them
 * the coordinates); 0, or -1 when memory runs out (compare_free is safe
 * either way). */
int compare_init(Compare *c, const eomc_reference *ref, int nq);
void compare_free(Compare *c);
/* Forget the rows and flips measured: a new run. */
void compare_reset(Compare *c);
/* The run's flip of switch k (eomc_model.h's mode k) at t, as it fires,
 * the state x [nx] there; 0, or -1 when memory runs out. */
int compare_flip(Compare *c, int k, double t, const double *x);
/* After the run (rtol, atol its tolerances, 0 for fixed steps; t0, t_end
 * its span): whether its flips part from the reference's, 1 with
 * c->part, else 0 (also when the reference's are not known). */
int compare_switches(Compare *c, double rtol, double atol, double t0, double t_end);
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
