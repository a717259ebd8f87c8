/*
 * diag: print a diagnostic with the offending source line and a caret,
 * then unwind to the loader's catch point.
 *
 * Sources are registered by file name so that any SrcLoc can be quoted;
 * columns count characters (UTF-8 sequences are one column, as libyaml
 * counts them), and the caret line copies the tabs of the source line so
 * that it lines up in a terminal.
 */
#include "diag.h"
#include "runtime/base/nearest.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_SOURCES = 16 };

static struct {
    const char *file, *text;
    size_t len;
} sources[MAX_SOURCES];
static int nsources;
static jmp_buf *jump_target;
static FILE *output; /* NULL: stderr */
static int nerrors;
static SrcLoc last_error; /* one message per place: a second says less */

void
diag_add_source(const char *file, const char *text, size_t len)
{
    if (nsources == MAX_SOURCES) /* keep the newest: shift the oldest out */
        memmove(sources, sources + 1, sizeof sources[0] * --nsources);
    sources[nsources].file = file;
    sources[nsources].text = text;
    sources[nsources].len = len;
    nsources++;
}

void diag_forget_sources(void) { nsources = 0; }

jmp_buf *
diag_set_jump(jmp_buf *target)
{
    jmp_buf *old = jump_target;
    jump_target = target;
    return old;
}

FILE *
diag_set_output(FILE *out)
{
    FILE *old = output;
    output = out;
    return old;
}

/* The text of line `line` (1-based) of `file`, and its length. */
static const char *
source_line(const char *file, int line, size_t *len)
{
    for (int i = nsources - 1; i >= 0; i--) {
        if (strcmp(sources[i].file, file) != 0)
            continue;
        const char *p = sources[i].text, *end = p + sources[i].len;
        int l = 1;
        for (; l < line && p < end; l++) {
            const char *nl = memchr(p, '\n', (size_t)(end - p));
            p = nl ? nl + 1 : end;
        }
        if (l < line) /* past the end; the line after a final newline is empty */
            return NULL;
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        *len = (size_t)((nl ? nl : end) - p);
        if (*len && p[*len - 1] == '\r')
            (*len)--;
        return p;
    }
    return NULL;
}

static int is_cont(unsigned char c) { return (c & 0xC0) == 0x80; }

enum { EXCERPT_MAX = 100 }; /* longer lines are shown around the column */

/* The length of the well-formed UTF-8 sequence at text[i], or 0. */
static size_t
utf8_len(const char *text, size_t i, size_t len)
{
    unsigned char c = (unsigned char)text[i];
    size_t n = c < 0x80 ? 1 : c >= 0xc2 && c < 0xe0 ? 2 : c >= 0xe0 && c < 0xf0 ? 3
             : c >= 0xf0 && c < 0xf5 ? 4 : 0;
    for (size_t k = 1; k < n; k++)
        if (i + k >= len || !is_cont((unsigned char)text[i + k]))
            return 0;
    if (c == 0xed && (unsigned char)text[i + 1] >= 0xa0) /* a UTF-16 surrogate */
        return 0;
    return n;
}

/* The excerpt as the terminal should show it: '?' for a control character
 * (other than tab) and for each byte that is not part of well-formed
 * UTF-8; the error message names such bytes. */
static void
print_shown(FILE *out, const char *text, size_t len)
{
    for (size_t i = 0; i < len;) {
        unsigned char c = (unsigned char)text[i];
        size_t n = utf8_len(text, i, len);
        if (n == 0 || (c < 0x20 && c != '\t') || c == 0x7f) {
            fputc('?', out);
            i++;
            continue;
        }
        fwrite(text + i, 1, n, out);
        i += n;
    }
}

/*  12 | the line
 *     |    ^      */
static void
print_excerpt(FILE *out, SrcLoc at)
{
    size_t len;
    const char *text = source_line(at.file, at.line, &len);
    if (!text)
        return;
    /* a window of a long line: whole characters, starting EXCERPT_MAX/2
     * characters before the column */
    int col = 1, skip = at.col - EXCERPT_MAX / 2;
    const char *pre = "", *post = "";
    while (col < skip && len > 0) {
        text++, len--;
        if (len == 0 || !is_cont((unsigned char)*text))
            col++;
        pre = "...";
    }
    size_t shown = 0;
    for (int chars = 0; shown < len; shown++) {
        if (!is_cont((unsigned char)text[shown]) && chars++ == EXCERPT_MAX) {
            post = "...";
            break;
        }
    }
    char gutter[16];
    int w = snprintf(gutter, sizeof gutter, "%d", at.line);
    fprintf(out, " %s | %s", gutter, pre);
    print_shown(out, text, shown);
    fprintf(out, "%s\n %*s | %*s", post, w, "", (int)strlen(pre), "");
    len = shown;
    for (size_t i = 0; i < len && col < at.col; i++) {
        unsigned char c = (unsigned char)text[i];
        if (is_cont(c))
            continue;
        fputc(c == '\t' ? '\t' : ' ', out);
        col++;
    }
    fputs("^\n", out);
}

/* nonnull: without it gcc -O2 -fsanitize=undefined warns of a null format
 * once the stream is not a constant */
static void __attribute__((format(printf, 3, 0), nonnull(3)))
report(const char *kind, SrcLoc at, const char *fmt, va_list ap)
{
    FILE *out = output ? output : stderr;
    fflush(stdout);
    if (at.file && at.line > 0)
        fprintf(out, "%s:%d:%d: %s: ", at.file, at.line, at.col > 0 ? at.col : 1, kind);
    else if (at.file)
        fprintf(out, "%s: %s: ", at.file, kind);
    else
        fprintf(out, "eomc: %s: ", kind);
    vfprintf(out, fmt, ap);
    fputc('\n', out);
    if (at.file && at.line > 0)
        print_excerpt(out, at);
}

void
diag_error(SrcLoc at, const char *fmt, ...)
{
    int again = nerrors && at.file && last_error.file && at.line > 0 &&
                at.line == last_error.line && at.col == last_error.col &&
                !strcmp(at.file, last_error.file);
    if (!again) {
        va_list ap;
        va_start(ap, fmt);
        report("error", at, fmt, ap);
        va_end(ap);
        nerrors++;
    }
    last_error = at;
    diag_abandon();
}

int diag_error_count(void) { return nerrors; }

void
diag_reset_errors(void)
{
    nerrors = 0;
    last_error = (SrcLoc){NULL, 0, 0};
}

void
diag_abandon(void)
{
    if (nerrors == 0)
        diag_unreachable(); /* unwinding with nothing said would be a silent failure */
    if (jump_target)
        longjmp(*jump_target, 1);
    exit(2);
}

void
diag_warning(SrcLoc at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report("warning", at, fmt, ap);
    va_end(ap);
}

void
diag_note(SrcLoc at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report("note", at, fmt, ap);
    va_end(ap);
}

const char *
diag_nearest(const char *name, const char *const *cands, int n)
{
    static char buf[512];
    return nearest_names(name, cands, n, buf, sizeof buf);
}

void
diag_internal(const char *file, int line)
{
    fflush(stdout);
    fprintf(stderr, "eomc: internal error at %s:%d (a bug in eomc; please report it "
                    "with the spec that caused it)\n", file, line);
    exit(70);
}
