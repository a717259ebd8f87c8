/*
 * summary: what a simulator says about a run on stderr, after it: the
 * statistics (--stats), the paragraph (--summary), the error against the
 * reference (--error), the warnings a run's tallies call for, what the
 * CSV holds after a failure or a signal, and the progress line during it.
 */
#ifndef EOMC_SUMMARY_H
#define EOMC_SUMMARY_H

#include "options.h"
#include "rows.h"

/* The progress line of a run on a terminal (stderr): t, after the first
 * second, every tenth of a second. */
typedef struct Progress {
    const char *name;    /* the model's */
    double t_end;
    double wall0, next_show;
    int tty, shown;
} Progress;
void summary_progress_start(Progress *p, const eomc_model *m, double t_end);
/* eomc_run_opts.on_progress, ctx a Progress. */
void summary_progress(void *ctx, double t);
/* The line cleared, when it was shown. */
void summary_progress_end(Progress *p);

/* --stats: one "name value" line each. */
void summary_stats(const Rows *w, const eomc_stats *st, int stabilize);
/* --summary: a paragraph, wrapped. */
void summary_text(const Options *c, const eomc_model *m, const Rows *w, const eomc_stats *st);
/* The one line of --error alone: the largest error and the component
 * that keeps the fewest digits. */
void summary_error(const Options *c, const eomc_model *m, const Rows *w,
                   const eomc_reference *ref);
/* The warnings of a run: an ill-conditioned solve, a conserved quantity
 * that drifted beyond what the steps' errors allow, an event's reset off
 * the constraints. */
void summary_warnings(const Options *c, const eomc_model *m, const eomc_stats *st,
                      const Rows *w);
/* After a numerical failure: what the CSV holds. */
void summary_kept(const Options *c, const Rows *w);
/* After signal sig stopped the run: where, and the rows written. */
void summary_interrupted(const Options *c, const Rows *w, int sig);

#endif
