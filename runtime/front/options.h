/*
 * options: a simulator's command line, read and checked (eomc_main).
 *
 * Options are read completely and checked before anything runs, so a
 * mistake costs nothing but a message (exit status 2).  The checks of
 * what the options say together are here, and nowhere else; what each
 * option is, and its help, is in the table of options (option_table.h).
 */
#ifndef EOMC_OPTIONS_H
#define EOMC_OPTIONS_H

#include "eomc.h"

typedef struct Options {
    const char *prog;
    const char *self;     /* how the user runs it, for --help: prog, or under
                           * `eomc run` "eomc run SPEC" ($EOMC_RUN_COMMAND) */
    eomc_run_opts run;
    const char *out;
    int stats, summary, accel, assemble, work_precision, error, linearize, equilibrium;
    int accel_extended; /* --accel-extended: --accel, solved by the twin */
    int no_assemble;      /* --no-assemble: not even the scene's assembly */
    int scene_assembles;  /* the model's scene says `assemble:` */
    unsigned char *held;  /* [nq + nv] what the assembly keeps (held_marks) */
    int stabilize;        /* EOMC_STABILIZE_... */
    double alpha, beta;   /* Baumgarte's rates */
    int rates_given, method_given, fixed_given, t0_given, t_end_given;
    char **set, **init;   /* NAME=VALUE arguments, in order */
    int nset, ninit;
    /* the reference and the report */
    const char *reference, *reference_out, *csv, *plot;
    int reference_method; /* EOMC_REFERENCE_... (--reference-method) */
    const char *errors;   /* --errors FILE: the errors by component */
    const char *events;   /* --events FILE */
    const char *animate;  /* --animate FILE.html */
    const char *hold;     /* --hold LIST, for --assemble */
    char **sweep;         /* --sweep NAME=START:STOP:COUNT, in order */
    int nsweep, threads;  /* and --threads N */
    int batch, batch_given; /* --batch N: 1, or EOMC_LANES (the default) */
    const char *sweep_file;
    const char **methods; /* NULL-terminated */
    double *tolerances, *steps, target;
    int ntolerances, nsteps;
    unsigned report_given; /* bit k: option O_METHODS + k (report-only) was given */
} Options;

/* Defaults from the model's scene; prog from argv[0]; -1 when memory
 * runs out (opt_free is safe either way). */
int opt_init(Options *c, int argc, char **argv, const eomc_model *m);
void opt_free(Options *c);
/* Read and check argv.  Returns EOMC_OK, EOMC_EUSAGE (said), or -1 when
 * --help or --version was handled. */
int opt_parse(Options *c, int argc, char **argv, const eomc_model *m);

/* --set's values into sim, then the parameters' check (eomc_sim_check). */
int opt_apply_sets(Options *c, eomc_sim *sim);
/* --stabilize and --baumgarte into sim. */
int opt_stabilize(Options *c, eomc_sim *sim);
/* --init's values over the initial state x [nq + nv]. */
int opt_apply_inits(Options *c, const eomc_model *m, double *x);
/* What the assembly keeps, into c->held [nq + nv]: --hold's list, else the
 * scene's, else nothing. */
int opt_held_marks(Options *c, const eomc_model *m);
/* "none", "baumgarte", "project" (EOMC_STABILIZE_...). */
const char *opt_stabilize_name(int method);

/* "PROG: MESSAGE\n(see SELF --help)" on stderr; returns EOMC_EUSAGE. */
int opt_usage(const Options *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* " (did you mean 'x'?)" for the nearest of names[0..n) (suffixed), every
 * one as near ("'rk4' or 'rkf45'"), or "": the compiler's rule
 * (nearest.h).  Valid until the next call. */
const char *opt_nearest(const char *word, const char *const *names, int n,
                        const char *suffix);
/* names[0..n), suffixed, separated by ", ", onto f. */
void opt_list_names(FILE *f, const char *const *names, int n, const char *suffix);

#endif
