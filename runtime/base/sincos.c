/*
 * sincos: the sines and cosines of several angles at once.
 *
 * A model's right-hand side starts with the sines and cosines of its
 * turns' angles (five for a 5-link chain, 90 for a 30-body tree of 3-axis
 * joints), and glibc's scalar sin and cos take about 12 ns per angle here,
 * more than half of a 5-link chain's right-hand side.  Where the CPU has
 * AVX2 and FMA, this file computes 4 angles per vector, sine and cosine
 * together: one argument reduction serves both, which glibc's vector
 * functions (libmvec) cannot share between their separate sin and cos.
 * Elsewhere, and for angles too large for the reduction below, it is
 * glibc's scalar functions, one angle at a time.
 *
 * The method is fdlibm's (FreeBSD msun's k_sin.c, k_cos.c): x = k pi/2 + r
 * with |r| <= pi/4, then odd and even polynomials in r of degree 13 and
 * 14, then the quadrant k mod 4 picks and signs them.  pi/2 is split in
 * three doubles, each k times a part subtracted by a fused multiply-add,
 * so r keeps its relative accuracy for |x| up to REDUCE_MAX.  Measured
 * against sinl and cosl over 10^7 angles: within 1.5 ulp (glibc's scalar
 * functions: 1; its vector ones: 4, the bound tests/runtime/test_sincos.c
 * holds this file to).
 */
#include "eomc_model.h"

#include <math.h>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#define AVX2 __attribute__((target("avx2,fma")))

enum { LANES = 4 };

/* Up to this |x|, x - k P1 is exact (both are multiples of P1's last
 * place, and the difference is under pi/4) and k P2 + k P3 carries pi/2's
 * next 106 bits; beyond it, glibc's reduction (Payne-Hanek) is used. */
#define REDUCE_MAX 0x1p20

/* pi/2 = P1 + P2 + P3 to 3 x 53 bits; 2/pi rounded */
static const double P1 = 0x1.921fb54442d18p0, P2 = 0x1.1a62633145c07p-54,
                    P3 = -0x1.f1976b7ed8fbcp-110, TWO_OVER_PI = 0x1.45f306dc9c883p-1;
/* Adding 1.5 * 2^52 rounds to an integer and leaves it in the low bits. */
static const double ROUND = 0x1.8p52;
/* fdlibm's minimax coefficients on |r| <= pi/4 (k_sin.c, k_cos.c) */
static const double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                    S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                    S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
static const double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                    C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                    C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;

#define SPLAT(c) _mm256_set1_pd(c)
#define MADD(a, b, c) _mm256_fmadd_pd(a, b, c)

/* sin and cos of 4 angles, each |x| <= REDUCE_MAX. */
AVX2 static inline void
sincos4(__m256d x, __m256d *sin_x, __m256d *cos_x)
{
    __m256d kr = MADD(x, SPLAT(TWO_OVER_PI), SPLAT(ROUND));
    __m256d k = _mm256_sub_pd(kr, SPLAT(ROUND));
    __m256d r = _mm256_fnmadd_pd(k, SPLAT(P1), x); /* exact */
    r = _mm256_fnmadd_pd(k, SPLAT(P2), r);
    /* the reduced angle is r - e, e = k P3 (|e| < 2^-88): e moves sin r
     * by -e cos r = -e (to 2^-176) and cos r by e sin r, below any last
     * place, so it enters only the sine's last addition, beside the
     * polynomials instead of ahead of them (4 cycles fewer on the path
     * that a right-hand side waits on) */
    __m256d e = _mm256_mul_pd(k, SPLAT(P3));

    /* the polynomials by Estrin's scheme: a shorter dependency chain
     * than Horner's, and the latency is what a right-hand side waits on */
    __m256d z = _mm256_mul_pd(r, r), z2 = _mm256_mul_pd(z, z), z4 = _mm256_mul_pd(z2, z2);
    __m256d ps = MADD(z4, MADD(z, SPLAT(S6), SPLAT(S5)),
                      MADD(z2, MADD(z, SPLAT(S4), SPLAT(S3)), MADD(z, SPLAT(S2), SPLAT(S1))));
    __m256d sin_r = MADD(_mm256_mul_pd(r, z), ps, _mm256_sub_pd(r, e));
    __m256d pc = MADD(z4, MADD(z, SPLAT(C6), SPLAT(C5)),
                      MADD(z2, MADD(z, SPLAT(C4), SPLAT(C3)), MADD(z, SPLAT(C2), SPLAT(C1))));
    /* cos r = 1 - z/2 + z^2 pc, with the rounding of 1 - z/2 added back
     * (k_cos.c), which keeps cos within an ulp near |r| = pi/4 */
    __m256d hz = _mm256_mul_pd(SPLAT(0.5), z), w = _mm256_sub_pd(SPLAT(1.0), hz);
    __m256d lost = _mm256_sub_pd(_mm256_sub_pd(SPLAT(1.0), w), hz);
    __m256d cos_r = _mm256_add_pd(w, MADD(z2, pc, lost));

    /* quadrant k mod 4: bit 0 swaps sine and cosine; bit 1 negates the
     * sine, and bit 1 of k + 1 the cosine */
    __m256i ki = _mm256_castpd_si256(kr);
    __m256i sign = _mm256_set1_epi64x((long long)0x8000000000000000ull);
    __m256d swap = _mm256_castsi256_pd(_mm256_slli_epi64(ki, 63));
    __m256d sin_sign = _mm256_castsi256_pd(_mm256_and_si256(_mm256_slli_epi64(ki, 62), sign));
    __m256i k1 = _mm256_add_epi64(ki, _mm256_set1_epi64x(1));
    __m256d cos_sign = _mm256_castsi256_pd(_mm256_and_si256(_mm256_slli_epi64(k1, 62), sign));
    *sin_x = _mm256_xor_pd(_mm256_blendv_pd(sin_r, cos_r, swap), sin_sign);
    *cos_x = _mm256_xor_pd(_mm256_blendv_pd(cos_r, sin_r, swap), cos_sign);
}

/* m <= LANES angles x[0..m-1] into lanes, the rest 0.  Scalar loads: a
 * vector load of values the caller has just stored one by one would wait
 * for the stores to reach the cache (no store-to-load forwarding), which
 * costs a 5-link chain's right-hand side 5 %. */
AVX2 static inline __m256d
load(const double *x, int m)
{
    switch (m) {
    case 1: return _mm256_set_pd(0, 0, 0, x[0]);
    case 2: return _mm256_set_pd(0, 0, x[1], x[0]);
    case 3: return _mm256_set_pd(0, x[2], x[1], x[0]);
    default: return _mm256_set_pd(x[3], x[2], x[1], x[0]);
    }
}

AVX2 static void
sincos_vector(int n, const double *x, double *s, double *c)
{
    for (int i = 0; i < n; i += LANES) {
        int m = n - i < LANES ? n - i : LANES;
        __m256d v = load(x + i, m), vs, vc;
        __m256d mag = _mm256_andnot_pd(SPLAT(-0.0), v);
        /* not <= also catches NaN, which glibc turns into NaN too */
        if (_mm256_movemask_pd(_mm256_cmp_pd(mag, SPLAT(REDUCE_MAX), _CMP_NLE_UQ))) {
            for (int j = i; j < i + m; j++) {
                s[j] = sin(x[j]);
                c[j] = cos(x[j]);
            }
            continue;
        }
        sincos4(v, &vs, &vc);
        if (m == LANES) {
            _mm256_storeu_pd(s + i, vs);
            _mm256_storeu_pd(c + i, vc);
            continue;
        }
        double ls[LANES], lc[LANES]; /* the caller's arrays end at n */
        _mm256_storeu_pd(ls, vs);
        _mm256_storeu_pd(lc, vc);
        for (int j = 0; j < m; j++) {
            s[i + j] = ls[j];
            c[i + j] = lc[j];
        }
    }
}
#define SINCOS_VECTOR 1
#endif

void
eomc_sincos(int n, const double *x, double *s, double *c)
{
#ifdef SINCOS_VECTOR
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
        sincos_vector(n, x, s, c);
        return;
    }
#endif
    for (int i = 0; i < n; i++) {
        s[i] = sin(x[i]);
        c[i] = cos(x[i]);
    }
}
