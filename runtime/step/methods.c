/*
 * methods: the integration methods (methods.def) as GSL step types, what
 * each can do, and a run's options checked against them and the
 * simulator (eomc_run_check), before any step.
 */
#include "methods.h"
#include "model/simimpl.h"
#include "fixed.h"
#include "taylor.h"

#include <math.h>
#include <string.h>

/* Taylor's method has no GSL step type: its null one marks it (Method). */
static const gsl_odeiv2_step_type *const eomc_taylor_series = NULL;

#define FIXED_GSL(g) &g, 0
#define FIXED_RK4(g) &fixed_rk4, 1
#define FIXED_RK1IMP(g) &fixed_rk1imp, 1
#define FIXED_RK2IMP(g) &fixed_rk2imp, 1
#define FIXED_RK4IMP(g) &fixed_rk4imp, 1
#define FIXED_NONE(g) NULL, 0
static const Method methods[] = {
#define METHOD(name, gsl, fixed, jac, description) \
    {#name, &gsl, FIXED_##fixed(gsl), jac, description},
#include "base/methods.def"
#undef METHOD
};
enum { NMETHODS = sizeof methods / sizeof methods[0] };

const char *const eomc_methods[] = {
#define METHOD(name, gsl, fixed, jac, description) #name,
#include "base/methods.def"
#undef METHOD
    NULL,
};

const Method *
method_find(const char *name)
{
    for (int k = 0; k < NMETHODS; k++)
        if (name && strcmp(name, methods[k].name) == 0)
            return &methods[k];
    return NULL;
}

const char *
eomc_method_description(const char *name)
{
    const Method *m = method_find(name);
    return m ? m->description : NULL;
}

int
eomc_method_steps(const char *name)
{
    const Method *m = method_find(name);
    return !m ? -1 : !m->fixed ? EOMC_STEPS_ADAPTIVE : m->own_fixed ? EOMC_STEPS_DOUBLING
                                                                    : EOMC_STEPS_EMBEDDED;
}

int
eomc_method_jacobian(const char *name)
{
    const Method *m = method_find(name);
    return m ? m->jacobian : -1;
}

eomc_run_opts
eomc_run_defaults(const eomc_model *m)
{
    eomc_run_opts o = {.t0 = 0.0, .t_end = m->t_end, .dt = m->dt, .method = m->method,
                       .rtol = m->rtol, .atol = m->atol, .h_fixed = m->h_fixed};
    return o;
}

int
eomc_run_check(eomc_sim *s, const eomc_run_opts *o)
{
    const Method *m = method_find(o->method);
    if (!m)
        return sim_usage_error(s, "unknown method '%s'", o->method ? o->method : "");
    if (eomc_sim_check(s) != EOMC_OK)
        return EOMC_EUSAGE;
    if (m->jacobian && !eomc_sim_model(s)->jacobian)
        return sim_no_jacobian(s, o->method);
    if (m->jacobian && eomc_sim_model(s)->nv > 0 && !eomc_sim_model(s)->qdot_jacobian)
        return sim_usage_error(s, "%s needs the Jacobian of %s's kinematic equation q' = "
                               "W(q) v (qdot_jacobian), which it was built without",
                               o->method, eomc_sim_model(s)->name);
    if (!isfinite(o->t0) || !isfinite(o->t_end) || o->t_end < o->t0)
        return sim_usage_error(s, "the end time %g is before the start time %g", o->t_end,
                               o->t0);
    if (!isfinite(o->dt) || o->dt <= 0)
        return sim_usage_error(s, "the output interval must be positive, not %g", o->dt);
    if (!(o->rtol >= 0) || !(o->atol >= 0) || !isfinite(o->rtol) ||
        !isfinite(o->atol) || (o->rtol == 0 && o->atol == 0 && o->h_fixed <= 0))
        return sim_usage_error(s, "tolerances must be finite, not negative and not "
                               "both zero (rtol %g, atol %g)", o->rtol, o->atol);
    if (!(o->h_fixed >= 0) || !isfinite(o->h_fixed))
        return sim_usage_error(s, "the fixed step must be positive, not %g", o->h_fixed);
    if (o->h_fixed > 0 && !m->fixed)
        return sim_usage_error(s, "%s chooses its own steps and orders: fixed steps are "
                               "for the one-step methods", o->method);
    /* the multistep methods: no fixed steps, and GSL's (Taylor's method
     * has neither, and is a one-step method: its series starts afresh
     * from each step's end, projected or not) */
    int multistep = !m->fixed && *m->adaptive;
    if (sim_stabilize_method(s) == EOMC_STABILIZE_PROJECT && multistep)
        return sim_usage_error(s, "%s builds on the history of its steps, which projecting "
                               "the state after every step would throw away (it would "
                               "restart at order 1 each time, slow and inaccurate): with "
                               "--stabilize project use a one-step method (rk2, rk4, "
                               "rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, taylor)",
                               o->method);
    if (o->max_steps < 0)
        return sim_usage_error(s, "the step limit must be positive, not %ld",
                               o->max_steps);
    const eomc_model *md = eomc_sim_model(s);
    if (md->nfric > 0 && md->nc > 0)
        return sim_usage_error(s, "%s has dry friction (%s) and constraints: the solve that "
                               "holds a stuck coordinate does not take constraints yet (turn "
                               "the friction's effect off with --effects)", md->name,
                               md->fric_names[0]);
    if (md->nfric > 0 && !*m->adaptive)
        return sim_usage_error(s, "taylor: %s has dry friction (%s), whose stuck "
                               "coordinates' accelerations are a solve Taylor's series do "
                               "not expand: use another method", md->name,
                               md->fric_names[0]);
    if (!*m->adaptive && sim_control_period(s) == 0)
        return sim_usage_error(s, "taylor: a continuous controller has no Taylor series of "
                               "its inputs: give it a period (a sampled controller, whose "
                               "inputs are held between its samples), or use another "
                               "method");
    if (!*m->adaptive)
        return taylor_check(s, o);
    return EOMC_OK;
}
