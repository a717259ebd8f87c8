/*
 * forms: the residual forms of the equations of motion.
 *
 * Each form builds E_i(t, q, q', q'') from its own definition (never by
 * rewriting another form's result: their agreement is a test).  All are
 * affine in q''; eom.c takes M = dE/dq'' and h = E(q'' = 0) from any of
 * them.
 */
#ifndef EOMC_FORMS_H
#define EOMC_FORMS_H

#include "mechanics/mech.h"

typedef struct Form {
    const char *name;    /* --form NAME */
    const char *formula; /* the residual, for banners and --explain */
    /* Residual E[n] in A, or NULL with *why set when the form does not
     * apply to this model. */
    ExprId *(*residual)(const Mech *m, Arena *A, ExprPool *P, Diff *D,
                        const char **why);
    int eliminate;       /* constraints by elimination rather than multipliers */
    /* It takes speeds that are no coordinate's rates (a quaternion's
     * angular velocity, mech.h): its residual is a balance of forces
     * along each slot's virtual speed, not Lagrange's in coordinates. */
    int speeds;
    /* The mass matrix [n*n], when the form has a cheaper way to it than
     * dE/dq'' (equal to it); NULL: eom.c differentiates E. */
    ExprId *(*mass)(const Mech *m, Arena *A, ExprPool *P, Diff *D);
    /* The accelerations by a recursion of the form's own, for any number
     * of coordinates, without factoring M (NULL: eom.c factors M, up to
     * EOM_SOLVE_MAX coordinates).  Writes acc, piv and mkk [n] as eom.h
     * describes them.  With load [n] (else NULL), acc = M^-1 load
     * instead: at rest, no gravity, no force but the load (a constrained
     * tree's unit-load passes, M^-1 B^T a row at a time). */
    void (*solve)(const Mech *m, Arena *A, ExprPool *P, Diff *D, const ExprId *load,
                  ExprId *acc, ExprId *piv, ExprId *mkk);
} Form;

/* The articulated-body form's model as tables, for code that loops over
 * them (runtime/include/eomc_tree.h) instead of unrolling the recursion: per joint
 * five integers (up, coordinate, axis: 0-2 a coordinate axis of its own,
 * 3 a vector; whether a constant rotation precedes it; whether it slides)
 * and
 * FORM_TABLE_STRIDE numbers (expressions of the parameters), then a0[6];
 * and the generalized forces the tables leave out.  NULL with *why set
 * where it cannot be put so. */
enum { FORM_TABLE_STRIDE = 25 }; /* eomc_tree.h's EOMC_TREE_STRIDE */
enum { FORM_TABLE_INTS = 5 };    /* eomc_tree_turn's members */
typedef struct FormTables {
    int nt;
    int *turn;   /* [FORM_TABLE_INTS nt] */
    ExprId *num; /* [FORM_TABLE_STRIDE nt + 6] */
    ExprId *tau; /* [n]: Q - dV/dq but for the gravity that a0 stands for */
} FormTables;
FormTables *form_tables(const Mech *m, Arena *A, ExprPool *P, Diff *D, const char **why);

/* maggi is Lagrange's residual with the constraints eliminated (C^T E =
 * 0, f = 0); --eliminate selects elimination for the other forms. */
extern const Form form_lagrange, form_nielsen, form_tzenoff, form_gibbs_appell, form_maggi,
    form_newton_euler, form_articulated;

/* The k-th form of the table (--form's order), NULL past the last. */
const Form *form_at(int k);
/* The form called `name`, or NULL. */
const Form *form_find(const char *name);
/* Comma-separated list of the form names, for messages. */
const char *form_names(void);
/* The form a misspelt name most likely meant, or NULL. */
const char *form_nearest(const char *name);


#endif
