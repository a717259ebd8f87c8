/*
 * sim: the simulator object: a model, its parameters and inputs, the
 * accelerations, the exact Jacobian of the first-order system, drift
 * control, and the messages of everything that can fail.
 *
 * Every work array is allocated in eomc_sim_alloc: the right-hand side and
 * the Jacobian run without allocating.  GSL's error handler is turned off
 * so that a failing factorization comes back as a status, never an abort.
 * The solves below (linalg.c, kkt.c, project.c) return statuses; the
 * messages, which name the time and the state, are made here.
 *
 * struct eomc_sim is this file's alone (the layers above use eomc.h and
 * simimpl.h), so what reads its state is here: that is why the file is
 * somewhat over 800 lines.
 */
#include "simimpl.h"
#include "depend.h"
#include "friction.h"
#include "kkt.h"
#include "linalg.h"
#include "base/numfmt.h"
#include "project.h"
#include "state.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The generated solve reports its smallest balanced pivot at every
 * PIVOT_EVERY-th call (a power of 2): several per step of any method. */
enum { PIVOT_EVERY = 4 };

struct eomc_sim {
    const eomc_model *m;
    int n, nv, nu;           /* coordinates nq, speeds (eomc_nv), inputs */
    double *p;               /* [np + nd] parameter values, then derive's */
    double *u, *dudt;        /* [nu] inputs at the last time asked (u: then the
                                [nmode] modes, eomc_model.h) */
    double *u_const;         /* [nu] held values, where u_held */
    double *sw;              /* [nmode] the switch functions (sim_set_modes) */
    int modes_run;           /* a run sets the modes (sim_modes_run); else each
                                evaluation at a state takes its own (at_state) */
    unsigned char *u_held;   /* [nu] */
    /* the controller in the loop (eomc_sim_set_controller): called every
     * period at a run's samples (sim_sample), its inputs held between, or
     * with period 0 at every evaluation at a state (sim_inputs_at) */
    eomc_controller_fn ctrl;
    void *ctrl_ctx;
    double ctrl_period;
    unsigned char *ctrl_drives; /* [nu] the inputs it sets */
    double *ctrl_u, *ctrl_tmp;  /* [nu] the sample's outputs, held; a call's */
    int ctrl_have;           /* a sample was taken: ctrl_u holds its outputs */
    int ctrl_status;         /* a continuous controller's failure (sticky until
                              * the next run), or EOMC_OK */
    double *jrows;           /* [(nq + nv + nu) * nv] the Jacobian's right-hand sides
                              * as rows, solved at once (jacobian_columns,
                              * eomc_sim_accel_derivatives; NULL until the first) */
    /* below, n is nq and the speeds' arrays have nv entries */
    double *M, *h, *a, *Mrel;             /* [nv*nv], [nv], [nv], [nv] pivots / M_kk */
    size_t *Mperm;           /* [nv] M's pivot order (la_ldlt_factor) */
    double *arow;            /* [max(nq, nv)] the accelerations of a row
                              * (eomc_sim_outputs), an event's q */
    double *dEdq, *dEdv, *dEdu, *dEdt;    /* residual Jacobians [nv*nq], [nv*nv], ... */
    double *dqdq, *dqdv;     /* [nq*nq], [nq*nv] qdot_jacobian's (nv > 0) */
    double *wtw, *wrel, *wzero;           /* [nv*nv], [nv], [nv]: sim_speeds_of's */
    size_t *wperm;                        /* [nv] */
    double *col;             /* [max(nq, nv)] one right-hand side of M y = b */
    double *fk;              /* [nc] f (scratch) */
    LaLu *mlu;               /* M, balanced, for its condition (sim_condition) */
    double *cy, *cd;         /* [nv + nc] its near-null direction, [nv] the balance */
    char *cwhat;             /* sim_condition_what's text */
    double pivot;            /* the smallest balanced pivot since sim_take_pivot */
    unsigned solves;         /* generated solves so far (PIVOT_EVERY) */
    size_t errlen;
    char *err;               /* the last error message */
    Kkt *kkt;                /* constrained models: the solve and multipliers */
    Fric *fric;              /* dry friction: its stuck speeds (friction.h), or NULL */
    double *fnear;           /* [nfric] fric_condition's near-null direction */
    double flip_cond, flip_t;/* the worst stuck rows' condition at a let-go since
                              * sim_take_flip_condition, and its time */
    char *flip_what;         /* what they were */
    Proj *proj;              /* constrained models: projection */
    int stabilize;           /* EOMC_STABILIZE_... */
    double alpha, beta;      /* Baumgarte's rates */
    /* the rows the solves use, chosen at the first state solved
     * (choose_rows), again after the parameters change */
    Depend *dep;
    int chosen;
    double *Bc, *ce;         /* [nc*nv] B there, [nc] the rows' residuals (the watch) */
    int *cl, *crow;          /* [nc] their levels, a list of rows */
};

double *
sim_zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

/* The values of the parameters alone, after any change of them. */
static void
sim_derive(eomc_sim *s)
{
    if (s->m->derive)
        s->m->derive(s->p, s->p + s->m->np);
}

eomc_sim *
eomc_sim_alloc(const eomc_model *m)
{
    if (!m || m->abi != EOMC_ABI_VERSION || m->nq < 1 || m->nv < 0 ||
        (m->nv > 0 && (!m->qdot || !m->v_names)) || (m->nquat > 0 && !m->quat))
        return NULL;
    eomc_sim *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    size_t n = (size_t)m->nq, nv = (size_t)eomc_nv(m), nu = (size_t)m->nu;
    size_t np = (size_t)m->np, most = n > nv ? n : nv;
    s->m = m;
    s->n = m->nq;
    s->nv = (int)nv;
    s->nu = m->nu;
    s->p = sim_zeros(np + (size_t)m->nd); /* the parameters, then derive's values */
    s->u = sim_zeros(nu + (size_t)m->nmode); /* the modes after the inputs */
    s->sw = sim_zeros((size_t)m->nmode);
    s->dudt = sim_zeros(nu);
    s->u_const = sim_zeros(nu);
    s->u_held = calloc(nu ? nu : 1, 1);
    s->ctrl_drives = calloc(nu ? nu : 1, 1);
    s->ctrl_u = sim_zeros(nu);
    s->ctrl_tmp = sim_zeros(nu);
    s->M = sim_zeros(nv * nv);
    s->h = sim_zeros(nv);
    s->a = sim_zeros(nv);
    s->arow = sim_zeros(most);
    s->Mrel = sim_zeros(nv);
    s->Mperm = calloc(nv, sizeof *s->Mperm);
    s->dEdq = sim_zeros(nv * n);
    s->dEdv = sim_zeros(nv * nv);
    s->dEdu = sim_zeros(nv * nu);
    s->dEdt = sim_zeros(nv);
    s->dqdq = sim_zeros(m->nv > 0 ? n * n : 0);
    s->dqdv = sim_zeros(m->nv > 0 ? n * nv : 0);
    s->wtw = sim_zeros(m->nv > 0 ? nv * nv : 0);
    s->wrel = sim_zeros(nv);
    s->wzero = sim_zeros(nv);
    s->wperm = calloc(nv, sizeof *s->wperm);
    s->col = sim_zeros(most);
    s->fk = sim_zeros((size_t)m->nc);
    s->mlu = la_lu_alloc((int)nv);
    s->cy = sim_zeros(nv + (size_t)m->nc);
    s->cd = sim_zeros(nv);
    /* Room for the cause and every coordinate and speed by name. */
    s->errlen = 1024;
    char name[STATE_NAME_MAX];
    for (int i = 0; i < eomc_nx(m); i++)
        s->errlen += strlen(state_name(m, i, name, sizeof name)) + 32;
    for (int k = 0; k < m->nc; k++)
        s->errlen += strlen(m->c_names[k]) +
                     strlen(kkt_dependent_name(m, k, name, sizeof name)) + 8;
    s->err = calloc(s->errlen, 1);
    s->cwhat = calloc(s->errlen, 1);
    s->kkt = m->nc > 0 ? kkt_alloc(m) : NULL;
    s->proj = m->nc > 0 ? proj_alloc(m) : NULL;
    s->dep = m->nc > 0 ? depend_alloc(m) : NULL;
    s->fric = m->nfric > 0 ? fric_alloc(m, m) : NULL;
    s->fnear = sim_zeros((size_t)m->nfric);
    size_t flen = 128;
    for (int j = 0; j < m->nfric; j++)
        flen += strlen(m->fric_names[j]) + 2;
    s->flip_what = calloc(flen, 1);
    s->Bc = sim_zeros((size_t)m->nc * nv);
    s->ce = sim_zeros((size_t)m->nc);
    s->cl = calloc((size_t)m->nc + 1, sizeof *s->cl);
    s->crow = calloc((size_t)m->nc + 1, sizeof *s->crow);
    if (!s->p || !s->u || !s->sw || !s->dudt || !s->u_const || !s->u_held || !s->ctrl_drives ||
        !s->ctrl_u || !s->ctrl_tmp || !s->M || !s->h ||
        !s->a || !s->arow || !s->Mrel || !s->Mperm || !s->dEdq || !s->dEdv || !s->dEdu || !s->dEdt ||
        !s->dqdq || !s->dqdv || !s->wtw || !s->wrel || !s->wzero || !s->wperm ||
        !s->col || !s->fk || !s->err || !s->mlu || !s->cy || !s->cd || !s->cwhat ||
        !s->Bc || !s->ce || !s->cl || !s->crow || !s->fnear || !s->flip_what ||
        (m->nc > 0 && (!s->kkt || !s->proj || !s->dep)) || (m->nfric > 0 && !s->fric)) {
        eomc_sim_free(s);
        return NULL;
    }
    memcpy(s->p, m->p_default, np * sizeof(double));
    sim_derive(s);
    s->pivot = 1;
    return s;
}

void
eomc_sim_free(eomc_sim *s)
{
    if (!s)
        return;
    void *arrays[] = {s->p, s->u, s->sw, s->dudt, s->u_const, s->u_held, s->ctrl_drives,
                      s->ctrl_u, s->ctrl_tmp, s->M, s->h,
                      s->a, s->arow, s->Mrel, s->Mperm, s->dEdq, s->dEdv, s->dEdu, s->dEdt, s->col,
                      s->fk, s->err, s->cy, s->cd, s->cwhat, s->Bc, s->ce, s->cl, s->crow,
                      s->dqdq, s->dqdv, s->wtw, s->wrel, s->wzero, s->wperm, s->fnear,
                      s->flip_what};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    free(s->jrows);
    kkt_free(s->kkt);
    fric_free(s->fric);
    proj_free(s->proj);
    depend_free(s->dep);
    la_lu_free(s->mlu);
    free(s);
}

int
eomc_sim_check(eomc_sim *s)
{
    const eomc_model *m = s->m;
    int k = m->check ? m->check(s->p) : 0;
    if (k == 0)
        return EOMC_OK;
    /* the parameters it names, with their values */
    char vals[512] = "";
    const char *names = m->check_params[k - 1];
    for (int i = 0; i < m->np; i++) {
        size_t len = strlen(m->p_names[i]);
        for (const char *at = names; (at = strstr(at, m->p_names[i])) != NULL; at += len)
            if ((at == names || at[-1] == ' ') && (at[len] == ',' || at[len] == '\0')) {
                size_t used = strlen(vals);
                snprintf(vals + used, sizeof vals - used, "%s%s = %g", used ? ", " : "",
                         m->p_names[i], s->p[i]);
                break;
            }
    }
    return sim_usage_error(s, "%s (%s)", m->check_what[k - 1], vals);
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

int
sim_usage_error(eomc_sim *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->err, s->errlen, fmt, ap);
    va_end(ap);
    return EOMC_EUSAGE;
}

int
sim_no_jacobian(eomc_sim *s, const char *what)
{
    return sim_usage_error(s, "%s needs the Jacobian of the equations, which %s was built "
                           "without (eomc leaves it out when the scene's method needs none): "
                           "rebuild with `eomc build %s --jacobian auto`", what, s->m->name, s->m->spec);
}

/* "t = T: CAUSE; state: q1 = .., q2 = .., q1' = .., q2' = .." (the speeds
 * by their names) */
int
sim_numeric_error(eomc_sim *s, double t, const double *q, const double *v,
                  const char *fmt, ...)
{
    size_t len = 0, cap = s->errlen;
    char name[STATE_NAME_MAX];
    len += (size_t)snprintf(s->err, cap, "t = %.17g: ", t);
    va_list ap;
    va_start(ap, fmt);
    if (len < cap)
        len += (size_t)vsnprintf(s->err + len, cap - len, fmt, ap);
    va_end(ap);
    if (q && v)
        for (int k = 0; k < s->n + s->nv && len < cap; k++)
            len += (size_t)snprintf(s->err + len, cap - len, "%s%s = %.17g",
                                    k ? ", " : "; state: ",
                                    state_name(s->m, k, name, sizeof name),
                                    k < s->n ? q[k] : v[k - s->n]);
    return EOMC_ENUMERIC;
}

void
sim_qdot(const eomc_sim *s, const double *q, const double *v, double *qd)
{
    state_qdot(s->m, q, v, qd);
}

int
sim_speeds_of(eomc_sim *s, const double *q, const double *qd, double *v)
{
    const eomc_model *m = s->m;
    int n = s->n, nv = s->nv;
    if (m->nv == 0 || !m->qdot_jacobian)
        return -1;
    m->qdot_jacobian(q, s->wzero, s->dqdq, s->dqdv); /* W = dq'/dv, whatever v */
    const double *W = s->dqdv;
    for (int a = 0; a < nv; a++) {
        double b = 0;
        for (int i = 0; i < n; i++)
            b += W[i * nv + a] * qd[i];
        v[a] = b;
        for (int c = 0; c <= a; c++) {
            double w = 0;
            for (int i = 0; i < n; i++)
                w += W[i * nv + a] * W[i * nv + c];
            s->wtw[a * nv + c] = s->wtw[c * nv + a] = w;
        }
    }
    if (la_ldlt_factor(s->wtw, nv, s->wrel, s->wperm) != 0)
        return -1;
    la_ldlt_solve(s->wtw, nv, s->wperm, v);
    return 0;
}

int
sim_qddot(eomc_sim *s, const double *x, const double *f, double *qdd)
{
    const eomc_model *m = s->m;
    int n = s->n, nv = s->nv;
    if (m->nv == 0 || !m->qdot_jacobian)
        return -1;
    m->qdot_jacobian(x, x + n, s->dqdq, s->dqdv);
    for (int i = 0; i < n; i++) {
        double d = 0;
        for (int j = 0; j < n; j++)
            d += s->dqdq[i * n + j] * f[j];
        for (int k = 0; k < nv; k++)
            d += s->dqdv[i * nv + k] * f[n + k];
        qdd[i] = d;
    }
    return 0;
}

/* The solves and projections told which rows depend_dropped leaves out. */
static int
use_rows(eomc_sim *s)
{
    const unsigned char *drop = depend_dropped(s->dep);
    kkt_set_dropped(s->kkt, drop);
    if (proj_set_dropped(s->proj, drop) != 0)
        return sim_usage_error(s, "out of memory for the constraints' projection");
    return EOMC_OK;
}

int
eomc_sim_set(eomc_sim *s, const char *name, double value)
{
    const eomc_model *m = s->m;
    for (int k = 0; k < m->np; k++)
        if (strcmp(name, m->p_names[k]) == 0) {
            if (m->p_fixed[k]) {
                char num[NUM_MAX];
                return sim_usage_error(s, "parameter '%s' is fixed at %s in %s%s%s: it was "
                                       "folded into the code (compile without fixing it to "
                                       "vary it)", name, num_shortest(num, m->p_default[k]),
                                       *m->scene ? "scene '" : "the spec's scene",
                                       m->scene, *m->scene ? "'" : "");
            }
            s->p[k] = value;
            sim_derive(s);
            if (s->dep && depend_dropped(s->dep)) { /* chosen again at the next start */
                depend_clear(s->dep);
                if (use_rows(s) != EOMC_OK)
                    return EOMC_EUSAGE;
            }
            s->chosen = 0;
            return EOMC_OK;
        }
    for (int k = 0; k < m->nu; k++)
        if (strcmp(name, m->u_names[k]) == 0) {
            s->u_const[k] = value;
            s->u_held[k] = 1;
            return EOMC_OK;
        }
    return sim_usage_error(s, "'%s' is neither a parameter nor an input of %s", name,
                           m->name);
}

const double *
eomc_sim_params(const eomc_sim *s)
{
    return s->p;
}

int
eomc_sim_input_held(const eomc_sim *s, int k, double *value)
{
    if (k < 0 || k >= s->nu || !s->u_held[k])
        return 0;
    *value = s->u_const[k];
    return 1;
}

int
eomc_sim_set_controller(eomc_sim *s, eomc_controller_fn fn, void *ctx, double period,
                        const unsigned char *drives)
{
    if (!(period >= 0) || !isfinite(period))
        return sim_usage_error(s, "a controller's period must be positive (sampled) or 0 "
                               "(continuous), not %g", period);
    if (fn && s->nu == 0)
        return sim_usage_error(s, "%s has no inputs for a controller to set", s->m->name);
    s->ctrl = fn;
    s->ctrl_ctx = ctx;
    s->ctrl_period = fn ? period : 0;
    s->ctrl_have = 0;
    s->ctrl_status = EOMC_OK;
    for (int k = 0; k < s->nu; k++)
        s->ctrl_drives[k] = (unsigned char)(!drives || drives[k]);
    return EOMC_OK;
}

double
sim_control_period(const eomc_sim *s)
{
    return s->ctrl ? s->ctrl_period : -1;
}

/* The controller's outputs at (t, q, v) into u [nu], which holds the
 * inputs' own values: EOMC_OK, its nonzero status, or EOMC_ENUMERIC (the
 * message naming it) where an input it sets is not finite. */
static int
control_call(eomc_sim *s, double t, const double *q, const double *v, double *u)
{
    int rc = s->ctrl(s->ctrl_ctx, t, q, v, u);
    if (rc != 0) {
        sim_numeric_error(s, t, q, v, "the controller failed (status %d)", rc);
        return rc;
    }
    for (int k = 0; k < s->nu; k++)
        if (s->ctrl_drives[k] && !isfinite(u[k]))
            return sim_numeric_error(s, t, q, v, "the controller set input %s to %g",
                                     s->m->u_names[k], u[k]);
    return EOMC_OK;
}

const unsigned char *
sim_control_drives(const eomc_sim *s)
{
    return s->ctrl_drives;
}

int
sim_control_call(eomc_sim *s, double t, const double *x, double *u)
{
    return control_call(s, t, x, x + s->n, u);
}

int
sim_sample(eomc_sim *s, double t, const double *x)
{
    const double *q = x, *v = x + s->n;
    s->ctrl_status = EOMC_OK;
    s->ctrl_have = 0;
    sim_inputs_at(s, t, q, v); /* the inputs' own values, which it may keep */
    memcpy(s->ctrl_tmp, s->u, (size_t)s->nu * sizeof *s->u);
    int rc = control_call(s, t, q, v, s->ctrl_tmp);
    if (rc != EOMC_OK)
        return rc;
    memcpy(s->ctrl_u, s->ctrl_tmp, (size_t)s->nu * sizeof *s->ctrl_u);
    s->ctrl_have = 1;
    return EOMC_OK;
}

int
sim_control_failed(const eomc_sim *s)
{
    return s->ctrl_status;
}

void
sim_control_start(eomc_sim *s)
{
    s->ctrl_status = EOMC_OK;
    s->ctrl_have = 0;
}

const double *
sim_inputs_at(eomc_sim *s, double t, const double *q, const double *v)
{
    if (s->nu == 0)
        return s->u;
    s->m->inputs(t, s->p, s->u, s->dudt);
    for (int k = 0; k < s->nu; k++)
        if (s->u_held[k]) {
            s->u[k] = s->u_const[k];
            s->dudt[k] = 0;
        }
    if (!s->ctrl)
        return s->u;
    const double *c = s->ctrl_u; /* sampled: the last sample's, held */
    if (s->ctrl_period == 0) {    /* continuous: its call at this state */
        if (!q)
            return s->u; /* no state: the inputs' own values (eomc_sim_inputs) */
        if (s->ctrl_status == EOMC_OK)
            s->ctrl_status = control_call(s, t, q, v, memcpy(s->ctrl_tmp, s->u,
                                                             (size_t)s->nu * sizeof *s->u));
        if (s->ctrl_status != EOMC_OK)
            return s->u; /* (eomc_sim_accel fails: sim_control_failed) */
        c = s->ctrl_tmp;
    } else if (!s->ctrl_have) {
        return s->u; /* no sample yet: the inputs' own values */
    }
    for (int k = 0; k < s->nu; k++)
        if (s->ctrl_drives[k]) {
            s->u[k] = c[k];
            s->dudt[k] = 0;
        }
    return s->u;
}

const double *
sim_p(const eomc_sim *s)
{
    return s->p;
}

int
sim_stabilize_method(const eomc_sim *s)
{
    return s->stabilize;
}

void
sim_save_start(eomc_sim *s)
{
    if (s->kkt)
        kkt_save_start(s->kkt);
}

void
sim_restore_start(eomc_sim *s)
{
    if (s->kkt)
        kkt_restore_start(s->kkt);
}

int
sim_vanished(const eomc_sim *s, double *fraction)
{
    return s->kkt ? kkt_vanished(s->kkt, fraction) : -1;
}

void
eomc_sim_inputs(eomc_sim *s, double t, double *u)
{
    sim_inputs_at(s, t, NULL, NULL);
    if (s->nu)
        memcpy(u, s->u, (size_t)s->nu * sizeof *u);
}

void
eomc_sim_initial(const eomc_sim *s, double *q, double *v)
{
    s->m->initial(s->p, q, v);
}

int
sim_all_finite(const double *x, int n)
{
    /* x * 0 is 0, or NaN where x is an infinity or a NaN: summed without
     * a branch, in four sums that do not wait on each other (Taylor's
     * method checks its whole series each step: the Pleiades' 420
     * coefficients took 9 instructions each one by one, 3 this way) */
    double s[4] = {0, 0, 0, 0};
    int i = 0;
#if defined(__SSE2__)
    /* the four sums as two SSE2 vectors, which gcc -O3 does not make of
     * them (Kepler's step at order 15: 4 031 instructions to 4 018) */
    __m128d zero = _mm_setzero_pd(), s01 = zero, s23 = zero;
    for (; i + 4 <= n; i += 4) {
        s01 = _mm_add_pd(s01, _mm_mul_pd(_mm_loadu_pd(x + i), zero));
        s23 = _mm_add_pd(s23, _mm_mul_pd(_mm_loadu_pd(x + i + 2), zero));
    }
    _mm_storeu_pd(s, s01);
    _mm_storeu_pd(s + 2, s23);
#endif
    for (; i + 4 <= n; i += 4)
        for (int j = 0; j < 4; j++)
            s[j] += x[i + j] * 0;
    for (; i < n; i++)
        s[0] += x[i] * 0;
    return s[0] + s[1] + s[2] + s[3] == 0;
}

double
sim_seconds(int cpu)
{
    struct timespec ts;
    clock_gettime(cpu ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The sum of x[0..n-1], by two running sums: finite whenever every x[i]
 * is, and also when one overflows, which the callers then look at one by
 * one (sim_all_finite).  One addition per entry and half the depth of one
 * sum, for the checks on every right-hand side: the last one waits for
 * q'' and is on the path of a small model's call. */
static inline double
finite_sum(const double *x, int n)
{
    double z0 = 0.0, z1 = 0.0;
    int i = 0;
    for (; i + 1 < n; i += 2) {
        z0 += x[i];
        z1 += x[i + 1];
    }
    if (i < n)
        z0 += x[i];
    return z0 + z1;
}

static int
pivot_error(eomc_sim *s, double t, const double *q, const double *v, int k)
{
    char name[STATE_NAME_MAX];
    if (s->m->nv > 0)
        return sim_numeric_error(s, t, q, v, "mass matrix is singular or not positive "
                                 "definite (pivot %d, speed %s)", k,
                                 state_speed(s->m, k - 1, name, sizeof name));
    return sim_numeric_error(s, t, q, v,
                             "mass matrix is singular or not positive definite "
                             "(pivot %d, coordinate %s)", k, s->m->q_names[k - 1]);
}

/* Of the rows rows [nr] at B and (t, q, v), the dependent ones and
 * those their combinations use (depend_involved), "" if none; into *dims
 * the dimensions those span. */
static const char *
dependent_rows(eomc_sim *s, double t, const double *q, const double *v, const double *B,
               const int *rows, int nr, int *dims)
{
    int rank, inv = 0;
    sim_inputs_at(s, t, q, v);
    s->m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
    const char *names = depend_involved(s->dep, B, s->M, rows, nr, &rank);
    for (const char *c = names; *names && c; c = strchr(c + 1, ','))
        inv++;
    *dims = inv - (nr - rank);
    return names;
}

/* The message of a kkt.c status: a singular system names the rows at
 * fault, those dependent here among the rows it solves. */
static int
kkt_error(eomc_sim *s, double t, const double *q, const double *v, int rc)
{
    const char *names = kkt_names(s->kkt);
    const eomc_model *m = s->m;
    double fraction;
    char dep[STATE_NAME_MAX];
    int c = kkt_vanished(s->kkt, &fraction);
    if (c >= 0 && rc != KKT_DEPENDENT)
        return sim_numeric_error(s, t, q, v, "the constraint %s (%s) degenerates here: "
                                 "its df/dq'' has fallen to %.2g of its largest size in the "
                                 "run (two of its roots in q'' merge, or it no longer "
                                 "constrains the motion)", m->c_names[c],
                                 kkt_dependent_name(m, c, dep, sizeof dep), fraction);
    if (rc == KKT_SINGULAR || rc == KKT_DEPENDENT) {
        const unsigned char *drop = depend_dropped(s->dep);
        int nr = 0, dims;
        for (int k = 0; k < m->nc; k++)
            if (!drop || !drop[k])
                s->crow[nr++] = k;
        const char *dep = dependent_rows(s, t, q, v, kkt_rows(s->kkt), s->crow, nr, &dims);
        if (*dep)
            return sim_numeric_error(s, t, q, v, "the constrained system is singular: the "
                                     "constraints %s are dependent here (their rows "
                                     "df/dq'' span %d dimension%s)", dep, dims,
                                     dims == 1 ? "" : "s");
    }
    switch (rc) {
    case KKT_DEPENDENT:
        return sim_numeric_error(s, t, q, v, "the constraints cannot be solved for their "
                                 "dependent coordinates (df/dq'' of the dependent ones is "
                                 "singular): %s", names);
    case KKT_NEWTON:
        return sim_numeric_error(s, t, q, v, "Newton's method on the constraints %s did "
                                 "not converge in %d iterations", names, KKT_NEWTON_MAX);
    default:
        return sim_numeric_error(s, t, q, v, "the constrained system is singular, though "
                                 "the rows df/dq'' of its constraints %s are independent "
                                 "here: the mass matrix is singular on the motions they "
                                 "allow", names);
    }
}

/* The rows the solves use, chosen where the model is first solved
 * (depend.c): B at (t, q, v), at any q'' (every f affine in q''), and M
 * to scale it.  A model with a constraint nonlinear in q'' keeps every
 * row; an eliminating one cannot leave a row out (each determines a
 * coordinate), and is refused where its rows are dependent. */
static int
choose_rows(eomc_sim *s, double t, const double *q, const double *v)
{
    const eomc_model *m = s->m;
    if (!sim_all_finite(q, s->n) || !sim_all_finite(v, s->nv))
        return EOMC_OK; /* the solve says so; chosen at the next state */
    s->chosen = 1;
    if (!m->c_affine)
        return EOMC_OK;
    sim_inputs_at(s, t, q, v);
    memset(s->col, 0, (size_t)s->nv * sizeof *s->col);
    m->constraint(t, q, v, s->col, s->p, s->u, s->fk, s->Bc);
    m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
    if (depend_choose(s->dep, s->Bc, s->M) == DEPEND_DROPPED && m->eliminate) {
        s->chosen = 0;
        int rc = sim_numeric_error(s, t, q, v, "the constraints are dependent here (%s), and "
                                   "elimination needs independent ones (each determines a "
                                   "coordinate): build the model without --eliminate, with "
                                   "multipliers, which leave the dependent rows out",
                                   depend_note(s->dep));
        depend_clear(s->dep);
        return rc;
    }
    return use_rows(s);
}

int
sim_choose_rows(eomc_sim *s, double t, const double *q, const double *v)
{
    return !s->dep || s->chosen ? EOMC_OK : choose_rows(s, t, q, v);
}

int
sim_start_rows(eomc_sim *s, double t, const double *q, const double *v)
{
    if (!s->dep)
        return EOMC_OK;
    s->chosen = 0;
    if (depend_dropped(s->dep)) {
        depend_clear(s->dep);
        if (use_rows(s) != EOMC_OK)
            return EOMC_EUSAGE;
    }
    return choose_rows(s, t, q, v);
}

const unsigned char *
sim_dropped_rows(const eomc_sim *s)
{
    return s->dep ? depend_dropped(s->dep) : NULL;
}

const char *
sim_dropped_note(const eomc_sim *s)
{
    return sim_dropped_rows(s) ? depend_note(s->dep) : "";
}

int
sim_dropped_watch(eomc_sim *s, double t, const double *q, const double *v)
{
    const unsigned char *drop = sim_dropped_rows(s);
    double kept;
    if (!drop || !sim_has_levels(s))
        return EOMC_OK;
    eomc_sim_inconsistencies(s, t, q, v, s->ce, s->cl);
    int c = depend_watch(s->dep, s->ce, &kept);
    if (c < 0)
        return EOMC_OK;
    return sim_numeric_error(s, t, q, v, "the constraint %s no longer holds: it was left out "
                             "of the solves at the start as dependent on the others (%s), "
                             "but its residual is %.2g of the size of its terms (%s), the "
                             "others' at most %.2g: the constraints are not dependent here, "
                             "and the motion does not meet it", s->m->c_names[c],
                             depend_note(s->dep), s->ce[c],
                             s->cl[c] ? "velocities" : "positions", kept);
}

/* t + the state's and inputs' entries: finite whenever they all are (and
 * where it is not, inputs_finite looks one by one). */
static double
state_sum(const eomc_sim *s, double t, const double *q, const double *v)
{
    return t + finite_sum(q, s->n) + finite_sum(v, s->nv) + finite_sum(s->u, s->nu);
}

static int
inputs_finite(const eomc_sim *s, double t, const double *q, const double *v)
{
    return isfinite(t) && sim_all_finite(q, s->n) && sim_all_finite(v, s->nv) &&
           sim_all_finite(s->u, s->nu);
}

static int
state_error(eomc_sim *s, double t, const double *q, const double *v)
{
    return sim_numeric_error(s, t, q, v, "the state or an input is not finite");
}

static int
accel_error(eomc_sim *s, double t, const double *q, const double *v, const double *a)
{
    char name[STATE_NAME_MAX];
    for (int i = 0; i < s->nv; i++)
        if (!isfinite(a[i]))
            return sim_numeric_error(s, t, q, v, "acceleration %s is not finite",
                                     state_rate(s->m, i, name, sizeof name));
    return EOMC_OK; /* the sum overflowed, no entry did */
}

/* A model with its own solve (the accel member, straight-line code) is
 * called before its inputs are checked, and one test after it covers
 * both: a non-finite input makes the solve fail or q'' non-finite, never
 * pass unseen, and the check's branch then sits at the end instead of
 * ahead of the work, which saves a small model a twentieth of its call. */
static int
accel_own(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    int n = s->nv;
    double in = state_sum(s, t, q, v);
    /* the pivot, for the condition watch, at every PIVOT_EVERY-th solve:
     * finding it costs a tenth of a small model's right-hand side */
    double pivot = 1;
    int want = (++s->solves & (PIVOT_EVERY - 1)) == 0;
    int k = s->m->accel(t, q, v, s->p, s->u, a, want ? &pivot : NULL);
    int bad = k != 0 || !isfinite(in);
    /* q'' one entry at a time, not summed: this test waits for the last
     * entry, and a sum's chain of additions would add its length */
    for (int i = 0; i < n && !bad; i++)
        bad = !isfinite(a[i]);
    if (bad) {
        if (!isfinite(in) && !inputs_finite(s, t, q, v))
            return state_error(s, t, q, v);
        if (k != 0)
            return pivot_error(s, t, q, v, k);
        if ((k = accel_error(s, t, q, v, a)) != EOMC_OK)
            return k;
    }
    if (pivot < s->pivot) /* not fmin: a call, in the hottest path */
        s->pivot = pivot;
    return EOMC_OK;
}

/* Outside a run, the modes of the state itself, from the signs of its
 * switch functions: a value (q'', T and V, an output) is the same in
 * either mode on a kink, where the two branches meet.  EOMC_OK, or where
 * dry friction's modes cannot be decided (sim_set_modes) the error. */
static int
at_state(eomc_sim *s, double t, const double *q, const double *v)
{
    if (s->m->nmode > 0 && !s->modes_run)
        return sim_set_modes(s, t, q, v);
    return EOMC_OK;
}

/* An entry of a near-null direction this large against its largest
 * takes part in the ill-conditioning. */
#define INVOLVED 0.25

/* The message of a friction.h status at (t, q, v). */
static int
fric_error(eomc_sim *s, double t, const double *q, const double *v, int rc)
{
    const eomc_model *m = s->m;
    char name[STATE_NAME_MAX];
    int j = fric_bad(s->fric);
    switch (rc) {
    case STICK_PIVOT:
        return sim_numeric_error(s, t, q, v, "the mass matrix of the speeds that dry friction "
                                 "does not hold is singular or not positive definite "
                                 "(speed %s)", state_speed(m, j, name, sizeof name));
    case STICK_NEGATIVE:
        return sim_numeric_error(s, t, q, v, "dry friction %s: its force is %.17g, below 0 "
                                 "(the largest force it can exert cannot be negative)",
                                 m->fric_names[j], fric_bound_of(s->fric, j));
    case STICK_SPANNED:
        return sim_numeric_error(s, t, q, v, "dry friction %s lets go, yet the items still "
                                 "stuck hold its point along its axis too (their rows span "
                                 "its row): it cannot move, and holding it needs a force "
                                 "beyond its bound; no choice of the items' modes follows "
                                 "the motion here", m->fric_names[j]);
    default:
        return sim_numeric_error(s, t, q, v, "dry friction %s at rest: held, it needs a force "
                                 "beyond its bound, yet let go it would accelerate against "
                                 "its slip; no choice of the items' modes follows the motion "
                                 "here", m->fric_names[j]);
    }
}

/* Dry friction's q'': with an item stuck, its speed held at 0
 * (friction.h); -1 where none is (the model's own solve then), the
 * bounds checked either way. */
static int
accel_friction(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    int rc;
    if (!fric_any(s->fric, s->u)) {
        rc = fric_bounds(s->fric, t, q, v, s->p, s->u);
        return rc == STICK_OK ? -1 : fric_error(s, t, q, v, rc);
    }
    if (s->kkt)
        return sim_usage_error(s, "dry friction holds a coordinate of %s, which has "
                               "constraints: the stuck solve does not take them yet",
                               s->m->name);
    if (!isfinite(state_sum(s, t, q, v)) && !inputs_finite(s, t, q, v))
        return state_error(s, t, q, v);
    if ((rc = fric_solve(s->fric, t, q, v, s->p, s->u, a)) != STICK_OK)
        return fric_error(s, t, q, v, rc);
    if (fric_pivot(s->fric) < s->pivot)
        s->pivot = fric_pivot(s->fric);
    return isfinite(finite_sum(a, s->nv)) ? EOMC_OK : accel_error(s, t, q, v, a);
}

void
sim_modes_run(eomc_sim *s, int on)
{
    s->modes_run = on;
}

int
eomc_sim_accel(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    const eomc_model *m = s->m;
    int n = s->nv, k;
    if ((k = at_state(s, t, q, v)) != EOMC_OK)
        return k;
    sim_inputs_at(s, t, q, v);
    if (s->ctrl_status != EOMC_OK) /* a continuous controller failed: the message is its */
        return EOMC_ENUMERIC;
    if (s->fric && (k = accel_friction(s, t, q, v, a)) >= 0)
        return k;
    if (!s->kkt && m->accel)
        return accel_own(s, t, q, v, a);
    if (!isfinite(state_sum(s, t, q, v)) && !inputs_finite(s, t, q, v))
        return state_error(s, t, q, v);
    if (s->kkt) {
        if (!s->chosen && (k = choose_rows(s, t, q, v)) != EOMC_OK)
            return k;
        if ((k = kkt_accel(s->kkt, t, q, v, s->p, s->u, a)) != KKT_OK)
            return kkt_error(s, t, q, v, k);
        double pivot = kkt_pivot(s->kkt);
        if (pivot < s->pivot) /* not fmin: a call, in the hottest path */
            s->pivot = pivot;
    } else {
        m->mass_bias(t, q, v, s->p, s->u, s->M, a);
        if ((k = m->mass_parent ? la_ltdl_factor(s->M, n, m->mass_parent, s->Mrel)
                                : la_ldlt_factor(s->M, n, s->Mrel, s->Mperm)) != 0)
            return pivot_error(s, t, q, v, k);
        for (int i = 0; i < n; i++)
            if (s->Mrel[i] < s->pivot)
                s->pivot = s->Mrel[i];
        if (m->mass_parent)
            la_ltdl_solve_neg(s->M, n, m->mass_parent, a);
        else
            la_ldlt_solve_neg(s->M, n, s->Mperm, a);
    }
    return isfinite(finite_sum(a, n)) ? EOMC_OK : accel_error(s, t, q, v, a);
}

void
sim_set_dense(eomc_sim *s, int dense)
{
    if (s->kkt)
        kkt_set_dense(s->kkt, dense);
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
        kkt_residuals(s->kkt, t, q, v, s->a, s->p, s->u, res);
    return rc;
}

int
sim_has_levels(const eomc_sim *s)
{
    return s->proj && proj_levels(s->proj);
}

void
sim_baumgarte(const eomc_sim *s, int c, double *wv, double *wp)
{
    *wv = *wp = 0;
    if (s->kkt)
        kkt_baumgarte_weights(s->kkt, c, wv, wp);
}

int
eomc_sim_stabilize(eomc_sim *s, int method, double alpha, double beta)
{
    if (method < EOMC_STABILIZE_NONE || method > EOMC_STABILIZE_PROJECT)
        return sim_usage_error(s, "unknown stabilization method %d", method);
    if (method != EOMC_STABILIZE_NONE && !sim_has_levels(s))
        return sim_usage_error(s, "%s has no holonomic or first-order constraint to "
                               "stabilize", s->m->name);
    if (!(alpha >= 0 && beta >= 0 && isfinite(alpha) && isfinite(beta)))
        return sim_usage_error(s, "Baumgarte's rates must be finite and not negative, "
                               "not %g, %g", alpha, beta);
    s->stabilize = method;
    s->alpha = alpha;
    s->beta = beta;
    if (s->kkt) {
        int on = method == EOMC_STABILIZE_BAUMGARTE;
        kkt_set_baumgarte(s->kkt, on ? 2 * alpha : 0, on ? beta * beta : 0,
                          on ? alpha : 0);
    }
    return EOMC_OK;
}

/* A level's projection found G M^-1 G^T singular at (t, q, v): the rows
 * dependent there, or every row of the level where none is (the metric
 * then is at fault). */
static int
project_singular(eomc_sim *s, double t, const double *q, const double *v, int level)
{
    const char *what = level ? "velocities" : "positions";
    int nr, dims;
    const int *rows = proj_rows(s->proj, level, &nr);
    sim_inputs_at(s, t, q, v);
    memset(s->col, 0, (size_t)s->nv * sizeof *s->col);
    s->m->constraint(t, q, v, s->col, s->p, s->u, s->fk, s->Bc);
    const char *dep = dependent_rows(s, t, q, v, s->Bc, rows, nr, &dims);
    if (*dep)
        return sim_numeric_error(s, t, q, v, "cannot project the %s onto the constraints: "
                                 "%s are dependent here (their rows span %d dimension%s)",
                                 what, dep, dims, dims == 1 ? "" : "s");
    return sim_numeric_error(s, t, q, v, "cannot project the %s onto the constraints %s: "
                             "they are degenerate here", what, proj_names(s->proj, level));
}

int
eomc_sim_project(eomc_sim *s, double t, double *q, double *v)
{
    return eomc_sim_project_held(s, t, q, v, NULL);
}

int
eomc_sim_project_held(eomc_sim *s, double t, double *q, double *v, const unsigned char *hold)
{
    if (!s->proj)
        return EOMC_OK;
    if (!sim_all_finite(q, s->n) || !sim_all_finite(v, s->nv))
        return sim_numeric_error(s, t, q, v, "the state is not finite");
    int level, rc = sim_choose_rows(s, t, q, v);
    if (rc != EOMC_OK)
        return rc;
    sim_inputs_at(s, t, q, v);
    rc = proj_apply_held(s->proj, t, q, v, s->p, s->u, hold, &level);
    const char *what = level ? state_speed_word(s->m, 1) : "positions";
    int held = 0;
    for (int i = 0; hold && i < (level ? s->nv : s->n); i++)
        held |= hold[level * s->n + i];
    char qn[STATE_NAME_MAX], vn[STATE_NAME_MAX];
    int hq, hv;
    switch (rc) {
    case PROJ_OK:
        return EOMC_OK;
    case PROJ_HOLD:
        proj_hold_conflict(s->proj, &hq, &hv);
        return sim_usage_error(s, "cannot keep %s as it is while the speed %s, not held, "
                               "moves it (with the other coordinates that speed moves): "
                               "hold every coordinate a speed moves, a unit quaternion's "
                               "four together, or none of them",
                               state_name(s->m, hq, qn, sizeof qn),
                               state_speed(s->m, hv, vn, sizeof vn));
    case PROJ_NOT_PD:
        return sim_numeric_error(s, t, q, v, "cannot project onto the constraints: "
                                 "the mass matrix is not positive definite%s",
                                 held ? " on what is not held" : "");
    case PROJ_SINGULAR:
        if (held)
            return sim_numeric_error(s, t, q, v, "cannot project the %s onto the "
                                     "constraints %s moving only the %s not held: with "
                                     "those held they cannot all be met, or they are "
                                     "dependent here", what, proj_names(s->proj, level),
                                     what);
        return project_singular(s, t, q, v, level);
    default:
        return sim_numeric_error(s, t, q, v, "projecting the %s onto the constraints "
                                 "%s did not converge in %d Gauss-Newton steps", what,
                                 proj_names(s->proj, level), PROJ_MAX);
    }
}

double
sim_level_residual(eomc_sim *s, double t, const double *q, const double *v)
{
    if (!sim_has_levels(s))
        return 0;
    sim_inputs_at(s, t, q, v);
    return proj_residual(s->proj, t, q, v, s->p, s->u);
}

double
eomc_sim_inconsistency(eomc_sim *s, double t, const double *q, const double *v,
                       int *worst, int *level)
{
    *worst = -1, *level = 0;
    if (!sim_has_levels(s))
        return 0;
    sim_inputs_at(s, t, q, v);
    return proj_inconsistency(s->proj, t, q, v, s->p, s->u, worst, level);
}

double
eomc_sim_inconsistencies(eomc_sim *s, double t, const double *q, const double *v, double *e,
                         int *level)
{
    int worst, lev;
    if (!sim_has_levels(s)) {
        for (int k = 0; k < s->m->nc; k++) {
            e[k] = 0;
            if (level)
                level[k] = 0;
        }
        return 0;
    }
    sim_inputs_at(s, t, q, v);
    return proj_inconsistencies(s->proj, t, q, v, s->p, s->u, &worst, &lev, e, level);
}

int
sim_off_constraints(eomc_sim *s, double t, const double *q, const double *v,
                    const char *what)
{
    const eomc_model *m = s->m;
    int nc = m->nc;
    if (!sim_has_levels(s))
        return EOMC_OK;
    double *e = sim_zeros((size_t)nc);
    int *level = calloc((size_t)nc, sizeof *level);
    if (!e || !level) {
        free(e);
        free(level);
        return sim_usage_error(s, "out of memory checking the constraints");
    }
    int rc = EOMC_OK, off = 0;
    if (eomc_sim_inconsistencies(s, t, q, v, e, level) > EOMC_INCONSISTENT) {
        for (int k = 0; k < nc; k++)
            off += e[k] > EOMC_INCONSISTENT;
        char list[1024];
        size_t len = 0;
        /* worst first: each pass takes the largest left */
        for (int done = 0; done < off && len < sizeof list; done++) {
            int k = 0;
            for (int j = 1; j < nc; j++)
                k = e[j] > e[k] ? j : k;
            len += (size_t)snprintf(list + len, sizeof list - len,
                                    done ? ", %s (%s: %.2g)"
                                         : "%s (%s: its residual is %.2g of the size of its "
                                           "terms)", m->c_names[k],
                                    level[k] ? "velocities" : "positions", e[k]);
            e[k] = -1;
        }
        if (off == 1)
            rc = sim_numeric_error(s, t, q, v, "%s: the state is off the constraint %s", what,
                                   list);
        else
            rc = sim_numeric_error(s, t, q, v, "%s: the state is off %d constraints, worst "
                                   "first: %s", what, off, list);
    }
    free(e);
    free(level);
    return rc;
}

double
sim_condition(eomc_sim *s, double t, const double *q, const double *v)
{
    const eomc_model *m = s->m;
    int n = s->nv;
    if (s->kkt)
        return eomc_sim_accel(s, t, q, v, s->a) == EOMC_OK
                   ? kkt_condition(s->kkt, t, q, v, s->p, s->u)
                   : NAN;
    sim_inputs_at(s, t, q, v);
    m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
    for (int i = 0; i < n; i++) {
        double d = s->M[i * n + i];
        s->cd[i] = d > 0 && isfinite(d) ? 1 / sqrt(d) : 1;
    }
    la_lu_factor_scaled(s->mlu, s->M, s->cd); /* NAN below if it failed */
    return la_lu_condition(s->mlu);
}

/* "the mass matrix (coordinates th1, th2)", "the constrained system
 * (coordinates x1; constraints rod1, rod2)": each part only if any (the
 * speeds by their names, "(speeds root_wx, ...", where they are not the
 * rates). */
const char *
sim_condition_what(eomc_sim *s)
{
    const eomc_model *m = s->m;
    int n = s->nv;
    char name[STATE_NAME_MAX];
    if (s->kkt)
        kkt_near_null(s->kkt, s->cy);
    else
        la_lu_near_null(s->mlu, s->cy);
    size_t len = s->errlen, at = (size_t)snprintf(s->cwhat, len, "%s",
                                                 s->kkt ? "the constrained system" :
                                                          "the mass matrix");
    const char *open = m->nv > 0 ? " (speeds " : " (coordinates ";
    for (int i = 0; i < n && at < len; i++)
        if (fabs(s->cy[i]) >= INVOLVED)
            at += (size_t)snprintf(s->cwhat + at, len - at, "%s%s", open,
                                   m->nv > 0 ? state_speed(m, i, name, sizeof name)
                                             : m->q_names[i]),
                open = ", ";
    const char *part = open[0] == ',' ? "; constraints " : " (constraints ";
    for (int c = 0; s->kkt && !m->eliminate && c < m->nc && at < len; c++)
        if (fabs(s->cy[n + c]) >= INVOLVED)
            at += (size_t)snprintf(s->cwhat + at, len - at, "%s%s", part, m->c_names[c]),
                part = ", ", open = ", ";
    if (open[0] == ',' && at < len)
        snprintf(s->cwhat + at, len - at, ")");
    return s->cwhat;
}

double
eomc_sim_condition(eomc_sim *s, double t, const double *q, const double *v,
                   const char **what)
{
    double c = sim_condition(s, t, q, v);
    if (what)
        *what = sim_condition_what(s);
    return c;
}

double
sim_take_pivot(eomc_sim *s)
{
    double p = s->pivot;
    s->pivot = 1;
    return p;
}

int
sim_constraint_rows(eomc_sim *s, double t, const double *x, double *B)
{
    const eomc_model *m = s->m;
    int n = s->n;
    if (!sim_all_finite(x, n + s->nv))
        return -1;
    if (!m->c_affine && eomc_sim_accel(s, t, x, x + n, s->a) != EOMC_OK)
        return -1;
    if (m->c_affine)
        memset(s->a, 0, (size_t)s->nv * sizeof *s->a);
    sim_inputs_at(s, t, x, x + s->n);
    m->constraint(t, x, x + n, s->a, s->p, s->u, s->fk, B);
    return 0;
}

void
eomc_sim_energy(eomc_sim *s, double t, const double *q, const double *v, double *T,
                double *V)
{
    double TV[2];
    (void)at_state(s, t, q, v); /* (friction's modes put nothing in T or V) */
    sim_inputs_at(s, t, q, v);
    s->m->energy(t, q, v, s->p, s->u, TV);
    *T = TV[0];
    *V = TV[1];
}

int
eomc_sim_outputs(eomc_sim *s, double t, const double *q, const double *v, double *out)
{
    const eomc_model *m = s->m;
    if (!m->outputs)
        return EOMC_OK;
    /* the accelerations and multipliers of this very state */
    if (eomc_sim_accel(s, t, q, v, s->arow) != EOMC_OK)
        return EOMC_ENUMERIC;
    sim_inputs_at(s, t, q, v);
    m->outputs(t, q, v, s->arow, s->p, s->u, eomc_sim_multipliers(s), out);
    return EOMC_OK;
}

void
sim_switches(eomc_sim *s, double t, const double *q, const double *v, double *sw)
{
    sim_inputs_at(s, t, q, v);
    s->m->switches(t, q, v, s->p, s->u, sw);
    /* the stick switches' functions, from the holding forces (NAN where
     * they cannot be solved: the run's right-hand side says why) */
    if (s->fric)
        (void)fric_functions(s->fric, t, q, v, s->p, s->u, sw);
}

int
sim_mode_held(const eomc_sim *s, int k)
{
    return s->fric && fric_item_stick(s->fric, k) >= 0;
}

/* A stuck item lets go at (t, q, v): the stuck rows' condition there, in
 * the modes before (fric_condition), the worst kept.  The solve the run
 * made there is the one that decides the let-go. */
static void
watch_let_go(eomc_sim *s, double t, const double *q, const double *v)
{
    const eomc_model *m = s->m;
    if (fric_solve(s->fric, t, q, v, s->p, s->u, s->a) != STICK_OK)
        return; /* (the flip says why) */
    double c = fric_condition(s->fric, s->fnear);
    if (!(c > s->flip_cond))
        return;
    s->flip_cond = c, s->flip_t = t;
    int at = sprintf(s->flip_what, "the stuck friction rows");
    const char *open = " (";
    for (int j = 0; j < m->nfric; j++)
        if (s->fnear[j] >= INVOLVED)
            at += sprintf(s->flip_what + at, "%s%s", open, m->fric_names[j]), open = ", ";
    sprintf(s->flip_what + at, "%s at a let-go", open[0] == ',' ? ")" : "");
}

double
sim_take_flip_condition(eomc_sim *s, double *t, const char **what)
{
    double c = s->flip_cond;
    *t = s->flip_t, *what = s->flip_what;
    s->flip_cond = 0;
    return c;
}

int
sim_flip(eomc_sim *s, int k, int on, double t, double *x)
{
    if (!s->fric) {
        sim_set_mode(s, k, on);
        return EOMC_OK;
    }
    double *q = x, *v = x + s->n;
    sim_inputs_at(s, t, x, x + s->n);
    if (!on && fric_item_stick(s->fric, k) >= 0)
        watch_let_go(s, t, q, v);
    int rc = fric_flip(s->fric, k, on, t, q, v, s->p, s->u);
    return rc == STICK_OK ? EOMC_OK : fric_error(s, t, q, v, rc);
}

void
sim_span(eomc_sim *s, double span)
{
    if (s->fric)
        fric_span(s->fric, span);
}

void
sim_set_mode(eomc_sim *s, int k, int on)
{
    s->u[s->nu + k] = on ? 1.0 : 0.0;
}

int
sim_mode(const eomc_sim *s, int k)
{
    return s->u[s->nu + k] != 0.0;
}

int
sim_set_modes(eomc_sim *s, double t, const double *q, const double *v)
{
    /* a switch function may read other modes (max of a max): each pass
     * settles at least the modes the ones before decided; dry friction's
     * stick switches are friction's to set, after */
    for (int pass = 0; pass <= s->m->nmode; pass++) {
        int changed = 0;
        sim_inputs_at(s, t, q, v);
        s->m->switches(t, q, v, s->p, s->u, s->sw);
        for (int k = 0; k < s->m->nmode; k++) {
            int on = s->sw[k] > 0;
            if (sim_mode_held(s, k))
                continue;
            changed |= on != sim_mode(s, k);
            sim_set_mode(s, k, on);
        }
        if (!changed)
            break;
    }
    if (!s->fric)
        return EOMC_OK;
    sim_inputs_at(s, t, q, v);
    int rc = fric_settle(s->fric, t, q, v, s->p, s->u);
    return rc == STICK_OK ? EOMC_OK : fric_error(s, t, q, v, rc);
}

void
eomc_sim_events(eomc_sim *s, double t, const double *q, const double *v, double *g)
{
    sim_inputs_at(s, t, q, v);
    s->m->events(t, q, v, s->p, s->u, g);
}

void
eomc_sim_event_set(eomc_sim *s, int k, double t, const double *x, double *x1)
{
    const eomc_model *m = s->m;
    int n = s->n;
    /* the values it sets are computed from the state before: a copy */
    memcpy(s->arow, x, (size_t)n * sizeof *x);
    memcpy(s->col, x + n, (size_t)s->nv * sizeof *x);
    memmove(x1, x, (size_t)(n + s->nv) * sizeof *x);
    if (m->ev_action[k] != EOMC_EVENT_SET || !m->event_set)
        return;
    sim_inputs_at(s, t, x, x + s->n);
    m->event_set(k, t, s->arow, s->col, s->p, s->u, x1, x1 + n);
}

int
eomc_sim_invariant(eomc_sim *s, double t, const double *q, const double *v, double *h)
{
    if (!s->m->invariant)
        return sim_usage_error(s, "%s conserves no quantity that eomc knows of: %s",
                               s->m->name, s->m->invariant_note);
    (void)at_state(s, t, q, v); /* (none conserved with friction on) */
    sim_inputs_at(s, t, q, v);
    s->m->invariant(t, q, v, s->p, s->u, h);
    return EOMC_OK;
}

/* The rows of q' in dx'/dx [N x N] and dx'/dt: [0, I] when the speeds
 * are the rates, else [dq'/dq, dq'/dv] of the kinematic equation (q' has
 * no t of its own). */
static int
rates_jacobian(eomc_sim *s, const double *x, double *dfdx, double *dfdt)
{
    const eomc_model *m = s->m;
    int n = s->n, nv = s->nv, N = n + nv;
    if (m->nv > 0 && !m->qdot_jacobian)
        return sim_usage_error(s, "the Jacobian of %s's equations needs that of its "
                               "kinematic equation q' = W(q) v (qdot_jacobian), which it "
                               "was built without", m->name);
    if (m->nv > 0 && dfdx)
        m->qdot_jacobian(x, x + n, s->dqdq, s->dqdv);
    for (int i = 0; dfdx && i < n; i++)
        for (int j = 0; j < N; j++)
            dfdx[i * N + j] = m->nv == 0 ? j == n + i
                              : j < n    ? s->dqdq[i * n + j]
                                         : s->dqdv[i * nv + j - n];
    for (int i = 0; dfdt && i < n; i++)
        dfdt[i] = 0;
    return EOMC_OK;
}

/* Whether dry friction holds a speed in the modes as they are: then the
 * Jacobian's solves are friction's (the stuck speeds' rows 0). */
static int
stuck(const eomc_sim *s)
{
    return s->fric && fric_any(s->fric, s->u);
}

/* b = -M^-1 b with M as eomc_sim_jacobian factored it (or friction.h's
 * block, some speed held). */
static void
jacobian_solve_neg(eomc_sim *s, double *b)
{
    if (stuck(s))
        fric_solve_neg(s->fric, b);
    else if (s->m->mass_parent)
        la_ltdl_solve_neg(s->M, s->nv, s->m->mass_parent, b);
    else
        la_ldlt_solve_neg(s->M, s->nv, s->Mperm, b);
}

/* Columns of -M^-1 A, A [nv x k] row-major (k of them, a column of A a
 * right-hand side) with M as eomc_sim_jacobian factored it, into out[i *
 * stride + j] (row i, column j): all at once, by a tree's LTDL
 * (la_ltdl_solve_cols_neg, in place) or the dense factorization
 * (la_ldlt_solve_rows_neg); one column at a time with friction's block,
 * or when memory runs out. */
static void
jacobian_columns(eomc_sim *s, const double *A, int k, double *out, int stride)
{
    int nv = s->nv;
    size_t room = ((size_t)s->n + (size_t)nv + (size_t)s->nu) * (size_t)nv;
    if (!stuck(s) && s->m->mass_parent) { /* a tree's: every column at once, in place */
        for (int i = 0; i < nv; i++)
            memcpy(out + (size_t)i * stride, A + (size_t)i * k, (size_t)k * sizeof *A);
        la_ltdl_solve_cols_neg(s->M, nv, s->m->mass_parent, out, k, stride);
        return;
    }
    int whole = !stuck(s);
    if (!s->jrows && whole)
        s->jrows = malloc((room ? room : 1) * sizeof *s->jrows);
    if (whole && s->jrows) {
        double *Z = s->jrows;
        for (int j = 0; j < k; j++)
            for (int i = 0; i < nv; i++)
                Z[(size_t)j * nv + i] = A[(size_t)i * k + j];
        if (la_ldlt_solve_rows_neg(s->M, nv, s->Mperm, Z, k) == 0) {
            for (int j = 0; j < k; j++)
                for (int i = 0; i < nv; i++)
                    out[(size_t)i * stride + j] = Z[(size_t)j * nv + i];
            return;
        }
    }
    for (int j = 0; j < k; j++) {
        for (int i = 0; i < nv; i++)
            s->col[i] = A[(size_t)i * k + j];
        jacobian_solve_neg(s, s->col);
        for (int i = 0; i < nv; i++)
            out[(size_t)i * stride + j] = s->col[i];
    }
}

/* E's derivatives at (t, q, v) and s->a (eomc_sim_accel's there) into
 * s->dEdq, dEdv, dEdu and dEdt, and M factored for their columns (a
 * model's own solve, the accel member, leaves it unfactored); without
 * constraints. */
static int
residual_jacobian(eomc_sim *s, double t, const double *q, const double *v)
{
    const eomc_model *m = s->m;
    int nv = s->nv;
    m->jacobian(t, q, v, s->a, s->p, s->u, s->dEdq, s->dEdv, s->dEdu, s->dEdt);
    if (!stuck(s)) { /* (else eomc_sim_accel factored the free speeds' block) */
        m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
        int k = m->mass_parent ? la_ltdl_factor(s->M, nv, m->mass_parent, s->Mrel)
                               : la_ldlt_factor(s->M, nv, s->Mrel, s->Mperm);
        if (k)
            return pivot_error(s, t, q, v, k);
    }
    return EOMC_OK;
}

/* dv'/dx = -M^-1 [dE/dq, dE/dv] and dv'/dt = -M^-1 (dE/dt + dE/du u'),
 * each column solved with the factored M; the rows of q' above them.
 * With a speed held by dry friction, its rows are 0 and the rest solve
 * with the block of the free speeds (the stuck speeds' accelerations are
 * 0 whatever the state). */
int
eomc_sim_jacobian(eomc_sim *s, double t, const double *x, double *dfdx, double *dfdt)
{
    const eomc_model *m = s->m;
    int n = s->n, nv = s->nv, nu = s->nu, N = n + nv;
    const double *q = x, *v = x + n;
    if (!m->jacobian)
        return sim_no_jacobian(s, "eomc_sim_jacobian");
    int rc = eomc_sim_accel(s, t, q, v, s->a);
    if (rc)
        return rc;
    if ((rc = rates_jacobian(s, x, dfdx, dfdt)) != EOMC_OK)
        return rc;
    if (s->kkt) {
        rc = kkt_jacobian(s->kkt, t, x, s->p, s->u, s->dudt, s->a, dfdx, dfdt);
        return rc == KKT_OK ? EOMC_OK : kkt_error(s, t, q, v, rc);
    }
    if ((rc = residual_jacobian(s, t, q, v)) != EOMC_OK)
        return rc;
    if (dfdx) {
        jacobian_columns(s, s->dEdq, n, dfdx + (size_t)n * N, N);
        jacobian_columns(s, s->dEdv, nv, dfdx + (size_t)n * N + n, N);
    }
    if (dfdt) {
        for (int i = 0; i < nv; i++) {
            double b = s->dEdt[i];
            for (int k2 = 0; k2 < nu; k2++)
                b += s->dEdu[i * nu + k2] * s->dudt[k2];
            s->col[i] = b;
        }
        jacobian_solve_neg(s, s->col);
        memcpy(dfdt + n, s->col, (size_t)nv * sizeof *dfdt);
    }
    return EOMC_OK;
}

int
eomc_sim_mass_bias(eomc_sim *s, double t, const double *q, const double *v, double *M,
                   double *h)
{
    int rc = at_state(s, t, q, v);
    if (rc != EOMC_OK)
        return rc;
    sim_inputs_at(s, t, q, v);
    if (s->ctrl_status != EOMC_OK)
        return EOMC_ENUMERIC;
    s->m->mass_bias(t, q, v, s->p, s->u, M, h);
    if (!sim_all_finite(M, s->nv * s->nv) || !sim_all_finite(h, s->nv))
        return sim_numeric_error(s, t, q, v, "the mass matrix or the bias is not finite");
    return EOMC_OK;
}

/* Without constraints, M^-1's columns straight into the caller's arrays;
 * along a tree all of them in one pass of la_ltdl_solve_cols_neg (its
 * rows [dE/dq | dE/dv | dE/du] side by side in s->jrows, which has room
 * for them), as eomc_sim_jacobian's own solves give them to the bit.  A
 * constrained model's through the KKT system's (eomc_sim_jacobian). */
int
eomc_sim_accel_derivatives(eomc_sim *s, double t, const double *q, const double *v,
                           double *dadq, double *dadv, double *dadu)
{
    const eomc_model *m = s->m;
    int n = s->n, nv = s->nv, nu = s->nu, N = n + nv;
    if (!m->jacobian)
        return sim_no_jacobian(s, "eomc_sim_accel_derivatives");
    if (!s->kkt) {
        int rc = eomc_sim_accel(s, t, q, v, s->a);
        if (rc == EOMC_OK)
            rc = residual_jacobian(s, t, q, v);
        if (rc != EOMC_OK)
            return rc;
        int K = n + nv + nu, tree = !stuck(s) && m->mass_parent;
        if (tree && !s->jrows)
            s->jrows = malloc((size_t)K * nv * sizeof *s->jrows);
        if (tree && s->jrows && dadq && dadv && (dadu || !nu)) {
            double *X = s->jrows;
            for (int i = 0; i < nv; i++) {
                double *row = X + (size_t)i * K;
                memcpy(row, s->dEdq + (size_t)i * n, (size_t)n * sizeof *row);
                memcpy(row + n, s->dEdv + (size_t)i * nv, (size_t)nv * sizeof *row);
                if (nu)
                    memcpy(row + N, s->dEdu + (size_t)i * nu, (size_t)nu * sizeof *row);
            }
            la_ltdl_solve_cols_neg(s->M, nv, m->mass_parent, X, K, K);
            for (int i = 0; i < nv; i++) {
                const double *row = X + (size_t)i * K;
                memcpy(dadq + (size_t)i * n, row, (size_t)n * sizeof *row);
                memcpy(dadv + (size_t)i * nv, row + n, (size_t)nv * sizeof *row);
                if (nu)
                    memcpy(dadu + (size_t)i * nu, row + N, (size_t)nu * sizeof *row);
            }
            return EOMC_OK;
        }
        if (dadq)
            jacobian_columns(s, s->dEdq, n, dadq, n);
        if (dadv)
            jacobian_columns(s, s->dEdv, nv, dadv, nv);
        if (dadu && nu)
            jacobian_columns(s, s->dEdu, nu, dadu, nu);
        return EOMC_OK;
    }
    double *x = malloc((size_t)N * sizeof *x), *J = malloc((size_t)N * N * sizeof *J);
    double *B = malloc(((size_t)N * nu + 1) * sizeof *B);
    int rc = x && J && B ? EOMC_OK : sim_usage_error(s, "out of memory for the derivatives");
    if (rc == EOMC_OK) {
        memcpy(x, q, (size_t)n * sizeof *x);
        memcpy(x + n, v, (size_t)nv * sizeof *x);
        rc = eomc_sim_jacobian(s, t, x, J, NULL);
    }
    if (rc == EOMC_OK && dadu && nu > 0 && sim_input_jacobian(s, t, x, B) != 0)
        rc = sim_numeric_error(s, t, q, v, "the constrained solve for dq''/du failed");
    for (int i = 0; rc == EOMC_OK && i < nv; i++) {
        const double *row = J + (size_t)(n + i) * N;
        if (dadq)
            memcpy(dadq + (size_t)i * n, row, (size_t)n * sizeof *row);
        if (dadv)
            memcpy(dadv + (size_t)i * nv, row + n, (size_t)nv * sizeof *row);
        for (int k = 0; dadu && k < nu; k++)
            dadu[(size_t)i * nu + k] = B[(size_t)(n + i) * nu + k];
    }
    free(x);
    free(J);
    free(B);
    return rc;
}

int
sim_input_jacobian(eomc_sim *s, double t, const double *x, double *B)
{
    int n = s->n, nv = s->nv, nu = s->nu, N = n + nv;
    if (nu == 0)
        return 0;
    if (!s->kkt) { /* dv'/du = -M^-1 dE/du, with M as eomc_sim_jacobian factored it */
        memset(B, 0, (size_t)n * nu * sizeof *B);
        jacobian_columns(s, s->dEdu, nu, B + (size_t)n * nu, nu);
        return 0;
    }
    /* the KKT system's time column is linear in the input rates: its
     * difference with a unit rate and without is B's column */
    double *rate = calloc((size_t)nu, sizeof *rate), *f0 = calloc((size_t)N, sizeof *f0);
    double *f1 = calloc((size_t)N, sizeof *f1);
    int rc = rate && f0 && f1 ? 0 : -1;
    const double *u = s->u; /* at t: eomc_sim_jacobian computed them */
    if (!rc)
        rc = kkt_jacobian(s->kkt, t, x, s->p, u, rate, s->a, NULL, f0) ? -1 : 0;
    for (int k = 0; k < nu && !rc; k++) {
        rate[k] = 1;
        rc = kkt_jacobian(s->kkt, t, x, s->p, u, rate, s->a, NULL, f1) ? -1 : 0;
        rate[k] = 0;
        for (int i = 0; i < N; i++)
            B[i * nu + k] = f1[i] - f0[i];
    }
    free(rate);
    free(f0);
    free(f1);
    return rc;
}
