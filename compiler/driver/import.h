/*
 * import: a robot model in MJCF or URDF, loaded and compiled by MuJoCo
 * (mj_loadXML), written as an eomc spec (docs/import.md): frames, points
 * and bodies, names from the model.  MuJoCo decides everything its
 * compiler decides (defaults, classes, inertias from geoms, units); this
 * module reads the compiled model and prints, nothing more.
 */
#ifndef EOMC_IMPORT_H
#define EOMC_IMPORT_H

#include "import_where.h"

#include <stddef.h>
#include <stdio.h>

/* Whether this eomc was built with MuJoCo (libmujoco-dev). */
int import_available(void);

/* What `eomc import` is asked for besides the model (docs/import.md). */
typedef struct ImportOptions {
    int floating;     /* a URDF's root links given free joints */
    int strict;       /* what would be dropped is an error */
    int joint_inputs; /* an input tau_J on each joint but a free one (a URDF's always) */
    int parameters;   /* masses, inertias, damping, stiffness, armature as parameters */
} ImportOptions;

/* The spec of the model at path onto out, as opt asks, what it drops named
 * on warn (with opt->strict, an error).  0, or -1 with the reason in err
 * (MuJoCo's loader message, or what cannot be imported) and where it is
 * in *at. */
int import_model(const char *path, const ImportOptions *opt, FILE *out, FILE *warn, char *err,
                 size_t len, ImportWhere *at);

#endif
