/*
 * io: the streams the runtime prints on, the calling thread's (io.h).
 */
#define _POSIX_C_SOURCE 200809L
#include "io.h"

#include <unistd.h>

/* NULL: the process's stdout or stderr.  A pointer pair per thread, so
 * one thread's eomc_main_mem never captures another's text. */
static _Thread_local FILE *thread_out, *thread_err;

FILE *
io_out(void)
{
    return thread_out ? thread_out : stdout;
}

FILE *
io_err(void)
{
    return thread_err ? thread_err : stderr;
}

void
io_set(FILE *out, FILE *err, IoSaved *saved)
{
    if (saved)
        *saved = (IoSaved){thread_out, thread_err};
    thread_out = out;
    thread_err = err;
}

void
io_restore(const IoSaved *saved)
{
    thread_out = saved ? saved->out : NULL;
    thread_err = saved ? saved->err : NULL;
}

int
io_err_tty(void)
{
    int fd = fileno(io_err()); /* -1 for a stream in memory */
    return fd >= 0 && isatty(fd);
}

int
io_silence(void)
{
    return freopen("/dev/null", "w", stdout) && freopen("/dev/null", "w", stderr) ? 0 : -1;
}
