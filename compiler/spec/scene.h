/*
 * scene: what a run does, besides the model: the scene compiled
 * (`scene:`, or one of `scenes:` that --scene picks) with its effects,
 * times, method, tolerances, fixed parameters, initial state, outputs,
 * events and assembly; --fix; and the other named scenes, checked and
 * summarized for --explain.
 */
#ifndef EOMC_SPEC_SCENE_H
#define EOMC_SPEC_SCENE_H

#include "loader.h"

/* The scene's defaults, before its keys. */
extern const SpecScene spec_scene_defaults;

/* The scene to compile (L->opt->scene picks among `scenes:`), or NULL;
 * Spec.scenes names them all. */
yaml_node_t *spec_pick_scene(Loader *L, yaml_node_t *root);
/* Its `fix:` (an EntryFn on the scene's map), then --fix, which wins. */
void spec_live_fix(Loader *L, yaml_node_t *scene, int i);
void spec_fix_option(Loader *L);
/* `initial:` at the top level (live: its values are kept). */
void spec_load_initial(Loader *L, yaml_node_t *map, int live);
/* The scene compiled, but its `fix:` (an EntryFn on its map). */
void spec_live_scene(Loader *L, yaml_node_t *scene, int i);
/* Named scene i of `scenes:` checked (the one compiled is already read)
 * and summarized in Spec.scenes (an EntryFn). */
void spec_other_scene(Loader *L, yaml_node_t *scenes, int i);

#endif
