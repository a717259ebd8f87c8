/*
 * eomc's side of the contact benchmark (bench/contact_bench.sh): one
 * generated model (-DMODEL=NAME_model) at its spec's initial state, its
 * modes those of the state (each switch on where its function is > 0,
 * again until none changes: the runtime's rule at a run's start).  It
 * prints
 *   ns per right-hand side: the model's accel (M, h and their unrolled
 *      solve; mass_bias where it has none), as a run calls it, the modes
 *      held
 *   ns per call of its switches (the step's end and each trial time
 *      of a located switch evaluate them all)
 *   the modes on, all, and the near switches on (contact pairs near,
 *      EFFECT.A.B.near)
 * each the best of 9 runs of enough calls for 50 ms.  The state is
 * perturbed by 1e-12 from call to call, so that nothing is hoisted.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "eomc.h"

extern const eomc_model MODEL;

static double
now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct Work {
    const eomc_model *m;
    const double *p;
    double *q, *v, *u, *M, *a, *sw, q0, sum;
    int what; /* 0: the right-hand side, 1: the switches */
} Work;

static void
run(Work *w, long calls)
{
    const eomc_model *m = w->m;
    for (long k = 0; k < calls; k++) {
        w->q[0] = w->q0 + 1e-12 * (double)(k & 1); /* defeat hoisting */
        if (w->what)
            m->switches(0, w->q, w->v, w->p, w->u, w->sw);
        else if (m->accel)
            m->accel(0, w->q, w->v, w->p, w->u, w->a, NULL);
        else
            m->mass_bias(0, w->q, w->v, w->p, w->u, w->M, w->a);
        w->sum += w->what ? w->sw[0] : w->a[eomc_nv(m) - 1];
    }
}

static double
best_ns(Work *w)
{
    long calls = 1;
    double t0, t1, best;
    do {
        calls *= 4;
        t0 = now();
        run(w, calls);
        t1 = now();
    } while (t1 - t0 < 0.05);
    best = t1 - t0;
    for (int r = 0; r < 9; r++) {
        t0 = now();
        run(w, calls);
        t1 = now();
        if (t1 - t0 < best)
            best = t1 - t0;
    }
    return best / (double)calls * 1e9;
}

int
main(void)
{
    const eomc_model *m = &MODEL;
    eomc_sim *s = eomc_sim_alloc(m);
    if (!s)
        return 1;
    int nv = eomc_nv(m), nm = m->nmode;
    Work w = {m, eomc_sim_params(s), calloc((size_t)m->nq + 1, sizeof(double)),
              calloc((size_t)nv + 1, sizeof(double)),
              calloc((size_t)(m->nu + nm) + 1, sizeof(double)),
              calloc((size_t)nv * (size_t)nv + 1, sizeof(double)),
              calloc((size_t)nv + 1, sizeof(double)), calloc((size_t)nm + 1, sizeof(double)),
              0, 0, 0};
    eomc_sim_initial(s, w.q, w.v);
    eomc_sim_inputs(s, 0, w.u);
    w.q0 = w.q[0];
    int on = 0;
    for (int pass = 0; nm && pass <= nm; pass++) {
        int changed = 0;
        m->switches(0, w.q, w.v, w.p, w.u, w.sw);
        on = 0;
        for (int k = 0; k < nm; k++) {
            double mode = w.sw[k] > 0;
            changed |= mode != w.u[m->nu + k];
            w.u[m->nu + k] = mode;
            on += w.sw[k] > 0;
        }
        if (!changed)
            break;
    }
    double rhs = best_ns(&w), sw = -1;
    if (nm) {
        w.what = 1;
        sw = best_ns(&w);
    }
    int near = 0;
    for (int k = 0; k < nm; k++) {
        const char *name = m->sw_names ? m->sw_names[k] : "";
        size_t len = strlen(name);
        near += w.u[m->nu + k] != 0 && len > 5 && !strcmp(name + len - 5, ".near");
    }
    printf("%.1f %.1f %d %d %d\n", rhs, sw, on, nm, near);
    fprintf(stderr, "(checksum %g)\n", w.sum);
    eomc_sim_free(s);
    return 0;
}
