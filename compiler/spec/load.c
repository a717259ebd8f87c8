/*
 * load: spec_load, the phases of a load in their order (loader.h), each
 * section read by the file of its concept.
 */
#include "loader.h"

#include "bodies.h"
#include "checks.h"
#include "constraints.h"
#include "effects.h"
#include "fold.h"
#include "frames.h"
#include "names.h"
#include "scene.h"
#include "view.h"
#include "yaml.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

enum { MAX_SPEC_BYTES = 16 << 20 };

/* The spec's name: `name:`, or the file's base name made an identifier. */
static const char *
spec_name(Loader *L, yaml_node_t *n)
{
    if (n) {
        const char *name = spec_scalar(L, n, "name");
        if (!spec_is_identifier(name) || strlen(name) > 64)
            diag_error(spec_loc(L, n), "name '%s' must be a C identifier (letters, digits, _)",
                       name);
        return arena_strdup(L->A, name);
    }
    const char *base = strrchr(L->path, '/');
    base = base ? base + 1 : L->path;
    size_t len = strcspn(base, ".");
    if (len > 64)
        len = 64;
    char *name = arena_alloc(L->A, len + 3);
    size_t k = 0;
    if (len == 0 || (base[0] >= '0' && base[0] <= '9'))
        name[k++] = 'm', name[k++] = '_';
    for (size_t i = 0; i < len; i++)
        name[k++] = spec_is_identifier((char[]){'a', base[i], 0}) ? base[i] : '_';
    return name;
}

static const char *const top_keys[] = {
    "name", "description", "parameters", "coordinates", "define", "frames", "points", "inputs",
    "particles", "bodies", "ground", "kinetic", "potential", "effects", "constraints",
    "initial", "scene", "scenes",
    NULL,
};

static void
load_root(Loader *L, yaml_node_t *root)
{
    Spec *s = L->s;
    spec_expect(L, root, YAML_MAPPING_NODE, "the top level of a spec");
    spec_unique_keys(L, root, "the spec");
    spec_check_keys(L, root, top_keys, "the spec");
    s->name = spec_name(L, spec_section(L, root, "name", 0));
    yaml_node_t *d = spec_section(L, root, "description", 0);
    s->description = d ? arena_strdup(L->A, spec_scalar(L, d, "description")) : "";
    yaml_node_t *params = spec_section(L, root, "parameters", 1);
    yaml_node_t *coords = spec_lookup(L, root, "coordinates");
    yaml_node_t *inputs = spec_section(L, root, "inputs", 1);
    yaml_node_t *defines = spec_section(L, root, "define", 1);
    yaml_node_t *frames = spec_section(L, root, "frames", 1);
    yaml_node_t *points = spec_section(L, root, "points", 1);
    yaml_node_t *bodies = spec_section(L, root, "bodies", 1);
    if (!coords)
        diag_error(spec_loc(L, root), "the spec has no `coordinates:`");
    int most = (params ? NPAIRS(params) : 0) + (inputs ? NPAIRS(inputs) : 0) +
               (defines ? NPAIRS(defines) : 0) + (frames ? NPAIRS(frames) : 0) +
               (points ? NPAIRS(points) : 0) +
               (coords->type == YAML_SEQUENCE_NODE ? NITEMS(coords) : 0) +
               spec_count_speeds(L, frames, bodies);
    L->names = arena_new_array(L->A, Name, most + 1);
    L->quat_of = arena_new_array(L->A, const char *, most + 1);
    for (int i = 0; i <= most; i++)
        L->quat_of[i] = NULL;
    if (params)
        spec_name_parameters(L, params);
    spec_load_coordinates(L, coords);
    if (inputs)
        spec_name_inputs(L, inputs);
    spec_name_items(L, defines, frames, points);
    spec_name_speeds(L, frames, bodies);
    spec_stop_if_failed(); /* everything below is read with these names */
    spec_resolve_defines(L);
    if (params)
        spec_load_parameters(L, params);
    if (inputs)
        spec_load_inputs(L, inputs);
    /* fixed values first: the physical data are checked with them */
    L->scene = spec_pick_scene(L, root);
    if (L->scene)
        spec_checked(L, spec_live_fix, L->scene, 0);
    spec_fix_option(L);
    spec_check_axes(L);
    yaml_node_t *n;
    if ((n = spec_section(L, root, "particles", 1)))
        spec_load_particles(L, n);
    if (bodies)
        spec_load_bodies(L, bodies);
    spec_velocity_slots(L);
    spec_draw_items(L, spec_section(L, root, "ground", 0));
    spec_checked(L, spec_load_energy, root, 0);
    spec_checked(L, spec_load_energy, root, 1);
    if ((n = spec_section(L, root, "effects", 1)))
        spec_load_effects(L, n);
    if ((n = spec_section(L, root, "constraints", 1)))
        spec_load_constraints(L, n);
    if ((n = spec_section(L, root, "initial", 1)))
        spec_load_initial(L, n, 1);
    if (diag_error_count() == 0) /* it reads the bodies' and the parameters' values */
        spec_unit_constraints(L);
    if (L->scene)
        spec_checked(L, spec_live_scene, L->scene, 0);
    if ((n = spec_section(L, root, "scenes", 1)))
        for (int i = 0; i < s->nscenes; i++)
            spec_checked(L, spec_other_scene, n, i);
    spec_stop_if_failed();
    spec_fold_fixed(L);
    if (s->npart == 0 && s->nbody == 0 && s->nkinetic == 0)
        diag_error(spec_loc(L, root), "the spec has no kinetic energy: give `particles:`, "
                   "`bodies:` or `kinetic:` terms");
}

/* The whole spec; apart from spec_load_buffer, so that nothing of its
 * own lives in the frame that setjmp returns to twice. */
static void
load_spec(Loader *L)
{
    load_root(L, spec_read(L));
}

Spec *
spec_load_buffer(const char *path, const char *text, size_t len, const SpecOptions *o,
                 Arena *A, ExprPool *P)
{
    static const SpecOptions none = {NULL, NULL};
    Loader *L = arena_alloc(A, sizeof *L);
    L->opt = o ? o : &none;
    L->path = arena_strdup(A, path);
    L->text = text;
    L->len = len;
    L->A = A;
    L->P = P;
    L->sc = spec_scope(P);
    expr_clear_rates(P); /* an earlier spec's speeds are not this one's */
    expr_clear_switches(P); /* nor its kinks */
    L->s = arena_alloc(A, sizeof *L->s);
    L->s->path = L->path;
    L->s->scene = spec_scene_defaults;
    diag_add_source(L->path, text, len);
    diag_reset_errors();
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    Spec *volatile result = NULL;
    if (setjmp(jb) == 0) {
        load_spec(L);
        result = L->s;
    }
    diag_set_jump(old);
    if (L->have_doc)
        yaml_document_delete(&L->doc);
    diff_free(L->sc.D);
    return result;
}

Spec *
spec_load(const char *path, const SpecOptions *o, Arena *A, ExprPool *P)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "eomc: cannot read %s: %s\n", path, strerror(errno));
        return NULL;
    }
    errno = 0;
    size_t cap = 1 << 14, n = 0, k;
    char *buf = arena_alloc(A, cap);
    while ((k = fread(buf + n, 1, cap - n, f)) > 0) {
        n += k;
        if (n == cap) {
            if (cap >= MAX_SPEC_BYTES) {
                fclose(f);
                fprintf(stderr, "eomc: %s: a spec is at most %d MiB\n", path, MAX_SPEC_BYTES >> 20);
                return NULL;
            }
            char *bigger = arena_alloc(A, cap * 2);
            memcpy(bigger, buf, n);
            buf = bigger, cap *= 2;
        }
    }
    int err = ferror(f) ? errno : 0; /* a directory opens, and fails to read */
    fclose(f);
    if (err) {
        fprintf(stderr, "eomc: cannot read %s: %s\n", path, strerror(err));
        return NULL;
    }
    return spec_load_buffer(path, buf, n, o, A, P);
}
