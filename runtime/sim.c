/*
 * sim: a model, its parameters and inputs, the accelerations, the exact
 * Jacobian of the first-order system, and integration with GSL odeiv2.
 *
 * Every work array is allocated in eomc_sim_alloc: the right-hand side and
 * the Jacobian run without allocating.  GSL's error handler is turned off
 * so that a failing factorization comes back as a status, never an abort.
 */
#include "simimpl.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *const eomc_methods[] = {
    "rk2", "rk4", "rkf45", "rkck", "rk8pd", "rk1imp", "rk2imp", "rk4imp",
    "bsimp", "msadams", "msbdf", NULL,
};

static const gsl_odeiv2_step_type *
step_type(const char *name)
{
    const gsl_odeiv2_step_type *types[] = {
        gsl_odeiv2_step_rk2,    gsl_odeiv2_step_rk4,    gsl_odeiv2_step_rkf45,
        gsl_odeiv2_step_rkck,   gsl_odeiv2_step_rk8pd,  gsl_odeiv2_step_rk1imp,
        gsl_odeiv2_step_rk2imp, gsl_odeiv2_step_rk4imp, gsl_odeiv2_step_bsimp,
        gsl_odeiv2_step_msadams, gsl_odeiv2_step_msbdf,
    };
    for (int k = 0; eomc_methods[k]; k++)
        if (name && strcmp(name, eomc_methods[k]) == 0)
            return types[k];
    return NULL;
}

double *
sim_zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

eomc_sim *
eomc_sim_alloc(const eomc_model *m)
{
    if (!m || m->abi != EOMC_ABI_VERSION || m->nq < 1)
        return NULL;
    gsl_set_error_handler_off();
    eomc_sim *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    size_t n = (size_t)m->nq, nu = (size_t)m->nu, np = (size_t)m->np;
    s->m = m;
    s->n = m->nq;
    s->nu = m->nu;
    s->p = sim_zeros(np);
    s->u = sim_zeros(nu);
    s->dudt = sim_zeros(nu);
    s->u_const = sim_zeros(nu);
    s->u_held = calloc(nu ? nu : 1, 1);
    s->M = sim_zeros(n * n);
    s->h = sim_zeros(n);
    s->a = sim_zeros(n);
    s->Mdiag = sim_zeros(n);
    s->dEdq = sim_zeros(n * n);
    s->dEdv = sim_zeros(n * n);
    s->dEdu = sim_zeros(n * nu);
    s->dEdt = sim_zeros(n);
    s->col = sim_zeros(n);
    /* Room for the cause and every coordinate and velocity by name. */
    s->errlen = 1024;
    for (int i = 0; i < m->nq; i++)
        s->errlen += 2 * (strlen(m->q_names[i]) + 32);
    for (int k = 0; k < m->nc; k++)
        s->errlen += strlen(m->c_names[k]) + strlen(m->q_names[m->c_dependent[k]]) + 8;
    s->err = calloc(s->errlen, 1);
    s->kkt = m->nc > 0 ? kkt_alloc(m) : NULL;
    s->proj = m->nc > 0 ? proj_alloc(m) : NULL;
    size_t nc = (size_t)m->nc;
    s->B0 = sim_zeros(nc * n), s->B1 = sim_zeros(nc * n), s->fk = sim_zeros(nc);
    s->x0 = sim_zeros(2 * n), s->xt = sim_zeros(2 * n), s->xerr = sim_zeros(2 * n);
    if (!s->p || !s->u || !s->dudt || !s->u_const || !s->u_held || !s->M || !s->h ||
        !s->a || !s->Mdiag || !s->dEdq || !s->dEdv || !s->dEdu || !s->dEdt ||
        !s->col || !s->err || (m->nc > 0 && (!s->kkt || !s->proj)) || !s->B0 || !s->B1 ||
        !s->fk || !s->x0 || !s->xt || !s->xerr) {
        eomc_sim_free(s);
        return NULL;
    }
    memcpy(s->p, m->p_default, np * sizeof(double));
    return s;
}

void
eomc_sim_free(eomc_sim *s)
{
    if (!s)
        return;
    void *arrays[] = {s->p, s->u, s->dudt, s->u_const, s->u_held, s->M, s->h,
                      s->a, s->Mdiag, s->dEdq, s->dEdv, s->dEdu, s->dEdt, s->col,
                      s->err, s->B0, s->B1, s->fk, s->x0, s->xt, s->xerr};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    kkt_free(s->kkt);
    proj_free(s->proj);
    free(s);
}

const eomc_model *
eomc_sim_model(const eomc_sim *s)
{
    return s->m;
}

const char *
eomc_sim_error(const eomc_sim *s)
{
    return s->err;
}

static int
usage_error(eomc_sim *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->err, s->errlen, fmt, ap);
    va_end(ap);
    return EOMC_EUSAGE;
}

/* "t = T: CAUSE; state: q1 = .., q2 = .., q1' = .., q2' = .." */
int
sim_numeric_error(eomc_sim *s, double t, const double *q, const double *v,
                  const char *fmt, ...)
{
    size_t len = 0, cap = s->errlen;
    len += (size_t)snprintf(s->err, cap, "t = %.17g: ", t);
    va_list ap;
    va_start(ap, fmt);
    if (len < cap)
        len += (size_t)vsnprintf(s->err + len, cap - len, fmt, ap);
    va_end(ap);
    if (q && v)
        for (int k = 0; k < 2 * s->n && len < cap; k++) {
            int i = k % s->n;
            len += (size_t)snprintf(s->err + len, cap - len, "%s%s%s = %.17g",
                                    k ? ", " : "; state: ", s->m->q_names[i],
                                    k < s->n ? "" : "'", k < s->n ? q[i] : v[i]);
        }
    return EOMC_ENUMERIC;
}

int
eomc_sim_set(eomc_sim *s, const char *name, double value)
{
    const eomc_model *m = s->m;
    for (int k = 0; k < m->np; k++)
        if (strcmp(name, m->p_names[k]) == 0) {
            s->p[k] = value;
            return EOMC_OK;
        }
    for (int k = 0; k < m->nu; k++)
        if (strcmp(name, m->u_names[k]) == 0) {
            s->u_const[k] = value;
            s->u_held[k] = 1;
            return EOMC_OK;
        }
    return usage_error(s, "'%s' is neither a parameter nor an input of %s", name,
                       m->name);
}

const double *
eomc_sim_params(const eomc_sim *s)
{
    return s->p;
}

/* u and du/dt at t into s->u, s->dudt, held inputs as constants. */
void
sim_inputs_at(eomc_sim *s, double t)
{
    if (s->nu == 0)
        return;
    s->m->inputs(t, s->p, s->u, s->dudt);
    for (int k = 0; k < s->nu; k++)
        if (s->u_held[k]) {
            s->u[k] = s->u_const[k];
            s->dudt[k] = 0;
        }
}

void
eomc_sim_inputs(eomc_sim *s, double t, double *u)
{
    sim_inputs_at(s, t);
    if (s->nu)
        memcpy(u, s->u, (size_t)s->nu * sizeof *u);
}

void
eomc_sim_initial(const eomc_sim *s, double *q, double *v)
{
    s->m->initial(s->p, q, v);
}

static int
all_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* 0.0 when every x[i] is finite, NaN otherwise: x - x is 0 for a finite
 * x and NaN for an infinity or a NaN.  Branch-free, so the common case
 * costs a few subtractions (the checks are on every right-hand side). */
static double
nonfinite_sum(const double *x, int n)
{
    double z = 0.0;
    for (int i = 0; i < n; i++)
        z += x[i] - x[i];
    return z;
}

/* M = L D L^T in place (GSL), with the generated solve's pivot test: a
 * pivot d_k <= EOMC_PIVOT_TOL * M_kk means M is singular or not positive
 * definite.  Returns 0 or the failing pivot k + 1. */
static int
factor_mass(eomc_sim *s)
{
    int n = s->n;
    for (int i = 0; i < n; i++)
        s->Mdiag[i] = s->M[i * n + i];
    gsl_matrix_view M = gsl_matrix_view_array(s->M, (size_t)n, (size_t)n);
    int rc = gsl_linalg_ldlt_decomp(&M.matrix);
    for (int i = 0; i < n; i++)
        if (!(s->M[i * n + i] > EOMC_PIVOT_TOL * s->Mdiag[i]))
            return i + 1;
    return rc == GSL_SUCCESS ? 0 : 1;
}

/* Overwrite b [n] with -M^-1 b, M factored. */
static void
solve_neg(eomc_sim *s, double *b)
{
    gsl_matrix_view L = gsl_matrix_view_array(s->M, (size_t)s->n, (size_t)s->n);
    gsl_vector_view x = gsl_vector_view_array(b, (size_t)s->n);
    gsl_linalg_ldlt_svx(&L.matrix, &x.vector);
    for (int i = 0; i < s->n; i++)
        b[i] = -b[i];
}

static int
pivot_error(eomc_sim *s, double t, const double *q, const double *v, int k)
{
    return sim_numeric_error(s, t, q, v,
                         "mass matrix is singular or not positive definite "
                         "(pivot %d, coordinate %s)", k, s->m->q_names[k - 1]);
}

int
eomc_sim_accel(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    const eomc_model *m = s->m;
    int n = s->n, k;
    sim_inputs_at(s, t);
    double z = (t - t) + nonfinite_sum(q, n) + nonfinite_sum(v, n) +
               nonfinite_sum(s->u, s->nu);
    if (z != 0.0)
        return sim_numeric_error(s, t, q, v, "the state or an input is not finite");
    if (s->kkt) {
        if ((k = kkt_accel(s, t, q, v, a)) != EOMC_OK)
            return k;
    } else if (m->accel) {
        k = m->accel(t, q, v, s->p, s->u, a);
    } else {
        m->mass_bias(t, q, v, s->p, s->u, s->M, a);
        k = factor_mass(s);
        if (!k)
            solve_neg(s, a);
    }
    if (k)
        return pivot_error(s, t, q, v, k);
    if (nonfinite_sum(a, n) != 0.0)
        for (int i = 0; i < n; i++)
            if (!isfinite(a[i]))
                return sim_numeric_error(s, t, q, v, "acceleration %s'' is not finite",
                                     m->q_names[i]);
    return EOMC_OK;
}

const double *
eomc_sim_multipliers(const eomc_sim *s)
{
    return s->kkt ? kkt_multipliers(s->kkt) : NULL;
}

int
eomc_sim_residuals(eomc_sim *s, double t, const double *q, const double *v, double *res)
{
    if (!s->kkt)
        return EOMC_OK;
    int rc = eomc_sim_accel(s, t, q, v, s->a);
    if (rc == EOMC_OK)
        kkt_residuals(s, t, q, v, s->a, res);
    return rc;
}

int
eomc_sim_stabilize(eomc_sim *s, int method, double alpha, double beta)
{
    if (method < EOMC_STABILIZE_NONE || method > EOMC_STABILIZE_PROJECT)
        return usage_error(s, "unknown stabilization method %d", method);
    if (method != EOMC_STABILIZE_NONE && !(s->proj && proj_levels(s->proj)))
        return usage_error(s, "%s has no holonomic or first-order constraint to "
                           "stabilize", s->m->name);
    if (!(alpha >= 0 && beta >= 0 && isfinite(alpha) && isfinite(beta)))
        return usage_error(s, "Baumgarte's rates must be finite and not negative, "
                           "not %g, %g", alpha, beta);
    s->stabilize = method;
    s->alpha = alpha;
    s->beta = beta;
    return EOMC_OK;
}

int
eomc_sim_project(eomc_sim *s, double t, double *q, double *v)
{
    if (!s->proj)
        return EOMC_OK;
    if (!all_finite(q, s->n) || !all_finite(v, s->n))
        return sim_numeric_error(s, t, q, v, "the state is not finite");
    return proj_apply(s, t, q, v);
}

void
eomc_sim_energy(eomc_sim *s, double t, const double *q, const double *v, double *T,
                double *V)
{
    double TV[2];
    sim_inputs_at(s, t);
    s->m->energy(t, q, v, s->p, s->u, TV);
    *T = TV[0];
    *V = TV[1];
}

/* dq''/dx = -M^-1 [dE/dq, dE/dv] and dq''/dt = -M^-1 (dE/dt + dE/du u'),
 * each column solved with the factored M. */
int
eomc_sim_jacobian(eomc_sim *s, double t, const double *x, double *dfdx, double *dfdt)
{
    const eomc_model *m = s->m;
    int n = s->n, nu = s->nu, N = 2 * n;
    const double *q = x, *v = x + n;
    if (s->kkt)
        return kkt_jacobian(s, t, x, dfdx, dfdt);
    int rc = eomc_sim_accel(s, t, q, v, s->a);
    if (rc)
        return rc;
    m->jacobian(t, q, v, s->a, s->p, s->u, s->dEdq, s->dEdv, s->dEdu, s->dEdt);
    m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
    int k = factor_mass(s);
    if (k)
        return pivot_error(s, t, q, v, k);
    if (dfdx) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < N; j++)
                dfdx[i * N + j] = j == n + i;
        for (int j = 0; j < N; j++) {
            const double *D = j < n ? s->dEdq : s->dEdv;
            for (int i = 0; i < n; i++)
                s->col[i] = D[i * n + j % n];
            solve_neg(s, s->col);
            for (int i = 0; i < n; i++)
                dfdx[(n + i) * N + j] = s->col[i];
        }
    }
    if (dfdt) {
        for (int i = 0; i < n; i++) {
            double b = s->dEdt[i];
            for (int k2 = 0; k2 < nu; k2++)
                b += s->dEdu[i * nu + k2] * s->dudt[k2];
            s->col[i] = b;
            dfdt[i] = 0;
        }
        solve_neg(s, s->col);
        memcpy(dfdt + n, s->col, (size_t)n * sizeof *dfdt);
    }
    return EOMC_OK;
}

/* ---- integration ---- */

eomc_run_opts
eomc_run_defaults(const eomc_model *m)
{
    eomc_run_opts o = {0.0, m->t_end, m->dt, m->method, m->rtol, m->atol,
                       m->h_fixed, 0, 0};
    return o;
}

static double
wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Every 256 right-hand sides: after the first second, t on the terminal
 * every tenth of a second. */
static void
show_progress(eomc_sim *s, double t)
{
    if (!s->progress || (s->st->rhs_evals & 255))
        return;
    double now = wall_seconds();
    if (now < s->next_show)
        return;
    s->next_show = now + 0.1;
    if (now - s->wall0 < 1.0)
        return;
    fprintf(stderr, "\r%s: t = %-12.6g of %g", s->m->name, t, s->t_end);
    s->shown = 1;
}

static int
rhs(double t, const double *x, double *dxdt, void *ctx)
{
    eomc_sim *s = ctx;
    int n = s->n;
    s->st->rhs_evals++;
    show_progress(s, t);
    if (eomc_sim_accel(s, t, x, x + n, dxdt + n) != EOMC_OK)
        return GSL_EBADFUNC;
    memcpy(dxdt, x + n, (size_t)n * sizeof *dxdt);
    return GSL_SUCCESS;
}

static int
jac(double t, const double *x, double *dfdx, double *dfdt, void *ctx)
{
    eomc_sim *s = ctx;
    s->st->jac_evals++;
    return eomc_sim_jacobian(s, t, x, dfdx, dfdt) == EOMC_OK ? GSL_SUCCESS
                                                             : GSL_EBADFUNC;
}

static int
check_opts(eomc_sim *s, const eomc_run_opts *o)
{
    if (!step_type(o->method))
        return usage_error(s, "unknown method '%s'", o->method ? o->method : "");
    if (!isfinite(o->t0) || !isfinite(o->t_end) || o->t_end < o->t0)
        return usage_error(s, "the end time %g is before the start time %g", o->t_end,
                           o->t0);
    if (!isfinite(o->dt) || o->dt <= 0)
        return usage_error(s, "the output interval must be positive, not %g", o->dt);
    if (!(o->rtol >= 0) || !(o->atol >= 0) || !isfinite(o->rtol) ||
        !isfinite(o->atol) || (o->rtol == 0 && o->atol == 0 && o->h_fixed <= 0))
        return usage_error(s, "tolerances must be finite, not negative and not "
                              "both zero (rtol %g, atol %g)", o->rtol, o->atol);
    if (!(o->h_fixed >= 0) || !isfinite(o->h_fixed))
        return usage_error(s, "the fixed step must be positive, not %g", o->h_fixed);
    if (o->h_fixed > 0 && strncmp(o->method, "ms", 2) == 0)
        return usage_error(s, "%s chooses its own steps and orders: fixed steps are "
                              "for the one-step methods", o->method);
    if (o->max_steps < 0)
        return usage_error(s, "the step limit must be positive, not %ld", o->max_steps);
    return EOMC_OK;
}

/* The message for a driver status other than success. */
static int
driver_error(eomc_sim *s, int status, double t, const double *x, double hmin,
             long max_steps)
{
    int n = s->n;
    switch (status) {
    case GSL_EBADFUNC:
        return EOMC_ENUMERIC; /* the right-hand side said why */
    case GSL_EMAXITER:
        return sim_numeric_error(s, t, x, x + n, "too many steps (the limit is %ld)",
                             max_steps);
    case GSL_ENOPROG:
        return sim_numeric_error(s, t, x, x + n, "step size underflow (below %.3g)", hmin);
    default:
        return sim_numeric_error(s, t, x, x + n, "the integrator failed: %s",
                             gsl_strerror(status));
    }
}

/* ---- degenerate constraints ----
 *
 * A constraint degenerates where its row of B = df/dq'' vanishes (Appell's
 * cone at v = 0): there the accelerations are not determined, and the
 * KKT solution can pass smoothly through the point onto another branch
 * without the integrator noticing.  After each step we compare every row
 * with the row before it: a row that reversed direction went through zero
 * or close to it.  The step is then bisected to the reversal, and if the
 * row is small there relative to its size at either end (not merely
 * turned by a right angle in one long step), the run stops with an error
 * at that time and state. */

#define DEGENERATE_TOL 1e-3 /* |B_k| at the reversal, relative to the ends */
enum { BISECTIONS = 60 };

/* The rows of B at the state x [2n] and t into B [nc*n]. */
static int
constraint_rows(eomc_sim *s, double t, const double *x, double *B)
{
    const eomc_model *m = s->m;
    int n = s->n;
    if (!all_finite(x, 2 * n))
        return -1;
    if (!m->c_affine && eomc_sim_accel(s, t, x, x + n, s->a) != EOMC_OK)
        return -1;
    if (m->c_affine)
        memset(s->a, 0, (size_t)n * sizeof *s->a);
    sim_inputs_at(s, t);
    m->constraint(t, x, x + n, s->a, s->p, s->u, s->fk, B);
    return 0;
}

/* The first row k of B1 that reversed direction since B0, or -1. */
static int
reversed_row(const eomc_sim *s, const double *B0, const double *B1)
{
    int n = s->n;
    for (int k = 0; k < s->m->nc; k++)
        if (kkt_dot(B0 + k * n, B1 + k * n, n) <= 0)
            return k;
    return -1;
}

/* Row k reversed in the step from (s->t0, s->x0) to t1: bisect the step
 * for the reversal; an error there if the row is (nearly) zero. */
static int
locate_degeneracy(eomc_sim *s, gsl_odeiv2_step *step, const gsl_odeiv2_system *sys,
                  int k, double t1)
{
    int n = s->n, N = 2 * n;
    double *Bk0 = s->B0 + k * n, ends = fmax(sqrt(kkt_dot(Bk0, Bk0, n)),
                                             sqrt(kkt_dot(s->B1 + k * n, s->B1 + k * n, n)));
    double lo = 0, hi = t1 - s->t0, small = INFINITY;
    for (int it = 0; it < BISECTIONS; it++) {
        double h = 0.5 * (lo + hi);
        memcpy(s->xt, s->x0, (size_t)N * sizeof *s->xt);
        gsl_odeiv2_step_reset(step);
        if (gsl_odeiv2_step_apply(step, s->t0, h, s->xt, s->xerr, NULL, NULL, sys) !=
                GSL_SUCCESS ||
            constraint_rows(s, s->t0 + h, s->xt, s->B1) != 0) {
            small = 0; /* the solve broke down this close to it */
            break;
        }
        double *Bk = s->B1 + k * n;
        small = fmin(small, sqrt(kkt_dot(Bk, Bk, n)));
        *(kkt_dot(Bk0, Bk, n) > 0 ? &lo : &hi) = h;
    }
    gsl_odeiv2_step_reset(step);
    if (!(small <= DEGENERATE_TOL * ends))
        return GSL_SUCCESS; /* the row turned, it did not vanish */
    memcpy(s->xt, s->x0, (size_t)N * sizeof *s->xt);
    if (lo > 0)
        gsl_odeiv2_step_apply(step, s->t0, lo, s->xt, s->xerr, NULL, NULL, sys);
    gsl_odeiv2_step_reset(step);
    sim_numeric_error(s, s->t0 + lo, s->xt, s->xt + n, "the constraint %s degenerates: "
                      "its row of B = df/dq'' vanishes here (it reverses direction), so "
                      "the accelerations are no longer determined", s->m->c_names[k]);
    return GSL_EBADFUNC;
}

/* After each accepted step of a constrained model: check that no
 * constraint degenerated, measure the drift, and project when asked.  A
 * projected state is not the one the stepper produced, so its history
 * (multistep methods) is dropped. */
static int
after_step(eomc_sim *s, gsl_odeiv2_driver *d, double t, double *x, eomc_stats *st)
{
    int n = s->n;
    if (!s->kkt || !all_finite(x, 2 * n))
        return GSL_SUCCESS; /* a non-finite state is reported at the output time */
    if (constraint_rows(s, t, x, s->B1) != 0)
        return GSL_EBADFUNC;
    int k = reversed_row(s, s->B0, s->B1);
    if (k >= 0 && locate_degeneracy(s, d->s, d->sys, k, t) != GSL_SUCCESS)
        return GSL_EBADFUNC;
    if (proj_levels(s->proj)) {
        double r = proj_residual(s, t, x, x + n);
        st->max_drift = fmax(st->max_drift, r);
        if (s->stabilize == EOMC_STABILIZE_PROJECT) {
            if (proj_apply(s, t, x, x + n) != EOMC_OK)
                return GSL_EBADFUNC;
            gsl_odeiv2_step_reset(d->s);
            r = proj_residual(s, t, x, x + n);
            if (constraint_rows(s, t, x, s->B1) != 0)
                return GSL_EBADFUNC;
        }
        st->max_residual = fmax(st->max_residual, r);
    }
    double *B = s->B0; /* the rows after this step are the next one's start */
    s->B0 = s->B1, s->B1 = B;
    return GSL_SUCCESS;
}

/* Before each step: keep its start for after_step. */
static void
before_step(eomc_sim *s, double t, const double *x)
{
    if (s->kkt) {
        s->t0 = t;
        memcpy(s->x0, x, 2 * (size_t)s->n * sizeof *x);
    }
}

/* Advance from *t to t1 in fixed steps that divide the interval evenly.
 * They bypass the driver's error control, which would refuse a step whose
 * error estimate exceeds the tolerances. */
static int
advance_fixed(eomc_sim *s, gsl_odeiv2_driver *d, const eomc_run_opts *o, double *t,
              double t1, double *x, eomc_stats *st)
{
    double span = t1 - *t;
    unsigned long k = (unsigned long)ceil(span / o->h_fixed * (1 - 1e-12));
    if (k < 1)
        k = 1;
    double h = span / (double)k;
    if (st->h_used == 0)
        st->h_used = h; /* a whole interval's step, not the last sliver's */
    for (unsigned long i = 0; i < k; i++) {
        if (o->max_steps > 0 && (long)d->e->count >= o->max_steps)
            return GSL_EMAXITER;
        before_step(s, *t, x);
        int rc = gsl_odeiv2_evolve_apply_fixed_step(d->e, NULL, d->s, d->sys, t, h, x);
        if (rc == GSL_SUCCESS)
            rc = after_step(s, d, *t, x, st);
        if (rc != GSL_SUCCESS)
            return rc;
    }
    *t = t1; /* the sum of k steps may miss t1 by an ulp */
    return GSL_SUCCESS;
}

/* Advance adaptively, as gsl_odeiv2_driver_apply does, but checking the
 * step budget before each step (the driver lets two more through) and
 * not mistaking the short step that lands on t1 for an underflow. */
static int
advance(eomc_sim *s, gsl_odeiv2_driver *d, const eomc_run_opts *o, double *t, double t1,
        double *x, eomc_stats *st, double hmin)
{
    if (o->h_fixed > 0)
        return advance_fixed(s, d, o, t, t1, x, st);
    while (*t < t1) {
        if (o->max_steps > 0 && (long)d->e->count >= o->max_steps)
            return GSL_EMAXITER;
        before_step(s, *t, x);
        int rc = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, d->sys, t, t1, &d->h, x);
        if (rc == GSL_SUCCESS)
            rc = after_step(s, d, *t, x, st);
        if (rc != GSL_SUCCESS)
            return rc;
        if (*t < t1 && fabs(d->h) < hmin)
            return GSL_ENOPROG;
    }
    return GSL_SUCCESS;
}

int
eomc_sim_integrate(eomc_sim *s, const eomc_run_opts *o, double *x, eomc_row_fn row,
                   void *ctx, eomc_stats *st)
{
    eomc_stats local;
    if (!st)
        st = &local;
    memset(st, 0, sizeof *st);
    int rc = check_opts(s, o);
    if (rc)
        return rc;
    int n = s->n;
    if (!all_finite(x, 2 * n) || !all_finite(s->p, s->m->np))
        return sim_numeric_error(s, o->t0, x, x + n,
                             "the initial state or a parameter is not finite");
    s->st = st;
    s->progress = o->progress && isatty(2);
    s->t_end = o->t_end;
    s->wall0 = wall_seconds();
    s->next_show = s->wall0;
    s->shown = 0;

    double span = o->t_end - o->t0;
    double hmin = 1e-14 * fmax(1.0, fmax(fabs(o->t0), fabs(o->t_end)));
    double h0 = o->h_fixed > 0 ? o->h_fixed : fmin(o->dt, span > 0 ? span : o->dt) * 1e-3;
    gsl_odeiv2_system sys = {rhs, jac, (size_t)(2 * n), s};
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, step_type(o->method), h0,
                                                         o->atol, o->rtol);
    if (!d)
        return usage_error(s, "cannot set up the %s integrator", o->method);

    clock_t c0 = clock();
    double t = o->t0;
    if (s->proj && proj_levels(s->proj))
        st->max_residual = st->max_drift = proj_residual(s, t, x, x + n);
    rc = row ? row(ctx, t, x) : 0;
    if (rc == EOMC_OK && s->kkt && constraint_rows(s, t, x, s->B0) != 0)
        rc = EOMC_ENUMERIC;
    for (long k = 1; rc == EOMC_OK && t < o->t_end; k++) {
        double t1 = o->t0 + (double)k * o->dt;
        if (t1 > o->t_end - 1e-9 * o->dt) /* no sliver of an interval at the end */
            t1 = o->t_end;
        int status = advance(s, d, o, &t, t1, x, st, hmin);
        st->steps = (long)d->e->count;
        st->rejected = (long)d->e->failed_steps;
        if (status != GSL_SUCCESS) {
            rc = driver_error(s, status, t, x, hmin, o->max_steps);
            break;
        }
        if (!all_finite(x, 2 * n)) {
            rc = sim_numeric_error(s, t, x, x + n, "the state is not finite");
            break;
        }
        rc = row ? row(ctx, t, x) : 0;
    }
    if (o->h_fixed > 0)
        st->steps = (long)d->e->count;
    st->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    gsl_odeiv2_driver_free(d);
    if (s->shown)
        fprintf(stderr, "\r%*s\r", 60, "");
    s->st = NULL;
    return rc;
}
