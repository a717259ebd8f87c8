/*
 * signals: SIGINT and SIGTERM during a run.  The handler only notes the
 * signal; the row being written is finished and the run stops there
 * (rows_write returns SIGNALS_STOPPED), with the conventional exit status
 * 128 + the signal.
 */
#ifndef EOMC_SIGNALS_H
#define EOMC_SIGNALS_H

/* The status a row callback stops the run with on a signal (no EOMC_
 * status, no callback's own). */
enum { SIGNALS_STOPPED = -2 };

/* Catch SIGINT and SIGTERM until signals_restore puts back the handlers
 * before. */
void signals_catch(void);
void signals_restore(void);
/* The signal caught (SIGINT or SIGTERM), or 0. */
int signals_caught(void);

#endif
