/*
 * mj_pairs: the geom pairs MuJoCo's collision driver makes contacts of, at
 * the model's qpos0, each once as "NAME1 NAME2" (sorted within the pair),
 * for test_import_contact.sh to hold eomc import's pairs against: a model
 * whose geoms all overlap at qpos0 has every pair MuJoCo's filters keep.
 * With --rest T K: qpos[K] after MuJoCo's own steps to time T instead,
 * where a model comes to rest by MuJoCo's contacts.
 * usage: mj_pairs MODEL.xml [--rest T K]
 */
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int
main(int argc, char **argv)
{
    char err[1000];
    if (argc != 2 && !(argc == 5 && !strcmp(argv[2], "--rest"))) {
        fprintf(stderr, "usage: mj_pairs MODEL.xml [--rest T K]\n");
        return 2;
    }
    mjModel *m = mj_loadXML(argv[1], NULL, err, sizeof err);
    if (!m) {
        fprintf(stderr, "mj_pairs: %s\n", err);
        return 1;
    }
    mjData *d = mj_makeData(m);
    if (argc == 5) {
        double T = atof(argv[3]);
        while (d->time < T)
            mj_step(m, d);
        printf("%.17g\n", d->qpos[atoi(argv[4])]);
        mj_deleteData(d);
        mj_deleteModel(m);
        return 0;
    }
    mj_forward(m, d);
    for (int c = 0; c < d->ncon; c++) {
        int a = d->contact[c].geom1, b = d->contact[c].geom2, seen = 0;
        for (int e = 0; e < c && !seen; e++) /* a box on a plane: several, one pair */
            seen = (d->contact[e].geom1 == a && d->contact[e].geom2 == b) ||
                   (d->contact[e].geom1 == b && d->contact[e].geom2 == a);
        if (seen)
            continue;
        const char *na = mj_id2name(m, mjOBJ_GEOM, a), *nb = mj_id2name(m, mjOBJ_GEOM, b);
        if (strcmp(na, nb) > 0) {
            const char *t = na;
            na = nb, nb = t;
        }
        printf("%s %s\n", na, nb);
    }
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
