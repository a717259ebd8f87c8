/*
 * stops: an effect item `limit: q` (docs/spec.md, "Stops"): compliant
 * stops at the ends of a coordinate's range, written as the virtual work
 * of their switched forces.
 */
#ifndef EOMC_SPEC_STOPS_H
#define EOMC_SPEC_STOPS_H

#include "loader.h"

/* The item map (whose `limit:` is v) of effect `owner` into f, a
 * FORCE_WORK: the stops' generalized force on q times delta(q). */
void spec_load_stop(Loader *L, yaml_node_t *map, yaml_node_t *v, const char *owner,
                    SpecForce *f);

#endif
