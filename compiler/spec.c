/*
 * spec: YAML (libyaml's document API) -> checked Spec.
 *
 * The loader works in phases, so that every name is known before any
 * expression is parsed: names (parameters, coordinates, inputs, defines),
 * then the defines in dependency order (found by lexing their texts, so
 * that a cycle is reported as one, and no define expansion recurses),
 * then everything else.  Each expression is parsed with the DEP_ bits
 * of what it may depend on; parse.c rejects the rest at the right column.
 *
 * Errors go through diag_error, which longjmps back to spec_load_buffer:
 * everything the loader allocates lives in the arena or the pool, so
 * nothing leaks when it unwinds, except the libyaml document, which the
 * catch point deletes.
 */
#include "spec.h"
#include "parse.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

/* The runtime's list of integration methods, the one list of them. */
const char *const spec_methods[] = {
#define METHOD(name, gsl, fixed, jac, description) #name,
#include "../runtime/methods.def"
#undef METHOD
    NULL,
};
static const char spec_method_jac[] = {
#define METHOD(name, gsl, fixed, jac, description) jac,
#include "../runtime/methods.def"
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

enum { MAX_SPEC_BYTES = 16 << 20 };

typedef enum { NAME_PARAM, NAME_COORD, NAME_INPUT, NAME_DEFINE, NAME_FRAME, NAME_POINT } NameKind;

typedef struct Name {
    const char *name;
    NameKind kind;
    int index; /* into Spec.param / coord / input, or Loader.def (an item) */
    SrcLoc loc;
} Name;

/* What names stand for that is built from other names, in the order
 * their uses require: a define's value (a scalar or a vector), a frame, a
 * point.  Each names the others it uses, and they are resolved depth
 * first, after what they use. */
typedef enum { ITEM_DEFINE, ITEM_FRAME, ITEM_POINT } ItemKind;

typedef struct Define {
    const char *name;
    ItemKind kind;
    yaml_node_t *node; /* a define's scalar; a frame's or point's map */
    ParseVal value;    /* a define's; value.e[0] = EXPR_NONE until resolved */
    int kin;           /* a frame's or point's index in kin.h, once resolved */
    int state;         /* 0 new, 1 being ordered, 2 ordered */
    int bad;           /* it had an error, already reported */
    int *deps;         /* items it names, and where (scalar, byte) */
    yaml_node_t **dep_node;
    size_t *dep_off;
    int ndeps;
} Define;

typedef struct Loader {
    ParseScope sc; /* first: parser callbacks receive the Loader */
    const char *path, *text;
    size_t len;
    size_t *line_start; /* byte offset of each line */
    size_t nlines;
    yaml_document_t doc;
    int have_doc;
    Arena *A;
    ExprPool *P;
    Spec *s;
    Name *names;
    int nnames;
    Define *def; /* the items: defines, then frames, then points */
    int ndef, nitem_defs, nframes, npoints;
    Kin *K;
    double *pdef;  /* the parameters' defaults, once loaded (defaults()) */
    char *bad_param; /* per parameter: its value had an error */
    char *bad_part, *bad_body; /* per particle and body: it had an error */
    int *body_frame;           /* per body: the frame it is placed by, or -1 */
    int stop;      /* no use going on: SPEC_MAX_ERRORS reached, or a limit */
    const SpecOptions *opt; /* never NULL */
    yaml_node_t *scene;     /* the scene compiled: its map, or NULL */
    SpecScene *scene_into;  /* the scene being read: Spec.scene or a scratch copy */
    int scene_live;         /* it is the scene compiled */
    struct AxisCheck *axes; /* fixed axes of parameters, checked once they are loaded */
    const char **quat_of;   /* per coordinate: whose Euler parameter it is, or NULL */
    int capfquat;           /* room in Spec.fquat */
} Loader;

/* A turn's axis of parameters, |a|^2 at node n of frame name: frames are
 * built before the parameters' values are read, so its check waits. */
typedef struct AxisCheck {
    ExprId n2;
    const yaml_node_t *n;
    const char *name;
    struct AxisCheck *next;
} AxisCheck;

/* A scalar being parsed as an expression: where() maps its bytes back. */
typedef struct Scalar {
    ParseSrc src; /* first */
    const Loader *L;
    const yaml_node_t *node;
} Scalar;

/* ---- locations ---- */

static SrcLoc
loc_of(const Loader *L, const yaml_node_t *n)
{
    return (SrcLoc){L->path, (int)n->start_mark.line + 1, (int)n->start_mark.column + 1};
}

static int is_cont(unsigned char c) { return (c & 0xC0) == 0x80; }

/* Byte offset of (line, column), both 0-based, column in characters. */
static size_t
byte_at(const Loader *L, size_t line, size_t col)
{
    if (line >= L->nlines)
        return L->len;
    size_t i = L->line_start[line];
    while (i < L->len && col > 0) {
        i++;
        while (i < L->len && is_cont((unsigned char)L->text[i]))
            i++;
        col--;
    }
    return i;
}

static size_t
escape_len(const char *s, size_t i, size_t end)
{
    if (i + 1 >= end)
        return 1;
    switch (s[i + 1]) {
    case 'x': return 4;
    case 'u': return 6;
    case 'U': return 10;
    case '\n': return 2;
    }
    return 2;
}

/* A node's mark is at its anchor (&a) or tag (!t) when it has one: the
 * byte where its text starts, past them and the blanks after them. */
static size_t
skip_properties(const char *s, size_t i, size_t end, size_t *line, size_t *col)
{
    while (i < end && (s[i] == '&' || s[i] == '!')) {
        for (; i < end && s[i] != ' ' && s[i] != '\t' && s[i] != '\n' && s[i] != '\r'; i++)
            *col += !is_cont((unsigned char)s[i]);
        while (i < end && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) {
            if (s[i] == '\n')
                (*line)++, *col = 0;
            else if (s[i] != '\r')
                (*col)++;
            i++;
        }
    }
    return i;
}

/* Walk the source of a scalar and its value side by side up to byte `off`
 * of the value: line folding, quotes and escapes are skipped in the
 * source. */
static SrcLoc
scalar_where(const ParseSrc *src, size_t off)
{
    const Scalar *sc = (const Scalar *)src;
    const Loader *L = sc->L;
    const yaml_node_t *n = sc->node;
    size_t line = n->start_mark.line, col = n->start_mark.column;
    size_t i = byte_at(L, line, col), end = L->len;
    const char *s = L->text, *v = src->text;
    yaml_scalar_style_t style = n->data.scalar.style;
    i = skip_properties(s, i, end, &line, &col);
    if (style == YAML_SINGLE_QUOTED_SCALAR_STYLE || style == YAML_DOUBLE_QUOTED_SCALAR_STYLE) {
        i++, col++;
    } else if (style == YAML_LITERAL_SCALAR_STYLE || style == YAML_FOLDED_SCALAR_STYLE) {
        while (i < end && s[i] != '\n')
            i++;
        i++, line++, col = 0;
    }
    for (size_t k = 0; k < off && k < src->len && i < end;) {
        unsigned char c = (unsigned char)s[i], vc = (unsigned char)v[k];
        size_t step = 1, vstep = 1;
        if (style == YAML_DOUBLE_QUOTED_SCALAR_STYLE && c == '\\') {
            step = escape_len(s, i, end);
            while (k + vstep < src->len && is_cont((unsigned char)v[k + vstep]))
                vstep++;
        } else if (style == YAML_SINGLE_QUOTED_SCALAR_STYLE && c == '\'' && vc == '\'') {
            step = 2;
        } else if (c != vc) {
            if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
                break; /* lost track: report what we have */
            vstep = 0;   /* folded whitespace: source only */
        }
        for (size_t j = 0; j < step && i < end; j++, i++) {
            if (s[i] == '\n')
                line++, col = 0;
            else if (!is_cont((unsigned char)s[i]))
                col++;
        }
        k += vstep;
    }
    return (SrcLoc){L->path, (int)line + 1, (int)col + 1};
}

/* ---- YAML node access ---- */

static yaml_node_t *
node(Loader *L, int id)
{
    yaml_node_t *n = yaml_document_get_node(&L->doc, id);
    if (!n)
        diag_unreachable();
    return n;
}

static const char *
kind_name(const yaml_node_t *n)
{
    switch (n->type) {
    case YAML_SCALAR_NODE: return "a scalar";
    case YAML_SEQUENCE_NODE: return "a sequence";
    case YAML_MAPPING_NODE: return "a mapping";
    default: return "nothing";
    }
}

static int
is_null(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    const char *v = (const char *)n->data.scalar.value;
    return !*v || !strcmp(v, "~") || !strcmp(v, "null") || !strcmp(v, "Null") ||
           !strcmp(v, "NULL");
}

static void
expect_type(Loader *L, const yaml_node_t *n, yaml_node_type_t type, const char *what)
{
    if (n->type == type && !(type == YAML_SCALAR_NODE && is_null(n)))
        return;
    const char *want = type == YAML_SCALAR_NODE ? "a value"
                     : type == YAML_SEQUENCE_NODE ? "a sequence [...]" : "a mapping";
    diag_error(loc_of(L, n), "%s must be %s, not %s", what, want,
               is_null(n) ? "empty" : kind_name(n));
}

static const char *
scalar(Loader *L, const yaml_node_t *n, const char *what)
{
    expect_type(L, n, YAML_SCALAR_NODE, what);
    if (strlen((const char *)n->data.scalar.value) != n->data.scalar.length)
        diag_error(loc_of(L, n), "%s contains a NUL character", what);
    return (const char *)n->data.scalar.value;
}

static const char *
key_of(Loader *L, const yaml_node_pair_t *p)
{
    return scalar(L, node(L, p->key), "a key");
}

#define PAIRS(map) (map)->data.mapping.pairs.start
#define NPAIRS(map) ((int)((map)->data.mapping.pairs.top - (map)->data.mapping.pairs.start))
#define ITEMS(seq) (seq)->data.sequence.items.start
#define NITEMS(seq) ((int)((seq)->data.sequence.items.top - (seq)->data.sequence.items.start))

typedef struct KeyRef {
    const char *key;
    int index;
} KeyRef;

static int
cmp_key(const void *a, const void *b)
{
    const KeyRef *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : (x->index > y->index) - (x->index < y->index);
}

/* Keys are scalars, each at most once (sorted: no quadratic scan); a
 * repeated one is reported where it repeats, naming the first. */
static void
check_unique_keys(Loader *L, yaml_node_t *map, const char *what)
{
    int n = NPAIRS(map);
    if (n < 2)
        return;
    KeyRef *k = arena_new_array(L->A, KeyRef, n);
    for (int i = 0; i < n; i++)
        k[i] = (KeyRef){key_of(L, &PAIRS(map)[i]), i};
    qsort(k, (size_t)n, sizeof *k, cmp_key);
    for (int i = 1; i < n; i++) {
        if (strcmp(k[i].key, k[i - 1].key))
            continue;
        SrcLoc first = loc_of(L, node(L, PAIRS(map)[k[i - 1].index].key));
        diag_error(loc_of(L, node(L, PAIRS(map)[k[i].index].key)),
                   "duplicate key '%s' in %s (first at line %d, column %d)", k[i].key, what,
                   first.line, first.col);
    }
}

static yaml_node_t *
as_map(Loader *L, yaml_node_t *n, const char *what)
{
    expect_type(L, n, YAML_MAPPING_NODE, what);
    check_unique_keys(L, n, what);
    return n;
}

/* Where each key of the format belongs, for a key found elsewhere. */
static const struct {
    const char *key, *where;
} key_homes[] = {
    {"mass", "in a particle or a body"}, {"position", "in a particle"},
    {"center", "in a body"}, {"inertia", "in a body"}, {"rotation", "in a body"},
    {"omega", "in a body"}, {"angle", "in a body"}, {"gravity", "in an effect"},
    {"force", "in an effect"}, {"torque", "in an effect"}, {"work", "in an effect"},
    {"on", "in an effect"}, {"expr", "in a constraint"}, {"dependent", "in a constraint"},
    {"t_end", "in a scene"}, {"dt", "in a scene"}, {"method", "in a scene"},
    {"rtol", "in a scene"}, {"atol", "in a scene"}, {"fixed_step", "in a scene"},
    {"fix", "in a scene"}, {"outputs", "in a scene"}, {"events", "in a scene"},
    {"assemble", "in a scene"}, {"hold", "in a scene's `assemble:`"},
    {"quaternion", "in a body's rotation or a frame's turns"},
    {"when", "in an event"}, {"direction", "in an event"}, {"action", "in an event"},
    {"coordinates", "at the top level"}, {"parameters", "at the top level"},
    {"particles", "at the top level"}, {"bodies", "at the top level"},
    {"define", "at the top level"}, {"inputs", "at the top level"},
    {"kinetic", "at the top level"}, {"initial", "at the top level"},
    {"constraints", "at the top level"}, {"scene", "at the top level"},
    {"scenes", "at the top level"},
};

static const char *
key_home(const char *key)
{
    for (size_t i = 0; i < sizeof key_homes / sizeof key_homes[0]; i++)
        if (!strcmp(key_homes[i].key, key))
            return key_homes[i].where;
    return NULL;
}

/* Key i of map must be one of `allowed` (NULL-terminated).  An unknown
 * key gets the nearest allowed ones, or where it belongs if it is a key of
 * another part of the spec, or the list of allowed keys. */
static void
check_key(Loader *L, yaml_node_t *map, int i, const char *const *allowed, const char *where)
{
    int nallowed = 0;
    while (allowed[nallowed])
        nallowed++;
    const char *k = key_of(L, &PAIRS(map)[i]);
    for (int j = 0; j < nallowed; j++)
        if (!strcmp(k, allowed[j]))
            return;
    const char *near = diag_nearest(k, allowed, nallowed);
    SrcLoc at = loc_of(L, node(L, PAIRS(map)[i].key));
    if (near)
        diag_error(at, "unknown key '%s' in %s; did you mean %s?", k, where, near);
    const char *home = key_home(k);
    if (home)
        diag_error(at, "'%s' is not a key of %s: it belongs %s", k, where, home);
    char list[512] = "";
    for (int j = 0; j < nallowed; j++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", j ? ", " : "",
                 allowed[j]);
    diag_error(at, "unknown key '%s' in %s; expected one of: %s", k, where, list);
}

/* Only `allowed` keys may appear in map: the first that is not is the
 * error. */
static void
check_keys(Loader *L, yaml_node_t *map, const char *const *allowed, const char *where)
{
    for (int i = 0; i < NPAIRS(map); i++)
        check_key(L, map, i, allowed, where);
}

static yaml_node_t *
lookup_key(Loader *L, yaml_node_t *map, const char *key)
{
    for (int i = 0; i < NPAIRS(map); i++)
        if (!strcmp(key_of(L, &PAIRS(map)[i]), key))
            return node(L, PAIRS(map)[i].value);
    return NULL;
}

/* ---- names ---- */

static int
is_identifier(const char *s)
{
    if (!(*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
        return 0;
    for (; *s; s++)
        if (!(*s == '_' || (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
              (*s >= '0' && *s <= '9')))
            return 0;
    return 1;
}

static Name *
find_name(Loader *L, const char *name)
{
    for (int i = 0; i < L->nnames; i++)
        if (!strcmp(L->names[i].name, name))
            return &L->names[i];
    return NULL;
}

static const char *const kind_names[] = {"a parameter", "a coordinate", "an input",
                                         "a define", "a frame", "a point"};

/* Names are looked up by a linear search, and models are dense in their
 * coordinates: a spec with more names than this is refused rather than
 * compiled for minutes. */
enum { SPEC_MAX_NAMES = 10000 };

/* Check a new name (identifier, not reserved, not taken) and keep it. */
static const char *
add_name(Loader *L, yaml_node_t *n, NameKind kind, int index)
{
    const char *name = scalar(L, n, "a name");
    SrcLoc at = loc_of(L, n);
    if (!is_identifier(name))
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
    Name *old = find_name(L, name);
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
static Define *
item(Loader *L, const Name *nm)
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
    Name *nm = find_name(L, name);
    ExprId e = EXPR_NONE;
    if (nm) {
        switch (nm->kind) {
        case NAME_PARAM: e = expr_param(L->P, nm->index); break;
        case NAME_COORD: e = expr_var(L->P, nm->index, 0); break;
        case NAME_INPUT: e = expr_input(L->P, nm->index); break;
        case NAME_DEFINE: return item(L, nm)->value;
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
static int
frame_or_point(Loader *L, const char *name, NameKind want, SrcLoc at)
{
    Name *nm = find_name(L, name);
    if (!nm && want == NAME_FRAME && !strcmp(name, "world"))
        return KIN_WORLD;
    if (!nm && want == NAME_POINT && !strcmp(name, "origin"))
        return KIN_ORIGIN;
    if (!nm)
        unknown_name(L, name, (int)want, at);
    if (nm->kind != want)
        diag_error(at, "'%s' is %s, not a %s", name, kind_names[nm->kind],
                   want == NAME_FRAME ? "frame" : "point");
    return item(L, nm)->kin;
}

static int
frame_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    return frame_or_point((Loader *)sc, name, NAME_FRAME, at);
}

static int
point_arg(ParseScope *sc, const char *name, SrcLoc at)
{
    return frame_or_point((Loader *)sc, name, NAME_POINT, at);
}

static const char *
leaf_name(ParseScope *sc, ExprId leaf)
{
    Loader *L = (Loader *)sc;
    const ExprNode *nd = expr_node(L->P, leaf);
    switch (nd->op) {
    case EXPR_VAR: return L->s->coord[nd->a].name;
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

/* What each kind of expression may depend on. */
enum {
    ALLOW_CONST = 0,
    ALLOW_PARAM = DEP_P,
    ALLOW_SIGNAL = DEP_T | DEP_P,
    ALLOW_POSITION = DEP_T | DEP_ORDER(0) | DEP_P,
    ALLOW_KINETIC = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P,
    ALLOW_POTENTIAL = DEP_T | DEP_ORDER(0) | DEP_P | DEP_U,
    ALLOW_FORCE = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P | DEP_U,
    ALLOW_WORK = ALLOW_FORCE | DEP_S, /* forces times variations delta(e) */
    ALLOW_FIELD = DEP_T | DEP_P | DEP_U,
    ALLOW_CONSTRAINT = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_ORDER(2) | DEP_P | DEP_U,
    ALLOW_OUTPUT = ALLOW_CONSTRAINT | DEP_L,
    ALLOW_EVENT = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P,
    ALLOW_ALL = 0xff,
};

static void
scalar_src(Loader *L, Scalar *sc, const yaml_node_t *n, const char *what)
{
    const char *text = scalar(L, n, what);
    sc->src = (ParseSrc){text, n->data.scalar.length, scalar_where, NULL};
    sc->L = L;
    sc->node = n;
}

static ExprId
expression(Loader *L, const yaml_node_t *n, unsigned allow, const char *what)
{
    Scalar sc;
    scalar_src(L, &sc, n, what);
    L->sc.allow = allow;
    L->sc.what = what;
    return parse_expr(&L->sc, &sc.src);
}

/* A number: a constant expression (2*pi is fine), finite. */
static double
number(Loader *L, const yaml_node_t *n, const char *what)
{
    ExprId e = expression(L, n, ALLOW_CONST, what);
    double v;
    if (!expr_is_const(L->P, e, &v))
        diag_error(loc_of(L, n), "%s does not evaluate to a finite number", what);
    return v;
}

/* A vector of 2 or 3 expressions. */
static int
vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what, ExprId out[3])
{
    expect_type(L, n, YAML_SEQUENCE_NODE, what);
    int dim = NITEMS(n);
    if (dim != 2 && dim != 3)
        diag_error(loc_of(L, n), "%s must have 2 or 3 components, not %d", what, dim);
    for (int k = 0; k < dim; k++)
        out[k] = expression(L, node(L, ITEMS(n)[k]), allow, what);
    return dim;
}

/* A vector in world components: [x, y] or [x, y, z] as vector() reads
 * it, the name of a point (its position), or a vector expression such as
 * pos(P) - pos(Q) or -k*vel(P) (3 components). */
static int
world_vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what, ExprId out[3])
{
    if (n->type != YAML_SCALAR_NODE)
        return vector(L, n, allow, what, out);
    const char *text = scalar(L, n, what);
    Name *nm = find_name(L, text);
    if ((nm && nm->kind == NAME_POINT) || (!nm && !strcmp(text, "origin"))) {
        kin_pos(L->K, frame_or_point(L, text, NAME_POINT, loc_of(L, n)), out);
        L->sc.allow = allow;
        L->sc.what = what;
        for (int k = 0; k < 3; k++) /* what a point moves with may not be allowed here */
            if (expr_deps(L->P, out[k]) & ~allow) {
                Scalar sc;
                scalar_src(L, &sc, n, what);
                parse_vector(&L->sc, &sc.src, out); /* says what, at the name */
            }
        return 3;
    }
    Scalar sc;
    scalar_src(L, &sc, n, what);
    L->sc.allow = allow;
    L->sc.what = what;
    parse_vector(&L->sc, &sc.src, out);
    return 3;
}

/* ---- frames and points ---- */

/* The Euler parameters [e0, e1, e2, e3] at v, of `owner` ("body 'top'"):
 * four distinct coordinates, none another quaternion's, into q. */
static void
quaternion_coords(Loader *L, yaml_node_t *v, const char *owner, int q[4])
{
    expect_type(L, v, YAML_SEQUENCE_NODE, "the Euler parameters of a rotation");
    if (NITEMS(v) != 4)
        diag_error(loc_of(L, v), "a quaternion has 4 Euler parameters [e0, e1, e2, e3] "
                   "(scalar first), not %d", (int)NITEMS(v));
    for (int i = 0; i < 4; i++) {
        yaml_node_t *n = node(L, ITEMS(v)[i]);
        const char *name = scalar(L, n, "an Euler parameter");
        Name *nm = find_name(L, name);
        if (!nm || nm->kind != NAME_COORD)
            diag_error(loc_of(L, n), "the Euler parameters of a quaternion are coordinates, "
                       "and '%s' is not one (list it in `coordinates:`)", name);
        for (int j = 0; j < i; j++)
            if (q[j] == nm->index)
                diag_error(loc_of(L, n), "'%s' is already an Euler parameter of this "
                           "quaternion", name);
        if (L->quat_of[nm->index])
            diag_error(loc_of(L, n), "'%s' is already an Euler parameter of %s", name,
                       L->quat_of[nm->index]);
        q[i] = nm->index;
    }
    for (int i = 0; i < 4; i++)
        L->quat_of[q[i]] = owner;
}

/* A frame's turn {quaternion: [e0, e1, e2, e3]} (t, its map; v, the
 * list): the Euler parameters are coordinates, kept in Spec.fquat for the
 * unit constraint and the inertia along e (mech.c), as a body's are. */
static void
frame_quaternion(Loader *L, int f, const char *name, yaml_node_t *t, yaml_node_t *v)
{
    Spec *s = L->s;
    SpecQuat fq = {name, arena_printf(L->A, "frame '%s'", name), {-1, -1, -1, -1},
                   loc_of(L, node(L, PAIRS(t)[0].key))};
    quaternion_coords(L, v, fq.owner, fq.q);
    ExprId e[4];
    for (int k = 0; k < 4; k++)
        e[k] = expr_var(L->P, fq.q[k], 0);
    kin_turn_quaternion(L->K, f, e);
    if (s->nfquat == L->capfquat) {
        L->capfquat = L->capfquat ? 2 * L->capfquat : 4;
        SpecQuat *more = arena_new_array(L->A, SpecQuat, L->capfquat);
        if (s->nfquat)
            memcpy(more, s->fquat, (size_t)s->nfquat * sizeof *more);
        s->fquat = more;
    }
    s->fquat[s->nfquat++] = fq;
}

/* One turn of a frame's rotation: {x: ANGLE} (or y, z), about its own
 * axis as turned so far, or {axis: [ax, ay, az], angle: ANGLE} about a
 * fixed direction in those axes (any length but zero). */
static void
frame_turn(Loader *L, int f, const char *name, yaml_node_t *t)
{
    static const char *const keys[] = {"x", "y", "z", "axis", "angle", "quaternion", NULL};
    as_map(L, t, "a turn");
    check_keys(L, t, keys, "a turn");
    yaml_node_t *qn = lookup_key(L, t, "quaternion");
    if (qn) {
        if (NPAIRS(t) != 1)
            diag_error(loc_of(L, t), "a turn by a quaternion is {quaternion: [e0, e1, e2, "
                       "e3]}, alone");
        frame_quaternion(L, f, name, t, qn);
        return;
    }
    yaml_node_t *ax = lookup_key(L, t, "axis"), *ang = lookup_key(L, t, "angle");
    if (ax || ang) {
        if (!ax || !ang || NPAIRS(t) != 2)
            diag_error(loc_of(L, t), "a turn about a fixed direction is {axis: [ax, ay, az], "
                       "angle: ANGLE}");
        ExprId a[3];
        if (vector(L, ax, ALLOW_PARAM, "an axis", a) != 3)
            diag_error(loc_of(L, ax), "an axis has 3 components, in the frame's axes as "
                       "turned so far");
        ExprId n2 = EXPR_ZERO;
        for (int k = 0; k < 3; k++)
            n2 = expr_add(L->P, n2, expr_mul(L->P, a[k], a[k]));
        if (n2 == EXPR_ZERO)
            diag_error(loc_of(L, ax), "an axis cannot be zero");
        AxisCheck *c = arena_new_array(L->A, AxisCheck, 1);
        *c = (AxisCheck){n2, ax, name, L->axes};
        L->axes = c;
        ExprId len = expr_unary(L->P, EXPR_SQRT, n2);
        for (int k = 0; k < 3; k++)
            a[k] = expr_div(L->P, a[k], len);
        kin_turn(L->K, f, a, expression(L, ang, ALLOW_POSITION, "an angle"));
        return;
    }
    if (NPAIRS(t) != 1)
        diag_error(loc_of(L, t), "a turn is one of {x: ANGLE}, {y: ANGLE}, {z: ANGLE}, "
                   "{axis: [ax, ay, az], angle: ANGLE} or {quaternion: [e0, e1, e2, e3]}");
    const char *k = key_of(L, &PAIRS(t)[0]);
    kin_turn_axis(L->K, f, k[0] - 'x',
                  expression(L, node(L, PAIRS(t)[0].value), ALLOW_POSITION, "an angle"));
}

/* FRAME: {parent: FRAME, rotation: [TURN, ...], origin: POINT}, every key
 * optional (the world, no turn, no origin). */
static void
build_frame(Loader *L, Define *d)
{
    static const char *const keys[] = {"parent", "rotation", "origin", NULL};
    yaml_node_t *m = d->node, *v;
    int parent = KIN_WORLD;
    if (!is_null(m)) {
        as_map(L, m, "a frame");
        check_keys(L, m, keys, "a frame");
    }
    if (!is_null(m) && (v = lookup_key(L, m, "parent")))
        parent = frame_or_point(L, scalar(L, v, "a frame"), NAME_FRAME, loc_of(L, v));
    int f = kin_frame(L->K, parent);
    if (!is_null(m) && (v = lookup_key(L, m, "rotation"))) {
        if (v->type == YAML_MAPPING_NODE) {
            frame_turn(L, f, d->name, v);
        } else {
            expect_type(L, v, YAML_SEQUENCE_NODE, "a frame's rotation (a list of turns)");
            for (int i = 0; i < NITEMS(v); i++)
                frame_turn(L, f, d->name, node(L, ITEMS(v)[i]));
        }
    }
    if (!is_null(m) && (v = lookup_key(L, m, "origin")))
        kin_set_origin(L->K, f, frame_or_point(L, scalar(L, v, "a point"), NAME_POINT,
                                               loc_of(L, v)));
    d->kin = f;
}

/* A point's offset written as a vector expression: vec(F, a, b, c) is
 * the offset [a, b, c] in F's axes (as {frame: F, at: [a, b, c]}, so that
 * velocities keep the links' structure, kin.h); any other vector, such as
 * -R*world.z or pos(Q) - pos(P), is its world components. */
static void
offset_expression(Loader *L, yaml_node_t *m, yaml_node_t *v, int *f, ExprId at[3])
{
    for (int i = 0; i < NPAIRS(m); i++)
        if (!strcmp(key_of(L, &PAIRS(m)[i]), "frame"))
            diag_error(loc_of(L, node(L, PAIRS(m)[i].key)), "a point's offset "
                       "written as a vector expression takes no `frame:` (vec(F, a, b, c) is "
                       "in F's axes, any other vector in the world's); with `frame:`, give "
                       "the offset as components [a, b, c] in that frame's axes");
    Scalar sc;
    scalar_src(L, &sc, v, "a point's offset");
    L->sc.allow = ALLOW_POSITION;
    L->sc.what = "a point's offset";
    if (!parse_frame_vector(&L->sc, &sc.src, f, at)) {
        *f = KIN_WORLD;
        parse_vector(&L->sc, &sc.src, at);
    }
}

/* POINT: {frame: FRAME, from: POINT, at: [x, y, z]}: at from, offset by
 * at in the frame's axes; every key optional (the world, its origin,
 * [0, 0, 0]).  An offset of 2 components has z = 0.  `at` may instead be
 * a vector expression (offset_expression). */
static void
build_point(Loader *L, Define *d)
{
    static const char *const keys[] = {"frame", "from", "at", NULL};
    yaml_node_t *m = d->node, *v;
    int f = KIN_WORLD, from = KIN_ORIGIN;
    ExprId at[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    if (!is_null(m)) {
        as_map(L, m, "a point");
        check_keys(L, m, keys, "a point");
        if ((v = lookup_key(L, m, "frame")))
            f = frame_or_point(L, scalar(L, v, "a frame"), NAME_FRAME, loc_of(L, v));
        if ((v = lookup_key(L, m, "from")))
            from = frame_or_point(L, scalar(L, v, "a point"), NAME_POINT, loc_of(L, v));
        if ((v = lookup_key(L, m, "at")) && v->type == YAML_SCALAR_NODE && !is_null(v))
            offset_expression(L, m, v, &f, at);
        else if (v)
            vector(L, v, ALLOW_POSITION, "a point's offset", at);
    }
    d->kin = kin_point(L->K, from, f, at);
}

/* ---- going on after an error ---- */

/* Past this many errors a spec is not worth reading further: later
 * messages grow likelier to follow from earlier ones (clang's default
 * -ferror-limit is the same). */
enum { SPEC_MAX_ERRORS = 20 };

typedef void EntryFn(Loader *L, yaml_node_t *map, int i);

/* f(L, map, i), one entry of a section, so that an error in it is
 * reported and loading goes on with the next entry: a spec's independent
 * mistakes are found in one run.  0 if it failed.  What depends on a
 * failed entry is marked by the caller, and its uses are abandoned
 * without a second message (diag_abandon). */
/* After an entry's error: stop reading past SPEC_MAX_ERRORS.  (Its own
 * function: no temporary of it lives in checked's frame across longjmp.) */
static void
count_error(Loader *L)
{
    if (diag_error_count() >= SPEC_MAX_ERRORS && !L->stop) {
        diag_note((SrcLoc){L->path, 0, 0}, "stopping after %d errors", SPEC_MAX_ERRORS);
        L->stop = 1;
    }
    if (L->stop)
        diag_abandon();
}

static int
checked(Loader *L, EntryFn *f, yaml_node_t *map, int i)
{
    jmp_buf jb;
    jmp_buf *outer = diag_set_jump(&jb);
    if (setjmp(jb)) {
        diag_set_jump(outer);
        count_error(L);
        return 0;
    }
    f(L, map, i);
    diag_set_jump(outer);
    return 1;
}

/* Stop here if anything so far failed: what follows depends on it. */
static void
stop_if_failed(void)
{
    if (diag_error_count())
        diag_abandon();
}

/* ---- the sections ---- */

static void
name_parameter(Loader *L, yaml_node_t *map, int i)
{
    yaml_node_pair_t *p = &PAIRS(map)[i];
    L->s->param[i].name = add_name(L, node(L, p->key), NAME_PARAM, i);
    L->s->param[i].loc = loc_of(L, node(L, p->key));
}

static void
name_parameters(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->np = NPAIRS(map);
    s->param = arena_new_array(L->A, SpecParam, s->np);
    for (int i = 0; i < s->np; i++)
        checked(L, name_parameter, map, i);
}

static void
load_parameter(Loader *L, yaml_node_t *map, int i)
{
    L->s->param[i].value = number(L, node(L, PAIRS(map)[i].value), "a parameter value");
}

/* After every name is known, so that `k: 2*x` says x is a coordinate. */
static void
load_parameters(Loader *L, yaml_node_t *map)
{
    L->bad_param = arena_new_array(L->A, char, L->s->np + 1);
    for (int i = 0; i < L->s->np; i++)
        L->bad_param[i] = !checked(L, load_parameter, map, i);
}

static void
name_coordinate(Loader *L, yaml_node_t *seq, int i)
{
    Spec *s = L->s;
    yaml_node_t *n = node(L, ITEMS(seq)[i]);
    s->coord[i].q0 = s->coord[i].v0 = EXPR_ZERO;
    s->coord[i].name = add_name(L, n, NAME_COORD, i);
    s->coord[i].loc = loc_of(L, n);
}

static void
load_coordinates(Loader *L, yaml_node_t *seq)
{
    Spec *s = L->s;
    expect_type(L, seq, YAML_SEQUENCE_NODE, "coordinates");
    s->nq = NITEMS(seq);
    if (s->nq == 0)
        diag_error(loc_of(L, seq), "a spec needs at least one coordinate");
    s->coord = arena_new_array(L->A, SpecCoord, s->nq);
    L->sc.ncoord = s->nq;
    for (int i = 0; i < s->nq; i++)
        checked(L, name_coordinate, seq, i);
}

static void
name_input(Loader *L, yaml_node_t *map, int i)
{
    yaml_node_t *k = node(L, PAIRS(map)[i].key);
    L->s->input[i].name = add_name(L, k, NAME_INPUT, i);
    L->s->input[i].loc = loc_of(L, k);
}

static void
name_inputs(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nu = NPAIRS(map);
    s->input = arena_new_array(L->A, SpecInput, s->nu);
    for (int i = 0; i < s->nu; i++)
        checked(L, name_input, map, i);
}

/* Item `at` of L->def, the i-th pair of map, a define, frame or point. */
static void
name_item(Loader *L, yaml_node_t *map, int i, int at, ItemKind kind)
{
    static const NameKind kinds[] = {NAME_DEFINE, NAME_FRAME, NAME_POINT};
    Define *d = &L->def[at];
    d->kind = kind;
    d->node = node(L, PAIRS(map)[i].value);
    d->value = (ParseVal){0, {EXPR_NONE, EXPR_NONE, EXPR_NONE}};
    yaml_node_t *k = node(L, PAIRS(map)[i].key);
    const char *name = scalar(L, k, "a name");
    if (kind == ITEM_FRAME && !strcmp(name, "world"))
        diag_error(loc_of(L, k), "'world' is the inertial frame, there from the start: "
                   "name this frame otherwise");
    if (kind == ITEM_POINT && !strcmp(name, "origin"))
        diag_error(loc_of(L, k), "'origin' is the world's origin, there from the start: "
                   "name this point otherwise");
    d->name = add_name(L, k, kinds[kind], at);
}

static void
name_define(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, i, ITEM_DEFINE);
}

static void
name_frame(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, L->nitem_defs + i, ITEM_FRAME);
}

static void
name_point(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, L->nitem_defs + L->nframes + i, ITEM_POINT);
}

/* Every define, frame and point named, as items of L->def. */
static void
name_items(Loader *L, yaml_node_t *defines, yaml_node_t *frames, yaml_node_t *points)
{
    L->nitem_defs = defines ? NPAIRS(defines) : 0;
    L->nframes = frames ? NPAIRS(frames) : 0;
    L->npoints = points ? NPAIRS(points) : 0;
    L->ndef = L->nitem_defs + L->nframes + L->npoints;
    L->def = arena_new_array(L->A, Define, L->ndef + 1);
    for (int i = 0; i < L->nitem_defs; i++)
        checked(L, name_define, defines, i);
    for (int i = 0; i < L->nframes; i++)
        checked(L, name_frame, frames, i);
    for (int i = 0; i < L->npoints; i++)
        checked(L, name_point, points, i);
    L->K = kin_new(L->A, L->P, L->sc.D, L->nframes, L->npoints);
    L->sc.K = L->K;
    L->s->kin = L->K;
}

typedef struct DepCollect {
    Loader *L;
    Define *d;
    yaml_node_t *node; /* the scalar being read */
    int cap;
} DepCollect;

static void
collect_dep(void *ctx, const char *name, size_t len, size_t off)
{
    DepCollect *c = ctx;
    char buf[80];
    if (len >= sizeof buf)
        return;
    memcpy(buf, name, len);
    buf[len] = '\0';
    Name *nm = find_name(c->L, buf);
    if (!nm || (nm->kind != NAME_DEFINE && nm->kind != NAME_FRAME && nm->kind != NAME_POINT))
        return;
    Define *d = c->d;
    if (d->ndeps == c->cap) {
        int cap = c->cap ? 2 * c->cap : 8;
        int *deps = arena_new_array(c->L->A, int, cap);
        size_t *offs = arena_new_array(c->L->A, size_t, cap);
        yaml_node_t **nodes = arena_new_array(c->L->A, yaml_node_t *, cap);
        if (d->ndeps) {
            memcpy(deps, d->deps, sizeof *deps * (size_t)d->ndeps);
            memcpy(offs, d->dep_off, sizeof *offs * (size_t)d->ndeps);
            memcpy(nodes, d->dep_node, sizeof *nodes * (size_t)d->ndeps);
        }
        d->deps = deps, d->dep_off = offs, d->dep_node = nodes, c->cap = cap;
    }
    d->deps[d->ndeps] = nm->index;
    d->dep_node[d->ndeps] = c->node;
    d->dep_off[d->ndeps++] = off;
}

/* The names in every scalar under n (a mapping's values, not its keys). */
static void
collect_deps(DepCollect *c, yaml_node_t *n)
{
    Loader *L = c->L;
    if (n->type == YAML_SCALAR_NODE) {
        Scalar sc;
        scalar_src(L, &sc, n, "a name");
        c->node = n;
        parse_names(&sc.src, collect_dep, c);
    } else if (n->type == YAML_SEQUENCE_NODE) {
        for (int i = 0; i < NITEMS(n); i++)
            collect_deps(c, node(L, ITEMS(n)[i]));
    } else if (n->type == YAML_MAPPING_NODE) {
        for (int i = 0; i < NPAIRS(n); i++)
            collect_deps(c, node(L, PAIRS(n)[i].value));
    }
}

/* Define i refers to itself: report the cycle at its first step. */
static _Noreturn void
define_cycle(Loader *L, const int *stack, const int *edge, int sp, int i)
{
    int from = sp - 1;
    while (from > 0 && stack[from] != i)
        from--;
    char path[1024] = "";
    for (int k = from; k < sp; k++)
        snprintf(path + strlen(path), sizeof path - strlen(path), "%s -> ", L->def[stack[k]].name);
    snprintf(path + strlen(path), sizeof path - strlen(path), "%s", L->def[i].name);
    Define *d = &L->def[stack[from]];
    Scalar sc;
    scalar_src(L, &sc, d->dep_node[edge[from] - 1], "a define");
    SrcLoc at = scalar_where(&sc.src, d->dep_off[edge[from] - 1]);
    static const char *const kinds[] = {"define", "frame", "point"};
    diag_error(at, "%s '%s' refers to itself: %s", kinds[L->def[i].kind], L->def[i].name,
               path);
}

static void build_frame(Loader *L, Define *d);
static void build_point(Loader *L, Define *d);

static void
resolve_define_at(Loader *L, yaml_node_t *map, int i)
{
    (void)map;
    Define *d = &L->def[i];
    if (d->kind == ITEM_FRAME) {
        build_frame(L, d);
        return;
    }
    if (d->kind == ITEM_POINT) {
        build_point(L, d);
        return;
    }
    char what[120];
    snprintf(what, sizeof what, "define '%s'", d->name);
    Scalar sc;
    scalar_src(L, &sc, d->node, "a define");
    L->sc.allow = ALLOW_ALL;
    L->sc.what = arena_strdup(L->A, what);
    d->value = parse_value(&L->sc, &sc.src);
}

/* A define with an error is marked, and so are the defines and the
 * expressions that use it, silently: the one message is its own. */
static void
resolve_define(Loader *L, Define *d)
{
    if (!checked(L, resolve_define_at, NULL, (int)(d - L->def)))
        d->bad = 1;
}

/* Resolve every define after the defines it names: a depth-first
 * post-order with an explicit stack (chains of defines can be long). */
static void
resolve_defines(Loader *L)
{
    for (int i = 0; i < L->ndef; i++) {
        DepCollect c = {L, &L->def[i], NULL, 0};
        collect_deps(&c, L->def[i].node);
    }
    int *stack = arena_new_array(L->A, int, L->ndef + 1);
    int *edge = arena_new_array(L->A, int, L->ndef + 1);
    for (int root = 0; root < L->ndef; root++) {
        if (L->def[root].state)
            continue;
        int sp = 0;
        stack[sp] = root, edge[sp++] = 0;
        L->def[root].state = 1;
        while (sp) {
            Define *d = &L->def[stack[sp - 1]];
            if (edge[sp - 1] == d->ndeps) {
                resolve_define(L, d);
                d->state = 2;
                sp--;
                continue;
            }
            int next = d->deps[edge[sp - 1]++];
            if (L->def[next].state == 1)
                define_cycle(L, stack, edge, sp, next);
            if (L->def[next].state == 0) {
                L->def[next].state = 1;
                stack[sp] = next, edge[sp++] = 0;
            }
        }
    }
}

static void
load_input(Loader *L, yaml_node_t *map, int i)
{
    L->s->input[i].expr = expression(L, node(L, PAIRS(map)[i].value), ALLOW_SIGNAL,
                                     "an input signal");
}

static void
load_inputs(Loader *L, yaml_node_t *map)
{
    for (int i = 0; i < L->s->nu; i++)
        checked(L, load_input, map, i);
}

/* ---- physical data ---- */

/* The parameters' default values, for evaluating with them; the
 * parameters must be loaded. */
static const double *
defaults(Loader *L)
{
    Spec *s = L->s;
    if (!L->pdef) {
        L->pdef = arena_new_array(L->A, double, s->np + 1);
        for (int i = 0; i < s->np; i++)
            L->pdef[i] = s->param[i].value;
    }
    return L->pdef;
}

/* Require e > 0 (strict) or e >= 0 of the parameters, for the physical
 * datum at n: now, with the parameters' defaults (an error at n, saying
 * what and the value when it is a single number), and in the simulator
 * for the values --set gives (Spec.check).  The parameters must be
 * loaded. */
static void
require(Loader *L, ExprId e, int strict, const yaml_node_t *n, int show, const char *fmt,
        ...)
{
    Spec *s = L->s;
    for (int i = 0; i < s->np; i++) /* no value to check it with: its error is said */
        if (L->bad_param && L->bad_param[i] && expr_depends(L->P, e, expr_param(L->P, i)))
            return;
    char what[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    ExprEnv env = {.p = defaults(L)};
    double v = expr_eval(L->P, e, &env);
    for (int i = 0; i < s->np; i++) /* the value may be a scene's choice */
        if (s->param[i].fixed && expr_depends(L->P, e, expr_param(L->P, i)))
            snprintf(what + strlen(what), sizeof what - strlen(what), "%s%s fixed at %g",
                     strstr(what, " fixed at ") ? ", " : " (with ", s->param[i].name,
                     s->param[i].value);
    if (strstr(what, " fixed at "))
        snprintf(what + strlen(what), sizeof what - strlen(what), ")");
    if (!(strict ? v > 0 : v >= 0)) {
        if (show)
            diag_error(loc_of(L, n), "%s; it is %g", what, v);
        diag_error(loc_of(L, n), "%s", what);
    }
    if (expr_is_const(L->P, e, NULL))
        return; /* no parameter can change it */
    char params[512] = "";
    for (int i = 0; i < s->np; i++)
        if (expr_depends(L->P, e, expr_param(L->P, i)))
            snprintf(params + strlen(params), sizeof params - strlen(params), "%s%s",
                     params[0] ? ", " : "", s->param[i].name);
    if (s->ncheck == s->capcheck) {
        s->capcheck = s->capcheck ? 2 * s->capcheck : 16;
        SpecCheck *c = arena_new_array(L->A, SpecCheck, s->capcheck);
        if (s->ncheck)
            memcpy(c, s->check, (size_t)s->ncheck * sizeof *c);
        s->check = c;
    }
    s->check[s->ncheck++] = (SpecCheck){e, strict, arena_strdup(L->A, what),
                                        arena_strdup(L->A, params), loc_of(L, n)};
}

/* A mass: of parameters, not negative (a massless point is fine: forces
 * can act on it). */
static ExprId
mass_of(Loader *L, const yaml_node_t *n, const char *kind, const char *name)
{
    ExprId m = expression(L, n, ALLOW_PARAM, "a mass");
    require(L, m, 0, n, 1, "%s '%s': a mass cannot be negative", kind, name);
    return m;
}

/* Body b's inertia at n, once loaded: a planar moment must be positive; a
 * 3-D tensor I positive definite (a zero principal moment leaves a
 * rotation without inertia: the mass matrix is singular), and that of
 * some distribution of mass: S = tr(I)/2 - I, its second moments
 * sum m x_i x_j, positive semi-definite, which for principal moments is
 * the triangle inequality A + B >= C in every order. */
static void
require_inertia(Loader *L, const yaml_node_t *n, const SpecBody *b)
{
    ExprPool *P = L->P;
    const ExprId *I = b->inertia;
    if (b->dim == 2) {
        require(L, I[0], 1, n, 1, "body '%s': its moment of inertia must be positive",
                b->name);
        return;
    }
    const char *pd = "body '%s': its inertia must be positive definite (a principal "
                     "moment of zero or less leaves a rotation with no inertia)";
    ExprId m2b = expr_mul(P, I[1], I[3]);
    ExprId m2 = expr_sub(P, expr_mul(P, I[0], I[4]), m2b);
    ExprId det = EXPR_ZERO, S[9], half = expr_const(P, 0.5);
    for (int j = 0; j < 3; j++) { /* along the first row */
        int a = (j + 1) % 3, c = (j + 2) % 3;
        ExprId ca = expr_mul(P, I[3 + c], I[6 + a]);
        ExprId minor = expr_sub(P, expr_mul(P, I[3 + a], I[6 + c]), ca);
        det = expr_add(P, det, expr_mul(P, I[j], minor));
    }
    require(L, I[0], 1, n, 0, pd, b->name);
    require(L, m2, 1, n, 0, pd, b->name);
    require(L, det, 1, n, 0, pd, b->name);
    ExprId tr = expr_mul(P, half, expr_add(P, expr_add(P, I[0], I[4]), I[8]));
    for (int k = 0; k < 9; k++)
        S[k] = k % 4 == 0 ? expr_sub(P, tr, I[k]) : expr_neg(P, I[k]);
    const char *real = "body '%s': no distribution of mass has this inertia (its principal "
                       "moments must satisfy A + B >= C in every order)";
    for (int k = 0; k < 3; k++) /* every principal minor of S */
        require(L, S[4 * k], 0, n, 0, real, b->name);
    for (int k = 0; k < 3; k++) {
        int a = (k + 1) % 3, c = (k + 2) % 3;
        ExprId off = expr_mul(P, S[3 * a + c], S[3 * c + a]);
        require(L, expr_sub(P, expr_mul(P, S[4 * a], S[4 * c]), off), 0, n, 0, real, b->name);
    }
    ExprId dS = EXPR_ZERO;
    for (int j = 0; j < 3; j++) {
        int a = (j + 1) % 3, c = (j + 2) % 3;
        ExprId ca = expr_mul(P, S[3 + c], S[6 + a]);
        ExprId minor = expr_sub(P, expr_mul(P, S[3 + a], S[6 + c]), ca);
        dS = expr_add(P, dS, expr_mul(P, S[j], minor));
    }
    require(L, dS, 0, n, 0, real, b->name);
}

static void
load_particle(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"mass", "position", NULL};
    {
        yaml_node_t *k = node(L, PAIRS(map)[i].key), *v = node(L, PAIRS(map)[i].value);
        SpecParticle *pt = &L->s->part[i];
        pt->name = arena_strdup(L->A, scalar(L, k, "a particle name"));
        pt->loc = loc_of(L, k);
        as_map(L, v, "a particle");
        check_keys(L, v, keys, "a particle");
        yaml_node_t *mass = lookup_key(L, v, "mass"), *pos = lookup_key(L, v, "position");
        if (!mass)
            diag_error(loc_of(L, v), "particle '%s' has no mass", pt->name);
        if (!pos)
            diag_error(loc_of(L, v), "particle '%s' has no position", pt->name);
        pt->mass = mass_of(L, mass, "particle", pt->name);
        pt->dim = world_vector(L, pos, ALLOW_POSITION, "a position", pt->pos);
        Name *nm = pos->type == YAML_SCALAR_NODE ? find_name(L, scalar(L, pos, "a point")) : NULL;
        pt->point = -1;
        if (nm && nm->kind == NAME_POINT) {
            pt->point = item(L, nm)->kin;
            kin_vel(L->K, pt->point, pt->vel);
            pt->has_vel = 1;
        }
    }
}

/* A particle or body that failed keeps a name ("" if even that failed),
 * so that a force on it is abandoned, not reported as unknown. */
static void
load_particles(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->npart = NPAIRS(map);
    s->part = arena_new_array(L->A, SpecParticle, s->npart);
    L->bad_part = arena_new_array(L->A, char, s->npart + 1);
    for (int i = 0; i < s->npart; i++)
        if (!checked(L, load_particle, map, i)) {
            L->bad_part[i] = 1;
            if (!s->part[i].name)
                s->part[i].name = "";
        }
}

/* Inertia about the centre in the body frame: a scalar (planar), three
 * principal moments, or a symmetric 3 x 3 tensor. */
static void
load_inertia(Loader *L, yaml_node_t *n, SpecBody *b)
{
    for (int k = 0; k < 9; k++)
        b->inertia[k] = EXPR_ZERO;
    if (b->dim == 2) {
        b->inertia[0] = expression(L, n, ALLOW_PARAM, "an inertia");
        return;
    }
    expect_type(L, n, YAML_SEQUENCE_NODE, "an inertia (3 principal moments or a 3 x 3 tensor)");
    if (NITEMS(n) != 3)
        diag_error(loc_of(L, n), "an inertia has 3 principal moments or 3 rows, not %d",
                   (int)NITEMS(n));
    int tensor = node(L, ITEMS(n)[0])->type == YAML_SEQUENCE_NODE;
    for (int i = 0; i < 3; i++) {
        yaml_node_t *row = node(L, ITEMS(n)[i]);
        if ((row->type == YAML_SEQUENCE_NODE) != tensor)
            diag_error(loc_of(L, row), "write an inertia as 3 moments or as 3 rows, not both");
        if (!tensor) {
            b->inertia[4 * i] = expression(L, row, ALLOW_PARAM, "a principal moment");
            continue;
        }
        if (NITEMS(row) != 3)
            diag_error(loc_of(L, row), "a row of the inertia tensor has 3 entries, not %d",
                       (int)NITEMS(row));
        for (int j = 0; j < 3; j++)
            b->inertia[3 * i + j] = expression(L, node(L, ITEMS(row)[j]), ALLOW_PARAM,
                                               "an inertia entry");
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < i; j++)
            if (b->inertia[3 * i + j] != b->inertia[3 * j + i])
                diag_error(loc_of(L, n), "the inertia tensor of body '%s' is not symmetric "
                           "(row %d, column %d)", b->name, i + 1, j + 1);
}

/* The Euler parameters e = (e0, e1, e2, e3) of a rotation, scalar first:
 * R = (e0^2 - |v|^2) I + 2 v v^T + 2 e0 [v x] with v = (e1, e2, e3), and
 * in body axes w = 2 L e' with
 *     L = [-e1  e0  e3 -e2;  -e2 -e3  e0  e1;  -e3  e2 -e1  e0]
 * (on |e| = 1, which the unit constraint keeps).  The parameters must be
 * four distinct coordinates. */
static void
quaternion_omega(Loader *L, yaml_node_t *k, yaml_node_t *v, SpecBody *b)
{
    ExprPool *P = L->P;
    ExprId e[4], d[4];
    quaternion_coords(L, v, arena_printf(L->A, "body '%s'", b->name), b->quat);
    for (int i = 0; i < 4; i++) {
        e[i] = expr_var(P, b->quat[i], 0);
        d[i] = expr_var(P, b->quat[i], 1);
    }
    static const int Lrow[3][4][2] = { /* (sign, index of e) per column */
        {{-1, 1}, {1, 0}, {1, 3}, {-1, 2}},
        {{-1, 2}, {-1, 3}, {1, 0}, {1, 1}},
        {{-1, 3}, {1, 2}, {-1, 1}, {1, 0}},
    };
    ExprId two = expr_const(P, 2);
    for (int r = 0; r < 3; r++) {
        ExprId w = EXPR_ZERO;
        for (int c = 0; c < 4; c++) {
            ExprId t = expr_mul(P, e[Lrow[r][c][1]], d[c]);
            w = Lrow[r][c][0] > 0 ? expr_add(P, w, t) : expr_sub(P, w, t);
        }
        b->omega[r] = expr_mul(P, two, w);
    }
    b->quat_loc = loc_of(L, k);
}

/* omega for intrinsic rotations R = R_a1(th1) R_a2(th2) ... about the
 * axes of the sequence ("zxz": z, then the new x, then the new z):
 *     w = e_an th_n' + R_an^T (e_a(n-1) th_(n-1)' + R_a(n-1)^T (...)) */
static void
rotation_omega(Loader *L, yaml_node_t *map, SpecBody *b)
{
    ExprPool *P = L->P;
    if (NPAIRS(map) != 1)
        diag_error(loc_of(L, map), "a rotation is one sequence of axes with its angles, "
                   "such as {zxz: [psi, theta, phi]}, or {quaternion: [e0, e1, e2, e3]}");
    yaml_node_t *k = node(L, PAIRS(map)[0].key), *v = node(L, PAIRS(map)[0].value);
    const char *axes = scalar(L, k, "a rotation sequence");
    if (!strcmp(axes, "quaternion")) {
        quaternion_omega(L, k, v, b);
        return;
    }
    size_t na = strlen(axes);
    if (na < 1 || na > 3 || strspn(axes, "xyz") != na)
        diag_error(loc_of(L, k), "'%s' is not a rotation sequence: 1 to 3 of the axes "
                   "x, y, z, such as zxz or zyx, or quaternion", axes);
    expect_type(L, v, YAML_SEQUENCE_NODE, "the angles of a rotation");
    if ((size_t)NITEMS(v) != na)
        diag_error(loc_of(L, v), "rotation %s has %zu angles, not %d", axes, na,
                   (int)NITEMS(v));
    ExprId w[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    for (size_t i = 0; i < na; i++) {
        ExprId th = expression(L, node(L, ITEMS(v)[i]), ALLOW_POSITION, "an angle");
        ExprId c = expr_unary(P, EXPR_COS, th), s = expr_unary(P, EXPR_SIN, th);
        int a = axes[i] - 'x', j = (a + 1) % 3, l = (a + 2) % 3;
        /* R_a^T w: rotate the other two components by -th */
        ExprId sl = expr_mul(P, s, w[l]);
        ExprId wj = expr_add(P, expr_mul(P, c, w[j]), sl);
        ExprId sj = expr_mul(P, s, w[j]);
        ExprId wl = expr_sub(P, expr_mul(P, c, w[l]), sj);
        w[j] = wj, w[l] = wl;
        ExprId rate = diff_time(L->sc.D, th);
        w[a] = expr_add(P, w[a], rate);
    }
    for (int i = 0; i < 3; i++)
        b->omega[i] = w[i];
}

/* More than one of rotation, omega, angle: at the second one written. */
static _Noreturn void
two_orientations(Loader *L, const SpecBody *b, yaml_node_t *map)
{
    static const char *const keys[] = {"rotation", "omega", "angle", "frame"};
    int found[2], n = 0;
    for (int i = 0; i < NPAIRS(map) && n < 2; i++)
        for (int k = 0; k < 4; k++)
            if (!strcmp(key_of(L, &PAIRS(map)[i]), keys[k]))
                found[n++] = i;
    const char *first = key_of(L, &PAIRS(map)[found[0]]);
    const char *second = key_of(L, &PAIRS(map)[found[1]]);
    diag_error(loc_of(L, node(L, PAIRS(map)[found[1]].key)), "body '%s' has both `%s` and "
               "`%s`; its orientation is exactly one of frame, rotation, omega, angle", b->name,
               first, second);
}

static void
load_body(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"mass", "center", "inertia", "rotation", "omega",
                                       "angle", "frame", NULL};
    Spec *s = L->s;
    {
        yaml_node_t *k = node(L, PAIRS(map)[i].key), *v = node(L, PAIRS(map)[i].value);
        SpecBody *b = &s->body[i];
        b->name = arena_strdup(L->A, scalar(L, k, "a body name"));
        b->loc = loc_of(L, k);
        for (int j = 0; j < s->npart; j++)
            if (!strcmp(s->part[j].name, b->name))
                diag_error(b->loc, "'%s' is already the name of a particle (line %d)", b->name,
                           s->part[j].loc.line);
        as_map(L, v, "a body");
        check_keys(L, v, keys, "a body");
        yaml_node_t *mass = lookup_key(L, v, "mass"), *c = lookup_key(L, v, "center");
        yaml_node_t *in = lookup_key(L, v, "inertia"), *rot = lookup_key(L, v, "rotation");
        yaml_node_t *om = lookup_key(L, v, "omega"), *ang = lookup_key(L, v, "angle");
        yaml_node_t *fr = lookup_key(L, v, "frame");
        const char *missing = !mass ? "mass" : !c ? "center" : !in ? "inertia" : NULL;
        if (missing)
            diag_error(loc_of(L, v), "body '%s' has no %s", b->name, missing);
        b->quat[0] = -1;
        b->frame = b->point = -1;
        b->mass = mass_of(L, mass, "body", b->name);
        int how = !!rot + !!om + !!ang + !!fr;
        if (how > 1)
            two_orientations(L, b, v);
        if (fr) { /* placed by a frame: it turns with it, its inertia in its axes */
            int f = frame_or_point(L, scalar(L, fr, "a frame"), NAME_FRAME, loc_of(L, fr));
            b->dim = world_vector(L, c, ALLOW_POSITION, "a centre of mass", b->center);
            if (b->dim != 3)
                diag_error(loc_of(L, c), "a body placed by a frame has a 3-D centre: a point, "
                           "or [x, y, z]");
            const char *cn = c->type == YAML_SCALAR_NODE ? scalar(L, c, "a point") : "";
            Name *nm = find_name(L, cn);
            if (kin_origin(L->K, f) < 0 && nm && nm->kind == NAME_POINT)
                kin_set_origin(L->K, f, item(L, nm)->kin); /* vel(P, F) moves with it */
            if (nm && nm->kind == NAME_POINT) { /* its velocity by the links' structure */
                b->point = item(L, nm)->kin;
                kin_vel(L->K, b->point, b->center_vel);
                b->has_center_vel = 1;
            }
            b->frame = f;
            L->body_frame[i] = f;
            load_inertia(L, in, b);
            require_inertia(L, in, b);
            kin_omega_local(L->K, f, b->omega);
            return;
        }
        b->dim = vector(L, c, ALLOW_POSITION, "a centre of mass", b->center);
        load_inertia(L, in, b);
        require_inertia(L, in, b);
        b->omega[0] = b->omega[1] = b->omega[2] = EXPR_ZERO;
        if (how != 1)
            diag_error(loc_of(L, v), "body '%s' needs exactly one of %s", b->name,
                       b->dim == 2 ? "angle (planar), omega"
                                   : "frame, rotation (e.g. {zxz: [psi, theta, phi]}), omega");
        if (ang && b->dim != 2)
            diag_error(loc_of(L, ang), "`angle` is for planar bodies; a 3-D body takes a "
                       "`rotation` or `omega`");
        if (ang)
            b->omega[0] = diff_time(L->sc.D, expression(L, ang, ALLOW_POSITION, "an angle"));
        else if (rot && b->dim != 2)
            rotation_omega(L, as_map(L, rot, "a rotation"), b);
        else if (rot)
            diag_error(loc_of(L, rot), "a planar body turns by an `angle`");
        else if (b->dim == 2)
            b->omega[0] = expression(L, om, ALLOW_KINETIC, "an angular velocity");
        else if (vector(L, om, ALLOW_KINETIC, "an angular velocity", b->omega) != 3)
            diag_error(loc_of(L, om), "a 3-D body's angular velocity has 3 components");
    }
}

static void
load_bodies(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nbody = NPAIRS(map);
    s->body = arena_new_array(L->A, SpecBody, s->nbody);
    L->bad_body = arena_new_array(L->A, char, s->nbody + 1);
    L->body_frame = arena_new_array(L->A, int, s->nbody + 1);
    for (int i = 0; i < s->nbody; i++)
        L->body_frame[i] = -1;
    for (int i = 0; i < s->nbody; i++)
        if (!checked(L, load_body, map, i)) {
            L->bad_body[i] = 1;
            if (!s->body[i].name)
                s->body[i].name = "";
        }
}

/* A scalar or a sequence of scalars: the terms of an energy. */
static SpecTerm *
load_terms(Loader *L, yaml_node_t *n, unsigned allow, const char *what, int *count)
{
    int one = n->type == YAML_SCALAR_NODE;
    if (!one)
        expect_type(L, n, YAML_SEQUENCE_NODE, what);
    *count = one ? 1 : NITEMS(n);
    SpecTerm *t = arena_new_array(L->A, SpecTerm, *count);
    for (int i = 0; i < *count; i++) {
        yaml_node_t *item = one ? n : node(L, ITEMS(n)[i]);
        t[i].loc = loc_of(L, item);
        t[i].expr = expression(L, item, allow, what);
    }
    return t;
}

/* The index of the name node n holds among cands[0..count), or a
 * diagnostic at n: "unknown WHAT 'x'", or with is_not "'x' is not a
 * WHAT", and "; did you mean 'y'?" when a name is close, else the list
 * of them (PLURAL) when it is short. */
static int
find_in(Loader *L, yaml_node_t *n, const char *what, const char *plural, int is_not,
        const char **cands, int count)
{
    const char *name = scalar(L, n, what);
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
        diag_error(loc_of(L, n), "%s; did you mean %s?", msg, near);
    if (count == 0 || count > 12)
        diag_error(loc_of(L, n), "%s", msg);
    char list[1024] = "";
    for (int i = 0; i < count; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                 cands[i]);
    diag_error(loc_of(L, n), "%s; the %s %s %s", msg, count == 1 ? what : plural,
               count == 1 ? "is" : "are", list);
}

/* The particle or body a force acts on: its index, *is_body set. */
static int
find_target(Loader *L, yaml_node_t *n, int *is_body)
{
    const Spec *s = L->s;
    const char **cands = arena_new_array(L->A, const char *, s->npart + s->nbody + 1);
    for (int i = 0; i < s->npart; i++)
        cands[i] = s->part[i].name;
    for (int i = 0; i < s->nbody; i++)
        cands[s->npart + i] = s->body[i].name;
    int k = find_in(L, n, "particle or body", "particles and bodies", 0, cands,
                    s->npart + s->nbody);
    *is_body = k >= s->npart;
    if (*is_body ? L->bad_body[k - s->npart] : L->bad_part[k])
        diag_abandon(); /* its own error is reported */
    return *is_body ? k - s->npart : k;
}

/* A force vector on a particle or a body's centre, or a torque on a body. */
static void
load_applied(Loader *L, yaml_node_t *map, yaml_node_t *v, yaml_node_t *on, SpecForce *f,
             int torque)
{
    const char *what = torque ? "a torque" : "a force";
    if (!on)
        diag_error(loc_of(L, map), "%s needs `on: %s`, what it acts on", what,
                   torque ? "BODY" : "PARTICLE");
    int is_body, k = find_target(L, on, &is_body);
    f->particle = is_body ? -1 : k;
    f->body = is_body ? k : -1;
    int dim = is_body ? L->s->body[k].dim : L->s->part[k].dim;
    const char *name = is_body ? L->s->body[k].name : L->s->part[k].name;
    if (torque && !is_body)
        diag_error(loc_of(L, on), "a torque acts on a body, and '%s' is a particle", name);
    if (torque && dim == 2) {
        f->dim = 1;
        f->vec[0] = expression(L, v, ALLOW_FORCE, what);
        return;
    }
    if (torque && v->type == YAML_SCALAR_NODE) { /* a vector: to the body's axes */
        if (L->body_frame[k] < 0)
            diag_error(loc_of(L, v), "a torque as a vector needs a body placed by `frame:`; "
                       "on body '%s', give its components in its axes, [tx, ty, tz]", name);
        ExprId w[3];
        world_vector(L, v, ALLOW_FORCE, what, w);
        kin_to_frame(L->K, L->body_frame[k], w, f->vec);
        f->dim = 3;
        return;
    }
    f->dim = torque ? vector(L, v, ALLOW_FORCE, what, f->vec)
                    : world_vector(L, v, ALLOW_FORCE, what, f->vec);
    if (f->dim != dim)
        diag_error(loc_of(L, v), "%s has %d components but %s '%s' is %d-D", what, f->dim,
                   is_body ? "body" : "particle", name, dim);
}

/* Virtual work W at node v, linear in the variations: W = sum_i Q_i
 * delta(q_i) with no Q_i holding a variation and nothing left over.  An
 * error at v otherwise, with the form it should take. */
#define WORK_HINT "; for example work: \"-c*r'*delta(r) + u*delta(theta_m)\" (a force " \
                  "times the variation of what it acts along)"
static ExprId
work(Loader *L, yaml_node_t *v)
{
    ExprPool *P = L->P;
    ExprId W = expression(L, v, ALLOW_WORK, "a virtual-work expression");
    if (!(expr_deps(P, W) & DEP_S))
        diag_error(loc_of(L, v), "virtual work is a sum of forces times variations "
                   "delta(...), and this expression has none" WORK_HINT);
    int n = L->s->nq;
    ExprId *seeds = arena_new_array(L->A, ExprId, n), *zeros = arena_new_array(L->A, ExprId, n);
    for (int i = 0; i < n; i++) {
        seeds[i] = expr_seed(P, i, 0), zeros[i] = EXPR_ZERO;
        if (expr_deps(P, diff_partial(L->sc.D, W, seeds[i])) & DEP_S)
            diag_error(loc_of(L, v), "virtual work is not linear in the variations here: "
                       "delta(%s) is multiplied by a variation, or inside a function"
                       WORK_HINT, L->s->coord[i].name);
    }
    if (expr_subst(P, W, n, seeds, zeros) != EXPR_ZERO)
        diag_error(loc_of(L, v), "a term of this virtual work has no variation: every term is "
                   "a force times a variation delta(...)" WORK_HINT);
    return W;
}

static void
load_force(Loader *L, yaml_node_t *map, SpecForce *f)
{
    static const char *const keys[] = {"gravity", "potential", "force", "torque", "work",
                                       "kinetic", "on", NULL};
    as_map(L, map, "a force");
    check_keys(L, map, keys, "an effect");
    f->loc = loc_of(L, map);
    int kinds = 0;
    yaml_node_t *v, *on = lookup_key(L, map, "on");
    if ((v = lookup_key(L, map, "gravity"))) {
        f->kind = FORCE_GRAVITY, kinds++;
        f->dim = vector(L, v, ALLOW_FIELD, "a gravity field", f->vec);
        for (int k = 0; k < L->s->npart; k++)
            if (!L->bad_part[k] && L->s->part[k].dim != f->dim)
                diag_error(loc_of(L, v), "gravity has %d components but particle '%s' is %d-D",
                           f->dim, L->s->part[k].name, L->s->part[k].dim);
        for (int k = 0; k < L->s->nbody; k++)
            if (!L->bad_body[k] && L->s->body[k].dim != f->dim)
                diag_error(loc_of(L, v), "gravity has %d components but body '%s' is %d-D",
                           f->dim, L->s->body[k].name, L->s->body[k].dim);
        if (L->s->npart + L->s->nbody == 0)
            diag_error(loc_of(L, v), "gravity acts on particles and bodies, and this spec "
                       "has none (write a potential instead)");
    }
    if ((v = lookup_key(L, map, "potential")))
        f->kind = FORCE_POTENTIAL, kinds++,
        f->expr = expression(L, v, ALLOW_POTENTIAL, "a potential");
    if ((v = lookup_key(L, map, "work")))
        f->kind = FORCE_WORK, kinds++,
        f->expr = work(L, v);
    if ((v = lookup_key(L, map, "kinetic")))
        f->kind = FORCE_KINETIC, kinds++,
        f->expr = expression(L, v, ALLOW_KINETIC, "a kinetic-energy term");
    if ((v = lookup_key(L, map, "force")))
        f->kind = FORCE_VECTOR, kinds++, load_applied(L, map, v, on, f, 0);
    if ((v = lookup_key(L, map, "torque")))
        f->kind = FORCE_TORQUE, kinds++, load_applied(L, map, v, on, f, 1);
    if (on && kinds == 1 && f->kind != FORCE_VECTOR && f->kind != FORCE_TORQUE)
        diag_error(loc_of(L, on), "`on` belongs to a force or a torque");
    if (kinds != 1)
        diag_error(loc_of(L, map), kinds ? "an effect item has exactly one of gravity, "
                   "potential, force, torque, work, kinetic (write a list for several)"
                   : "an effect item needs one of gravity, potential, force, torque, work, "
                   "kinetic");
}

static void
load_effect(Loader *L, yaml_node_t *map, int i)
{
    Spec *s = L->s;
    {
        yaml_node_t *k = node(L, PAIRS(map)[i].key), *v = node(L, PAIRS(map)[i].value);
        SpecEffect *e = &s->effect[i];
        e->name = arena_strdup(L->A, scalar(L, k, "an effect name"));
        e->loc = loc_of(L, k);
        e->enabled = 1;
        if (!is_identifier(e->name))
            diag_error(e->loc, "'%s' is not a valid effect name", e->name);
        int list = v->type == YAML_SEQUENCE_NODE;
        e->nforce = list ? NITEMS(v) : 1;
        if (e->nforce == 0)
            diag_error(loc_of(L, v), "effect '%s' is empty", e->name);
        e->force = arena_new_array(L->A, SpecForce, e->nforce);
        for (int j = 0; j < e->nforce; j++)
            load_force(L, list ? node(L, ITEMS(v)[j]) : v, &e->force[j]);
    }
}

static void
load_effects(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->neffect = NPAIRS(map);
    s->effect = arena_new_array(L->A, SpecEffect, s->neffect);
    for (int i = 0; i < s->neffect; i++)
        if (!checked(L, load_effect, map, i) && !s->effect[i].name)
            s->effect[i].name = "";
}

static int
find_coordinate(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->nq + 1);
    for (int i = 0; i < L->s->nq; i++)
        cands[i] = L->s->coord[i].name;
    return find_in(L, n, "coordinate", "coordinates", 1, cands, L->s->nq);
}

/* NAME: EXPR, or NAME: {expr: EXPR, dependent: COORDINATE}. */
static void
load_constraint(Loader *L, yaml_node_t *k, yaml_node_t *v, SpecConstraint *c)
{
    static const char *const keys[] = {"expr", "dependent", NULL};
    c->name = arena_strdup(L->A, scalar(L, k, "a constraint name"));
    c->loc = loc_of(L, k);
    c->dependent = -1;
    if (!is_identifier(c->name))
        diag_error(c->loc, "'%s' is not a valid constraint name", c->name);
    yaml_node_t *e = v;
    if (v->type == YAML_MAPPING_NODE) {
        as_map(L, v, "a constraint");
        check_keys(L, v, keys, "a constraint");
        if (!(e = lookup_key(L, v, "expr")))
            diag_error(loc_of(L, v), "constraint '%s' has no `expr:`", c->name);
        yaml_node_t *d = lookup_key(L, v, "dependent");
        if (d) {
            c->dependent = find_coordinate(L, d);
            c->dep_loc = loc_of(L, d);
        }
    }
    c->expr = expression(L, e, ALLOW_CONSTRAINT, "a constraint");
    c->order = expr_max_order(L->P, c->expr);
    if (!(expr_deps(L->P, c->expr) & DEP_ANY_Q))
        diag_error(loc_of(L, e), "constraint '%s' involves no coordinate, so it constrains "
                   "nothing (its order cannot be determined)", c->name);
    /* only second-order constraints are used as written: the others are
     * differentiated, and an input's derivative is unknown.  Parsed again
     * without inputs, the error points at the input. */
    if (c->order < 2 && (expr_deps(L->P, c->expr) & DEP_U))
        expression(L, e, ALLOW_CONSTRAINT & ~(unsigned)DEP_U,
                   c->order == 0 ? "a holonomic constraint" : "a first-order constraint");
}

static void
load_constraint_at(Loader *L, yaml_node_t *map, int i)
{
    Spec *s = L->s;
    SpecConstraint *c = &s->constraint[i];
    load_constraint(L, node(L, PAIRS(map)[i].key), node(L, PAIRS(map)[i].value), c);
    for (int j = 0; j < i; j++)
        if (c->dependent >= 0 && s->constraint[j].dependent == c->dependent)
            diag_error(c->dep_loc, "coordinate '%s' is already the dependent coordinate "
                       "of constraint '%s'", s->coord[c->dependent].name,
                       s->constraint[j].name);
}

static void
load_constraints(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nconstraint = NPAIRS(map);
    s->constraint = arena_new_array(L->A, SpecConstraint, s->nconstraint);
    for (int i = 0; i < s->nconstraint; i++)
        s->constraint[i].dependent = -1;
    for (int i = 0; i < s->nconstraint; i++)
        checked(L, load_constraint_at, map, i);
    if (s->nconstraint >= s->nq) /* at the one too many */
        diag_error(s->constraint[s->nq - 1].loc, "%d constraint%s on %d coordinate%s "
                   "leave%s no freedom of motion", s->nconstraint,
                   s->nconstraint == 1 ? "" : "s", s->nq, s->nq == 1 ? "" : "s",
                   s->nconstraint == 1 ? "s" : "");
}

/* A quaternion's unit constraint, NAME_unit: e.e - 1 = 0, after the
 * spec's own constraints (holonomic, kept like any other: at acceleration
 * level, projected by --stabilize project), the bodies' first, then the
 * frames'.  For elimination its dependent coordinate is the Euler
 * parameter largest at the start (with the defaults), where
 * df/de'' = 2 e is surest not to vanish; no fixed choice is safe for
 * every orientation. */
static void
add_unit_constraints(Loader *L)
{
    Spec *s = L->s;
    ExprPool *P = L->P;
    SpecQuat *quat = arena_new_array(L->A, SpecQuat, s->nbody + s->nfquat + 1);
    int extra = 0;
    for (int i = 0; i < s->nbody; i++)
        if (s->body[i].quat[0] >= 0) {
            const SpecBody *b = &s->body[i];
            quat[extra] = (SpecQuat){b->name, arena_printf(L->A, "body '%s'", b->name),
                                     {b->quat[0], b->quat[1], b->quat[2], b->quat[3]},
                                     b->quat_loc};
            extra++;
        }
    for (int i = 0; i < s->nfquat; i++)
        quat[extra++] = s->fquat[i];
    if (!extra)
        return;
    int nuser = s->nconstraint;
    SpecConstraint *c = arena_new_array(L->A, SpecConstraint, s->nconstraint + extra);
    if (s->nconstraint)
        memcpy(c, s->constraint, (size_t)s->nconstraint * sizeof *c);
    s->constraint = c;
    for (int i = 0; i < extra; i++) {
        const SpecQuat *qu = &quat[i];
        const char *name = arena_printf(L->A, "%s_unit", qu->name);
        for (int j = 0; j < s->nconstraint; j++) {
            if (strcmp(s->constraint[j].name, name))
                continue;
            if (j < nuser)
                diag_error(s->constraint[j].loc, "'%s' is the name of %s's unit quaternion "
                           "constraint; name this one otherwise", name, qu->owner);
            diag_error(qu->loc, "%s and %s would both have the unit quaternion constraint "
                       "'%s': rename one", quat[j - nuser].owner, qu->owner, name);
        }
        ExprId g = expr_const(P, -1);
        for (int k = 0; k < 4; k++)
            g = expr_add(P, g, expr_powi(P, expr_var(P, qu->q[k], 0), 2));
        double best = -1;
        ExprEnv env = {.p = defaults(L)};
        int dep = -1;
        for (int k = 0; k < 4; k++) {
            int taken = 0;
            for (int j = 0; j < s->nconstraint; j++)
                taken |= s->constraint[j].dependent == qu->q[k];
            double v = fabs(expr_eval(P, s->coord[qu->q[k]].q0, &env));
            if (!taken && v > best)
                best = v, dep = qu->q[k];
        }
        s->constraint[s->nconstraint++] = (SpecConstraint){name, qu->loc, g, 0, dep, qu->loc};
    }
    if (s->nconstraint >= s->nq)
        diag_error(s->constraint[s->nconstraint - 1].loc, "%d constraints (with the unit "
                   "quaternions') on %d coordinates leave no freedom of motion",
                   s->nconstraint, s->nq);
}

static const char *
method_name(Loader *L, yaml_node_t *n)
{
    const char *m = scalar(L, n, "method");
    int count = 0;
    for (; spec_methods[count]; count++)
        if (!strcmp(spec_methods[count], m))
            return spec_methods[count];
    const char *near = diag_nearest(m, spec_methods, count);
    if (near)
        diag_error(loc_of(L, n), "unknown method '%s'; did you mean %s?", m, near);
    char list[256] = "";
    for (int k = 0; k < count; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "",
                 spec_methods[k]);
    diag_error(loc_of(L, n), "unknown method '%s'; the methods are %s", m, list);
}

static int
find_effect(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->neffect + 1);
    for (int i = 0; i < L->s->neffect; i++)
        cands[i] = L->s->effect[i].name;
    return find_in(L, n, "effect", "effects", 0, cands, L->s->neffect);
}

static double
positive(Loader *L, yaml_node_t *n, const char *what, int zero_ok)
{
    double v = number(L, n, what);
    if (v < 0 || (!zero_ok && v == 0))
        diag_error(loc_of(L, n), "%s must be %s, not %.17g", what,
                   zero_ok ? "zero or positive" : "positive", v);
    return v;
}

/* ---- scenes ---- */

static yaml_node_t *
section(Loader *L, yaml_node_t *root, const char *key, int map)
{
    yaml_node_t *n = lookup_key(L, root, key);
    if (!n || is_null(n))
        return NULL;
    return map ? as_map(L, n, key) : n;
}


/* Command-line errors: no location, "eomc: error: ...". */
static const SrcLoc cmdline = {NULL, 0, 0};

/* Where `key` of map is written. */
static SrcLoc
key_loc(Loader *L, yaml_node_t *map, const char *key)
{
    for (int i = 0; i < NPAIRS(map); i++)
        if (!strcmp(key_of(L, &PAIRS(map)[i]), key))
            return loc_of(L, node(L, PAIRS(map)[i].key));
    return loc_of(L, map);
}

/* The scene to compile: `scene:`, or the named scene of `scenes:` that
 * --scene picks (the first by default).  Every named scene is listed in
 * Spec.scenes. */
static yaml_node_t *
pick_scene(Loader *L, yaml_node_t *root)
{
    Spec *s = L->s;
    yaml_node_t *one = section(L, root, "scene", 1), *many = section(L, root, "scenes", 1);
    const char *want = L->opt->scene;
    if (one && many)
        diag_error(key_loc(L, root, "scenes"), "a spec has `scene:` (one scene) or "
                   "`scenes:` (named ones), not both");
    if (!many) {
        if (want)
            diag_error(cmdline, "--scene %s: %s has no named scenes (`scenes:`)", want,
                       L->path);
        return one;
    }
    check_unique_keys(L, many, "scenes");
    s->nscenes = NPAIRS(many);
    if (s->nscenes == 0)
        diag_error(loc_of(L, many), "`scenes:` is empty: name at least one scene");
    s->scenes = arena_new_array(L->A, SpecSceneInfo, s->nscenes);
    const char **names = arena_new_array(L->A, const char *, s->nscenes);
    int pick = want ? -1 : 0;
    for (int i = 0; i < s->nscenes; i++) {
        yaml_node_t *k = node(L, PAIRS(many)[i].key);
        const char *name = scalar(L, k, "a scene name");
        if (!is_identifier(name) || strlen(name) > 64)
            diag_error(loc_of(L, k), "'%s' is not a valid scene name (letters, digits and _, "
                       "not starting with a digit)", name);
        as_map(L, node(L, PAIRS(many)[i].value), "a scene");
        names[i] = s->scenes[i].name = arena_strdup(L->A, name);
        s->scenes[i].loc = loc_of(L, k);
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
    return node(L, PAIRS(many)[pick].value);
}

static int
find_param(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->np + 1);
    for (int i = 0; i < L->s->np; i++)
        cands[i] = L->s->param[i].name;
    return find_in(L, n, "parameter", "parameters", 1, cands, L->s->np);
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
    int k = find_param(L, node(L, PAIRS(map)[i].key));
    double v = number(L, node(L, PAIRS(map)[i].value), "a fixed parameter's value");
    if (L->scene_live)
        fix_param(L, k, v);
}

static void
load_fix(Loader *L, yaml_node_t *scene, int live)
{
    yaml_node_t *map = lookup_key(L, scene, "fix");
    if (!map || is_null(map))
        return;
    as_map(L, map, "fix");
    L->scene_live = live;
    for (int i = 0; i < NPAIRS(map); i++)
        checked(L, fix_entry, map, i);
}

static void
live_fix(Loader *L, yaml_node_t *scene, int i)
{
    (void)i;
    as_map(L, scene, "scene");
    load_fix(L, scene, 1);
}

/* --fix NAME=VALUE,NAME=VALUE: after the scene's, so they win. */
static void
apply_fix_option(Loader *L)
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
    yaml_node_t *k = node(L, PAIRS(map)[i].key);
    const char *name = scalar(L, k, "an output name");
    if (!is_identifier(name) || strlen(name) > 64)
        diag_error(loc_of(L, k), "'%s' is not a valid output name (letters, digits and _, "
                   "not starting with a digit)", name);
    for (int c = 0; c < L->s->nq; c++)
        if (!strcmp(name, L->s->coord[c].name))
            diag_error(loc_of(L, k), "output '%s' would repeat the column of coordinate "
                       "'%s': name it differently", name, name);
    sc->output[i].name = arena_strdup(L->A, name);
    sc->output[i].loc = loc_of(L, k);
    sc->output[i].expr = expression(L, node(L, PAIRS(map)[i].value), ALLOW_OUTPUT,
                                    "an output");
}

static void
load_outputs(Loader *L, yaml_node_t *map, SpecScene *sc)
{
    as_map(L, map, "outputs");
    sc->noutput = NPAIRS(map);
    sc->output = arena_new_array(L->A, SpecOutput, sc->noutput + 1);
    for (int i = 0; i < sc->noutput; i++)
        checked(L, output_entry, map, i);
}

/* The coordinate (x) or velocity (x') a key names: 2 i, or 2 i + 1.
 * (No node is made: the order of the leaves is the order of first use.) */
static int
state_var(Loader *L, yaml_node_t *k, const char *what)
{
    Spec *s = L->s;
    const char *key = scalar(L, k, what);
    size_t len = strlen(key);
    int vel = len > 1 && key[len - 1] == '\'';
    for (int c = 0; c < s->nq; c++)
        if (strlen(s->coord[c].name) == len - (size_t)vel &&
            !strncmp(s->coord[c].name, key, len - (size_t)vel))
            return 2 * c + vel;
    const char **cands = arena_new_array(L->A, const char *, 2 * s->nq);
    for (int c = 0; c < s->nq; c++) {
        cands[2 * c] = s->coord[c].name;
        cands[2 * c + 1] = arena_printf(L->A, "%s'", s->coord[c].name);
    }
    const char *near = diag_nearest(key, cands, 2 * s->nq);
    if (near)
        diag_error(loc_of(L, k), "'%s' is not a coordinate or velocity; did you mean %s?",
                   key, near);
    diag_error(loc_of(L, k), "'%s' is not a coordinate (x) or a velocity (x')", key);
}

/* `initial:` at the top level, or a scene's, which overrides it (live:
 * the scene compiled; the others are only checked). */
static void
initial_value(Loader *L, yaml_node_t *map, int i, int live)
{
    Spec *s = L->s;
    int var = state_var(L, node(L, PAIRS(map)[i].key), "an initial-state name");
    ExprId e = expression(L, node(L, PAIRS(map)[i].value), ALLOW_PARAM, "an initial value");
    if (!live)
        return;
    if (var & 1)
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

static void
load_initial(Loader *L, yaml_node_t *map, int live)
{
    for (int i = 0; i < NPAIRS(map); i++)
        checked(L, live ? initial_live : initial_checked, map, i);
}

static void
load_event(Loader *L, yaml_node_t *k, yaml_node_t *map, SpecEvent *ev)
{
    static const char *const keys[] = {"when", "direction", "action", NULL};
    const char *name = scalar(L, k, "an event name");
    if (!is_identifier(name) || strlen(name) > 64)
        diag_error(loc_of(L, k), "'%s' is not a valid event name (letters, digits and _, "
                   "not starting with a digit)", name);
    ev->name = arena_strdup(L->A, name);
    ev->loc = loc_of(L, k);
    as_map(L, map, "an event");
    check_keys(L, map, keys, "an event");
    yaml_node_t *v = lookup_key(L, map, "when");
    if (!v)
        diag_error(loc_of(L, map), "event '%s' needs `when:`, the expression whose zero "
                   "crossing it is", name);
    ev->when = expression(L, v, ALLOW_EVENT, "an event's `when`");
    ev->direction = 0;
    if ((v = lookup_key(L, map, "direction"))) {
        const char *d = scalar(L, v, "direction");
        static const char *const dirs[] = {"up", "down", "both"};
        if (!strcmp(d, "up"))
            ev->direction = 1;
        else if (!strcmp(d, "down"))
            ev->direction = -1;
        else if (strcmp(d, "both")) {
            const char *near = diag_nearest(d, dirs, 3);
            if (near)
                diag_error(loc_of(L, v), "unknown direction '%s'; did you mean %s?", d, near);
            diag_error(loc_of(L, v), "unknown direction '%s'; expected up, down or both", d);
        }
    }
    ev->action = EVENT_STOP;
    if (!(v = lookup_key(L, map, "action")))
        return;
    if (v->type == YAML_SCALAR_NODE) {
        const char *a = scalar(L, v, "action");
        static const char *const acts[] = {"stop", "record", "set"};
        if (!strcmp(a, "record"))
            ev->action = EVENT_RECORD;
        else if (!strcmp(a, "set"))
            diag_error(loc_of(L, v), "action set needs the values: `action: {set: {\"x'\": "
                       "EXPR}}`");
        else if (strcmp(a, "stop")) {
            const char *near = diag_nearest(a, acts, 3);
            if (near)
                diag_error(loc_of(L, v), "unknown action '%s'; did you mean %s?", a, near);
            diag_error(loc_of(L, v), "unknown action '%s'; expected stop, record or "
                       "{set: {...}}", a);
        }
        return;
    }
    static const char *const akeys[] = {"set", NULL};
    as_map(L, v, "an action");
    check_keys(L, v, akeys, "an action");
    yaml_node_t *set = lookup_key(L, v, "set");
    if (!set)
        diag_error(loc_of(L, v), "an action map is {set: {NAME: EXPR, ...}}");
    as_map(L, set, "set");
    if (NPAIRS(set) == 0)
        diag_error(loc_of(L, set), "`set:` is empty: name what the event changes");
    ev->action = EVENT_SET;
    ev->nset = NPAIRS(set);
    ev->set_var = arena_new_array(L->A, ExprId, ev->nset);
    ev->set_expr = arena_new_array(L->A, ExprId, ev->nset);
    for (int i = 0; i < ev->nset; i++) {
        int var = state_var(L, node(L, PAIRS(set)[i].key), "a coordinate or velocity");
        ev->set_var[i] = expr_var(L->P, var / 2, var & 1);
        for (int j = 0; j < i; j++)
            if (ev->set_var[j] == ev->set_var[i])
                diag_error(loc_of(L, node(L, PAIRS(set)[i].key)), "'%s' is set twice",
                           key_of(L, &PAIRS(set)[i]));
        ev->set_expr[i] = expression(L, node(L, PAIRS(set)[i].value), ALLOW_EVENT,
                                     "a value an event sets");
    }
}

static void
event_entry(Loader *L, yaml_node_t *map, int i)
{
    load_event(L, node(L, PAIRS(map)[i].key), node(L, PAIRS(map)[i].value),
               &L->scene_into->event[i]);
}

static void
load_events(Loader *L, yaml_node_t *map, SpecScene *sc)
{
    as_map(L, map, "events");
    sc->nevent = NPAIRS(map);
    sc->event = arena_new_array(L->A, SpecEvent, sc->nevent + 1);
    for (int i = 0; i < sc->nevent; i++)
        checked(L, event_entry, map, i);
}

/* One of a scene's `effects:`, turned on in the scene compiled. */
static void
effect_entry(Loader *L, yaml_node_t *seq, int i)
{
    int k = find_effect(L, node(L, ITEMS(seq)[i]));
    if (L->scene_live)
        L->s->effect[k].enabled = 1;
}

/* One name of `assemble: {hold: [...]}`: a coordinate (x) or velocity
 * (x') the assembly keeps as it is. */
static void
hold_entry(Loader *L, yaml_node_t *seq, int i)
{
    yaml_node_t *k = node(L, ITEMS(seq)[i]);
    int var = state_var(L, k, "a coordinate or velocity to hold");
    int n = L->s->nq, at = var & 1 ? n + var / 2 : var / 2;
    if (L->scene_into->hold[at])
        diag_error(loc_of(L, k), "'%s' is held twice", scalar(L, k, "a name"));
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
        const char *b = scalar(L, v, "assemble");
        if (strcmp(b, "true") && strcmp(b, "false"))
            diag_error(loc_of(L, v), "%s, not '%s'", usage, b);
        sc->assemble = !strcmp(b, "true");
    } else {
        if (v->type != YAML_MAPPING_NODE)
            diag_error(loc_of(L, v), "%s", usage);
        as_map(L, v, "assemble");
        check_keys(L, v, keys, "`assemble:`");
        yaml_node_t *h = lookup_key(L, v, "hold");
        if (!h)
            diag_error(loc_of(L, v), "%s", usage);
        expect_type(L, h, YAML_SEQUENCE_NODE, "`hold:`, the names the assembly keeps,");
        sc->assemble = 1;
        sc->hold = arena_new_array(L->A, unsigned char, 2 * L->s->nq);
        memset(sc->hold, 0, 2 * (size_t)L->s->nq);
        for (int i = 0; i < NITEMS(h); i++)
            checked(L, hold_entry, h, i);
    }
    int levels = 0; /* what an assembly moves the state onto */
    for (int c = 0; c < L->s->nconstraint; c++)
        levels |= L->s->constraint[c].order <= 1;
    for (int b = 0; b < L->s->nbody; b++)
        levels |= L->s->body[b].quat[0] >= 0;
    if (sc->assemble && !levels)
        diag_error(loc_of(L, v), "`assemble:` puts the initial state onto the holonomic and "
                   "first-order constraints, and this spec has none");
}

/* Entry i of a scene (L->scene_into, L->scene_live) but `fix`
 * (load_fix), on its own: an error in one does not hide the others. */
static void
scene_entry(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"effects", "t_end", "dt", "method", "rtol", "atol",
                                       "fixed_step", "fix", "initial", "outputs", "events",
                                       "assemble", NULL};
    SpecScene *sc = L->scene_into;
    int live = L->scene_live;
    check_key(L, map, i, keys, "a scene");
    const char *k = key_of(L, &PAIRS(map)[i]);
    yaml_node_t *v = node(L, PAIRS(map)[i].value);
    if (!strcmp(k, "effects")) {
        expect_type(L, v, YAML_SEQUENCE_NODE, "the scene's effects");
        for (int e = 0; e < L->s->neffect && live; e++)
            L->s->effect[e].enabled = 0;
        for (int e = 0; e < NITEMS(v); e++)
            checked(L, effect_entry, v, e);
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
    } else if (!strcmp(k, "initial") && !is_null(v)) {
        load_initial(L, as_map(L, v, "initial"), live);
    } else if (!strcmp(k, "outputs") && !is_null(v)) {
        load_outputs(L, v, sc);
    } else if (!strcmp(k, "events") && !is_null(v)) {
        load_events(L, v, sc);
    } else if (!strcmp(k, "assemble")) {
        load_assemble(L, v, sc);
    }
}

/* The scene's defaults, before its keys. */
static const SpecScene scene_defaults = {.t_end = 10.0, .dt = 0.01, .method = "rk8pd",
                                         .rtol = 1e-10, .atol = 1e-10};

/* A scene's keys but `fix` (load_fix), each on its own.  live: the scene
 * compiled, into Spec.scene and the effects' switches; the other scenes
 * are checked into a scratch copy, so that a mistake in any of them is
 * found. */
static void
load_scene(Loader *L, yaml_node_t *map, int live)
{
    SpecScene scratch = scene_defaults, *sc = live ? &L->s->scene : &scratch;
    as_map(L, map, "scene");
    L->scene_into = sc;
    L->scene_live = live;
    int errors = diag_error_count();
    for (int i = 0; i < NPAIRS(map); i++)
        checked(L, scene_entry, map, i);
    if (diag_error_count() == errors && sc->rtol == 0 && sc->atol == 0 && sc->h_fixed == 0)
        diag_error(loc_of(L, map), "rtol and atol cannot both be zero for adaptive steps");
}

/* One line for --explain: what a named scene turns on. */
static const char *
scene_summary(Loader *L, yaml_node_t *map)
{
    char buf[1024] = "";
    yaml_node_t *v;
    size_t n;
#define ADD(...) (n = strlen(buf), snprintf(buf + n, sizeof buf - n, __VA_ARGS__))
    if ((v = lookup_key(L, map, "effects")) && v->type == YAML_SEQUENCE_NODE) {
        ADD("effects:");
        for (int i = 0; i < NITEMS(v); i++)
            ADD(" %s", scalar(L, node(L, ITEMS(v)[i]), "an effect"));
        if (NITEMS(v) == 0)
            ADD(" (none)");
    } else {
        ADD("effects: the spec's");
    }
    static const char *const lists[] = {"fix", "initial", "outputs", "events"};
    for (int j = 0; j < 4; j++) {
        if (!(v = lookup_key(L, map, lists[j])) || v->type != YAML_MAPPING_NODE)
            continue;
        ADD("; %s:", lists[j]);
        for (int i = 0; i < NPAIRS(v); i++)
            ADD(" %s", key_of(L, &PAIRS(v)[i]));
    }
    if ((v = lookup_key(L, map, "assemble")) && v->type == YAML_MAPPING_NODE &&
        (v = lookup_key(L, v, "hold")) && v->type == YAML_SEQUENCE_NODE) {
        ADD("; assemble, holding:");
        for (int i = 0; i < NITEMS(v); i++)
            ADD(" %s", scalar(L, node(L, ITEMS(v)[i]), "a name"));
    } else if ((v = lookup_key(L, map, "assemble")) && v->type == YAML_SCALAR_NODE &&
               !strcmp(scalar(L, v, "assemble"), "true")) {
        ADD("; assemble");
    }
#undef ADD
    return arena_strdup(L->A, buf);
}

/* Fixed parameters become constants everywhere: every expression of the
 * spec, rebuilt in one pass, folds them (expr_subst_many). */
static void
fold_fixed(Loader *L)
{
    Spec *s = L->s;
    if (s->nfixed == 0)
        return;
    int cap = 64, n = 0;
    ExprId **at = arena_new_array(L->A, ExprId *, cap);
#define VISIT(e)                                                                       \
    do {                                                                               \
        if ((e) != EXPR_NONE) {                                                        \
            if (n == cap) {                                                            \
                ExprId **bigger = arena_new_array(L->A, ExprId *, 2 * cap);           \
                memcpy(bigger, at, (size_t)n * sizeof *at);                            \
                at = bigger, cap *= 2;                                                 \
            }                                                                          \
            at[n++] = &(e);                                                            \
        }                                                                              \
    } while (0)
    for (int i = 0; i < s->nq; i++)
        {
        VISIT(s->coord[i].q0);
        VISIT(s->coord[i].v0);
    }
    for (int i = 0; i < s->nu; i++)
        VISIT(s->input[i].expr);
    for (int i = 0; i < s->npart; i++) {
        VISIT(s->part[i].mass);
        for (int k = 0; k < 3; k++) {
            VISIT(s->part[i].pos[k]);
            if (s->part[i].has_vel)
                VISIT(s->part[i].vel[k]);
        }
    }
    for (int i = 0; i < s->nbody; i++) {
        SpecBody *b = &s->body[i];
        VISIT(b->mass);
        for (int k = 0; k < 3; k++) {
            VISIT(b->center[k]);
            VISIT(b->omega[k]);
            if (b->has_center_vel)
                VISIT(b->center_vel[k]);
        }
        for (int k = 0; k < 9; k++)
            VISIT(b->inertia[k]);
    }
    for (int i = 0; i < s->neffect; i++)
        for (int j = 0; j < s->effect[i].nforce; j++) {
            SpecForce *f = &s->effect[i].force[j];
            for (int k = 0; k < 3; k++)
                VISIT(f->vec[k]);
            VISIT(f->expr);
        }
    for (int i = 0; i < s->nkinetic; i++)
        VISIT(s->kinetic[i].expr);
    for (int i = 0; i < s->npotential; i++)
        VISIT(s->potential[i].expr);
    for (int i = 0; i < s->nconstraint; i++)
        VISIT(s->constraint[i].expr);
    for (int i = 0; i < s->ncheck; i++)
        VISIT(s->check[i].expr);
    for (int i = 0; i < s->scene.noutput; i++)
        VISIT(s->scene.output[i].expr);
    for (int i = 0; i < s->scene.nevent; i++) {
        SpecEvent *ev = &s->scene.event[i];
        VISIT(ev->when);
        for (int k = 0; k < ev->nset; k++)
            VISIT(ev->set_expr[k]);
    }
#undef VISIT
    ExprId *roots = arena_new_array(L->A, ExprId, n + 1);
    ExprId *from = arena_new_array(L->A, ExprId, s->nfixed);
    ExprId *to = arena_new_array(L->A, ExprId, s->nfixed);
    for (int i = 0; i < n; i++)
        roots[i] = *at[i];
    int k = 0;
    for (int i = 0; i < s->np; i++)
        if (s->param[i].fixed) {
            from[k] = expr_param(L->P, i);
            to[k++] = expr_const(L->P, s->param[i].value);
        }
    expr_subst_many(L->P, n, roots, k, from, to, roots);
    for (int i = 0; i < n; i++)
        *at[i] = roots[i];
    /* conditions that no parameter can change any more held when checked */
    int kept = 0;
    for (int i = 0; i < s->ncheck; i++)
        if (!expr_is_const(L->P, s->check[i].expr, NULL))
            s->check[kept++] = s->check[i];
    s->ncheck = kept;
}

/* The spec's name: `name:`, or the file's base name made an identifier. */
static const char *
spec_name(Loader *L, yaml_node_t *n)
{
    if (n) {
        const char *name = scalar(L, n, "name");
        if (!is_identifier(name) || strlen(name) > 64)
            diag_error(loc_of(L, n), "name '%s' must be a C identifier (letters, digits, _)", name);
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
        name[k++] = is_identifier((char[]){'a', base[i], 0}) ? base[i] : '_';
    return name;
}

static const char *const top_keys[] = {
    "name", "description", "parameters", "coordinates", "define", "frames", "points", "inputs",
    "particles", "bodies", "kinetic", "potential", "effects", "constraints", "initial",
    "scene", "scenes",
    NULL,
};

/* `kinetic:` (i = 0) or `potential:` (i = 1) terms. */
static void
load_energy(Loader *L, yaml_node_t *root, int i)
{
    yaml_node_t *n = section(L, root, i ? "potential" : "kinetic", 0);
    if (n && i)
        L->s->potential = load_terms(L, n, ALLOW_POTENTIAL, "a potential-energy term",
                                     &L->s->npotential);
    else if (n)
        L->s->kinetic = load_terms(L, n, ALLOW_KINETIC, "a kinetic-energy term",
                                   &L->s->nkinetic);
}

static void
live_scene(Loader *L, yaml_node_t *scene, int i)
{
    (void)i;
    load_scene(L, scene, 1);
}

/* Every named scene is checked, and summarized for --explain. */
static void
other_scene(Loader *L, yaml_node_t *scenes, int i)
{
    yaml_node_t *sc = node(L, PAIRS(scenes)[i].value);
    if (sc != L->scene) {
        as_map(L, sc, "scene");
        load_fix(L, sc, 0);
        load_scene(L, sc, 0);
    }
    L->s->scenes[i].summary = scene_summary(L, sc);
}

static void
load_root(Loader *L, yaml_node_t *root)
{
    Spec *s = L->s;
    expect_type(L, root, YAML_MAPPING_NODE, "the top level of a spec");
    check_unique_keys(L, root, "the spec");
    check_keys(L, root, top_keys, "the spec");
    s->name = spec_name(L, section(L, root, "name", 0));
    yaml_node_t *d = section(L, root, "description", 0);
    s->description = d ? arena_strdup(L->A, scalar(L, d, "description")) : "";
    yaml_node_t *params = section(L, root, "parameters", 1);
    yaml_node_t *coords = lookup_key(L, root, "coordinates");
    yaml_node_t *inputs = section(L, root, "inputs", 1);
    yaml_node_t *defines = section(L, root, "define", 1);
    yaml_node_t *frames = section(L, root, "frames", 1);
    yaml_node_t *points = section(L, root, "points", 1);
    if (!coords)
        diag_error(loc_of(L, root), "the spec has no `coordinates:`");
    int most = (params ? NPAIRS(params) : 0) + (inputs ? NPAIRS(inputs) : 0) +
               (defines ? NPAIRS(defines) : 0) + (frames ? NPAIRS(frames) : 0) +
               (points ? NPAIRS(points) : 0) +
               (coords->type == YAML_SEQUENCE_NODE ? NITEMS(coords) : 0);
    L->names = arena_new_array(L->A, Name, most + 1);
    L->quat_of = arena_new_array(L->A, const char *, most + 1);
    for (int i = 0; i <= most; i++)
        L->quat_of[i] = NULL;
    if (params)
        name_parameters(L, params);
    load_coordinates(L, coords);
    if (inputs)
        name_inputs(L, inputs);
    name_items(L, defines, frames, points);
    stop_if_failed(); /* everything below is read with these names */
    resolve_defines(L);
    if (params)
        load_parameters(L, params);
    if (inputs)
        load_inputs(L, inputs);
    /* fixed values first: the physical data are checked with them */
    L->scene = pick_scene(L, root);
    if (L->scene)
        checked(L, live_fix, L->scene, 0);
    apply_fix_option(L);
    /* an axis of parameters has no direction where they make it zero */
    for (const AxisCheck *c = L->axes; c; c = c->next)
        require(L, c->n2, 1, c->n, 0, "frame '%s': an axis cannot be zero", c->name);
    yaml_node_t *n;
    if ((n = section(L, root, "particles", 1)))
        load_particles(L, n);
    if ((n = section(L, root, "bodies", 1)))
        load_bodies(L, n);
    checked(L, load_energy, root, 0);
    checked(L, load_energy, root, 1);
    if ((n = section(L, root, "effects", 1)))
        load_effects(L, n);
    if ((n = section(L, root, "constraints", 1)))
        load_constraints(L, n);
    if ((n = section(L, root, "initial", 1)))
        load_initial(L, n, 1);
    if (diag_error_count() == 0) /* it reads the bodies' and the parameters' values */
        add_unit_constraints(L);
    if (L->scene)
        checked(L, live_scene, L->scene, 0);
    if ((n = section(L, root, "scenes", 1)))
        for (int i = 0; i < s->nscenes; i++)
            checked(L, other_scene, n, i);
    stop_if_failed();
    fold_fixed(L);
    if (s->npart == 0 && s->nbody == 0 && s->nkinetic == 0)
        diag_error(loc_of(L, root), "the spec has no kinetic energy: give `particles:`, "
                   "`bodies:` or `kinetic:` terms");
}

static void
index_lines(Loader *L)
{
    size_t n = 1;
    for (size_t i = 0; i < L->len; i++)
        n += L->text[i] == '\n';
    L->line_start = arena_new_array(L->A, size_t, n);
    L->nlines = 0;
    L->line_start[L->nlines++] = 0;
    for (size_t i = 0; i < L->len; i++)
        if (L->text[i] == '\n')
            L->line_start[L->nlines++] = i + 1;
}

/* Line and column of a byte offset (libyaml's reader errors give one). */
static SrcLoc
loc_of_byte(const Loader *L, size_t off)
{
    size_t line = 0;
    while (line + 1 < L->nlines && L->line_start[line + 1] <= off)
        line++;
    int col = 1;
    for (size_t i = L->line_start[line]; i < off && i < L->len; i++)
        col += !is_cont((unsigned char)L->text[i]);
    return (SrcLoc){L->path, (int)line + 1, col};
}

/* Where a reader error is: libyaml gives the byte after a truncated
 * UTF-8 sequence; the sequence starts at its lead byte. */
static size_t
reader_offset(const Loader *L, const yaml_parser_t *yp)
{
    size_t off = yp->problem_offset;
    if (!yp->problem || strcmp(yp->problem, "invalid trailing UTF-8 octet") || off > L->len)
        return off;
    while (off > 0 && is_cont((unsigned char)L->text[off - 1]))
        off--;
    return off > 0 ? off - 1 : off;
}

/* libyaml's reader errors, with the byte they are about: a spec is UTF-8
 * text without control characters. */
static void
reader_problem(const Loader *L, const yaml_parser_t *yp, char *msg, size_t len)
{
    const char *p = yp->problem ? yp->problem : "";
    int v = yp->problem_value;
    size_t off = reader_offset(L, yp);
    if (!strcmp(p, "invalid trailing UTF-8 octet") && off < L->len)
        snprintf(msg, len, "incomplete UTF-8 sequence (byte 0x%02x without the bytes that "
                 "follow it): a spec must be UTF-8 text", (unsigned char)L->text[off]);
    else if (strstr(p, "UTF-8") && v >= 0)
        snprintf(msg, len, "%s (byte 0x%02x): a spec must be UTF-8 text", p, v & 0xff);
    else if (strstr(p, "UTF-8") || strstr(p, "Unicode"))
        snprintf(msg, len, "%s: a spec must be UTF-8 text", p);
    else if (strstr(p, "control characters") && v >= 0)
        snprintf(msg, len, "control character (U+%04X) in the text: a spec cannot contain "
                 "control characters other than tab and line breaks", (unsigned)v);
    else
        snprintf(msg, len, "%s", p);
}

/* libyaml's own errors, with its marks; the parser is deleted first. */
static _Noreturn void
yaml_failure(Loader *L, yaml_parser_t *yp)
{
    SrcLoc at = {L->path, (int)yp->problem_mark.line + 1, (int)yp->problem_mark.column + 1};
    if (yp->error == YAML_READER_ERROR)
        at = loc_of_byte(L, reader_offset(L, yp));
    char msg[512];
    const char *problem = yp->problem ? yp->problem : "cannot parse the YAML";
    if (yp->context)
        snprintf(msg, sizeof msg, "%s %s that started at line %d, column %d", problem,
                 yp->context, (int)yp->context_mark.line + 1, (int)yp->context_mark.column + 1);
    else
        snprintf(msg, sizeof msg, "%s", problem);
    size_t b = byte_at(L, yp->problem_mark.line, yp->problem_mark.column);
    if (yp->error != YAML_READER_ERROR && b < L->len && L->text[b] == '\t')
        snprintf(msg, sizeof msg, "a tab character: YAML indents with spaces only");
    else if (yp->error == YAML_READER_ERROR)
        reader_problem(L, yp, msg, sizeof msg);
    else if (yp->error != YAML_READER_ERROR && b < L->len &&
             (L->text[b] == '[' || L->text[b] == ']') && yp->context &&
             strstr(yp->context, "flow"))
        snprintf(msg + strlen(msg), sizeof msg - strlen(msg),
                 " (inside { } or [ ], quote an expression with brackets: \"lambda[c]\")");
    else if (yp->problem && !strcmp(yp->problem, "did not find expected key") && yp->context &&
             strstr(yp->context, "block mapping"))
        snprintf(msg + strlen(msg), sizeof msg - strlen(msg),
                 " (is this line indented like the keys of that mapping?)");
    yaml_parser_delete(yp);
    diag_error(at, "%s", msg);
}

/* libyaml's scanner slows down quadratically with flow nesting, and a
 * deep document would make every later walk deep: refuse one nested
 * deeper than SPEC_MAX_DEPTH, reading events (which stops at the first
 * offending level instead of scanning the whole file), before loading. */
enum { SPEC_MAX_DEPTH = 64 };

static void
check_depth(Loader *L)
{
    yaml_parser_t yp;
    yaml_event_t ev;
    if (!yaml_parser_initialize(&yp))
        diag_error((SrcLoc){L->path, 0, 0}, "out of memory");
    yaml_parser_set_input_string(&yp, (const unsigned char *)L->text, L->len);
    for (int depth = 0, done = 0; !done;) {
        if (!yaml_parser_parse(&yp, &ev))
            yaml_failure(L, &yp);
        int type = ev.type;
        SrcLoc at = {L->path, (int)ev.start_mark.line + 1, (int)ev.start_mark.column + 1};
        yaml_event_delete(&ev);
        if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT)
            depth++;
        else if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT)
            depth--;
        done = type == YAML_STREAM_END_EVENT;
        if (depth > SPEC_MAX_DEPTH) {
            yaml_parser_delete(&yp);
            diag_error(at, "the YAML is nested more than %d levels deep", SPEC_MAX_DEPTH);
        }
    }
    yaml_parser_delete(&yp);
}

static void
load_document(Loader *L)
{
    yaml_parser_t yp;
    check_depth(L);
    if (!yaml_parser_initialize(&yp))
        diag_error((SrcLoc){L->path, 0, 0}, "out of memory");
    yaml_parser_set_input_string(&yp, (const unsigned char *)L->text, L->len);
    if (!yaml_parser_load(&yp, &L->doc))
        yaml_failure(L, &yp);
    L->have_doc = 1;
    /* a second document would be ignored silently: refuse it */
    yaml_document_t extra;
    if (!yaml_parser_load(&yp, &extra))
        yaml_failure(L, &yp);
    int more = yaml_document_get_root_node(&extra) != NULL;
    SrcLoc at = {L->path, (int)extra.start_mark.line + 1, (int)extra.start_mark.column + 1};
    yaml_document_delete(&extra);
    yaml_parser_delete(&yp);
    if (more)
        diag_error(at, "a spec is one YAML document; this is a second one");
}

/* ---- expressions that YAML split ---- */

/* Inside { } and [ ], YAML reads a comma as a separator, also in
 * dot(a, b): the expression arrives in pieces, and the errors that follow
 * (an unknown key 'b)', a vector of 6 components) describe only the
 * symptom.  A piece that opens a parenthesis which a later piece closes
 * can only be such an expression: it is reported first, quoted as it
 * should be written, and nothing is read from a document whose structure
 * is not the one meant. */

/* The parentheses a plain scalar opens and does not close, or 0 for any
 * other node (a quoted scalar's are the parser's to judge). */
static int
paren_balance(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    int b = 0;
    for (size_t i = 0; i < n->data.scalar.length; i++)
        b += (n->data.scalar.value[i] == '(') - (n->data.scalar.value[i] == ')');
    return b;
}

/* A flow collection's pieces in the order written: a sequence's items, a
 * mapping's keys and values. */
static int
flow_pieces(const yaml_node_t *c)
{
    return c->type == YAML_SEQUENCE_NODE ? NITEMS(c) : 2 * NPAIRS(c);
}

static yaml_node_t *
flow_piece(Loader *L, const yaml_node_t *c, int k)
{
    if (c->type == YAML_SEQUENCE_NODE)
        return node(L, ITEMS(c)[k]);
    const yaml_node_pair_t *p = &PAIRS(c)[k / 2];
    return node(L, k % 2 ? p->value : p->key);
}

/* The piece that closes what piece i of c opens, or -1; *last, the last
 * piece looked at (a later search starts after it: one pass over c). */
static int
split_end(Loader *L, const yaml_node_t *c, int i, int *last)
{
    int b = paren_balance(flow_piece(L, c, i));
    *last = i;
    if (b <= 0)
        return -1;
    for (int j = i + 1; j < flow_pieces(c); j++) {
        yaml_node_t *n = flow_piece(L, c, j);
        *last = j;
        if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
            return -1;
        if ((b += paren_balance(n)) <= 0)
            return b == 0 ? j : -1;
    }
    return -1;
}

enum { SPLIT_SHOWN = 240 }; /* a longer expression is shown cut short */

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

/* Pieces i .. split_end of flow collection c are one expression: an error
 * at its start, with its source text quoted (line breaks and comments
 * between the pieces dropped). */
static void
split_expression(Loader *L, yaml_node_t *c, int i)
{
    int last;
    const yaml_node_t *a = flow_piece(L, c, i), *z = flow_piece(L, c, split_end(L, c, i, &last));
    size_t from = byte_at(L, a->start_mark.line, a->start_mark.column);
    size_t to = byte_at(L, z->end_mark.line, z->end_mark.column);
    char q[SPLIT_SHOWN + 8];
    size_t n = 0;
    for (size_t k = from; k < to && n < SPLIT_SHOWN; k++) {
        char ch = L->text[k];
        if (ch == '#' && k > from && is_blank(L->text[k - 1])) {
            while (k + 1 < to && L->text[k + 1] != '\n')
                k++;
            continue;
        }
        if (is_blank(ch)) { /* a run of blanks is one space */
            if (n > 0 && q[n - 1] != ' ')
                q[n++] = ' ';
            continue;
        }
        if (ch == '"' || ch == '\\')
            q[n++] = '\\';
        q[n++] = ch;
    }
    while (n > 0 && q[n - 1] == ' ')
        n--;
    q[n] = '\0';
    diag_error(loc_of(L, a), "an expression with commas inside %s must be quoted: \"%s%s\" "
               "(YAML splits it at its commas)", c->type == YAML_SEQUENCE_NODE ? "[ ]" : "{ }",
               q, n >= SPLIT_SHOWN ? "..." : "");
}

/* Every split expression of the document, each node once (the node list,
 * not a walk: aliases share nodes). */
static void
check_splits(Loader *L)
{
    for (yaml_node_t *c = L->doc.nodes.start; c < L->doc.nodes.top; c++) {
        int flow = c->type == YAML_SEQUENCE_NODE
                       ? c->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE
                       : c->type == YAML_MAPPING_NODE &&
                             c->data.mapping.style == YAML_FLOW_MAPPING_STYLE;
        for (int i = 0, last; flow && i < flow_pieces(c) && !L->stop; i = last + 1)
            if (split_end(L, c, i, &last) >= 0)
                checked(L, split_expression, c, i);
    }
    stop_if_failed();
}

/* The whole spec; apart from spec_load_buffer, so that nothing of its
 * own lives in the frame that setjmp returns to twice. */
static void
load_spec(Loader *L)
{
    index_lines(L);
    load_document(L);
    yaml_node_t *root = yaml_document_get_root_node(&L->doc);
    if (!root)
        diag_error((SrcLoc){L->path, 1, 1}, "the spec is empty");
    check_splits(L);
    load_root(L, root);
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
    L->sc = (ParseScope){P, diff_new(P), lookup, multiplier, leaf_name, 0, "", 0,
                         frame_arg, point_arg, NULL};
    L->s = arena_alloc(A, sizeof *L->s);
    L->s->path = L->path;
    L->s->scene = scene_defaults;
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

/* --effects with a typo: the nearest effect, or NULL if none is close. */
static const char *
effect_typo(const Spec *s, const char *name, size_t n)
{
    char buf[80];
    const char *cands[64];
    int count = s->neffect < 64 ? s->neffect : 64;
    if (n >= sizeof buf)
        return NULL;
    memcpy(buf, name, n);
    buf[n] = '\0';
    for (int i = 0; i < count; i++)
        cands[i] = s->effect[i].name;
    return diag_nearest(buf, cands, count);
}

int
spec_select_effects(Spec *s, const char *list)
{
    for (int i = 0; i < s->neffect; i++)
        s->effect[i].enabled = 0;
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (int i = 0; i < s->neffect; i++)
            if (strlen(s->effect[i].name) == n && !strncmp(s->effect[i].name, p, n))
                s->effect[i].enabled = found = 1;
        if (!found && n > 0) {
            const char *near = effect_typo(s, p, n);
            fprintf(stderr, "eomc: --effects: unknown effect '%.*s'; ", (int)n, p);
            if (near)
                fprintf(stderr, "did you mean %s? ", near);
            fprintf(stderr, "%s has", s->path);
            for (int i = 0; i < s->neffect; i++)
                fprintf(stderr, "%s %s", i ? "," : "", s->effect[i].name);
            fprintf(stderr, "%s\n", s->neffect ? "" : " no effects");
            return -1;
        }
        p += n;
        p += *p == ',';
    }
    return 0;
}
