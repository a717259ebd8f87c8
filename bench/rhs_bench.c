/*
 * ns per right-hand side (generated M and h, then the runtime's solve) of
 * one generated model, a check that the right-hand side allocates
 * nothing, and ns per call of the model's full Jacobian (jacobian
 * member); each the median over stack placements of the best of 9
 * timed runs (see best_ns).  Compiled by chain_bench.sh
 * with -DMODEL=chainN_model and -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc.
 * With -DMODEL_EXT=treeN_model_ext (the same C compiled a second time with
 * -DEOMC_EXTENDED, tree_bench.sh) it also prints how far the double q''
 * is from the model's own long-double solution, relative to its largest
 * entry (nan where the model has no accel member to run in long double).
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "eomc.h"

extern const eomc_model MODEL;

static long nalloc;
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n) { nalloc++; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t k) { nalloc++; return __real_calloc(n, k); }
void *__wrap_realloc(void *p, size_t n) { nalloc++; return __real_realloc(p, n); }

static double
now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct Work {
    eomc_sim *sim;
    const eomc_model *m;
    double *q, *v, *a, *u, *dEdq, *dEdv, *dEdu, *dEdt;
    double sum; /* keeps the results alive */
} Work;

static void
rhs_calls(Work *w, long calls)
{
    for (long k = 0; k < calls; k++) {
        w->q[0] = 0.3 + 1e-9 * (double)k; /* defeat hoisting */
        eomc_sim_accel(w->sim, 0.0, w->q, w->v, w->a);
        w->sum += w->a[eomc_nv(w->m) - 1];
    }
}

static void
jac_calls(Work *w, long calls)
{
    int n = w->m->nq;
    for (long k = 0; k < calls; k++) {
        w->q[0] = 0.3 + 1e-9 * (double)k;
        w->m->jacobian(0.0, w->q, w->v, w->a, eomc_sim_params(w->sim), w->u, w->dEdq, w->dEdv,
                       w->dEdu, w->dEdt);
        w->sum += w->dEdq[n * n - 1];
    }
}

#ifdef MODEL_EXT
extern const eomc_model_ext MODEL_EXT;

static double
qdd_error(const eomc_model *m, eomc_sim *sim, const double *q, const double *v)
{
    const eomc_model_ext *x = &MODEL_EXT;
    int n = m->nq, np = m->np, nd = m->nd;
    if (!x->accel || m->nu > 0)
        return NAN;
    double *a = calloc((size_t)n, sizeof *a);
    eomc_ext *p = calloc((size_t)(np + nd + 1), sizeof *p);
    eomc_ext *qe = calloc((size_t)n, sizeof *qe), *ve = calloc((size_t)n, sizeof *ve);
    eomc_ext *ae = calloc((size_t)n, sizeof *ae), u[1] = {0};
    for (int k = 0; k < np; k++)
        p[k] = m->p_default[k];
    if (x->derive)
        x->derive(p, p + np);
    for (int i = 0; i < n; i++)
        qe[i] = q[i], ve[i] = v[i];
    double err = NAN;
    if (eomc_sim_accel(sim, 0.0, q, v, a) == EOMC_OK && x->accel(0, qe, ve, p, u, ae, NULL) == 0) {
        eomc_ext dmax = 0, amax = 0;
        for (int i = 0; i < eomc_nv(m); i++) { /* a: one per speed */
            eomc_ext d = fabsl((eomc_ext)a[i] - ae[i]), s = fabsl(ae[i]);
            dmax = d > dmax ? d : dmax;
            amax = s > amax ? s : amax;
        }
        err = (double)(dmax / amax);
    }
    free(a);
    free(p);
    free(qe);
    free(ve);
    free(ae);
    return err;
}
#endif

/* ns per call: enough calls for 50 ms, then the best of 9 such runs (the
 * minimum filters out the time other processes take from this one). */
static double
best_ns_here(void (*run)(Work *, long), Work *w)
{
    long calls = 1;
    double t0, t1;
    do {
        calls *= 4;
        t0 = now();
        run(w, calls);
        t1 = now();
    } while (t1 - t0 < 0.05);
    double best = t1 - t0;
    for (int r = 0; r < 9; r++) {
        t0 = now();
        run(w, calls);
        t1 = now();
        if (t1 - t0 < best)
            best = t1 - t0;
    }
    return best / (double)calls * 1e9;
}

/* The same from `depth` frames of 512 bytes further down the stack. */
static double
at_depth(void (*run)(Work *, long), Work *w, int depth)
{
    volatile char pad[512];
    pad[0] = (char)depth;
    if (depth == 0)
        return best_ns_here(run, w);
    return at_depth(run, w, depth - 1) + 0 * pad[0];
}

static int
cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The cost depends on where the stack lies relative to the heap (the
 * generated code spills to the stack; addresses equal mod 4096 make loads
 * wait for unrelated stores): 121 or 160 ns for the 5-link chain,
 * depending on the size of the environment.  So: the median over 8 stack
 * placements 512 bytes apart, with the least and most on stderr. */
static double
best_ns(void (*run)(Work *, long), Work *w, const char *what)
{
    double ns[8];
    for (int d = 0; d < 8; d++)
        ns[d] = at_depth(run, w, d);
    qsort(ns, 8, sizeof ns[0], cmp_double);
    fprintf(stderr, "%s: %.1f to %.1f ns over 8 stack placements\n", what, ns[0], ns[7]);
    return 0.5 * (ns[3] + ns[4]);
}

int
main(void)
{
    const eomc_model *m = &MODEL;
    int n = m->nq;
    eomc_sim *sim = eomc_sim_alloc(m);
    double *q = calloc((size_t)n, sizeof *q), *v = calloc((size_t)n, sizeof *v);
    double *a = calloc((size_t)n, sizeof *a), sum = 0;
    for (int i = 0; i < n; i++) {
        q[i] = 0.3 / (i + 1);
        v[i] = 0.2;
    }
    double *dEdq = calloc((size_t)n * (size_t)n, sizeof *dEdq);
    double *dEdv = calloc((size_t)n * (size_t)n, sizeof *dEdv);
    double *dEdt = calloc((size_t)n, sizeof *dEdt);
    double *dEdu = calloc((size_t)(n * m->nu + 1), sizeof *dEdu);
    double *u = calloc((size_t)m->nu + 1, sizeof *u);
    Work w = {sim, m, q, v, a, u, dEdq, dEdv, dEdu, dEdt, 0};
    /* a model built without its Jacobian (eomc_model.h) has none to time */
    double ns_rhs = best_ns(rhs_calls, &w, "rhs");
    double ns_jac = m->jacobian ? best_ns(jac_calls, &w, "jacobian") : NAN;
    sum = w.sum;
    long before = nalloc;
    for (int k = 0; k < 1000; k++)
        eomc_sim_accel(sim, 0.0, q, v, a);
    long allocs = nalloc - before;
    for (int i = 0; i < n; i++) /* the timed state, q[0] back where it started */
        q[i] = 0.3 / (i + 1);
#ifdef MODEL_EXT
    double err = qdd_error(m, sim, q, v);
#else
    double err = NAN;
#endif
    printf("%.1f %ld %.0f %.2g\n", ns_rhs, allocs, ns_jac, err);
    fprintf(stderr, "(checksum %g)\n", sum);
    eomc_sim_free(sim);
    free(q);
    free(v);
    free(a);
    free(dEdq);
    free(dEdv);
    free(dEdt);
    free(dEdu);
    free(u);
    return allocs != 0;
}
