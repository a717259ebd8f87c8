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
#include <stdlib.h>
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

const char *
state_switch_name(const eomc_model *m, int k, char *buf, size_t len)
{
    if (m->sw_names && m->sw_names[k])
        snprintf(buf, len, "%s", m->sw_names[k]);
    else /* (a model written by hand may name none) */
        snprintf(buf, len, "switch %d", k);
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

/* Where coordinate i is one of a unit quaternion's: that quaternion's
 * index, its parameter's place (0 for e0 ...) into *r; else -1. */
static int
quat_of(const eomc_model *m, int i, int *r)
{
    for (int j = 0; j < m->nquat; j++)
        for (int c = 0; c < 4; c++)
            if (m->quat[4 * j + c] == i) {
                *r = c;
                return j;
            }
    return -1;
}

/* Speed k's column of W: q' of the speed alone, at the unit quaternions
 * 1 and the other coordinates 0.  There e' = 1/2 (0, w), so the speed
 * that turns about axis a moves e_{a+1} alone, by 1/2 (exactly, in
 * binary), and a coordinate's rate moves that coordinate alone, by 1. */
int
state_tangent(const eomc_model *m, int *slot)
{
    int nq = m->nq, nv = m->nv, rc = 0;
    if (nv == 0) {
        for (int k = 0; k < nq; k++)
            slot[k] = k;
        return 0;
    }
    double *q = calloc((size_t)(2 * nq + nv), sizeof *q);
    unsigned char *taken = calloc((size_t)nq * 3 + 1, 1);
    if (!q || !taken) {
        free(q);
        free(taken);
        return -1;
    }
    double *qd = q + nq, *v = qd + nq;
    for (int j = 0; j < m->nquat; j++)
        q[m->quat[4 * j]] = 1;
    for (int k = 0; k < nv && rc == 0; k++) {
        v[k] = 1;
        m->qdot(q, v, qd);
        v[k] = 0;
        int moved = -1, count = 0;
        for (int i = 0; i < nq; i++)
            if (qd[i] != 0)
                moved = i, count++;
        int r, j = moved >= 0 ? quat_of(m, moved, &r) : -1;
        if (count != 1)
            rc = -1;
        else if (j < 0 && qd[moved] == 1 && !taken[3 * moved])
            slot[k] = moved, taken[3 * moved] = 1;
        else if (j >= 0 && r > 0 && qd[moved] == 0.5 && !taken[3 * m->quat[4 * j] + r - 1])
            slot[k] = STATE_ROTATION(j, r - 1), taken[3 * m->quat[4 * j] + r - 1] = 1;
        else
            rc = -1;
    }
    free(q);
    free(taken);
    return rc;
}

const char *
state_rotation_name(const eomc_model *m, int k, char *buf, size_t len)
{
    const char *w = m->v_names[k];
    size_t n = strlen(w);
    if (n >= 2 && w[n - 2] == 'w' && strchr("xyz", w[n - 1]) && w[n - 1])
        snprintf(buf, len, "%.*sr%c", (int)(n - 2), w, w[n - 1]);
    else
        snprintf(buf, len, "rot_%s", w);
    return buf;
}
