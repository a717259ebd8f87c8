/*
 * eomc_taylor.h (issue 26): the Taylor coefficients of every operation,
 * to order K = 20, against coefficients computed independently in long
 * double:
 *
 * - closed forms, on the series of t itself (or 1 + t, 1 - t): sin, cos,
 *   exp, sinh, cosh (t^k / k!), log(1 + t) ((-1)^(k+1) / k), sqrt(1 + t)
 *   and (1 + t)^e (binomial coefficients), 1/(1 - t) (ones), tan and tanh
 *   (tangent numbers, in integers), tan' = 1 + tan^2, asin (its central
 *   binomial series), acos = pi/2 - asin, sqrt(1 - t^2), atan and
 *   atan2(t, 1) (alternating odd powers), time (t0, 1, then zeros);
 * - every operation (the linear ones, const, abs and sign too) of a
 *   composed argument (a polynomial with a nonzero value at 0, so that
 *   each k = 0 path is taken, or a + b exp(c t)), and of two such
 *   arguments for mul, div and atan2 (in three quadrants), and for the
 *   products two and four at once (mul2, mul4), which also give mul's
 *   bits exactly, in both precisions,
 *   against the Cauchy integral c_k = 1/(2 pi i) \oint f(z) z^(-k-1) dz
 *   on the circle |z| = r, by the trapezoidal rule on N points in long
 *   double complex (csinl, clogl, casinl, ...): a method that shares
 *   nothing with the recurrences, exact but for aliasing, which is of
 *   relative size (r / R)^N for the radius of convergence R (each case's
 *   r is about R / 2, below 1e-30 at N = 128; N = 128 against 2N = 256
 *   shows it is converged, and that no branch cut is crossed), and for
 *   rounding, of order 1e-19 of the largest |f| on the circle.  The Cauchy reference is itself checked against the closed
 *   forms.
 *
 * The error's scale: coefficient k is compared in the units of the terms
 * c_k r^k of the series on the circle |t| = r of the case, the largest of
 * which sets the scale: err = max_k |c_k - ref_k| r^k / max_j |ref_j| r^j.
 * That is the error of the truncated series itself, as Taylor's method
 * sums it over a step h <= r; a relative error of each coefficient alone
 * means nothing for the coefficients that are 0 (and the Cauchy
 * reference's own error is absolute, of the order of 1e-19 of the
 * largest term).  Each r is about half the radius of convergence R (for
 * the entire functions, 1.5 to 5), so the term of order 20 is 1e-3 to
 * 1e-11 of the largest, as in the steps Taylor's method takes: the high
 * orders are not hidden under the scale.  For the closed forms, each
 * nonzero coefficient's relative error is bounded as well.  Bound: 1e-14
 * in double, and 1e-17 for the extended-precision compilation
 * (EOMC_EXTENDED, taylor_ops_ext.c: every operation again, on the
 * operands' long double coefficients).
 */
#include "../unit/check.h"

#include <complex.h>
#include <string.h>

#define TAY_RUN taylor_run
#include "taylor_ops_run.h"

void taylor_run_ext(int op, int K, const long double *a, const long double *b, long double p,
                    long double *y, long double *u, long double *v);

typedef long double complex cld;

enum { K = 20, N = 128 };
static const double TOL = 1e-14, TOL_EXT = 1e-17, TOL_REF = 1e-17;
static const long double PI = 3.141592653589793238462643383279502884L;

/* An operand: p0 + p1 t + p2 t^2 (kind POLY) or p0 + p1 exp(p2 t) (kind
 * EXPO), both with coefficients known exactly. */
enum { POLY, EXPO };
typedef struct Opnd {
    int kind;
    long double p[3];
} Opnd;

static const Opnd T = {POLY, {0, 1, 0}};   /* t */
static const Opnd U = {POLY, {1, 1, 0}};   /* 1 + t */
static const Opnd V = {POLY, {1, -1, 0}};  /* 1 - t */
static const Opnd ONE = {POLY, {1, 0, 0}};
static const Opnd C17 = {POLY, {1.7L, 0, 0}}; /* a coefficient of the spec's */
/* a general argument: its singularities for tan, asin, atan, ... at
 * |t| >= 0.9 */
static const Opnd PA = {POLY, {0.4L, 0.9L, -0.6L}};
/* positive and away from 0 (log, sqrt, powers, denominators): zeros at
 * |t| = 2.28 */
static const Opnd PL = {POLY, {1.3L, -0.5L, 0.25L}};
static const Opnd NA = {POLY, {-0.7L, 0.4L, 0.3L}}; /* negative at 0 */
static const Opnd ZA = {POLY, {0, -0.6L, 0.5L}};    /* 0 at 0, then negative */
static const Opnd EA = {EXPO, {0.5L, 0.8L, -0.7L}}; /* 1.3 at 0; 0 at |t| >= 4.5 */
static const Opnd NE = {EXPO, {-0.5L, -0.8L, 0.6L}}; /* -1.3 at 0 */

static cld
opnd_at(const Opnd *o, cld z)
{
    if (o->kind == POLY)
        return o->p[0] + z * (o->p[1] + z * o->p[2]);
    return o->p[0] + o->p[1] * cexpl(o->p[2] * z);
}

/* The operand's coefficients 0 .. K, in long double. */
static void
opnd_coef(const Opnd *o, long double *c)
{
    memset(c, 0, (K + 1) * sizeof *c);
    if (o->kind == POLY) {
        for (int j = 0; j < 3; j++)
            c[j] = o->p[j];
        return;
    }
    long double term = o->p[1]; /* p1 p2^k / k! */
    for (int k = 0; k <= K; k++) {
        c[k] = term;
        term *= o->p[2] / (k + 1);
    }
    c[0] += o->p[0];
}

/* The functions of the operands' values a, b whose series are compared;
 * x holds a0, b0 (the operands at 0) and the case's constant. */
typedef struct Ctx {
    long double a0, b0, p;
} Ctx;
typedef cld (*Fn)(cld a, cld b, const Ctx *x);

static cld f_add(cld a, cld b, const Ctx *x) { (void)x; return a + b; }
static cld f_sub(cld a, cld b, const Ctx *x) { (void)x; return a - b; }
static cld f_neg(cld a, cld b, const Ctx *x) { (void)b, (void)x; return -a; }
static cld f_scale(cld a, cld b, const Ctx *x) { (void)a; return x->a0 * b; }
static cld f_mul(cld a, cld b, const Ctx *x) { (void)x; return a * b; }
static cld f_sqr(cld a, cld b, const Ctx *x) { (void)b, (void)x; return a * a; }
static cld f_b2(cld a, cld b, const Ctx *x) { (void)a, (void)x; return b * b; }
static cld f_div(cld a, cld b, const Ctx *x) { (void)x; return a / b; }
static cld f_inv(cld a, cld b, const Ctx *x) { (void)b, (void)x; return 1 / a; }
static cld f_sqrt(cld a, cld b, const Ctx *x) { (void)b, (void)x; return csqrtl(a); }
static cld f_exp(cld a, cld b, const Ctx *x) { (void)b, (void)x; return cexpl(a); }
static cld f_log(cld a, cld b, const Ctx *x) { (void)b, (void)x; return clogl(a); }
static cld f_pow(cld a, cld b, const Ctx *x) { (void)b; return cexpl(x->p * clogl(a)); }
static cld f_sin(cld a, cld b, const Ctx *x) { (void)b, (void)x; return csinl(a); }
static cld f_cos(cld a, cld b, const Ctx *x) { (void)b, (void)x; return ccosl(a); }
static cld f_sinh(cld a, cld b, const Ctx *x) { (void)b, (void)x; return csinhl(a); }
static cld f_cosh(cld a, cld b, const Ctx *x) { (void)b, (void)x; return ccoshl(a); }
static cld f_tan(cld a, cld b, const Ctx *x) { (void)b, (void)x; return ctanl(a); }
static cld f_tanh(cld a, cld b, const Ctx *x) { (void)b, (void)x; return ctanhl(a); }
/* tan' = 1 / cos^2 and tanh' = 1 / cosh^2, not from tan itself */
static cld f_tan_w(cld a, cld b, const Ctx *x) { (void)b, (void)x; cld c = ccosl(a); return 1 / (c * c); }
static cld f_tanh_w(cld a, cld b, const Ctx *x) { (void)b, (void)x; cld c = ccoshl(a); return 1 / (c * c); }
static cld f_asin(cld a, cld b, const Ctx *x) { (void)b, (void)x; return casinl(a); }
static cld f_acos(cld a, cld b, const Ctx *x) { (void)b, (void)x; return cacosl(a); }
static cld f_1ma2(cld a, cld b, const Ctx *x) { (void)b, (void)x; return 1 - a * a; }
/* sqrt(1 - a^2) = cos(asin(a)) */
static cld f_s1ma2(cld a, cld b, const Ctx *x) { (void)b, (void)x; return ccosl(casinl(a)); }
static cld f_atan(cld a, cld b, const Ctx *x) { (void)b, (void)x; return catanl(a); }
static cld f_1pa2(cld a, cld b, const Ctx *x) { (void)b, (void)x; return 1 + a * a; }
/* atan2(b, a) near (a0, b0) is the angle at 0 plus the angle turned
 * since: atan of (a0 b - b0 a) / (a0 a + b0 b), analytic for complex a, b
 * near the real ones (a is the numerator here, as in eomc_tay_atan2) */
static cld
f_atan2(cld a, cld b, const Ctx *x)
{
    return atan2l(x->a0, x->b0) + catanl((x->b0 * a - x->a0 * b) / (x->b0 * b + x->a0 * a));
}
static cld f_a2b2(cld a, cld b, const Ctx *x) { (void)x; return a * a + b * b; }
static cld f_abs(cld a, cld b, const Ctx *x) { (void)b; return x->p < 0 ? -a : a; }
static cld f_sign(cld a, cld b, const Ctx *x) { (void)a, (void)b; return x->p; }
static cld f_const(cld a, cld b, const Ctx *x) { (void)a, (void)b; return x->p; }

/* Closed forms on t (the case's operand is t, 1 + t or 1 - t). */
typedef void (*Closed)(long double *c, long double p);

static void
cl_exp(long double *c, long double p)
{
    (void)p;
    c[0] = 1;
    for (int k = 1; k <= K; k++)
        c[k] = c[k - 1] / k;
}
/* t^k / k! on the powers k = m mod 4 (sign +) and m + 2 mod 4 (sign s2) */
static void
cl_trig(long double *c, int m, int s2)
{
    long double f = 1;
    for (int k = 0; k <= K; k++) {
        if (k > 0)
            f /= k;
        c[k] = k % 2 != m % 2 ? 0 : (k % 4 == m ? f : s2 * f);
    }
}
static void cl_sin(long double *c, long double p) { (void)p; cl_trig(c, 1, -1); }
static void cl_cos(long double *c, long double p) { (void)p; cl_trig(c, 0, -1); }
static void cl_sinh(long double *c, long double p) { (void)p; cl_trig(c, 1, 1); }
static void cl_cosh(long double *c, long double p) { (void)p; cl_trig(c, 0, 1); }
static void
cl_log1p(long double *c, long double p)
{
    (void)p;
    c[0] = 0;
    for (int k = 1; k <= K; k++)
        c[k] = (k % 2 ? 1.0L : -1.0L) / k;
}
/* (1 + t)^p: the binomial coefficients (p choose k) */
static void
cl_binom(long double *c, long double p)
{
    c[0] = 1;
    for (int k = 1; k <= K; k++)
        c[k] = c[k - 1] * (p - (k - 1)) / k;
}
static void cl_sqrt1p(long double *c, long double p) { (void)p; cl_binom(c, 0.5L); }
static void
cl_ones(long double *c, long double p)
{
    (void)p;
    for (int k = 0; k <= K; k++)
        c[k] = 1;
}
/* tan t = sum_n T_n t^(2n-1) / (2n-1)! with the tangent numbers T_n (1,
 * 2, 16, 272, ...; Brent and Zimmermann, "Modern Computer Arithmetic",
 * algorithm TangentNumbers), in integers: T_11 = 4951498053124096 < 2^53;
 * tanh t the same with alternating signs (sign -1). */
static void
cl_tan_(long double *c, int sign, int order)
{
    enum { NT = (K + 2) / 2 };
    unsigned long long tn[NT + 1];
    tn[1] = 1;
    for (int k = 2; k <= NT; k++)
        tn[k] = (unsigned long long)(k - 1) * tn[k - 1];
    for (int k = 2; k <= NT; k++)
        for (int j = k; j <= NT; j++)
            tn[j] = (unsigned long long)(j - k) * tn[j - 1] + (unsigned long long)(j - k + 2) * tn[j];
    long double f = 1; /* 1 / k! */
    for (int k = 0; k <= order; k++) {
        if (k > 0)
            f /= k;
        int n = (k + 1) / 2;
        c[k] = k % 2 == 0 ? 0 : (sign < 0 && n % 2 == 0 ? -1 : 1) * (long double)tn[n] * f;
    }
}
static void cl_tan(long double *c, long double p) { (void)p; cl_tan_(c, 1, K); }
static void cl_tanh(long double *c, long double p) { (void)p; cl_tan_(c, -1, K); }
/* tan' = 1 + tan^2: the derivative of the series, (k + 1) y_(k+1) */
static void
cl_tan_w_(long double *c, int sign)
{
    long double y[K + 2];
    cl_tan_(y, sign, K + 1);
    for (int k = 0; k <= K; k++)
        c[k] = (k + 1) * y[k + 1];
}
static void cl_tan_w(long double *c, long double p) { (void)p; cl_tan_w_(c, 1); }
static void cl_tanh_w(long double *c, long double p) { (void)p; cl_tan_w_(c, -1); }
/* asin t = sum_n (2n)! / (4^n (n!)^2 (2n + 1)) t^(2n + 1) */
static void
cl_asin(long double *c, long double p)
{
    (void)p;
    long double g = 1; /* (2n choose n) / 4^n */
    for (int k = 0; k <= K; k++) {
        c[k] = 0;
        if (k % 2 == 1) {
            int n = (k - 1) / 2;
            if (n > 0)
                g *= (2.0L * n - 1) / (2.0L * n);
            c[k] = g / k;
        }
    }
}
/* acos = pi/2 - asin */
static void
cl_acos(long double *c, long double p)
{
    cl_asin(c, p);
    for (int k = 0; k <= K; k++)
        c[k] = -c[k];
    c[0] = PI / 2;
}
static void cl_1mt2(long double *c, long double p) { (void)p; memset(c, 0, (K + 1) * sizeof *c); c[0] = 1, c[2] = -1; }
static void cl_1pt2(long double *c, long double p) { (void)p; memset(c, 0, (K + 1) * sizeof *c); c[0] = 1, c[2] = 1; }
/* sqrt(1 - t^2): (1/2 choose n) (-1)^n on t^(2n) */
static void
cl_s1mt2(long double *c, long double p)
{
    (void)p;
    long double b[K + 1];
    cl_binom(b, 0.5L);
    for (int k = 0; k <= K; k++)
        c[k] = k % 2 ? 0 : ((k / 2) % 2 ? -1 : 1) * b[k / 2];
}
static void
cl_atan(long double *c, long double p)
{
    (void)p;
    for (int k = 0; k <= K; k++)
        c[k] = k % 2 == 0 ? 0 : ((k / 2) % 2 ? -1.0L : 1.0L) / k;
}

/* One case: op on operands a, b (b for the binary operations), its
 * constant p, the circle's radius r, and the function (and where known
 * the closed form) of each output y, u, v. */
typedef struct Case {
    const char *name;
    int op;
    const Opnd *a, *b;
    long double p, r;
    Fn f[3];
    Closed cl[3];
} Case;

/* The Cauchy integral on |z| = r, n points: c_k = 1/(n r^k) sum_m
 * f(z_m) exp(-2 pi i m k / n), z_m = r exp(2 pi i m / n). */
static void
cauchy(const Case *cs, Fn f, int n, long double *c)
{
    cld w[2 * N], fz[2 * N];
    Ctx x = {cs->a->p[0] + (cs->a->kind == EXPO ? cs->a->p[1] : 0), 0, cs->p};
    if (cs->b)
        x.b0 = cs->b->p[0] + (cs->b->kind == EXPO ? cs->b->p[1] : 0);
    for (int m = 0; m < n; m++)
        w[m] = cosl(2 * PI * m / n) + I * sinl(2 * PI * m / n);
    for (int m = 0; m < n; m++) {
        cld z = cs->r * w[m];
        fz[m] = f(opnd_at(cs->a, z), cs->b ? opnd_at(cs->b, z) : 0, &x);
    }
    long double rk = 1;
    for (int k = 0; k <= K; k++) {
        cld s = 0;
        for (int m = 0; m < n; m++)
            s += fz[m] * conjl(w[(m * k) % n]);
        c[k] = creall(s) / (n * rk);
        rk *= cs->r;
    }
}

/* max_k |c_k - ref_k| r^k / max_j |ref_j| r^j (NaN: infinity) */
static double
err_scaled(const long double *c, const long double *ref, long double r)
{
    long double scale = 0, e = 0, rk = 1;
    for (int k = 0; k <= K; k++, rk *= r)
        scale = fmaxl(scale, fabsl(ref[k]) * rk);
    rk = 1;
    for (int k = 0; k <= K; k++, rk *= r) {
        long double d = fabsl(c[k] - ref[k]) * rk;
        if (!(d <= e))
            e = isnan(d) ? INFINITY : d;
    }
    return (double)(e / (scale > 0 ? scale : 1));
}

static const char *const OUT[3] = {"", " (aux 1)", " (aux 2)"};

static double worst[OP_MUL4 + 1], worst_ext[OP_MUL4 + 1], worst_rel[OP_MUL4 + 1];
static int has_closed[OP_MUL4 + 1];

static void
run_case(const Case *cs)
{
    long double a[TAY_KMAX], b[TAY_KMAX] = {0};
    double ad[TAY_KMAX], bd[TAY_KMAX] = {0}, y[3][TAY_KMAX];
    long double ye[3][TAY_KMAX];
    opnd_coef(cs->a, a);
    if (cs->b)
        opnd_coef(cs->b, b);
    for (int k = 0; k <= K; k++)
        ad[k] = (double)a[k], bd[k] = (double)b[k];
    memset(y, 0, sizeof y);
    memset(ye, 0, sizeof ye);
    taylor_run(cs->op, K, ad, bd, (double)cs->p, y[0], y[1], y[2]);
    taylor_run_ext(cs->op, K, a, b, cs->p, ye[0], ye[1], ye[2]);
    for (int o = 0; o < 3 && cs->f[o]; o++) {
        long double ref[K + 1], ref2[K + 1], yl[K + 1];
        cauchy(cs, cs->f[o], N, ref);
        cauchy(cs, cs->f[o], 2 * N, ref2);
        double conv = err_scaled(ref, ref2, cs->r);
        CHECK(conv <= TOL_REF, "%s%s: the Cauchy reference on |t| = %Lg, N = %d and %d, agree to "
              "%.2g", cs->name, OUT[o], cs->r, N, 2 * N, conv);
        if (cs->cl[o]) {
            long double cl[K + 1];
            cs->cl[o](cl, cs->p);
            double ecl = err_scaled(ref, cl, cs->r);
            CHECK(ecl <= TOL_REF, "%s%s: the Cauchy reference is the closed form to %.2g",
                  cs->name, OUT[o], ecl);
            memcpy(ref, cl, sizeof cl);
        }
        for (int k = 0; k <= K; k++)
            yl[k] = y[o][k];
        double e = err_scaled(yl, ref, cs->r), ee = err_scaled(ye[o], ref, cs->r);
        CHECK(e <= TOL, "%s%s, orders 0..%d: double within %.2g (<= %g) of the %s", cs->name,
              OUT[o], K, e, TOL, cs->cl[o] ? "closed form" : "Cauchy integral");
        CHECK(ee <= TOL_EXT, "%s%s, orders 0..%d: extended within %.2g (<= %g)", cs->name,
              OUT[o], K, ee, TOL_EXT);
        if (cs->cl[o]) { /* and each nonzero coefficient on its own */
            double rel = 0, rel_ext = 0;
            for (int k = 0; k <= K; k++)
                if (ref[k] != 0) {
                    rel = fmax(rel, (double)fabsl((yl[k] - ref[k]) / ref[k]));
                    rel_ext = fmax(rel_ext, (double)fabsl((ye[o][k] - ref[k]) / ref[k]));
                }
            CHECK(rel <= TOL && rel_ext <= TOL_EXT, "%s%s: each nonzero coefficient's relative "
                  "error %.2g in double, %.2g in extended", cs->name, OUT[o], rel, rel_ext);
            worst_rel[cs->op] = fmax(worst_rel[cs->op], rel);
            has_closed[cs->op] = 1;
        }
        worst[cs->op] = fmax(worst[cs->op], e);
        worst_ext[cs->op] = fmax(worst_ext[cs->op], ee);
    }
}

static const char *const OPNAME[OP_MUL4 + 1] = {
    "const", "time", "add", "sub", "neg", "scale", "mul", "sqr", "div", "inv", "sqrt", "exp",
    "log", "powc", "sincos", "sinhcosh", "tan", "tanh", "asin", "acos", "atan", "atan2", "abs",
    "sign", "mul2", "mul4"};

/* mul2 and mul4 give each product's bits as mul alone does: the same
 * sums in the same order (double and extended). */
static void
side_by_side(const Opnd *pa, const Opnd *pb, const char *name)
{
    long double a[TAY_KMAX], b[TAY_KMAX], one[3][TAY_KMAX], y[3][TAY_KMAX];
    double ad[TAY_KMAX], bd[TAY_KMAX], oned[3][TAY_KMAX], yd[3][TAY_KMAX];
    opnd_coef(pa, a);
    opnd_coef(pb, b);
    for (int k = 0; k <= K; k++)
        ad[k] = (double)a[k], bd[k] = (double)b[k];
    taylor_run(OP_MUL, K, ad, bd, 0, oned[0], NULL, NULL);
    taylor_run(OP_MUL, K, ad, ad, 0, oned[1], NULL, NULL);
    taylor_run(OP_MUL, K, bd, bd, 0, oned[2], NULL, NULL);
    taylor_run_ext(OP_MUL, K, a, b, 0, one[0], NULL, NULL);
    taylor_run_ext(OP_MUL, K, a, a, 0, one[1], NULL, NULL);
    taylor_run_ext(OP_MUL, K, b, b, 0, one[2], NULL, NULL);
    for (int op = OP_MUL2; op <= OP_MUL4; op++) {
        int n = op == OP_MUL2 ? 2 : 3;
        taylor_run(op, K, ad, bd, 0, yd[0], yd[1], yd[2]);
        taylor_run_ext(op, K, a, b, 0, y[0], y[1], y[2]);
        int same = 1;
        for (int o = 0; o < n; o++) /* == on values: a long double has padding bytes */
            for (int k = 0; k <= K; k++)
                same &= yd[o][k] == oned[o][k] && y[o][k] == one[o][k];
        CHECK(same, "%s (%s): each product's coefficients, orders 0..%d, mul's to the bit, in "
              "double and extended", OPNAME[op], name, K);
    }
}

int
main(void)
{
    static const Case cases[] = {
        /* closed forms */
        {"const 2.5", OP_CONST, &ONE, NULL, 2.5L, 1, {f_const}, {0}},
        {"time about t0 = 0.75", OP_TIME, &ONE, NULL, 0.75L, 1, {0}, {0}},
        {"exp(t)", OP_EXP, &T, NULL, 0, 3, {f_exp}, {cl_exp}},
        {"sin, cos (t)", OP_SINCOS, &T, NULL, 0, 3, {f_sin, f_cos}, {cl_sin, cl_cos}},
        {"sinh, cosh (t)", OP_SINHCOSH, &T, NULL, 0, 3, {f_sinh, f_cosh}, {cl_sinh, cl_cosh}},
        {"log(1 + t)", OP_LOG, &U, NULL, 0, 0.5L, {f_log}, {cl_log1p}},
        {"sqrt(1 + t)", OP_SQRT, &U, NULL, 0, 0.5L, {f_sqrt}, {cl_sqrt1p}},
        {"(1 + t)^2.5", OP_POWC, &U, NULL, 2.5L, 0.5L, {f_pow}, {cl_binom}},
        {"(1 + t)^(-1/3)", OP_POWC, &U, NULL, -1.0L / 3, 0.5L, {f_pow}, {cl_binom}},
        {"inv(1 - t)", OP_INV, &V, NULL, 0, 0.5L, {f_inv}, {cl_ones}},
        {"1 / (1 - t)", OP_DIV, &ONE, &V, 0, 0.5L, {f_div}, {cl_ones}},
        {"tan(t), 1 + tan^2", OP_TAN, &T, NULL, 0, 0.5L, {f_tan, f_tan_w}, {cl_tan, cl_tan_w}},
        {"tanh(t), 1 - tanh^2", OP_TANH, &T, NULL, 0, 0.5L, {f_tanh, f_tanh_w},
         {cl_tanh, cl_tanh_w}},
        {"asin(t), 1 - t^2, sqrt(1 - t^2)", OP_ASIN, &T, NULL, 0, 0.35L,
         {f_asin, f_1ma2, f_s1ma2}, {cl_asin, cl_1mt2, cl_s1mt2}},
        {"acos(t), 1 - t^2, sqrt(1 - t^2)", OP_ACOS, &T, NULL, 0, 0.35L,
         {f_acos, f_1ma2, f_s1ma2}, {cl_acos, cl_1mt2, cl_s1mt2}},
        {"atan(t), 1 + t^2", OP_ATAN, &T, NULL, 0, 0.35L, {f_atan, f_1pa2}, {cl_atan, cl_1pt2}},
        {"atan2(t, 1), 1 + t^2", OP_ATAN2, &T, &ONE, 0, 0.35L, {f_atan2, f_a2b2},
         {cl_atan, cl_1pt2}},
        /* composed arguments, against the Cauchy integral */
        {"PA + EA", OP_ADD, &PA, &EA, 0, 5, {f_add}, {0}},
        {"PA - EA", OP_SUB, &PA, &EA, 0, 5, {f_sub}, {0}},
        {"-EA", OP_NEG, &EA, NULL, 0, 5, {f_neg}, {0}},
        {"1.7 EA", OP_SCALE, &C17, &EA, 0, 5, {f_scale}, {0}},
        {"PA EA", OP_MUL, &PA, &EA, 0, 4, {f_mul}, {0}},
        {"EA NE", OP_MUL, &EA, &NE, 0, 4, {f_mul}, {0}},
        {"PA EA, PA^2 (mul2)", OP_MUL2, &PA, &EA, 0, 2, {f_mul, f_sqr}, {0}},
        {"PA EA, PA^2, EA^2 (mul4)", OP_MUL4, &PA, &EA, 0, 2, {f_mul, f_sqr, f_b2}, {0}},
        {"EA NE, EA^2, NE^2 (mul4)", OP_MUL4, &EA, &NE, 0, 4, {f_mul, f_sqr, f_b2}, {0}},
        {"PA^2", OP_SQR, &PA, NULL, 0, 2, {f_sqr}, {0}},
        {"EA^2", OP_SQR, &EA, NULL, 0, 4, {f_sqr}, {0}},
        {"PA / EA", OP_DIV, &PA, &EA, 0, 2.2L, {f_div}, {0}},
        {"EA / PL", OP_DIV, &EA, &PL, 0, 1.1L, {f_div}, {0}},
        {"1 / PL", OP_INV, &PL, NULL, 0, 1.1L, {f_inv}, {0}},
        {"1 / NE", OP_INV, &NE, NULL, 0, 2.6L, {f_inv}, {0}},
        {"sqrt(PL)", OP_SQRT, &PL, NULL, 0, 1.1L, {f_sqrt}, {0}},
        {"sqrt(EA)", OP_SQRT, &EA, NULL, 0, 2.2L, {f_sqrt}, {0}},
        {"exp(PA)", OP_EXP, &PA, NULL, 0, 2, {f_exp}, {0}},
        {"exp(NE)", OP_EXP, &NE, NULL, 0, 2.5L, {f_exp}, {0}},
        {"log(PL)", OP_LOG, &PL, NULL, 0, 1.1L, {f_log}, {0}},
        {"log(EA)", OP_LOG, &EA, NULL, 0, 2.2L, {f_log}, {0}},
        {"PL^2.5", OP_POWC, &PL, NULL, 2.5L, 1.1L, {f_pow}, {0}},
        {"EA^(-1/3)", OP_POWC, &EA, NULL, -1.0L / 3, 2.2L, {f_pow}, {0}},
        {"PL^-2", OP_POWC, &PL, NULL, -2, 1.1L, {f_pow}, {0}},
        {"sin, cos (PA)", OP_SINCOS, &PA, NULL, 0, 1.5L, {f_sin, f_cos}, {0}},
        {"sin, cos (NE)", OP_SINCOS, &NE, NULL, 0, 2.5L, {f_sin, f_cos}, {0}},
        {"sinh, cosh (PA)", OP_SINHCOSH, &PA, NULL, 0, 1.5L, {f_sinh, f_cosh}, {0}},
        {"sinh, cosh (NE)", OP_SINHCOSH, &NE, NULL, 0, 2.5L, {f_sinh, f_cosh}, {0}},
        {"tan(PA), its w", OP_TAN, &PA, NULL, 0, 0.6L, {f_tan, f_tan_w}, {0}},
        {"tan(NA), its w", OP_TAN, &NA, NULL, 0, 0.85L, {f_tan, f_tan_w}, {0}},
        {"tanh(PA), its w", OP_TANH, &PA, NULL, 0, 0.55L, {f_tanh, f_tanh_w}, {0}},
        {"tanh(NE), its w", OP_TANH, &NE, NULL, 0, 1.6L, {f_tanh, f_tanh_w}, {0}},
        {"asin(PA), r, s", OP_ASIN, &PA, NULL, 0, 0.47L, {f_asin, f_1ma2, f_s1ma2}, {0}},
        {"asin(NA), r, s", OP_ASIN, &NA, NULL, 0, 0.5L, {f_asin, f_1ma2, f_s1ma2}, {0}},
        {"acos(PA), r, s", OP_ACOS, &PA, NULL, 0, 0.47L, {f_acos, f_1ma2, f_s1ma2}, {0}},
        {"acos(NA), r, s", OP_ACOS, &NA, NULL, 0, 0.5L, {f_acos, f_1ma2, f_s1ma2}, {0}},
        {"atan(PA), w", OP_ATAN, &PA, NULL, 0, 0.42L, {f_atan, f_1pa2}, {0}},
        {"atan(NE), w", OP_ATAN, &NE, NULL, 0, 1.7L, {f_atan, f_1pa2}, {0}},
        {"atan2(PA, EA), w (first quadrant)", OP_ATAN2, &PA, &EA, 0, 0.5L, {f_atan2, f_a2b2},
         {0}},
        {"atan2(EA, NA), w (second quadrant)", OP_ATAN2, &EA, &NA, 0, 0.7L, {f_atan2, f_a2b2},
         {0}},
        {"atan2(NA, NE), w (third quadrant)", OP_ATAN2, &NA, &NE, 0, 1.2L, {f_atan2, f_a2b2},
         {0}},
        {"abs(NA)", OP_ABS, &NA, NULL, -1, 1, {f_abs}, {0}},
        {"abs(PA)", OP_ABS, &PA, NULL, 1, 1, {f_abs}, {0}},
        {"abs(EA)", OP_ABS, &EA, NULL, 1, 5, {f_abs}, {0}},
        {"abs(ZA) (0 at t = 0, then negative)", OP_ABS, &ZA, NULL, -1, 1, {f_abs}, {0}},
        {"sign(NA)", OP_SIGN, &NA, NULL, -1, 1, {f_sign}, {0}},
        {"sign(PA)", OP_SIGN, &PA, NULL, 1, 1, {f_sign}, {0}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const Case *cs = &cases[i];
        if (cs->op == OP_TIME) { /* t0, 1, then zeros */
            double y[TAY_KMAX];
            long double ye[TAY_KMAX], u[TAY_KMAX];
            taylor_run(OP_TIME, K, NULL, NULL, (double)cs->p, y, NULL, NULL);
            taylor_run_ext(OP_TIME, K, NULL, NULL, cs->p, ye, u, u);
            int ok = y[0] == 0.75 && y[1] == 1 && ye[0] == 0.75L && ye[1] == 1;
            for (int k = 2; k <= K; k++)
                ok &= y[k] == 0 && ye[k] == 0;
            CHECK(ok, "time about 0.75: 0.75, 1, then zeros (double and extended)");
            continue;
        }
        run_case(cs);
    }
    side_by_side(&PA, &EA, "PA, EA");
    side_by_side(&EA, &NE, "EA, NE");
    for (int op = 0; op <= OP_MUL4; op++)
    {
        char rel[64] = "";
        if (has_closed[op])
            snprintf(rel, sizeof rel, "; closed forms, relative %.2g", worst_rel[op]);
        printf("# %-9s largest error: double %.2g, extended %.2g%s\n", OPNAME[op], worst[op],
               worst_ext[op], rel);
    }
    return check_done();
}
