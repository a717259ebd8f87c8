/*
 * spec: load a model spec (YAML, through libyaml) into a Spec.
 *
 * Every expression is parsed (parse.h), its names resolved and its
 * defines expanded, so a Spec holds only ExprIds over coordinates
 * (EXPR_VAR), parameters, inputs and t.  All entities keep the location
 * of their YAML node for later diagnostics.  A Spec that spec_load returns
 * has been checked: bad input never gets past it.  The format is
 * documented in docs/spec.md.  The loader is in spec/, one file per
 * concept (spec/loader.h); this header is its whole interface.
 */
#ifndef EOMC_SPEC_H
#define EOMC_SPEC_H

#include "base/arena.h"
#include "base/diag.h"
#include "expr/expr.h"

/* Every ExprId field of the structs below is visited by
 * spec_foreach_expr (spec/fold.c), which folding (--fix) and any other
 * pass over all of a Spec's expressions go through: a new field that
 * holds an expression must be added there, or it escapes them. */

typedef struct SpecParam {
    const char *name;
    SrcLoc loc;
    double value; /* default, or the value it is fixed at */
    int fixed;    /* fixed by the scene (`fix:`) or --fix: a constant in every
                   * expression, folded at compile time */
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
    ExprId vel[3]; /* at a point of frames: its velocity by their structure */
    int has_vel;   /* (kin.h); 0: the time derivative of pos */
    int point;     /* that point (kin.h), or -1 */
} SpecParticle;

/* A turn by Euler parameters, of a body (`rotation: {quaternion: [...]}`)
 * or of a frame (a turn {quaternion: [...]}): the parameters' coordinates
 * (scalar first), whose they are ("body 'top'", "frame 'ball'"), and
 * where.  Each gets the holonomic constraint NAME_unit:
 * e0^2 + e1^2 + e2^2 + e3^2 - 1 = 0. */
typedef struct SpecQuat {
    const char *name; /* the body's or frame's: its constraint is NAME_unit */
    const char *owner;
    int q[4];
    SrcLoc loc;
    /* Its first speed (SpecSpeed, three in a row: `speeds:`), whose rates
     * the Euler parameters' are (no unit constraint, no inertia along e);
     * -1: the parameters' rates are coordinates' (the unit constraint). */
    int speed;
} SpecQuat;

/* A speed that is no coordinate's rate: a component of the angular
 * velocity, in its own turned axes, of a frame or body turned by a
 * quaternion with `speeds:`.  Speed k is the leaf expr_var(nq + k, 1),
 * its rate expr_var(nq + k, 2), and has no coordinate (order 0). */
typedef struct SpecSpeed {
    const char *name;
    SrcLoc loc;
    ExprId v0;       /* initial value: an expression of p */
} SpecSpeed;

/* A rigid body: T = 1/2 m |c'|^2 + 1/2 w.I w with w its body-frame
 * angular velocity.  Planar bodies (dim 2) have one angle and a scalar
 * inertia (inertia[0], omega[0]). */
typedef struct SpecBody {
    const char *name;
    SrcLoc loc;
    ExprId mass;       /* of p and t */
    int dim;           /* 2 or 3 */
    ExprId center[3];  /* centre of mass, of t, q, p */
    ExprId center_vel[3]; /* its velocity, when frames give it by their structure */
    int has_center_vel;   /* (kin.h); 0: the time derivative of center */
    int frame, point;     /* placed by a frame, centre at a point (kin.h); -1: not */
    ExprId inertia[9]; /* about the centre, body frame, row-major, of p */
    ExprId omega[3];   /* body-frame angular velocity, of t, q, q', p */
    /* rotation: {quaternion: [e0, e1, e2, e3]}: the Euler parameters'
     * coordinates (scalar first), and where; quat[0] = -1 otherwise.
     * omega = 2 L(e) e', and the spec gets the constraint NAME_unit:
     * e0^2 + e1^2 + e2^2 + e3^2 - 1 = 0. */
    int quat[4];
    SrcLoc quat_loc;
    int quat_speed;    /* as SpecQuat.speed */
    /* What it is drawn at (--animate): turned by a rotation sequence or
     * quaternion, rot is its rotation matrix (row-major, body to world) and
     * has_rot 1; planar with an `angle:`, angle is it (else EXPR_NONE).
     * A body placed by a frame is drawn with the frame's rotation; one
     * given by `omega:` alone is drawn unturned (nothing says where it
     * points). */
    ExprId rot[9];
    int has_rot;
    ExprId angle;
} SpecBody;

/* A shape a body is drawn as (`shapes:`), in its frame, or the ground
 * (`ground:`), in the world's: numbers only.  A contact effect makes
 * shapes collide (SpecForce.pair).  A plane (the ground's only) is a
 * half-space, not drawn: its pos a point of its surface, its quat's +z
 * the outward normal. */
enum { SPEC_SHAPE_BOX, SPEC_SHAPE_SPHERE, SPEC_SHAPE_CAPSULE, SPEC_SHAPE_CYLINDER,
       SPEC_SHAPE_ELLIPSOID, SPEC_SHAPE_PLANE };
typedef struct SpecShape {
    int body, type;  /* the draw item's index (a body's is its Spec.body index: the
                      * bodies come first); SPEC_SHAPE_* (eomc_model.h's order) */
    double size[3];  /* box: half-sizes; sphere: radius; capsule, cylinder:
                      * radius, half-length; ellipsoid: semi-axes (unused 0) */
    double pos[3], quat[4], rgba[4];
    /* a size or position of parameters (its number: at their defaults),
     * else EXPR_NONE */
    ExprId esize[3], epos[3];
    /* `name:`, else its body's name (BODY.k, k from 1, where the body has
     * several; the ground's: ground, ground.k) */
    const char *name;
    /* which shapes a contact's `all` pairs it with (MuJoCo's bit masks):
     * two collide iff (a.contype & b.conaffinity) || (b.contype & a.conaffinity) */
    unsigned contype, conaffinity;
    SrcLoc loc;
} SpecShape;

/* What a run's page draws: every body, every particle, the ground (where
 * `ground:` gives it shapes), then the points and frames the scene's
 * `view:` names (eomc_model.h's draw items, same order; the ground is
 * drawn as a body that does not move, EOMC_DRAW_BODY). */
enum { SPEC_DRAW_BODY, SPEC_DRAW_PARTICLE, SPEC_DRAW_POINT, SPEC_DRAW_FRAME, SPEC_DRAW_GROUND };
typedef struct SpecDrawItem {
    const char *name;
    int kind;  /* SPEC_DRAW_* */
    int index; /* into Spec.body or Spec.part, or kin.h's point or frame */
    int dim;   /* 2 (z = 0, turning about z) or 3 */
    int unturned; /* a body turned by `omega:` alone: nothing says where it points */
} SpecDrawItem;

typedef struct SpecView {
    int nitem;
    SpecDrawItem *item;
    int nlink, ntrace;
    int *link;         /* [2 nlink] item indices */
    int *trace;        /* [ntrace] */
    int frames;        /* 1: draw the frame items' axes; 2 (`frames: true`): each body's too */
    int has_camera;
    double camera[9];  /* position, target, up */
    int follow;        /* the item the camera follows, or -1 */
    double floor;      /* the floor's height (3-D): where the grid lies */
} SpecView;

typedef enum SpecForceKind {
    FORCE_GRAVITY,   /* vec: field g; V -= m_k g . r_k for every particle */
    FORCE_POTENTIAL, /* expr: added to V */
    FORCE_VECTOR,    /* vec applied at particle (or a body's centre):
                      * Q_i += F . dr/dq_i */
    FORCE_TORQUE,    /* vec (body frame; planar: vec[0]) on body:
                      * Q_i += tau . dw/dq_i' */
    FORCE_WORK,      /* expr W = sum_i Q_i delta(q_i) (seeds): Q_i += dW/d delta(q_i) */
    FORCE_KINETIC,   /* expr: added to T while the effect is on (a rotor's
                      * inertia, MuJoCo's armature) */
    FORCE_CONTACT,   /* pair: shapes that push each other apart where they
                      * overlap, N = max(0, k d + c d') (mechanics/contact.c) */
} SpecForceKind;

typedef struct SpecForce {
    SpecForceKind kind;
    SrcLoc loc;
    int particle; /* FORCE_VECTOR: index into Spec.part, or -1 */
    int body;     /* FORCE_VECTOR, FORCE_TORQUE: index into Spec.body, or -1 */
    int dim;      /* FORCE_GRAVITY, FORCE_VECTOR: 2 or 3 */
    ExprId vec[3];
    ExprId expr;  /* FORCE_POTENTIAL, FORCE_WORK, FORCE_KINETIC */
    /* FORCE_CONTACT: npair pairs of Spec.shape indices, pair[2 j] and
     * pair[2 j + 1] as written (each of two types eomc has a gap for),
     * and the normal force's stiffness k and damping c (of p, >= 0);
     * mu, the friction coefficient of pairs with a plane (EXPR_ZERO: none) */
    int npair;
    int *pair;
    ExprId stiffness, damping, mu;
    /* A dry-friction item (`friction: q`, spec/friction.c) is FORCE_WORK
     * with friction = 1: on coordinate coord, at most the force bound,
     * slip and stick its switches (the pool's); friction = 0 otherwise. */
    int friction, coord, slip, stick;
    ExprId bound;
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

/* A constraint expr = 0, classified by the highest derivative of a
 * coordinate in it (defines expanded): 0 holonomic g(t, q), 1 first
 * order phi(t, q, q') (linear or not), 2 second order f(t, q, q', q''). */
typedef struct SpecConstraint {
    const char *name;
    SrcLoc loc;
    ExprId expr;
    int order;
    int dependent;    /* coordinate to eliminate, or -1: the compiler chooses */
    SrcLoc dep_loc;   /* of `dependent:` */
} SpecConstraint;

/* A column the scene adds to the output: NAME = expr of t, q, q', q'',
 * the inputs and the multipliers. */
typedef struct SpecOutput {
    const char *name;
    SrcLoc loc;
    ExprId expr;
} SpecOutput;

enum { EVENT_STOP, EVENT_RECORD, EVENT_SET };

/* A zero crossing of `when` (of t, q, q', p) in a direction (+1 up, -1
 * down, 0 both), and what it does: stop, record the state, or set
 * coordinates and velocities (set_var[k] = expr_var(i, 0 or 1)) to
 * set_expr[k] of the state just before. */
typedef struct SpecEvent {
    const char *name;
    SrcLoc loc;
    ExprId when;
    int direction;
    int action;
    int nset;
    ExprId *set_var, *set_expr;
} SpecEvent;

typedef struct SpecScene {
    const char *name;   /* NULL: the unnamed `scene:`, or none */
    double t_end, dt;   /* defaults 10, 0.01 */
    const char *method; /* default "rk8pd" */
    double rtol, atol;  /* defaults 1e-10, 1e-10 */
    double h_fixed;     /* 0 = adaptive */
    int noutput, nevent;
    SpecOutput *output;
    SpecEvent *event;
    /* `assemble:`: every run first puts the initial state onto the
     * holonomic and first-order constraints (1), keeping what hold marks
     * [nq + nv] as it is (hold[i]: q_i, hold[nq + j]: velocity slot j; NULL: nothing);
     * 0: runs start as given. */
    int assemble;
    unsigned char *hold;
} SpecScene;

/* Every named scene, for --explain: what each turns on, in one line. */
typedef struct SpecSceneInfo {
    const char *name;
    SrcLoc loc;
    const char *summary;
} SpecSceneInfo;

/* A condition that physical data must meet, on the parameters: expr > 0
 * (strict) or expr >= 0.  spec_load checks it with the parameters'
 * defaults (an error at loc); the generated simulator checks it again for
 * the values --set gives (a usage error naming what and params). */
typedef struct SpecCheck {
    ExprId expr;
    int strict;
    const char *what;   /* "particle 'bob': its mass must not be negative" */
    const char *params; /* the parameters it depends on: "m" */
    SrcLoc loc;
} SpecCheck;

/* The integrators the runtime offers (ORDER: runtime/model/sim.c eomc_methods). */
extern const char *const spec_methods[];
/* 1 if the method solves with the Jacobian of the equations (the
 * implicit ones), 0 if not, -1 for a name not among spec_methods. */
int spec_method_jacobian(const char *name);

typedef struct Spec {
    const char *path;        /* as given */
    const char *name;        /* `name:` or the file's base name; a C identifier */
    const char *description; /* or "" */
    int nq, np, nu, npart, nbody, neffect, nkinetic, npotential, nconstraint;
    SpecCoord *coord;
    SpecParam *param;
    SpecInput *input;
    SpecParticle *part;
    SpecBody *body;
    SpecEffect *effect;
    SpecTerm *kinetic;   /* explicit kinetic-energy terms */
    SpecTerm *potential; /* always-on potential-energy terms */
    SpecConstraint *constraint;
    SpecScene scene;     /* the scene compiled */
    int nscenes;         /* named scenes (`scenes:`), 0 with `scene:` */
    SpecSceneInfo *scenes;
    int nfixed;          /* parameters fixed (SpecParam.fixed) */
    int ncheck, capcheck;
    SpecCheck *check;    /* masses and inertias: what --set must respect */
    int nspeed;          /* speeds that are no coordinate's rate */
    SpecSpeed *speed;
    /* The velocity slots, nv of them: vcoord[j] is the leaf coordinate of
     * slot j, i for coordinate i's rate or nq + k for speed k, in the
     * order of the coordinates with a quaternion's three speeds where its
     * first Euler parameter is.  Without speeds, nv = nq and vcoord[i] =
     * i.  vslot[c] (c < nq + nspeed) is c's slot, -1 for an Euler
     * parameter that has speeds. */
    int nv;
    int *vcoord, *vslot;
    int nfquat;          /* frames turned by quaternions: each adds to T */
    SpecQuat *fquat;     /* 1/2 c (e.e')^2 (mech.c) and a unit constraint */
    const struct Kin *kin; /* the frames and points (kin.h) */
    int nshape;
    SpecShape *shape;    /* the bodies' `shapes:` */
    SpecView view;       /* the compiled scene's `view:` and the draw items */
    /* The places a caller asks the pose and velocity Jacobian of, by name:
     * every body (at its centre of mass) and particle, then every frame
     * and point the spec names, in the order of the spec (not a view's:
     * the same for every scene). */
    int nplace;
    SpecDrawItem *place;
} Spec;

/* What the command line chooses: a named scene (NULL: the first), and
 * parameters to fix: "NAME=VALUE,NAME=VALUE" (NULL: none), on top of the
 * scene's `fix:`. */
typedef struct SpecOptions {
    const char *scene;
    const char *fix;
} SpecOptions;

/* Load and check a spec.  On bad input, prints the diagnostic and returns
 * NULL; nothing else is left behind.  The Spec lives in A, its
 * expressions in P.  o may be NULL (the first scene, nothing fixed). */
Spec *spec_load(const char *path, const SpecOptions *o, Arena *A, ExprPool *P);
/* The same from a buffer (fuzzing, tests); `path` is only used in messages. */
Spec *spec_load_buffer(const char *path, const char *text, size_t len,
                       const SpecOptions *o, Arena *A, ExprPool *P);

/* Spec.nv, vcoord and vslot for a spec without speeds (nv = nq, every
 * slot its coordinate's rate): for a Spec built by hand (tests); the
 * loader sets them itself. */
void spec_plain_slots(Spec *s, Arena *A);

/* f(&e, ctx) for every expression field e of s (not EXPR_NONE), which f
 * may rewrite: initial values, inputs, particles, bodies, effects, energy
 * terms, constraints, checks, and the scene's outputs and events. */
typedef void SpecExprFn(ExprId *e, void *ctx);
void spec_foreach_expr(Spec *s, SpecExprFn *f, void *ctx);

/* Turn effects on or off by name before deriving: `list` is a
 * comma-separated list of effect names ("" = none); returns 0, or -1
 * after printing an error naming the unknown effect. */
int spec_select_effects(Spec *s, const char *list);

#endif
