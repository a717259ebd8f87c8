/*
 * cmdline: eomc's command line, read into Options: the commands, one
 * table of their options (which commands take each, its values, its
 * messages), the help, and what a run's simulator options ask of the
 * model (the Jacobian, the extended-precision twin).  Bad usage exits
 * with EXIT_USAGE and a message.
 */
#ifndef EOMC_CMDLINE_H
#define EOMC_CMDLINE_H

#include <stdio.h>

enum { EXIT_USAGE = 2 };

typedef struct Options {
    const char *cmd, *spec, *out, *form, *effects, *jacobian, *scene, *code, *branches;
    char *fix; /* --fix values, comma-joined: "g=9.81,l=1" */
    int stats, eliminate, explain, mpi;
    int floating;       /* --floating: a URDF given as SPEC with its root link free */
    int joint_inputs;   /* --joint-inputs: an MJCF given as SPEC, tau_J on its joints */
    int parameters;     /* --parameters: a model given as SPEC, its values parameters */
    int shared;         /* --shared: a shared library (for Python), not a simulator */
    int taylor;         /* --taylor: the series of Taylor's method, whatever the scene */
    int needs_taylor;   /* ... or what the simulator is asked to do needs them */
    /* `run`: the method its simulator options name (the last --method; NULL:
     * the scene's), whether it integrates with it (not --accel, --linearize,
     * --equilibrium, --help, ... alone), and whether they ask for a
     * reference by Taylor's method that the run computes: what refuses a
     * model without Taylor series before it is built (main.c) */
    const char *run_method;
    int run_integrates, taylor_reference;
    int cache;          /* --cache: built into eomc's cache (as run's), its path printed */
    int extended;       /* --extended: the extended-precision twin, whatever the size */
    int portable;       /* --portable: the model's code for any CPU of its kind, not this one */
    int needs_jacobian; /* what the simulator is asked to do needs it */
    int needs_twin;     /* ... or the twin: a reference solution it must compute */
    int nsim; /* `run`: options passed on to the simulator */
    char **sim;
    /* SPEC given as an MJCF or URDF model: its spec as imported, and the
     * name messages give it */
    char *imported;
    size_t imported_len;
    char imported_name[600];
} Options;

/* Read argv (argv[1] a command other than import) into *o, or exit. */
void cmdline_parse(int argc, char **argv, Options *o);
/* eomc --help's text */
void cmdline_usage(FILE *f);
/* "eomc: FMT" (FMT's one %s is ARG), a pointer to --help, EXIT_USAGE */
_Noreturn void cmdline_usage_error(const char *fmt, const char *arg);
/* An option eomc does not know: the nearest one it does, if close. */
_Noreturn void cmdline_unknown_option(const char *a);
/* --jacobian's and --code's values (checked by cmdline_parse) as lower.h's modes */
int cmdline_jacobian_mode(const char *jacobian);
int cmdline_code_mode(const char *code);

#endif
