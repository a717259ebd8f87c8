/*
 * forms: the table of forms and what they share.
 */
#include "forms.h"

#include <string.h>

static const Form *const all[] = {
    &form_lagrange, &form_maggi, &form_nielsen, &form_tzenoff, &form_gibbs_appell,
    &form_newton_euler, &form_articulated,
};

const Form *
form_at(int k)
{
    return k >= 0 && k < (int)(sizeof all / sizeof all[0]) ? all[k] : NULL;
}

const Form *
form_find(const char *name)
{
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (strcmp(all[i]->name, name) == 0)
            return all[i];
    return NULL;
}

const char *
form_nearest(const char *name)
{
    const char *names[sizeof all / sizeof all[0]];
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        names[i] = all[i]->name;
    return diag_nearest(name, names, (int)(sizeof all / sizeof all[0]));
}

const char *
form_names(void)
{
    return "lagrange, maggi, nielsen, tzenoff, gibbs-appell, newton-euler, articulated-body";
}

ExprId *
form_gradient(const Mech *m, ExprId f, int order, Arena *A, Diff *D)
{
    ExprId *g = arena_new_array(A, ExprId, m->n);
    diff_gradient(D, f, m->n, m->q[order], g);
    return g;
}

ExprId *
form_applied(const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    ExprId *G = form_gradient(m, m->V, 0, A, D);
    for (int i = 0; i < m->n; i++)
        G[i] = expr_sub(P, G[i], m->Q[i]);
    return G;
}
