/*
 * ns per mj_forward of a MuJoCo model (Debian's libmujoco-dev), the peer
 * the chain and tree benchmarks time beside eomc's right-hand side:
 * contact, limits and friction loss off, so that it computes what eomc's
 * does (positions, velocities, M, its factorization, q''), at the state
 * rhs_bench.c sets (q_i = 0.3/(i + 1), q_i' = 0.2).  The same timing rule
 * as rhs_bench.c: the best of 9 runs of enough calls for 50 ms.
 *
 *   mj_bench MODEL.xml   (specs/gen_chain.sh N --mjcf, specs/gen_tree.sh N --mjcf)
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <time.h>

static double
now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double
calls(const mjModel *m, mjData *d, long n)
{
    double sum = 0, t0 = now();
    for (long k = 0; k < n; k++) {
        d->qpos[0] = 0.3 + 1e-9 * (double)k; /* as rhs_bench.c: nothing to hoist */
        mj_forward(m, d);
        sum += d->qacc[m->nv - 1];
    }
    double t = now() - t0;
    return sum == sum ? t : -t; /* keeps the results alive */
}

int
main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: mj_bench MODEL.xml\n");
        return 2;
    }
    char err[1000] = "";
    mjModel *m = mj_loadXML(argv[1], NULL, err, sizeof err);
    if (!m) {
        fprintf(stderr, "mj_bench: %s: %s\n", argv[1], err);
        return 2;
    }
    m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS;
    mjData *d = mj_makeData(m);
    for (int i = 0; i < m->nq; i++)
        d->qpos[i] = 0.3 / (i + 1);
    for (int i = 0; i < m->nv; i++)
        d->qvel[i] = 0.2;
    long n = 1;
    double t;
    do {
        n *= 4;
        t = calls(m, d, n);
    } while (t < 0.05);
    double best = t;
    for (int r = 0; r < 9; r++) {
        t = calls(m, d, n);
        if (t < best)
            best = t;
    }
    printf("%.1f\n", best / (double)n * 1e9);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
