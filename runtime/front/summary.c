/*
 * summary: a run's report on stderr (summary.h).
 */
#include "summary.h"
#include "base/io.h"
#include "base/numfmt.h"
#include "model/state.h"

#include <float.h>
#include <math.h>
#include <signal.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* A monotonic clock's seconds. */
static double
wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A run shorter than this is over before a progress line could help. */
#define PROGRESS_AFTER 1.0
/* The line is redrawn at most this often (seconds). */
#define PROGRESS_EVERY 0.1
/* The width the line is cleared over: its text and then some. */
enum { PROGRESS_WIDTH = 60 };

void
summary_progress_start(Progress *p, const eomc_model *m, double t_end)
{
    *p = (Progress){.name = m->name, .t_end = t_end, .tty = io_err_tty()};
    p->wall0 = p->next_show = wall_seconds();
}

void
summary_progress(void *ctx, double t)
{
    Progress *p = ctx;
    if (!p->tty)
        return;
    double now = wall_seconds();
    if (now < p->next_show)
        return;
    p->next_show = now + PROGRESS_EVERY;
    if (now - p->wall0 < PROGRESS_AFTER)
        return;
    fprintf(io_err(), "\r%s: t = %-12.6g of %g", p->name, t, p->t_end);
    p->shown = 1;
}

void
summary_progress_end(Progress *p)
{
    if (p->shown)
        fprintf(io_err(), "\r%*s\r", PROGRESS_WIDTH, "");
    p->shown = 0;
}

/* "name value" of --stats: a figure in the shortest digits that read back
 * as the same double (numfmt.h), so that a program reading the lines (the
 * Python package's Run.stats) gets the figure itself, not 3 digits of it. */
static void
put_stat(const char *name, double x)
{
    char num[NUM_MAX];
    fprintf(io_err(), "%s %s\n", name, num_shortest(num, x));
}

void
summary_stats(const Rows *w, const eomc_stats *st, int stabilize)
{
    const eomc_model *m = eomc_sim_model(w->sim);
    fprintf(io_err(), "steps %ld\nrejected %ld\nrhs_evals %ld\njac_evals %ld\n"
            "cpu_seconds %.6f\n", st->steps, st->rejected, st->rhs_evals,
            st->jac_evals, st->cpu_seconds);
    if (st->h_used > 0)
        put_stat("h_used", st->h_used);
    fprintf(io_err(), "side_steps %ld\n", st->side_steps);
    if (st->order_sum > 0) /* Taylor's method: its orders, on average */
        put_stat("order_mean", (double)st->order_sum / (double)st->steps);
    put_stat("max_condition", st->max_condition);
    put_stat("t_condition", st->t_condition);
    fprintf(io_err(), "condition_estimates %ld\n", st->condition_estimates);
    fprintf(io_err(), "monitor_seconds %.6f\n", st->monitor_seconds);
    if (st->invariant_budget > 0)
        put_stat("invariant_budget", st->invariant_budget);
    if (m->nc > 0)
        put_stat("max_residual", fmax(st->max_residual, w->res_max));
    if (stabilize == EOMC_STABILIZE_PROJECT)
        put_stat("max_drift", st->max_drift);
    if (m->nquat > 0) { /* the unit quaternions' lengths before renormalizing */
        put_stat("quat_drift", st->quat_drift);
        put_stat("quat_ratio", st->quat_ratio);
    }
    if (w->invariant)
        put_stat("invariant_drift", w->dh);
    if (w->ref) {
        put_stat("error_end", w->err_end);
        put_stat("error_max", w->err_max);
        put_stat("reference_error", w->ref->error);
        fprintf(io_err(), "reference_method %s\n", w->ref->method);
        if (w->ref->refinements > 0) /* computed, not read */
            fprintf(io_err(), "reference_steps %ld\nreference_rhs_evals %ld\n",
                    w->ref->steps, w->ref->rhs_evals);
        if (w->ref->nswitch >= 0 && m->nmode > 0)
            fprintf(io_err(), "reference_switches %ld\nswitches %ld\n", w->ref->nswitch,
                    w->cmp.nflip);
        if (w->cmp.parted) {
            put_stat("t_switches_part", w->cmp.part.t);
            put_stat("error_max_before_part", w->cmp.part.err_before);
        }
    }
    if (m->nevent > 0)
        fprintf(io_err(), "events %ld\nevent_evals %ld\n", st->events, st->event_evals);
    if (st->reset_event >= 0) {
        fprintf(io_err(), "reset_event %s\n", m->ev_names[st->reset_event]);
        put_stat("t_reset", st->reset_t);
        fprintf(io_err(), "reset_constraint %s\n", m->c_names[st->reset_constraint]);
        put_stat("reset_inconsistency", st->reset_inconsistency);
    }
    if (st->stop_event >= 0) {
        fprintf(io_err(), "stop_event %s\n", m->ev_names[st->stop_event]);
        put_stat("t_stop", st->t_stop);
    }
}

/* Print words wrapped at 72 columns. */
static void
wrap(FILE *f, char *text)
{
    int col = 0;
    for (char *save = NULL, *w = strtok_r(text, " ", &save); w;
         w = strtok_r(NULL, " ", &save)) {
        int len = (int)strlen(w);
        if (col && col + 1 + len > 72) {
            fputc('\n', f);
            col = 0;
        } else if (col) {
            fputc(' ', f);
            col++;
        }
        fputs(w, f);
        col += len;
    }
    fputc('\n', f);
}

void
summary_text(const Options *c, const eomc_model *m, const Rows *w, const eomc_stats *st)
{
    char text[4096];
    size_t len = 0, cap = sizeof text;
#define ADD(...) (len += len < cap ? (size_t)snprintf(text + len, cap - len, __VA_ARGS__) : 0)
    ADD("%s: %d coordinate%s (", m->name, m->nq, m->nq == 1 ? "" : "s");
    for (int i = 0; i < m->nq && i < 8; i++)
        ADD("%s%s", i ? ", " : "", m->q_names[i]);
    ADD("%s)", m->nq > 8 ? ", ..." : "");
    if (m->nv > 0) { /* speeds of their own */
        ADD(" and %d speed%s (", m->nv, m->nv == 1 ? "" : "s");
        for (int i = 0; i < m->nv && i < 8; i++)
            ADD("%s%s", i ? ", " : "", m->v_names[i]);
        ADD("%s)", m->nv > 8 ? ", ..." : "");
    }
    ADD(", equations in %s form from %s. ", m->form, m->spec);
    double t_last = st->stop_event >= 0 ? st->t_stop : c->run.t_end;
    ADD("Integrated from t = %g to %.17g with %s", c->run.t0, t_last, c->run.method);
    if (c->run.h_fixed > 0)
        ADD(" in fixed steps of %g: ", st->h_used);
    else
        ADD(" (rtol %g, atol %g): ", c->run.rtol, c->run.atol);
    ADD("%ld step%s (%ld rejected), %ld right-hand side%s and %ld Jacobian%s in %.3g s "
        "of CPU time. ", st->steps, num_plural(st->steps), st->rejected, st->rhs_evals,
        num_plural(st->rhs_evals), st->jac_evals, num_plural(st->jac_evals), st->cpu_seconds);
    ADD("Wrote %ld row%s every %g to %s. ", w->rows, num_plural(w->rows), c->run.dt,
        c->out ? c->out : "stdout");
    int resets = 0;
    for (int k = 0; k < m->nevent; k++)
        resets |= m->ev_action[k] == EOMC_EVENT_SET;
    if (m->nevent > 0)
        ADD("%ld event%s fired", st->events, st->events == 1 ? "" : "s");
    if (st->stop_event >= 0)
        ADD("; %s stopped the run at t = %.17g (t_end was %g)", m->ev_names[st->stop_event],
            st->t_stop, c->run.t_end);
    if (m->nevent > 0)
        ADD(". ");
    /* the change against the energy the motion moves about, not against h's
     * value, which a potential's constant sets anywhere (0 included) */
    char rel[80] = "";
    if (w->invariant && w->T_max > 0)
        snprintf(rel, sizeof rel, " (%.3g of the largest kinetic energy, %.3g)",
                 w->dh / w->T_max, w->T_max);
    if (w->invariant && resets && st->events > 0)
        ADD("The conserved quantity %s, measured afresh after each reset, changed by at "
            "most %.3g between them%s; it last started at %.10g.", m->invariant_name, w->dh,
            rel, w->h0);
    else if (w->invariant)
        ADD("The conserved quantity %s started at %.10g; its largest change was %.3g%s.",
            m->invariant_name, w->h0, w->dh, rel);
    else
        ADD("No drift is reported: %s.", m->invariant_note);
    if (m->nc > 0)
        ADD(" The largest constraint residual was %.3g", fmax(st->max_residual, w->res_max));
    if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_PROJECT)
        ADD(" with projection after every step (%.3g before it).", st->max_drift);
    else if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_BAUMGARTE)
        ADD(" with Baumgarte's stabilization (rates %g, %g).", c->alpha, c->beta);
    else if (m->nc > 0)
        ADD(", without stabilization.");
    if (m->nquat > 0)
        ADD(" The unit quaternion%s %s renormalized after every step; %s length had "
            "drifted from 1 by at most %.3g before (%s's, at t = %.6g).",
            m->nquat == 1 ? "" : "s", m->nquat == 1 ? "was" : "were",
            m->nquat == 1 ? "its" : "their", st->quat_drift,
            st->quat_name ? st->quat_name : m->q_names[m->quat[0]], st->quat_t);
    if (w->ref && isnan(w->ref->error))
        /* one read with --reference carries no estimate of its own error */
        ADD(" Against the reference solution read from %s (its own error not known), the "
            "error was at most %.3g over the rows and %.3g at t = %g.", c->reference,
            w->err_max, w->err_end, c->run.t_end);
    else if (w->ref)
        ADD(" Against the reference solution (%s%s, good to %.2g), the error was at "
            "most %.3g over the rows and %.3g at t = %g.", w->ref->method,
            w->ref->stiff ? ", as the problem is stiff" : "", w->ref->error, w->err_max,
            w->err_end, c->run.t_end);
    if (w->ref && w->cmp.parted)
        ADD(" The run's switches part from the reference's at t = %.6g; before it the "
            "error was at most %.3g, and after it the rows compare two branches of the "
            "motion.", w->cmp.part.t, w->cmp.part.err_before);
#undef ADD
    text[0] = (char)(text[0]); /* the model's name starts the paragraph as it is */
    wrap(io_err(), text);
}

/* An event's `set` that breaks the constraints is the same mistake as
 * such a start, made during the run, where its drift would otherwise pass
 * unseen: say so, for the first one. */
static void
warn_reset(const Options *c, const eomc_model *m, const eomc_stats *st)
{
    if (st->reset_event < 0)
        return;
    const char *name = m->c_names[st->reset_constraint];
    if (!strchr(st->reset_off, ',')) /* one constraint */
        fprintf(io_err(), "%s: warning: t = %.6g: event %s set %s that violate the constraint "
                "%s: its residual is %.2g of the size of its terms; ", c->prog, st->reset_t,
                m->ev_names[st->reset_event], st->reset_level ? "velocities" : "positions",
                name, st->reset_inconsistency);
    else
        fprintf(io_err(), "%s: warning: t = %.6g: event %s set a state off the constraints, "
                "worst first: %s (each residual as a share of the size of its terms); ",
                c->prog, st->reset_t, m->ev_names[st->reset_event], st->reset_off);
    if (c->stabilize == EOMC_STABILIZE_PROJECT)
        fprintf(io_err(), "the projection after the next step moved the state back onto the "
                "constraints, changing what the event set\n");
    else
        fprintf(io_err(), "the motion from there drifts off the constraints (column "
                "res[%s] shows how far; --stabilize project moves the state back onto "
                "them)\n", name);
}

/* The run's solve lost more digits than its tolerance leaves: say so,
 * with where and what (eomc_stats.ill). */
static void
warn_condition(const Options *c, const eomc_stats *st)
{
    if (isnan(st->ill_t))
        return;
    int fixed = c->run.h_fixed > 0 || !(c->run.rtol > 0);
    int kept = (int)lround(-log10(st->max_condition * DBL_EPSILON));
    fprintf(io_err(), "%s: warning: t = %.6g: %s is ill-conditioned (condition %.2g at "
            "worst, at t = %.6g): q'' keeps about %d of its 16 digits, fewer than the %d "
            "%s; the motion is probably less accurate than asked\n", c->prog, st->ill_t,
            st->ill, st->max_condition, st->t_condition, kept > 0 ? kept : 0,
            (int)lround(-log10(st->cond_tol)), fixed ? "a fixed-step run should keep" :
            "its rtol asks for");
}

/* The conserved quantity moves only by the steps' errors, so it may drift
 * by the sum of what their error estimates make of it (eomc_stats'
 * invariant_budget).  The estimates of healthy runs account for their
 * drift to within a factor of 2, bsimp's to within 90 (measured over the
 * shipped specs, every method, rtol 1e-4 .. 1e-12); beyond DRIFT_SLACK
 * times, an error the estimates cannot see is at work. */
#define DRIFT_SLACK 1e3

/* Fixed steps estimate no error of their own: a conserved quantity that
 * moved by more than FIXED_DRIFT of the largest kinetic energy has fewer
 * than two digits right, and the motion is no better. */
#define FIXED_DRIFT 1e-2

/* A unit quaternion's length moves only by the steps' errors: a step
 * that moved it by more than DRIFT_SLACK times what its own error
 * estimate allows (eomc_stats' quat_ratio) had an error the estimate did
 * not see; fixed steps, which estimate none, are told when a step moved
 * it by more than FIXED_DRIFT (fewer than two digits of the orientation
 * right in that step). */
static void
warn_quaternion(const Options *c, const eomc_model *m, const eomc_stats *st)
{
    if (m->nquat == 0)
        return;
    char q4[4 * STATE_NAME_MAX + 8] = "";
    for (int j = 0; j < m->nquat; j++) { /* the one whose drift st names */
        const int *e = m->quat + 4 * j;
        if (st->quat_name && !strcmp(st->quat_name, m->q_names[e[0]]))
            snprintf(q4, sizeof q4, "(%s, %s, %s, %s)", m->q_names[e[0]], m->q_names[e[1]],
                     m->q_names[e[2]], m->q_names[e[3]]);
    }
    if (st->h_used > 0 && st->quat_drift > FIXED_DRIFT)
        fprintf(io_err(), "%s: warning: fixed steps of %.3g: the unit quaternion %s moved off "
                "length 1 by %.3g in a step (at t = %.6g) before it was renormalized: fewer "
                "than two digits of the orientation are right there (shorter --fixed-step, "
                "or adaptive steps, give more)\n", c->prog, st->h_used, q4, st->quat_drift,
                st->quat_t);
    else if (st->quat_ratio > DRIFT_SLACK)
        fprintf(io_err(), "%s: warning: a step moved a unit quaternion's length by %.3g times "
                "what the step's own error estimate allows: an error the integrator cannot "
                "see is at work (a solve that loses digits, a force that is not smooth); "
                "the motion is probably less accurate than asked\n", c->prog,
                st->quat_ratio);
}

static void
warn_drift(const Options *c, const eomc_model *m, const eomc_stats *st, const Rows *w)
{
    if (st->h_used > 0 && w->invariant && w->dh > FIXED_DRIFT * w->T_max) {
        fprintf(io_err(), "%s: warning: fixed steps of %.3g: the conserved quantity %s changed "
                "by %.3g, %.2g of the largest kinetic energy (%.3g): fewer than two of its "
                "digits are right, and the motion's are probably no better (shorter "
                "--fixed-step, or adaptive steps, give more)\n", c->prog, st->h_used,
                m->invariant_name, w->dh, w->dh / w->T_max, w->T_max);
        return;
    }
    if (!(st->invariant_budget > 0) ||
        !(st->invariant_drift > DRIFT_SLACK * st->invariant_budget))
        return;
    fprintf(io_err(), "%s: warning: the conserved quantity %s drifted by %.3g, %.3g times "
            "what the steps' own error estimates allow (%.3g): an error the integrator "
            "cannot see is at work (a solve that loses digits, a force that is not "
            "smooth, or a model that does not conserve %s); the motion is probably less "
            "accurate than asked\n", c->prog, m->invariant_name, st->invariant_drift,
            st->invariant_drift / st->invariant_budget, st->invariant_budget,
            m->invariant_name);
}

/* After a failure: what the CSV holds. */
void
summary_kept(const Options *c, const Rows *w)
{
    char num[NUM_MAX];
    if (w->rows == 0)
        fprintf(io_err(), "%s: no row was computed: %s holds the header alone\n", c->prog,
                c->out ? c->out : "stdout");
    else if (w->rows == 1)
        fprintf(io_err(), "%s: the one row computed, at t = %s, is kept\n", c->prog,
                num_shortest(num, w->t_last));
    else
        fprintf(io_err(), "%s: the %ld rows computed up to then, to t = %s, are kept\n",
                c->prog, w->rows, num_shortest(num, w->t_last));
}

/* The run's switches parting from the reference's (compare.h): its
 * errors after that compare two branches of the motion, which the reader
 * of the error must know. */
static void
warn_switches(const Options *c, const eomc_model *m, const Rows *w)
{
    if (w->ref && w->ref->nswitch < 0 && m->nmode > 0)
        fprintf(io_err(), "%s: note: the reference read from %s has rows, not the flips of "
                "the switches between them: the run's flips are not compared with any\n",
                c->prog, c->reference);
    if (!w->ref || !w->cmp.parted)
        return;
    const ComparePart *p = &w->cmp.part;
    char a[STATE_NAME_MAX], b[STATE_NAME_MAX];
    const char *after = "the errors after t are not the run's error: they compare two "
                        "branches of the motion";
    if (p->ref_k >= 0 && p->ref_k == p->run_k)
        fprintf(io_err(), "%s: warning: the reference and the run flipped '%s' at different "
                "times, t = %.17g and %.17g, further apart than the run's error there "
                "explains (%.2g) (%s)\n", c->prog, state_switch_name(m, p->ref_k, a, sizeof a),
                p->t_ref, p->t_run, p->allowed, after);
    else if (p->ref_k >= 0 && p->run_k >= 0)
        fprintf(io_err(), "%s: warning: the reference and the run switched differently at "
                "t = %.17g: the reference flipped '%s', the run '%s' (%s)\n", c->prog, p->t,
                state_switch_name(m, p->ref_k, a, sizeof a),
                state_switch_name(m, p->run_k, b, sizeof b), after);
    else
        fprintf(io_err(), "%s: warning: the reference and the run switched differently at "
                "t = %.17g: the %s flipped '%s', the %s did not (%s)\n", c->prog, p->t,
                p->ref_k >= 0 ? "reference" : "run",
                state_switch_name(m, p->ref_k >= 0 ? p->ref_k : p->run_k, a, sizeof a),
                p->ref_k >= 0 ? "run" : "reference", after);
}

void
summary_warnings(const Options *c, const eomc_model *m, const eomc_stats *st, const Rows *w)
{
    warn_condition(c, st);
    warn_drift(c, m, st, w);
    warn_quaternion(c, m, st);
    warn_reset(c, m, st);
    warn_switches(c, m, w);
}

void
summary_error(const Options *c, const eomc_model *m, const Rows *w, const eomc_reference *ref)
{
    char good[200];
    if (isnan(ref->error))
        snprintf(good, sizeof good, "the reference, read from %s, has no estimate of "
                 "its own error", c->reference);
    else
        snprintf(good, sizeof good, "the reference, by %s%s, is good to %.2g",
                 ref->method, ref->stiff ? " (the problem is stiff)" : "", ref->error);
    double digits;
    int i = compare_worst(&w->cmp, &digits);
    char worst[160 + STATE_NAME_MAX] = "; every row is the reference's to the last bit";
    char name[STATE_NAME_MAX];
    if (digits < INFINITY) /* each component against its own size (compare.h) */
        snprintf(worst, sizeof worst, "; %s keeps the fewest digits, %.1f",
                 state_name(m, i, name, sizeof name), digits);
    char part[160] = "";
    if (w->cmp.parted) /* what the run's error is, where it is still the run's */
        snprintf(part, sizeof part, "; before t = %.6g, where the switches part, at most %.3g",
                 w->cmp.part.t, w->cmp.part.err_before);
    fprintf(io_err(), "%s: error against the reference solution: at most %.3g over "
            "the %ld row%s, %.3g at t = %g (%s)%s%s\n", c->prog, w->err_max, w->rows,
            num_plural(w->rows), w->err_end, c->run.t_end, good, worst, part);
}

void
summary_interrupted(const Options *c, const Rows *w, int sig)
{
    char num[NUM_MAX];
    fprintf(io_err(), "%s: interrupted at t = %s (%s): the %ld row%s up to then %s "
            "written\n", c->prog, num_shortest(num, w->t_last),
            sig == SIGINT ? "SIGINT" : "SIGTERM", w->rows, num_plural(w->rows),
            w->rows == 1 ? "is" : "are");
}
