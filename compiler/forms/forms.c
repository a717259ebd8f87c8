/*
 * forms: the table of forms.
 */
#include "forms.h"

#include <stdio.h>
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
    static char names[256]; /* written once, from the table */
    if (!names[0])
        for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
            size_t at = strlen(names);
            snprintf(names + at, sizeof names - at, "%s%s", i ? ", " : "", all[i]->name);
        }
    return names;
}
