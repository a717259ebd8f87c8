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

/* The nearest of cands[0..n) to name, or NULL if none is a plausible typo. */
static inline const char *
nearest_name(const char *name, const char *const *cands, int n)
{
    const char *best = NULL;
    int bestd = 99;
    for (int i = 0; i < n; i++) {
        int d = nearest_distance(name, cands[i]);
        if (d < bestd)
            bestd = d, best = cands[i];
    }
    int len = (int)strlen(name), allowed = len / 3;
    if (allowed < 1 && len >= 3)
        allowed = 1;
    return bestd <= allowed ? best : NULL;
}

#endif
