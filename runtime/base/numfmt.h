/*
 * numfmt: numbers as the CSVs and reports print them: the shortest
 * decimal that reads back as the same double (0.05, not
 * 0.050000000000000003), as the generated C prints its constants: exact,
 * and readable.
 */
#ifndef EOMC_NUMFMT_H
#define EOMC_NUMFMT_H

#include <stddef.h>
#include <stdio.h>

/* Longest output: sign, 17 digits, point, exponent, NUL. */
enum { NUM_MAX = 32 };

/* x into buf [NUM_MAX]; returns buf.  -0 is "0": it reads back as a zero,
 * and a sign on a zero (x'' -0) only puzzles. */
const char *num_shortest(char *buf, double x);
/* x onto f. */
void num_put(FILE *f, double x);
/* "s" after a count of n, or "": "1 row", "2 rows". */
const char *num_plural(long n);

#endif
