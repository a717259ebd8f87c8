/*
 * info: a model's sizes and names by kind, for a caller that cannot read
 * eomc_model's layout, which changes with EOMC_ABI_VERSION: the Python
 * package, through ctypes.  Three functions instead of a mirror of the
 * struct in Python, so the package follows the runtime it loads.
 */
#include "eomc.h"

#include <string.h>

/* The count and names of one kind, or 0 for an unknown kind. */
static int
kind_of(const eomc_model *m, const char *kind, int *n, const char *const **names)
{
    static const char *const kinds[] = {"q", "p", "u", "c", "out", "event", "v"};
    int k = 0;
    while (k < 7 && strcmp(kinds[k], kind))
        k++;
    switch (k) {
    case 0: *n = m->nq, *names = m->q_names; return 1;
    case 1: *n = m->np, *names = m->p_names; return 1;
    case 2: *n = m->nu, *names = m->u_names; return 1;
    case 3: *n = m->nc, *names = m->c_names; return 1;
    case 4: *n = m->nout, *names = m->out_names; return 1;
    case 5: *n = m->nevent, *names = m->ev_names; return 1;
    /* the speeds' own names: none when they are the rates, named q' */
    case 6: *n = m->nv, *names = m->v_names; return 1;
    default: return 0;
    }
}

int
eomc_model_count(const eomc_model *m, const char *kind)
{
    int n;
    const char *const *names;
    if (!strcmp(kind, "place")) /* (a table of items, not of names) */
        return m->nplace;
    return kind_of(m, kind, &n, &names) ? n : -1;
}

const char *
eomc_model_name(const eomc_model *m, const char *kind, int k)
{
    int n;
    const char *const *names;
    if (!strcmp(kind, "place"))
        return k >= 0 && k < m->nplace ? m->places[k].name : NULL;
    return kind_of(m, kind, &n, &names) && k >= 0 && k < n ? names[k] : NULL;
}

const char *
eomc_model_text(const eomc_model *m, const char *what)
{
    return !strcmp(what, "name")     ? m->name
           : !strcmp(what, "spec")   ? m->spec
           : !strcmp(what, "form")   ? m->form
           : !strcmp(what, "scene")  ? m->scene
           : !strcmp(what, "method") ? m->method
           : !strcmp(what, "invariant") ? m->invariant_name
                                     : NULL;
}
