/*
 * tree: a spec's masses as a tree of rigid bodies on turning joints, for
 * the recursive form (forms/newton_euler.c).
 *
 * It applies when every coordinate is the angle of one turn of a frame,
 * every mass (a body placed by a frame with its centre at a point, or a
 * particle at a point) hangs from the world through offsets fixed in the
 * frames above it, and all the masses a frame turns are turned about one
 * point, its pivot.  A turn then moves everything below it as one rigid
 * body: its spatial axis S = (a, p x a) (world components, about the
 * world origin; a the turn's unit axis, p the pivot) is the same for all
 * of them, and the mass matrix is sum S_i^T Ic S_j with Ic the inertia of
 * the masses both turns move (Featherstone's composite-rigid-body
 * algorithm).
 */
#ifndef EOMC_TREE_H
#define EOMC_TREE_H

#include "spec.h"
#include "diff.h"

/* Each turn also has its own coordinates, for the articulated-body form:
 * origin at its frame's pivot, axes those of its frame just after it
 * (turn by turn, the local frames of Featherstone's algorithm).  The axis
 * is then a constant, and each turn is placed in the one above it by a
 * rotation that is a constant times its own Rodrigues matrix and a
 * constant offset. */
typedef struct TreeTurn {
    int coord;   /* its angle is coordinate coord */
    ExprId a[3]; /* unit axis, world components */
    int up;      /* the turn above it: its parent body; -1 the world */
    ExprId al[3]; /* the axis in its own axes */
    ExprId Q[9]; /* its axes in up's (row-major, columns the axes) */
    ExprId r[3]; /* its origin from up's, in up's axes */
} TreeTurn;

typedef struct TreeFrame {
    int parent;        /* index among the tree's frames; -1: the world */
    int first, nturns; /* its turns: turn[first .. first + nturns - 1] */
    ExprId pivot[3];   /* the point its turns turn about, world components */
    /* The spatial inertia, about the world origin, of the masses placed
     * in this frame: mass m, first moment h = m c, and the rotational
     * inertia I (3 x 3 row-major, symmetric) about the origin. */
    ExprId m, h[3], I[9];
    /* The same masses in local coordinates: about the origin of the turn
     * that carries them (the last turn at or above the frame; -1: none,
     * they do not move), in its axes. */
    int carrier;
    ExprId hl[3], Il[9];
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
