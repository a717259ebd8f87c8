/*
 * effects: what acts on the system, in named effects that scenes and
 * --effects turn on and off (gravity, potentials, forces, torques,
 * virtual work, kinetic terms), and the always-on energy terms
 * (`kinetic:`, `potential:`).
 */
#ifndef EOMC_SPEC_EFFECTS_H
#define EOMC_SPEC_EFFECTS_H

#include "loader.h"

/* `effects:`, each effect on its own (after the particles and bodies). */
void spec_load_effects(Loader *L, yaml_node_t *map);
/* `kinetic:` (i = 0) or `potential:` (i = 1) terms of root (an EntryFn). */
void spec_load_energy(Loader *L, yaml_node_t *root, int i);
/* The index of the effect node n names, or an error. */
int spec_find_effect(Loader *L, yaml_node_t *n);

#endif
