/*
 * The taylor member (eomc_model.h; compiler/lower/lower_taylor.c prints its
 * program) of shipped and test specs, checked independently of the
 * recurrences it calls: q(t) and q'(t) are made up as cubic polynomials
 * in tau = t - t0 (not a motion, and not consistent with each other),
 * their coefficients written into the caller's slots, taylor called for
 * k = 0 .. K, and the series it leaves for each M_ij, h_i and g_e summed
 * at small tau.  Those sums must equal what the model's own mass_bias and
 * events compute at q(tau), q'(tau), t0 + tau: the truncation is
 * O(tau^(K+1)), far below rounding at |tau| <= 2e-2, so they agree to
 * rounding of the values' scale.  Constrained models' series of B and f
 * and of the constraints' own levels are checked the same way against
 * constraint and c_levels: f at q'' = 0 where every constraint is affine
 * in q'', else (cubic.yaml) at a made-up q''(t) written into taylor_a's
 * slots.  What taylor_mass claims of M, against mass_bias at the same
 * made-up states: constant in t, the same M at every tau and t0 to the
 * bit; diagonal, its entries off the diagonal 0.
 */
#include "../unit/check.h"
#include "eomc_model.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef SERIES_LINE_BY_LINE
/* The models whose series has packs (compiler/lower/lower_pack.c), built
 * with -DEOMC_NO_PACKS: their packs' lines one at a time, which must be
 * the loop's bits as the vectors are. */
#define MODELS(X) X(kepler) X(arenstorf) X(spinning_hoop) X(pleiades) X(outer_solar_system)
#else
#define MODELS(X)                                                                       \
    X(pendulum) X(double_pendulum) X(chain5) X(spinning_hoop) X(kepler) X(arenstorf)   \
    X(swing) X(gear_link) X(bouncing_ball) X(falling_particle) X(sleeping_top_euler) \
    X(forced_hoop) X(taylor_ops) X(cartesian_pendulum) X(appell) X(precession)                \
    X(chaplygin_sleigh) X(central_constant_speed) X(car_axis) X(andrews) X(cubic)     \
    X(pleiades) X(outer_solar_system) X(cartpole)
#endif
#define DECLARE(name) extern const eomc_model name##_model;
MODELS(DECLARE)
#define ENTRY(name) &name##_model,
static const eomc_model *const models[] = {MODELS(ENTRY)};

enum { NMAX = 18, CMAX = 8, PMAX = 256, EMAX = 8, UMAX = 8, K = 12, DEG = 3 };
/* an order above LOW_SERIES_ORDERS (compiler/lower/lowered.h), where
 * taylor_run loops over the program rather than running it written out */
enum { K_LOOP = 24 };

/* The agreement required, relative to the largest |value| of M, h or g
 * (at least 1): a few hundred ulps of sums over the order and of the
 * terms that cancel in h. */
#define TOL 1e-13

/* sum_j c[j] tau^j, j = 0 .. K, by Horner's rule. */
static double
series_at(const double *c, double tau)
{
    double s = 0;
    for (int j = K; j >= 0; j--)
        s = s * tau + c[j];
    return s;
}

/* Slot s's series at tau (s < 0: zero at every order). */
static double
slot_at(const double *T, int s, double tau)
{
    return s < 0 ? 0 : series_at(T + s * (K + 1), tau);
}

/* The largest error of the series of M, h, g and the constraints' B, b,
 * pos and vel at taus, against the model's own functions, relative to
 * their scale. */
/* Where M breaks what taylor_mass claims: the number of (tau, entry)
 * pairs, summed over check_model's calls. */
static int mass_claims_broken;
/* M at the first state check_model saw, for the constant claim */
static double M_first[NMAX * NMAX];
static int have_M_first;

/* The parameters with the derived values after them, and the inputs at
 * t0 (held over the step). */
static void
params_inputs(const eomc_model *m, double t0, double *p, double *u)
{
    memcpy(p, m->p_default, (size_t)m->np * sizeof *p);
    if (m->derive)
        m->derive(p, p + m->np);
    if (m->nu)
        m->inputs(t0, p, u, NULL);
}

static double
check_model(const eomc_model *m, double t0, double *worst_scale)
{
    int n = m->nq, ne = m->nevent, nc = m->nc;
    double p[PMAX], u[UMAX + 1] = {0};
    params_inputs(m, t0, p, u);
    /* q_i(tau) and q_i'(tau): cubics of made-up coefficients */
    double qc[NMAX][K + 1], vc[NMAX][K + 1], ac[NMAX][K + 1];
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= K; j++) {
            qc[i][j] = j <= DEG ? check_rand(-0.6, 0.6) : 0;
            vc[i][j] = j <= DEG ? check_rand(-0.8, 0.8) : 0;
            ac[i][j] = j <= DEG && m->taylor_a ? check_rand(-0.8, 0.8) : 0;
        }
    double *T = calloc((size_t)m->taylor_nslot * (K + 1) + 1, sizeof *T);
    for (int k = 0; k <= K; k++) {
        for (int i = 0; i < n; i++) {
            if (m->taylor_q[i] >= 0)
                T[m->taylor_q[i] * (K + 1) + k] = qc[i][k];
            if (m->taylor_v[i] >= 0)
                T[m->taylor_v[i] * (K + 1) + k] = vc[i][k];
            if (m->taylor_a && m->taylor_a[i] >= 0)
                T[m->taylor_a[i] * (K + 1) + k] = ac[i][k];
        }
        m->taylor(k, K, t0, p, u, T);
    }
    static const double taus[] = {1e-2, -1.5e-2, 2e-2, 0};
    double worst = 0;
    *worst_scale = 0;
    for (size_t t = 0; t < sizeof taus / sizeof taus[0]; t++) {
        double tau = taus[t], q[NMAX], v[NMAX], M[NMAX * NMAX], h[NMAX], g[EMAX];
        double a[NMAX], f[CMAX], B[CMAX * NMAX] = {0}, pos[CMAX], vel[CMAX];
        for (int i = 0; i < n; i++) {
            q[i] = series_at(qc[i], tau);
            v[i] = series_at(vc[i], tau);
            a[i] = series_at(ac[i], tau); /* 0 unless taylor_a */
        }
        m->mass_bias(t0 + tau, q, v, p, u, M, h);
        if (!have_M_first) {
            memcpy(M_first, M, (size_t)n * n * sizeof *M);
            have_M_first = 1;
        }
        for (int i = 0; i < n * n; i++) {
            if ((m->taylor_mass & EOMC_TAYLOR_M_CONSTANT) && M[i] != M_first[i])
                mass_claims_broken++;
            if ((m->taylor_mass & EOMC_TAYLOR_M_DIAGONAL) && i / n != i % n && M[i] != 0)
                mass_claims_broken++;
        }
        if (ne)
            m->events(t0 + tau, q, v, p, u, g);
        if (nc) {
            m->constraint(t0 + tau, q, v, a, p, u, f, B);
            m->c_levels(t0 + tau, q, v, p, u, pos, vel);
        }
        double scale = 1;
        for (int i = 0; i < n * n; i++)
            scale = fmax(scale, fabs(M[i]));
        for (int i = 0; i < n; i++)
            scale = fmax(scale, fabs(h[i]));
        for (int e = 0; e < ne; e++)
            scale = fmax(scale, fabs(g[e]));
        for (int c = 0; c < nc; c++) {
            scale = fmax(scale, fmax(fabs(f[c]), fmax(fabs(pos[c]), fabs(vel[c]))));
            for (int i = 0; i < n; i++)
                scale = fmax(scale, fabs(B[c * n + i]));
        }
        double err = 0;
        for (int i = 0; i < n * n; i++)
            err = fmax(err, fabs(slot_at(T, m->taylor_M[i], tau) - M[i]));
        for (int i = 0; i < n; i++)
            err = fmax(err, fabs(slot_at(T, m->taylor_h[i], tau) - h[i]));
        for (int e = 0; e < ne; e++)
            err = fmax(err, fabs(slot_at(T, m->taylor_g[e], tau) - g[e]));
        for (int c = 0; c < nc; c++) {
            err = fmax(err, fabs(slot_at(T, m->taylor_f[c], tau) - f[c]));
            err = fmax(err, fabs(slot_at(T, m->taylor_pos[c], tau) - pos[c]));
            err = fmax(err, fabs(slot_at(T, m->taylor_vel[c], tau) - vel[c]));
            for (int i = 0; i < n; i++)
                err = fmax(err, fabs(slot_at(T, m->taylor_B[c * n + i], tau) - B[c * n + i]));
        }
        if (!(err / scale <= worst)) /* NaN included */
            worst = err / scale, *worst_scale = scale;
    }
    free(T);
    return worst;
}

/* A state near the model's own initial one (made up: each value moved by
 * up to 5 %, plus a little where it is 0), p and u as check_model's. */
static void
near_start(const eomc_model *m, double t0, double *p, double *u, double *q, double *v)
{
    params_inputs(m, t0, p, u);
    m->initial(p, q, v);
    for (int i = 0; i < m->nq; i++) {
        q[i] = q[i] * (1 + check_rand(-0.05, 0.05)) + check_rand(-0.01, 0.01);
        v[i] = v[i] * (1 + check_rand(-0.05, 0.05)) + check_rand(-0.01, 0.01);
    }
}

/* The test's own solve for taylor_run (eomc_model.h's eomc_tay_solve):
 * M_0 kept at k = 0, then b := -M_0^-1 b by check_solve's Gaussian
 * elimination, on a copy. */
typedef struct TestSolve {
    int n;
    double M0[NMAX * NMAX];
} TestSolve;

static int
test_solve(void *ctx, int k, const double *M0, double *b)
{
    TestSolve *ts = ctx;
    int n = ts->n;
    if (k == 0)
        memcpy(ts->M0, M0, (size_t)n * n * sizeof *M0);
    double A[NMAX * NMAX], x[NMAX];
    memcpy(A, ts->M0, (size_t)n * n * sizeof *A);
    memcpy(x, b, (size_t)n * sizeof *x);
    if (check_solve(A, x, n) != 0)
        return -1;
    for (int i = 0; i < n; i++)
        b[i] = -x[i];
    return 0;
}

/* Whether m's M is constant and diagonal (eomc_model.h's taylor_mass):
 * then the generator solves it itself; else taylor_run calls the solve. */
static int
mass_diagonal(const eomc_model *m)
{
    return m->taylor_mass == (EOMC_TAYLOR_M_CONSTANT | EOMC_TAYLOR_M_DIAGONAL);
}

/* taylor_run, where the model has one (no constraints), against two
 * things at a state near its start:
 *  - the loop over taylor with the runtime's arithmetic (taylor.c's
 *    where M is constant and diagonal: v_{k+1} = -((h_k / M_jj) / (k + 1))
 *    and q_{k+1} = -((h_{k-1} / M_jj) / (k (k + 1))) for k > 0; else
 *    a_k = -M_0^-1 (h_k + sum_{i=1..k} M_i a_{k-i}), the sum from 0
 *    entry by entry, by the same solve, test_solve, then / (k + 1)): the
 *    same series to the bit, as eomc_model.h says (the rows the same
 *    either way);
 *  - the motion's equations, independently of any recurrence: the
 *    polynomials it leaves for q and v, at small tau, with their own
 *    derivatives, satisfy q' = v and M v' + h(t, q, v) = 0 by mass_bias,
 *    to the truncation of a series of degree K (far below rounding at
 *    |tau| a twentieth of the series' radius) and rounding.
 * The largest residual relative to the scale of h, M v' and M q / rho^2
 * (rho the series' radius, the motion's time); the number
 * of coefficients that differ from the loop's into *differ; -1 where
 * taylor_run left the order to the loop (returned 1). */
static double
check_run(const eomc_model *m, double t0, int order, int *differ)
{
    int n = m->nq, ne = m->nevent + m->nmode, S = order + 1;
    int diagonal = mass_diagonal(m);
    double p[PMAX], u[UMAX + 1] = {0}, q0[NMAX], v0[NMAX];
    near_start(m, t0, p, u, q0, v0);
    double *T1 = calloc((size_t)m->taylor_nslot * S + 1, sizeof *T1);
    double *T2 = calloc((size_t)m->taylor_nslot * S + 1, sizeof *T2);
    double *X = calloc((size_t)S * 2 * n + 1, sizeof *X); /* X[j 2n + i] (q, then v) */
    double *A = calloc((size_t)S * n + 1, sizeof *A);     /* a_i's at A[i S + k] */
    for (int i = 0; i < n; i++) {
        X[i] = T2[m->taylor_q[i] * S] = q0[i];
        X[n + i] = T2[m->taylor_v[i] * S] = v0[i];
    }
    TestSolve run = {.n = n}, loop = {.n = n};
    int rc = m->taylor_run(order, t0, p, u, T1, X, test_solve, &run);
    if (rc != 0) {
        *differ = rc < 0;
        free(T1), free(T2), free(X), free(A);
        return rc < 0 ? INFINITY : -1;
    }
    for (int k = 0; k < order; k++) {
        m->taylor(k, order, t0, p, u, T2);
        double b[NMAX], M0[NMAX * NMAX];
        for (int i = 0; i < n; i++) {
            int h = m->taylor_h[i];
            if (diagonal) {
                b[i] = -((h < 0 ? 0 : T2[h * S + k]) / T2[m->taylor_M[i * n + i] * S]);
                continue;
            }
            double sum = 0;
            for (int l = 0; l < n; l++) {
                int e = m->taylor_M[i * n + l];
                for (int j = 1; j <= k && e >= 0; j++)
                    sum += T2[e * S + j] * A[l * S + k - j];
            }
            b[i] = (h < 0 ? 0 : T2[h * S + k]) + sum;
        }
        for (int e = 0; e < n * n && k == 0; e++)
            M0[e] = m->taylor_M[e] < 0 ? 0 : T2[m->taylor_M[e] * S];
        if (!diagonal && test_solve(&loop, k, M0, b) != 0)
            b[0] = NAN;
        for (int i = 0; i < n; i++) {
            int h = m->taylor_h[i];
            double *q = T2 + m->taylor_q[i] * S, *v = T2 + m->taylor_v[i] * S;
            A[i * S + k] = b[i];
            if (diagonal) { /* both from h's series over M_jj */
                double Mii = T2[m->taylor_M[i * n + i] * S];
                double hk = h < 0 ? 0 : T2[h * S + k], hk1 = h < 0 || !k ? 0 : T2[h * S + k - 1];
                q[k + 1] = k == 0 ? v[0] : -(hk1 / Mii / (k * (k + 1)));
                v[k + 1] = -(hk / Mii / (k + 1));
                continue;
            }
            q[k + 1] = v[k] / (k + 1);
            v[k + 1] = b[i] / (k + 1);
        }
    }
    *differ = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= order; j++)
            *differ += X[j * 2 * n + i] != T2[m->taylor_q[i] * S + j] ||
                       X[j * 2 * n + n + i] != T2[m->taylor_v[i] * S + j];
    for (int i = 0; i < n && diagonal; i++) /* (else the solve tested M_0) */
        *differ += T1[m->taylor_M[i * n + i] * S] != T2[m->taylor_M[i * n + i] * S];
    for (int e = 0; e < ne; e++)
        for (int j = 0; j < order && m->taylor_g[e] >= 0; j++)
            *differ += T1[m->taylor_g[e] * S + j] != T2[m->taylor_g[e] * S + j];
    /* the taus a thirtieth of the series' own radius (its least ratio
     * (|x_1| / |x_K|)^(1/(order - 1)) over q and v): Arenstorf's orbit starts
     * 0.006 from the Moon, Kepler's half a unit from the Sun */
    double rho = INFINITY;
    for (int i = 0; i < 2 * n; i++) {
        double c1 = X[2 * n + i], cK = X[order * 2 * n + i];
        if (c1 != 0 && cK != 0)
            rho = fmin(rho, pow(fabs(c1 / cK), 1.0 / (order - 1)));
    }
    if (!(rho < INFINITY))
        rho = 1; /* a polynomial motion: any tau */
    const double taus[] = {rho / 30, -rho / 21, 0};
    double worst = 0;
    for (size_t t = 0; t < sizeof taus / sizeof taus[0]; t++) {
        double tau = taus[t], q[NMAX], v[NMAX], dq[NMAX], dv[NMAX], M[NMAX * NMAX], h[NMAX];
        for (int i = 0; i < n; i++) {
            q[i] = v[i] = dq[i] = dv[i] = 0;
            for (int j = order; j >= 0; j--) { /* the values and derivatives, by Horner */
                const double *c = X + j * 2 * n;
                q[i] = q[i] * tau + c[i];
                v[i] = v[i] * tau + c[n + i];
                if (j >= 1) {
                    dq[i] = dq[i] * tau + j * c[i];
                    dv[i] = dv[i] * tau + j * c[n + i];
                }
            }
        }
        m->mass_bias(t0 + tau, q, v, p, u, M, h);
        double scale = 0, err = 0;
        for (int i = 0; i < n; i++) {
            double Mdv = 0;
            for (int l = 0; l < n; l++)
                Mdv += M[i * n + l] * dv[l];
            /* near an equilibrium h is small where its terms are not (the
             * hoop's gravity against its turn): the scale is also the
             * motion's own, M times q or v over the series' time rho */
            scale = fmax(scale, fmax(fabs(Mdv), fabs(h[i])));
            scale = fmax(scale, fabs(M[i * n + i]) * fmax(fabs(q[i]) / (rho * rho),
                                                         fabs(v[i]) / rho));
            err = fmax(err, fabs(Mdv + h[i]));
            err = fmax(err, fabs(dq[i] - v[i]) * fabs(M[i * n + i]) / rho); /* as a force */
        }
        if (!(err / fmax(scale, DBL_MIN) <= worst))
            worst = err / fmax(scale, DBL_MIN);
    }
    free(T1);
    free(T2);
    free(X);
    free(A);
    return worst;
}

/* taylor_run4, where the model has one, against taylor_run lane by lane:
 * EOMC_LANES made-up states (each its own parameters, inputs and t0) to
 * order `order`, side by side, and each alone; eomc_model.h says each
 * lane's bits are its run's, in X and in what T leaves the caller (the
 * event functions' series, M's diagonal).  The values that differ, or -1
 * where taylor_run4 left the order to one run at a time (returned 1). */
static int
check_run4(const eomc_model *m, int order)
{
    enum { L = EOMC_LANES };
    int n = m->nq, N = 2 * n, S = order + 1, ng = m->nevent + m->nmode;
    int np = m->np + m->nd, nu = m->nu + m->nmode, nslot = m->taylor_nslot;
    size_t nT = (size_t)nslot * S + 1, nX = (size_t)S * N + 1;
    double p[L][PMAX], u[L][UMAX + 1], t0[L], q0[NMAX], v0[NMAX];
    double *T = calloc(nT * L, sizeof *T), *X = calloc(nX * L, sizeof *X);
    double *T4 = aligned_alloc(64, (nT * L * sizeof *T + 63) / 64 * 64);
    double *X4 = aligned_alloc(64, (nX * L * sizeof *X + 63) / 64 * 64);
    double *p4 = aligned_alloc(64, ((size_t)(np + 1) * L * sizeof *p4 + 63) / 64 * 64);
    double *u4 = aligned_alloc(64, ((size_t)(nu + 1) * L * sizeof *u4 + 63) / 64 * 64);
    double *t4 = aligned_alloc(64, 64);
    memset(T4, 0, nT * L * sizeof *T4);
    for (int l = 0; l < L; l++) {
        t0[l] = t4[l] = 0.2 + 0.9 * l;
        memset(u[l], 0, sizeof u[l]);
        near_start(m, t0[l], p[l], u[l], q0, v0);
        for (int i = 0; i < n; i++) {
            X[l * nX + i] = X4[i * L + l] = q0[i];
            X[l * nX + n + i] = X4[(n + i) * L + l] = v0[i];
        }
        for (int i = 0; i < np; i++)
            p4[i * L + l] = p[l][i];
        for (int i = 0; i < nu; i++)
            u4[i * L + l] = u[l][i];
    }
    int differ = 0, rc = m->taylor_run4(order, t4, p4, u4, T4, X4);
    for (int l = 0; l < L && rc == 0; l++) {
        double *Tl = T + l * nT, *Xl = X + l * nX;
        TestSolve ts = {.n = n}; /* (M being diagonal, not called) */
        m->taylor_run(order, t0[l], p[l], u[l], Tl, Xl, test_solve, &ts);
        for (int i = 0; i < S * N; i++) /* (the same bits: == alone would pass -0 for 0) */
            differ += memcmp(&Xl[i], &X4[i * L + l], sizeof *Xl) != 0;
        for (int e = 0; e < ng; e++)
            for (int j = 0, g = m->taylor_g[e]; g >= 0 && j < order; j++)
                differ += memcmp(&Tl[g * S + j], &T4[(g * S + j) * L + l], sizeof *Tl) != 0;
        for (int i = 0; i < n; i++) {
            int d = m->taylor_M[i * n + i];
            differ += memcmp(&Tl[d * S], &T4[d * S * L + l], sizeof *Tl) != 0;
        }
    }
    free(T), free(X), free(T4), free(X4), free(p4), free(u4), free(t4);
    return rc == 0 ? differ : -1;
}

int
main(void)
{
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        const eomc_model *m = models[k];
        CHECK(m->taylor && !m->taylor_why && m->nq <= NMAX && m->nevent <= EMAX &&
                  m->nc <= CMAX && m->nu <= UMAX && m->np + m->nd <= PMAX,
              "%s: a taylor member", m->name);
        if (!m->taylor)
            continue;
        int ok = 1; /* every slot the tables name is one */
        for (int i = 0; i < m->nq * m->nq; i++)
            ok &= m->taylor_M[i] < m->taylor_nslot;
        for (int i = 0; i < m->nq; i++)
            ok &= m->taylor_h[i] < m->taylor_nslot && m->taylor_q[i] < m->taylor_nslot &&
                  m->taylor_v[i] < m->taylor_nslot;
        for (int e = 0; e < m->nevent; e++)
            ok &= m->taylor_g[e] < m->taylor_nslot;
        ok &= m->nc == 0 || (m->taylor_B && m->taylor_f && m->taylor_pos && m->taylor_vel);
        for (int c = 0; ok && c < m->nc; c++) {
            ok &= m->taylor_f[c] < m->taylor_nslot && m->taylor_pos[c] < m->taylor_nslot &&
                  m->taylor_vel[c] < m->taylor_nslot;
            for (int i = 0; i < m->nq; i++)
                ok &= m->taylor_B[c * m->nq + i] < m->taylor_nslot;
        }
        CHECK(ok && (m->nevent == 0 || m->taylor_g), "%s: its %d slots", m->name,
              m->taylor_nslot);
        if (!ok)
            continue;
        /* the N-body models are here for taylor_run (below): made-up
         * positions within 0.6 of each other come close enough for their
         * series' radius to be below these taus */
        if (m == &pleiades_model || m == &outer_solar_system_model)
            continue;
        double worst = 0;
        mass_claims_broken = have_M_first = 0;
        for (int r = 0; r < 3; r++) { /* three made-up curves, at t0 = 0.3, 1.7, 4.1 */
            double scale, err = check_model(m, 0.3 + 1.4 * r + 0.1 * r * r, &scale);
            if (!(err <= worst))
                worst = err;
        }
        printf("# %s: largest error %.2e of the values' scale\n", m->name, worst);
        static const char *const claim[] = {"claimed neither constant nor diagonal",
                                            "constant", "diagonal", "constant and diagonal"};
        int said = m->taylor_mass & (EOMC_TAYLOR_M_CONSTANT | EOMC_TAYLOR_M_DIAGONAL);
        CHECK(mass_claims_broken == 0, "%s: M is what taylor_mass claims (%s) at 12 states "
              "(%d entries not)", m->name, claim[said], mass_claims_broken);
        CHECK(worst <= TOL, "%s: the series of M, h%s sum to mass_bias%s "
              "at |tau| <= 2e-2 (%.2e)", m->name, m->nc ? ", g, B, b, pos and vel" : " and g",
              m->nc ? ", events, constraint and c_levels" : " and events", worst);
    }
    int nrun = 0, nrun_general = 0;
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        const eomc_model *m = models[k];
        /* (with speeds of their own, q' = W(q) v: the rows' closed forms
         * check those, tests/cli/test_taylor_speeds.sh) */
        if (!m->taylor_run || m->taylor_qd)
            continue;
        nrun++;
        double worst = 0;
        int differ = 0, left = 0, general = !mass_diagonal(m);
        for (int r = 0; r < 9; r++) { /* at orders K and 20 written out, at K_LOOP looped */
            int d;
            double err = check_run(m, 0.2 + 1.3 * (r % 3), r < 3 ? K : r < 6 ? 20 : K_LOOP, &d);
            if (err < 0) { /* left to the runtime's loop */
                left++;
                continue;
            }
            if (!(err <= worst))
                worst = err;
            differ += d;
        }
        nrun_general += general;
        printf("# %s: taylor_run's motion, largest residual %.2e\n", m->name, worst);
        CHECK(differ == 0 && left == (general ? 3 : 0),
              "%s: taylor_run's series are the runtime loop's to the bit at 3 states, to "
              "orders %d, 20 and %d (%d coefficients not; %d runs left to the loop, %s)", m->name,
              K, K_LOOP, differ, left,
              general ? "M not constant and diagonal: those at order 24" : "none");
        CHECK(worst <= TOL, "%s: taylor_run's q(tau) and v(tau) satisfy q' = v and M v' + h "
              "= 0 by mass_bias at |tau| <= rho / 21 (%.2e)", m->name, worst);
    }
    int nrun4 = 0;
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        const eomc_model *m = models[k];
        if (!m->taylor_run4)
            continue;
        nrun4++;
        int d = check_run4(m, K), d20 = check_run4(m, 20), left = check_run4(m, K_LOOP);
        CHECK(d == 0 && d20 == 0 && left == -1,
              "%s: taylor_run4's %d lanes are taylor_run's to the bit at orders %d and 20 (%d "
              "and %d values not), and order %d is left to one run at a time", m->name,
              EOMC_LANES, K, d, d20, K_LOOP);
    }
#ifndef SERIES_LINE_BY_LINE
    /* where M is constant and diagonal, the series short, and the compiler
     * has vectors: not chain5 (M(q)), nor the Pleiades (a series in parts) */
#ifdef __GNUC__
    int want4 = 1;
#else
    int want4 = 0;
#endif
    CHECK(nrun4 >= 5 * want4 && !!kepler_model.taylor_run4 == want4 &&
              !!bouncing_ball_model.taylor_run4 == want4 && !chain5_model.taylor_run4 &&
              !cartesian_pendulum_model.taylor_run4,
          "taylor_run4: %d models, kepler's and bouncing_ball's among them, not chain5's (M(q)) "
          "or cartesian_pendulum's (a constraint)", nrun4);
    /* the models without constraints have it (written out where M is not
     * constant and diagonal); the others do not */
    CHECK(nrun >= 5 && nrun_general >= 2 && kepler_model.taylor_run &&
              arenstorf_model.taylor_run && chain5_model.taylor_run &&
              !cartesian_pendulum_model.taylor_run,
          "taylor_run: %d models (%d with M not constant and diagonal), kepler's, arenstorf's "
          "and chain5's (M(q)) among them, not cartesian_pendulum's (a constraint)", nrun,
          nrun_general);
    CHECK(cubic_model.taylor_a && !chain5_model.taylor_a && !cartesian_pendulum_model.taylor_a,
          "taylor_a: cubic's constraint is nonlinear in q'', the others' are not");
#else
    CHECK(nrun == 5, "taylor_run: the %d models with packs", nrun);
    (void)nrun_general, (void)nrun4;
#endif
    return check_done();
}
