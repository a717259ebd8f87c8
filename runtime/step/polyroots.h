/*
 * polyroots.h: the first real roots of a polynomial on an interval, for
 * Taylor's method's events (taylor.c).  Not installed.
 */
#ifndef EOMC_POLYROOTS_H
#define EOMC_POLYROOTS_H

/* The roots of c[0] + c[1] x + ... + c[d] x^d in (0, 1] (d <= POLY_MAX_DEGREE;
 * c is not changed), isolated by Descartes' rule of signs and bisection:
 * 0 when it has none there, 1 for one (or a cluster of roots closer than
 * 2^-POLY_MAX_DEPTH, which it counts as one), 2 for two or more, and then
 * *cut is a point past the first and before the second.  A root at 0
 * itself is not counted. */
enum { POLY_MAX_DEGREE = 64, POLY_MAX_DEPTH = 30 };
int poly_first_roots(const double *c, int d, double *cut);

#endif
