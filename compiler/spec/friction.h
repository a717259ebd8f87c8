/*
 * friction: dry friction on a coordinate, an effect item
 * `friction: q, force: F` (F >= 0, the largest force it exerts): F
 * against the slip while q' is not 0, and while q is stuck whatever
 * force holds it, as long as that is within F (the runtime's).
 */
#ifndef EOMC_SPEC_FRICTION_H
#define EOMC_SPEC_FRICTION_H

#include "loader.h"

/* The item at map whose `friction:` is v, of effect owner, into f. */
void spec_load_friction(Loader *L, yaml_node_t *map, yaml_node_t *v, const char *owner,
                        SpecForce *f);

#endif
