/*
 * sincos: the sines and cosines of several angles at once.
 *
 * A model's right-hand side starts with the sines and cosines of its
 * turns' angles (five for a 5-link chain, 90 for a 30-body tree of 3-axis
 * joints), and glibc's scalar sin and cos take about 12 ns per angle
 * here, more than half of a 5-link chain's right-hand side.  glibc also
 * has them as vector functions (libmvec, linked through -lm): 8 angles per
 * call with AVX-512, 4 with AVX2, each result within 4 ulp (the scalar
 * ones: within 1), where the CPU has the instructions.  Elsewhere, one at
 * a time.
 */
#include "eomc_model.h"

#include <math.h>

#if defined(EOMC_HAVE_LIBMVEC) && defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

/* glibc's vector math, by the x86-64 vector function ABI's names (each
 * passes its vector in a register only the target's instructions have) */
#define AVX512 __attribute__((target("avx512f")))
#define AVX2 __attribute__((target("avx2")))
AVX512 __m512d _ZGVeN8v_sin(__m512d);
AVX512 __m512d _ZGVeN8v_cos(__m512d);
AVX2 __m256d _ZGVdN4v_sin(__m256d);
AVX2 __m256d _ZGVdN4v_cos(__m256d);

/* Up to 8 angles: the lanes past n are read and written as nothing. */
AVX512 static void
sincos8(int n, const double *x, double *s, double *c)
{
    __mmask8 m = (__mmask8)((1u << n) - 1);
    __m512d v = _mm512_maskz_loadu_pd(m, x);
    _mm512_mask_storeu_pd(s, m, _ZGVeN8v_sin(v));
    _mm512_mask_storeu_pd(c, m, _ZGVeN8v_cos(v));
}

AVX2 static void
sincos4(const double *x, double *s, double *c)
{
    __m256d v = _mm256_loadu_pd(x);
    _mm256_storeu_pd(s, _ZGVdN4v_sin(v));
    _mm256_storeu_pd(c, _ZGVdN4v_cos(v));
}
#define SINCOS_VECTOR 1
#endif

void
eomc_sincos(int n, const double *x, double *s, double *c)
{
#ifdef SINCOS_VECTOR
    enum { LANES8 = 8, LANES4 = 4 };
    if (__builtin_cpu_supports("avx512f")) {
        for (; n > 0; n -= LANES8, x += LANES8, s += LANES8, c += LANES8)
            sincos8(n < LANES8 ? n : LANES8, x, s, c);
        return;
    }
    if (__builtin_cpu_supports("avx2"))
        for (; n >= LANES4; n -= LANES4, x += LANES4, s += LANES4, c += LANES4)
            sincos4(x, s, c);
#endif
    for (int i = 0; i < n; i++) {
        s[i] = sin(x[i]);
        c[i] = cos(x[i]);
    }
}
