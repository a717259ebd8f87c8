/*
 * lowered: the lowered model's data, which every file of lower/ and the
 * emitter share, and the lookups on it.  No file here calls another of
 * lower/: lower.c builds a Lowered, lower_schedule, lower_taylor and
 * repeat read or rewrite its functions, emit/ prints it.
 *
 * A function is a signature and a list of (expression, output slot).  A
 * signature is written once, as a string of argument names: inputs,
 * then `>`, then outputs; `t` is a scalar, every other argument an array;
 * an output marked `?` may be NULL (its stores are guarded).  For
 * example "t q v p u > M h".
 */
#ifndef EOMC_LOWERED_H
#define EOMC_LOWERED_H

#include "forms/eom.h"

enum { LOW_MAX_ARGS = 16 };

typedef struct LowSig {
    const char *name;    /* the function's name after the model's: "mass_bias" */
    const char *comment; /* one sentence (" * " continues a line) */
    const char *args;    /* "t q v p u > M h" */
    int member;          /* 1: a member of eomc_model, which the model's struct names */
} LowSig;

/* One output: expression e goes to element `index` of output argument
 * `arg` (counted among the outputs, from 0). */
typedef struct LowSlot {
    ExprId e;
    int arg, index;
} LowSlot;

typedef struct LowFunc {
    const LowSig *sig;
    const char *stat;  /* the row of `--stats` its operations count toward */
    int double_only;   /* not needed by the reference solution: not compiled
                        * with -DEOMC_EXTENDED */
    int nout, cap;
    LowSlot *out;
    /* NULL, or per node id its index in the input `shared` (-1: not
     * there): values another function computed once. */
    int *shared;
    /* Called at every step: reads the parameters' derived values
     * (Lowered.derived) instead of computing them. */
    int per_step;
    /* per_step's: NULL until lower_model has derived them, then
     * Lowered.derived (per node id its index in pd[], -1: not there) */
    const int *derived;
    /* Output k's first fill[k] entries are set to 0 first, by a loop, and
     * its zero slots are not in out: an array of mostly zeros (a
     * constraint Jacobian's derivatives) is not a line per zero. */
    int fill[LOW_MAX_ARGS];
    int zeros[LOW_MAX_ARGS]; /* zero slots of each output so far */
    /* bit k: output k arrives zeroed (the caller's part of the contract:
     * eomc_model.h's c_nz), so its fill is not printed */
    unsigned zeroed;
    /* NULL, or copies of one subtree (repeat.h): copy's outputs are the
     * first copy's, and the function runs copy for each c < ncopy with
     * its coordinate-indexed arrays (q v a, seeds, every output) shifted
     * by dq[c] and u by du[c] (dq[0] = du[0] = 0); out holds the rest. */
    struct LowFunc *copy;
    int ncopy;
    int *dq, *du;
    int *dv; /* with speeds: the shift of v, a, dv, da and the outputs (else NULL: dq) */
    /* the first copy's coordinates: span0 .. span0+span-1 (every copy
     * output's slot is one of them, shifted); zero_skip: its outputs
     * vanish with its seeds (a unit load's: no load, no motion), so a copy
     * whose seeds are all 0 stores zeros there instead of running */
    int span0, span, zero_skip;
} LowFunc;

/* The parsed signature: argument names, which are outputs, which may be
 * NULL. */
typedef struct LowArgs {
    int n, nin;               /* arguments, of which the first nin are inputs */
    char name[LOW_MAX_ARGS][16];
    int optional[LOW_MAX_ARGS];
} LowArgs;

void lower_args(const LowSig *sig, LowArgs *a);

/* ---- what the emitter prints besides the functions (lower_describe.c) ---- */

typedef struct LowParam {
    const char *name;
    double value; /* default, or the value it is fixed at */
    int fixed;    /* a constant of the generated code */
} LowParam;

typedef struct LowEffect {
    const char *name;
    int enabled; /* on in the scene (off: no code) */
} LowEffect;

typedef struct LowConstraint {
    const char *name;
    int order;              /* the spec's: 0 holonomic, 1, 2 */
    const char *order_name; /* "holonomic", "first-order", "second-order" */
    int dependent;          /* the coordinate it determines */
} LowConstraint;

typedef struct LowEvent {
    const char *name;
    int direction, action; /* eomc_model.h's */
} LowEvent;

/* What a run's page draws (eomc_model.h's eomc_draw_item, eomc_shape and
 * the view's members; EOMC_POSE and EOMC_DRAW_MASS are these sizes). */
enum { EOMC_POSE_SIZE = 12, EOMC_DRAW_MASS_SIZE = 13, EOMC_SHAPE_NUMS_SIZE = 6 };
typedef struct LowDrawItem {
    const char *name;
    int kind, dim; /* eomc_model.h's EOMC_DRAW_* order */
    int unturned;  /* a body turned by `omega:` alone, drawn unturned */
} LowDrawItem;
typedef SpecShape LowShape; /* .body is its item: the bodies come first */

/* A dry-friction item (eomc_model.h's fric_ members): its name
 * EFFECT.q, the velocity slot of q, the modes of its slip and stick
 * switches; a contact's (speed -1), its speed along a plane's axis, row
 * (fric_rows: its derivatives). */
typedef struct LowFric {
    const char *name;
    int speed, slip, stick;
    ExprId row;
} LowFric;

typedef struct LowCheck {
    const char *what;   /* "particle 'bob': its mass must not be negative" */
    const char *params; /* the parameters it depends on: "m" */
    int strict;         /* expr > 0, else expr >= 0 */
} LowCheck;

/* The model's names, sizes, the scene's choices and the banner's facts,
 * copied out of the spec, the form, the constraints and the invariant so
 * that the emitter prints the lowered model alone. */
typedef struct LowModel {
    const char *name;    /* a C identifier: every global's prefix */
    const char *spec;    /* the spec's file name without directories: output
                          * must not depend on where eomc was run from */
    const char *form, *formula;
    int nq, np, nu, neffect;
    const char **coord;  /* [nq + nspeed] names: the coordinates', then the speeds' */
    /* The speeds (spec.h): nspeed 0, nv = nq and vslot[i] = i.  Else a
     * leaf of order 1 and up of coordinate c is velocity slot vslot[c]
     * (c < nq + nspeed), v_names [nv] the slots' column names ("x'",
     * "root_wx"), and quat [4 nquat] the Euler parameters of each
     * quaternion with speeds. */
    int nv, nspeed, nquat;
    int *vslot, *vcoord, *quat; /* vcoord [nv]: slot j's leaf coordinate (spec.h) */
    const char **v_names;
    LowParam *param;     /* [np] */
    const char **input;  /* [nu] names */
    LowEffect *effect;   /* [neffect] */
    /* the scene */
    const char *scene;   /* NULL: the spec's `scene:` */
    double t_end, dt, rtol, atol, h_fixed;
    const char *method;
    int noutput, nevent, ncheck;
    int nmode;           /* switches of max, min, clamp the functions read */
    int *mode_slot;      /* per switch of the pool: its mode's index, at
                          * u[nu + mode_slot[k]], or -1: not the model's */
    const char **mode_name; /* [nmode]: each switch's name (expr_name_switch) */
    const char **output; /* [noutput] names */
    LowEvent *event;     /* [nevent] */
    int assemble;
    unsigned char *hold; /* [nq + nv] what assembly keeps, or NULL */
    LowCheck *check;     /* [ncheck] */
    /* The constraints (constrained: they were derived); nc names also
     * name the multipliers. */
    int constrained, nc, affine;
    LowConstraint *constraint;
    const char *invariant;      /* its name, NULL if none */
    const char *invariant_note; /* one sentence: what is conserved and why, or why not */
    int *mass_parent; /* [nv] M's tree for an unconstrained model, else NULL */
    /* what a run's page draws: ndraw 0, nothing */
    int ndraw, nshape, nlink, ntrace, view_frames, has_camera;
    LowDrawItem *draw_item; /* [ndraw] */
    LowShape *shape;        /* [nshape] */
    int *view_link;         /* [2 nlink] */
    int *view_trace;        /* [ntrace] */
    double camera[9];
    int view_follow;    /* the item the camera follows, or -1 */
    double view_floor; /* the floor's height: where the page's grid lies */
    /* the places a caller asks the pose and velocity Jacobian of (Spec.place;
     * unturned: the model gives no angular velocity) */
    int nplace;
    LowDrawItem *place; /* [nplace] */
    int nfric;          /* dry-friction items of the effects that are on */
    LowFric *fric;      /* [nfric] */
} LowModel;

/* ---- Taylor's method: the series program (lower_taylor.c) ---- */

/* One call of runtime/include/eomc_taylor.h, printed
 * eomc_tay_CALL(T + slot[0] * S, ..., [value,] k): slot[0 .. nslot-1] are
 * its series arguments in the call's order (results, auxiliary series,
 * operands), then, for const and time, the value (src). */
enum {
    LOW_TAY_SRC_NONE,  /* no value argument */
    LOW_TAY_SRC_CONST, /* value */
    LOW_TAY_SRC_P,     /* p[index] */
    LOW_TAY_SRC_U,     /* u[index] */
    LOW_TAY_SRC_T,     /* t0 */
};
/* The most slots of a call: four products at once (mul4, lower_taylor). */
#define LOW_TAY_MAX_SLOTS 12

typedef struct LowTayStep {
    const char *call; /* "mul": eomc_tay_mul */
    int nslot, nres;  /* slots, of which the first nres are written */
    int slot[LOW_TAY_MAX_SLOTS];
    int src, index;
    double value;
} LowTayStep;

/* What is known of M's series: every entry constant in t, every entry off
 * the diagonal 0 (eomc_model.h's EOMC_TAYLOR_M_*, which the C names). */
enum { LOW_TAYLOR_M_CONSTANT = 1, LOW_TAYLOR_M_DIAGONAL = 2 };

/* taylor_run's program as straight-line code (lower_series.c): each call
 * of the program at each order k < LOW_SERIES_ORDERS written out over
 * cells, slot s's coefficient j being cell j nslot + col[s] (LowSeries').
 * A line computes, in this order (each part absent where it says so):
 *     v = term_first + ... (SUM: each term coef * x * y, added left to
 *         right; coef +-1 a sign, cell y -1 none, x -1 the number coef),
 *     v = v * times (1: none), v = v + term[last] (-1: none),
 *     v = v / (over * cell over_cell) (over 0: none),
 *     v = -v (negate), v = v / after (0: none);
 * a VALUE is src's (LowTayStep's src, index, value); a CALL is fn(x) or
 * fn(x, y) of libm; a SELECT is x where the mode (src U, index) is not 0,
 * else y; a SOLVE is the caller's solve of M_0 a = -b at order index, in
 * place over the x cells from dst (b's on the way in), and at order 0 its
 * terms are M_0's x^2 entries, row-major.  A cell -1 as an operand is 0.  These are the arithmetic of
 * eomc_taylor.h's recurrences in their order, so the same bits, but that
 * a term with a factor 0 at every step (a constant's coefficient past
 * the first, a product of polynomials past its degree) is left out, and
 * a cell no term reaches is not written: its readers see -1, and those
 * of the cells taylor_run copies out are listed in zero_out. */
enum { LOW_SER_SUM, LOW_SER_VALUE, LOW_SER_CALL, LOW_SER_SELECT, LOW_SER_SOLVE };
typedef struct LowSerTerm {
    double coef;
    int x, y;
} LowSerTerm;
typedef struct LowSerLine {
    int dst, kind;
    int first, nterm; /* SUM: term[first .. first + nterm - 1] */
    double times;
    int last;
    double over;
    int over_cell, negate;
    double after;
    const char *fn; /* CALL: sqrt, exp, pow, sin, cos, sinh or cosh (eomc_taylor.h
                     * has an eomc_v4_ helper for each, for taylor_run4) */
    int x, y;       /* CALL's, SELECT's operands (-1: 0; CALL's y -1: one operand) */
    int src, index;
    double value;
    int pack;       /* 2 or 4: this line and the next pack - 1 are one pack,
                     * printed as one line on vectors (lower_pack.c); else 0 */
} LowSerLine;
/* The orders written out: rtol down to 1e-16 asks for at most 20
 * (taylor.c's order rule); taylor_run loops over the program above. */
enum { LOW_SERIES_ORDERS = 20 };
/* Up to this many terms the written-out series is one function, which
 * the C compiler optimizes whole (Kepler's values stay in registers from
 * one line to the next).  Past it, the optimizer's time grows faster than
 * the terms do (gcc -Og or -O1: the Pleiades' 25 000 terms take 31 or 47
 * s as one function, the register allocator's time), so the series is cut
 * into parts of a few lines each (emit_taylor.c, SERIES_PART_LINES),
 * each a function of its own that the optimizer sees alone. */
enum { LOW_SERIES_OPTIMIZED_TERMS = 2500 };
/* The most terms written out: a larger model's series is its program's
 * loop (docs/internals.md, "Taylor's series written out"). */
enum { LOW_SERIES_MAX_TERMS = 60000 };
typedef struct LowSeries {
    int ncell;
    int *col;       /* [nslot]: slot s's coefficient j is cell j nslot + col[s]
                     * (lower_pack.c lays the slots out for its packs) */
    int *place;     /* [nslot] by column: the state's index (the cell is the
                     * caller's X[j nstate + place]), or -1 (W's) */
    LowSerLine *line;
    int nline;
    int *start;     /* [LOW_SERIES_ORDERS + 1]: order k's lines from start[k] */
    LowSerTerm *term;
    int nterm;
    int *zero_out;  /* the cells taylor_run copies out that no line writes
                     * (0 at every step): written 0 (nzero_out) */
    int nzero_out;
    int parted;      /* more than LOW_SERIES_OPTIMIZED_TERMS terms: printed in parts */
    int lanes;       /* also for four runs at once (taylor_run4): M constant
                      * and diagonal, and one function */
} LowSeries;

/* The program of the model's taylor member (eomc_model.h): nstep calls
 * over nslot series, in an order where every operand is computed before
 * it is read; the caller writes the slots of q and of the speeds v
 * (q_slot [nq], v_slot [nv], -1: nothing reads it; nv = nq without
 * speeds, v = q').  M_slot[i nv + j], h_slot[i], g_slot[e]: the results
 * (-1: zero at every order); with constraints also B_slot[c nv + i] (B =
 * df/dv'), f_slot[c], pos_slot[c] and vel_slot[c] (c_levels'): f at v' =
 * 0 when every constraint is affine in v', else (nonlinear) at the v'
 * the caller writes into a_slot[i].  With speeds of their own, qd_slot[i]
 * is the series of q_i' = W(q) v's row i (qdot's), from which the runtime
 * sums q: a rate that is a speed is that speed's own slot, v_slot's;
 * NULL without.  why: NULL, or why there is no program (one sentence),
 * and then nothing else is set. */
typedef struct LowTaylor {
    const char *why;
    int nslot, nstep;
    LowTayStep *step;
    int *q_slot;          /* [nq] */
    int *v_slot;          /* [nv] */
    int *qd_slot;         /* [nq] with speeds, else NULL */
    int *M_slot;          /* [nv nv] */
    int *h_slot;          /* [nv] */
    int *g_slot;          /* [nevent + nmode]: the events', the switches' */
    int nevent, nmode, nc, nonlinear;
    int *a_slot;          /* [nv] */
    int mass;             /* LOW_TAYLOR_M_CONSTANT | LOW_TAYLOR_M_DIAGONAL */
    int nrun;             /* taylor_run's calls after each order's program,
                           * step[nstep .. nstep + nrun - 1] (every q and v
                           * then has a slot); 0: no taylor_run */
    int nstate, nv;       /* with taylor_run: nq + nv, and the speeds nv */
    int *state_slot;      /* [nstate]: the state's slots, q's then v's (the
                           * caller's X's order) */
    int *acc_slot;        /* [nv] where taylor_run solves M_0 a_k = -b_k by the
                           * caller's hook (M not constant and diagonal):
                           * a's series, consecutive slots; else NULL */
    LowSeries *series;    /* taylor_run written out, or NULL: its loop */
    int *B_slot;          /* [nc nv] */
    int *f_slot, *pos_slot, *vel_slot; /* [nc] */
} LowTaylor;

/* The model's functions in the order they are printed. */
typedef struct Lowered {
    LowModel model;
    int nfunc, cap;
    LowFunc **func;
    /* the ones the emitter wraps in hand-written C (NULL when absent) */
    LowFunc *jac_dv;      /* seeded Jacobian: its per-column loop follows */
    LowFunc *jac_shared;
    LowFunc *accel_solve; /* the pivot check follows */
    LowFunc *mass_times;  /* mass_bias by columns follows (bias before it) */
    LowFunc *check_values;
    /* The values of the parameters alone that the per-step functions
     * need: derive computes them into pd[] when the parameters change,
     * and derived[id] is node id's index there (-1: not derived). */
    LowFunc *derive;
    LowFunc *outputs;     /* the scene's outputs, or NULL */
    LowFunc *events;      /* the scene's event functions g [nevent], or NULL */
    LowFunc *switches;    /* the switch functions s [nmode] (expr.h), or NULL */
    LowFunc *fric_bound;  /* the friction items' force bounds F [nfric], or NULL */
    LowFunc *fric_rows;   /* their rows and biases, where a contact has friction, or NULL */
    LowFunc *draw, *draw_mass; /* the draw items' poses and the bodies' masses, or NULL */
    LowFunc *draw_shapes;      /* the shapes' sizes and positions of parameters, or NULL */
    LowFunc *places, *place_velocity; /* the places' poses and velocities, or NULL */
    LowFunc **event_set;  /* [nevent]: the resets of `set` events (else NULL) */
    LowFunc *last_set;    /* the last of them: the dispatcher follows it */
    int *derived;
    size_t derived_ids; /* derived's length: the pool's size when it was made */
    int nd;
    /* code = LOWER_CODE_TABLES: tau, then accel and mass_bias by hand over
     * the tables, whose numbers are pd[tree_base ...] */
    int code;
    /* every branch of every switched expression computed, none in lazy
     * blocks (lower_schedule.h; --branches eager): set by the caller */
    int eager_branches;
    const FormTables *tables;
    const char *tables_why; /* --code tables asked, and why they could not be */
    LowFunc *tau, *potential;
    int tree_base;
    /* Constrained, every constraint affine in q'', with multipliers, and
     * the form solves for q'' (a tree): accel is the solve without the
     * constraints (eomc_model's free_accel) and minv = M^-1 da by unit
     * loads (eomc_model's minv), from which the runtime solves the
     * multipliers without forming M (kkt.c); with tables both are loops
     * over them (minv NULL).  loads 0 and minv NULL otherwise. */
    LowFunc *minv;
    int loads;
    /* With loads and no tables, where neither function was split into
     * copies: accel stores into shared[] the loads_shared values minv
     * reads instead of computing the recursion again (0: minv computes
     * all, lower_loads_shared). */
    int loads_shared;
    /* [nc] with loads: 1 where the recursion's q'' meets the constraint
     * by itself, its multiplier 0 (a frame's unit quaternion, when no
     * potential, force or kinetic term of the spec's own acts on its
     * parameters); NULL: none */
    unsigned char *held;
    int n;                /* coordinates */
    int nv;               /* velocity slots (n without speeds) */
    LowFunc *qdot;        /* q' = W(q) v and its Jacobian, with speeds (else NULL) */
    LowFunc *qdot_jacobian;
    int jacobian;         /* how it was lowered: _UNROLLED, _SEEDED or _NONE */
    int invariant_energy; /* the invariant is T + V: energy's sum, not a function */
    LowTaylor *taylor;    /* the taylor member's program, or why there is none */
} Lowered;

/* How the jacobian member is computed.  UNROLLED: every entry of dE/dq
 * and dE/dq' as its own expression, the fastest to run; code grows as
 * n |E|.  SEEDED: the directional derivatives of E along seeds dq and
 * dq' as two functions (code ~ |E|) that jacobian calls once per column
 * with a unit seed: exact all the same, slower to run, far less for the C
 * compiler.  NONE: not at all (the member is NULL; the implicit methods
 * and the linearization refuse the model).  AUTO: unrolled up to
 * LOWER_UNROLLED_JACOBIAN_MAX operations, seeded beyond; AUTO_LIBRARY,
 * auto for a library (eomc build --shared), up to
 * LOWER_UNROLLED_JACOBIAN_LIBRARY_MAX. */
enum {
    LOWER_JACOBIAN_AUTO,
    LOWER_JACOBIAN_UNROLLED,
    LOWER_JACOBIAN_SEEDED,
    LOWER_JACOBIAN_NONE,
    LOWER_JACOBIAN_AUTO_LIBRARY,
};
/* Measured on the chain benchmark (gcc 12, -O2): cc spends ~0.3 ms per
 * operation, linearly; the seeded Jacobian runs 2-3x slower (N = 20:
 * 4.5 -> 13 us, N = 50: 47 -> 97 us) but is 6x (N = 20) to 16x (N = 50)
 * less code.  Up to here the unrolled one costs < 6 s of cc. */
enum { LOWER_UNROLLED_JACOBIAN_MAX = EOM_STRAIGHT_LINE_MAX };
/* A library's Jacobian is its caller's: the Python package's
 * accel_derivatives and linearize, called in loops, where a simulator's
 * implicit method calls it once a step or less.  There the faster one is
 * worth more of cc: MuJoCo's humanoid (58 723 operations unrolled, 12 563
 * seeded) builds in 6.3 s instead of 4.2 s (two cores, -Og and -O1 units)
 * and its accel_derivatives takes 48 us instead of 79 (docs/benchmarks.md).
 * The 50-link chain (90 700) stays seeded. */
enum { LOWER_UNROLLED_JACOBIAN_LIBRARY_MAX = 65536 };

/* How the articulated-body form's accel and mass_bias are written.
 * STRAIGHT: straight-line code, every constant folded, the fastest to run
 * and slowest to compile (~0.3 ms of cc -O2 per operation).  TABLES:
 * loops over the model's tables (runtime/include/eomc_tree.h, forms.h's
 * FormTables), a few hundred lines of C whatever the size, 2-3 times
 * slower to run.  AUTO: tables when the straight-line solve, bias and
 * energies would pass LOWER_TABLES_MIN operations (measured, gcc 12 -O2:
 * gen_tree 30's 27 051 take 11 s of cc, the 200-link chain's 32 206 take
 * 19 s; with tables each builds in 1-2 s).  Other forms are always
 * straight-line. */
enum { LOWER_CODE_AUTO, LOWER_CODE_STRAIGHT, LOWER_CODE_TABLES };
enum { LOWER_TABLES_MIN = 30000 };

/* 1 + the highest index stored to output argument `arg` (0 if none),
 * copies included. */
int lower_size(const LowFunc *f, int arg);

/* The function named `name`, or NULL. */
const LowFunc *lower_find(const Lowered *L, const char *name);

#endif
