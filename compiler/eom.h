/*
 * eom: from a form's residual E(t, q, q', q'') to what the runtime needs:
 * the mass matrix M = dE/dq'', the bias h = E(q'' = 0) and the partial
 * derivatives of E for implicit steppers.  Reverse mode gives each row in
 * one sweep.
 */
#ifndef EOMC_EOM_H
#define EOMC_EOM_H

#include "forms/forms.h"

typedef struct Eom {
    int n, nu;
    const Form *form;
    ExprId *E;    /* [n] residual */
    ExprId *M;    /* [n*n] row-major; M[j*n+i] is M[i*n+j] (symmetric) */
    ExprId *h;    /* [n] */
    ExprId *dEdq, *dEdv; /* [n*n] */
    ExprId *dEdu; /* [n*nu] */
    ExprId *dEdt; /* [n] */
} Eom;

/* NULL with *why set if the form does not apply to the model. */
Eom *eom_derive(const Spec *s, const Mech *m, const Form *f, Arena *A,
                ExprPool *P, Diff *D, const char **why);

#endif
