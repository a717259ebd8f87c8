/*
 * ctrlosc.c: m x'' + k x = u, the plant of the controller tests
 * (test_control.c), with its twin for the reference solution: compiled a
 * second time with -DEOMC_EXTENDED, as eomc compiles a generated model.
 * p = (m, k), u held at 0 unless set or controlled; x(0) = 0.2, x'(0) =
 * -0.1 (models.h: CTRLOSC_...).
 */
#include "eomc_model.h"
#include "models.h"

#include <stddef.h>

static void
co_inputs(eomc_real t, const eomc_real *p, eomc_real *u, eomc_real *dudt)
{
    (void)t, (void)p;
    u[0] = 0;
    if (dudt)
        dudt[0] = 0;
}

static void
co_mass_bias(eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p,
             const eomc_real *u, eomc_real *M, eomc_real *h)
{
    (void)t, (void)v;
    M[0] = p[0];
    h[0] = p[1] * q[0] - u[0];
}

#ifndef EOMC_EXTENDED

static const char *const co_q[] = {"x"};
static const char *const co_p[] = {"m", "k"};
static const char *const co_u[] = {"u"};
static const double co_pdef[] = {CTRLOSC_M, CTRLOSC_K};
static const unsigned char co_fixed[] = {0, 0};

static void
co_initial(const double *p, double *q, double *v)
{
    (void)p;
    q[0] = CTRLOSC_X0;
    v[0] = CTRLOSC_V0;
}

static void
co_energy(double t, const double *q, const double *v, const double *p, const double *u,
          double *TV)
{
    (void)t, (void)u;
    TV[0] = 0.5 * p[0] * v[0] * v[0];
    TV[1] = 0.5 * p[1] * q[0] * q[0];
}

static void
co_jacobian(double t, const double *q, const double *v, const double *a, const double *p,
            const double *u, double *dEdq, double *dEdv, double *dEdu, double *dEdt)
{
    (void)t, (void)q, (void)v, (void)a, (void)u;
    dEdq[0] = p[1];
    dEdv[0] = 0;
    dEdu[0] = -1;
    dEdt[0] = 0;
}

const eomc_model ctrlosc_model = {
    .abi = EOMC_ABI_VERSION, .name = "ctrlosc", .spec = "ctrlosc.yaml", .form = "lagrange",
    .options = "", .nq = 1, .np = 2, .nu = 1, .q_names = co_q, .p_names = co_p,
    .u_names = co_u, .p_default = co_pdef, .scene = "", .p_fixed = co_fixed, .t_end = 3.0,
    .dt = 0.05, .method = "rk8pd", .rtol = 1e-10, .atol = 1e-10, .initial = co_initial,
    .inputs = co_inputs, .mass_bias = co_mass_bias, .energy = co_energy,
    .jacobian = co_jacobian, .c_affine = 1, .taylor_why = "a hand-written model without series",
};

#else /* the twin: what the reference evaluates */

const eomc_model_ext ctrlosc_model_ext = {
    .abi = EOMC_ABI_VERSION, .name = "ctrlosc", .inputs = co_inputs,
    .mass_bias = co_mass_bias,
};

#endif
