/*
 * eomc_sincos (runtime/base/sincos.c), which generated code calls for the sines
 * and cosines of a function's angles, several at once where the machine
 * has vector instructions: every value within 2 ulp (runtime/base/sincos.c
 * measures 1.5; the C library's scalar functions, used elsewhere, are
 * within 1) of sinl and cosl in extended precision, for every count from 1
 * to 19 (whole vectors and the lanes left over), for angles up to 1e5,
 * for the doubles nearest to multiples of pi/2 up to the vector code's
 * limit of 2^20 and on both sides of it (where the reduced angle is
 * smallest, so its relative error largest), and for large ones (1e9 to
 * 1e22, where argument reduction is the hard part); NaN and the
 * infinities give NaN, -0 keeps its sign; nothing past the n-th entry is
 * written.
 */
#include "../unit/check.h"
#include "eomc_model.h"

#include <float.h>
#include <string.h>

enum { NMAX = 19, ULPS = 2 };

/* |got - want| in units of the last place of want rounded to double. */
static double
ulps(double got, long double want)
{
    double w = (double)want, a = fabs(w);
    double ulp = a > 0 ? nextafter(a, INFINITY) - a : DBL_TRUE_MIN;
    return (double)fabsl((long double)got - want) / ulp;
}

/* The largest error in ulps over n angles x, and whether s[n], c[n] (a
 * sentinel) stayed as they were. */
static double
worst(int n, const double *x, int *kept)
{
    double s[NMAX + 1], c[NMAX + 1], err = 0;
    s[n] = c[n] = 42.0;
    eomc_sincos(n, x, s, c);
    for (int i = 0; i < n; i++) {
        double e1 = ulps(s[i], sinl((long double)x[i]));
        double e2 = ulps(c[i], cosl((long double)x[i]));
        err = fmax(err, fmax(e1, e2));
        if (!(e1 <= ULPS && e2 <= ULPS)) /* NaN counts as a failure */
            err = INFINITY;
    }
    *kept = s[n] == 42.0 && c[n] == 42.0;
    return err;
}

int
main(void)
{
    double x[NMAX + 1];
    int all_kept = 1, kept;
    double err = 0;
    for (int n = 1; n <= NMAX; n++) /* angles over [-10, 10], 20 000 per count */
        for (int r = 0; r < 1000; r++) {
            for (int i = 0; i < n; i++)
                x[i] = -10.0 + 20.0 * (double)((r * 7919 + i * 104729) % 100003) / 100003.0;
            err = fmax(err, worst(n, x, &kept));
            all_kept &= kept;
        }
    CHECK(err <= ULPS && all_kept,
          "1 to %d angles in [-10, 10]: within %.2f ulp of sinl, cosl (<= %d); nothing "
          "written past n", NMAX, err, ULPS);

    double big = 0;
    for (int k = 0; k < 200; k++) {
        for (int i = 0; i < 8; i++)
            x[i] = pow(10.0, 1 + 4.0 * (k * 8 + i) / 1600.0) * (i % 2 ? -1 : 1);
        big = fmax(big, worst(8, x, &kept));
    }
    CHECK(big <= ULPS, "|angle| from 10 to 1e5: within %.2f ulp", big);
    /* k pi/2 rounded, and its two neighbours, for k = 1 .. 2^20 * 2/pi
     * spread log-uniformly; then around 2^20 itself */
    double near = 0;
    for (int k = 0; k < 2000; k++) {
        double m = floor(pow(667544.0, k / 1999.0)), at = m * 1.57079632679489661923;
        double y[NMAX] = {at, nextafter(at, 0), nextafter(at, INFINITY), -at};
        near = fmax(near, worst(4, y, &kept));
    }
    double edge = 0x1p20, e[6] = {nextafter(edge, 0), edge, nextafter(edge, INFINITY),
                                  -edge, 0x1p20 - 0.5, 0x1p20 + 0.5};
    near = fmax(near, worst(6, e, &kept));
    CHECK(near <= ULPS, "the doubles nearest to k pi/2 up to 2^20, and around 2^20: within "
          "%.2f ulp", near);
    double huge = 0;
    for (int k = 0; k < 100; k++) {
        for (int i = 0; i < 5; i++)
            x[i] = pow(10.0, 9 + 13.0 * (k * 5 + i) / 500.0);
        huge = fmax(huge, worst(5, x, &kept));
    }
    CHECK(huge <= ULPS, "|angle| from 1e9 to 1e22: within %.2f ulp", huge);

    double sp[5] = {NAN, INFINITY, -INFINITY, -0.0, 0.5}, s[5], c[5];
    eomc_sincos(5, sp, s, c);
    CHECK(isnan(s[0]) && isnan(c[0]) && isnan(s[1]) && isnan(c[1]) && isnan(s[2]) &&
              isnan(c[2]),
          "NaN and +-inf give NaN");
    CHECK(s[3] == 0 && signbit(s[3]) && c[3] == 1, "-0: sin -0, cos 1");
    double one[2] = {1.0, 0.0}, s1[2] = {7, 7}, c1[2] = {7, 7};
    eomc_sincos(0, one, s1, c1);
    CHECK(s1[0] == 7 && c1[0] == 7, "n = 0 writes nothing");
    return check_done();
}
