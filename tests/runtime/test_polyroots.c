/*
 * runtime/step/polyroots.c (Taylor's method's events), on polynomials built
 * from known roots, c = k prod (x - r_i), expanded here:
 *  - two roots in (0, 1], close or far apart, with roots outside beside
 *    them: 2, and the cut lies strictly between the first two;
 *  - one root, or none (a minimum above zero, every root outside): 1, 0;
 *  - a root at 0 is not counted, a root at 1 is;
 *  - a double root (a tangency) is one;
 *  - 2000 random sets of 0 to 5 roots in (-0.5, 1.5) at least 1e-3
 *    apart, of random degree up to 12 with complex pairs besides: the
 *    count and the cut as the roots say.
 */
#include "../unit/check.h"
#include "step/polyroots.h"

#include <math.h>

enum { DMAX = 24 };

/* c [d + 1] := k prod_i (x - r_i) times prod_j ((x - a_j)^2 + b_j^2). */
static int
expand(const double *r, int nr, const double *ab, int npair, double k, double *c)
{
    int d = 0;
    c[0] = k;
    for (int i = 0; i < nr; i++, d++) { /* times (x - r_i) */
        c[d + 1] = c[d];
        for (int j = d; j > 0; j--)
            c[j] = c[j - 1] - r[i] * c[j];
        c[0] *= -r[i];
    }
    for (int p = 0; p < npair; p++) { /* times x^2 - 2 a x + a^2 + b^2 */
        double a = ab[2 * p], b2 = ab[2 * p + 1] * ab[2 * p + 1];
        for (int rep = 0; rep < 2; rep++, d++) {
            c[d + 1] = 0;
        }
        for (int j = d; j >= 0; j--) {
            double v = (a * a + b2) * c[j];
            if (j >= 1)
                v += -2 * a * c[j - 1];
            if (j >= 2)
                v += c[j - 2];
            c[j] = v;
        }
    }
    return d;
}

/* Whether n and cut are what the roots r [nr] say (a double root counts
 * once); lo_hi: the first two in (0, 1]. */
static int
count(const double *r, int nr, double cut, int n, double *lo_hi)
{
    double first = INFINITY, second = INFINITY;
    int in = 0;
    for (int i = 0; i < nr; i++)
        if (r[i] > 0 && r[i] <= 1 && r[i] != first) {
            in++;
            if (r[i] < first)
                second = first, first = r[i];
            else if (r[i] < second)
                second = r[i];
        }
    lo_hi[0] = first, lo_hi[1] = second;
    int want = in < 2 ? in : 2;
    return n == want && (n < 2 || (cut > first && cut < second));
}

static void
one(const char *what, const double *r, int nr, const double *ab, int npair, int want)
{
    double c[DMAX + 1], cut, lh[2];
    int d = expand(r, nr, ab, npair, 1.7, c);
    int n = poly_first_roots(c, d, &cut);
    int right = count(r, nr, cut, n, lh);
    CHECK(n == want && right, "%s: %d roots in (0, 1] (want %d), cut %.6g", what, n, want, cut);
}

int
main(void)
{
    one("0.3 and 0.31", (double[]){0.3, 0.31}, 2, NULL, 0, 2);
    one("0.2, 0.7 and 0.9", (double[]){0.2, 0.7, 0.9}, 3, NULL, 0, 2);
    one("0.2, 0.7, and -0.4, 1.3 outside", (double[]){-0.4, 0.2, 1.3, 0.7}, 4, NULL, 0, 2);
    one("one root, 0.45", (double[]){0.45, 1.6, -2}, 3, NULL, 0, 1);
    one("none: a minimum 1e-3 above zero at 0.5", NULL, 0, (double[]){0.5, 0.0316}, 1, 0);
    one("none: roots outside", (double[]){-0.1, 1.1, 2.5}, 3, NULL, 0, 0);
    one("a root at 0 and one at 0.5", (double[]){0, 0.5}, 2, NULL, 0, 1);
    one("roots at 0.4 and 1", (double[]){0.4, 1}, 2, NULL, 0, 2);
    one("a double root at 0.5 (a tangency)", (double[]){0.5, 0.5}, 2, NULL, 0, 1);
    one("the graze: 0.0447 and 0.134", (double[]){0.0447, 0.134}, 2,
        (double[]){0.5, 0.3, 1.2, 0.8}, 2, 2);
    int bad = 0, total = 2000;
    for (int t = 0; t < total; t++) {
        double r[5], ab[6], c[DMAX + 1], cut, lh[2];
        int nr = (int)check_rand(0, 5.999), npair = (int)check_rand(0, 3.999);
        for (int i = 0; i < nr; i++) {
            int apart;
            do { /* at least 1e-3 apart, and from 0 and 1 */
                r[i] = check_rand(-0.5, 1.5);
                apart = fabs(r[i]) > 1e-3 && fabs(r[i] - 1) > 1e-3;
                for (int j = 0; j < i; j++)
                    apart &= fabs(r[i] - r[j]) > 1e-3;
            } while (!apart);
        }
        for (int p = 0; p < npair; p++)
            ab[2 * p] = check_rand(-1, 2), ab[2 * p + 1] = check_rand(0.05, 1);
        int d = expand(r, nr, ab, npair, check_rand(-3, 3), c);
        int n = poly_first_roots(c, d, &cut);
        if (!count(r, nr, cut, n, lh) && bad++ < 5)
            printf("# roots %d in, found %d, cut %.17g, first two %.17g %.17g\n", nr, n, cut,
                   lh[0], lh[1]);
    }
    CHECK(bad == 0, "%d random polynomials: the count and the cut as their roots say, %d "
          "wrong", total, bad);
    return check_done();
}
