/*
 * monomial: products written again as monomials, a factor constant in t
 * times powers of bases, for a program whose cost is one call per
 * operation and order (Taylor's series).  A potential's force comes out
 * of differentiation as (mu/r)/r * (0.5/r) * 2 x with r = sqrt(s); as a
 * monomial it is mu x s^(-3/2): one power of the shared sum s (one
 * recurrence, eomc_tay_powc) and one product, where the other is a root,
 * three quotients and three products.  Only the nodes the roots reach are
 * written again; the pool keeps the originals, so the other functions'
 * code is unchanged.
 */
#ifndef EOMC_MONOMIAL_H
#define EOMC_MONOMIAL_H

#include "expr.h"

typedef struct Monomials Monomials;

/* A rewriter on P: a node is constant when it depends on none of the
 * DEP_ bits in varying (for Taylor's series: t, q and its rates, the
 * seeds and the multipliers; parameters and inputs held are constant),
 * and such a node is kept whole, a factor of the monomial's constant. */
Monomials *mono_new(ExprPool *P, unsigned varying);
void mono_free(Monomials *mo);
/* e written again; e itself where nothing changes.  Memoized: a node
 * shared by several roots is written once. */
ExprId mono_rewrite(Monomials *mo, ExprId e);
/* The roots and real powers below e (counted once each path, up to 254):
 * a rewrite that merges roots into powers has fewer than its original. */
int mono_real_powers(Monomials *mo, ExprId e);

#endif
