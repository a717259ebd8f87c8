/*
 * spec: load a model spec (YAML, through libyaml) into a Spec.
 *
 * Every expression is parsed (parse.h), its names resolved and its
 * defines expanded, so a Spec holds only ExprIds over coordinates
 * (EXPR_VAR), parameters, inputs and t.  All entities keep the location
 * of their YAML node for later diagnostics.  A Spec that spec_load returns
 * has been checked: bad input never gets past it.  The format is
 * documented in docs/spec.md.
 */
#ifndef EOMC_SPEC_H
#define EOMC_SPEC_H

#include "arena.h"
#include "diag.h"
#include "expr.h"

typedef struct SpecParam {
    const char *name;
    SrcLoc loc;
    double value; /* default */
} SpecParam;

typedef struct SpecCoord {
    const char *name;
    SrcLoc loc;
    ExprId q0, v0; /* initial value and velocity: expressions of p only */
} SpecCoord;

typedef struct SpecInput {
    const char *name;
    SrcLoc loc;
    ExprId expr; /* u(t, p) */
} SpecInput;

typedef struct SpecParticle {
    const char *name;
    SrcLoc loc;
    ExprId mass;   /* of p and t */
    int dim;       /* 2 or 3 */
    ExprId pos[3]; /* of t, q, p, inputs */
} SpecParticle;

typedef enum SpecForceKind {
    FORCE_GRAVITY,   /* vec: field g; V -= m_k g . r_k for every particle */
    FORCE_POTENTIAL, /* expr: added to V */
    FORCE_VECTOR,    /* vec applied at particle: Q_i += F . dr/dq_i */
    FORCE_WORK,      /* expr W: Q_i += dW/dq_i (force factors free of q) */
} SpecForceKind;

typedef struct SpecForce {
    SpecForceKind kind;
    SrcLoc loc;
    int particle; /* FORCE_VECTOR: index into Spec.part */
    int dim;      /* FORCE_GRAVITY, FORCE_VECTOR: 2 or 3 */
    ExprId vec[3];
    ExprId expr;  /* FORCE_POTENTIAL, FORCE_WORK */
} SpecForce;

typedef struct SpecEffect {
    const char *name;
    SrcLoc loc;
    int nforce;
    SpecForce *force;
    int enabled; /* on in the scene */
} SpecEffect;

typedef struct SpecTerm {
    SrcLoc loc;
    ExprId expr;
} SpecTerm;

typedef struct SpecScene {
    double t_end, dt;   /* defaults 10, 0.01 */
    const char *method; /* default "rk8pd" */
    double rtol, atol;  /* defaults 1e-10, 1e-10 */
    double h_fixed;     /* 0 = adaptive */
} SpecScene;

/* The integrators the runtime offers (ORDER: runtime/sim.c eomc_methods). */
extern const char *const spec_methods[];

typedef struct Spec {
    const char *path;        /* as given */
    const char *name;        /* `name:` or the file's base name; a C identifier */
    const char *description; /* or "" */
    int nq, np, nu, npart, neffect, nkinetic, npotential;
    SpecCoord *coord;
    SpecParam *param;
    SpecInput *input;
    SpecParticle *part;
    SpecEffect *effect;
    SpecTerm *kinetic;   /* explicit kinetic-energy terms */
    SpecTerm *potential; /* always-on potential-energy terms */
    SpecScene scene;
} Spec;

/* Load and check a spec.  On bad input, prints the diagnostic and returns
 * NULL; nothing else is left behind.  The Spec lives in A, its
 * expressions in P. */
Spec *spec_load(const char *path, Arena *A, ExprPool *P);
/* The same from a buffer (fuzzing, tests); `path` is only used in messages. */
Spec *spec_load_buffer(const char *path, const char *text, size_t len,
                       Arena *A, ExprPool *P);

/* Turn effects on or off by name before deriving: `list` is a
 * comma-separated list of effect names ("" = none); returns 0, or -1
 * after printing an error naming the unknown effect. */
int spec_select_effects(Spec *s, const char *list);

#endif
