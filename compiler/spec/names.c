/*
 * names: the spec's names, and the scope its expressions are parsed in
 * (names.h).
 */
#include "names.h"

#include <stdio.h>
#include <string.h>

int
spec_is_identifier(const char *s)
{
    if (!(*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
        return 0;
    for (; *s; s++)
        if (!(*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
              (*s >= '0' && *s <= '9')))
            return 0;
    return 1;
}

Name *
spec_find_name(Loader *L, const char *name)
{
    for (int i = 0; i < L->nnames; i++)
        if (!strcmp(L->names[i].name, name))
            return &L->names[i];
    return NULL;
}

static const char *const kind_names[] = {"a parameter", "a coordinate", "an input",
                                         "a define", "a frame", "a point", "a speed"};

/* Names are looked up by a linear search, and models are dense in their
 * coordinates: a spec with more names than this is refused rather than
 * compiled for minutes. */
enum { SPEC_MAX_NAMES = 10000 };

/* Check a new name (identifier, not reserved, not taken) and keep it. */
const char *
spec_add_name(Loader *L, yaml_node_t *n, NameKind kind, int index)
{
    const char *name = spec_scalar(L, n, "a name");
    SrcLoc at = spec_loc(L, n);
    if (!spec_is_identifier(name))
        diag_error(at, "'%s' is not a valid name (letters, digits and _, not starting "
                   "with a digit)", name);
    if (strlen(name) > 64)
        diag_error(at, "name '%.20s...' is longer than 64 characters", name);
    if (parse_is_reserved(name))
        diag_error(at, "'%s' is reserved: t is the time and pi the number (the only "
                   "reserved names)", name);
    if (L->nnames >= SPEC_MAX_NAMES && (L->stop = 1))
        diag_error(at, "more than %d names (parameters, coordinates, inputs and defines)",
                   SPEC_MAX_NAMES);
    Name *old = spec_find_name(L, name);
    if (old && old->loc.line == at.line)
        diag_error(at, "'%s' is already %s (line %d, column %d)", name, kind_names[old->kind],
                   old->loc.line, old->loc.col);
    if (old)
        diag_error(at, "'%s' is already %s (line %d)", name, kind_names[old->kind],
                   old->loc.line);
    L->names[L->nnames++] = (Name){arena_strdup(L->A, name), kind, index, at};
    return L->names[L->nnames - 1].name;
}

static int
is_value_name(const Name *nm)
{
    return nm->kind != NAME_FRAME && nm->kind != NAME_POINT;
}

/* An unknown name where a NameKind `want` (NAME_FRAME, NAME_POINT, or -1
 * for a value) is expected: the nearest of those names, or their list. */
static _Noreturn void
unknown_name(Loader *L, const char *name, int want, SrcLoc at)
{
    const char *what = want == NAME_FRAME ? "frame" : want == NAME_POINT ? "point" : "name";
    if (want < 0 && parse_is_function(name))
        diag_error(at, "'%s' is a function: write %s(...)", name, name);
    const char **cands = arena_new_array(L->A, const char *, L->nnames + 2);
    int n = 0;
    for (int i = 0; i < L->nnames; i++)
        if (want < 0 ? is_value_name(&L->names[i]) : (int)L->names[i].kind == want)
            cands[n++] = L->names[i].name;
    if (want == NAME_FRAME)
        cands[n++] = "world";
    if (want == NAME_POINT)
        cands[n++] = "origin";
    const char *near = diag_nearest(name, cands, n);
    if (near)
        diag_error(at, "unknown %s '%s'; did you mean %s?", what, name, near);
    if (n == 0 || n > 12)
        diag_error(at, "unknown %s '%s'", what, name);
    char list[1024] = "";
    for (int i = 0; i < n; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                 cands[i]);
    diag_error(at, "unknown %s '%s' (the %ss here are %s)", what, name, what, list);
}

/* A resolved item, or abandon: its error is reported. */
Define *
spec_item(Loader *L, const Name *nm)
{
    Define *d = &L->def[nm->index];
    if (d->bad)
        diag_abandon();
    if (d->state != 2)
        diag_unreachable(); /* ordered before its users */
    return d;
}

static ParseVal
lookup(ParseScope *sc, const char *name, SrcLoc at)
{
    Loader *L = (Loader *)sc;
    Name *nm = spec_find_name(L, name);
    ExprId e = EXPR_NONE;
    if (nm) {
        switch (nm->kind) {
        case NAME_PARAM: e = expr_param(L->P, nm->index); break;
        case NAME_COORD: e = expr_var(L->P, nm->index, 0); break;
        case NAME_SPEED: e = expr_var(L->P, L->s->nq + nm->index, 1); break;
        case NAME_INPUT: e = expr_input(L->P, nm->index); break;
        case NAME_DEFINE: return spec_item(L, nm)->value;
        case NAME_FRAME:
            diag_error(at, "'%s' is a frame, not a value: its axes are %s.x, %s.y and %s.z, "
                       "its angular velocity omega(%s)", name, name, name, name, name);
        case NAME_POINT:
            diag_error(at, "'%s' is a point, not a value: its position is pos(%s), its "
                       "velocity vel(%s)", name, name, name);
        }
        return (ParseVal){0, {e, EXPR_NONE, EXPR_NONE}};
    }
    if (!strcmp(name, "nan") || !strcmp(name, "NaN") || !strcmp(name, "inf") ||
        !strcmp(name, "Inf") || !strcmp(name, "infinity"))
        diag_error(at, "'%s' is not allowed: every value must be a finite number", name);
    unknown_name(L, name, -1, at);
}

/* A frame or point argument (parse.h): the world and its origin unless a
 * name of the spec's takes their names. */
int
spec_frame_or_point(Loader *L, const char *name, NameKind want, SrcLoc at)
{
    Name *nm = spec_find_name(L, name);
    if (!nm && want == NAME_FRAME && !strcmp(name, "world"))
        return KIN_WORLD;
    if (!nm && want == NAME_POINT && !strcmp(name, "origin"))
        return KIN_ORIGIN;
    if (!nm)
        unknown_name(L, name, (int)want, at);
    if (nm->kind != want)
        diag_error(at, "'%s' is %s, not a %s", name, kind_names[nm->kind],
                   want == NAME_FRAME ? "frame" : "point");
    return spec_item(L, nm)->kin;
}

static int
frame_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    return spec_frame_or_point((Loader *)sc, name, NAME_FRAME, at);
}

static int
point_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    return spec_frame_or_point((Loader *)sc, name, NAME_POINT, at);
}

static const char *
leaf_name(ParseScope *sc, ExprId leaf)
{
    Loader *L = (Loader *)sc;
    const ExprNode *nd = expr_node(L->P, leaf);
    switch (nd->op) {
    case EXPR_VAR: /* a coordinate, or a speed past them */
        if ((int)nd->a >= L->s->nq)
            return L->s->speed[(int)nd->a - L->s->nq].name;
        return L->s->coord[nd->a].name;
    case EXPR_PARAM: return L->s->param[nd->a].name;
    case EXPR_INPUT: return L->s->input[nd->a].name;
    case EXPR_MULT: return L->s->constraint[nd->a].name;
    }
    return "t";
}

/* lambda[NAME] */
static ExprId
multiplier(ParseScope *sc, const char *name, SrcLoc at)
{
    Loader *L = (Loader *)sc;
    Spec *s = L->s;
    if (s->nconstraint == 0)
        diag_error(at, "lambda[%s]: the spec has no constraints, so no multipliers", name);
    const char **cands = arena_new_array(L->A, const char *, s->nconstraint);
    for (int c = 0; c < s->nconstraint; c++) {
        if (!strcmp(s->constraint[c].name, name))
            return expr_mult(L->P, c);
        cands[c] = s->constraint[c].name;
    }
    const char *near = diag_nearest(name, cands, s->nconstraint);
    if (near)
        diag_error(at, "'%s' is not a constraint; did you mean %s?", name, near);
    char list[1024] = "";
    for (int c = 0; c < s->nconstraint; c++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", c ? ", " : "",
                 cands[c]);
    diag_error(at, "'%s' is not a constraint; the constraints are %s", name, list);
}

/* ---- expressions ---- */

ExprId
spec_expr(Loader *L, const yaml_node_t *n, unsigned allow, const char *what)
{
    Scalar sc;
    spec_scalar_src(L, &sc, n, what);
    L->sc.allow = allow;
    L->sc.what = what;
    return parse_expr(&L->sc, &sc.src);
}

/* A number: a constant expression (2*pi is fine), finite. */
double
spec_number(Loader *L, const yaml_node_t *n, const char *what)
{
    ExprId e = spec_expr(L, n, ALLOW_CONST, what);
    double v;
    if (!expr_is_const(L->P, e, &v))
        diag_error(spec_loc(L, n), "%s does not evaluate to a finite number", what);
    return v;
}

/* A vector of 2 or 3 expressions. */
int
spec_vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what, ExprId out[3])
{
    spec_expect(L, n, YAML_SEQUENCE_NODE, what);
    int dim = NITEMS(n);
    if (dim != 2 && dim != 3)
        diag_error(spec_loc(L, n), "%s must have 2 or 3 components, not %d", what, dim);
    for (int k = 0; k < dim; k++)
        out[k] = spec_expr(L, spec_node(L, ITEMS(n)[k]), allow, what);
    return dim;
}

/* A vector in world components: [x, y] or [x, y, z] as spec_vector() reads
 * it, the name of a point (its position), or a vector expression such as
 * pos(P) - pos(Q) or -k*vel(P) (3 components). */
int
spec_world_vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what, ExprId out[3])
{
    if (n->type != YAML_SCALAR_NODE)
        return spec_vector(L, n, allow, what, out);
    const char *text = spec_scalar(L, n, what);
    Name *nm = spec_find_name(L, text);
    if ((nm && nm->kind == NAME_POINT) || (!nm && !strcmp(text, "origin"))) {
        kin_pos(L->K, spec_frame_or_point(L, text, NAME_POINT, spec_loc(L, n)), out);
        L->sc.allow = allow;
        L->sc.what = what;
        for (int k = 0; k < 3; k++) /* what a point moves with may not be allowed here */
            if (expr_deps(L->P, out[k]) & ~allow) {
                Scalar sc;
                spec_scalar_src(L, &sc, n, what);
                parse_vector(&L->sc, &sc.src, out); /* says what, at the name */
            }
        return 3;
    }
    Scalar sc;
    spec_scalar_src(L, &sc, n, what);
    L->sc.allow = allow;
    L->sc.what = what;
    parse_vector(&L->sc, &sc.src, out);
    return 3;
}

/* ---- the sections of names ---- */

static void
name_parameter(Loader *L, yaml_node_t *map, int i)
{
    yaml_node_pair_t *p = &PAIRS(map)[i];
    L->s->param[i].name = spec_add_name(L, spec_node(L, p->key), NAME_PARAM, i);
    L->s->param[i].loc = spec_loc(L, spec_node(L, p->key));
}

void
spec_name_parameters(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->np = NPAIRS(map);
    s->param = arena_new_array(L->A, SpecParam, s->np);
    for (int i = 0; i < s->np; i++)
        spec_checked(L, name_parameter, map, i);
}

static void
load_parameter(Loader *L, yaml_node_t *map, int i)
{
    L->s->param[i].value = spec_number(L, spec_node(L, PAIRS(map)[i].value), "a parameter value");
}

/* After every name is known, so that `k: 2*x` says x is a coordinate. */
void
spec_load_parameters(Loader *L, yaml_node_t *map)
{
    L->bad_param = arena_new_array(L->A, char, L->s->np + 1);
    for (int i = 0; i < L->s->np; i++)
        L->bad_param[i] = !spec_checked(L, load_parameter, map, i);
}

static void
name_coordinate(Loader *L, yaml_node_t *seq, int i)
{
    Spec *s = L->s;
    yaml_node_t *n = spec_node(L, ITEMS(seq)[i]);
    s->coord[i].q0 = s->coord[i].v0 = EXPR_ZERO;
    s->coord[i].name = spec_add_name(L, n, NAME_COORD, i);
    s->coord[i].loc = spec_loc(L, n);
}

void
spec_load_coordinates(Loader *L, yaml_node_t *seq)
{
    Spec *s = L->s;
    spec_expect(L, seq, YAML_SEQUENCE_NODE, "coordinates");
    s->nq = NITEMS(seq);
    if (s->nq == 0)
        diag_error(spec_loc(L, seq), "a spec needs at least one coordinate");
    s->coord = arena_new_array(L->A, SpecCoord, s->nq);
    L->sc.ncoord = s->nq;
    for (int i = 0; i < s->nq; i++)
        spec_checked(L, name_coordinate, seq, i);
}

static void
name_input(Loader *L, yaml_node_t *map, int i)
{
    yaml_node_t *k = spec_node(L, PAIRS(map)[i].key);
    L->s->input[i].name = spec_add_name(L, k, NAME_INPUT, i);
    L->s->input[i].loc = spec_loc(L, k);
}

void
spec_name_inputs(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nu = NPAIRS(map);
    s->input = arena_new_array(L->A, SpecInput, s->nu);
    for (int i = 0; i < s->nu; i++)
        spec_checked(L, name_input, map, i);
}

static void
load_input(Loader *L, yaml_node_t *map, int i)
{
    L->s->input[i].expr = spec_expr(L, spec_node(L, PAIRS(map)[i].value), ALLOW_SIGNAL,
                                     "an input signal");
}

void
spec_load_inputs(Loader *L, yaml_node_t *map)
{
    for (int i = 0; i < L->s->nu; i++)
        spec_checked(L, load_input, map, i);
}

/* The index of the name node n holds among cands[0..count), or a
 * diagnostic at n: "unknown WHAT 'x'", or with is_not "'x' is not a
 * WHAT", and "; did you mean 'y'?" when a name is close, else the list
 * of them (PLURAL) when it is short. */
int
spec_scalar_coordinate(Loader *L, yaml_node_t *n, const char *what)
{
    Spec *s = L->s;
    const char **cands = arena_new_array(L->A, const char *, s->nq + 1);
    for (int i = 0; i < s->nq; i++)
        cands[i] = s->coord[i].name;
    int q = spec_find_in(L, n, "coordinate", "coordinates", 1, cands, s->nq);
    if (L->quat_of && L->quat_of[q])
        diag_error(spec_loc(L, n), "'%s' is an Euler parameter of %s: %s acts on a "
                   "coordinate that is an angle or a length", s->coord[q].name,
                   L->quat_of[q], what);
    return q;
}

int
spec_find_in(Loader *L, yaml_node_t *n, const char *what, const char *plural, int is_not,
        const char **cands, int count)
{
    const char *name = spec_scalar(L, n, what);
    for (int i = 0; i < count; i++)
        if (!strcmp(cands[i], name))
            return i;
    const char *near = diag_nearest(name, cands, count);
    char msg[256];
    if (is_not)
        snprintf(msg, sizeof msg, "'%s' is not a %s", name, what);
    else
        snprintf(msg, sizeof msg, "unknown %s '%s'", what, name);
    if (near)
        diag_error(spec_loc(L, n), "%s; did you mean %s?", msg, near);
    if (count == 0 || count > 12)
        diag_error(spec_loc(L, n), "%s", msg);
    char list[1024] = "";
    for (int i = 0; i < count; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                 cands[i]);
    diag_error(spec_loc(L, n), "%s; the %s %s %s", msg, count == 1 ? what : plural,
               count == 1 ? "is" : "are", list);
}

ParseScope
spec_scope(ExprPool *P)
{
    return (ParseScope){P, diff_new(P), lookup, multiplier, leaf_name, 0, "", 0,
                        frame_arg, point_arg, NULL, NULL};
}
