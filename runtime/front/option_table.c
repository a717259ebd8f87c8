/*
 * option_table: every option of a simulator described in one table, in
 * the order --help lists them (option_table.h).  Parsing finds options
 * here by name; --help is written from the rows, with the model's own
 * lists (methods, events) and defaults filled in where a row asks.
 */
#include "option_table.h"
#include "base/io.h"

#include <stdio.h>
#include <string.h>

/* Which models have a use for a row: the others' --help leaves it out. */
enum When {
    ANY,
    CONSTRAINED,     /* m->nc > 0: drift control and assembly */
    SCENE_ASSEMBLES, /* ... and the scene says `assemble:` */
    EVENTS,          /* the scene has events */
};

/* What MARK in a row's help stands for: one of the model's defaults. */
enum Default { NO_DEFAULT, D_T_END, D_DT, D_METHOD, D_TOLERANCES, D_RATES };
#define MARK "{}"


/* The layout of --help, in columns of an 80-column terminal. */
enum {
    INDENT = 2,     /* an option */
    SUB_INDENT = 4, /* an option that belongs to the one above it */
    COL = 21,       /* where an option's help starts */
    WIDE_COL = 25,  /* ... when the option's group has labels too long for COL */
    LIST_COL = 23,  /* a model's list under an option (methods, events) */
    METHOD_W = 8,   /* a method's name, padded: the longest (msadams) has 7 letters */
    EVENT_W = 12,   /* an event's name, padded (a longer one widens the column) */
    TEXT_MAX = 80,  /* a label or a default: at most a line */
};

typedef struct Row {
    const char *name;  /* NULL: more lines of the option above */
    int option;        /* enum Option */
    const char *value; /* the value's placeholder; NULL for a flag */
    /* Lines separated by '\n'.  NULL: the option shares the line of the
     * one above ("--rtol X, --atol X").  A name that appears twice has
     * a second use, described where it applies (--csv). */
    const char *help;
    int when;          /* enum When */
    int sub;           /* 1: an option of the option above (SUB_INDENT) */
    int col;           /* where help starts; 0: COL */
    int dflt;          /* enum Default */
    void (*list)(const eomc_model *m); /* the model's list after the help */
} Row;

static void methods_list(const eomc_model *m);
static void events_list(const eomc_model *m);

static const Row rows[] = {
    {"--t0", O_T0, "T", "start time (default 0)", .when = ANY},
    {"--t-end", O_T_END, "T", "end time, after the start (default {})",
     .when = ANY, .dflt = D_T_END},
    {"--dt", O_DT, "T",
     "output interval (default {}); rows between steps\n"
     "are interpolated, so a small dt costs no steps",
     .when = ANY, .dflt = D_DT},
    {"--method", O_METHOD, "NAME", "integration method (default {}):",
     .when = ANY, .dflt = D_METHOD, .list = methods_list},
    {"--rtol", O_RTOL, "X", "adaptive tolerances (default {})",
     .when = ANY, .dflt = D_TOLERANCES},
    {"--atol", O_ATOL, "X", NULL, .when = ANY},
    {"--fixed-step", O_FIXED_STEP, "H", "fixed steps of at most H, evenly dividing the time span",
     .when = ANY},
    {"--max-steps", O_MAX_STEPS, "N", "fail after N steps", .when = ANY},
    {"--set", O_SET, "NAME=VALUE", "a parameter, or an input held constant", .when = ANY},
    {"--init", O_INIT, "NAME=VALUE", "initial coordinate NAME or velocity NAME'", .when = ANY},
    {"-o", O_OUT, "FILE", "write the CSV to FILE instead of stdout (- for stdout)", .when = ANY},
    {"--animate", O_ANIMATE, "FILE.html",
     "also write the motion as a page for a web browser,\n"
     "self-contained, offline (three.js: libjs-three)",
     .when = ANY},
    {"--stabilize", O_STABILIZE, "NAME", "drift control: none (default), baumgarte, project",
     .when = CONSTRAINED},
    {"--baumgarte", O_BAUMGARTE, "A,B",
     "Baumgarte's rates: g'' + 2A g' + B^2 g = 0, phi' + A phi = 0\n"
     "(default {}; implies --stabilize baumgarte)",
     .when = CONSTRAINED, .dflt = D_RATES},
    {"--assemble", O_ASSEMBLE, NULL, "project the initial state onto the constraints first",
     .when = CONSTRAINED},
    {NULL, O_ASSEMBLE, NULL, "(the scene does, for every run)", .when = SCENE_ASSEMBLES},
    {"--hold", O_HOLD, "LIST",
     "with --assemble: keep these coordinates (x) and velocities (x')\n"
     "as they are; the others meet the constraints",
     .when = CONSTRAINED},
    {NULL, O_HOLD, NULL, "(instead of the scene's list)", .when = SCENE_ASSEMBLES},
    {"--no-assemble", O_NO_ASSEMBLE, NULL, "start from the initial state as given, not assembled",
     .when = SCENE_ASSEMBLES},
    {"--events", O_EVENTS, "FILE",
     "each event as it fires, in CSV: t, event, the\n"
     "coordinates and velocities before its action",
     .when = EVENTS, .list = events_list},
    {"--stats", O_STATS, NULL, "integrator statistics on stderr", .when = ANY},
    {"--summary", O_SUMMARY, NULL, "a paragraph about the run on stderr", .when = ANY},
    {"--accel", O_ACCEL, NULL, "print q'' at the initial state and exit", .when = ANY},
    {"--accel-extended", O_ACCEL_EXTENDED, NULL,
     "the same, solved in the extended precision of the\n"
     "model's twin (eomc build --extended) and rounded",
     .when = ANY},
    {"--error", O_ERROR, NULL, "measure the run's error against the reference solution",
     .when = ANY},
    {"--reference", O_REFERENCE, "FILE",
     "the reference from FILE (a CSV with this simulator's\n"
     "columns and rows) instead of computing it",
     .when = ANY},
    {"--reference-out", O_REFERENCE_OUT, "FILE", "write the reference, in this simulator's columns",
     .when = ANY},
    {"--reference-method", O_REFERENCE_METHOD, "HOW",
     "how the reference is computed: extrapolation (the\n"
     "default) or taylor (Taylor's method in the same\n"
     "extended precision, a second and independent way)",
     .when = ANY},
    {"--errors", O_ERRORS, "FILE",
     "each run's errors by coordinate and velocity, as CSV\n"
     "(implies --error; with --work-precision, every run's)",
     .when = ANY},
    {"--work-precision", O_WORK_PRECISION, NULL,
     "what accuracy costs: run every method over tolerances\n"
     "and fixed steps, and report CPU time against error:",
     .when = ANY},
    /* the report's own options */
    {"--methods", O_METHODS, "LIST", "comma-separated (default: all)",
     .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--tolerances", O_TOLERANCES, "LIST",
     "rtol = atol of the adaptive runs (default 1e-3, ...,\n"
     "1e-13)",
     .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--steps", O_STEPS, "LIST",
     "fixed steps (default span/100, /1000, /10000, for\n"
     "rk4 rk1imp rk2imp rk4imp; given: every one-step\n"
     "method)",
     .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--csv", O_CSV, "FILE", "one row per run", .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--plot", O_PLOT, "FILE", "the work-precision diagram, .svg or .png (gnuplot)",
     .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--target", O_TARGET, "ERR", "the cheapest setting with error_max <= ERR",
     .when = ANY, .sub = 1, .col = WIDE_COL},
    {"--sweep", O_SWEEP, "NAME=START:STOP:COUNT",
     "one run per value (repeatable: a grid, the\n"
     "last one fastest); -o FILE gets the summary: the swept\n"
     "values, status, t, the state and the outputs at the end",
     .when = ANY},
    {"--sweep-file", O_SWEEP_FILE, "FILE", "one run per row of a CSV (a header of parameter names)",
     .when = ANY},
    {"--threads", O_THREADS, "N", "run a sweep's runs on N threads (same summary)", .when = ANY},
    {"--batch", O_BATCH, "N",
     "a Taylor sweep's runs N at a time, one vector's lanes\n"
     "(1 or 4; default 4 where the model has the series for\n"
     "it; same summary)",
     .when = ANY},
    {"--linearize", O_LINEARIZE, NULL,
     "A = dz'/dz and B = dz'/du at the initial state (or --init),\n"
     "z the coordinates and velocities (a constrained model's\n"
     "independent ones), exact; A's eigenvalues, the largest\n"
     "real part first; with --sweep, one row per value: the\n"
     "swept values, re1,im1,re2,im2,...",
     .when = ANY},
    {"--equilibrium", O_EQUILIBRIUM, NULL,
     "an equilibrium (q' = 0, q'' = 0) by Newton's method from\n"
     "the initial coordinates, its linearization and stability",
     .when = ANY},
    /* --csv again: what it writes for --linearize and --equilibrium */
    {"--csv", O_CSV, "FILE",
     "(both) A, B and the eigenvalues as matrix,row,column,value\n"
     "(eig,K,re,VALUE and eig,K,im,VALUE)",
     .when = ANY, .sub = 1},
    {"--help", O_HELP, NULL, "", .when = ANY},
    {"--version", O_VERSION, NULL, NULL, .when = ANY},
};
enum { NROWS = sizeof rows / sizeof rows[0] };

int
option_find(const char *arg, size_t len)
{
    for (int k = 0; k < NROWS; k++)
        if (rows[k].name && strlen(rows[k].name) == len && strncmp(arg, rows[k].name, len) == 0)
            return rows[k].option;
    return -1;
}

int
option_takes_value(int option)
{
    for (int k = 0; k < NROWS; k++)
        if (rows[k].name && rows[k].option == option)
            return rows[k].value != NULL;
    return -1;
}

const char *
option_name(int option)
{
    for (int k = 0; k < NROWS; k++)
        if (rows[k].name && rows[k].option == option)
            return rows[k].name;
    return "?";
}

static void
methods_list(const eomc_model *m)
{
    (void)m; /* the methods are the runtime's, the same for every model */
    for (int k = 0; eomc_methods[k]; k++)
        fprintf(io_out(), "%*s%-*s %s\n", LIST_COL, "", METHOD_W, eomc_methods[k],
                eomc_method_description(eomc_methods[k]));
}

static void
events_list(const eomc_model *m)
{
    static const char *const actions[] = {"stops the run", "is recorded", "sets the state"};
    fprintf(io_out(), "%*sthe scene's events:\n", INDENT, "");
    int w = EVENT_W;
    for (int k = 0; k < m->nevent; k++)
        if ((int)strlen(m->ev_names[k]) > w)
            w = (int)strlen(m->ev_names[k]);
    for (int k = 0; k < m->nevent; k++)
        fprintf(io_out(), "%*s%-*s %s (g crossing 0 %s)\n", LIST_COL, "", w, m->ev_names[k],
                actions[m->ev_action[k]], m->ev_direction[k] > 0   ? "upward"
                                         : m->ev_direction[k] < 0 ? "downward"
                                                                   : "either way");
}

static int
shown(int when, const eomc_model *m)
{
    switch (when) {
    case CONSTRAINED: return m->nc > 0;
    case SCENE_ASSEMBLES: return m->nc > 0 && m->assemble;
    case EVENTS: return m->nevent > 0;
    }
    return 1;
}

/* The text MARK stands for in a row's help. */
static void
default_text(int dflt, const eomc_model *m, char *buf, size_t size)
{
    switch (dflt) {
    case D_T_END: snprintf(buf, size, "%g", m->t_end); return;
    case D_DT: snprintf(buf, size, "%g", m->dt); return;
    case D_METHOD: snprintf(buf, size, "%s", m->method); return;
    case D_TOLERANCES: snprintf(buf, size, "%g, %g", m->rtol, m->atol); return;
    case D_RATES: snprintf(buf, size, "%g,%g", OPTION_DEFAULT_RATE, OPTION_DEFAULT_RATE); return;
    }
    buf[0] = '\0';
}

/* Help's lines from the current column on; the first continues a line
 * already begun (first), the others start at col. */
static void
help_lines(const char *help, int first, int col, const char *dflt)
{
    for (const char *p = help; *p;) {
        size_t len = strcspn(p, "\n");
        const char *mark = strstr(p, MARK);
        if (!first)
            fprintf(io_out(), "%*s", col, "");
        first = 0;
        size_t at = mark ? (size_t)(mark - p) : len, after = at + strlen(MARK);
        if (at < len)
            fprintf(io_out(), "%.*s%s%.*s\n", (int)at, p, dflt, (int)(len - after), p + after);
        else
            fprintf(io_out(), "%.*s\n", (int)len, p);
        p += len;
        p += *p == '\n';
    }
}

void
option_help(const char *self, const eomc_model *m)
{
    fprintf(io_out(), "usage: %s [OPTION]...\n"
            "Simulate %s (%s, %s form%s%s%s%s) and write the trajectory as CSV:\n"
            "t, each coordinate, each velocity (name'), T, V and E = T + V%s.\n\n",
            self, m->name, m->spec, m->form, *m->options ? ", " : "", m->options,
            *m->scene ? ", scene " : "", m->scene,
            m->invariant_name && !strcmp(m->invariant_name, "h")
               ? ", h (the conserved energy function)" : "");
    int col = COL;
    for (int k = 0; k < NROWS; k++) {
        const Row *r = &rows[k];
        if (!shown(r->when, m))
            continue;
        char dflt[TEXT_MAX];
        default_text(r->dflt, m, dflt, sizeof dflt);
        if (!r->name) {
            help_lines(r->help, 0, col, dflt);
            continue;
        }
        /* the label: the option, and those that share its line */
        char label[TEXT_MAX];
        int len = snprintf(label, sizeof label, "%*s%s%s%s", r->sub ? SUB_INDENT : INDENT, "",
                           r->name, r->value ? " " : "", r->value ? r->value : "");
        for (; k + 1 < NROWS && !rows[k + 1].help; k++)
            if (len < TEXT_MAX)
                len += snprintf(label + len, sizeof label - (size_t)len, ", %s%s%s",
                                rows[k + 1].name, rows[k + 1].value ? " " : "",
                                rows[k + 1].value ? rows[k + 1].value : "");
        col = r->col ? r->col : COL;
        if (!*r->help) {
            fprintf(io_out(), "%s\n", label);
            continue;
        }
        /* past the column, two spaces keep the label and its help apart */
        fprintf(io_out(), "%-*s%s", col, label, len < col ? "" : "  ");
        help_lines(r->help, 1, col, dflt);
        if (r->list)
            r->list(m);
    }
    fprintf(io_out(), "\ncoordinates: ");
    for (int k = 0; k < m->nq; k++)
        fprintf(io_out(), "%s%s", k ? ", " : "", m->q_names[k]);
    if (m->nv > 0) { /* speeds of their own, not the rates x' */
        fprintf(io_out(), "\nspeeds: ");
        for (int k = 0; k < m->nv; k++)
            fprintf(io_out(), "%s%s", k ? ", " : "", m->v_names[k]);
    }
    fprintf(io_out(), "\nparameters: ");
    for (int k = 0; k < m->np; k++)
        fprintf(io_out(), "%s%s=%g%s", k ? ", " : "", m->p_names[k], m->p_default[k],
                m->p_fixed[k] ? " (fixed)" : "");
    fprintf(io_out(), "\ninputs: ");
    for (int k = 0; k < m->nu; k++)
        fprintf(io_out(), "%s%s", k ? ", " : "", m->u_names[k]);
    fprintf(io_out(),
            "%s\n%s.\nExit status: 0 done, 2 usage error, 3 numerical failure (the rows "
            "computed so far are kept).\n", m->nu ? "" : "(none)", m->invariant_note);
}
