/*
 * frames: the spec's frames and points (`frames:`, `points:`, kin.h) and
 * its defines, the items built from other names, each after the items it
 * names (a cycle is an error at its first step).
 */
#ifndef EOMC_SPEC_FRAMES_H
#define EOMC_SPEC_FRAMES_H

#include "names.h"

/* Every define, frame and point named, as items of L->def (L->K made for
 * them); then each resolved after the items it uses. */
void spec_name_items(Loader *L, yaml_node_t *defines, yaml_node_t *frames, yaml_node_t *points);
void spec_resolve_defines(Loader *L);
/* The Euler parameters [e0, e1, e2, e3] at v, of `owner` ("body 'top'"):
 * four distinct coordinates, none another quaternion's, into q. */
void spec_quaternion_coords(Loader *L, yaml_node_t *v, const char *owner, int q[4]);
/* The speeds of the frames' turns and the bodies' rotations (`speeds:`
 * beside a quaternion): how many, before the names are kept; then each
 * named (Spec.speed), as the other names are, before any expression. */
int spec_count_speeds(Loader *L, yaml_node_t *frames, yaml_node_t *bodies);
void spec_name_speeds(Loader *L, yaml_node_t *frames, yaml_node_t *bodies);
/* A quaternion's `speeds:` list sp (named above): *first, the index of its
 * first speed, their leaves w, and the Euler parameters q's rates from
 * them (expr_set_rate). */
void spec_quaternion_speeds(Loader *L, yaml_node_t *sp, const int q[4], int *first, ExprId w[3]);
/* Spec.nv, vcoord and vslot, once every frame and body is read. */
void spec_velocity_slots(Loader *L);

#endif
