/*
 * rows: the rows a simulator writes and reads, in CSV.
 *  - a run's trajectory (-o): t, the coordinates, the velocities (name'),
 *    T, V, E, the conserved quantity when it is not E, the multipliers,
 *    the constraints' residuals and the scene's outputs; the writer also
 *    tallies what the summary reports (the conserved quantity's change,
 *    the largest residual, the error against a reference);
 *  - the events file (--events): t, the event, the state before its action;
 *  - the sweep summary's header (sweep.c writes its rows);
 *  - and a reference read back from such a CSV (eomc_reference_read).
 */
#ifndef EOMC_ROWS_H
#define EOMC_ROWS_H

#include "eomc.h"
#include "analysis/compare.h"

#include <stdio.h>

typedef struct Rows {
    FILE *f;
    eomc_sim *sim;
    long rows;
    int invariant;       /* the model conserves h (or E) */
    double h0, dh;       /* its first value, largest change seen */
    double *res;         /* [nc] constraint residuals of a row, then [nout]
                          * its outputs */
    double res_max;      /* the largest |residual| written */
    const eomc_reference *ref; /* measure against it, or NULL */
    double *arow;        /* [n] scratch: a row's accelerations */
    int rebase;          /* an event reset the state at t_reset: h starts */
    double t_reset;      /* afresh with the first row after it */
    FILE *events;        /* --events FILE, or NULL */
    FILE *tee;           /* a copy of the rows for --plot, or NULL */
    double *out_max;     /* [nout] each output's largest |value| written (for
                          * --plot's panels), after the block's room in res */
    char *blk;           /* rows not yet written, whole rows only: rows.c's ROW_BLOCK
                          * and room for one more (in res's allocation) */
    size_t blen;
    double h_first;      /* the conserved quantity at the first row */
    double T_max;        /* the largest kinetic energy written: the scale of the
                          * energy the motion moves about, for the drift's */
    double t_last;       /* the time of the last row written */
    double err_max, err_end;
    Compare cmp;         /* the errors by component, with ref */
    /* the rows as numbers in memory (eomc_main_extra), CSV text on f only
     * when f is a file (-o FILE): mem [mem_rows * ncols], grown as they
     * come (NULL: not kept) */
    int in_memory, csv, ncols;
    double *mem;
    long mem_rows, mem_cap;
} Rows;

/* A writer of rows to f (NULL: none yet); w.res NULL when out of memory
 * (rows_free is safe either way). */
Rows rows_new(FILE *f, eomc_sim *sim);
void rows_free(Rows *w);
/* The trajectory's columns: t, the state, T, V, E, ... (rows_header's). */
int rows_columns(const eomc_model *m);
/* The trajectory's header line onto f. */
void rows_header(FILE *f, const eomc_model *m);
/* One row at (t, x) (an eomc_row_fn, ctx a Rows): into the block of whole
 * rows, written when it is full.  EOMC_ENUMERIC when the row's
 * accelerations fail; SIGNALS_STOPPED after a signal, the row written. */
int rows_write(void *ctx, double t, const double *x);
/* Write the rows not yet written. */
void rows_flush(Rows *w);
/* An event as it fires (eomc_run_opts.on_event, ctx a Rows): a row of
 * --events FILE, and a reset ends the conserved quantity's comparison with
 * the rows before. */
int rows_event(void *ctx, int k, double t, const double *x);
/* The events file's header line onto f. */
void rows_events_header(FILE *f, const eomc_model *m);
/* A sweep summary's header onto f: the swept names, then columns (a sweep
 * of cells), or status, t, the coordinates, the velocities and the
 * outputs. */
void rows_sweep_header(FILE *f, const eomc_model *m, const char *const *names, int nparam,
                       const char *columns);

/* Open path for opt to write (NULL: stdout); NULL after saying why. */
FILE *rows_open(const char *prog, const char *opt, const char *path);
/* Flush and close f (not stdout); nonzero after saying it failed. */
int rows_close(const char *prog, FILE *f, const char *path);

#endif
