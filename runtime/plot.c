/*
 * plot: gnuplot scripts for the report's and a run's pictures (plot.h).
 */
#define _POSIX_C_SOURCE 200809L
#include "plot.h"

#include <errno.h>
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
        fprintf(stderr, "%s: --plot: gnuplot could not write %s\n", prog, path);
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

int
plot_trajectory(const char *prog, const eomc_model *m, const char *data, const char *path,
                double h0, int resets)
{
    char script[] = "/tmp/eomc-plot-XXXXXX";
    int fd = mkstemp(script);
    size_t len = strlen(path) + 32;
    char *tmp = malloc(len);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f || !tmp) {
        fprintf(stderr, "%s: --plot: cannot write a gnuplot script: %s\n", prog,
                strerror(errno));
        if (f)
            fclose(f);
        if (fd >= 0)
            unlink(script);
        free(tmp);
        return EOMC_EUSAGE;
    }
    snprintf(tmp, len, "%s.tmp%ld", path, (long)getpid());
    int n = m->nq, own_h = m->invariant && strcmp(m->invariant_name, "E") != 0;
    int h_col = m->invariant ? 2 * n + 4 + own_h : 0; /* E = column 2n + 4, or h after it */
    int out0 = 2 * n + 5 + own_h + 2 * m->nc;
    int panels = 1 + (m->invariant != NULL) + (m->nout > 0);
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
    if (m->nout > 0)
        panel(f, data, "outputs", out0, out0 + m->nout - 1);
    fprintf(f, "unset multiplot\n");
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad) {
        fprintf(stderr, "%s: --plot: cannot write a gnuplot script\n", prog);
        unlink(script);
        free(tmp);
        return EOMC_EUSAGE;
    }
    int rc = plot_finish(prog, script, tmp, path);
    free(tmp);
    return rc;
}
