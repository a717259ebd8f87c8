/*
 * The two ways eomc prints the jacobian member (compiler/emit.h) against
 * each other, for every shipped spec at random states: the unrolled
 * matrices (generated/NAME.c, what these small models get by default) and
 * `eomc compile --jacobian seeded`, which loops over unit seeds of the
 * directional derivative of E.  Both are exact derivatives evaluated in a
 * different order, so they agree to rounding.  The seeded files are
 * compiled with the project's warnings (-Wall -Wextra -Wpedantic -Werror)
 * and NAME_model renamed to NAME_seeded_model.
 */
#include "../unit/check.h"
#include "eomc_model.h"

#include <string.h>

#define MODELS(X) X(falling_particle) X(pendulum) X(gear_link) \
                  X(double_pendulum) X(chain5)
#define DECLARE(name) extern const eomc_model name##_model, name##_seeded_model;
MODELS(DECLARE)
#define PAIR(name) {&name##_model, &name##_seeded_model},
static const eomc_model *const pairs[][2] = {MODELS(PAIR)};

enum { NMAX = 8, UMAX = 4, PMAX = 256 };

/* The default parameters and the values derive computes from them: what
 * every model function reads (eomc_model.h). */
static const double *
params(const eomc_model *m, double *p)
{
    memcpy(p, m->p_default, (size_t)m->np * sizeof *p);
    if (m->derive)
        m->derive(p, p + m->np);
    return p;
}

static int
compare(const eomc_model *m, const eomc_model *s)
{
    int n = m->nq, nu = m->nu, ok = 1;
    double q[NMAX], v[NMAX], a[NMAX], u[UMAX + 1], J[2][4][NMAX * NMAX];
    double pm[PMAX], ps[PMAX];
    if (m->np + m->nd > PMAX || s->np + s->nd > PMAX)
        return 0;
    for (int trial = 0; trial < 20; trial++) {
        double t = check_rand(-1, 1);
        for (int i = 0; i < n; i++) {
            q[i] = check_rand(-1.5, 1.5);
            v[i] = check_rand(-1.5, 1.5);
            a[i] = check_rand(-1.5, 1.5);
        }
        for (int k = 0; k < nu; k++)
            u[k] = check_rand(-1, 1);
        memset(J, 0, sizeof J);
        m->jacobian(t, q, v, a, params(m, pm), u, J[0][0], J[0][1], J[0][2], J[0][3]);
        s->jacobian(t, q, v, a, params(s, ps), u, J[1][0], J[1][1], J[1][2], J[1][3]);
        int len[4] = {n * n, n * n, n * nu, n};
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < len[k]; i++)
                ok &= check_close(J[1][k][i], J[0][k][i], 1e-12);
    }
    return ok;
}

int
main(void)
{
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
        const eomc_model *m = pairs[k][0], *s = pairs[k][1];
        CHECK(m->nq <= NMAX && m->nu <= UMAX && compare(m, s),
              "%s: seeded jacobian = unrolled jacobian", m->name);
    }
    return check_done();
}
