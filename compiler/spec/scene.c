/*
 * scene: the scenes, --fix, the initial state (scene.h), and the
 * integration methods a scene may name (spec.h).
 */
#include "scene.h"

#include "effects.h"
#include "names.h"
#include "view.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The runtime's list of integration methods, the one list of them. */
const char *const spec_methods[] = {
#define METHOD(name, gsl, fixed, jac, description) #name,
#include "runtime/base/methods.def"
#undef METHOD
    NULL,
};
static const char spec_method_jac[] = {
#define METHOD(name, gsl, fixed, jac, description) jac,
#include "runtime/base/methods.def"
#undef METHOD
};

int
spec_method_jacobian(const char *name)
{
    for (int k = 0; spec_methods[k]; k++)
        if (!strcmp(spec_methods[k], name))
            return spec_method_jac[k];
    return -1;
}

static const char *
method_name(Loader *L, yaml_node_t *n)
{
    const char *m = spec_scalar(L, n, "method");
    int count = 0;
    for (; spec_methods[count]; count++)
        if (!strcmp(spec_methods[count], m))
            return spec_methods[count];
    const char *near = diag_nearest(m, spec_methods, count);
    if (near)
        diag_error(spec_loc(L, n), "unknown method '%s'; did you mean %s?", m, near);
    char list[256] = "";
    for (int k = 0; k < count; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "",
                 spec_methods[k]);
    diag_error(spec_loc(L, n), "unknown method '%s'; the methods are %s", m, list);
}

static double
positive(Loader *L, yaml_node_t *n, const char *what, int zero_ok)
{
    double v = spec_number(L, n, what);
    if (v < 0 || (!zero_ok && v == 0))
        diag_error(spec_loc(L, n), "%s must be %s, not %.17g", what,
                   zero_ok ? "zero or positive" : "positive", v);
    return v;
}

/* Command-line errors: no location, "eomc: error: ...". */
static const SrcLoc cmdline = {NULL, 0, 0};

/* The scene to compile: `scene:`, or the named scene of `scenes:` that
 * --scene picks (the first by default).  Every named scene is listed in
 * Spec.scenes. */
yaml_node_t *
spec_pick_scene(Loader *L, yaml_node_t *root)
{
    Spec *s = L->s;
    yaml_node_t *one = spec_section(L, root, "scene", 1);
    yaml_node_t *many = spec_section(L, root, "scenes", 1);
    const char *want = L->opt->scene;
    if (one && many)
        diag_error(spec_key_loc(L, root, "scenes"), "a spec has `scene:` (one scene) or "
                   "`scenes:` (named ones), not both");
    if (!many) {
        if (want)
            diag_error(cmdline, "--scene %s: %s has no named scenes (`scenes:`)", want,
                       L->path);
        return one;
    }
    spec_unique_keys(L, many, "scenes");
    s->nscenes = NPAIRS(many);
    if (s->nscenes == 0)
        diag_error(spec_loc(L, many), "`scenes:` is empty: name at least one scene");
    s->scenes = arena_new_array(L->A, SpecSceneInfo, s->nscenes);
    const char **names = arena_new_array(L->A, const char *, s->nscenes);
    int pick = want ? -1 : 0;
    for (int i = 0; i < s->nscenes; i++) {
        yaml_node_t *k = spec_node(L, PAIRS(many)[i].key);
        const char *name = spec_scalar(L, k, "a scene name");
        if (!spec_is_identifier(name) || strlen(name) > 64)
            diag_error(spec_loc(L, k), "'%s' is not a valid scene name (letters, digits and _, "
                       "not starting with a digit)", name);
        spec_map(L, spec_node(L, PAIRS(many)[i].value), "a scene");
        names[i] = s->scenes[i].name = arena_strdup(L->A, name);
        s->scenes[i].loc = spec_loc(L, k);
        if (want && !strcmp(want, name))
            pick = i;
    }
    if (pick < 0) {
        const char *near = diag_nearest(want, names, s->nscenes);
        if (near)
            diag_error(cmdline, "--scene: unknown scene '%s'; did you mean %s?", want, near);
        char list[1024] = "";
        for (int i = 0; i < s->nscenes; i++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                     names[i]);
        diag_error(cmdline, "--scene: unknown scene '%s'; the scenes of %s are %s", want,
                   L->path, list);
    }
    s->scene.name = s->scenes[pick].name;
    return spec_node(L, PAIRS(many)[pick].value);
}

static int
find_param(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->np + 1);
    for (int i = 0; i < L->s->np; i++)
        cands[i] = L->s->param[i].name;
    return spec_find_in(L, n, "parameter", "parameters", 1, cands, L->s->np);
}

static void
fix_param(Loader *L, int i, double v)
{
    SpecParam *p = &L->s->param[i];
    L->s->nfixed += !p->fixed;
    p->fixed = 1;
    p->value = v;
}

/* A scene's `fix: {NAME: VALUE}`: parameters held at a value.  The
 * scene compiled (L->scene_live) fixes them; the others are only checked.
 * Each entry on its own, as every part of a scene: a scene's mistakes are
 * all found in one run. */
static void
fix_entry(Loader *L, yaml_node_t *map, int i)
{
    int k = find_param(L, spec_node(L, PAIRS(map)[i].key));
    double v = spec_number(L, spec_node(L, PAIRS(map)[i].value), "a fixed parameter's value");
    if (L->scene_live)
        fix_param(L, k, v);
}

static void
load_fix(Loader *L, yaml_node_t *scene, int live)
{
    yaml_node_t *map = spec_lookup(L, scene, "fix");
    if (!map || spec_is_null(map))
        return;
    spec_map(L, map, "fix");
    L->scene_live = live;
    for (int i = 0; i < NPAIRS(map); i++)
        spec_checked(L, fix_entry, map, i);
}

void
spec_live_fix(Loader *L, yaml_node_t *scene, int i)
{
    (void)i;
    spec_map(L, scene, "scene");
    load_fix(L, scene, 1);
}

/* --fix NAME=VALUE,NAME=VALUE: after the scene's, so they win. */
void
spec_fix_option(Loader *L)
{
    Spec *s = L->s;
    for (const char *p = L->opt->fix; p && *p;) {
        size_t len = strcspn(p, ",");
        char item[256];
        snprintf(item, sizeof item, "%.*s", (int)(len < 255 ? len : 255), p);
        p += len;
        p += *p == ',';
        char *eq = strchr(item, '=');
        if (!eq || eq == item)
            diag_error(cmdline, "--fix: expected NAME=VALUE, not '%s'", item);
        *eq = '\0';
        int k = -1;
        for (int i = 0; i < s->np && k < 0; i++)
            if (!strcmp(s->param[i].name, item))
                k = i;
        if (k < 0) {
            const char **cands = arena_new_array(L->A, const char *, s->np + 1);
            for (int i = 0; i < s->np; i++)
                cands[i] = s->param[i].name;
            const char *near = diag_nearest(item, cands, s->np);
            if (near)
                diag_error(cmdline, "--fix: unknown parameter '%s'; did you mean %s?", item,
                           near);
            diag_error(cmdline, "--fix: '%s' is not a parameter of %s", item, L->path);
        }
        char *end;
        errno = 0;
        double v = strtod(eq + 1, &end);
        if (end == eq + 1 || *end || errno == ERANGE || !isfinite(v))
            diag_error(cmdline, "--fix %s: '%s' is not a finite number", item, eq + 1);
        fix_param(L, k, v);
    }
}

/* A scene's `outputs: {NAME: EXPR}`, each on its own. */
static void
output_entry(Loader *L, yaml_node_t *map, int i)
{
    SpecScene *sc = L->scene_into;
    yaml_node_t *k = spec_node(L, PAIRS(map)[i].key);
    const char *name = spec_scalar(L, k, "an output name");
    if (!spec_is_identifier(name) || strlen(name) > 64)
        diag_error(spec_loc(L, k), "'%s' is not a valid output name (letters, digits and _, "
                   "not starting with a digit)", name);
    for (int c = 0; c < L->s->nq; c++)
        if (!strcmp(name, L->s->coord[c].name))
            diag_error(spec_loc(L, k), "output '%s' would repeat the column of coordinate "
                       "'%s': name it differently", name, name);
    sc->output[i].name = arena_strdup(L->A, name);
    sc->output[i].loc = spec_loc(L, k);
    sc->output[i].expr = spec_expr(L, spec_node(L, PAIRS(map)[i].value), ALLOW_OUTPUT,
                                    "an output");
}

static void
load_outputs(Loader *L, yaml_node_t *map, SpecScene *sc)
{
    spec_map(L, map, "outputs");
    sc->noutput = NPAIRS(map);
    sc->output = arena_new_array(L->A, SpecOutput, sc->noutput + 1);
    for (int i = 0; i < sc->noutput; i++)
        spec_checked(L, output_entry, map, i);
}

/* The coordinate (x), velocity (x') or speed (wx) a key names: 2 c, or
 * 2 c + 1 for the leaf coordinate c of a velocity or speed (a speed's is
 * nq + k).  (No node is made: the order of the leaves is the order of
 * first use.) */
static int
state_var(Loader *L, yaml_node_t *k, const char *what)
{
    Spec *s = L->s;
    const char *key = spec_scalar(L, k, what);
    size_t len = strlen(key);
    int vel = len > 1 && key[len - 1] == '\'';
    for (int c = 0; c < s->nq; c++)
        if (strlen(s->coord[c].name) == len - (size_t)vel &&
            !strncmp(s->coord[c].name, key, len - (size_t)vel)) {
            if (vel && s->vslot[c] < 0)
                diag_error(spec_loc(L, k), "'%s' is an Euler parameter whose rate its "
                           "quaternion's speeds give: name a speed", s->coord[c].name);
            return 2 * c + vel;
        }
    for (int j = 0; j < s->nspeed; j++)
        if (!strcmp(s->speed[j].name, key))
            return 2 * (s->nq + j) + 1;
    int nc = 2 * s->nq + s->nspeed;
    const char **cands = arena_new_array(L->A, const char *, nc);
    for (int c = 0; c < s->nq; c++) {
        cands[2 * c] = s->coord[c].name;
        cands[2 * c + 1] = arena_printf(L->A, "%s'", s->coord[c].name);
    }
    for (int j = 0; j < s->nspeed; j++)
        cands[2 * s->nq + j] = s->speed[j].name;
    const char *near = diag_nearest(key, cands, nc);
    if (near)
        diag_error(spec_loc(L, k), "'%s' is not a coordinate or velocity; did you mean %s?",
                   key, near);
    diag_error(spec_loc(L, k), "'%s' is not a coordinate (x) or a velocity (x')", key);
}

/* `initial:` at the top level, or a scene's, which overrides it (live:
 * the scene compiled; the others are only checked). */
static void
initial_value(Loader *L, yaml_node_t *map, int i, int live)
{
    Spec *s = L->s;
    int var = state_var(L, spec_node(L, PAIRS(map)[i].key), "an initial-state name");
    ExprId e = spec_expr(L, spec_node(L, PAIRS(map)[i].value), ALLOW_PARAM, "an initial value");
    if (!live)
        return;
    if (var & 1 && var / 2 >= s->nq)
        s->speed[var / 2 - s->nq].v0 = e;
    else if (var & 1)
        s->coord[var / 2].v0 = e;
    else
        s->coord[var / 2].q0 = e;
}

static void
initial_live(Loader *L, yaml_node_t *map, int i)
{
    initial_value(L, map, i, 1);
}

static void
initial_checked(Loader *L, yaml_node_t *map, int i)
{
    initial_value(L, map, i, 0);
}

void
spec_load_initial(Loader *L, yaml_node_t *map, int live)
{
    for (int i = 0; i < NPAIRS(map); i++)
        spec_checked(L, live ? initial_live : initial_checked, map, i);
}

static void
load_event(Loader *L, yaml_node_t *k, yaml_node_t *map, SpecEvent *ev)
{
    static const char *const keys[] = {"when", "direction", "action", NULL};
    const char *name = spec_scalar(L, k, "an event name");
    if (!spec_is_identifier(name) || strlen(name) > 64)
        diag_error(spec_loc(L, k), "'%s' is not a valid event name (letters, digits and _, "
                   "not starting with a digit)", name);
    ev->name = arena_strdup(L->A, name);
    ev->loc = spec_loc(L, k);
    spec_map(L, map, "an event");
    spec_check_keys(L, map, keys, "an event");
    yaml_node_t *v = spec_lookup(L, map, "when");
    if (!v)
        diag_error(spec_loc(L, map), "event '%s' needs `when:`, the expression whose zero "
                   "crossing it is", name);
    ev->when = spec_expr(L, v, ALLOW_EVENT, "an event's `when`");
    ev->direction = 0;
    if ((v = spec_lookup(L, map, "direction"))) {
        const char *d = spec_scalar(L, v, "direction");
        static const char *const dirs[] = {"up", "down", "both"};
        if (!strcmp(d, "up"))
            ev->direction = 1;
        else if (!strcmp(d, "down"))
            ev->direction = -1;
        else if (strcmp(d, "both")) {
            const char *near = diag_nearest(d, dirs, 3);
            if (near)
                diag_error(spec_loc(L, v), "unknown direction '%s'; did you mean %s?", d, near);
            diag_error(spec_loc(L, v), "unknown direction '%s'; expected up, down or both", d);
        }
    }
    ev->action = EVENT_STOP;
    if (!(v = spec_lookup(L, map, "action")))
        return;
    if (v->type == YAML_SCALAR_NODE) {
        const char *a = spec_scalar(L, v, "action");
        static const char *const acts[] = {"stop", "record", "set"};
        if (!strcmp(a, "record"))
            ev->action = EVENT_RECORD;
        else if (!strcmp(a, "set"))
            diag_error(spec_loc(L, v), "action set needs the values: `action: {set: {\"x'\": "
                       "EXPR}}`");
        else if (strcmp(a, "stop")) {
            const char *near = diag_nearest(a, acts, 3);
            if (near)
                diag_error(spec_loc(L, v), "unknown action '%s'; did you mean %s?", a, near);
            diag_error(spec_loc(L, v), "unknown action '%s'; expected stop, record or "
                       "{set: {...}}", a);
        }
        return;
    }
    static const char *const akeys[] = {"set", NULL};
    spec_map(L, v, "an action");
    spec_check_keys(L, v, akeys, "an action");
    yaml_node_t *set = spec_lookup(L, v, "set");
    if (!set)
        diag_error(spec_loc(L, v), "an action map is {set: {NAME: EXPR, ...}}");
    spec_map(L, set, "set");
    if (NPAIRS(set) == 0)
        diag_error(spec_loc(L, set), "`set:` is empty: name what the event changes");
    ev->action = EVENT_SET;
    ev->nset = NPAIRS(set);
    ev->set_var = arena_new_array(L->A, ExprId, ev->nset);
    ev->set_expr = arena_new_array(L->A, ExprId, ev->nset);
    for (int i = 0; i < ev->nset; i++) {
        int var = state_var(L, spec_node(L, PAIRS(set)[i].key), "a coordinate or velocity");
        ev->set_var[i] = expr_var(L->P, var / 2, var & 1);
        for (int j = 0; j < i; j++)
            if (ev->set_var[j] == ev->set_var[i])
                diag_error(spec_loc(L, spec_node(L, PAIRS(set)[i].key)), "'%s' is set twice",
                           spec_key(L, &PAIRS(set)[i]));
        ev->set_expr[i] = spec_expr(L, spec_node(L, PAIRS(set)[i].value), ALLOW_EVENT,
                                     "a value an event sets");
    }
}

static void
event_entry(Loader *L, yaml_node_t *map, int i)
{
    load_event(L, spec_node(L, PAIRS(map)[i].key), spec_node(L, PAIRS(map)[i].value),
               &L->scene_into->event[i]);
}

static void
load_events(Loader *L, yaml_node_t *map, SpecScene *sc)
{
    spec_map(L, map, "events");
    sc->nevent = NPAIRS(map);
    sc->event = arena_new_array(L->A, SpecEvent, sc->nevent + 1);
    for (int i = 0; i < sc->nevent; i++)
        spec_checked(L, event_entry, map, i);
}

/* One of a scene's `effects:`, turned on in the scene compiled. */
static void
effect_entry(Loader *L, yaml_node_t *seq, int i)
{
    int k = spec_find_effect(L, spec_node(L, ITEMS(seq)[i]));
    if (L->scene_live)
        L->s->effect[k].enabled = 1;
}

/* One name of `assemble: {hold: [...]}`: a coordinate (x) or velocity
 * (x') the assembly keeps as it is. */
static void
hold_entry(Loader *L, yaml_node_t *seq, int i)
{
    yaml_node_t *k = spec_node(L, ITEMS(seq)[i]);
    int var = state_var(L, k, "a coordinate or velocity to hold");
    int n = L->s->nq, at = var & 1 ? n + L->s->vslot[var / 2] : var / 2;
    if (L->scene_into->hold[at])
        diag_error(spec_loc(L, k), "'%s' is held twice", spec_scalar(L, k, "a name"));
    L->scene_into->hold[at] = 1;
}

/* `assemble: true` (every run puts the initial state onto the
 * constraints, moving anything), `false` (runs start as given), or
 * `{hold: [NAME, ...]}` (the assembly keeps these coordinates and
 * velocities as they are). */
static void
load_assemble(Loader *L, yaml_node_t *v, SpecScene *sc)
{
    static const char *const keys[] = {"hold", NULL};
    const char *usage = "`assemble:` is true, false or {hold: [x, y', ...]}";
    sc->assemble = 0;
    sc->hold = NULL;
    if (v->type == YAML_SCALAR_NODE) {
        const char *b = spec_scalar(L, v, "assemble");
        if (strcmp(b, "true") && strcmp(b, "false"))
            diag_error(spec_loc(L, v), "%s, not '%s'", usage, b);
        sc->assemble = !strcmp(b, "true");
    } else {
        if (v->type != YAML_MAPPING_NODE)
            diag_error(spec_loc(L, v), "%s", usage);
        spec_map(L, v, "assemble");
        spec_check_keys(L, v, keys, "`assemble:`");
        yaml_node_t *h = spec_lookup(L, v, "hold");
        if (!h)
            diag_error(spec_loc(L, v), "%s", usage);
        spec_expect(L, h, YAML_SEQUENCE_NODE, "`hold:`, the names the assembly keeps,");
        sc->assemble = 1;
        sc->hold = arena_new_array(L->A, unsigned char, L->s->nq + L->s->nv);
        memset(sc->hold, 0, (size_t)(L->s->nq + L->s->nv));
        for (int i = 0; i < NITEMS(h); i++)
            spec_checked(L, hold_entry, h, i);
    }
    int levels = 0; /* what an assembly moves the state onto */
    for (int c = 0; c < L->s->nconstraint; c++)
        levels |= L->s->constraint[c].order <= 1;
    for (int b = 0; b < L->s->nbody; b++)
        levels |= L->s->body[b].quat[0] >= 0;
    if (sc->assemble && !levels)
        diag_error(spec_loc(L, v), "`assemble:` puts the initial state onto the holonomic and "
                   "first-order constraints, and this spec has none");
}

/* Entry i of a scene (L->scene_into, L->scene_live) but `fix`
 * (load_fix), on its own: an error in one does not hide the others. */
static void
scene_entry(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"effects", "t_end", "dt", "method", "rtol", "atol",
                                       "fixed_step", "fix", "initial", "outputs", "events",
                                       "assemble", "view", NULL};
    SpecScene *sc = L->scene_into;
    int live = L->scene_live;
    spec_check_key(L, map, i, keys, "a scene");
    const char *k = spec_key(L, &PAIRS(map)[i]);
    yaml_node_t *v = spec_node(L, PAIRS(map)[i].value);
    if (!strcmp(k, "effects")) {
        spec_expect(L, v, YAML_SEQUENCE_NODE, "the scene's effects");
        for (int e = 0; e < L->s->neffect && live; e++)
            L->s->effect[e].enabled = 0;
        for (int e = 0; e < NITEMS(v); e++)
            spec_checked(L, effect_entry, v, e);
    } else if (!strcmp(k, "t_end")) {
        sc->t_end = positive(L, v, "t_end", 0);
    } else if (!strcmp(k, "dt")) {
        sc->dt = positive(L, v, "dt", 0);
    } else if (!strcmp(k, "method")) {
        sc->method = method_name(L, v);
    } else if (!strcmp(k, "rtol")) {
        sc->rtol = positive(L, v, "rtol", 1);
    } else if (!strcmp(k, "atol")) {
        sc->atol = positive(L, v, "atol", 1);
    } else if (!strcmp(k, "fixed_step")) {
        sc->h_fixed = positive(L, v, "fixed_step", 1);
    } else if (!strcmp(k, "initial") && !spec_is_null(v)) {
        spec_load_initial(L, spec_map(L, v, "initial"), live);
    } else if (!strcmp(k, "outputs") && !spec_is_null(v)) {
        load_outputs(L, v, sc);
    } else if (!strcmp(k, "events") && !spec_is_null(v)) {
        load_events(L, v, sc);
    } else if (!strcmp(k, "assemble")) {
        load_assemble(L, v, sc);
    } else if (!strcmp(k, "view") && !spec_is_null(v)) {
        spec_load_view(L, v, live);
    }
}

/* The scene's defaults, before its keys. */
const SpecScene spec_scene_defaults = {.t_end = 10.0, .dt = 0.01, .method = "rk8pd",
                                         .rtol = 1e-10, .atol = 1e-10};

/* A scene's keys but `fix` (load_fix), each on its own.  live: the scene
 * compiled, into Spec.scene and the effects' switches; the other scenes
 * are checked into a scratch copy, so that a mistake in any of them is
 * found. */
static void
load_scene(Loader *L, yaml_node_t *map, int live)
{
    SpecScene scratch = spec_scene_defaults, *sc = live ? &L->s->scene : &scratch;
    spec_map(L, map, "scene");
    L->scene_into = sc;
    L->scene_live = live;
    int errors = diag_error_count();
    for (int i = 0; i < NPAIRS(map); i++)
        spec_checked(L, scene_entry, map, i);
    if (diag_error_count() == errors && sc->rtol == 0 && sc->atol == 0 && sc->h_fixed == 0)
        diag_error(spec_loc(L, map), "rtol and atol cannot both be zero for adaptive steps");
}

/* One line for --explain: what a named scene turns on. */
static const char *
scene_summary(Loader *L, yaml_node_t *map)
{
    char buf[1024] = "";
    yaml_node_t *v;
    size_t n;
#define ADD(...) (n = strlen(buf), snprintf(buf + n, sizeof buf - n, __VA_ARGS__))
    if ((v = spec_lookup(L, map, "effects")) && v->type == YAML_SEQUENCE_NODE) {
        ADD("effects:");
        for (int i = 0; i < NITEMS(v); i++)
            ADD(" %s", spec_scalar(L, spec_node(L, ITEMS(v)[i]), "an effect"));
        if (NITEMS(v) == 0)
            ADD(" (none)");
    } else {
        ADD("effects: the spec's");
    }
    static const char *const lists[] = {"fix", "initial", "outputs", "events"};
    for (int j = 0; j < 4; j++) {
        if (!(v = spec_lookup(L, map, lists[j])) || v->type != YAML_MAPPING_NODE)
            continue;
        ADD("; %s:", lists[j]);
        for (int i = 0; i < NPAIRS(v); i++)
            ADD(" %s", spec_key(L, &PAIRS(v)[i]));
    }
    if ((v = spec_lookup(L, map, "assemble")) && v->type == YAML_MAPPING_NODE &&
        (v = spec_lookup(L, v, "hold")) && v->type == YAML_SEQUENCE_NODE) {
        ADD("; assemble, holding:");
        for (int i = 0; i < NITEMS(v); i++)
            ADD(" %s", spec_scalar(L, spec_node(L, ITEMS(v)[i]), "a name"));
    } else if ((v = spec_lookup(L, map, "assemble")) && v->type == YAML_SCALAR_NODE &&
               !strcmp(spec_scalar(L, v, "assemble"), "true")) {
        ADD("; assemble");
    }
#undef ADD
    return arena_strdup(L->A, buf);
}

void
spec_live_scene(Loader *L, yaml_node_t *scene, int i)
{
    (void)i;
    load_scene(L, scene, 1);
}

/* Every named scene is checked, and summarized for --explain. */
void
spec_other_scene(Loader *L, yaml_node_t *scenes, int i)
{
    yaml_node_t *sc = spec_node(L, PAIRS(scenes)[i].value);
    if (sc != L->scene) {
        spec_map(L, sc, "scene");
        load_fix(L, sc, 0);
        load_scene(L, sc, 0);
    }
    L->s->scenes[i].summary = scene_summary(L, sc);
}
