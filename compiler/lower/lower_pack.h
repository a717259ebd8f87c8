/*
 * lower_pack: the written-out series' lines in packs (lowered.h's
 * LowSerLine.pack): where lines of one shape write consecutive cells from
 * consecutive (or the same) cells, the emitter prints them as one line
 * on vectors of two or four doubles, each lane the same arithmetic.
 */
#ifndef EOMC_LOWER_PACK_H
#define EOMC_LOWER_PACK_H

#include "lowered.h"

/* The column of each of ty's slots in an order's row of cells (col[s],
 * [nslot], a permutation), chosen so that the slots that lines of one
 * shape write and read lie side by side: the N-body's 21 pairs' r^2, or
 * x's and y's products with r^-3.  The state's slots keep their own
 * (their cells are the caller's X).  lower_series calls it where M is
 * constant and diagonal (no solve, whose cells must stay as they are). */
void pack_columns(const LowTaylor *ty, int *col);

/* Where a cell lives, for pack_lines: the state's slots' (place[col] >= 0)
 * in the caller's X at j N + place, the others in W. */
typedef struct PackCells {
    const int *place; /* [nslot] by column: the state's index, or -1 */
    int nslot, N, ncell;
} PackCells;

/* Order one order's lines line[0 .. n-1] again, every line still after
 * those that write what it reads, so that lines of one shape that could
 * run together stand together, by their cells; then mark the packs
 * (LowSerLine.pack).  Only for a series whose every cell is written once
 * (no solve); writer: [ncell] scratch, all -1, left so. */
void pack_lines(LowSerLine *line, int n, const LowSerTerm *term, const PackCells *pc,
                int *writer);

#endif
