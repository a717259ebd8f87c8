/*
 * The jacobian member (compiler/emit/emit.h) of every shipped spec, in both
 * ways eomc prints it: the unrolled matrices (generated/NAME.c, what these
 * small models get by default) and `eomc compile --jacobian seeded`, which
 * loops over unit seeds of the directional derivative of E.  Each is
 * checked at random states against finite differences of the residual
 * E = M a + h that the model's mass_bias computes (no derivative taken by
 * eomc): central differences at steps d and d/2, combined by Richardson's
 * extrapolation (error O(d^4) plus rounding of E's terms over d).  The
 * seeded files are compiled with the project's warnings (-Wall -Wextra
 * -Wpedantic -Werror) and NAME_model renamed to NAME_seeded_model.
 */
#include "../unit/check.h"
#include "eomc_model.h"

#include <float.h>
#include <string.h>

#define MODELS(X) X(falling_particle) X(pendulum) X(gear_link) \
                  X(double_pendulum) X(chain5)
#define DECLARE(name) extern const eomc_model name##_model, name##_seeded_model;
MODELS(DECLARE)
#define PAIR(name) {&name##_model, &name##_seeded_model},
static const eomc_model *const pairs[][2] = {MODELS(PAIR)};

enum { NMAX = 8, UMAX = 4, PMAX = 256 };

/* The step of the differences, relative to the variable's size, and the
 * agreement required, relative to the size of E_i's terms: rounding
 * contributes about DBL_EPSILON / STEP = 2e-13 of it, truncation
 * STEP^4 = 1e-12 of the fifth derivative; the models reach 7e-13. */
#define STEP 1e-3
#define TOL 1e-10

typedef struct State {
    double t, q[NMAX], v[NMAX], a[NMAX], u[UMAX + 1];
} State;

/* E = M a + h at x; *size gets max_i (|h_i| + sum_j |M_ij a_j|), the
 * magnitude of E's terms. */
static void
residual(const eomc_model *m, const double *p, const State *x, double *E, double *size)
{
    int n = m->nq;
    double M[NMAX * NMAX], h[NMAX];
    m->mass_bias(x->t, x->q, x->v, p, x->u, M, h);
    for (int i = 0; i < n; i++) {
        double s = fabs(h[i]);
        E[i] = h[i];
        for (int j = 0; j < n; j++) {
            E[i] += M[i * n + j] * x->a[j];
            s += fabs(M[i * n + j] * x->a[j]);
        }
        if (s > *size)
            *size = s;
    }
}

/* Variable j of x: q_j, then q'_j, u_j and t (j < 2 nq + nu + 1). */
static double *
variable(const eomc_model *m, State *x, int j)
{
    int n = m->nq;
    return j < n ? &x->q[j] : j < 2 * n ? &x->v[j - n] : j < 2 * n + m->nu ? &x->u[j - 2 * n]
                                                                           : &x->t;
}

/* dE/dz for variable j. */
static void
difference(const eomc_model *m, const double *p, const State *x, int j, double *dE,
           double *size)
{
    State y = *x;
    double *z = variable(m, &y, j), z0 = *z, d = STEP * fmax(1.0, fabs(z0));
    double D[2][NMAX];
    for (int r = 0; r < 2; r++, d /= 2) {
        double Ep[NMAX], Em[NMAX];
        *z = z0 + d;
        residual(m, p, &y, Ep, size);
        *z = z0 - d;
        residual(m, p, &y, Em, size);
        for (int i = 0; i < m->nq; i++)
            D[r][i] = (Ep[i] - Em[i]) / (2 * d);
    }
    for (int i = 0; i < m->nq; i++)
        dE[i] = (4 * D[1][i] - D[0][i]) / 3;
}

/* The largest |jacobian - differences| over the size of E's terms, at 20
 * random states. */
static double
worst_error(const eomc_model *m)
{
    int n = m->nq, nu = m->nu;
    double p[PMAX], worst = 0;
    if (m->np + m->nd > PMAX)
        return INFINITY;
    memcpy(p, m->p_default, (size_t)m->np * sizeof *p);
    if (m->derive)
        m->derive(p, p + m->np);
    for (int trial = 0; trial < 20; trial++) {
        State x;
        memset(&x, 0, sizeof x);
        x.t = check_rand(-1, 1);
        for (int i = 0; i < n; i++) {
            x.q[i] = check_rand(-1.5, 1.5);
            x.v[i] = check_rand(-1.5, 1.5);
            x.a[i] = check_rand(-1.5, 1.5);
        }
        for (int k = 0; k < nu; k++)
            x.u[k] = check_rand(-1, 1);
        /* dE/da is M itself: the other columns, [dE/dq dE/dq' dE/du dE/dt] */
        double J[4][NMAX * NMAX];
        m->jacobian(x.t, x.q, x.v, x.a, p, x.u, J[0], J[1], J[2], J[3]);
        for (int j = 0; j < 2 * n + nu + 1; j++) {
            const double *col = j < n ? J[0] + j : j < 2 * n ? J[1] + j - n
                                : j < 2 * n + nu ? J[2] + j - 2 * n : J[3];
            int stride = j < 2 * n ? n : j < 2 * n + nu ? nu : 1;
            double fd[NMAX], size = DBL_MIN;
            difference(m, p, &x, j, fd, &size);
            for (int i = 0; i < n; i++) {
                double e = fabs(col[i * stride] - fd[i]) / size;
                if (!(e <= worst)) /* NaN is the worst */
                    worst = isnan(e) ? INFINITY : e;
            }
        }
    }
    return worst;
}

int
main(void)
{
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++)
        for (int s = 0; s < 2; s++) {
            const eomc_model *m = pairs[k][s];
            double e = m->nq <= NMAX && m->nu <= UMAX && m->jacobian ? worst_error(m) : INFINITY;
            CHECK(e <= TOL, "%s, %s jacobian: dE/dq, dE/dq', dE/du, dE/dt against differences "
                  "of M a + h, largest error %.2g of E's terms", m->name,
                  s ? "seeded" : "unrolled", e);
        }
    return check_done();
}
