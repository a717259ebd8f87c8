/*
 * rows: the CSVs a simulator writes and reads (rows.h).
 */
#include "rows.h"
#include "base/io.h"
#include "model/linalg.h"
#include "base/numfmt.h"
#include "signals.h"
#include "model/simimpl.h"
#include "model/state.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Rows go out in blocks of whole rows, each block one write: a run killed
 * at any moment (SIGKILL) leaves a CSV of whole rows.  64 KiB: a few
 * hundred rows of a small model. */
enum { ROW_BLOCK = 64 << 10 };

/* An event as it fires: a row of --events FILE, and a reset ends the
 * conserved quantity's comparison with the rows before. */
int
rows_event(void *ctx, int k, double t, const double *x)
{
    Rows *w = ctx;
    const eomc_model *m = eomc_sim_model(w->sim);
    char name[STATE_NAME_MAX];
    if (k < m->nevent && m->ev_action[k] == EOMC_EVENT_SET)
        w->rebase = 1, w->t_reset = t;
    /* the run's flips, for the reference's to be compared with */
    if (w->ref && k >= m->nevent && compare_flip(&w->cmp, k - m->nevent, t, x) != 0)
        return sim_usage_error(w->sim, "out of memory for the run's switches");
    if (!w->events)
        return EOMC_OK;
    num_put(w->events, t);
    if (k < m->nevent)
        fprintf(w->events, ",%s", m->ev_names[k]);
    else /* a switch of max, min, clamp or step (eomc.h's on_event) */
        fprintf(w->events, ",%s", state_switch_name(m, k - m->nevent, name, sizeof name));
    for (int i = 0; i < eomc_nx(m); i++) {
        fputc(',', w->events);
        num_put(w->events, x[i]);
    }
    fputc('\n', w->events);
    return EOMC_OK;
}


void
rows_flush(Rows *w)
{
    if (w->blen == 0)
        return;
    FILE *files[] = {w->f, w->tee};
    for (int j = 0; j < 2 && files[j]; j++) {
        fwrite(w->blk, 1, w->blen, files[j]);
        fflush(files[j]);
    }
    w->blen = 0;
}

/* A writer of rows to f (NULL: none yet); w.res NULL when out of memory. */
Rows
rows_new(FILE *f, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    size_t nres = (size_t)(m->nc + m->nout), n = (size_t)eomc_nv(m), nx = (size_t)eomc_nx(m);
    Rows w = {.f = f, .sim = sim, .invariant = m->invariant != NULL, .csv = 1,
              .ncols = rows_columns(m)};
    /* a row's cells: t, q, v, T, V, E, h, lambda, res, outputs */
    size_t cells = 1 + nx + 4 + nres + (size_t)m->nc, row = cells * (NUM_MAX + 1) + 1;
    size_t blk = (ROW_BLOCK + row) / sizeof(double) + 1;
    w.res = calloc(nres + n + 1 + blk + (size_t)m->nout, sizeof(double));
    w.arow = w.res ? w.res + nres : NULL;
    w.blk = w.res ? (char *)(w.arow + n + 1) : NULL;
    w.out_max = w.res ? w.arow + n + 1 + blk : NULL;
    return w;
}

void
rows_free(Rows *w)
{
    free(w->res);
    free(w->mem);
    w->res = NULL;
    w->mem = NULL;
}

/* Whether the model's conserved quantity is not E = T + V, so that it
 * gets a column of its own. */
static int
own_invariant_column(const eomc_model *m)
{
    return m->invariant && m->invariant_name && strcmp(m->invariant_name, "E") != 0;
}

/* ",q1,q2,q1',q2'": the state's names (the speeds' own, where they are not
 * the rates). */
static void
state_header(FILE *f, const eomc_model *m)
{
    char name[STATE_NAME_MAX];
    for (int i = 0; i < eomc_nx(m); i++)
        fprintf(f, ",%s", state_name(m, i, name, sizeof name));
}

void
rows_header(FILE *f, const eomc_model *m)
{
    fprintf(f, "t");
    state_header(f, m);
    fprintf(f, ",T,V,E");
    if (own_invariant_column(m))
        fprintf(f, ",%s", m->invariant_name);
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",lambda[%s]", m->c_names[k]);
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",res[%s]", m->c_names[k]);
    for (int k = 0; k < m->nout; k++)
        fprintf(f, ",%s", m->out_names[k]);
    fprintf(f, "\n");
}

/* The row's values into w->mem, in the CSV's columns (rows_header),
 * which grows by doubling: EOMC_OK, or -1 when memory runs out. */
static int
keep_row(Rows *w, double t, const double *x, double T, double V, double h, const double *lam,
         const double *out)
{
    const eomc_model *m = eomc_sim_model(w->sim);
    int nx = eomc_nx(m), nc = m->nc;
    if (w->mem_rows == w->mem_cap) {
        long cap = w->mem_cap ? 2 * w->mem_cap : 1024;
        double *mem = realloc(w->mem, (size_t)cap * (size_t)w->ncols * sizeof *mem);
        if (!mem)
            return -1;
        w->mem = mem, w->mem_cap = cap;
    }
    double *row = w->mem + (size_t)w->mem_rows++ * (size_t)w->ncols;
    int j = 0;
    row[j++] = t;
    for (int i = 0; i < nx; i++)
        row[j++] = x[i];
    row[j++] = T, row[j++] = V, row[j++] = T + V;
    if (own_invariant_column(m))
        row[j++] = h;
    for (int k = 0; k < nc; k++)
        row[j++] = lam[k];
    for (int k = 0; k < nc; k++)
        row[j++] = w->res[k];
    for (int k = 0; k < m->nout; k++)
        row[j++] = out[k];
    return EOMC_OK;
}

int
rows_columns(const eomc_model *m)
{
    return 1 + eomc_nx(m) + 3 + own_invariant_column(m) + 2 * m->nc + m->nout;
}

int
rows_write(void *ctx, double t, const double *x)
{
    Rows *w = ctx;
    const eomc_model *m = eomc_sim_model(w->sim);
    int n = m->nq, nc = m->nc;
    double *out = w->res + nc;
    /* the multipliers and outputs of this very state (it also solves
     * for its accelerations) */
    if (m->nout > 0 && eomc_sim_outputs(w->sim, t, x, x + n, out) != EOMC_OK)
        return EOMC_ENUMERIC;
    if (nc > 0 && m->nout == 0 && eomc_sim_accel(w->sim, t, x, x + n, w->arow) != EOMC_OK)
        return EOMC_ENUMERIC;
    if (nc > 0 && eomc_sim_residuals(w->sim, t, x, x + n, w->res) != EOMC_OK)
        return EOMC_ENUMERIC;
    double T, V, h = 0;
    eomc_sim_energy(w->sim, t, x, x + n, &T, &V);
    w->T_max = fmax(w->T_max, fabs(T));
    if (w->invariant) {
        eomc_sim_invariant(w->sim, t, x, x + n, &h);
        if (w->rows == 0)
            w->h_first = h;
        if (w->rows == 0 || (w->rebase && t > w->t_reset))
            w->h0 = h, w->rebase = 0;
        w->dh = fmax(w->dh, fabs(h - w->h0));
    }
    if (w->ref && w->rows < w->ref->nrows) {
        compare_row(&w->cmp, x);
        w->err_end = w->cmp.err_end;
        w->err_max = w->cmp.err_max;
    }
    for (int k = 0; k < nc; k++)
        w->res_max = fmax(w->res_max, fabs(w->res[k]));
    for (int k = 0; k < m->nout; k++)
        w->out_max[k] = fmax(w->out_max[k], fabs(out[k]));
    const double *lam = eomc_sim_multipliers(w->sim);
    if (w->in_memory && keep_row(w, t, x, T, V, h, lam, out) != EOMC_OK)
        return sim_usage_error(w->sim, "out of memory for the rows in memory (%ld kept)",
                               w->mem_rows);
    if (!w->csv) {
        w->rows++;
        w->t_last = t;
        return signals_caught() ? SIGNALS_STOPPED : EOMC_OK;
    }
    /* the row into the block of whole rows (room for one more row is
     * always there: rows_new sized it, and it is flushed past ROW_BLOCK) */
    char num[NUM_MAX];
#define CELL(first, v)                                                                 \
    (w->blen += (size_t)sprintf(w->blk + w->blen, "%s%s", (first) ? "" : ",",         \
                                num_shortest(num, (v))))
    CELL(1, t);
    for (int i = 0; i < n + eomc_nv(m); i++)
        CELL(0, x[i]);
    CELL(0, T);
    CELL(0, V);
    CELL(0, T + V);
    if (own_invariant_column(m))
        CELL(0, h);
    for (int k = 0; k < nc; k++)
        CELL(0, lam[k]);
    for (int k = 0; k < nc; k++)
        CELL(0, w->res[k]);
    for (int k = 0; k < m->nout; k++)
        CELL(0, out[k]);
#undef CELL
    w->blk[w->blen++] = '\n';
    w->rows++;
    w->t_last = t;
    if (w->blen >= ROW_BLOCK)
        rows_flush(w);
    if (signals_caught()) { /* this row is whole: stop here */
        rows_flush(w);
        return SIGNALS_STOPPED;
    }
    return EOMC_OK;
}

void
rows_events_header(FILE *f, const eomc_model *m)
{
    fprintf(f, "t,event");
    state_header(f, m);
    fputc('\n', f);
}

void
rows_sweep_header(FILE *f, const eomc_model *m, const char *const *names, int nparam,
                  const char *columns)
{
    for (int j = 0; j < nparam; j++)
        fprintf(f, "%s,", names[j]);
    if (columns) {
        fprintf(f, "%s\n", columns);
        return;
    }
    fprintf(f, "status,t");
    state_header(f, m);
    for (int i = 0; i < m->nout; i++)
        fprintf(f, ",%s", m->out_names[i]);
    fprintf(f, "\n");
}

FILE *
rows_open(const char *prog, const char *opt, const char *path)
{
    if (!path)
        return io_out();
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(io_err(), "%s: %s: cannot write '%s': %s\n", prog, opt, path,
                strerror(errno));
    return f;
}

int
rows_close(const char *prog, FILE *f, const char *path)
{
    int bad = fflush(f) != 0 || ferror(f);
    if (f != io_out())
        bad |= fclose(f) != 0;
    if (bad)
        fprintf(io_err(), "%s: error writing %s\n", prog, path ? path : "stdout");
    return bad;
}

/* ---- a reference from a file ---- */

/* The index of column name among the header's cols, or -1. */
static int
column(char **cols, int ncols, const char *name)
{
    for (int k = 0; k < ncols; k++)
        if (strcmp(cols[k], name) == 0)
            return k;
    return -1;
}

/* Split line at commas in place (the newline cut); the number of fields. */
static int
split(char *line, char **fields, int max)
{
    int n = 0;
    line[strcspn(line, "\r\n")] = '\0';
    for (char *p = line; n < max;) {
        fields[n++] = p;
        char *comma = strchr(p, ',');
        if (!comma)
            break;
        *comma = '\0';
        p = comma + 1;
    }
    return n;
}

int
eomc_reference_read(eomc_sim *s, const char *path, const eomc_run_opts *o,
                    eomc_reference *ref)
{
    const eomc_model *m = eomc_sim_model(s);
    int N = eomc_nx(m);
    memset(ref, 0, sizeof *ref);
    ref->nswitch = m->nmode > 0 ? -1 : 0; /* a file has rows, not the flips between them */
    FILE *f = fopen(path, "r");
    if (!f)
        return sim_usage_error(s, "--reference: cannot read %s: %s", path, strerror(errno));
    long nrows = eomc_run_rows(o), line_no = 1;
    size_t cap = 0, maxf = 0;
    char *line = NULL, **fields = NULL;
    int *col = calloc((size_t)N + 1, sizeof *col), rc = EOMC_OK, nf = 0;
    ssize_t len = getline(&line, &cap, f);
    if (len > 0)
        maxf = (size_t)len / 2 + 2;
    fields = calloc(maxf + 1, sizeof *fields);
    ref->t = calloc((size_t)nrows, sizeof *ref->t);
    ref->x = calloc((size_t)nrows * (size_t)N, sizeof *ref->x);
    if (!col || !fields || !ref->t || !ref->x)
        rc = sim_usage_error(s, "--reference: out of memory");
    else if (len <= 0)
        rc = sim_usage_error(s, "%s:1: empty: expected a header naming t, the coordinates "
                             "and the velocities", path);
    else
        nf = split(line, fields, (int)maxf);
    char name[STATE_NAME_MAX];
    for (int i = -1; rc == EOMC_OK && i < N; i++) {
        if (i < 0)
            snprintf(name, sizeof name, "t");
        else
            state_name(m, i, name, sizeof name);
        int k = column(fields, nf, name);
        if (k < 0)
            rc = sim_usage_error(s, "%s:1: no column '%s': the header must name t, every "
                                 "coordinate and every %s, as the simulator's CSV does",
                                 path, name, state_speed_word(m, 0));
        col[i + 1] = k;
    }
    long k = 0;
    while (rc == EOMC_OK && (len = getline(&line, &cap, f)) > 0) {
        line_no++;
        if ((size_t)len / 2 + 2 > maxf) {
            maxf = (size_t)len / 2 + 2;
            char **more = realloc(fields, (maxf + 1) * sizeof *fields);
            if (!more) {
                rc = sim_usage_error(s, "--reference: out of memory");
                break;
            }
            fields = more;
        }
        nf = split(line, fields, (int)maxf);
        if (k >= nrows) {
            rc = sim_usage_error(s, "%s:%ld: more rows than the %ld output times of t = %g "
                                 "to %g every %g", path, line_no, nrows, o->t0, o->t_end,
                                 o->dt);
            break;
        }
        double *row = ref->x + (size_t)k * (size_t)N;
        for (int i = -1; i < N && rc == EOMC_OK; i++) {
            int c = col[i + 1];
            char *end;
            double x = c < nf ? strtod(fields[c], &end) : NAN;
            if (c >= nf || end == fields[c] || *end != '\0' || !isfinite(x))
                rc = sim_usage_error(s, "%s:%ld: column %d is not a finite number", path,
                                     line_no, c + 1);
            else if (i < 0)
                ref->t[k] = x;
            else
                row[i] = x;
        }
        double want = eomc_run_row_time(o, k);
        if (rc == EOMC_OK && !(fabs(ref->t[k] - want) <= 1e-9 * o->dt))
            rc = sim_usage_error(s, "%s:%ld: a row at t = %.17g where the runs have one at "
                                 "t = %.17g: the reference needs a row at each output time "
                                 "(t = %g to %g every %g)", path, line_no, ref->t[k], want,
                                 o->t0, o->t_end, o->dt);
        ref->t[k] = want;
        k++;
    }
    if (rc == EOMC_OK && k != nrows)
        rc = sim_usage_error(s, "%s:%ld: %ld row%s where the runs have %ld output times "
                             "(t = %g to %g every %g)", path, line_no, k, k == 1 ? "" : "s",
                             nrows, o->t0, o->t_end, o->dt);
    fclose(f);
    free(line);
    free(fields);
    free(col);
    if (rc != EOMC_OK) {
        eomc_reference_free(ref);
        return rc;
    }
    ref->nrows = nrows;
    ref->nx = N;
    ref->error = NAN;
    ref->scale = la_max_abs(ref->x, (size_t)nrows * (size_t)N);
    snprintf(ref->source, sizeof ref->source, "read from %s", path);
    ref->method = "a file";
    return EOMC_OK;
}
