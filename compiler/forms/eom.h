/*
 * eom: from a form's residual E(t, q, q', q'') to what the runtime needs:
 * the mass matrix M = dE/dq'', the bias h = E(q'' = 0) and the partial
 * derivatives of E for implicit steppers.  Reverse mode gives each row in
 * one sweep.
 */
#ifndef EOMC_EOM_H
#define EOMC_EOM_H

#include "forms.h"

typedef struct Eom {
    int n, nu;    /* velocity slots (mech.h), inputs */
    int nq;       /* coordinates: dEdq's columns */
    const Form *form;
    ExprId *E;    /* [n] residual */
    ExprId *M;    /* [n*n] row-major; M[j*n+i] is M[i*n+j] (symmetric);
                   * NULL until eom_mass where the form solves for q'' */
    ExprId *h;    /* [n] */
    ExprId *dEdq, *dEdv; /* [n*nq], [n*n]; NULL until eom_derive_jacobian */
    ExprId *dEdu; /* [n*nu] */
    ExprId *dEdt; /* [n] */
    /* The same partials as directional derivatives: jvp_q[i] = sum_j
     * dE_i/dq_j dq_j and jvp_v[i] = sum_j dE_i/dv_j dv_j over the seeds
     * expr_seed(j, 0) = dq_j (j < nq) and expr_seed(j, 1) = dv_j (j < n).  About the size
     * of E itself, where dEdq and dEdv grow as n |E|: the emitter prints
     * these and loops over unit seeds when the unrolled matrices would be
     * too much code. */
    ExprId *jvp_q, *jvp_v; /* [n] */
    /* a = -M^-1 h by an unrolled LDL^T factorization built in the DAG
     * (structural zeros of M drop out by simplification), its pivots d_k
     * and M's diagonal M_kk: M is safely positive definite when every
     * d_k > EOMC_PIVOT_TOL M_kk, and min d_k / M_kk measures how nearly
     * singular it is.  NULL when n > EOM_SOLVE_MAX and M is too dense
     * (EOM_SPARSE_SOLVE_MAX), unless the form has a solve of its own
     * (forms.h). */
    ExprId *acc, *piv, *mkk;
    /* Where acc is NULL: M's tree of structural nonzeros (eomc_model.h's
     * mass_parent), or NULL when M is not so sparse (or not derived: a
     * recursive solve). */
    int *mass_parent;
    /* Where the form solves for q'' itself: minv = M^-1 x for the load x
     * given as the seeds expr_seed(j, 2), by the same recursion (a
     * constrained tree's M^-1 B^T, a row of B at a time); NULL until
     * eom_minv. */
    ExprId *minv;
    /* derive_solve's factors, in its order ldl_ord [n]: L [n*n] (unit
     * lower triangle) and the pivots' reciprocals ldl_inv [n]; NULL where
     * acc is the form's own solve or there is none.  ldl_loads: minv may
     * take them (no unit quaternion without speeds, whose row only the
     * articulated recursion is known to meet by itself: lower.c). */
    ExprId *ldl_L, *ldl_inv;
    int *ldl_ord;
    int ldl_loads;
} Eom;

/* Up to this many coordinates the solve is emitted as straight-line code
 * (measured: GSL's Cholesky takes 370 ns at n = 5, the whole budget of a
 * right-hand side three times over; the 20-link chain's right-hand side
 * 2.9 us with the runtime's LDL^T, 1.5 us unrolled, for 1.6 s more of
 * cc -O2).  Must match eomc_model.h. */
enum { EOM_SOLVE_MAX = 24 };
/* Past it, still when M's structural zeros leave the unrolled solve no
 * more multiplications than a dense one of EOM_SOLVE_MAX coordinates
 * (24^3/6 for the factorization, 3 * 24^2/2 for the pivots and solves),
 * so that the code costs the compiler no more: a tree's M factored leaves
 * first, which has no fill-in (Featherstone's LTDL, the sparsity its
 * branches give; gen_tree 9, 27 coordinates, 3 106). */
enum { EOM_SPARSE_SOLVE_MAX = 24 * 24 * 24 / 6 + 3 * 24 * 24 / 2 };

/* An operation of the runtime's dense LDL^T against one of generated
 * straight-line code (measured, bench/tree_bench.sh, gen_tree 5: 15
 * coordinates, Newton-Euler's M and h 3 831 operations and the factorized
 * solve 4.3 us, against 2.9 us for the articulated-body solve's ~6 800
 * operations: about 0.43 ns per straight-line operation, 2.4 ns per one
 * of the factorization's 1 575). */
enum { EOM_DENSE_WEIGHT = 5 };

/* Straight-line code past this many operations is too much for the C
 * compiler (measured on the chain benchmark, gcc 12 -O2: ~0.3 ms per
 * operation up to here, faster growth beyond): the Jacobian is seeded
 * past it (lower.h). */
enum { EOM_STRAIGHT_LINE_MAX = 20000 };

/* E, M, h and the solve, or NULL with *why set if the form does not
 * apply to the model.  The partial derivatives are left NULL: most of the
 * work, and only the Jacobian needs them. */
Eom *eom_derive(const Spec *s, const Mech *m, const Form *f, Arena *A,
                ExprPool *P, Diff *D, const char **why);
/* What one right-hand side of e costs, in operations, with nc
 * constraints (0: none), which the runtime may solve by unit loads
 * (loads: every one affine in q'', with multipliers):
 * - unconstrained, where e solves for q'': its solve;
 * - constrained so, where e solves: its solve without the constraints,
 *   nc passes of minv (M^-1 B^T) and the nc x nc system B M^-1 B^T;
 * - else M and h, plus the dense factorization the runtime then does:
 *   LDL^T of M (n^3/3 + 2 n^2) or LU of the KKT matrix ((n + nc)^3 / 3
 *   + 2 (n + nc)^2), each operation weighed as EOM_DENSE_WEIGHT
 *   straight-line ones.
 * The constraints' own functions cost the same whatever the form, so they
 * are left out. */
long eom_cost(Eom *e, const Mech *m, int nc, int loads, Arena *A, ExprPool *P, Diff *D);
/* Can a constrained e be solved by unit loads: does it have a solve for
 * q'' (the form's recursion, or the unrolled LDL^T whose factors minv
 * reuses)? */
int eom_loads(const Eom *e);
/* e->minv, derived on first use (NULL where eom_loads is 0). */
ExprId *eom_minv(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D);
/* e->M, derived on first use where the form solves for q'' itself (its
 * recursion never forms M; constraints and the cost of a constrained
 * model need it). */
ExprId *eom_mass(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D);
/* The default form's E, M, h and solve: the cheapest of those that apply
 * (eom.c says how they are weighed), or NULL if none does; the reason, with
 * what the others cost, in why[len].  series: Taylor's series are asked
 * for (a run by Taylor's method), so the cheapest form that can have them
 * (one that writes M's entries) where one applies. */
Eom *eom_derive_cheapest(const Spec *s, const Mech *m, int nc, int loads, int series,
                         Arena *A, ExprPool *P, Diff *D, char *why, size_t len);
/* dEdq, dEdv, dEdu, dEdt, jvp_q and jvp_v of e (again: nothing). */
void eom_derive_jacobian(Eom *e, const Mech *m, Arena *A, ExprPool *P, Diff *D);

#endif
