/*
 * expr: the expression DAG.
 *
 * Nodes are immutable and hash-consed: building a node that already exists
 * returns the existing id, so common subexpressions are shared by
 * construction.  A node's operands always have smaller ids than the node,
 * so id order is a topological order and ids are deterministic (they only
 * depend on the order of construction calls: so never build nodes in two
 * operands of one expression whose order C leaves unspecified, such as
 * two arguments of a call; generated/sequenced.py checks).
 *
 * The constructors simplify: constant folding (only to finite results;
 * -0.0 is stored as 0.0), x+0, x*1, x*0 = 0 (symbolically: no IEEE
 * infinities are assumed), --x, x-x, integer powers, and coefficient
 * factors (expressions of constants and parameters only, such as m*l^2)
 * collected to the left of a product and out of sums: c*x + c*y =
 * c*(x + y).  Mechanics is full of m and l; this keeps them from being
 * multiplied in again and again.  And sin(x)^2 + cos(x)^2 = 1 between any
 * two terms of a sum that differ only there (k R sin^2 + k R cos^2 = k R,
 * R a product of powers), the form of a squared speed on a circle.
 *
 * All nodes live in one ExprPool and are freed with it.
 */
#ifndef EOMC_EXPR_H
#define EOMC_EXPR_H

#include <stddef.h>
#include <stdint.h>

typedef uint32_t ExprId;

enum {
#define OP(name, arity, spell, kind) EXPR_##name,
#include "ops.def"
#undef OP
    EXPR_NOPS
};

#define EXPR_NONE ((ExprId)0xffffffffu) /* "no expression" sentinel */
enum { EXPR_ZERO = 0, EXPR_ONE = 1 }; /* made by expr_pool_new */
enum { EXPR_MAX_ORDER = 3 };     /* highest derivative a VAR may carry */

enum { OPK_LEAF, OPK_INFIX, OPK_PREFIX, OPK_CALL, OPK_SELECT };

/* What a node depends on (derived from its operands when it is built):
 * one bit per kind of leaf, and per derivative order of the coordinates. */
enum {
    DEP_T = 1 << 0,      /* time */
    DEP_Q = 1 << 1,      /* q; DEP_Q << k for the k-th derivative */
    DEP_P = 1 << 5,      /* parameters */
    DEP_U = 1 << 6,      /* inputs */
    DEP_S = 1 << 7,      /* seeds of a directional derivative */
    DEP_L = 1 << 8,      /* multipliers of the constraints */
    DEP_M = 1 << 9,      /* a switched expression (SELECT): it reads a mode,
                            an input slot, so DEP_U comes with it */
};
#define DEP_ORDER(k) (DEP_Q << (k))
#define DEP_ANY_Q (DEP_ORDER(0) | DEP_ORDER(1) | DEP_ORDER(2) | DEP_ORDER(3))

typedef struct ExprNode {
    uint8_t op;
    uint8_t coeff; /* depends on parameters and constants only (derived) */
    uint16_t deps; /* DEP_ bits of the leaves below (derived) */
    uint32_t a, b; /* operands, or leaf data: see ops.def */
    uint32_t height; /* 0 for a leaf, else 1 + the operands' highest (derived) */
    double value;  /* EXPR_CONST: the number; EXPR_SELECT: the mode index */
} ExprNode;

typedef struct ExprPool ExprPool;

ExprPool *expr_pool_new(void);
void expr_pool_free(ExprPool *P);
size_t expr_pool_size(const ExprPool *P);
const ExprNode *expr_node(const ExprPool *P, ExprId e);

/* Operator tables, from ops.def. */
extern const char *const expr_op_spelling[EXPR_NOPS];
extern const char *const expr_op_name[EXPR_NOPS];
extern const int expr_op_arity[EXPR_NOPS];
extern const int expr_op_kind[EXPR_NOPS];

/* Leaves. */
ExprId expr_const(ExprPool *P, double v);
ExprId expr_var(ExprPool *P, int coord, int order);
ExprId expr_param(ExprPool *P, int index);
ExprId expr_input(ExprPool *P, int index);
ExprId expr_time(ExprPool *P);
/* The seed component dq_i (kind 0), dq'_i (1) or dq''_i (2) of a directional
 * derivative (diff_jvp).  Only the emitter gives seeds values. */
ExprId expr_seed(ExprPool *P, int coord, int kind);
/* The multiplier of constraint c (outputs only: nothing differentiates it). */
ExprId expr_mult(ExprPool *P, int c);

/* A coordinate whose rate is not a speed of its own: q_coord' = rate, an
 * expression of the coordinates and the speeds (a unit quaternion's
 * Euler parameters, whose rates are 1/2 e (x) (0, w) in the body's angular
 * velocity w).  diff_time then takes rate for the coordinate's derivative,
 * and the coordinate has no leaves of order 1 and up.  Set it before any
 * derivative of an expression that holds the coordinate.  expr_rate is
 * EXPR_NONE where the coordinate's rate is its own leaf, q_coord'. */
void expr_set_rate(ExprPool *P, int coord, ExprId rate);
ExprId expr_rate(const ExprPool *P, int coord);
/* Every coordinate's rate its own leaf again (a pool that serves one spec
 * at a time: spec_load starts so). */
void expr_clear_rates(ExprPool *P);
/* No switches (a pool that serves one spec at a time: an earlier spec's
 * kinks are not this one's; its nodes keep their modes and are not used). */
void expr_clear_switches(ExprPool *P);

/* Simplifying constructors. */
ExprId expr_add(ExprPool *P, ExprId a, ExprId b);
ExprId expr_sub(ExprPool *P, ExprId a, ExprId b);
ExprId expr_mul(ExprPool *P, ExprId a, ExprId b);
ExprId expr_div(ExprPool *P, ExprId a, ExprId b);
ExprId expr_neg(ExprPool *P, ExprId a);
ExprId expr_powi(ExprPool *P, ExprId a, int n);
ExprId expr_pow(ExprPool *P, ExprId a, ExprId b);
/* Any unary (SIN..SIGN, NEG) or binary (ADD..DIV, POW, ATAN2) operator. */
ExprId expr_unary(ExprPool *P, int op, ExprId a);
ExprId expr_binary(ExprPool *P, int op, ExprId a, ExprId b);

/* Switched expressions.  max, min and clamp are not smooth: each kink
 * is a *switch* k, a smooth switch function s_k of the pool's, and a
 * mode that says on which side of s_k = 0 the run is (1 where s_k > 0,
 * 0 where s_k < 0).  Within a mode the expression is one smooth branch,
 * SELECT(k, a, b) = mode k ? a : b, so derivatives are exact there
 * (d SELECT(k, a, b) = SELECT(k, da, db)); the runtime ends a step at
 * each s_k = 0 and flips the mode.  A switch function met again (same
 * node) is the same switch: max(a, b) and min(a, b) share one.  Where s
 * is a constant the branch is chosen now and no switch is made.
 *   max(a, b)         = SELECT(k, a, b),  s_k = a - b
 *   min(a, b)         = SELECT(k, b, a),  s_k = a - b
 *   clamp(x, lo, hi)  = SELECT(k, hi, SELECT(j, x, lo)),
 *                       s_k = x - hi, s_j = x - lo
 *   step(x)           = SELECT(k, 1, 0),  s_k = x
 *   where(s, a, b)    = SELECT(k, a, b),  s_k = s  (a where s > 0, else b)
 * (clamp is hi where x > hi, else max(x, lo): lo <= hi is the caller's.) */
ExprId expr_select(ExprPool *P, int mode, ExprId a, ExprId b);
ExprId expr_where(ExprPool *P, ExprId s, ExprId a, ExprId b);
ExprId expr_max(ExprPool *P, ExprId a, ExprId b);
ExprId expr_min(ExprPool *P, ExprId a, ExprId b);
ExprId expr_clamp(ExprPool *P, ExprId x, ExprId lo, ExprId hi);
/* A switch that no function of the model drives: its mode is set by the
 * runtime alone (dry friction's stick, runtime/model/friction.c), and its
 * s_k is the constant -1, which the runtime replaces.  Always a new one;
 * its k.  SELECT it with expr_select. */
int expr_switch_held(ExprPool *P);
/* The pool's switches, in the order they were made: mode k's s_k. */
int expr_nswitch(const ExprPool *P);
ExprId expr_switch(const ExprPool *P, int k);
/* A switch's name, for a run's messages and --events (NULL: none
 * given).  Naming a named switch again keeps the first; a name another
 * switch has gets a suffix .2, .3, ... */
void expr_name_switch(ExprPool *P, int k, const char *name);
const char *expr_switch_name(const ExprPool *P, int k);
/* The mode a SELECT node reads. */
int expr_select_mode(const ExprPool *P, ExprId e);

/* Queries. */
int expr_is_const(const ExprPool *P, ExprId e, double *value);
/* Does e depend on parameters and constants only? */
int expr_is_coeff(const ExprPool *P, ExprId e);
/* Highest derivative order of any coordinate in e, or -1 if none. */
int expr_max_order(const ExprPool *P, ExprId e);
/* The DEP_ bits of e. */
unsigned expr_deps(const ExprPool *P, ExprId e);
/* The first leaf (lowest id) below e whose DEP_ bits meet `deps`, or
 * EXPR_NONE: to name what an expression should not depend on. */
ExprId expr_find_leaf(ExprPool *P, ExprId e, unsigned deps);
/* Does e contain the given leaf (a VAR, PARAM, INPUT or TIME node)? */
int expr_depends(ExprPool *P, ExprId e, ExprId leaf);

/* A POWI node of exponent n up to this is computed as x * x * ... * x
 * (n factors, left to right), as the C prints it: shorter than a call of
 * pow.  Past it, pow(x, n).  expr_eval and expr_eval_node compute it so
 * too. */
enum { EXPR_POWI_MUL_MAX = 4 };

/* Numerical evaluation (tests, checks, constant parameters). */
typedef struct ExprEnv {
    double t;
    const double *q[EXPR_MAX_ORDER + 1]; /* q[k][i]: k-th derivative of q_i */
    const double *p;
    const double *u;
    const double *seed[3]; /* seeds dq, dq', dq'' of EXPR_SEED; NULL reads as 0 */
    const double *lam;     /* multipliers of EXPR_MULT; NULL reads as 0 */
    const double *mode;    /* mode k's value (0 or 1) of EXPR_SELECT; NULL reads
                              as NaN: no branch is a guess */
} ExprEnv;
double expr_eval(ExprPool *P, ExprId e, const ExprEnv *env);
void expr_eval_many(ExprPool *P, int n, const ExprId *roots,
                    const ExprEnv *env, double *out);
/* Node e alone: an operator from its operands' values (operand[0] is
 * a's, operand[1] b's; NULL for a leaf), a leaf from env.  The arithmetic
 * of expr_eval, one node at a time, for an evaluator that keeps its own
 * values (lower_eval). */
double expr_eval_node(const ExprPool *P, ExprId e, const double *operand, const ExprEnv *env);

/* e evaluated in long double at n environments, each value with a bound
 * on its rounding error: |value - exact| <= err to first order (Higham's
 * running error analysis; library functions within a few ulps), and the
 * magnitude of the terms it is made of (|x| + |y| for x + y, |x| |y| for
 * x y), the scale against which a value that cancels is small.  err is
 * INFINITY where the bound cannot be trusted: a sign or a branch cut
 * within the error of its operand, a value that is not finite. */
typedef struct ExprBound {
    long double value, err, mag;
} ExprBound;
void expr_eval_bound(ExprPool *P, ExprId e, int n, const ExprEnv *env, ExprBound *out);

/* Replace leaves from[i] by to[i] everywhere in e (memoized per call). */
ExprId expr_subst(ExprPool *P, ExprId e, int n, const ExprId *from,
                  const ExprId *to);

/* The same for n roots at once, in one pass: out[i] for roots[i] (out
 * may be roots). */
void expr_subst_many(ExprPool *P, int nroots, const ExprId *roots, int n,
                     const ExprId *from, const ExprId *to, ExprId *out);

/* The magnitude of each root's terms, as an expression: every sum and
 * difference made a sum of its operands' magnitudes, a product the
 * product of theirs, a quotient over the divisor's |value|, a leaf or a
 * function's value its absolute value.  What the rounding of the root's
 * evaluation is relative to (a residual that should be 0 measured
 * against it), where the root's own value may be 0. */
void expr_magnitude_many(ExprPool *P, int nroots, const ExprId *roots, ExprId *out);

/* Operation counts of the nodes reachable from roots, each shared node
 * counted once (as straight-line code would compute it). */
typedef struct ExprCount {
    long adds, muls, divs, calls;
} ExprCount;
ExprCount expr_count_ops(ExprPool *P, int n, const ExprId *roots);
/* Operation counts of exactly the n given nodes (no traversal). */
ExprCount expr_count_list(ExprPool *P, size_t n, const ExprId *nodes);

/* Mark the nodes reachable from roots: mark[id] = 1.  mark has
 * expr_pool_size(P) entries and is not cleared first. */
void expr_mark(ExprPool *P, int n, const ExprId *roots, unsigned char *mark);

#endif
