/*
 * check.h: a minimal TAP harness (in the spirit of minctest.h).
 * Each CHECK prints one "ok N" / "not ok N" line; check_done() prints
 * the plan and returns the exit status.
 */
#ifndef EOMC_CHECK_H
#define EOMC_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_n, check_failed;
static char check_text[4096]; /* a message, before it is put on one line */

/* The message on one line: a quoted error's line breaks would leave
 * lines TAP does not know. */
static inline void
check_print(void)
{
    for (char *c = check_text; *c; c++)
        if (*c == '\n')
            *c = ' ';
    printf("%s\n", check_text);
}

#define CHECK(cond, ...)                                                   \
    do {                                                                   \
        int ok_ = !!(cond);                                                \
        check_n++;                                                         \
        if (!ok_)                                                          \
            check_failed++;                                                \
        printf("%sok %d - ", ok_ ? "" : "not ", check_n);                 \
        if (snprintf(check_text, sizeof check_text, __VA_ARGS__) < 0)      \
            check_text[0] = '\0';                                          \
        check_print();                                                     \
        if (!ok_)                                                          \
            printf("# failed at %s:%d: %s\n", __FILE__, __LINE__, #cond);  \
    } while (0)

/* |got - want| <= tol * max(1, |want|) */
static inline int
check_close(double got, double want, double tol)
{
    double scale = fabs(want) > 1 ? fabs(want) : 1;
    return isfinite(got) && fabs(got - want) <= tol * scale;
}

#define CHECK_NEAR(got, want, tol, ...)                                    \
    do {                                                                   \
        double g_ = (got), w_ = (want);                                    \
        if (!check_close(g_, w_, (tol)))                                   \
            printf("# got %.17g, want %.17g\n", g_, w_);                   \
        CHECK(check_close(g_, w_, (tol)), __VA_ARGS__);                    \
    } while (0)

static inline int
check_done(void)
{
    printf("1..%d\n", check_n);
    return check_failed ? 1 : 0;
}

/* A x = b for the n x n row-major A, by Gaussian elimination with
 * partial pivoting: a test's own solve, independent of the runtime's.  A
 * and b are overwritten, x into b.  0, or -1 where a pivot is 0. */
static inline int
check_solve(double *A, double *b, int n)
{
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r * n + c]) > fabs(A[piv * n + c]))
                piv = r;
        if (A[piv * n + c] == 0)
            return -1;
        for (int k = 0; k < n; k++) {
            double t = A[c * n + k];
            A[c * n + k] = A[piv * n + k], A[piv * n + k] = t;
        }
        double t = b[c];
        b[c] = b[piv], b[piv] = t;
        for (int r = c + 1; r < n; r++) {
            double f = A[r * n + c] / A[c * n + c];
            for (int k = c; k < n; k++)
                A[r * n + k] -= f * A[c * n + k];
            b[r] -= f * b[c];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        double sum = b[r];
        for (int k = r + 1; k < n; k++)
            sum -= A[r * n + k] * b[k];
        b[r] = sum / A[r * n + r];
    }
    return 0;
}

/* Deterministic pseudo-random numbers in [lo, hi) (xorshift64*). */
static unsigned long long check_rng_state = 0x9E3779B97F4A7C15ull;
static inline double
check_rand(double lo, double hi)
{
    unsigned long long x = check_rng_state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    check_rng_state = x;
    double u = (double)((x * 2685821657736338717ull) >> 11) / 9007199254740992.0;
    return lo + (hi - lo) * u;
}

#endif
