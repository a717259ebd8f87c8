/*
 * contacts: an effect's `contact:` item: which pairs of shapes push each
 * other apart where they overlap (all that the shapes' filters pair, or
 * the pairs it lists), and the normal force's stiffness and damping.  The
 * force itself is mechanics' (mechanics/contact.c).
 */
#ifndef EOMC_SPEC_CONTACTS_H
#define EOMC_SPEC_CONTACTS_H

#include "loader.h"

/* The contact item map of effect L->sc.owner into f (FORCE_CONTACT). */
void spec_load_contact(Loader *L, yaml_node_t *map, SpecForce *f);

#endif
