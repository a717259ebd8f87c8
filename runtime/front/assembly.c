/*
 * assembly: the initial state put on the constraints, or told off them
 * (assembly.h).
 */
#include "assembly.h"
#include "base/io.h"
#include "model/simimpl.h"
#include "model/state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Whether the model has a constraint below acceleration level. */
int
assembly_has_levels(const eomc_model *m)
{
    for (int k = 0; k < m->nc; k++)
        if (m->c_order[k] <= 1)
            return 1;
    return 0;
}

/* Project the initial state onto the constraints (c->held kept) and say
 * what moved. */
int
assembly_run(Options *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nx = eomc_nx(m), moved = 0;
    char name[STATE_NAME_MAX];
    /* the scene's assembly, or --assemble's */
    const char *who = c->hold || !c->scene_assembles ? "--assemble" : "the scene's assembly";
    if (!assembly_has_levels(m))
        return opt_usage(c, "--assemble: %s has no holonomic or first-order constraint to "
                     "assemble", m->name);
    if (!c->held && opt_held_marks(c, m) != EOMC_OK)
        return EOMC_EUSAGE;
    double *x0 = malloc((size_t)nx * sizeof *x0);
    if (!x0)
        return opt_usage(c, "out of memory");
    if (c->equilibrium) /* the search starts at rest */
        memset(x + n, 0, (size_t)(nx - n) * sizeof *x);
    memcpy(x0, x, (size_t)nx * sizeof *x0);
    int rc = eomc_sim_project_held(sim, c->run.t0, x, x + n, c->held);
    if (rc != EOMC_OK) {
        fprintf(io_err(), "%s: %s%s: %s\n", c->prog, rc == EOMC_EUSAGE ? "" : "error: ", who,
                eomc_sim_error(sim));
        free(x0);
        return rc;
    }
    for (int i = 0; i < nx; i++)
        if (x[i] != x0[i]) {
            if (!moved++)
                fprintf(io_err(), "%s: %s moved the initial state onto the "
                        "constraints:\n", c->prog, who);
            fprintf(io_err(), "  %s %.17g -> %.17g (%+.3g)\n",
                    state_name(m, i, name, sizeof name), x0[i], x[i], x[i] - x0[i]);
        }
    if (!moved && !c->scene_assembles)
        fprintf(io_err(), "%s: --assemble: the initial state already satisfies the "
                "constraints\n", c->prog);
    free(x0);
    return EOMC_OK;
}

/* The constraints x is off (eomc_sim_inconsistencies above
 * EOMC_INCONSISTENT), worst first, into buf: "rod (positions: its residual
 * is 0.12 of the size of its terms), ..."; returns how many. */
static int
describe_off(eomc_sim *sim, double t, const double *x, char *buf, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int nc = m->nc, off = 0;
    double *e = calloc((size_t)nc + 1, sizeof *e);
    int *level = calloc((size_t)nc + 1, sizeof *level);
    buf[0] = '\0';
    if (e && level && assembly_has_levels(m) &&
        eomc_sim_inconsistencies(sim, t, x, x + m->nq, e, level) > EOMC_INCONSISTENT) {
        for (int k = 0; k < nc; k++)
            off += e[k] > EOMC_INCONSISTENT;
        size_t at = 0;
        for (int done = 0; done < off && at < len; done++) { /* the largest left */
            int k = 0;
            for (int j = 1; j < nc; j++)
                k = e[j] > e[k] ? j : k;
            at += (size_t)snprintf(buf + at, len - at,
                                   done ? ", %s (%s: %.2g)"
                                        : "%s (%s: its residual is %.2g of the size of its "
                                          "terms)", m->c_names[k],
                                   level[k] ? "velocities" : "positions", e[k]);
            e[k] = -1;
        }
    }
    free(e);
    free(level);
    return off;
}

/* A start off the constraints is allowed (the drift then starts there),
 * but rarely meant: say so, once, before integrating, naming every
 * constraint it violates.  The test is relative to each constraint's terms
 * (eomc_sim_inconsistencies), so that it means the same in any units. */
void
assembly_check(const Options *c, eomc_sim *sim, const double *x)
{
    char list[2048];
    int off = describe_off(sim, c->run.t0, x, list, sizeof list);
    /* the constraint rows the solves use, chosen here if nothing chose
     * them yet (an eliminating model's refusal is the solve's to say) */
    if (sim_choose_rows(sim, c->run.t0, x, x + eomc_sim_model(sim)->nq) == EOMC_OK &&
        *sim_dropped_note(sim))
        fprintf(io_err(), "%s: note: constraints dependent at the start: %s; the solves "
                "leave the dependent rows out (their multipliers are 0), and the run stops "
                "if one of them no longer holds\n", c->prog, sim_dropped_note(sim));
    if (off == 1)
        fprintf(io_err(), "%s: warning: the initial state is off the constraint %s; --assemble "
                "projects the state onto the constraints\n", c->prog, list);
    else if (off > 1)
        fprintf(io_err(),
                "%s: warning: the initial state is off %d constraints, worst first: %s; "
                "--assemble projects the state onto the constraints\n", c->prog, off, list);
}

/* Whether the trial projection keeping hold [nx] puts x on the
 * constraints; moved gets what it would change: "x' 5 -> 0, ...". */
static int
trial_assembly(const Options *c, eomc_sim *sim, const double *x, const unsigned char *hold,
               char *moved, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nx = eomc_nx(m);
    char name[STATE_NAME_MAX];
    double *y = malloc((size_t)nx * sizeof *y);
    if (!y)
        return 0;
    memcpy(y, x, (size_t)nx * sizeof *y);
    int ok = eomc_sim_project_held(sim, c->run.t0, y, y + n, hold) == EOMC_OK;
    size_t at = 0;
    moved[0] = '\0';
    for (int i = 0; ok && i < nx && at < len; i++)
        if (y[i] != x[i])
            at += (size_t)snprintf(moved + at, len - at, "%s%s %.6g -> %.6g", at ? ", " : "",
                                   state_name(m, i, name, sizeof name), x[i], y[i]);
    free(y);
    return ok;
}

/* The names hold [nx] marks, as --hold takes them. */
static void
hold_names(const eomc_model *m, const unsigned char *hold, char *buf, size_t len)
{
    size_t at = 0;
    char name[STATE_NAME_MAX];
    buf[0] = '\0';
    for (int i = 0; i < eomc_nx(m) && at < len; i++)
        if (hold[i])
            at += (size_t)snprintf(buf + at, len - at, "%s%s", at ? "," : "",
                                   state_name(m, i, name, sizeof name));
}

/* After --linearize refused a state off the constraints: the --assemble
 * that would put it on them, tried first, with what it would move.  Two
 * holds make sense: what --init set (the user's values stay; the rest
 * moves), and the linearization's own coordinates and velocities (only
 * those the constraints determine move). */
void
assembly_suggest(Options *c, eomc_sim *sim, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nx = eomc_nx(m), nl = eomc_sim_linear_size(sim), said = 0;
    unsigned char *hold[2] = {calloc((size_t)nx, 1), calloc((size_t)nx, 1)};
    char names[2048], moved[2048];
    const char *why[2] = {"keeps what --init set and moves the rest onto the constraints",
                          "keeps the linearization's coordinates and velocities and moves "
                          "only those the constraints determine"};
    for (int k = 0; hold[0] && k < c->ninit; k++) { /* NAME=VALUE or NAME'=VALUE */
        char name[STATE_NAME_MAX];
        size_t len = strcspn(c->init[k], "=");
        snprintf(name, sizeof name, "%.*s", (int)len, c->init[k]);
        int rate, i = state_find(m, name, &rate);
        if (i >= 0 && !rate)
            hold[0][i] = 1;
    }
    int *slot = malloc((size_t)eomc_nv(m) * sizeof *slot);
    int tangent = slot && state_tangent(m, slot) == 0;
    for (int k = 0; hold[1] && k < nl; k++) {
        int coord, order;
        eomc_sim_linear_state(sim, k, &coord, &order);
        if (order == 0 || order == 1) /* a coordinate, a speed */
            hold[1][coord + order * n] = 1;
        else if (order == 2 && tangent) /* a rotation: its quaternion's four */
            for (int r = 0; r < 4; r++)
                hold[1][m->quat[4 * STATE_ROT_QUAT(slot[coord]) + r]] = 1;
    }
    free(slot);
    for (int j = 0; j < 2 && hold[0] && hold[1]; j++) {
        if ((j == 0 && c->ninit == 0) || (j == 1 && !memcmp(hold[0], hold[1], (size_t)nx)))
            continue;
        if (!trial_assembly(c, sim, x, hold[j], moved, sizeof moved))
            continue;
        hold_names(m, hold[j], names, sizeof names);
        fprintf(io_err(), "%s: %s --assemble --hold \"%s\" %s: %s\n", c->prog,
                said++ ? "or" : "to linearize on them,", names, why[j], moved);
    }
    if (!said)
        fprintf(io_err(),
                "%s: --assemble --hold LIST puts the state on the constraints keeping "
                "LIST as it is (neither what --init set nor the linearization's coordinates "
                "and velocities can be kept here)\n", c->prog);
    free(hold[0]);
    free(hold[1]);
}

int
assembly_unit(const Options *c, const eomc_model *m, double *x, int quiet)
{
    for (int j = 0; j < m->nquat; j++) {
        const int *e = m->quat + 4 * j;
        double len = state_quat_norm(m, x, j);
        char q4[4 * STATE_NAME_MAX + 8];
        snprintf(q4, sizeof q4, "(%s, %s, %s, %s)", m->q_names[e[0]], m->q_names[e[1]],
                 m->q_names[e[2]], m->q_names[e[3]]);
        if (!(len > 0) || !isfinite(len)) {
            if (!quiet)
                fprintf(io_err(), "%s: the unit quaternion %s of the initial state has "
                        "length %g: it is no rotation (set its four coordinates, e.g. "
                        "%s=1 and the others 0)\n", c->prog, q4, len, m->q_names[e[0]]);
            return EOMC_EUSAGE;
        }
        if (fabs(len - 1) > EOMC_INCONSISTENT && !quiet)
            fprintf(io_err(), "%s: warning: the unit quaternion %s of the initial state has "
                    "length %.17g, not 1: it is divided by its length (a rotation's four "
                    "coordinates are set together)\n", c->prog, q4, len);
    }
    state_normalize(m, x, NULL);
    return EOMC_OK;
}
