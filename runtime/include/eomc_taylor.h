/*
 * eomc_taylor.h: the Taylor coefficients of each operation, order by
 * order, for the generated `taylor` function (eomc_model.h) of Taylor's
 * method (--method taylor).
 *
 * A value w(t) near t0 is held as its normalized Taylor coefficients
 * w[j] = w^(j)(t0) / j!, j = 0 .. K.  Each function below computes one
 * coefficient, c[k], of its result from the coefficients 0 .. k of its
 * operands and 0 .. k-1 of itself (and of its auxiliary series, which it
 * also brings to order k): the standard recurrences of automatic
 * differentiation in Taylor mode (Griewank and Walther, "Evaluating
 * Derivatives", ch. 13; Jorba and Zou 2005, section 2), which follow from
 * the Leibniz rule for products and from a first-order ODE for each
 * elementary function (sin' = cos, exp' = exp, ...).  At k = 0 they are
 * the plain values.  Calling them for k = 0, 1, 2, ... over the nodes of a
 * DAG in topological order gives every node's series to order K in
 * O(K^2) per nonlinear node.
 *
 * Functions of a series whose value is 0 where the function is not
 * analytic (sqrt, log, a real power, a division by a series with b[0] =
 * 0) return non-finite coefficients, as the plain operation would; the
 * stepper checks every coefficient it uses.
 *
 * Everything is static inline on eomc_real (double, or extended in the
 * model's twin): the loops over the order are the only code, and the
 * generated function is a straight list of calls.
 */
#ifndef EOMC_TAYLOR_H
#define EOMC_TAYLOR_H

#include <math.h>

#include "eomc_model.h"

/* taylor_run4's values (eomc_model.h): a vector of four doubles, one
 * run's a lane, where the C compiler has GCC's vectors (gcc and clang);
 * may_alias, as the runtime's arrays of doubles are read through them.
 * EOMC_V4C(x) is the number x in every lane. */
#if defined(__GNUC__) && !defined(EOMC_EXTENDED)
#define EOMC_V4 1
typedef double eomc_v4 __attribute__((vector_size(4 * sizeof(double)), may_alias));
#define EOMC_V4C(x) ((eomc_v4){(x), (x), (x), (x)})

/* taylor_run4's libm calls (the series' order 0 of sqrt, exp, pow, sin,
 * cos, sinh, cosh) and a mode's choice, a lane at a time: r = f(a) in
 * each.  By pointers, as vectors passed by value would change the ABI
 * where the machine's vectors are narrower. */
#define EOMC_V4_CALL(f)                                                   \
    static inline void eomc_v4_##f(eomc_v4 *r, const eomc_v4 *a)           \
    {                                                                     \
        for (int l = 0; l < EOMC_LANES; l++)                              \
            (*r)[l] = f((*a)[l]);                                         \
    }
EOMC_V4_CALL(sqrt)
EOMC_V4_CALL(exp)
EOMC_V4_CALL(sin)
EOMC_V4_CALL(cos)
EOMC_V4_CALL(sinh)
EOMC_V4_CALL(cosh)
#undef EOMC_V4_CALL

static inline void
eomc_v4_pow(eomc_v4 *r, const eomc_v4 *a, const eomc_v4 *b)
{
    for (int l = 0; l < EOMC_LANES; l++)
        (*r)[l] = pow((*a)[l], (*b)[l]);
}

/* The written-out series' packs (compiler/lower/lower_pack.c), as vectors
 * unless EOMC_NO_PACKS asks for their lines one at a time (the same bits:
 * tests/sim's taylor-series runs both): the four (two) consecutive doubles
 * from p as one vector, p aligned to a double only; a number beside it is
 * spread over its lanes by the operator. */
#ifndef EOMC_NO_PACKS
#define EOMC_PACKS 1
#endif
typedef double eomc_v4u
    __attribute__((vector_size(4 * sizeof(double)), aligned(sizeof(double)), may_alias));
typedef double eomc_v2u
    __attribute__((vector_size(2 * sizeof(double)), aligned(sizeof(double)), may_alias));
#define EOMC_AT4(p) (*(eomc_v4u *)(p))
#define EOMC_AT2(p) (*(eomc_v2u *)(p))

/* r = a where the mode is on (not 0), b where it is off, lane by lane */
static inline void
eomc_v4_select(eomc_v4 *r, const eomc_v4 *mode, const eomc_v4 *a, const eomc_v4 *b)
{
    for (int l = 0; l < EOMC_LANES; l++)
        (*r)[l] = (*mode)[l] != 0 ? (*a)[l] : (*b)[l];
}
#endif

/* The upper halves of the 256-bit registers cleared, where taylor_run
 * and taylor_run4 return to the runtime: gcc leaves them dirty below -O2
 * (its vzeroupper pass needs -fexpensive-optimizations), and then every
 * SSE instruction of the runtime's that follows pays for it (a sweep's
 * 300 Kepler runs four at a time took 0.81 s instead of 0.46). */
#if defined(__AVX__) && defined(__GNUC__)
#define EOMC_ZEROUPPER() __builtin_ia32_vzeroupper()
#else
#define EOMC_ZEROUPPER() ((void)0)
#endif

#if defined(EOMC_EXTENDED)
#define EOMC_TAY_F(name) name##l
#else
#define EOMC_TAY_F(name) name
#endif

/* A value that does not depend on t: v, then zeros. */
static inline void
eomc_tay_const(eomc_real *c, eomc_real v, int k)
{
    c[k] = k == 0 ? v : 0;
}

/* t itself, expanded about t0: t0, 1, then zeros. */
static inline void
eomc_tay_time(eomc_real *c, eomc_real t0, int k)
{
    c[k] = k == 0 ? t0 : k == 1 ? 1 : 0;
}

/* The next coefficient of a value whose rate is r (q' = r): q[k + 1] =
 * r[k] / (k + 1).  The generated taylor_run (eomc_model.h) sums the
 * coordinates by it, and by the two below the speeds. */
static inline void
eomc_tay_integ(eomc_real *q, const eomc_real *r, int k)
{
    q[k + 1] = r[k] / (k + 1);
}

/* The next coefficient of a speed under a constant diagonal mass m and
 * the force -h: v' = -h / m, so v[k + 1] = h[k] / m[0] / -(k + 1), which
 * is -((h[k] / m[0]) / (k + 1)) to the bit (rounding is symmetric in the
 * sign), as taylor.c's loop rounds it. */
static inline void
eomc_tay_accel(eomc_real *v, const eomc_real *h, const eomc_real *m, int k)
{
    v[k + 1] = h[k] / m[0] / -(k + 1);
}

/* The next coefficient of a coordinate q whose rate is the speed v of
 * eomc_tay_accel: q[k + 1] = v[k] / (k + 1), which for k > 0 is
 * h[k - 1] / m[0] / -(k (k + 1)), from v's quotient h[k - 1] / m[0].
 * Through v it would be one division more after it, and the next
 * orders' products wait on q: Kepler's series to order 19 took 393 ns
 * so, 373 thus (docs/internals.md). */
static inline void
eomc_tay_integ2(eomc_real *q, const eomc_real *v, const eomc_real *h, const eomc_real *m,
                int k)
{
    q[k + 1] = k == 0 ? v[0] : h[k - 1] / m[0] / -(k * (k + 1));
}

/* The next coefficient of a value whose rate is 0 at every order. */
static inline void
eomc_tay_hold(eomc_real *c, int k)
{
    c[k + 1] = 0;
}

static inline void
eomc_tay_add(eomc_real *c, const eomc_real *a, const eomc_real *b, int k)
{
    c[k] = a[k] + b[k];
}

static inline void
eomc_tay_sub(eomc_real *c, const eomc_real *a, const eomc_real *b, int k)
{
    c[k] = a[k] - b[k];
}

/* A switched value: the series of the branch its mode v (0 or 1, held
 * over the step, which ends where the mode would flip) chooses. */
static inline void
eomc_tay_select(eomc_real *c, const eomc_real *a, const eomc_real *b, eomc_real v, int k)
{
    c[k] = v != 0 ? a[k] : b[k];
}

static inline void
eomc_tay_neg(eomc_real *c, const eomc_real *a, int k)
{
    c[k] = -a[k];
}

/* A value that is constant in t times a series (a coefficient of the
 * spec's: m*l^2): one product, not a convolution. */
static inline void
eomc_tay_scale(eomc_real *c, const eomc_real *a, const eomc_real *b, int k)
{
    c[k] = a[0] * b[k];
}

/* The i-th (i = 0 .. k) index j of a convolution's terms f(j, k - j), in
 * the order every recurrence here adds them: by the later of the term's
 * two orders, max(j, k - j), the earlier first, and j before k - j.  A
 * sum so takes the coefficients the program computed orders ago first
 * and those of order k, which it has just computed, last: it runs ahead
 * while they are computed instead of waiting for them at its first
 * term.  Kepler's series to order 19 took 393 ns for 537 summed j = 0 ..
 * k (docs/internals.md).  lower_series.c writes its sums out in the same
 * order, so that taylor_run has these bits. */
static inline int
eomc_tay_at_(int i, int k)
{
    int t = i + (k % 2 == 0 && i > 0);
    return t % 2 == 0 ? k / 2 - t / 2 : (k + 1) / 2 + t / 2;
}

/* c = a b: c_k = sum_{j=0..k} a_j b_{k-j}. */
static inline void
eomc_tay_mul(eomc_real *c, const eomc_real *a, const eomc_real *b, int k)
{
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        s += a[j] * b[k - j];
    }
    c[k] = s;
}

/* Two and four products at once (c = a b, c1 = a1 b1, ...): one loop
 * over the order with a sum for each, added up in eomc_tay_mul's order,
 * so the same bits.  Alone, a product's loop waits on its own sum at
 * every term; side by side the sums go at the machine's pace (the
 * products of one level of the program, lower_taylor.c). */
static inline void
eomc_tay_mul2(eomc_real *c, eomc_real *c1, const eomc_real *a, const eomc_real *b,
              const eomc_real *a1, const eomc_real *b1, int k)
{
    eomc_real s = 0, s1 = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        s += a[j] * b[k - j];
        s1 += a1[j] * b1[k - j];
    }
    c[k] = s;
    c1[k] = s1;
}

static inline void
eomc_tay_mul4(eomc_real *c, eomc_real *c1, eomc_real *c2, eomc_real *c3,
              const eomc_real *a, const eomc_real *b, const eomc_real *a1,
              const eomc_real *b1, const eomc_real *a2, const eomc_real *b2,
              const eomc_real *a3, const eomc_real *b3, int k)
{
    eomc_real s = 0, s1 = 0, s2 = 0, s3 = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        s += a[j] * b[k - j];
        s1 += a1[j] * b1[k - j];
        s2 += a2[j] * b2[k - j];
        s3 += a3[j] * b3[k - j];
    }
    c[k] = s;
    c1[k] = s1;
    c2[k] = s2;
    c3[k] = s3;
}

/* c = a^2, the convolution's symmetric half (j < k - j), then its middle. */
static inline void
eomc_tay_sqr(eomc_real *c, const eomc_real *a, int k)
{
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j < k - j)
            s += a[j] * a[k - j];
    }
    s *= 2;
    if (k % 2 == 0)
        s += a[k / 2] * a[k / 2];
    c[k] = s;
}

/* c = a / b: from c b = a, c_k = (a_k - sum_{j=1..k} b_j c_{k-j}) / b_0,
 * a_k added in the place of the term j = 0, b_0 c_k. */
static inline void
eomc_tay_div(eomc_real *c, const eomc_real *a, const eomc_real *b, int k)
{
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        s = j > 0 ? s - b[j] * c[k - j] : s + a[k];
    }
    c[k] = s / b[0];
}

/* c = 1 / a (a / b's with 1, 0, 0, ... over b = a). */
static inline void
eomc_tay_inv(eomc_real *c, const eomc_real *a, int k)
{
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0)
            s -= a[j] * c[k - j];
        else if (k == 0)
            s += 1;
    }
    c[k] = s / a[0];
}

/* c = sqrt(a): from c^2 = a, c_k = (a_k - sum_{j=1..k-1} c_j c_{k-j}) / (2 c_0). */
static inline void
eomc_tay_sqrt(eomc_real *c, const eomc_real *a, int k)
{
    if (k == 0) {
        c[0] = EOMC_TAY_F(sqrt)(a[0]);
        return;
    }
    eomc_real s = 0; /* a_k in the place of the terms j = 0 and k, 2 c_0 c_k */
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j == 0)
            s += a[k];
        else if (j < k)
            s -= c[j] * c[k - j];
    }
    c[k] = s / (2 * c[0]);
}

/* c = exp(a): c' = c a', so k c_k = sum_{j=1..k} j a_j c_{k-j}. */
static inline void
eomc_tay_exp(eomc_real *c, const eomc_real *a, int k)
{
    if (k == 0) {
        c[0] = EOMC_TAY_F(exp)(a[0]);
        return;
    }
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0)
            s += j * a[j] * c[k - j];
    }
    c[k] = s / k;
}

/* c = log(a): a c' = a', so c_k = (a_k - (1/k) sum_{j=1..k-1} j c_j a_{k-j}) / a_0. */
static inline void
eomc_tay_log(eomc_real *c, const eomc_real *a, int k)
{
    if (k == 0) {
        c[0] = EOMC_TAY_F(log)(a[0]);
        return;
    }
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0 && j < k)
            s += j * c[j] * a[k - j];
    }
    c[k] = (a[k] - s / k) / a[0];
}

/* c = a^e, e constant in t (e[0] its value): a c' = e c a', so
 * k a_0 c_k = sum_{j=0..k-1} (e (k - j) - j) a_{k-j} c_j. */
static inline void
eomc_tay_powc(eomc_real *c, const eomc_real *a, const eomc_real *e, int k)
{
    if (k == 0) {
        c[0] = EOMC_TAY_F(pow)(a[0], e[0]);
        return;
    }
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j < k)
            s += (e[0] * (k - j) - j) * a[k - j] * c[j];
    }
    c[k] = s / (k * a[0]);
}

/* The recurrence of sincos and sinhcosh at k > 0: s' = c a' and
 * c' = sign s a' (sign -1 for sin and cos, 1 for sinh and cosh). */
static inline void
eomc_tay_pair_(eomc_real *s, eomc_real *c, const eomc_real *a, int k, int sign)
{
    eomc_real ss = 0, cc = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0) {
            ss += j * a[j] * c[k - j];
            cc += j * a[j] * s[k - j];
        }
    }
    s[k] = ss / k;
    c[k] = sign * cc / k;
}

/* s = sin(a), c = cos(a) together: s' = c a', c' = -s a'. */
static inline void
eomc_tay_sincos(eomc_real *s, eomc_real *c, const eomc_real *a, int k)
{
    if (k == 0) {
        s[0] = EOMC_TAY_F(sin)(a[0]);
        c[0] = EOMC_TAY_F(cos)(a[0]);
    } else {
        eomc_tay_pair_(s, c, a, k, -1);
    }
}

/* s = sinh(a), c = cosh(a) together: s' = c a', c' = s a'. */
static inline void
eomc_tay_sinhcosh(eomc_real *s, eomc_real *c, const eomc_real *a, int k)
{
    if (k == 0) {
        s[0] = EOMC_TAY_F(sinh)(a[0]);
        c[0] = EOMC_TAY_F(cosh)(a[0]);
    } else {
        eomc_tay_pair_(s, c, a, k, 1);
    }
}

/* y = tan(a) with w = 1 + y^2 (sign = 1), or y = tanh(a) with w = 1 - y^2
 * (sign = -1): y' = w a', so k y_k = sum_{j=1..k} j a_j w_{k-j}; then w
 * is brought to order k. */
static inline void
eomc_tay_tan_(eomc_real *y, eomc_real *w, const eomc_real *a, int k, int sign)
{
    if (k == 0) {
        y[0] = sign > 0 ? EOMC_TAY_F(tan)(a[0]) : EOMC_TAY_F(tanh)(a[0]);
    } else {
        eomc_real s = 0;
        for (int i = 0; i <= k; i++) {
            int j = eomc_tay_at_(i, k);
            if (j > 0)
                s += j * a[j] * w[k - j];
        }
        y[k] = s / k;
    }
    eomc_real q = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        q += y[j] * y[k - j];
    }
    w[k] = (k == 0 ? 1 : 0) + sign * q;
}

static inline void
eomc_tay_tan(eomc_real *y, eomc_real *w, const eomc_real *a, int k)
{
    eomc_tay_tan_(y, w, a, k, 1);
}

static inline void
eomc_tay_tanh(eomc_real *y, eomc_real *w, const eomc_real *a, int k)
{
    eomc_tay_tan_(y, w, a, k, -1);
}

/* y with y' = sign a' / w, w's series known to order k:
 * k w_0 y_k = sign k a_k - sum_{j=1..k-1} j y_j w_{k-j}. */
static inline void
eomc_tay_quotient_rate_(eomc_real *y, const eomc_real *w, const eomc_real *a, int k,
                        int sign)
{
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0 && j < k)
            s += j * y[j] * w[k - j];
    }
    y[k] = (sign * a[k] - s / k) / w[0];
}

/* y = asin(a) (sign 1) or acos(a) (sign -1), with r = 1 - a^2 and
 * s = sqrt(r): y' = sign a' / s. */
static inline void
eomc_tay_asin_(eomc_real *y, eomc_real *r, eomc_real *s, const eomc_real *a, int k,
               int sign)
{
    eomc_real q = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        q += a[j] * a[k - j];
    }
    r[k] = (k == 0 ? 1 : 0) - q;
    eomc_tay_sqrt(s, r, k);
    if (k == 0)
        y[0] = sign > 0 ? EOMC_TAY_F(asin)(a[0]) : EOMC_TAY_F(acos)(a[0]);
    else
        eomc_tay_quotient_rate_(y, s, a, k, sign);
}

static inline void
eomc_tay_asin(eomc_real *y, eomc_real *r, eomc_real *s, const eomc_real *a, int k)
{
    eomc_tay_asin_(y, r, s, a, k, 1);
}

static inline void
eomc_tay_acos(eomc_real *y, eomc_real *r, eomc_real *s, const eomc_real *a, int k)
{
    eomc_tay_asin_(y, r, s, a, k, -1);
}

/* y = atan(a), with w = 1 + a^2: y' = a' / w. */
static inline void
eomc_tay_atan(eomc_real *y, eomc_real *w, const eomc_real *a, int k)
{
    eomc_real q = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        q += a[j] * a[k - j];
    }
    w[k] = (k == 0 ? 1 : 0) + q;
    if (k == 0)
        y[0] = EOMC_TAY_F(atan)(a[0]);
    else
        eomc_tay_quotient_rate_(y, w, a, k, 1);
}

/* y = atan2(b, a) (the angle of the point (a, b)), with w = a^2 + b^2:
 * y' = (a b' - b a') / w, so
 * k w_0 y_k = sum_{j=1..k} j (a_{k-j} b_j - b_{k-j} a_j) - sum_{j=1..k-1} j y_j w_{k-j}. */
static inline void
eomc_tay_atan2(eomc_real *y, eomc_real *w, const eomc_real *b, const eomc_real *a, int k)
{
    eomc_real q = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        q += a[j] * a[k - j] + b[j] * b[k - j];
    }
    w[k] = q;
    if (k == 0) {
        y[0] = EOMC_TAY_F(atan2)(b[0], a[0]);
        return;
    }
    eomc_real s = 0;
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0)
            s += j * (a[k - j] * b[j] - b[k - j] * a[j]);
    }
    for (int i = 0; i <= k; i++) {
        int j = eomc_tay_at_(i, k);
        if (j > 0 && j < k)
            s -= j * y[j] * w[k - j];
    }
    y[k] = s / (k * w[0]);
}

/* c = |a| = sign(a_0) a, where a_0 != 0 (at a_0 = 0 |a| has no Taylor
 * series; the sign of the first nonzero coefficient is taken, the side
 * the motion goes to). */
static inline void
eomc_tay_abs(eomc_real *c, const eomc_real *a, int k)
{
    int j = 0;
    while (j < k && a[j] == 0)
        j++;
    c[k] = a[j] < 0 ? -a[k] : a[k];
}

/* c = sign(a): constant while a keeps its sign. */
static inline void
eomc_tay_sign(eomc_real *c, const eomc_real *a, int k)
{
    c[k] = k == 0 ? (a[0] > 0) - (a[0] < 0) : 0;
}

#undef EOMC_TAY_F

#endif
