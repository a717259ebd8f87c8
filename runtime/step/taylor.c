/*
 * taylor: Taylor's method, the series of the motion through a state.
 *
 * The model's generated `taylor` function brings the series of every
 * value of M(q) and h(t, q, q') one order further at each call
 * (eomc_taylor.h's recurrences on the DAG).  The accelerations' series
 * follows from M q'' = -h order by order:
 *     M_0 a_k = -(h_k + sum_{j=1..k} M_j a_{k-j}),
 * so M is factored once per step (at the state itself, as eomc_sim_accel
 * factors it: along its tree by LTDL where the model gives one
 * (mass_parent), else GSL's pivoted Cholesky, with the same pivot test;
 * a diagonal M, eomc_model's taylor_mass says, by its own entries) and
 * never inverted symbolically; a constant M's higher orders are 0 and
 * their sums are skipped; then q_{k+1} = q'_k / (k + 1) and
 * q'_{k+1} = a_k / (k + 1), which the next call reads (with M constant
 * and diagonal, q'_{k+1} = (h_k / M_jj) / -(k + 1) and, for k > 0,
 * q_{k+1} = (h_{k-1} / M_jj) / -(k (k + 1)), from h_{k-1} / M_jj rather
 * than through q'_k).  Without
 * constraints the model's taylor_run gives the whole series in one call,
 * into X (run_series), with the same arithmetic: where M is constant and
 * diagonal the generator did the solve itself, else it calls run_solve
 * (this file's factorization and solve) at each order.
 *
 * With speeds of their own (a unit quaternion's angular velocity: the
 * state is (q [nq], v [nv]), q' = W(q) v) the same holds in the speeds:
 * M is nv x nv, a = v', and the program also carries the series of q' =
 * W(q) v (taylor_qd), whose coefficient k follows from q's and v's up to
 * k; so q_{k+1} = (q')_k / (k + 1) and v_{k+1} = a_k / (k + 1).  The series
 * keeps |e| as the motion does, to its truncation; the step's end is
 * renormalized as every method's is (evolve.c's keep_unit), and the
 * compensated sum starts again on the components that moved.
 *
 * With constraints f = B(t, q, q') q'' + b(t, q, q') = 0 (each affine in
 * q'', with Baumgarte's terms w_v vel + w_p pos added to b when asked)
 * the same holds for the KKT system: (a_k, lambda_k) solve
 *     [M_0 B_0^T; B_0 0] [a_k; lambda_k]
 *         = -[h_k + sum_{j=1..k} (M_j a_{k-j} + B_j^T lambda_{k-j});
 *             b_k + sum_{j=1..k} B_j a_{k-j}],
 * one LU of the KKT matrix per step, scaled and equilibrated as
 * eomc_sim_accel's (la_kkt_scaling).  When a constraint is nonlinear in
 * q'', B depends on q'' too: a_0 and lambda_0 are eomc_sim_accel's
 * (Newton's method), and for k >= 1 coefficient k of f and of B are
 * affine in a_k, f_k = f_k|(a_k = 0) + B_0 a_k and B_k = B_k|(a_k = 0) +
 * dB/dq'' a_k, so the same system holds with M_0 + sum_c lambda_0c
 * dB_c/dq'' in M_0's place, f_k|(a_k = 0) for the second row (the
 * program computes it with 0 written for a_k), and B_k|(a_k = 0) in the
 * sum; the program then runs again at order k with a_k written, so that
 * the orders above see it.  Models whose constraints are
 * eliminated (Maggi) solve the same motion (C^T E = 0 and f = 0 hold
 * where E + B^T lambda = 0 and f = 0 do), so they take this way too.
 *
 * The order and the step are Jorba and Zou's ("A software package for
 * the numerical integration of ODEs by means of high-order Taylor
 * methods", Exp. Math. 14, 2005, sec. 3.2): order p = ceil(-ln(eps)/2 +
 * 1) for the relative tolerance eps = rtol, and the step
 *     h = rho / e^2 * exp(-0.7 / (p - 1)),
 * rho = min over the state's components i and the last two orders j =
 * p - 1, p of (S_i / |x_ij|)^(1/j), where S_i + atol / rtol is the
 * component's own scale: its size over the step (step_size) plus what
 * GSL's test, atol + rtol |x_i|, adds over rtol.  Then the series' last
 * terms are about e^-2p S_i, about rtol S_i: the local error a GSL method
 * with these tolerances allows, so the tolerance means what it means for
 * the other methods.  rho is a time (a ratio of coefficients of the same
 * component, to the power 1/j), so rescaling the units of mass, length or
 * time rescales h with them (with atol 0, or atol rescaled too).
 */
#include "taylor.h"
#include "model/state.h"
#include "model/simimpl.h"
#include "model/linalg.h"
#include "polyroots.h"

#include <gsl/gsl_pow_int.h>
#include <math.h>
#if defined(__SSE2__)
#include <emmintrin.h>

/* |p[0]|, |p[1]|: the sign bits cleared, as fabs does */
static inline __m128d
abs2(const double *p)
{
    return _mm_andnot_pd(_mm_set1_pd(-0.0), _mm_loadu_pd(p));
}
#endif
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct Taylor {
    eomc_sim *s;
    const eomc_model *m;
    int n, nv, N, p;    /* coordinates, speeds (n without speeds of their own),
                         * state size n + nv, the order */
    double rtol, atol;
    double hlast;       /* the last series' step (step_size), 0 where the next
                         * does not continue it */
    double factor;      /* the step's fraction of the radius, e^-2 exp(-0.7 / (p - 1)) */
    double *T;          /* [nslot (p + 1)] the model's series, slot s's from
                         * T[s (p + 1)]: the order's stride, not the largest
                         * order's, so that a chain's 200 series of order 16
                         * (27 KB) stay in the first-level cache */
    double *X;          /* [(p + 1) N] the state's: X[j N + i], x_i's coefficient j */
    double *A;          /* [nv (p + 1)] the accelerations', A[i (p + 1) + k] */
    double *M0;         /* [nv nv] M_0, factored */
    double *rel;        /* [nv] the factorization's relative pivots */
    size_t *perm;       /* [nv] its permutation */
    double *b;          /* [nv] a right-hand side */
    double *S;          /* [N] the components' scales (step_size) */
    double *d;          /* [N] a step's change (value) */
    double *comp;       /* [N] the rounding the state's additions lost so far */
    double *comp0;      /* [N] ... up to the last series' start (value) */
    double *xlast;      /* [N] the state taylor_advance left: the compensation
                         * holds while the next series starts there */
    double t0;          /* the last series' start */
    const double *u0;   /* without inputs, the modes' values (sim_inputs_at's
                         * array, which stays where it is), else NULL */
    /* a batch's series (taylor_lanes_fill), taken where the next series
     * starts at (tb, xb): X's and T's next, swapped in (NULL till then) */
    double *Xb, *Tb, *xb, tb;
    int filled;
    double hb;          /* ... and its step, or 0: step_size's to compute */
    /* with constraints (nc > 0; else NULL) */
    int nc;
    double *K, *dK, *r; /* [(nv + nc)^2] the KKT matrix at the start, its scaling,
                         * [nv + nc] a right-hand side */
    LaLu *lu;           /* its factorization */
    double *L;          /* [nc (p + 1)] the multipliers', L[c (p + 1) + k] */
    double *wv, *wp;    /* [nc] Baumgarte's weights (sim_baumgarte) */
    double *J;          /* a constraint nonlinear in q'' (m->taylor_a): c_jacobian's
                         * outputs, dB/dq'' at (dBda) among them; else NULL */
    double *dBda;
};

int
taylor_order_for(double rtol)
{
    double p = ceil(-0.5 * log(rtol) + 1);
    return p < TAYLOR_MIN_ORDER ? TAYLOR_MIN_ORDER : p > TAYLOR_MAX_ORDER ? TAYLOR_MAX_ORDER
                                                                          : (int)p;
}

int
taylor_check(eomc_sim *s, const eomc_run_opts *o)
{
    const eomc_model *m = eomc_sim_model(s);
    if (!m->taylor)
        return sim_usage_error(s, "--method taylor: %s has no Taylor series: %s", m->name,
                               m->taylor_why ? m->taylor_why : "it was generated without them");
    /* speeds of their own (a unit quaternion's angular velocity): q's
     * series comes from q' = W(q) v's, which the model must carry */
    if (m->nv > 0 && !m->taylor_qd)
        return sim_usage_error(s, "--method taylor: %s's speeds are not its coordinates' "
                               "rates (%s is a speed of its own), and its series lack the "
                               "kinematic equation q' = W(q) v (taylor_qd) that Taylor's "
                               "method sums q from; generate it again, or choose another "
                               "method", m->name, state_own_speed(m));
    for (int k = 0; k < m->nu; k++) {
        double v;
        if (!eomc_sim_input_held(s, k, &v))
            return sim_usage_error(s, "--method taylor: input %s is a signal of time, whose "
                                   "series Taylor's method does not take; hold it constant "
                                   "(--set %s=VALUE) or choose another method",
                                   m->u_names[k], m->u_names[k]);
    }
    if (m->taylor_a && !m->c_jacobian)
        return sim_usage_error(s, "--method taylor: %s has a constraint nonlinear in q'' "
                               "but no c_jacobian, whose dB/dq'' the series need", m->name);
    if (!(o->rtol > 0))
        return sim_usage_error(s, "--method taylor: --rtol must be positive (the order "
                               "comes from it), not %g", o->rtol);
    return EOMC_OK;
}

Taylor *
taylor_alloc(eomc_sim *s, const eomc_run_opts *o)
{
    const eomc_model *m = eomc_sim_model(s);
    Taylor *tp = calloc(1, sizeof *tp);
    if (!tp)
        return NULL;
    int n = m->nq, nv = eomc_nv(m), K = TAYLOR_MAX_ORDER;
    *tp = (Taylor){.s = s, .m = m, .n = n, .nv = nv, .N = n + nv, .rtol = o->rtol,
                   .atol = o->atol, .p = taylor_order_for(o->rtol),
                   .u0 = m->nu == 0 ? sim_inputs_at(s, 0, NULL, NULL) : NULL};
    tp->factor = exp(-2.0 - TAYLOR_SAFETY / (tp->p - 1));
    tp->T = sim_zeros((size_t)m->taylor_nslot * (size_t)(K + 1) + 1);
    tp->X = sim_zeros((size_t)(K + 1) * (size_t)tp->N);
    tp->A = sim_zeros((size_t)(K + 1) * (size_t)nv);
    tp->M0 = sim_zeros((size_t)nv * (size_t)nv);
    tp->rel = sim_zeros((size_t)nv);
    tp->b = sim_zeros((size_t)nv);
    tp->S = sim_zeros((size_t)tp->N);
    tp->d = sim_zeros((size_t)tp->N);
    tp->comp = sim_zeros((size_t)tp->N);
    tp->comp0 = sim_zeros((size_t)tp->N);
    tp->xlast = sim_zeros((size_t)tp->N);
    tp->perm = calloc((size_t)nv + 1, sizeof *tp->perm);
    if (!tp->T || !tp->X || !tp->A || !tp->M0 || !tp->rel || !tp->b || !tp->perm || !tp->S ||
        !tp->d || !tp->comp || !tp->comp0 || !tp->xlast) {
        taylor_free(tp);
        return NULL;
    }
    int nc = tp->nc = m->nc, nk = nv + nc;
    if (nc == 0)
        return tp;
    tp->K = sim_zeros((size_t)nk * (size_t)nk);
    tp->dK = sim_zeros((size_t)nk);
    tp->r = sim_zeros((size_t)nk);
    tp->L = sim_zeros((size_t)(K + 1) * (size_t)nc);
    tp->wv = sim_zeros((size_t)nc);
    tp->wp = sim_zeros((size_t)nc);
    tp->lu = la_lu_alloc(nk);
    if (!tp->K || !tp->dK || !tp->r || !tp->L || !tp->wv || !tp->wp || !tp->lu) {
        taylor_free(tp);
        return NULL;
    }
    for (int c = 0; c < nc; c++)
        sim_baumgarte(s, c, &tp->wv[c], &tp->wp[c]);
    if (m->taylor_a) { /* dfdq, dfdv, dfdu, dfdt, dBdq, dBdv, dBda, dBdu, dBdt:
                        * by q nq columns, by v and a nv (eomc_model.h) */
        size_t cq = (size_t)nc * (size_t)n, cv = (size_t)nc * (size_t)nv, nu = (size_t)m->nu;
        tp->J = sim_zeros(cq + cv + nc * nu + nc + cv * n + 2 * cv * nv + cv * nu + cv);
        if (!tp->J) {
            taylor_free(tp);
            return NULL;
        }
        tp->dBda = tp->J + cq + cv + nc * nu + nc + cv * n + cv * nv;
    }
    return tp;
}

void
taylor_free(Taylor *tp)
{
    if (!tp)
        return;
    free(tp->T);
    free(tp->X);
    free(tp->A);
    free(tp->M0);
    free(tp->rel);
    free(tp->b);
    free(tp->S);
    free(tp->d);
    free(tp->comp);
    free(tp->comp0);
    free(tp->xlast);
    free(tp->Xb);
    free(tp->Tb);
    free(tp->xb);
    free(tp->perm);
    free(tp->K);
    free(tp->dK);
    free(tp->r);
    free(tp->L);
    free(tp->wv);
    free(tp->wp);
    la_lu_free(tp->lu);
    free(tp->J);
    free(tp);
}

/* The model's inputs and modes at (t, x) (sim_inputs_at), without the
 * call where there are no inputs (Taylor.u0). */
static const double *
inputs_at(const Taylor *tp, double t, const double *x)
{
    return tp->u0 ? tp->u0 : sim_inputs_at(tp->s, t, x, x + tp->n);
}

/* Whether a and b hold the same n doubles, bit for bit (memcmp's test,
 * inlined: a call of it was 25 of Kepler's 4 000 instructions a step). */
static int
same_bits(const double *a, const double *b, int n)
{
    for (int i = 0; i < n; i++) {
        uint64_t x, y;
        memcpy(&x, a + i, sizeof x);
        memcpy(&y, b + i, sizeof y);
        if (x != y)
            return 0;
    }
    return 1;
}

/* Slot s's coefficient k. */
static double
coef(const Taylor *tp, int slot, int k)
{
    return slot < 0 ? 0 : tp->T[(size_t)slot * (tp->p + 1) + (size_t)k];
}

/* Write the state's coefficient k into the series the model reads. */
static void
put_state(Taylor *tp, int k)
{
    const eomc_model *m = tp->m;
    const double *xk = tp->X + (size_t)k * (size_t)tp->N;
    for (int i = 0; i < tp->n; i++)
        if (m->taylor_q[i] >= 0)
            tp->T[(size_t)m->taylor_q[i] * (tp->p + 1) + (size_t)k] = xk[i];
    for (int j = 0; j < tp->nv; j++)
        if (m->taylor_v[j] >= 0)
            tp->T[(size_t)m->taylor_v[j] * (tp->p + 1) + (size_t)k] = xk[tp->n + j];
}

/* Coefficient k of q'' (ak; NULL: 0) into the series the constraints
 * read, where one is nonlinear in q''. */
static void
put_accel(Taylor *tp, int k, const double *ak)
{
    for (int i = 0; i < tp->nv; i++)
        if (tp->m->taylor_a[i] >= 0)
            tp->T[(size_t)tp->m->taylor_a[i] * (tp->p + 1) + (size_t)k] = ak ? ak[i] : 0;
}

/* a_0 into tp->b and lambda_0 into the multipliers' series by Newton's
 * method (eomc_sim_accel, from the last solution, as every method's
 * solves), and dB/dq'' there; 0, or -1 when it fails. */
static int
newton_start(Taylor *tp, double t0, const double *x)
{
    const eomc_model *m = tp->m;
    int n = tp->n, nv = tp->nv, nc = tp->nc;
    if (eomc_sim_accel(tp->s, t0, x, x + n, tp->b) != EOMC_OK)
        return -1;
    const double *lam = eomc_sim_multipliers(tp->s);
    for (int c = 0; c < nc; c++)
        tp->L[(size_t)c * (tp->p + 1)] = lam[c];
    size_t cq = (size_t)nc * (size_t)n, cv = (size_t)nc * (size_t)nv, nu = (size_t)m->nu;
    double *J = tp->J, *dBdq = J + cq + cv + nc * nu + nc;
    m->c_jacobian(t0, x, x + n, tp->b, sim_p(tp->s), sim_inputs_at(tp->s, t0, x, x + n), J, J + cq,
                  J + cq + cv, J + cq + cv + nc * nu, dBdq, dBdq + cv * n, tp->dBda,
                  tp->dBda + cv * nv, tp->dBda + cv * nv + cv * nu);
    return 0;
}

/* min(a^(1/ja), b^(1/jb)) for a, b > 0 or INFINITY (INFINITY when both
 * are): the two roots of radius, each e^(ln x / j), the larger never
 * computed (the exponent is monotone).  Two logs and an exp cost 120
 * instructions where two pow calls cost 310 (of Kepler's 5 300 a step at
 * order 15); the root is a step size's, which no digit of the answer
 * depends on beyond rounding, and a few units in its last place are
 * nothing to it. */
static double
least_root(double a, int ja, double b, int jb)
{
    double la = a < INFINITY ? log(a) / ja : INFINITY;
    double lb = b < INFINITY ? log(b) / jb : INFINITY;
    double l = lb < la ? lb : la;
    return l < INFINITY ? exp(l) : INFINITY;
}

/* The radius of the state's series by its last two terms: the least over
 * the components i and j = p - 1, p of (S_i / |x_ij|)^(1/j).  The root is
 * monotone, so each order's least ratio is found first and rooted once
 * (least_root); the loops run over one order's components at a time, X's
 * own layout.  INFINITY when no component has a last term. */
static double
radius(const Taylor *tp, const double *S)
{
    int p = tp->p, N = tp->N;
    double least[2];
    for (int j = p - 1; j <= p; j++) {
        const double *c = tp->X + (size_t)j * (size_t)N;
        double l = INFINITY;
        int i = 0;
#if defined(__SSE2__)
        /* two components a lane, the least of each lane's ratios kept
         * where S and |c| are > 0 (the ratios are then numbers, > 0, so
         * the least is the same whichever way it is found): Kepler's
         * step 4 018 instructions to 4 001 */
        const __m128d zero = _mm_setzero_pd();
        __m128d lv = _mm_set1_pd(INFINITY);
        for (; i + 2 <= N; i += 2) {
            __m128d s = _mm_loadu_pd(S + i), a = abs2(c + i);
            __m128d r = _mm_div_pd(s, a);
            __m128d keep = _mm_and_pd(_mm_and_pd(_mm_cmpgt_pd(s, zero), _mm_cmpgt_pd(a, zero)),
                                      _mm_cmplt_pd(r, lv));
            lv = _mm_or_pd(_mm_and_pd(keep, r), _mm_andnot_pd(keep, lv));
        }
        double two[2];
        _mm_storeu_pd(two, lv);
        l = two[1] < two[0] ? two[1] : two[0];
#endif
        for (; i < N; i++) {
            double a = fabs(c[i]), r = S[i] / a;
            l = S[i] > 0 && a > 0 && r < l ? r : l;
        }
        least[j - (p - 1)] = l;
    }
    return least_root(least[0], p - 1, least[1], p);
}

/* The first estimate of the radius, before any scale is known: radius's
 * rule with each component measured against its first coefficient that
 * is not 0, x_im (its size where it starts from rest or from 0), and
 * rooted by j - m. */
static double
radius_first(const Taylor *tp)
{
    int p = tp->p, N = tp->N;
    double least[TAYLOR_MAX_ORDER + 1]; /* by the root's degree, j - m */
    for (int e = 1; e <= p; e++)
        least[e] = INFINITY;
    for (int i = 0; i < N; i++) {
        int m = 0;
        while (m < p - 1 && tp->X[(size_t)m * (size_t)N + (size_t)i] == 0)
            m++;
        double scale = fabs(tp->X[(size_t)m * (size_t)N + (size_t)i]);
        for (int j = p - 1; j <= p; j++) {
            double a = fabs(tp->X[(size_t)j * (size_t)N + (size_t)i]);
            if (scale > 0 && a > 0 && j > m && scale / a < least[j - m])
                least[j - m] = scale / a;
        }
    }
    double rho = INFINITY;
    for (int e = 1; e <= p; e++)
        if (least[e] < INFINITY) {
            double r = pow(least[e], 1.0 / e);
            rho = r < rho ? r : rho;
        }
    return rho;
}

/* The loops over the orders run inside one over blocks of TAYLOR_BLOCK
 * components: a block's sums stay in registers from one order to the
 * next, where a loop over the components inside one over the orders
 * loads and stores each at every order (and gcc -O2 does not vectorize a
 * loop whose count it does not know).  The arithmetic of each component
 * is the same, in the same order.  Four: a Kepler orbit's state, and two
 * SSE2 vectors (Kepler's value and scales, 940 instructions a step, took
 * 470 so). */
enum { TAYLOR_BLOCK = 4 };

/* scales for the w <= TAYLOR_BLOCK components from X's column 0 (X's
 * stride N): inlined, w a constant for the whole blocks.  A whole block
 * on SSE2's two-lane vectors where the machine has them: the same
 * operations lane by lane (fabs as the sign bit cleared; maxpd(a, b) is
 * a > b ? a : b, NaNs too), so the same bits, which gcc -O3 does not
 * find itself (with value_block's: Kepler's step at order 15, 4 113
 * instructions to 4 031). */
static inline void
scales_block(const double *X, int N, int p, double h, double absolute, double *S, int w)
{
#if defined(__SSE2__)
    if (w == TAYLOR_BLOCK) {
        __m128d s0 = abs2(X), s1 = abs2(X + 2);
        double hj = 1;
        for (int j = 1; j <= p; j++) {
            const double *c = X + (size_t)j * (size_t)N;
            hj *= h;
            __m128d hv = _mm_set1_pd(hj);
            s0 = _mm_max_pd(_mm_mul_pd(abs2(c), hv), s0);
            s1 = _mm_max_pd(_mm_mul_pd(abs2(c + 2), hv), s1);
        }
        __m128d a = _mm_set1_pd(absolute);
        _mm_storeu_pd(S, _mm_add_pd(s0, a));
        _mm_storeu_pd(S + 2, _mm_add_pd(s1, a));
        return;
    }
#endif
    double s[TAYLOR_BLOCK], hj = 1;
    for (int l = 0; l < w; l++)
        s[l] = fabs(X[l]);
    for (int j = 1; j <= p; j++) {
        const double *c = X + (size_t)j * (size_t)N;
        hj *= h;
        for (int l = 0; l < w; l++) {
            double term = fabs(c[l]) * hj;
            s[l] = term > s[l] ? term : s[l];
        }
    }
    for (int l = 0; l < w; l++)
        S[l] = s[l] + absolute;
}

/* Component i's size over a step of h: its series' largest term there,
 * plus atol / rtol (GSL's atol + rtol |x_i|, over rtol). */
static void
scales(Taylor *tp, double h, double *restrict S)
{
    int p = tp->p, N = tp->N, i = 0;
    double absolute = tp->atol / tp->rtol;
    for (; i + TAYLOR_BLOCK <= N; i += TAYLOR_BLOCK)
        scales_block(tp->X + i, N, p, h, absolute, S + i, TAYLOR_BLOCK);
    if (i < N)
        scales_block(tp->X + i, N, p, h, absolute, S + i, N - i);
}

/* The step the series allows (Jorba and Zou, above), with each
 * component's scale its size over the step rather than at its start: a
 * component passing through 0 (a pendulum at the bottom) is measured
 * against how far it moves, not against its vanishing value.  The scales
 * and the step depend on each other.  Where the series continues the last
 * one's motion (hlast), the scales over the last step's size settle it in
 * one round: steps change little from one to the next, and the round and
 * the first terms' radius saved are a third of Kepler's step besides its
 * series.  At a start, after an event, or after a series that was a
 * polynomial (hlast infinite), the first terms' radius starts
 * TAYLOR_SCALE_ROUNDS rounds. */
static double
step_size(Taylor *tp)
{
    int warm = tp->hlast > 0 && tp->hlast < INFINITY;
    double h = warm ? tp->hlast : radius_first(tp) * tp->factor;
    for (int r = 0; r < (warm ? 1 : TAYLOR_SCALE_ROUNDS) && isfinite(h); r++) {
        scales(tp, h, tp->S);
        h = radius(tp, tp->S) * tp->factor;
    }
    return tp->hlast = h;
}

/* sum + sum_{j=1..k} c_j b_{k-j}, c slot's series (none for slot -1), b
 * a series of the same stride: the terms of order k of a product whose
 * factor b is not yet known at order k. */
static double
conv(const Taylor *tp, int slot, const double *b, int k, double sum)
{
    if (slot < 0)
        return sum;
    const double *c = tp->T + (size_t)slot * (size_t)(tp->p + 1);
    for (int j = 1; j <= k; j++)
        sum += c[j] * b[k - j];
    return sum;
}

/* sum_{j=1..k} (M_j a_{k-j})_i: each entry's series against the
 * accelerations' (A: coordinate by coordinate, contiguous). */
static double
mass_terms(const Taylor *tp, int i, int k)
{
    int n = tp->nv;
    double sum = 0;
    for (int l = 0; l < n; l++)
        sum = conv(tp, tp->m->taylor_M[i * n + l], tp->A + (size_t)l * (tp->p + 1), k, sum);
    return sum;
}

/* M_0, from its entries in tp->M0, factored (along its tree by LTDL
 * where the model gives one, else GSL's pivoted Cholesky; a diagonal one
 * only tested, its pivots its own entries).  0, or -1 when it is not
 * safely positive definite. */
static int
m0_factor(Taylor *tp)
{
    const eomc_model *m = tp->m;
    int n = tp->nv;
    if (m->taylor_mass & EOMC_TAYLOR_M_DIAGONAL) { /* la_ldlt_factor's test */
        for (int i = 0; i < n; i++)
            if (!(tp->M0[i * n + i] > EOMC_PIVOT_TOL * tp->M0[i * n + i]))
                return -1;
        return 0;
    }
    return m->mass_parent ? la_ltdl_factor(tp->M0, n, m->mass_parent, tp->rel)
                          : la_ldlt_factor(tp->M0, n, tp->rel, tp->perm);
}

/* b := -M_0^-1 b by m0_factor's factorization: a diagonal one's solve a
 * division, as its factorization's (L = 1, D = M_0). */
static void
m0_solve_neg(Taylor *tp, double *b)
{
    const eomc_model *m = tp->m;
    int n = tp->nv;
    if (m->taylor_mass & EOMC_TAYLOR_M_DIAGONAL)
        for (int i = 0; i < n; i++)
            b[i] = -(b[i] / tp->M0[i * n + i]);
    else if (m->mass_parent) /* along M's tree, as eomc_sim_accel solves */
        la_ltdl_solve_neg(tp->M0, n, m->mass_parent, b);
    else
        la_ldlt_solve_neg(tp->M0, n, tp->perm, b);
}

/* Coefficient k of the accelerations into tp->b, unconstrained:
 * M_0 a_k = -(h_k + sum_{j=1..k} M_j a_{k-j}), M_0 factored at k = 0.
 * 0, or -1 when M_0 is not safely positive definite. */
static int
mass_order(Taylor *tp, int k)
{
    const eomc_model *m = tp->m;
    int n = tp->nv;
    if (k == 0) {
        for (int i = 0; i < n * n; i++)
            tp->M0[i] = coef(tp, m->taylor_M[i], 0);
        if (m0_factor(tp) != 0)
            return -1;
    }
    /* b = h_k + sum_{j=1..k} M_j a_{k-j}, then a_k = -M_0^-1 b.  A
     * constant M's M_j are 0: the sum is +0, what its n^2 series of zeros
     * would add up to */
    int constant = m->taylor_mass & EOMC_TAYLOR_M_CONSTANT;
    for (int i = 0; i < n; i++)
        tp->b[i] = coef(tp, m->taylor_h[i], k) + (constant ? 0.0 : mass_terms(tp, i, k));
    m0_solve_neg(tp, tp->b);
    return 0;
}

/* taylor_run's solve (eomc_model.h's eomc_tay_solve): mass_order's
 * factorization and solve, on the generated code's M_0 and b. */
static int
run_solve(void *ctx, int k, const double *M0, double *b)
{
    Taylor *tp = ctx;
    if (k == 0) {
        memcpy(tp->M0, M0, (size_t)tp->nv * (size_t)tp->nv * sizeof *M0);
        if (m0_factor(tp) != 0)
            return -1;
    }
    m0_solve_neg(tp, b);
    return 0;
}

/* The same with constraints: (a_k, lambda_k) into tp->b and tp->L from
 * the KKT system (above), factored at k = 0.  0, or -1 when it is
 * singular. */
static int
kkt_order(Taylor *tp, int k)
{
    const eomc_model *m = tp->m;
    int n = tp->nv, nc = tp->nc, nk = n + nc, p = tp->p;
    /* a row left out of the solves: its row and column 0, a 1 between,
     * 0 on the right, its multiplier 0 at every order (kkt.c) */
    const unsigned char *drop = sim_dropped_rows(tp->s);
    if (k == 0) {
        memset(tp->K, 0, (size_t)nk * (size_t)nk * sizeof *tp->K);
        for (int i = 0; i < n; i++)
            for (int l = 0; l < n; l++)
                tp->K[i * nk + l] = coef(tp, m->taylor_M[i * n + l], 0);
        for (int c = 0; c < nc; c++)
            for (int i = 0; i < n; i++)
                tp->K[(n + c) * nk + i] = tp->K[i * nk + n + c] =
                    drop && drop[c] ? 0 : coef(tp, m->taylor_B[c * n + i], 0);
        for (int c = 0; drop && c < nc; c++)
            tp->K[(n + c) * nk + n + c] = drop[c];
        for (int c = 0; c < nc && tp->dBda; c++) { /* + sum_c lambda_0c dB_c/dq'' */
            double lc = tp->L[(size_t)c * (p + 1)];
            for (int i = 0; i < n; i++)
                for (int l = 0; l < n; l++)
                    tp->K[i * nk + l] += lc * tp->dBda[((size_t)c * n + i) * n + l];
        }
        la_kkt_scaling(tp->K, n, nc, tp->dK);
        if (la_lu_factor_scaled(tp->lu, tp->K, tp->dK) != 0)
            return -1;
        if (tp->dBda) /* a_0 and lambda_0 are Newton's */
            return 0;
    }
    for (int i = 0; i < n; i++)
        tp->r[i] = coef(tp, m->taylor_h[i], k) + mass_terms(tp, i, k);
    for (int c = 0; c < nc; c++) {
        double rc = coef(tp, m->taylor_f[c], k) + tp->wv[c] * coef(tp, m->taylor_vel[c], k) +
                    tp->wp[c] * coef(tp, m->taylor_pos[c], k);
        const double *lam = tp->L + (size_t)c * (p + 1);
        for (int i = 0; i < n; i++) {
            int slot = m->taylor_B[c * n + i];
            tp->r[i] += conv(tp, slot, lam, k, 0);
            if (!tp->dBda) /* else f_k has these terms already */
                rc += conv(tp, slot, tp->A + (size_t)i * (p + 1), k, 0);
        }
        tp->r[n + c] = drop && drop[c] ? 0 : rc;
    }
    la_lu_solve(tp->lu, tp->r);
    for (int i = 0; i < n; i++)
        tp->b[i] = -tp->r[i];
    for (int c = 0; c < nc; c++)
        tp->L[(size_t)c * (p + 1) + (size_t)k] = -tp->r[n + c];
    return 0;
}

/* The state's series by the model's taylor_run (eomc_model.h): the whole
 * series into X in one call from its coefficient 0 there, a constant and
 * diagonal M_0 tested as m0_factor tests it (else the solve did).  0; -1
 * when M_0 is not safely positive or a coefficient is not finite; 1 where
 * the order is above what it writes out, for the loop. */
static int
run_series(Taylor *tp, double t0, const double *par, const double *u)
{
    const eomc_model *m = tp->m;
    int nv = tp->nv, N = tp->N, p = tp->p;
    int rc = 0;
    if (tp->filled) { /* a batch's, for this very start (taylor_series) */
        double *X = tp->X, *T = tp->T;
        tp->X = tp->Xb, tp->T = tp->Tb, tp->Xb = X, tp->Tb = T;
    } else {
        rc = m->taylor_run(p, t0, par, u, tp->T, tp->X, run_solve, tp);
    }
    if (rc != 0)
        return rc;
    int diagonal = m->taylor_mass == (EOMC_TAYLOR_M_CONSTANT | EOMC_TAYLOR_M_DIAGONAL);
    for (int j = 0; j < nv && diagonal; j++) {
        double d = coef(tp, m->taylor_M[j * nv + j], 0);
        if (!(d > EOMC_PIVOT_TOL * d))
            return -1;
    }
    return sim_all_finite(tp->X + N, p * N) ? 0 : -1;
}

int
taylor_series(Taylor *tp, double t0, const double *x, double hmax, double *h)
{
    const eomc_model *m = tp->m;
    int n = tp->n, nv = tp->nv, N = tp->N, p = tp->p;
    const double *par = sim_p(tp->s);
    const double *u = inputs_at(tp, t0, x);
    /* a start the last advance did not leave (an event's reset, a side
     * step's own start) owes nothing; where the unit quaternions were
     * renormalized since, they owe nothing, and the rest what they did */
    if (!same_bits(x, tp->xlast, N)) {
        tp->hlast = 0;
        for (int i = 0; i < N; i++)
            if (m->nquat == 0 || x[i] != tp->xlast[i])
                tp->comp[i] = 0;
    }
    memcpy(tp->comp0, tp->comp, (size_t)N * sizeof *tp->comp);
    /* a batch's series is taken for its own start alone, to the bit */
    tp->filled = tp->filled && t0 == tp->tb && same_bits(x, tp->xb, N);
    memcpy(tp->filled ? tp->Xb : tp->X, x, (size_t)N * sizeof *x);
    tp->t0 = t0;
    if (tp->nc > 0 && sim_choose_rows(tp->s, t0, x, x + n) != EOMC_OK)
        return -1; /* the rows its solves use, where they are not chosen yet */
    int filled = tp->filled;
    int rc = m->taylor_run ? run_series(tp, t0, par, u) : 1;
    tp->filled = 0;
    if (rc < 0)
        return -1;
    if (rc == 0) {
        double hs = filled && tp->hb > 0 ? (tp->hlast = tp->hb) : step_size(tp);
        *h = hs < hmax ? hs : hmax;
        return 0;
    }
    /* a constant diagonal M, q' = v: q's next coefficient from a_{k-1} =
     * -(h_{k-1} / M_ii) rather than through q'_k, as taylor_run's
     * (eomc_tay_integ2; its v's, (h / M) / -(k + 1), is -(h / M) / (k + 1)
     * here to the bit, rounding being symmetric in the sign) */
    int fold = m->taylor_mass == (EOMC_TAYLOR_M_CONSTANT | EOMC_TAYLOR_M_DIAGONAL) &&
               !m->taylor_qd && tp->nc == 0;
    for (int k = 0; k < p; k++) {
        put_state(tp, k);
        if (tp->dBda && k == 0 && newton_start(tp, t0, x) != 0)
            return -1;
        if (tp->dBda)
            put_accel(tp, k, k == 0 ? tp->b : NULL);
        m->taylor(k, p, t0, par, u, tp->T);
        if (tp->nc > 0) {
            if (kkt_order(tp, k) != 0)
                return -1;
        } else if (mass_order(tp, k) != 0) {
            return -1;
        }
        if (tp->dBda && k > 0) { /* order k again, with a_k */
            put_accel(tp, k, tp->b);
            m->taylor(k, p, t0, par, u, tp->T);
        }
        double *next = tp->X + (size_t)(k + 1) * (size_t)N;
        const double *cur = tp->X + (size_t)k * (size_t)N;
        for (int j = 0; j < nv; j++) {
            tp->A[(size_t)j * (p + 1) + (size_t)k] = tp->b[j];
            next[n + j] = tp->b[j] / (k + 1);
        }
        for (int i = 0; i < n; i++) { /* q' = v, or W(q) v's series */
            if (fold && k > 0) /* a_{k-1} = -(h_{k-1} / M_ii), the quotient kept in A */
                next[i] = tp->A[(size_t)i * (p + 1) + (size_t)(k - 1)] / (k * (k + 1));
            else
                next[i] = (m->taylor_qd ? coef(tp, m->taylor_qd[i], k) : cur[n + i]) / (k + 1);
        }
    }
    /* once, not at each order: a non-finite coefficient only makes the
     * orders after it non-finite too */
    if (!sim_all_finite(tp->X + N, p * N))
        return -1;
    double hs = step_size(tp);
    *h = hs < hmax ? hs : hmax;
    return 0;
}

/* value for the w <= TAYLOR_BLOCK components from column 0 of X, comp0,
 * x and d (X's stride N), as scales_block (SSE2 too). */
static inline void
value_block(const double *X, const double *comp0, int N, int p, double tau, double *x,
            double *d, int w)
{
#if defined(__SSE2__)
    if (w == TAYLOR_BLOCK) {
        const double *top = X + (size_t)p * (size_t)N;
        __m128d a0 = _mm_loadu_pd(top), a1 = _mm_loadu_pd(top + 2), t = _mm_set1_pd(tau);
        for (int j = p - 1; j >= 1; j--) {
            const double *c = X + (size_t)j * (size_t)N;
            a0 = _mm_add_pd(_mm_mul_pd(a0, t), _mm_loadu_pd(c));
            a1 = _mm_add_pd(_mm_mul_pd(a1, t), _mm_loadu_pd(c + 2));
        }
        __m128d d0 = _mm_sub_pd(_mm_mul_pd(a0, t), _mm_loadu_pd(comp0));
        __m128d d1 = _mm_sub_pd(_mm_mul_pd(a1, t), _mm_loadu_pd(comp0 + 2));
        _mm_storeu_pd(d, d0);
        _mm_storeu_pd(d + 2, d1);
        _mm_storeu_pd(x, _mm_add_pd(_mm_loadu_pd(X), d0));
        _mm_storeu_pd(x + 2, _mm_add_pd(_mm_loadu_pd(X + 2), d1));
        return;
    }
#endif
    double a[TAYLOR_BLOCK];
    for (int l = 0; l < w; l++)
        a[l] = X[(size_t)p * (size_t)N + (size_t)l];
    for (int j = p - 1; j >= 1; j--) {
        const double *c = X + (size_t)j * (size_t)N;
        for (int l = 0; l < w; l++)
            a[l] = a[l] * tau + c[l];
    }
    for (int l = 0; l < w; l++) {
        d[l] = a[l] * tau - comp0[l];
        x[l] = X[l] + d[l];
    }
}

/* The change over tau, sum_{j>=1} x_j tau^j, by Horner's rule into d,
 * less what the state's rounding owes (comp); then the start plus it. */
static void
value(const Taylor *tp, double tau, double *x, double *restrict d)
{
    int N = tp->N, p = tp->p, i = 0;
    for (; i + TAYLOR_BLOCK <= N; i += TAYLOR_BLOCK)
        value_block(tp->X + i, tp->comp0 + i, N, p, tau, x + i, d + i, TAYLOR_BLOCK);
    if (i < N)
        value_block(tp->X + i, tp->comp0 + i, N, p, tau, x + i, d + i, N - i);
}

void
taylor_eval(const Taylor *tp, double tau, double *x)
{
    value(tp, tau, x, tp->d);
}

void
taylor_advance(Taylor *tp, double tau, double *x)
{
    value(tp, tau, x, tp->d);
    int i = 0;
#if defined(__SSE2__) /* two a lane, the same operations (with taylor_error's: Kepler's step 4 001
                       * instructions to 3 992) */
    for (; i + 2 <= tp->N; i += 2)
        _mm_storeu_pd(tp->comp + i,
                      _mm_sub_pd(_mm_sub_pd(_mm_loadu_pd(x + i), _mm_loadu_pd(tp->X + i)),
                                 _mm_loadu_pd(tp->d + i)));
#endif
    for (; i < tp->N; i++) /* Kahan: what x's addition lost */
        tp->comp[i] = (x[i] - tp->X[i]) - tp->d[i];
    memcpy(tp->xlast, x, (size_t)tp->N * sizeof *x);
}

void
taylor_error(const Taylor *tp, double h, double *err)
{
    const double *c = tp->X + (size_t)tp->p * (size_t)tp->N;
    double hp = gsl_pow_int(fabs(h), tp->p); /* by squaring: 30 instructions, pow's 155 */
    int i = 0;
#if defined(__SSE2__) /* (two a lane: fabs as the sign bit cleared) */
    const __m128d hv = _mm_set1_pd(hp);
    for (; i + 2 <= tp->N; i += 2)
        _mm_storeu_pd(err + i, _mm_mul_pd(abs2(c + i), hv));
#endif
    for (; i < tp->N; i++)
        err[i] = fabs(c[i]) * hp;
}

double
taylor_event_cut(const Taylor *tp, double h)
{
    const eomc_model *m = tp->m;
    double c[TAYLOR_MAX_ORDER + 1], hcut = h;
    for (int e = 0; e < m->nevent + m->nmode && m->taylor_g; e++) {
        if (m->taylor_g[e] < 0)
            continue;
        /* g's series has the orders the program reached, 0 .. p - 1 */
        double hj = 1, cut;
        for (int j = 0; j < tp->p; j++, hj *= h)
            c[j] = coef(tp, m->taylor_g[e], j) * hj;
        if (poly_first_roots(c, tp->p - 1, &cut) == 2)
            hcut = fmin(hcut, cut * h);
    }
    return hcut;
}

double
taylor_start(const Taylor *tp)
{
    return tp->t0;
}

int
taylor_order(const Taylor *tp)
{
    return tp->p;
}

/* ---- EOMC_LANES runs at once (taylor.h: taylor_lanes_fill) ---- */

struct TaylorLanes {
    const eomc_model *m;
    int p;                 /* the runs' order */
    double *t0, *par, *u;  /* the lanes' side by side: [i EOMC_LANES + l] */
    double *T, *X;
    double *idle;          /* an idle lane's series, dropped */
    double *S;             /* [N lanes] the components' scales (lanes_step) */
};

/* n doubles aligned to a vector of the lanes (eomc_model.h asks it), zeroed. */
static double *
lane_zeros(size_t n)
{
    size_t bytes = (n * EOMC_LANES * sizeof(double) + 63) / 64 * 64;
    double *a = aligned_alloc(64, bytes);
    if (a)
        memset(a, 0, bytes);
    return a;
}

TaylorLanes *
taylor_lanes_alloc(const eomc_model *m, const eomc_run_opts *o)
{
    int p = taylor_order_for(o->rtol), N = m->nq + eomc_nv(m);
    if (!m->taylor_run4 || !(o->rtol > 0))
        return NULL;
    TaylorLanes *b = calloc(1, sizeof *b);
    if (!b)
        return NULL;
    b->m = m, b->p = p;
    b->t0 = lane_zeros(1);
    b->par = lane_zeros((size_t)m->np + (size_t)m->nd + 1);
    b->u = lane_zeros((size_t)m->nu + (size_t)m->nmode + 1);
    b->T = lane_zeros((size_t)m->taylor_nslot * (size_t)(p + 1) + 1);
    b->X = lane_zeros((size_t)(p + 1) * (size_t)N);
    b->idle = sim_zeros((size_t)(p + 1) * (size_t)N);
    b->S = lane_zeros((size_t)N);
    if (!b->t0 || !b->par || !b->u || !b->T || !b->X || !b->idle || !b->S) {
        taylor_lanes_free(b);
        return NULL;
    }
    return b;
}

void
taylor_lanes_free(TaylorLanes *b)
{
    if (!b)
        return;
    free(b->t0);
    free(b->par);
    free(b->u);
    free(b->T);
    free(b->X);
    free(b->idle);
    free(b->S);
    free(b);
}

/* n values of lane l from a into the lanes' b. */
static void
to_lane(double *b, int l, const double *a, int n)
{
    for (int i = 0; i < n; i++)
        b[i * EOMC_LANES + l] = a[i];
}

/* step_size for the lanes where the series continues the last one's
 * motion (hlast), into h[l] (0 elsewhere, left to step_size; tp[first]
 * the first lane that is not idle): scales and
 * radius with the lanes side by side, each lane's arithmetic theirs in
 * their order, so its bits; the loops over the lanes vectorize. */
static void
lanes_step(const TaylorLanes *b, Taylor *const *tp, int first, const double *const *x,
           double *h)
{
    const Taylor *t0 = tp[first];
    int N = t0->N, p = b->p, warm = 0;
    double hj[EOMC_LANES], hw[EOMC_LANES], least[2][EOMC_LANES]; /* j = p - 1, p */
    for (int l = 0; l < EOMC_LANES; l++) {
        const Taylor *t = tp[l];
        int w = t && t->hlast > 0 && t->hlast < INFINITY &&
                same_bits(x[l], t->xlast, N);
        hw[l] = w ? t->hlast : 0;
        warm += w;
        hj[l] = 1;
        h[l] = 0;
    }
    if (!warm)
        return;
    double *restrict S = b->S;
    const double *restrict X = b->X;
    for (int i = 0; i < N * EOMC_LANES; i++)
        S[i] = fabs(X[i]);
    for (int j = 1; j <= p; j++) {
        const double *restrict c = X + (size_t)j * (size_t)N * EOMC_LANES;
        for (int l = 0; l < EOMC_LANES; l++)
            hj[l] *= hw[l];
        for (int i = 0; i < N; i++) {
            double *restrict s = S + i * EOMC_LANES;
            const double *restrict ci = c + i * EOMC_LANES;
            for (int l = 0; l < EOMC_LANES; l++) {
                double term = fabs(ci[l]) * hj[l];
                s[l] = term > s[l] ? term : s[l];
            }
        }
    }
    double absolute = t0->atol / t0->rtol;
    for (int i = 0; i < N * EOMC_LANES; i++)
        S[i] += absolute;
    for (int j = p - 1; j <= p; j++) {
        const double *c = X + (size_t)j * (size_t)N * EOMC_LANES;
        double *lj = least[j - (p - 1)];
        for (int l = 0; l < EOMC_LANES; l++)
            lj[l] = INFINITY;
        for (int i = 0; i < N; i++)
            for (int l = 0; l < EOMC_LANES; l++) {
                double s = S[i * EOMC_LANES + l], a = fabs(c[i * EOMC_LANES + l]), r = s / a;
                lj[l] = s > 0 && a > 0 && r < lj[l] ? r : lj[l];
            }
    }
    for (int l = 0; l < EOMC_LANES; l++)
        h[l] = hw[l] > 0 ? least_root(least[0][l], p - 1, least[1][l], p) * t0->factor : 0;
}

int
taylor_lanes_fill(TaylorLanes *b, Taylor *const *tp, const double *t0,
                  const double *const *x)
{
    const eomc_model *m = b->m;
    int first = -1;
    for (int l = EOMC_LANES - 1; l >= 0; l--)
        first = tp[l] ? l : first;
    if (first < 0)
        return 0;
    int N = tp[first]->N, p = b->p, S = p + 1;
    int nu = m->nu + m->nmode, ng = m->nevent + m->nmode;
    /* an idle lane repeats the first's, whose values are sound */
    for (int l = 0; l < EOMC_LANES; l++) {
        int k = tp[l] ? l : first;
        if (tp[k]->m != m || tp[k]->p != p)
            return -1;
        b->t0[l] = t0[k];
        to_lane(b->par, l, sim_p(tp[k]->s), m->np + m->nd); /* (and the derived) */
        to_lane(b->u, l, inputs_at(tp[k], t0[k], x[k]), nu);
        to_lane(b->X, l, x[k], N);
    }
    if (m->taylor_run4(p, b->t0, b->par, b->u, b->T, b->X) != 0)
        return -1;
    double h[EOMC_LANES];
    lanes_step(b, tp, first, x, h);
    double *dst[EOMC_LANES];
    for (int l = 0; l < EOMC_LANES; l++) {
        Taylor *t = tp[l];
        if (t && !t->Xb) { /* a Taylor in its first batch */
            t->Xb = sim_zeros((size_t)(TAYLOR_MAX_ORDER + 1) * (size_t)N);
            t->Tb = sim_zeros((size_t)m->taylor_nslot * (TAYLOR_MAX_ORDER + 1) + 1);
            t->xb = sim_zeros((size_t)N);
            if (!t->Xb || !t->Tb || !t->xb)
                return -1;
        }
        dst[l] = t ? t->Xb : b->idle;
    }
    /* the lanes apart, X's layout: one pass over the lanes' X, the lanes
     * written out (a loop over them costs three times as much) */
    _Static_assert(EOMC_LANES == 4, "the lanes are written out as four");
    double *d0 = dst[0], *d1 = dst[1], *d2 = dst[2], *d3 = dst[3];
    const double *v = b->X;
    for (int i = 0; i < S * N; i++, v += EOMC_LANES)
        d0[i] = v[0], d1[i] = v[1], d2[i] = v[2], d3[i] = v[3];
    for (int l = 0; l < EOMC_LANES; l++) {
        Taylor *t = tp[l];
        if (!t)
            continue;
        /* what taylor_run leaves in T for its caller (eomc_model.h): the
         * event functions' series, and M's diagonal where it is constant */
        for (int e = 0; e < ng; e++)
            for (int j = 0, g = m->taylor_g[e]; g >= 0 && j < p; j++)
                t->Tb[g * S + j] = b->T[(g * S + j) * EOMC_LANES + l];
        for (int j = 0; j < t->nv; j++) {
            int d = m->taylor_M[j * t->nv + j];
            t->Tb[d * S] = b->T[d * S * EOMC_LANES + l];
        }
        memcpy(t->xb, x[l], (size_t)N * sizeof *t->xb);
        t->tb = t0[l];
        t->hb = h[l];
        t->filled = 1;
    }
    return 0;
}
