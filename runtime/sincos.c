/*
 * sincos: the sines and cosines of several angles at once.
 *
 * A model's right-hand side starts with the sines and cosines of its
 * turns' angles (five for a 5-link chain, 90 for a 30-body tree of 3-axis
 * joints), and glibc's scalar sin and cos take about 12 ns per angle
 * here, more than half of a 5-link chain's right-hand side.  glibc also
 * has them as vector functions (libmvec, linked through -lm): 4 angles per
 * call with AVX2, each result within 4 ulp (the scalar ones: within 1),
 * where the CPU has the instructions.  Elsewhere, one at a time.
 */
#include "eomc_model.h"

#include <math.h>

#if defined(EOMC_HAVE_LIBMVEC) && defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

/* glibc's vector math, by the x86-64 vector function ABI's names (each
 * passes its vector in a register only AVX has).  Its AVX-512 versions
 * are left alone: as fast for a handful of angles, they slowed the scalar
 * code after them by a quarter (gen_tree 30's tables: 15.1 -> 19.4 us,
 * against 13.9 with these). */
#define AVX2 __attribute__((target("avx2")))
AVX2 __m256d _ZGVdN4v_sin(__m256d);
AVX2 __m256d _ZGVdN4v_cos(__m256d);

enum { LANES = 4 };

AVX2 static void
sincos4(const double *x, double *s, double *c)
{
    __m256d v = _mm256_loadu_pd(x);
    _mm256_storeu_pd(s, _ZGVdN4v_sin(v));
    _mm256_storeu_pd(c, _ZGVdN4v_cos(v));
}

/* Whole vectors; the angles left over one at a time (a padded vector
 * costs more than two or three scalar ones: chain 5's five angles, 125
 * against 102 ns a right-hand side). */
static int
sincos_vector(int n, const double *x, double *s, double *c)
{
    int done = 0;
    for (; n - done >= LANES; done += LANES)
        sincos4(x + done, s + done, c + done);
    return done;
}
#define SINCOS_VECTOR 1
#endif

void
eomc_sincos(int n, const double *x, double *s, double *c)
{
#ifdef SINCOS_VECTOR
    int done = n >= LANES && __builtin_cpu_supports("avx2") ? sincos_vector(n, x, s, c) : 0;
#else
    int done = 0;
#endif
    for (int i = done; i < n; i++) {
        s[i] = sin(x[i]);
        c[i] = cos(x[i]);
    }
}
