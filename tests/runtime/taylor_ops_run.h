/*
 * taylor_ops_run.h: one operation of eomc_taylor.h applied order by order
 * (k = 0 .. K) to operand series a and b, for test_taylor_ops.c.  Included
 * once in double (test_taylor_ops.c) and once in extended precision
 * (taylor_ops_ext.c, EOMC_EXTENDED), with TAY_RUN naming the function.
 */
#ifndef TAY_RUN
#error "define TAY_RUN before including taylor_ops_run.h"
#endif

#include "eomc_taylor.h"


#ifndef TAYLOR_OPS_ENUM
#define TAYLOR_OPS_ENUM
enum {
    OP_CONST, OP_TIME, OP_ADD, OP_SUB, OP_NEG, OP_SCALE, OP_MUL, OP_SQR, OP_DIV, OP_INV,
    OP_SQRT, OP_EXP, OP_LOG, OP_POWC, OP_SINCOS, OP_SINHCOSH, OP_TAN, OP_TANH, OP_ASIN,
    OP_ACOS, OP_ATAN, OP_ATAN2, OP_ABS, OP_SIGN, OP_MUL2, OP_MUL4
};
enum { TAY_KMAX = 32 }; /* the longest series a case asks for, plus one */
#endif

/* y: the result; u, v: the auxiliary series (cos of sincos, w of tan,
 * r and s of asin, ...), left alone by the operations without them.
 * mul2 gives a b and a^2 (y, u); mul4 a b, a^2, b^2 and b a (y, u, v,
 * and the last kept here), products side by side.
 * p: the constant of const (its value), time (t0) and powc (the
 * exponent). */
void TAY_RUN(int op, int K, const eomc_real *a, const eomc_real *b, eomc_real p,
             eomc_real *y, eomc_real *u, eomc_real *v);

void
TAY_RUN(int op, int K, const eomc_real *a, const eomc_real *b, eomc_real p, eomc_real *y,
        eomc_real *u, eomc_real *v)
{
    eomc_real e[TAY_KMAX] = {p}; /* powc's exponent, a series constant in t */
    eomc_real w[TAY_KMAX];       /* mul4's fourth product */
    for (int k = 0; k <= K; k++)
        switch (op) {
        case OP_CONST: eomc_tay_const(y, p, k); break;
        case OP_TIME: eomc_tay_time(y, p, k); break;
        case OP_ADD: eomc_tay_add(y, a, b, k); break;
        case OP_SUB: eomc_tay_sub(y, a, b, k); break;
        case OP_NEG: eomc_tay_neg(y, a, k); break;
        case OP_SCALE: eomc_tay_scale(y, a, b, k); break;
        case OP_MUL: eomc_tay_mul(y, a, b, k); break;
        case OP_SQR: eomc_tay_sqr(y, a, k); break;
        case OP_DIV: eomc_tay_div(y, a, b, k); break;
        case OP_INV: eomc_tay_inv(y, a, k); break;
        case OP_SQRT: eomc_tay_sqrt(y, a, k); break;
        case OP_EXP: eomc_tay_exp(y, a, k); break;
        case OP_LOG: eomc_tay_log(y, a, k); break;
        case OP_POWC: eomc_tay_powc(y, a, e, k); break;
        case OP_SINCOS: eomc_tay_sincos(y, u, a, k); break;
        case OP_SINHCOSH: eomc_tay_sinhcosh(y, u, a, k); break;
        case OP_TAN: eomc_tay_tan(y, u, a, k); break;
        case OP_TANH: eomc_tay_tanh(y, u, a, k); break;
        case OP_ASIN: eomc_tay_asin(y, u, v, a, k); break;
        case OP_ACOS: eomc_tay_acos(y, u, v, a, k); break;
        case OP_ATAN: eomc_tay_atan(y, u, a, k); break;
        case OP_ATAN2: eomc_tay_atan2(y, u, a, b, k); break;
        case OP_ABS: eomc_tay_abs(y, a, k); break;
        case OP_SIGN: eomc_tay_sign(y, a, k); break;
        case OP_MUL2: eomc_tay_mul2(y, u, a, b, a, a, k); break;
        case OP_MUL4: eomc_tay_mul4(y, u, v, w, a, b, a, a, b, b, b, a, k); break;
        }
}
