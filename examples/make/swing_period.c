/*
 * swing_period: a program of one's own around a model eomc generated.
 * It prints q'' at theta = 0.5, then the time at which the pendulum,
 * released from rest at theta0 = 1, first comes back to rest at -theta0
 * (half its period), found by integrating with the runtime.
 */
#include <math.h>
#include <stdio.h>

#include "eomc.h"

extern const eomc_model pendulum_model;

/* The first time theta' turns positive again: the far end of the swing. */
typedef struct Watch {
    double t_prev, v_prev, t_turn;
} Watch;

static int
watch(void *ctx, double t, const double *x)
{
    Watch *w = ctx;
    if (t > 0 && w->v_prev < 0 && x[1] >= 0 && isnan(w->t_turn))
        w->t_turn = w->t_prev - w->v_prev * (t - w->t_prev) / (x[1] - w->v_prev);
    w->t_prev = t, w->v_prev = x[1];
    return 0;
}

int
main(void)
{
    eomc_sim *sim = eomc_sim_alloc(&pendulum_model);
    if (!sim)
        return 1;
    double q[1] = {0.5}, v[1] = {0}, a[1];
    if (eomc_sim_accel(sim, 0, q, v, a) != EOMC_OK)
        return 1;
    printf("theta'' %.17g\n", a[0]);
    eomc_run_opts o = eomc_run_defaults(&pendulum_model);
    o.t_end = 1.5, o.dt = 1e-4;
    double x[2];
    eomc_sim_initial(sim, x, x + 1);
    Watch w = {0, 0, NAN};
    if (eomc_sim_integrate(sim, &o, x, watch, &w, NULL) != EOMC_OK)
        return 1;
    printf("half_period %.6f\n", w.t_turn);
    eomc_sim_free(sim);
    return 0;
}
