/*
 * diag: diagnostics carried as source locations from parse to error.
 *
 * Every user-facing error is printed as
 *
 *     file:line:col: error: message
 *      12 |     mass: m1 +* 2
 *         |              ^
 *
 * and then control returns to the innermost diag_catch point (set by the
 * loader with setjmp), or the process exits with status 2 if there is none.
 * Lines and columns are 1-based.
 */
#ifndef EOMC_DIAG_H
#define EOMC_DIAG_H

#include <setjmp.h>
#include <stddef.h>
#include <stdio.h>

typedef struct SrcLoc {
    const char *file; /* path as given by the user; NULL = no location */
    int line, col;    /* 1-based; 0 = unknown */
} SrcLoc;

/* Register a file's text so that errors can quote its lines.  The text is
 * borrowed and must outlive the diagnostics that refer to it. */
void diag_add_source(const char *file, const char *text, size_t len);
void diag_forget_sources(void);

/* Where diag_error jumps to; returns the previous target.  NULL exits(2). */
jmp_buf *diag_set_jump(jmp_buf *target);

/* Where errors, warnings and notes are printed; returns the previous
 * stream.  NULL = stderr (the default).  The fuzz targets send them to
 * /dev/null, so that formatting them is still exercised.  Internal errors
 * always go to stderr. */
FILE *diag_set_output(FILE *out);

_Noreturn void diag_error(SrcLoc at, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Errors printed since the last diag_reset_errors.  A loader that goes on
 * after an error (to report the independent ones in one run) catches it
 * with its own diag_set_jump, and stops at the end if any were counted. */
int diag_error_count(void);
void diag_reset_errors(void);

/* Unwind to the current target without a message: for input that depends
 * on something already reported (a define that failed), where a second
 * message would only repeat the first.  Only after an error was counted. */
_Noreturn void diag_abandon(void);
void diag_warning(SrcLoc at, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void diag_note(SrcLoc at, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* The names among `n` candidates nearest to `name` (edit distance), each
 * quoted: "'rk4' or 'rkf45'" when several are as near; NULL if none is
 * close enough to be a plausible typo.  The text lives until the next
 * call. */
const char *diag_nearest(const char *name, const char *const *cands, int n);

/* Internal invariant failures: a bug in eomc, not in the user's input. */
#define diag_unreachable() diag_internal(__FILE__, __LINE__)
_Noreturn void diag_internal(const char *file, int line);

#endif
