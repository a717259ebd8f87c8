/*
 * plot: gnuplot scripts for the report's and a run's pictures (plot.h).
 */
#define _POSIX_C_SOURCE 200809L
#include "plot.h"
#include "base/io.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

int
plot_have_gnuplot(void)
{
    const char *path = getenv("PATH");
    if (!path)
        return 0;
    char *copy = strdup(path), *save = NULL;
    int found = 0;
    for (char *dir = strtok_r(copy, ":", &save); dir && !found;
         dir = strtok_r(NULL, ":", &save)) {
        char file[4096];
        snprintf(file, sizeof file, "%s/gnuplot", *dir ? dir : ".");
        found = access(file, X_OK) == 0;
    }
    free(copy);
    return found;
}

void
plot_string(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'')
            fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

static int
ends_with(const char *s, const char *tail)
{
    size_t a = strlen(s), b = strlen(tail);
    return a >= b && strcmp(s + a - b, tail) == 0;
}

int
plot_format_ok(const char *path)
{
    return ends_with(path, ".svg") || ends_with(path, ".png");
}

void
plot_terminal(FILE *f, const char *path, const char *tmp, int width, int height)
{
    int png = ends_with(path, ".png");
    fprintf(f, "set terminal %s size %d,%d %s font 'sans,12' background rgb 'white'\n",
            png ? "pngcairo" : "svg", width, height, png ? "" : "dynamic");
    fprintf(f, "set output ");
    plot_string(f, tmp);
    fprintf(f, "\n");
}

int
plot_finish(const char *prog, const char *script, const char *tmp, const char *path)
{
    int status = -1;
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    if (pid > 0)
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
            ;
    unlink(script);
    struct stat st;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || stat(tmp, &st) != 0 ||
        rename(tmp, path) != 0) {
        fprintf(io_err(), "%s: --plot: gnuplot could not write %s\n", prog, path);
        unlink(tmp);
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

/* One panel: columns first..last of the data against t. */
static void
panel(FILE *f, const char *data, const char *ylabel, int first, int last)
{
    fprintf(f, "set ylabel ");
    plot_string(f, ylabel);
    fprintf(f, " noenhanced\nplot for [k=%d:%d] ", first, last);
    plot_string(f, data);
    fprintf(f, " using 1:k with lines linewidth 1.5 title columnhead(k)\n");
}

/* Outputs have no units in the spec, so an axis of their own is the only
 * safe one: one panel each, up to this many; more are grouped by
 * magnitude. */
enum { OUT_PANELS = 6 };

/* The outputs' panels: group [nout] gets each output's panel, 0, 1, ...;
 * returns how many.  Up to OUT_PANELS outputs, one each; else the
 * outputs, by their largest |value| over the run (scale), share a panel
 * with those within a factor of ratio of the smallest in it, ratio 10,
 * then 100, ... until OUT_PANELS panels are enough: no curve is drawn
 * flat against another a thousand times its size unless there are too
 * many to draw apart.  A scale of 0 (or not finite) is its own magnitude,
 * first. */
static int
group_outputs(const double *scale, int nout, int *group)
{
    if (nout <= OUT_PANELS) {
        for (int k = 0; k < nout; k++)
            group[k] = k;
        return nout;
    }
    int *order = malloc((size_t)nout * sizeof *order), panels = 0;
    if (!order) {
        for (int k = 0; k < nout; k++)
            group[k] = 0;
        return 1;
    }
    /* the outputs by magnitude (insertion: a scene has a few) */
    for (int k = 0; k < nout; k++) {
        double sk = isfinite(scale[k]) ? scale[k] : 0;
        int j = k;
        for (; j > 0 && (isfinite(scale[order[j - 1]]) ? scale[order[j - 1]] : 0) > sk; j--)
            order[j] = order[j - 1];
        order[j] = k;
    }
    for (double ratio = 10;; ratio *= 10) {
        double low = -1;
        panels = 0;
        for (int j = 0; j < nout; j++) {
            double s = isfinite(scale[order[j]]) ? scale[order[j]] : 0;
            if (panels == 0 || (low == 0 ? s > 0 : s > ratio * low))
                low = s, panels++;
            group[order[j]] = panels - 1;
        }
        if (panels <= OUT_PANELS)
            break;
    }
    free(order);
    return panels;
}

/* Panel g of the outputs: each output in it (columns out0 + k), labelled
 * with its name when it is alone. */
static void
output_panel(FILE *f, const eomc_model *m, const char *data, int out0, const int *group,
             int g)
{
    int count = 0, only = -1;
    for (int k = 0; k < m->nout; k++)
        if (group[k] == g)
            count++, only = k;
    fprintf(f, "set ylabel ");
    plot_string(f, count == 1 ? m->out_names[only] : "outputs");
    fprintf(f, " noenhanced\nplot");
    for (int k = 0, first = 1; k < m->nout; k++) {
        if (group[k] != g)
            continue;
        fprintf(f, "%s ", first ? "" : ",");
        plot_string(f, data);
        fprintf(f, " using 1:%d with lines linewidth 1.5 title columnhead(%d)", out0 + k,
                out0 + k);
        first = 0;
    }
    fprintf(f, "\n");
}

int
plot_trajectory(const char *prog, const eomc_model *m, const char *data, const char *path,
                double h0, int resets, const double *out_scale)
{
    char script[] = "/tmp/eomc-plot-XXXXXX";
    int fd = mkstemp(script);
    size_t len = strlen(path) + 32;
    char *tmp = malloc(len);
    int *group = calloc((size_t)m->nout + 1, sizeof *group);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f || !tmp || !group) {
        fprintf(io_err(), "%s: --plot: cannot write a gnuplot script: %s\n", prog,
                strerror(errno));
        if (f)
            fclose(f);
        if (fd >= 0)
            unlink(script);
        free(tmp);
        free(group);
        return EOMC_EUSAGE;
    }
    snprintf(tmp, len, "%s.tmp%ld", path, (long)getpid());
    int n = m->nq, nx = eomc_nx(m), own_h = m->invariant && strcmp(m->invariant_name, "E") != 0;
    /* E = column nx + 4 (t, the state, T, V), or h after it */
    int h_col = m->invariant ? nx + 4 + own_h : 0;
    int out0 = nx + 5 + own_h + 2 * m->nc;
    int out_panels = group_outputs(out_scale, m->nout, group);
    int panels = 1 + (m->invariant != NULL) + out_panels;
    plot_terminal(f, path, tmp, 1000, 330 * panels + 40);
    char title[512];
    snprintf(title, sizeof title, "%s%s%s (%s, %s form)", m->name, *m->scene ? ", scene " : "",
             m->scene, m->spec, m->form);
    /* the same margins for every panel: their time axes line up */
    fprintf(f, "set datafile separator ','\nset key outside right top noenhanced\n"
               "set lmargin 14\nset rmargin 24\n"
               "set grid\nset xlabel 't'\nset multiplot layout %d,1 title ", panels);
    plot_string(f, title);
    fprintf(f, " noenhanced\n");
    panel(f, data, "coordinates", 2, n + 1);
    if (m->invariant && resets) {
        char what[160];
        snprintf(what, sizeof what, "%s (the resets of events change it)", m->invariant_name);
        panel(f, data, what, h_col, h_col);
    } else if (m->invariant) {
        /* its drift: the change from the first row */
        fprintf(f, "h0 = %.17g\nset ylabel ", h0);
        char what[160];
        snprintf(what, sizeof what, "%s - %s(t0): drift", m->invariant_name,
                 m->invariant_name);
        plot_string(f, what);
        fprintf(f, " noenhanced\nplot ");
        plot_string(f, data);
        fprintf(f, " using 1:(column(%d) - h0) with lines linewidth 1.5 title ", h_col);
        plot_string(f, what);
        fprintf(f, "\n");
    }
    for (int g = 0; g < out_panels; g++)
        output_panel(f, m, data, out0, group, g);
    fprintf(f, "unset multiplot\n");
    free(group);
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad) {
        fprintf(io_err(), "%s: --plot: cannot write a gnuplot script\n", prog);
        unlink(script);
        free(tmp);
        return EOMC_EUSAGE;
    }
    int rc = plot_finish(prog, script, tmp, path);
    free(tmp);
    return rc;
}
