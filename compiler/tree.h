/*
 * tree: a spec's masses as a tree of rigid bodies on turning joints, for
 * the recursive forms (forms/newton_euler.c, forms/articulated.c).
 *
 * It applies when every coordinate is the angle of one turn of a frame,
 * every mass (a body placed by a frame with its centre at a point, or a
 * particle at a point) hangs from the world through offsets fixed in the
 * frames above it, and all the masses a frame turns are turned about one
 * point, its pivot.  A turn then moves everything below it as one rigid
 * body, and the turns are the joints of Featherstone's algorithms.
 *
 * Each turn has its own coordinates: origin at its frame's pivot, axes
 * those of its frame just after it.  Its axis is a constant there, and it
 * sits in the turn above it by a rotation (a constant one, from fixed
 * turns and frames between, times its own Rodrigues matrix) and a
 * constant offset; each frame's masses are constants in the coordinates
 * of the turn that carries them.  So the recursions' transforms are
 * products with few entries that are not constants, which fold.
 */
#ifndef EOMC_TREE_H
#define EOMC_TREE_H

#include "spec.h"
#include "diff.h"

typedef struct TreeTurn {
    int coord;   /* its angle is coordinate coord */
    int up;      /* the turn above it: its parent body; -1 the world */
    ExprId al[3]; /* the axis in its own axes */
    ExprId angle; /* the angle it turns by (a function of its coordinate) */
    ExprId Qf[9]; /* the axes just before it in up's (a constant) */
    ExprId Q[9]; /* its axes in up's: Qf Rk(angle) (row-major, columns the axes) */
    ExprId r[3]; /* its origin from up's, in up's axes */
} TreeTurn;

typedef struct TreeFrame {
    int parent;        /* index among the tree's frames; -1: the world */
    int first, nturns; /* its turns: turn[first .. first + nturns - 1] */
    /* The turn that carries the masses placed in this frame (the last
     * turn at or above it; -1: none, they do not move), and their spatial
     * inertia about its origin in its axes: mass m, first moment h = m c,
     * and the rotational inertia I (3 x 3 row-major, symmetric). */
    int carrier;
    ExprId m, h[3], I[9];
} TreeFrame;

typedef struct Tree {
    int nframes, nturns;
    TreeFrame *frame; /* parents before children */
    TreeTurn *turn;   /* in frame order, each frame's in turning order */
} Tree;

/* The tree, or NULL with *why set to the reason it does not apply.  q1
 * are the velocity leaves q_i'. */
Tree *tree_build(const Spec *s, const ExprId *q1, Arena *A, ExprPool *P, Diff *D,
                 const char **why);

#endif
