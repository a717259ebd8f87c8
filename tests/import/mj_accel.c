/*
 * MuJoCo's q'' of a model at a random state, in the coordinates of eomc's
 * import: the peer eomc's imported models are checked against
 * (test_import.sh).  Contact, joint limits, friction loss and equality
 * constraints are off: the smooth dynamics eomc imports.
 *
 *   mj_accel MODEL SEED   ->   a line of nq coordinates q, a line of nq
 *                              rates q', a line of nu controls (empty
 *                              without actuators), then q'' one per line
 *
 * Controls are neither clamped to their ranges nor forces to theirs, as
 * the import drops both.  The state: each hinge and slide coordinate, each
 * qvel entry and each control uniform
 * in [-1.5, 1.5] (splitmix64, seeded); a ball's or free joint's quaternion
 * four such numbers normalized.  eomc's coordinates are MuJoCo's qpos;
 * its rates are qvel, except that a rotation's are its Euler parameters'
 * rates e' where MuJoCo has the angular velocity w in the joint's own
 * axes (a free joint: after its position's rates, in the world):
 *   w = 2 L(e) e',  e' = L(e)^T w / 2,  e'' = (L(e')^T w + L(e)^T w') / 2
 * with L = [-e1 e0 e3 -e2; -e2 -e3 e0 e1; -e3 e2 -e1 e0], for a unit e
 * with e.e' = 0 (docs/import.md).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <mujoco/mujoco.h>

/* uniform in [-1.5, 1.5), by splitmix64: the same states everywhere */
static double
uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return 3 * ((double)(z >> 11) * 0x1p-53) - 1.5;
}

/* y = L(e)^T w / 2 */
static void
half_LT(const double *e, const double *w, double *y)
{
    const double L[3][4] = {{-e[1], e[0], e[3], -e[2]},
                            {-e[2], -e[3], e[0], e[1]},
                            {-e[3], e[2], -e[1], e[0]}};
    for (int c = 0; c < 4; c++)
        y[c] = (L[0][c] * w[0] + L[1][c] * w[1] + L[2][c] * w[2]) / 2;
}

int
main(int argc, char **argv)
{
    char err[1000] = "";
    mjModel *m = argc == 3 ? mj_loadXML(argv[1], NULL, err, sizeof err) : NULL;
    if (!m) {
        fprintf(stderr, "mj_accel: %s\n", argc == 3 ? err : "usage: mj_accel MODEL SEED");
        return 2;
    }
    m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS |
                           mjDSBL_EQUALITY | mjDSBL_CLAMPCTRL;
    for (int i = 0; i < m->nu; i++)
        m->actuator_forcelimited[i] = 0;
    mjData *d = mj_makeData(m);
    uint64_t seed = strtoull(argv[2], NULL, 10);
    for (int i = 0; i < m->nq; i++)
        d->qpos[i] = uniform(&seed);
    for (int i = 0; i < m->nv; i++)
        d->qvel[i] = uniform(&seed);
    for (int i = 0; i < m->nu; i++)
        d->ctrl[i] = uniform(&seed);
    for (int j = 0; j < m->njnt; j++) { /* unit quaternions */
        int type = m->jnt_type[j];
        if (type == mjJNT_BALL || type == mjJNT_FREE)
            mju_normalize4(d->qpos + m->jnt_qposadr[j] + (type == mjJNT_FREE ? 3 : 0));
    }
    mj_forward(m, d);
    double *v = calloc((size_t)m->nq, sizeof *v), *a = calloc((size_t)m->nq, sizeof *a);
    for (int j = 0; j < m->njnt; j++) {
        int type = m->jnt_type[j], q = m->jnt_qposadr[j], dv = m->jnt_dofadr[j];
        if (type == mjJNT_FREE)
            for (int k = 0; k < 3; k++)
                v[q + k] = d->qvel[dv + k], a[q + k] = d->qacc[dv + k];
        if (type == mjJNT_FREE)
            q += 3, dv += 3;
        if (type == mjJNT_BALL || type == mjJNT_FREE) {
            const double *e = d->qpos + q, *w = d->qvel + dv;
            double e1[4], t1[4], t2[4];
            half_LT(e, w, e1);
            half_LT(e1, w, t1);
            half_LT(e, d->qacc + dv, t2);
            for (int c = 0; c < 4; c++)
                v[q + c] = e1[c], a[q + c] = t1[c] + t2[c];
        } else if (type != mjJNT_FREE) {
            v[q] = d->qvel[dv], a[q] = d->qacc[dv];
        }
    }
    for (int i = 0; i < m->nq; i++)
        printf("%.17g%c", d->qpos[i], i + 1 < m->nq ? ' ' : '\n');
    for (int i = 0; i < m->nq; i++)
        printf("%.17g%c", v[i], i + 1 < m->nq ? ' ' : '\n');
    for (int i = 0; i < m->nu; i++)
        printf("%.17g%s", d->ctrl[i], i + 1 < m->nu ? " " : "");
    printf("\n");
    for (int i = 0; i < m->nq; i++)
        printf("%.17g\n", a[i]);
    free(v);
    free(a);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
