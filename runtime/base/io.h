/*
 * io: the streams the runtime prints on, the calling thread's.
 *
 * Everything the simulator says goes to io_out() and io_err() instead of
 * stdout and stderr, so that eomc_main_mem can hand one thread's text back
 * as memory while another thread runs its own command line (the Python
 * package calls simulators from several threads at once).  A thread that
 * set none prints on stdout and stderr, as a program does.
 */
#ifndef EOMC_IO_H
#define EOMC_IO_H

#include <stdio.h>

/* A thread's streams as they were, for io_restore. */
typedef struct IoSaved {
    FILE *out, *err;
} IoSaved;

/* The calling thread's streams: stdout and stderr unless io_set. */
FILE *io_out(void);
FILE *io_err(void);
/* The calling thread prints on out and err (NULL: stdout, stderr) until
 * io_restore puts back what *saved (unless NULL) gets. */
void io_set(FILE *out, FILE *err, IoSaved *saved);
void io_restore(const IoSaved *saved);
/* Whether io_err() is a terminal (a progress line is shown there only):
 * never for a stream in memory. */
int io_err_tty(void);
/* stdout and stderr go to /dev/null: an MPI rank other than 0, whose
 * rank 0 speaks for the job.  -1 when they cannot. */
int io_silence(void);

#endif
