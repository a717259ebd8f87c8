/*
 * numfmt: the shortest round-trip decimal (numfmt.h).
 */
#include "numfmt.h"

#include <stdlib.h>
#include <string.h>

static int
reads_back(char *buf, int prec, double x)
{
    snprintf(buf, NUM_MAX, "%.*g", prec, x);
    return strtod(buf, NULL) == x;
}

/* The shortest text among the %g forms that read back.  Most computed
 * values need 16 or 17 digits, so 17, 16 and 15 are tried first, and
 * fewer only while they still read back.  The shortest text is not
 * always the fewest digits: 10 is "10", not "1e+01", and 6803754343094190
 * is 16 digits without an exponent rather than 15 with one. */
const char *
num_shortest(char *buf, double x)
{
    char cand[NUM_MAX];
    if (x == 0) { /* -0 too: the sign of a zero is no number a reader wants */
        snprintf(buf, NUM_MAX, "0");
        return buf;
    }
    reads_back(buf, 17, x);
    for (int prec = 16; prec >= 1; prec--) {
        if (!reads_back(cand, prec, x)) {
            if (prec < 15)
                break; /* fewer digits cannot read back either */
            continue;
        }
        if (strlen(cand) <= strlen(buf))
            snprintf(buf, NUM_MAX, "%s", cand);
    }
    return buf;
}

void
num_put(FILE *f, double x)
{
    char buf[NUM_MAX];
    fputs(num_shortest(buf, x), f);
}

const char *
num_plural(long n)
{
    return n == 1 ? "" : "s";
}
