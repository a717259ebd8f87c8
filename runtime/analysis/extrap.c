/*
 * extrap: extrapolation steps in extended precision (extrap.h).
 *
 * Gragg-Bulirsch-Stoer.  A step of size H from (t, X) runs the explicit
 * midpoint rule with n_j substeps, j = 1 .. L,
 *     z_0 = X,  z_1 = z_0 + h f(t, z_0),
 *     z_(m+1) = z_(m-1) + 2h f(t + m h, z_m),   h = H / n_j,
 * whose end value T_j1 = z_(n_j) has an error expansion in even powers of
 * h (Gragg), and extrapolates to h = 0 by Aitken and Neville:
 *     T_j,k+1 = T_jk + (T_jk - T_(j-1)k) / ((n_j / n_(j-k))^2 - 1).
 * T_LL is of order 2L; |T_LL - T_L,L-1| estimates the error of the lower
 * order value, so the value kept is better than the control asks.
 *
 * The linearly implicit Euler method.  With J = df/dx at the step's
 * start, each level solves
 *     (I - h J) (y_(m+1) - y_m) = h f(t + m h, y_m),   m = 0 .. n_j - 1,
 * from y_0 = X, and extrapolates T_j1 = y_(n_j) in powers of h:
 *     T_j,k+1 = T_jk + (T_jk - T_(j-1)k) / (n_j / n_(j-k) - 1).
 * It is a one-step method with an increment smooth in h for any matrix
 * in J's place (a W-method), so the expansion, and the order L of T_LL,
 * hold whatever J's accuracy: J decides only the stability, and finite
 * differences in long double (relative error near sqrt(eps) = 3e-10) are
 * plenty.  For the same reason f's dependence on t is left out of the
 * matrix.  Its base method is L-stable and the extrapolated values are
 * A(alpha)-stable with alpha near 90 degrees (Hairer and Wanner, IV.9):
 * a mode far faster than the motion is damped, not followed.
 *
 * The step sequences.  Rounding errors of the T_j1 grow in the
 * extrapolation by the sum of its weights' absolute values (its Lebesgue
 * constant): Bulirsch's 2, 4, 6, 8, 12, 16, 24, 32 in h^2 sums to 9.1
 * (the harmonic 2, 4, 6, ... of the same order to 119); in h, 1, 2, 3, 4,
 * 6, 8, 12, 16 sums to 135 (1, 2, ..., 8 to 3392), which costs 135 units
 * of long double's rounding, 1.5e-17: below a double's.  Every running
 * sum is compensated (Kahan), so that the n_j additions of a level cost
 * no more than rounding once.
 *
 * Stiffness.  T_LL of GBS is stable on the negative real axis up to
 * H lambda = -8.6, and along the circle |H lambda| = 4 its error estimate
 * on y' = lambda y is 4e-7 of y (1.2e-11 at |H lambda| = 2; computed from
 * its stability polynomial).  A step the reference accepts at a tolerance
 * of 1e-15 or less with H rho >= 4 (EXTRAP_GBS_STIFF) therefore carries
 * its fastest mode at 1e-8 of the state or less: the step follows the
 * motion, not that mode, and is held near the stability bound only to
 * keep the mode from growing.  That is what stiffness is.
 *
 * The spectral radius.  Power iteration with products J w taken as
 * difference quotients (f(X + eta D w) - f(X)) / eta, D the components'
 * scales (D^-1 J D has J's eigenvalues, so the units do not matter), two
 * per call: rho = sqrt(|J^2 w| / |w|), which for a complex pair a +- ib
 * with a small (a lightly damped vibration, whose J^2 is -(a^2 + b^2) on
 * its plane) is its modulus from any w in that plane, where the one-step
 * quotient swings with the eigenvectors' skew.
 */
#include "extrap.h"
#include "model/linalg.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { LEVELS_MAX = EXTRAP_GBS_LEVELS > EXTRAP_LI_LEVELS ? EXTRAP_GBS_LEVELS
                                                         : EXTRAP_LI_LEVELS };

static const int gbs_seq[EXTRAP_GBS_LEVELS] = {2, 4, 6, 8, 12, 16, 24, 32};
static const int li_seq[EXTRAP_LI_LEVELS] = {1, 2, 3, 4, 6, 8, 12, 16};

struct Extrap {
    int N;
    ExtrapRhs f;
    void *ctx;
    eomc_ext *z0, *z1, *g, *c0, *c1; /* [N] running values, f, compensations */
    eomc_ext *T;                     /* [LEVELS_MAX N] the tableau's last row */
    eomc_ext *J, *W, *eq;            /* [N N] df/dx, I - h J factored, [2N] its scaling */
    int *perm;                       /* [N] */
    eomc_ext *w, *y;                 /* [N] the power iteration's direction, a state */
};

Extrap *
extrap_alloc(int N, ExtrapRhs f, void *ctx)
{
    size_t n = (size_t)(N > 0 ? N : 1);
    Extrap *e = calloc(1, sizeof *e);
    if (!e)
        return NULL;
    *e = (Extrap){.N = N, .f = f, .ctx = ctx};
    eomc_ext **arrays[] = {&e->z0, &e->z1, &e->g, &e->c0, &e->c1, &e->T,
                           &e->J,  &e->W,  &e->eq, &e->w, &e->y};
    size_t sizes[] = {n, n, n, n, n, LEVELS_MAX * n, n * n, n * n, 2 * n, n, n};
    int ok = 1;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        ok &= (*arrays[k] = calloc(sizes[k], sizeof(eomc_ext))) != NULL;
    ok &= (e->perm = calloc(n, sizeof *e->perm)) != NULL;
    if (!ok) {
        extrap_free(e);
        return NULL;
    }
    for (int i = 0; i < N; i++)
        e->w[i] = 1;
    return e;
}

void
extrap_free(Extrap *e)
{
    if (!e)
        return;
    eomc_ext *arrays[] = {e->z0, e->z1, e->g, e->c0, e->c1, e->T,
                          e->J,  e->W,  e->eq, e->w, e->y};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    free(e->perm);
    free(e);
}

int
extrap_error_order(int method)
{
    return method == EXTRAP_GBS ? 2 * EXTRAP_GBS_LEVELS - 1 : EXTRAP_LI_LEVELS;
}

/* s := s + y, with c the low part lost so far (the sum is s - c). */
static inline void
kahan_add(eomc_ext *s, eomc_ext *c, eomc_ext y)
{
    eomc_ext x = y - *c, t = *s + x;
    *c = (t - *s) - x;
    *s = t;
}

/* Row j of the tableau from its first value c (compensated: the value
 * with its lost low part), den[k] the divisor of column k + 1; the row
 * before is in e->T and becomes this one. */
static void
tableau_row(Extrap *e, int j, int i, eomc_ext c, const eomc_ext *den)
{
    int N = e->N;
    for (int k = 0; k < j; k++) {
        eomc_ext *row = e->T + (size_t)k * N;
        eomc_ext next = c + (c - row[i]) / den[k];
        row[i] = c;
        c = next;
    }
    e->T[(size_t)j * N + i] = c;
}

static int
gbs_step(Extrap *e, eomc_ext t, eomc_ext H, const eomc_ext *X, const eomc_ext *F)
{
    int N = e->N;
    eomc_ext *z0 = e->z0, *z1 = e->z1, *c0 = e->c0, *c1 = e->c1;
    for (int j = 0; j < EXTRAP_GBS_LEVELS; j++) {
        int nj = gbs_seq[j];
        eomc_ext h = H / nj, den[LEVELS_MAX];
        for (int i = 0; i < N; i++) {
            z0[i] = X[i];
            z1[i] = X[i] + h * F[i];
            c0[i] = c1[i] = 0;
        }
        for (int m = 1; m < nj; m++) {
            if (e->f(e->ctx, t + m * h, z1, e->g) != 0)
                return -1;
            for (int i = 0; i < N; i++) /* z0 := z0 + 2h g, the next z1 */
                kahan_add(&z0[i], &c0[i], 2 * h * e->g[i]);
            eomc_ext *tz = z0, *tc = c0;
            z0 = z1, c0 = c1, z1 = tz, c1 = tc;
        }
        for (int k = 0; k < j; k++) { /* (n_j / n_(j-k-1))^2 - 1 */
            eomc_ext ratio = (eomc_ext)nj / gbs_seq[j - k - 1];
            den[k] = ratio * ratio - 1;
        }
        for (int i = 0; i < N; i++)
            tableau_row(e, j, i, z1[i] - c1[i], den);
    }
    return 0;
}

static int
li_step(Extrap *e, eomc_ext t, eomc_ext H, const eomc_ext *X, const eomc_ext *F)
{
    int N = e->N;
    eomc_ext *y = e->z0, *c = e->c0, *d = e->z1;
    for (int j = 0; j < EXTRAP_LI_LEVELS; j++) {
        int nj = li_seq[j];
        eomc_ext h = H / nj, den[LEVELS_MAX];
        for (int i = 0; i < N * N; i++)
            e->W[i] = -h * e->J[i];
        for (int i = 0; i < N; i++)
            e->W[i * N + i] += 1;
        if (la_ext_lu_factor(e->W, N, e->perm, e->eq, NULL) != 0)
            return -1;
        for (int i = 0; i < N; i++) {
            y[i] = X[i];
            c[i] = 0;
        }
        for (int m = 0; m < nj; m++) {
            const eomc_ext *g = m == 0 ? F : e->g;
            if (m > 0 && e->f(e->ctx, t + m * h, y, e->g) != 0)
                return -1;
            for (int i = 0; i < N; i++)
                d[i] = h * g[i];
            la_ext_lu_solve(e->W, N, e->perm, e->eq, d);
            for (int i = 0; i < N; i++)
                kahan_add(&y[i], &c[i], d[i]);
        }
        for (int k = 0; k < j; k++) /* n_j / n_(j-k-1) - 1 */
            den[k] = (eomc_ext)nj / li_seq[j - k - 1] - 1;
        for (int i = 0; i < N; i++)
            tableau_row(e, j, i, y[i] - c[i], den);
    }
    return 0;
}

int
extrap_step(Extrap *e, int method, eomc_ext t, eomc_ext H, const eomc_ext *X,
            const eomc_ext *F, eomc_ext *out, eomc_ext *est)
{
    int L = method == EXTRAP_GBS ? EXTRAP_GBS_LEVELS : EXTRAP_LI_LEVELS, N = e->N;
    int rc = method == EXTRAP_GBS ? gbs_step(e, t, H, X, F) : li_step(e, t, H, X, F);
    if (rc != 0)
        return -1;
    const eomc_ext *hi = e->T + (size_t)(L - 1) * N, *lo = e->T + (size_t)(L - 2) * N;
    for (int i = 0; i < N; i++)
        est[i] = hi[i] - lo[i];
    memcpy(out, hi, (size_t)N * sizeof *out);
    return 0;
}

/* Component j's scale for a difference quotient: its own, or where the
 * caller has none (a group of components all 0 so far) the largest of
 * any, or 1 for the zero state (where any increment serves: f is linear
 * there to first order whatever its size). */
static eomc_ext
increment_scale(const Extrap *e, const eomc_ext *scale, int j)
{
    if (scale[j] > 0)
        return scale[j];
    eomc_ext big = 0;
    for (int i = 0; i < e->N; i++)
        big = fmaxl(big, scale[i]);
    return big > 0 ? big : 1;
}

int
extrap_jacobian(Extrap *e, eomc_ext t, const eomc_ext *X, const eomc_ext *F,
                const eomc_ext *scale)
{
    int N = e->N;
    eomc_ext eta = sqrtl(LDBL_EPSILON);
    memcpy(e->y, X, (size_t)N * sizeof *e->y);
    for (int j = 0; j < N; j++) {
        eomc_ext s = fmaxl(fabsl(X[j]), increment_scale(e, scale, j));
        e->y[j] = X[j] + eta * s;
        eomc_ext dx = e->y[j] - X[j]; /* the increment as represented */
        if (e->f(e->ctx, t, e->y, e->g) != 0)
            return -1;
        for (int i = 0; i < N; i++)
            e->J[i * N + j] = (e->g[i] - F[i]) / dx;
        e->y[j] = X[j];
    }
    return 0;
}

/* |D^-1 J D w| for w (max |w_i| = 1), into Jw (scaled), by one
 * difference quotient; -1 when f fails. */
static int
scaled_product(Extrap *e, eomc_ext t, const eomc_ext *X, const eomc_ext *F,
               const eomc_ext *scale, const eomc_ext *w, eomc_ext *Jw, eomc_ext *size)
{
    int N = e->N;
    eomc_ext eta = sqrtl(LDBL_EPSILON);
    for (int i = 0; i < N; i++)
        e->y[i] = X[i] + eta * increment_scale(e, scale, i) * w[i];
    if (e->f(e->ctx, t, e->y, e->g) != 0)
        return -1;
    *size = 0;
    for (int i = 0; i < N; i++) {
        Jw[i] = (e->g[i] - F[i]) / (eta * increment_scale(e, scale, i));
        *size = fmaxl(*size, fabsl(Jw[i]));
    }
    return 0;
}

int
extrap_spectral_radius(Extrap *e, eomc_ext t, const eomc_ext *X, const eomc_ext *F,
                       const eomc_ext *scale, double *rho)
{
    int N = e->N;
    eomc_ext p[2], *v = e->z0;
    for (int it = 0; it < 2; it++) {
        if (scaled_product(e, t, X, F, scale, e->w, v, &p[it]) != 0)
            return -1;
        if (!(p[it] > 0) || !isfinite(p[it])) { /* w in J's null space: start afresh */
            for (int i = 0; i < N; i++)
                e->w[i] = 1;
            *rho = 0;
            return 0;
        }
        for (int i = 0; i < N; i++)
            e->w[i] = v[i] / p[it];
    }
    *rho = (double)sqrtl(p[0] * p[1]);
    return 0;
}
