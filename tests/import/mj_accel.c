/*
 * MuJoCo's q'' of a model at a state: the peer eomc's imported models are
 * checked against (test_import.sh).  Contact, joint limits, friction loss
 * and equality constraints are off: the smooth dynamics eomc imports.
 *
 *   mj_accel MODEL.xml q_1 .. q_nq v_1 .. v_nv   ->   one qacc per line
 */
#include <stdio.h>
#include <stdlib.h>

#include <mujoco/mujoco.h>

int
main(int argc, char **argv)
{
    char err[1000] = "";
    mjModel *m = argc > 1 ? mj_loadXML(argv[1], NULL, err, sizeof err) : NULL;
    if (!m) {
        fprintf(stderr, "mj_accel: %s\n", argc > 1 ? err : "usage: mj_accel MODEL q.. v..");
        return 2;
    }
    if (argc != 2 + m->nq + m->nv) {
        fprintf(stderr, "mj_accel: %d values given, the model has nq = %d, nv = %d\n", argc - 2,
                m->nq, m->nv);
        return 2;
    }
    m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS |
                           mjDSBL_EQUALITY;
    mjData *d = mj_makeData(m);
    for (int i = 0; i < m->nq; i++)
        d->qpos[i] = strtod(argv[2 + i], NULL);
    for (int i = 0; i < m->nv; i++)
        d->qvel[i] = strtod(argv[2 + m->nq + i], NULL);
    mj_forward(m, d);
    for (int i = 0; i < m->nv; i++)
        printf("%.17g\n", d->qacc[i]);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
