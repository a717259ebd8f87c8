/*
 * repeat: a lowered function whose outputs fall into identical copies of
 * one subtree (22 humanoids, a hundred free bodies) becomes one copy's
 * code and a loop over the copies.
 *
 * The copies are found in the expressions themselves, not in the spec:
 * outputs are grouped by the coordinates and inputs they depend on
 * (union-find over the DAG), a group is a copy of the first of its size
 * when it is that group's expressions with its coordinates and inputs
 * renamed (the renaming rebuilt by expr_subst_many and compared by node
 * id: hash-consing makes equal expressions one node), its coordinates and
 * inputs a contiguous run at a constant offset from the first's.  What is
 * verified equal runs as the first copy's code with its arrays shifted
 * (LowFunc.copy); nothing else changes.
 */
#ifndef EOMC_REPEAT_H
#define EOMC_REPEAT_H

#include "lowered.h"

/* Below this many operations that the loop saves (the copies' code but
 * the first's), a function stays straight-line: a small model's C stays
 * what it was, and a call per copy costs more than it saves. */
enum { REPEAT_MIN_SAVED = 20000 };

/* Split f into f->copy and a loop where it repeats (n coordinates, nu
 * inputs) and the loop saves at least min_saved operations
 * (REPEAT_MIN_SAVED; tests ask 0); f unchanged otherwise.  1 if it
 * split. */
int repeat_split(LowFunc *f, int n, int nu, long min_saved, Arena *A, ExprPool *P);
/* The same for a model whose speeds are not its coordinates' rates (nq
 * coordinates, nv velocity slots, lowered.h's vslot and vcoord): a copy's
 * coordinates shift by LowFunc.dq, its speeds and its outputs (indexed by
 * slot) by LowFunc.dv. */
int repeat_split_speeds(LowFunc *f, int nq, int nv, const int *vslot, const int *vcoord, int nu,
                        long min_saved, Arena *A, ExprPool *P);

#endif
