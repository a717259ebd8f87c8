/*
 * tree: a spec's masses as a tree of rigid bodies on turning and sliding
 * joints, for the recursive forms (forms/newton_euler.c,
 * forms/articulated.c).
 *
 * It applies when every coordinate is the angle of one turn of a frame,
 * one of the Euler parameters of a turn by a quaternion (a ball joint), or
 * the length of one slide (a point offset c + d q in its frame), every
 * mass (a body placed by a frame with its centre at a point, or a particle
 * at a point) hangs from the world through such offsets in the frames
 * above it, and all the masses a frame turns are turned about one point,
 * its pivot.  A joint then moves everything after it as one rigid body,
 * and the joints are those of Featherstone's algorithms.  Kinetic-energy
 * terms of the spec's own are allowed where each moves with one joint's
 * rates (a rotor's inertia): the forms add them in the joint's block.
 *
 * Each joint has its own coordinates, where its axis is a constant, and
 * sits in the joint above it by a rotation (a constant one, from fixed
 * turns and frames between, times a turn's own Rodrigues matrix) and an
 * offset (constant, or for a slide affine in its length); the masses each
 * joint carries are constants in its coordinates.  So the recursions'
 * transforms are products with few entries that are not constants, which
 * fold.
 */
#ifndef EOMC_TREE_H
#define EOMC_TREE_H

#include "spec/spec.h"
#include "expr/diff.h"

/* A joint: a turn of a frame by a coordinate, or a link that slides by
 * one (its offset c + d q in its frame's axes).  Its own coordinates:
 * origin at its frame's pivot (a turn) or the link's end (a slide), axes
 * those of its frame just after the turn (a slide: its frame's). */
typedef struct TreeTurn {
    int coord;    /* its angle or length is coordinate coord (-1: a ball) */
    /* Its velocity slots qc (mech.h; the coordinates' rates without
     * speeds).  A ball joint (a turn by a quaternion) has four, its Euler
     * parameters' rates, or three, its speeds (`speeds:`: the angular
     * velocity in its own axes), no single axis (al zero, angle
     * EXPR_NONE), and its own angular velocity, in its own axes, is
     * sum_d Sw[d] qc[d]' (2 L e', kin_turn_quaternion; the unit axes for
     * speeds).  ndof = 1 for every other joint (qc[0] the slot of coord). */
    int ndof, qc[4];
    ExprId Sw[4][3];
    int up;       /* the joint above it: its parent body; -1 the world */
    int slide;    /* 1: a slide along al; 0: a turn about al */
    ExprId al[3]; /* the axis or direction in its own axes (a constant) */
    ExprId angle; /* a turn's angle (a function of its coordinate); EXPR_NONE */
    ExprId Qf[9]; /* the axes just before it in up's (a constant) */
    ExprId Q[9];  /* its axes in up's: Qf Rk(angle) for a turn, Qf for a slide
                   * (row-major, columns the axes) */
    ExprId r[3];  /* its origin from up's, in up's axes (constant for a turn,
                   * c + d q for a slide) */
    /* The masses it carries last (whose chain of joints ends with it):
     * mass m, first moment h = m c and rotational inertia I (3 x 3
     * row-major, symmetric) about its origin, in its axes. */
    ExprId m, h[3], I[9];
} TreeTurn;

typedef struct Tree {
    int nturns;
    TreeTurn *turn; /* parents before children */
} Tree;

/* The tree, or NULL with *why set to the reason it does not apply.  q1
 * are the velocity slots' leaves (mech.h); kin[0..nkin) the kinetic-energy terms no
 * mass carries, each of which must move with one joint's rates. */
Tree *tree_build(const Spec *s, const ExprId *q1, int nkin, const ExprId *kin, Arena *A,
                 ExprPool *P, Diff *D, const char **why);

#endif
