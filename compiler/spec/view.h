/*
 * view: what a run's page draws (--animate): a body's `shapes:`, the draw
 * items (every body and particle, then the points and frames a view
 * names), and a scene's `view:` (links, traces, frames' axes, camera).
 * All numbers or names: no expression of the model.
 */
#ifndef EOMC_SPEC_VIEW_H
#define EOMC_SPEC_VIEW_H

#include "loader.h"

/* Body `body`'s `shapes:` (a list), appended to Spec.shape. */
void spec_load_shapes(Loader *L, yaml_node_t *seq, int body);
/* The draw items every spec has: its bodies, then its particles (into
 * Spec.view, after both are loaded), then the ground where the spec's
 * `ground:` (a list of shapes, or NULL) draws shapes fixed to the world;
 * and the places (Spec.place): the bodies and particles again, and every
 * frame and point named. */
void spec_draw_items(Loader *L, yaml_node_t *ground);
/* A scene's `view:`: into Spec.view when live (the scene compiled), else
 * only checked. */
void spec_load_view(Loader *L, yaml_node_t *v, int live);

#endif
