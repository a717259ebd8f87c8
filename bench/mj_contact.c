/*
 * MuJoCo's side of the contact benchmark (bench/contact_bench.sh), on
 * one MJCF model with a free root standing on its floor:
 *
 *   mj_contact MODEL.xml pairs      the pairs of bodies MuJoCo lets touch,
 *                                   one "A B" a line ("ground" for the
 *                                   world's geoms): contype/conaffinity,
 *                                   never two geoms of one welded body nor
 *                                   of a welded parent and child (the
 *                                   world excepted), as mj_collision's
 *                                   broadphase
 *   mj_contact MODEL.xml drop       how far to lower qpos0's root for its
 *                                   lowest geom to go 1 mm into the floor
 *                                   (z = 0): capsules, spheres and boxes
 *   mj_contact MODEL.xml time DZ [frictionless]
 *                                   ns per mj_forward with contact on at
 *                                   qpos0 lowered by DZ, at rest (limits
 *                                   and friction loss off, as eomc's
 *                                   import), and the contacts it finds;
 *                                   frictionless: every geom condim 1
 *
 *   mj_contact MODEL.xml fall T H DT
 *                                   the model let go at qpos0 at rest,
 *                                   stepped by mj_step at step H to T
 *                                   (all of MuJoCo's effects on, as the
 *                                   model says): first "cpu SECONDS
 *                                   STEPS", then at every DT a row "t
 *                                   qpos qvel"
 *
 * The timing rule is mj_bench.c's: the best of 9 runs of enough calls
 * for 50 ms.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* the penetration of the lowest geom at the state timed */
#define SINK 1e-3

static double
now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* CPU seconds, as eomc's cpu_seconds counts them */
static double
cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static const char *
body_name(const mjModel *m, int b)
{
    return b == 0 ? "ground" : mj_id2name(m, mjOBJ_BODY, b);
}

/* Body pairs with a geom pair the broadphase keeps, each once. */
static void
pairs(const mjModel *m)
{
    char *seen = calloc((size_t)m->nbody * (size_t)m->nbody, 1);
    for (int g1 = 0; g1 < m->ngeom; g1++)
        for (int g2 = g1 + 1; g2 < m->ngeom; g2++) {
            int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
            int w1 = m->body_weldid[b1], w2 = m->body_weldid[b2];
            if (w1 == w2 || !((m->geom_contype[g1] & m->geom_conaffinity[g2]) ||
                              (m->geom_contype[g2] & m->geom_conaffinity[g1])))
                continue;
            int p1 = m->body_weldid[m->body_parentid[w1]], p2 = m->body_weldid[m->body_parentid[w2]];
            if (w1 != 0 && w2 != 0 && (p1 == w2 || p2 == w1))
                continue;
            int lo = b1 < b2 ? b1 : b2, hi = b1 < b2 ? b2 : b1;
            if (seen[lo * m->nbody + hi]++)
                continue;
            printf("%s %s\n", body_name(m, lo), body_name(m, hi));
        }
    free(seen);
}

/* The lowest point of the geoms not on the world, at d's state. */
static double
lowest(const mjModel *m, const mjData *d)
{
    double low = INFINITY;
    for (int g = 0; g < m->ngeom; g++) {
        if (m->geom_bodyid[g] == 0)
            continue;
        const double *R = d->geom_xmat + 9 * g, *s = m->geom_size + 3 * g;
        double z = d->geom_xpos[3 * g + 2];
        switch (m->geom_type[g]) {
        case mjGEOM_SPHERE:
            z -= s[0];
            break;
        case mjGEOM_CAPSULE:
            z -= s[0] + s[1] * fabs(R[8]);
            break;
        case mjGEOM_BOX:
            z -= s[0] * fabs(R[6]) + s[1] * fabs(R[7]) + s[2] * fabs(R[8]);
            break;
        default:
            continue;
        }
        if (z < low)
            low = z;
    }
    return low;
}

static double
calls(const mjModel *m, mjData *d, long n, double z)
{
    double sum = 0, t0 = now();
    for (long k = 0; k < n; k++) {
        d->qpos[2] = z + 1e-12 * (double)(k & 1); /* nothing to hoist */
        mj_forward(m, d);
        sum += d->qacc[m->nv - 1];
    }
    double t = now() - t0;
    return sum == sum ? t : -t;
}

/* The fall to T at step H (the state kept at every DT, printed after
 * the time, which printing would spoil); 0, or 2 where T/H or T/DT is
 * not a whole number of steps. */
static int
fall(const mjModel *m0, mjData *d, double T, double H, double DT)
{
    mjModel *m = mj_copyModel(NULL, m0);
    m->opt.timestep = H;
    long steps = lround(T / H), every = lround(DT / H), nrow = steps / every + 1;
    if (steps < 1 || every < 1 || fabs(steps * H - T) > 1e-9 * T || fabs(every * H - DT) > 1e-9 * DT) {
        fprintf(stderr, "mj_contact: fall: T and DT must be whole numbers of steps H\n");
        mj_deleteModel(m);
        return 2;
    }
    int w = 1 + m->nq + m->nv;
    double *rows = malloc((size_t)nrow * (size_t)w * sizeof *rows);
    mj_resetData(m, d);
    double t0 = cpu_now();
    for (long k = 0, r = 0; k <= steps; k++) {
        if (k % every == 0 && r < nrow) {
            double *row = rows + r++ * w;
            row[0] = d->time;
            mju_copy(row + 1, d->qpos, m->nq);
            mju_copy(row + 1 + m->nq, d->qvel, m->nv);
        }
        if (k < steps)
            mj_step(m, d);
    }
    printf("cpu %.6f %ld\n", cpu_now() - t0, steps);
    for (long r = 0; r < nrow; r++)
        for (int i = 0; i < w; i++)
            printf("%.17g%c", rows[r * w + i], i + 1 < w ? ' ' : '\n');
    free(rows);
    mj_deleteModel(m);
    return 0;
}

int
main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: mj_contact MODEL.xml pairs|drop|time DZ [frictionless]|fall T H DT\n");
        return 2;
    }
    char err[1000] = "";
    mjModel *m = mj_loadXML(argv[1], NULL, err, sizeof err);
    if (!m) {
        fprintf(stderr, "mj_contact: %s: %s\n", argv[1], err);
        return 2;
    }
    if (m->njnt < 1 || m->jnt_type[0] != mjJNT_FREE) {
        fprintf(stderr, "mj_contact: %s: the first joint is not a free root\n", argv[1]);
        return 2;
    }
    mjData *d = mj_makeData(m);
    int rc = 0;
    if (!strcmp(argv[2], "pairs")) {
        pairs(m);
    } else if (!strcmp(argv[2], "drop")) {
        mj_kinematics(m, d);
        printf("%.17g\n", lowest(m, d) + SINK);
    } else if (!strcmp(argv[2], "time") && argc >= 4) {
        m->opt.disableflags |= mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS;
        for (int g = 0; argc > 4 && !strcmp(argv[4], "frictionless") && g < m->ngeom; g++)
            m->geom_condim[g] = 1;
        double z = m->qpos0[2] - atof(argv[3]);
        mju_copy(d->qpos, m->qpos0, m->nq);
        long n = 1;
        double t;
        do {
            n *= 4;
            t = calls(m, d, n, z);
        } while (t < 0.05);
        double best = t;
        for (int r = 0; r < 9; r++) {
            t = calls(m, d, n, z);
            if (t < best)
                best = t;
        }
        printf("%.1f %d\n", best / (double)n * 1e9, d->ncon);
    } else if (!strcmp(argv[2], "fall") && argc >= 6) {
        rc = fall(m, d, atof(argv[3]), atof(argv[4]), atof(argv[5]));
    } else {
        fprintf(stderr, "mj_contact: unknown request '%s'\n", argv[2]);
        rc = 2;
    }
    mj_deleteData(d);
    mj_deleteModel(m);
    return rc;
}
