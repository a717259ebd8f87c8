/*
 * place: forward kinematics for a caller (eomc.h's eomc_sim_place): the
 * pose of a body, particle, frame or point by name, and its velocity
 * Jacobian, from the model's generated places and place_velocity.
 */
#include "simimpl.h"

#include <stdlib.h>
#include <string.h>

/* The velocity and angular velocity take 6 entries a place. */
enum { PLACE_VEL = 6 };

/* Whether item it has axes: a body's or frame's whose orientation the
 * model gives. */
static int
has_axes(const eomc_draw_item *it)
{
    return (it->kind == EOMC_DRAW_BODY || it->kind == EOMC_DRAW_FRAME) && !it->unturned;
}

int
eomc_model_place(const eomc_model *m, const char *name, int *axes)
{
    for (int k = 0; k < m->nplace; k++)
        if (!strcmp(m->places[k].name, name)) {
            if (axes)
                *axes = has_axes(&m->places[k]);
            return k;
        }
    return -1;
}

/* Whether place k is one, and has axes if asked for them (EOMC_OK), else
 * the usage error saying why not. */
static int
place_check(eomc_sim *s, int k, int axes)
{
    const eomc_model *m = eomc_sim_model(s);
    if (k < 0 || k >= m->nplace)
        return sim_usage_error(s, "place %d: %s has %d places (bodies, particles, frames "
                               "and points)", k, m->name, m->nplace);
    const eomc_draw_item *it = &m->places[k];
    if (!axes || has_axes(it))
        return EOMC_OK;
    if (it->kind == EOMC_DRAW_PARTICLE || it->kind == EOMC_DRAW_POINT)
        return sim_usage_error(s, "'%s' is a %s: it has a position and a velocity, no axes",
                               it->name, it->kind == EOMC_DRAW_POINT ? "point" : "particle");
    return sim_usage_error(s, "'%s': %s gives no orientation of it (a body turned by "
                           "`omega:` alone, or a frame turned by an input)", it->name, m->name);
}

int
eomc_sim_place(eomc_sim *s, int k, double t, const double *q, double *pos, double *R)
{
    int rc = place_check(s, k, R != NULL);
    if (rc != EOMC_OK)
        return rc;
    const eomc_model *m = eomc_sim_model(s);
    double *X = malloc((size_t)EOMC_POSE * m->nplace * sizeof *X);
    if (!X)
        return sim_usage_error(s, "out of memory for the places");
    m->place(t, q, eomc_sim_params(s), sim_inputs_at(s, t, NULL, NULL), X);
    const double *x = X + (size_t)EOMC_POSE * k;
    if (pos)
        memcpy(pos, x, 3 * sizeof *pos);
    if (R)
        memcpy(R, x + 3, 9 * sizeof *R);
    rc = sim_all_finite(x, EOMC_POSE) ? EOMC_OK
                                      : sim_numeric_error(s, t, q, NULL, "the pose of '%s' "
                                                          "is not finite", m->places[k].name);
    free(X);
    return rc;
}

int
eomc_sim_place_jacobian(eomc_sim *s, int k, double t, const double *q, double *Jv, double *Jw)
{
    int rc = place_check(s, k, Jw != NULL);
    if (rc != EOMC_OK)
        return rc;
    const eomc_model *m = eomc_sim_model(s);
    int nv = eomc_nv(m);
    double *W = malloc((size_t)PLACE_VEL * m->nplace * sizeof *W);
    double *dv = calloc((size_t)nv + 1, sizeof *dv);
    if (!W || !dv) {
        free(W);
        free(dv);
        return sim_usage_error(s, "out of memory for the places");
    }
    const double *p = eomc_sim_params(s), *u = sim_inputs_at(s, t, NULL, NULL);
    /* place_velocity is linear in dv: its value at the j-th unit speed is
     * the j-th column, exactly */
    for (int j = 0; j < nv && rc == EOMC_OK; j++) {
        dv[j] = 1;
        m->place_velocity(t, q, p, u, dv, W);
        dv[j] = 0;
        const double *w = W + (size_t)PLACE_VEL * k;
        if (!sim_all_finite(w, PLACE_VEL))
            rc = sim_numeric_error(s, t, q, NULL, "the velocity Jacobian of '%s' is not "
                                   "finite", m->places[k].name);
        for (int i = 0; i < 3; i++) {
            if (Jv)
                Jv[(size_t)i * nv + j] = w[i];
            if (Jw)
                Jw[(size_t)i * nv + j] = w[3 + i];
        }
    }
    free(W);
    free(dv);
    return rc;
}
