/*
 * state: the state's layout, its names and its unit quaternions (state.h).
 *
 * A model whose speeds are its coordinates' rates (nv = 0) names its
 * speeds after them, "x'", and their rates "x''", as it always has.  One
 * with speeds of its own (a free joint's angular velocity in its body's
 * axes) names them by v_names and their rates by one more quote,
 * "root_wx'".  Its unit quaternions are kept at length 1 by the steps:
 * q' = W(q) v keeps |e| constant exactly, and the integration's errors
 * move it by about the tolerance a step, which renormalizing takes back
 * (the exact motion has |e| = 1, so that is no approximation of it).
 */
#include "state.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* A quaternion whose length is within this many units of rounding of 1
 * is one already: dividing it by its length would only move its last
 * bits (so that a state renormalized once, or written by hand to the
 * digits, is kept to the bit by a second renormalization). */
#define UNIT_ROUNDING 4

const char *
state_name(const eomc_model *m, int k, char *buf, size_t len)
{
    if (k < m->nq)
        snprintf(buf, len, "%s", m->q_names[k]);
    else
        state_speed(m, k - m->nq, buf, len);
    return buf;
}

/* Speed k's name with `primes` more primes: v_names[k], or the
 * coordinate's with one prime more where the speeds are the rates. */
static const char *
speed_primed(const eomc_model *m, int k, const char *primes, char *buf, size_t len)
{
    if (m->nv > 0)
        snprintf(buf, len, "%s%s", m->v_names[k], primes);
    else
        snprintf(buf, len, "%s'%s", m->q_names[k], primes);
    return buf;
}

const char *
state_speed(const eomc_model *m, int k, char *buf, size_t len)
{
    return speed_primed(m, k, "", buf, len);
}

const char *
state_rate(const eomc_model *m, int k, char *buf, size_t len)
{
    return speed_primed(m, k, "'", buf, len);
}

const char *
state_own_speed(const eomc_model *m)
{
    for (int k = 0; k < m->nv; k++) {
        size_t len = strlen(m->v_names[k]);
        if (len == 0 || m->v_names[k][len - 1] != '\'')
            return m->v_names[k];
    }
    return m->nv > 0 ? m->v_names[0] : "";
}

const char *
state_speed_word(const eomc_model *m, int plural)
{
    if (m->nv > 0)
        return plural ? "speeds" : "speed";
    return plural ? "velocities" : "velocity";
}

int
state_find(const eomc_model *m, const char *name, int *rate)
{
    char buf[STATE_NAME_MAX];
    int nx = eomc_nx(m);
    if (rate)
        *rate = 0;
    for (int k = 0; k < nx; k++)
        if (!strcmp(name, state_name(m, k, buf, sizeof buf)))
            return k;
    for (int k = 0; k < eomc_nv(m); k++)
        if (!strcmp(name, state_rate(m, k, buf, sizeof buf))) {
            if (rate)
                *rate = 1;
            return m->nq + k;
        }
    return -1;
}

void
state_qdot(const eomc_model *m, const double *q, const double *v, double *qd)
{
    if (m->nv > 0)
        m->qdot(q, v, qd);
    else
        memcpy(qd, v, (size_t)m->nq * sizeof *qd);
}

double
state_quat_norm(const eomc_model *m, const double *q, int j)
{
    const int *e = m->quat + 4 * j;
    return sqrt(q[e[0]] * q[e[0]] + q[e[1]] * q[e[1]] + q[e[2]] * q[e[2]] +
                q[e[3]] * q[e[3]]);
}

double
state_normalize_quat(const eomc_model *m, double *q, int j)
{
    const int *e = m->quat + 4 * j;
    double len = state_quat_norm(m, q, j);
    if (!(len > 0) || !isfinite(len))
        return 0;
    double d = fabs(len - 1);
    for (int i = 0; i < 4 && d > UNIT_ROUNDING * DBL_EPSILON; i++)
        q[e[i]] /= len;
    return d;
}

double
state_normalize(const eomc_model *m, double *q, int *which)
{
    double worst = 0;
    if (which)
        *which = -1;
    for (int j = 0; j < m->nquat; j++) {
        double d = state_normalize_quat(m, q, j);
        if (which && (*which < 0 || d > worst))
            *which = j;
        worst = fmax(worst, d);
    }
    return worst;
}

eomc_ext
state_normalize_ext(const eomc_model *m, eomc_ext *q)
{
    eomc_ext worst = 0;
    for (int j = 0; j < m->nquat; j++) {
        const int *e = m->quat + 4 * j;
        eomc_ext len = sqrtl(q[e[0]] * q[e[0]] + q[e[1]] * q[e[1]] + q[e[2]] * q[e[2]] +
                             q[e[3]] * q[e[3]]);
        if (!(len > 0) || !isfinite(len))
            continue;
        worst = fmaxl(worst, fabsl(len - 1));
        for (int i = 0; i < 4 && fabsl(len - 1) > UNIT_ROUNDING * LDBL_EPSILON; i++)
            q[e[i]] /= len;
    }
    return worst;
}
