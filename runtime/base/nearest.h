/*
 * nearest.h: the one "did you mean" of eomc, for the compiler's messages
 * (diag_nearest) and the simulator's (cli.c).  Header-only, so that the
 * compiler uses it without linking the runtime.
 *
 * The distance is Damerau-Levenshtein (optimal string alignment): a swap
 * of two neighbouring letters (`bbo` for `bob`, `t_ned` for `t_end`) is
 * the commonest typo, one edit.  A name is a plausible typo of another
 * within a third of its length, at least one edit from three characters
 * on: any one-letter name is one edit from any other, so short names get
 * no guess.
 */
#ifndef EOMC_NEAREST_H
#define EOMC_NEAREST_H

#include <stdio.h>
#include <string.h>

/* Names longer than this are never guessed at. */
enum { NEAREST_MAX = 64 };

static inline int
nearest_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > NEAREST_MAX || lb > NEAREST_MAX)
        return 99;
    int d[NEAREST_MAX + 1][NEAREST_MAX + 1];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[la][lb];
}

/* The names of cands[0..n) nearest to name, when that is a plausible
 * typo: every one at the least distance (`rk45` is one edit from both
 * `rk4` and `rkf45`: naming one would hide the other), each quoted, in
 * cands' order and without repeats: "'rk4' or 'rkf45'", "'a', 'b' or
 * 'c'".  Written to buf (len bytes; past
 * NEAREST_TIES names, or when buf is full, the list ends with ", ..."),
 * and returned; NULL if none is close. */
enum { NEAREST_TIES = 16 };

static inline const char *
nearest_names(const char *name, const char *const *cands, int n, char *buf, size_t len)
{
    int bestd = 99, tie[NEAREST_TIES], nt = 0, more = 0;
    for (int i = 0; i < n; i++) {
        int d = nearest_distance(name, cands[i]);
        if (d < bestd)
            bestd = d, nt = 0, more = 0;
        if (d != bestd)
            continue;
        int repeat = 0;
        for (int j = 0; j < nt && !repeat; j++)
            repeat = !strcmp(cands[tie[j]], cands[i]);
        if (repeat)
            continue;
        if (nt < NEAREST_TIES)
            tie[nt++] = i;
        else
            more = 1;
    }
    int chars = (int)strlen(name), allowed = chars / 3;
    if (allowed < 1 && chars >= 3)
        allowed = 1;
    if (nt == 0 || bestd > allowed || len < 8)
        return NULL;
    size_t at = 0;
    buf[0] = '\0';
    for (int k = 0; k < nt; k++) {
        const char *sep = k == 0 ? "" : k == nt - 1 && !more ? " or " : ", ";
        size_t need = strlen(sep) + strlen(cands[tie[k]]) + 2;
        if (at + need + 5 >= len) { /* room for ", ..." kept */
            more = 1;
            break;
        }
        at += (size_t)snprintf(buf + at, len - at, "%s'%s'", sep, cands[tie[k]]);
    }
    if (more)
        snprintf(buf + at, len - at, "%s...", at ? ", " : "");
    return buf;
}

#endif
