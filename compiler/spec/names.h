/*
 * names: the spec's names and the scope its expressions are parsed in.
 *
 * Every name (parameter, coordinate, input, define, frame, point) is
 * known before any expression is read, so that an expression that uses
 * one where it may not is told what the name is.  An expression is a
 * scalar parsed in this scope with the DEP_ bits of what it may depend on
 * (ALLOW_*); parse.c rejects the rest at the right column.
 */
#ifndef EOMC_SPEC_NAMES_H
#define EOMC_SPEC_NAMES_H

#include "yaml.h"

typedef enum {
    NAME_PARAM, NAME_COORD, NAME_INPUT, NAME_DEFINE, NAME_FRAME, NAME_POINT, NAME_SPEED
} NameKind;

struct Name {
    const char *name;
    NameKind kind;
    int index; /* into Spec.param / coord / input / speed, or Loader.def (an item) */
    SrcLoc loc;
};

/* What names stand for that is built from other names, in the order
 * their uses require: a define's value (a scalar or a vector), a frame, a
 * point.  Each names the others it uses, and they are resolved depth
 * first, after what they use (frames.h). */
typedef enum { ITEM_DEFINE, ITEM_FRAME, ITEM_POINT } ItemKind;

struct Define {
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
};

/* What each kind of expression may depend on. */
enum {
    ALLOW_CONST = 0,
    ALLOW_PARAM = DEP_P,
    ALLOW_SIGNAL = DEP_T | DEP_P,
    ALLOW_POSITION = DEP_T | DEP_ORDER(0) | DEP_P,
    ALLOW_KINETIC = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P,
    /* switched expressions (max, min, clamp: DEP_M) in forces and
     * potentials only, whose functions all read the modes with u */
    ALLOW_POTENTIAL = DEP_T | DEP_ORDER(0) | DEP_P | DEP_U | DEP_M,
    ALLOW_FORCE = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P | DEP_U | DEP_M,
    ALLOW_WORK = ALLOW_FORCE | DEP_S, /* forces times variations delta(e) */
    ALLOW_FIELD = DEP_T | DEP_P | DEP_U,
    ALLOW_CONSTRAINT = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_ORDER(2) | DEP_P | DEP_U,
    ALLOW_OUTPUT = ALLOW_CONSTRAINT | DEP_L,
    ALLOW_EVENT = DEP_T | DEP_ORDER(0) | DEP_ORDER(1) | DEP_P,
    ALLOW_ALL = 0xff | DEP_M, /* a define: checked where it is used */
};

/* The parser's scope over L's names (L->sc; its Diff is the caller's to free). */
ParseScope spec_scope(ExprPool *P);

/* A letter or _, then letters, digits and _. */
int spec_is_identifier(const char *s);
/* The name, or NULL. */
Name *spec_find_name(Loader *L, const char *name);
/* Node n's scalar as a new name (an identifier, not reserved, not taken). */
const char *spec_add_name(Loader *L, yaml_node_t *n, NameKind kind, int index);
/* The item a define, frame or point name stands for, resolved; abandons
 * (no second message) if it had an error. */
Define *spec_item(Loader *L, const Name *nm);
/* A frame (want NAME_FRAME: world too) or point (NAME_POINT: origin too)
 * by name: its index in kin.h. */
int spec_frame_or_point(Loader *L, const char *name, NameKind want, SrcLoc at);
/* The index of node n's name among cands[0..count), or an error saying
 * "unknown WHAT 'x'" (is_not: "'x' is not a WHAT") and what was meant. */
int spec_find_in(Loader *L, yaml_node_t *n, const char *what, const char *plural, int is_not,
                 const char **cands, int count);
/* The coordinate node n names, an angle or a length (not an Euler
 * parameter), for `what` that acts on it ("a limit"); else an error. */
int spec_scalar_coordinate(Loader *L, yaml_node_t *n, const char *what);

/* An expression at n, which may depend on `allow`; a finite constant; a
 * vector of 2 or 3 expressions (its dimension); a vector in world
 * components, also a point's name or a vector expression (3). */
ExprId spec_expr(Loader *L, const yaml_node_t *n, unsigned allow, const char *what);
double spec_number(Loader *L, const yaml_node_t *n, const char *what);
int spec_vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what, ExprId out[3]);
int spec_world_vector(Loader *L, yaml_node_t *n, unsigned allow, const char *what,
                      ExprId out[3]);

/* The sections of names: `parameters:` named (spec_name_parameters) and
 * then, once every name is known, their values; `coordinates:`;
 * `inputs:` named, and then their signals. */
void spec_name_parameters(Loader *L, yaml_node_t *map);
void spec_load_parameters(Loader *L, yaml_node_t *map);
void spec_load_coordinates(Loader *L, yaml_node_t *seq);
void spec_name_inputs(Loader *L, yaml_node_t *map);
void spec_load_inputs(Loader *L, yaml_node_t *map);

#endif
