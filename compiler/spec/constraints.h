/*
 * constraints: `constraints:`, each classified by the highest derivative
 * of a coordinate in it, and the unit constraints of Euler parameters.
 */
#ifndef EOMC_SPEC_CONSTRAINTS_H
#define EOMC_SPEC_CONSTRAINTS_H

#include "loader.h"

/* `constraints:`, each on its own (fewer than the coordinates). */
void spec_load_constraints(Loader *L, yaml_node_t *map);
/* NAME_unit for every quaternion of a body or a frame, after the spec's
 * own constraints (once the initial values are read). */
void spec_unit_constraints(Loader *L);

#endif
