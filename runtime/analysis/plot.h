/*
 * plot: pictures drawn by gnuplot, for the report and for a run.
 *
 * A run's --plot FILE (.svg or .png) shows the coordinates against time;
 * the conserved quantity's drift on a second panel, when the model has
 * one; then the scene's outputs, each on a panel of its own (outputs have
 * no units in the spec: nothing says two may share an axis), or with more
 * than six, grouped by the magnitude of their values.  The data is the
 * run's own CSV.
 */
#ifndef EOMC_PLOT_H
#define EOMC_PLOT_H

#include "eomc.h"

#include <stdio.h>

/* Whether gnuplot can be run (checked before anything is computed). */
int plot_have_gnuplot(void);
/* Whether path names a picture gnuplot is asked for here: .svg or .png. */
int plot_format_ok(const char *path);

/* A string for gnuplot: single quotes, '' for a quote. */
void plot_string(FILE *f, const char *s);

/* The terminal for path (.png: pngcairo, else svg) at width x height,
 * writing to tmp (plot_finish renames it to path). */
void plot_terminal(FILE *f, const char *path, const char *tmp, int width, int height);

/* Run gnuplot on the script (then removed) and move tmp to path; 0, or
 * EOMC_EUSAGE after saying why (prog: for the message). */
int plot_finish(const char *prog, const char *script, const char *tmp, const char *path);

/* A run's plot of the CSV data file (the simulator's columns, m's
 * model), into path: h0 the conserved quantity's first value, resets
 * whether events reset the state, out_scale [nout] each output's largest
 * |value| over the rows (for grouping them). */
int plot_trajectory(const char *prog, const eomc_model *m, const char *data,
                    const char *path, double h0, int resets, const double *out_scale);

#endif
