/*
 * parse: the expression language of specs, parsed straight into the DAG.
 *
 *   expr    = term (("+" | "-") term)*
 *   term    = unary (("*" | "/") unary)*
 *   unary   = ("-" | "+") unary | power
 *   power   = postfix ("^" unary)?      right-associative; -x^2 = -(x^2)
 *   postfix = primary "'"*              x' = dot(x), x'' = dot(dot(x))
 *   primary = NUMBER | NAME | NAME "(" args ")" | "(" expr ")"
 *           | FRAME "." ("x" | "y" | "z")   a frame's axis, a vector
 *           | "lambda" "[" NAME "]"    a constraint's multiplier
 *
 * Functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt
 * abs pow, dot(e), the total time derivative, and delta(e), the variation
 * sum_i de/dq_i delta(q_i) of virtual work (the delta(q_i) are EXPR_SEED
 * leaves, kind 0; an expression may hold them when `allow` has DEP_S).
 *
 * A value is a scalar or a vector (three world components).  Vectors come
 * from frames and points (kin.h): pos(P), pos(P, Q), vel(P), vel(P, F),
 * acc(P), acc(P, F), omega(F), omega(F, G), alpha(F), alpha(F, G),
 * vec(F, a, b, c), F.x; they add, subtract, scale, divide by a scalar and
 * differentiate (' and dot(e): in the world); dot(a, b), cross(a, b) and
 * norm(a) combine them.  Function names are not reserved: they are
 * functions only when called (a name followed by "("), so a coordinate
 * may be called delta or omega.  Using a vector where a scalar is expected,
 * or the reverse, is an error at the place.  Names are resolved by the
 * caller's scope; `t` and `pi` are built in.  Every error is reported
 * through diag_error at its place inside the string.
 */
#ifndef EOMC_PARSE_H
#define EOMC_PARSE_H

#include "base/diag.h"
#include "diff.h"
#include "kin.h"

/* A scalar (vec = 0, e[0]) or a vector (vec = 1, world components). */
typedef struct ParseVal {
    int vec;
    ExprId e[3];
} ParseVal;

/* One expression's text and how to locate a byte of it in its file. */
typedef struct ParseSrc ParseSrc;
struct ParseSrc {
    const char *text;
    size_t len;
    SrcLoc (*where)(const ParseSrc *src, size_t off);
    const void *data; /* for where() */
};

typedef struct ParseScope ParseScope;
struct ParseScope {
    ExprPool *P;
    Diff *D;
    /* The value a name stands for; reports unknown names itself. */
    ParseVal (*lookup)(ParseScope *sc, const char *name, SrcLoc at);
    /* lambda[NAME]: the multiplier of constraint NAME (NULL: none here);
     * reports unknown names itself. */
    ExprId (*multiplier)(ParseScope *sc, const char *name, SrcLoc at);
    /* The user's name of a leaf (coordinate, parameter, input, multiplier). */
    const char *(*leaf_name)(ParseScope *sc, ExprId leaf);
    /* What the expression being parsed may depend on (DEP_ bits), and
     * what it is, for messages: "a mass", "a position". */
    unsigned allow;
    const char *what;
    int ncoord;  /* coordinates: the variations delta(q_i) */
    /* The frame or point (kin.h) a name stands for; report unknown names
     * and names of something else themselves.  NULL: none here. */
    int (*frame)(ParseScope *sc, const char *name, SrcLoc at);
    int (*point)(ParseScope *sc, const char *name, SrcLoc at);
    Kin *K;
    /* What names the switches made here (an effect, a define): a switch
     * of max in effect floor is floor.max.  NULL: the function alone. */
    const char *owner;
};

/* Parse src in scope sc: a scalar (a vector is an error), a vector (a
 * scalar is an error), or either.  Never EXPR_NONE. */
ExprId parse_expr(ParseScope *sc, const ParseSrc *src);
void parse_vector(ParseScope *sc, const ParseSrc *src, ExprId out[3]);
ParseVal parse_value(ParseScope *sc, const ParseSrc *src);

/* A vector written as vec(F, a, b, c), the whole of src: its frame and
 * its components in the frame's axes (1), so that an offset keeps the
 * frame it was written in; 0, with nothing parsed, for anything else. */
int parse_frame_vector(ParseScope *sc, const ParseSrc *src, int *frame, ExprId comps[3]);

/* Call fn for every name in src (not function names), in order, with its
 * byte offset: for dependency analysis before parsing.  Reports lexical
 * errors. */
void parse_names(const ParseSrc *src,
                 void (*fn)(void *ctx, const char *name, size_t len, size_t off),
                 void *ctx);

/* Is name reserved by the language (t, pi)?  Function names are not:
 * `delta` may name a coordinate, and delta(e) is still the variation. */
int parse_is_reserved(const char *name);
/* Is name a function's (sin, dot, delta, pos, ...)?  For the message
 * about a name that is none of the spec's. */
int parse_is_function(const char *name);

#endif
