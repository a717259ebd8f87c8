/*
 * fixed: one step of a Runge-Kutta method, no error estimate (fixed.h).
 *
 * The implicit methods are collocation methods with Butcher tableau
 * (A, b, c) and s stages.  With stage increments Z_j = Y_j - y0 the
 * stage equations are
 *     Z = h (A (x) I) F(Z),   F_j = f(t + c_j h, y0 + Z_j),
 * solved by the simplified Newton iteration of Hairer and Wanner (IV.8):
 *     (I - h A (x) J) dZ = -Z + h (A (x) I) F(Z),   J = df/dy (t, y0).
 * With theta the ratio of two successive corrections (scaled by the
 * driver's error levels) and eta = theta / (1 - theta), the error left
 * after a correction dZ is about eta |dZ|.  The iteration must reach the
 * run's tolerance as GSL's modnewton1 does, eta |dZ| < 1 in the driver's
 * levels, within NEWTON_MAX iterations and without diverging (theta >= 1),
 * or the step fails.  Then it goes on to the rounding of the stage values:
 * a fixed step has no error estimate, so its error must be the method's
 * alone, h^order, however small h is (stopped at the tolerance, rk4imp at
 * h = 5e-4 was no better than at 5e-3, for 10 times the cost).  It stops
 * when eta |dZ_ji| is within a unit of rounding of the stage value
 * y_i + Z_ji for every component, or when the corrections stop shrinking
 * (they are rounding then), or after NEWTON_ROUNDING_MAX iterations.  The
 * new value is
 *     y1 = y0 + sum_j d_j Z_j,   d = b^T A^-1,
 * which is y0 + h sum_j b_j F_j without evaluating F at the converged Z.
 */
#include "fixed.h"
#include "model/linalg.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_machine.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NEWTON_MAX = 7, STAGES_MAX = 2 }; /* GSL's modnewton1: 7 iterations */
/* From the tolerance to rounding: a simplified Newton iteration whose
 * corrections shrink by theta <= 0.1 gains a digit or more each, and
 * fixed steps that need more are too long for their order anyway. */
enum { NEWTON_ROUNDING_MAX = NEWTON_MAX + 16 };

/* ---- the classical Runge-Kutta 4 ---- */

typedef struct Rk4 {
    double *k, *acc, *ytmp; /* [dim] each */
} Rk4;

static void *
rk4_alloc(size_t dim)
{
    Rk4 *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->k = calloc(dim, sizeof(double));
    r->acc = calloc(dim, sizeof(double));
    r->ytmp = calloc(dim, sizeof(double));
    if (!r->k || !r->acc || !r->ytmp) {
        free(r->k), free(r->acc), free(r->ytmp), free(r);
        return NULL;
    }
    return r;
}

static void
rk4_free(void *state)
{
    Rk4 *r = state;
    free(r->k), free(r->acc), free(r->ytmp), free(r);
}

static int
rk4_apply(void *state, size_t dim, double t, double h, double y[], double yerr[],
          const double dydt_in[], double dydt_out[], const gsl_odeiv2_system *sys)
{
    Rk4 *r = state;
    static const double c[] = {0.5, 0.5, 1.0}, w[] = {1.0, 2.0, 2.0, 1.0};
    int rc;
    if (dydt_in)
        memcpy(r->k, dydt_in, dim * sizeof *r->k);
    else if ((rc = GSL_ODEIV_FN_EVAL(sys, t, y, r->k)) != GSL_SUCCESS)
        return rc;
    for (size_t i = 0; i < dim; i++)
        r->acc[i] = w[0] * r->k[i];
    for (int s = 0; s < 3; s++) {
        for (size_t i = 0; i < dim; i++)
            r->ytmp[i] = y[i] + c[s] * h * r->k[i];
        if ((rc = GSL_ODEIV_FN_EVAL(sys, t + c[s] * h, r->ytmp, r->k)) != GSL_SUCCESS)
            return rc;
        for (size_t i = 0; i < dim; i++)
            r->acc[i] += w[s + 1] * r->k[i];
    }
    for (size_t i = 0; i < dim; i++) {
        y[i] += h / 6.0 * r->acc[i];
        yerr[i] = 0.0;
    }
    return dydt_out ? GSL_ODEIV_FN_EVAL(sys, t + h, y, dydt_out) : GSL_SUCCESS;
}

static int
no_driver(void *state, const gsl_odeiv2_driver *d)
{
    (void)state;
    (void)d;
    return GSL_SUCCESS;
}

static int
no_reset(void *state, size_t dim)
{
    (void)state;
    (void)dim;
    return GSL_SUCCESS;
}

static unsigned int
order4(void *state)
{
    (void)state;
    return 4;
}

static const gsl_odeiv2_step_type rk4_type = {
    "rk4", 1, 1, rk4_alloc, rk4_apply, no_driver, no_reset, order4, rk4_free,
};
const gsl_odeiv2_step_type *const fixed_rk4 = &rk4_type;

/* ---- implicit collocation ---- */

typedef struct Tableau {
    int s;                          /* stages */
    double A[STAGES_MAX][STAGES_MAX], c[STAGES_MAX];
    double d[STAGES_MAX];           /* b^T A^-1 */
    unsigned int order;
} Tableau;

/* sqrt(3) / 6 and the Gauss nodes 1/2 -+ sqrt(3)/6 (b = 1/2, 1/2, so
 * d = b^T A^-1 = (-sqrt 3, sqrt 3)). */
#define GAUSS2_R 0.28867513459481288225
#define SQRT3 1.73205080756887729353

static const Tableau euler = {1, {{1.0}}, {1.0}, {1.0}, 1};
static const Tableau midpoint = {1, {{0.5}}, {0.5}, {2.0}, 2};
static const Tableau gauss2 = {
    2, {{0.25, 0.25 - GAUSS2_R}, {0.25 + GAUSS2_R, 0.25}},
    {0.5 - GAUSS2_R, 0.5 + GAUSS2_R}, {-SQRT3, SQRT3}, 4,
};

typedef struct Imp {
    const Tableau *tab;
    const gsl_odeiv2_driver *driver; /* for the error levels */
    size_t dim;
    double *J, *dfdt;              /* [dim*dim], [dim] */
    double *W;                     /* [(s dim)^2] I - h A (x) J, factored */
    double *Z, *F, *dZ, *Y;        /* [s dim] each; Y [dim] */
    double *errlev;                /* [dim] */
    double eta_prev;               /* Newton's last contraction estimate */
    LaLu *lu;                      /* W's */
} Imp;

static void
imp_free(void *state)
{
    Imp *m = state;
    if (!m)
        return;
    free(m->J), free(m->dfdt), free(m->W), free(m->Z), free(m->F), free(m->dZ);
    free(m->Y), free(m->errlev);
    la_lu_free(m->lu);
    free(m);
}

static void *
imp_alloc(size_t dim, const Tableau *tab)
{
    Imp *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    size_t sd = (size_t)tab->s * dim;
    m->tab = tab;
    m->dim = dim;
    m->eta_prev = GSL_DBL_MAX;
    m->J = calloc(dim * dim, sizeof(double));
    m->dfdt = calloc(dim, sizeof(double));
    m->W = calloc(sd * sd, sizeof(double));
    m->Z = calloc(sd, sizeof(double));
    m->F = calloc(sd, sizeof(double));
    m->dZ = calloc(sd, sizeof(double));
    m->Y = calloc(dim, sizeof(double));
    m->errlev = calloc(dim, sizeof(double));
    m->lu = la_lu_alloc((int)sd);
    if (!m->J || !m->dfdt || !m->W || !m->Z || !m->F || !m->dZ || !m->Y || !m->errlev ||
        !m->lu) {
        imp_free(m);
        return NULL;
    }
    return m;
}

static void *imp_alloc_euler(size_t dim) { return imp_alloc(dim, &euler); }
static void *imp_alloc_midpoint(size_t dim) { return imp_alloc(dim, &midpoint); }
static void *imp_alloc_gauss2(size_t dim) { return imp_alloc(dim, &gauss2); }

static int
imp_set_driver(void *state, const gsl_odeiv2_driver *d)
{
    ((Imp *)state)->driver = d;
    return GSL_SUCCESS;
}

static int
imp_reset(void *state, size_t dim)
{
    (void)dim;
    ((Imp *)state)->eta_prev = GSL_DBL_MAX;
    return GSL_SUCCESS;
}

static unsigned int
imp_order(void *state)
{
    return ((Imp *)state)->tab->order;
}

/* W = I - h A (x) J, factored; -1 when singular. */
static int
iteration_matrix(Imp *m, double h)
{
    int s = m->tab->s, n = (int)m->dim, sd = s * n;
    for (int j = 0; j < s; j++)
        for (int k = 0; k < s; k++)
            for (int r = 0; r < n; r++)
                for (int c = 0; c < n; c++)
                    m->W[(j * n + r) * sd + k * n + c] =
                        (j * n + r == k * n + c) - h * m->tab->A[j][k] * m->J[r * n + c];
    return la_lu_factor(m->lu, m->W);
}

/* The largest |dZ_ji| relative to the stage value it corrects,
 * |y_i| + |Z_ji| (a component that is 0 and stays so counts 0). */
static double
rounding_norm(const Imp *m, const double *y)
{
    double worst = 0;
    for (int j = 0; j < m->tab->s; j++)
        for (size_t i = 0; i < m->dim; i++) {
            double d = fabs(m->dZ[j * m->dim + i]);
            if (d > 0)
                worst = fmax(worst, d / (fabs(y[i]) + fabs(m->Z[j * m->dim + i])));
        }
    return worst;
}

/* The scaled norm of dZ: sqrt(sum (dZ_ji / errlev_i)^2). */
static double
scaled_norm(const Imp *m)
{
    double sum = 0;
    for (int j = 0; j < m->tab->s; j++)
        for (size_t i = 0; i < m->dim; i++) {
            double x = m->dZ[j * m->dim + i] / m->errlev[i];
            sum += x * x;
        }
    return sqrt(sum);
}

static int
imp_apply(void *state, size_t dim, double t, double h, double y[], double yerr[],
          const double dydt_in[], double dydt_out[], const gsl_odeiv2_system *sys)
{
    Imp *m = state;
    const Tableau *tab = m->tab;
    int s = tab->s, rc;
    size_t sd = (size_t)s * dim;
    if (!m->driver)
        return GSL_EFAULT;
    for (size_t i = 0; i < dim; i++)
        gsl_odeiv2_control_errlevel(m->driver->c, y[i], dydt_in ? dydt_in[i] : 0.0, h, i,
                                    &m->errlev[i]);
    if ((rc = GSL_ODEIV_JA_EVAL(sys, t, y, m->J, m->dfdt)) != GSL_SUCCESS)
        return rc;
    if (iteration_matrix(m, h) != 0)
        return GSL_FAILURE;
    memset(m->Z, 0, sd * sizeof *m->Z);
    /* The first iteration's estimate is the last step's (none yet: no
     * convergence in one iteration). */
    double norm = 0, eta = pow(fmax(m->eta_prev, GSL_DBL_EPSILON), 0.8);
    int converged = 0; /* to the run's tolerance */
    for (int it = 0; it < NEWTON_ROUNDING_MAX; it++) {
        for (int j = 0; j < s; j++) {
            for (size_t i = 0; i < dim; i++)
                m->Y[i] = y[i] + m->Z[j * dim + i];
            if ((rc = GSL_ODEIV_FN_EVAL(sys, t + tab->c[j] * h, m->Y, m->F + j * dim)) !=
                GSL_SUCCESS)
                return rc;
        }
        for (int j = 0; j < s; j++)
            for (size_t i = 0; i < dim; i++) {
                double sum = 0;
                for (int k = 0; k < s; k++)
                    sum += tab->A[j][k] * m->F[k * dim + i];
                m->dZ[j * dim + i] = -m->Z[j * dim + i] + h * sum;
            }
        la_lu_solve(m->lu, m->dZ);
        for (size_t i = 0; i < sd; i++)
            m->Z[i] += m->dZ[i];
        double prev = norm;
        norm = scaled_norm(m);
        if (it > 0) {
            double theta = norm / prev;
            if (!(theta < 1.0)) {
                if (converged)
                    break; /* the corrections are rounding */
                return GSL_FAILURE; /* diverging */
            }
            eta = theta / (1.0 - theta);
        }
        m->eta_prev = eta;
        converged |= eta * norm < 1.0 || norm == 0.0;
        if (converged && (norm == 0.0 || eta * rounding_norm(m, y) <= GSL_DBL_EPSILON))
            break;
        if (!converged && it + 1 == NEWTON_MAX)
            return GSL_FAILURE;
    }
    for (size_t i = 0; i < dim; i++) {
        double z = 0;
        for (int j = 0; j < s; j++)
            z += tab->d[j] * m->Z[j * dim + i];
        y[i] += z;
        yerr[i] = 0.0;
    }
    return dydt_out ? GSL_ODEIV_FN_EVAL(sys, t + h, y, dydt_out) : GSL_SUCCESS;
}

static const gsl_odeiv2_step_type rk1imp_type = {
    "rk1imp", 1, 1, imp_alloc_euler, imp_apply, imp_set_driver, imp_reset, imp_order,
    imp_free,
};
static const gsl_odeiv2_step_type rk2imp_type = {
    "rk2imp", 1, 1, imp_alloc_midpoint, imp_apply, imp_set_driver, imp_reset, imp_order,
    imp_free,
};
static const gsl_odeiv2_step_type rk4imp_type = {
    "rk4imp", 1, 1, imp_alloc_gauss2, imp_apply, imp_set_driver, imp_reset, imp_order,
    imp_free,
};
const gsl_odeiv2_step_type *const fixed_rk1imp = &rk1imp_type;
const gsl_odeiv2_step_type *const fixed_rk2imp = &rk2imp_type;
const gsl_odeiv2_step_type *const fixed_rk4imp = &rk4imp_type;
