/*
 * sweep: runs on threads and ranks, rows in sweep order (sweep.h).
 */
#define _POSIX_C_SOURCE 200809L
#include "sweep.h"
#include "base/io.h"
#include "rows.h"
#include "base/numfmt.h"
#include "step/integrate.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

static const eomc_parallel *parallel;

void
eomc_set_parallel(const eomc_parallel *p)
{
    parallel = p;
}

int
sweep_rank(void)
{
    return parallel ? parallel->rank : 0;
}

/* A growing string. */
typedef struct Text {
    char *s;
    size_t len, cap;
} Text;

static int
add(Text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = vsnprintf(t->s ? t->s + t->len : NULL, t->s ? t->cap - t->len : 0, fmt, ap);
        va_end(ap);
        if (k < 0)
            return -1;
        if (t->s && t->len + (size_t)k < t->cap) {
            t->len += (size_t)k;
            return 0;
        }
        size_t cap = 2 * (t->cap + (size_t)k) + 64;
        char *s = realloc(t->s, cap);
        if (!s)
            return -1;
        t->s = s, t->cap = cap;
    }
}

/* The last row a run reached: what its summary row reports. */
typedef struct Last {
    double t;
    double *x;
    int nx;     /* the state's entries */
} Last;

static int
keep_last(void *ctx, double t, const double *x)
{
    Last *l = ctx;
    l->t = t;
    memcpy(l->x, x, (size_t)l->nx * sizeof *x);
    return EOMC_OK;
}

/* A CSV cell for a message: quoted, quotes doubled, on one line. */
static void
add_quoted(Text *t, const char *msg)
{
    add(t, "\"");
    for (const char *p = msg; *p; p++)
        add(t, *p == '"' ? "\"\"" : *p == '\n' || *p == '\r' ? " " : "%c", *p);
    add(t, "\"");
}

/* A run in the making: its row's values, its simulator and arrays. */
typedef struct Run {
    long i;            /* in this rank's order */
    Text row;
    eomc_sim *sim;
    double *x, *last, *out;
    Last l;
    eomc_stats st;
    int rc;
} Run;

/* What run_begin allocated, but the row; returns the row. */
static char *
run_free(Run *r)
{
    eomc_sim_free(r->sim);
    free(r->x);
    free(r->last);
    free(r->out);
    return r->row.s;
}

/* The row of a sweep of cells (Sweep.cells) after its values: its status,
 * then its cells (empty when it failed); the run freed. */
static char *
cells_row(const Sweep *sw, Run *r)
{
    char *text = NULL;
    int rc = r->rc;
    if (rc == EOMC_OK)
        rc = sw->cells(sw->ctx, r->sim, r->x, &text);
    if (rc == EOMC_OK) {
        add(&r->row, "%sok%s\n", sw->nparam ? "," : "", text);
    } else {
        add(&r->row, "%s", sw->nparam ? "," : "");
        add_quoted(&r->row, r->sim ? eomc_sim_error(r->sim) : "out of memory");
        for (int i = 0; i < sw->ncells; i++)
            add(&r->row, ",");
        add(&r->row, "\n");
    }
    free(text);
    return run_free(r);
}

/* Run k up to its integration: its simulator set up and its initial
 * state (r->rc says whether they could be). */
static void
run_begin(const Sweep *sw, long k, Run *r)
{
    const eomc_model *m = sw->m;
    int nx = eomc_nx(m);
    char num[NUM_MAX];
    *r = (Run){0};
    for (int j = 0; j < sw->nparam; j++)
        add(&r->row, "%s%s", j ? "," : "", num_shortest(num, sw->values[k * sw->nparam + j]));
    r->sim = eomc_sim_alloc(m);
    r->x = calloc((size_t)nx + 1, sizeof *r->x);
    r->last = calloc((size_t)nx + 1, sizeof *r->x);
    r->out = calloc((size_t)m->nout + 1, sizeof *r->out);
    int rc = r->sim && r->x && r->last && r->out ? sw->prepare(sw->ctx, r->sim) : EOMC_EUSAGE;
    for (int j = 0; j < sw->nparam && rc == EOMC_OK; j++)
        rc = eomc_sim_set(r->sim, sw->names[j], sw->values[k * sw->nparam + j]);
    if (rc == EOMC_OK)
        rc = eomc_sim_check(r->sim);
    if (rc == EOMC_OK)
        rc = sw->initial(sw->ctx, r->sim, r->x);
    r->l = (Last){sw->run->t0, r->last, nx};
    if (r->x && r->last)
        memcpy(r->last, r->x, (size_t)nx * sizeof *r->x);
    r->rc = rc;
}

/* The run's row after its integration (r->rc its status), a malloc'd
 * line; what run_begin allocated freed. */
static char *
run_end(const Sweep *sw, Run *r)
{
    const eomc_model *m = sw->m;
    int n = m->nq, nx = eomc_nx(m), rc = r->rc;
    char num[NUM_MAX];
    if (rc == EOMC_OK && m->nout > 0)
        rc = eomc_sim_outputs(r->sim, r->l.t, r->last, r->last + n, r->out);
    if (rc == EOMC_OK) {
        add(&r->row, "%sok,%s", sw->nparam ? "," : "", num_shortest(num, r->l.t));
        for (int i = 0; i < nx; i++)
            add(&r->row, ",%s", num_shortest(num, r->last[i]));
        for (int i = 0; i < m->nout; i++)
            add(&r->row, ",%s", num_shortest(num, r->out[i]));
    } else {
        add(&r->row, "%s", sw->nparam ? "," : "");
        add_quoted(&r->row, r->sim ? eomc_sim_error(r->sim) : "out of memory");
        for (int i = 0; i < 1 + nx + m->nout; i++)
            add(&r->row, ",");
    }
    add(&r->row, "\n");
    return run_free(r);
}

/* Run k into its row (a malloc'd line). */
static char *
one_run(const Sweep *sw, long k)
{
    Run r;
    run_begin(sw, k, &r);
    if (sw->cells) /* the row holds its status until rank 0 writes it */
        return cells_row(sw, &r);
    if (r.rc == EOMC_OK)
        r.rc = eomc_sim_integrate(r.sim, sw->run, r.x, keep_last, &r.l, NULL);
    return run_end(sw, &r);
}

typedef struct Pool {
    const Sweep *sw;
    long first, step;     /* this rank's runs: first, first + step, ... */
    long count;           /* how many */
    atomic_long next;     /* the next of them to take */
    char **rows;          /* [count] */
    FILE *out, *err;      /* the starting thread's streams (io.h), which its
                           * workers print on: eomc_main_mem keeps them */
} Pool;

/* integrate.h's next: the pool's next run that can start, in a lane
 * (one that cannot gets its row at once). */
static int
lane_next(void *ctx, IntegrateLane *lane)
{
    Pool *p = ctx;
    for (long i; (i = atomic_fetch_add(&p->next, 1)) < p->count;) {
        Run *r = malloc(sizeof *r);
        if (!r) {
            p->rows[i] = NULL; /* (the sweep says it ran out of memory) */
            continue;
        }
        run_begin(p->sw, p->first + i * p->step, r);
        r->i = i;
        if (r->rc != EOMC_OK) {
            p->rows[i] = run_end(p->sw, r);
            free(r);
            continue;
        }
        *lane = (IntegrateLane){.s = r->sim, .x = r->x, .row = keep_last, .ctx = &r->l,
                                .st = &r->st, .tag = r};
        return 1;
    }
    return 0;
}

/* integrate.h's done: the lane's run into its row. */
static void
lane_done(void *ctx, IntegrateLane *lane)
{
    Pool *p = ctx;
    Run *r = lane->tag;
    r->rc = lane->rc;
    p->rows[r->i] = run_end(p->sw, r);
    free(r);
}

static void *
worker(void *arg)
{
    Pool *p = arg;
    const Sweep *sw = p->sw;
    if (sw->batch > 1 && !sw->cells && sw->m->taylor_run4 &&
        strcmp(sw->run->method, "taylor") == 0) {
        IntegrateRuns runs = {lane_next, lane_done, p};
        integrate_lanes(sw->m, sw->run, &runs);
        return NULL;
    }
    for (long i; (i = atomic_fetch_add(&p->next, 1)) < p->count;)
        p->rows[i] = one_run(p->sw, p->first + i * p->step);
    return NULL;
}

/* A worker on a thread of its own (the starting thread is the first
 * worker): it prints where the starting thread would. */
static void *
worker_thread(void *arg)
{
    Pool *p = arg;
    io_set(p->out, p->err, NULL); /* the thread ends with the sweep */
    return worker(p);
}

/* "warning: 2 of 5 runs failed ...; the first: l = 0: t = 0: ..." from
 * the first failed row: its values, then its status, a quoted CSV cell. */
static void
warn_failed(const Sweep *sw, long failed, const char *row)
{
    fprintf(io_err(), "%s: warning: %ld of %ld run%s failed (%s); the first:", sw->prog, failed,
            sw->nruns, sw->nruns == 1 ? "" : "s",
            sw->cells ? "their cells are empty" : "each row's status says why");
    for (int k = 0; k < sw->nparam; k++) {
        size_t len = strcspn(row, ",");
        fprintf(io_err(), " %s = %.*s%s", sw->names[k], (int)len, row, k + 1 < sw->nparam
                ? "," : ":");
        row += len + (row[len] == ',');
    }
    fputc(' ', io_err());
    for (const char *c = row + (*row == '"'); *c && *c != '\n'; c++) {
        if (*c == '"' && c[1] == '"')
            c++; /* a quote, doubled inside the cell */
        else if (*c == '"')
            break;
        fputc(*c, io_err());
    }
    fputc('\n', io_err());
}

/* A row of cells as it is written: its values (row .. st), then its
 * cells, past its status (a quoted CSV cell, or ok). */
static void
write_cells(FILE *f, const char *row, const char *st, const char *end)
{
    const char *c = st;
    if (*c == '"') /* past the closing quote: a doubled one is inside */
        for (c++; *c && !(*c == '"' && c[1] != '"'); c += *c == '"' ? 2 : 1)
            ;
    c = strpbrk(c, ",\n");
    if (st > row) /* the values and their comma */
        fwrite(row, 1, (size_t)(st - row) - 1, f);
    if (c && c < end && st > row)
        fwrite(c, 1, (size_t)(end - c) + 1, f); /* ",cells\n" */
    else if (c && c < end)
        fwrite(c + 1, 1, (size_t)(end - c), f);
    else
        fputc('\n', f);
}

int
sweep_run(const Sweep *sw, FILE *f)
{
    const eomc_model *m = sw->m;
    int rank = parallel ? parallel->rank : 0, size = parallel ? parallel->size : 1;
    Pool p = {sw, rank, size, 0, 0, NULL, io_out(), io_err()};
    p.count = sw->nruns > rank ? (sw->nruns - rank + size - 1) / size : 0;
    atomic_init(&p.next, 0);
    p.rows = calloc((size_t)p.count + 1, sizeof *p.rows);
    if (!p.rows)
        return EOMC_EUSAGE;
    int nt = sw->threads < 1 ? 1 : sw->threads;
    pthread_t *th = calloc((size_t)nt, sizeof *th);
    /* this thread is the first worker; the others are those created, th[0
     * .. started - 1] (one that cannot be created leaves its runs to them) */
    int started = 0;
    for (int k = 1; th && k < nt; k++)
        started += pthread_create(&th[started], NULL, worker_thread, &p) == 0;
    worker(&p);
    for (int k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    free(th);
    /* this rank's rows in its order, then rank 0 puts every rank's in
     * sweep order: run j is row j / size of rank j % size */
    Text mine = {0};
    int rc = EOMC_OK;
    for (long i = 0; i < p.count; i++) {
        if (!p.rows[i] || add(&mine, "%s", p.rows[i]) != 0)
            rc = EOMC_EUSAGE;
        free(p.rows[i]);
    }
    free(p.rows);
    char *all = mine.s;
    size_t *lens = NULL;
    if (parallel && parallel->gather(mine.s ? mine.s : "", mine.len, &all, &lens) != 0)
        rc = EOMC_EUSAGE;
    if (rank == 0 && rc == EOMC_OK) {
        rows_sweep_header(f, m, sw->names, sw->nparam, sw->cells ? sw->columns : NULL);
        /* the start of each rank's text, then its rows one line at a time */
        const char **at = calloc((size_t)size, sizeof *at);
        size_t off = 0;
        for (int r = 0; at && r < size; r++) {
            at[r] = (all ? all : "") + off;
            off += parallel ? lens[r] : mine.len;
        }
        long failed = 0;
        const char *first = NULL;
        for (long j = 0; at && j < sw->nruns; j++) {
            const char **pr = &at[j % size];
            const char *end = strchr(*pr, '\n');
            if (!end) {
                rc = EOMC_EUSAGE;
                break;
            }
            /* its status follows the swept values, numbers without commas */
            const char *st = *pr;
            for (int k = 0; k < sw->nparam && st; k++)
                st = strchr(st, ',') ? strchr(st, ',') + 1 : NULL;
            if (st && strncmp(st, "ok,", 3) != 0 && strncmp(st, "ok\n", 3) != 0 &&
                failed++ == 0)
                first = *pr;
            if (sw->cells && st)
                write_cells(f, *pr, st, end);
            else
                fwrite(*pr, 1, (size_t)(end - *pr) + 1, f);
            *pr = end + 1;
        }
        /* the rows say which runs failed; so does the run, once, where it is seen */
        if (failed > 0)
            warn_failed(sw, failed, first);
        free(at);
    }
    if (all != mine.s)
        free(all);
    free(mine.s);
    free(lens);
    if (rc != EOMC_OK && rank == 0)
        fprintf(io_err(), "%s: --sweep: out of memory, or the ranks' rows did not come back\n",
                sw->prog);
    return rc;
}
