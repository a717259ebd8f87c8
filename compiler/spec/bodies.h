/*
 * bodies: the spec's particles and rigid bodies (`particles:`,
 * `bodies:`), each placed by coordinates, by a point or a frame, and
 * turned by an angle, a rotation sequence, Euler parameters, an angular
 * velocity or a frame.
 */
#ifndef EOMC_SPEC_BODIES_H
#define EOMC_SPEC_BODIES_H

#include "loader.h"

/* Each entry on its own: one that fails keeps a name ("" if even that
 * failed) and is marked in L->bad_part or L->bad_body, so that a force on
 * it is abandoned, not reported as unknown. */
void spec_load_particles(Loader *L, yaml_node_t *map);
void spec_load_bodies(Loader *L, yaml_node_t *map);

#endif
