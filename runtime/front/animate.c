/*
 * animate: a run's motion as a self-contained HTML page (animate.h).
 */
#include "animate.h"
#include "animate_page.h" /* anim_page_js: animate_page.js, built in */
#include "base/io.h"
#include "model/simimpl.h"

#include <errno.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define THREE_DEFAULT "/usr/share/javascript/three"
static const char *const three_files[] = {"three.min.js",
                                          "examples/js/controls/OrbitControls.js"};
/* A number of the trajectory as written: "%.6g" and a comma, at most. */
enum { NUM_TEXT = 14 };
/* tan(45 / 2 degrees): the camera's vertical field of view is 45 degrees. */
#define TAN_HALF_FOV 0.41421356237309503

struct Anim {
    eomc_sim *sim;
    const eomc_model *m;
    const char *path;
    int width;       /* numbers a frame keeps: t, outputs, each item's pose */
    long stride;     /* rows kept: every stride-th row */
    long seen;       /* rows seen */
    long n, cap;     /* frames kept, and room for them */
    double *frames;  /* [cap * width] */
    double *last;    /* [width] the last row seen, kept unless it was */
    int last_kept;
    double *X;       /* [ndraw * EOMC_POSE] */
    long max_frames; /* the budget, in frames */
};

const char *
anim_three_dir(void)
{
    const char *d = getenv("EOMC_THREE_DIR");
    return d && *d ? d : THREE_DEFAULT;
}

const char *
anim_cannot(const eomc_model *m, char *buf, size_t len)
{
    if (m->ndraw <= 0 || !m->draw)
        return "this model has nothing to draw (no bodies or particles)";
    for (int k = 0; k < 2; k++) {
        snprintf(buf, len, "%s/%s", anim_three_dir(), three_files[k]);
        FILE *f = fopen(buf, "rb");
        if (!f) {
            snprintf(buf, len, "--animate: three.js is not installed (no %s/%s; Debian: "
                     "apt-get install libjs-three, or set EOMC_THREE_DIR)", anim_three_dir(),
                     three_files[k]);
            return buf;
        }
        fclose(f);
    }
    return NULL;
}

/* Numbers of item k's pose a frame keeps: its position, and the rotation
 * of a body or frame. */
static int
pose_width(const eomc_model *m, int k)
{
    int kind = m->draw_items[k].kind;
    return kind == EOMC_DRAW_BODY || kind == EOMC_DRAW_FRAME ? 12 : 3;
}

Anim *
anim_new(eomc_sim *sim, const char *path)
{
    const eomc_model *m = eomc_sim_model(sim);
    Anim *a = calloc(1, sizeof *a);
    if (!a)
        return NULL;
    a->sim = sim, a->m = m, a->path = path, a->stride = 1;
    a->width = 1 + m->nout;
    for (int k = 0; k < m->ndraw; k++)
        a->width += pose_width(m, k);
    a->max_frames = ANIM_MAX_TEXT / ((long)a->width * NUM_TEXT);
    if (a->max_frames > ANIM_MAX_FRAMES)
        a->max_frames = ANIM_MAX_FRAMES;
    if (a->max_frames < 2)
        a->max_frames = 2;
    a->cap = 2 * a->max_frames;
    a->frames = malloc((size_t)a->cap * (size_t)a->width * sizeof(double));
    a->last = malloc((size_t)a->width * sizeof(double));
    a->X = malloc((size_t)m->ndraw * EOMC_POSE * sizeof(double));
    if (!a->frames || !a->last || !a->X) {
        anim_free(a);
        return NULL;
    }
    return a;
}

void
anim_free(Anim *a)
{
    if (!a)
        return;
    free(a->frames);
    free(a->last);
    free(a->X);
    free(a);
}

/* Keep every other frame (the first, third, ...), the stride doubled. */
static void
thin(Anim *a)
{
    long j = 0;
    for (long i = 0; i < a->n; i += 2, j++)
        memmove(a->frames + j * a->width, a->frames + i * a->width,
                (size_t)a->width * sizeof(double));
    a->n = j;
    a->stride *= 2;
}

int
anim_row(Anim *a, double t, const double *x, const double *out)
{
    const eomc_model *m = a->m;
    const double *u = m->nu ? sim_inputs_at(a->sim, t) : NULL;
    double *f = a->last;
    m->draw(t, x, sim_p(a->sim), u, a->X);
    int at = 0;
    f[at++] = t;
    for (int k = 0; k < m->nout; k++)
        f[at++] = out[k];
    for (int k = 0; k < m->ndraw; k++) {
        int w = pose_width(m, k);
        memcpy(f + at, a->X + k * EOMC_POSE, (size_t)w * sizeof(double));
        at += w;
    }
    a->last_kept = a->seen % a->stride == 0;
    if (a->last_kept) {
        if (a->n == a->cap) {
            thin(a);
            a->last_kept = a->seen % a->stride == 0;
        }
        if (a->last_kept)
            memcpy(a->frames + a->n++ * a->width, f, (size_t)a->width * sizeof(double));
    }
    a->seen++;
    return EOMC_OK;
}

/* The uniform box of the same mass and inertia.  For a box of half-sizes
 * a_1, a_2, a_3 and mass m, the principal moments are
 * I_1 = m (a_2^2 + a_3^2) / 3 (and cyclically), so
 * a_i^2 = 3 (I_j + I_k - I_i) / (2 m). */
int
anim_equivalent_box(double mass, const double *I, double *half, double *R)
{
    double A[9], ev[3];
    memcpy(A, I, sizeof A);
    gsl_matrix_view Av = gsl_matrix_view_array(A, 3, 3);
    gsl_vector_view evv = gsl_vector_view_array(ev, 3);
    gsl_matrix_view Rv = gsl_matrix_view_array(R, 3, 3);
    gsl_eigen_symmv_workspace *w = gsl_eigen_symmv_alloc(3);
    int bad = !w || gsl_eigen_symmv(&Av.matrix, &evv.vector, &Rv.matrix, w) != 0;
    gsl_eigen_symmv_free(w);
    if (!bad) /* a rotation: det R = +1 */ {
        double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                     R[2] * (R[3] * R[7] - R[4] * R[6]);
        if (det < 0)
            for (int i = 0; i < 3; i++)
                R[3 * i + 2] = -R[3 * i + 2];
    }
    double big = 0;
    for (int i = 0; i < 3 && !bad; i++) {
        double s = 3 * (ev[(i + 1) % 3] + ev[(i + 2) % 3] - ev[i]) / (2 * mass);
        bad = !(mass > 0) || !(s >= -1e-12 * fabs(ev[i] + ev[(i + 1) % 3]) / mass) || !isfinite(s);
        half[i] = sqrt(fmax(s, 0));
        big = fmax(big, half[i]);
    }
    if (bad) {
        for (int i = 0; i < 9; i++)
            R[i] = i % 4 == 0;
        half[0] = half[1] = half[2] = 0;
        return -1;
    }
    for (int i = 0; i < 3; i++) /* a flat or thin body: still something to see */
        half[i] = fmax(half[i], 0.02 * big);
    return 0;
}

static void
put_num(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.6g", x);
    else
        fputs("null", f);
}

static void
put_nums(FILE *f, const double *x, int n)
{
    fputc('[', f);
    for (int i = 0; i < n; i++) {
        if (i)
            fputc(',', f);
        put_num(f, x[i]);
    }
    fputc(']', f);
}

/* A JSON string, safe inside <script> ("</" never appears). */
static void
put_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20 || ch == '<' || ch == '>' || ch == '&')
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

static int
copy_file(FILE *to, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    char buf[1 << 16];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        fwrite(buf, 1, n, to);
    int bad = ferror(f);
    fclose(f);
    return bad ? -1 : 0;
}

static const char *const kind_names[] = {"body", "particle", "point", "frame"};

/* The scene and the trajectory: the page's JSON. */
static void
put_json(FILE *f, const Anim *a)
{
    const eomc_model *m = a->m;
    double *D = m->draw_mass ? calloc((size_t)m->ndraw * EOMC_DRAW_MASS, sizeof *D) : NULL;
    if (D)
        m->draw_mass(sim_p(a->sim), D);
    fputs("{\"name\":", f);
    put_str(f, m->name);
    fputs(",\"items\":[", f);
    int planar = 1;
    for (int k = 0; k < m->ndraw; k++) {
        const eomc_draw_item *it = &m->draw_items[k];
        int kind = it->kind >= 0 && it->kind < 4 ? it->kind : EOMC_DRAW_POINT;
        /* the bodies and particles decide: a point, a frame or the origin
         * is 3-D for the compiler, yet in a planar spec it lies in z = 0 */
        if (kind == EOMC_DRAW_BODY || kind == EOMC_DRAW_PARTICLE)
            planar &= it->dim == 2;
        fprintf(f, "%s{\"name\":", k ? "," : "");
        put_str(f, it->name);
        fprintf(f, ",\"kind\":\"%s\",\"dim\":%d", kind_names[kind], it->dim);
        int shaped = 0;
        for (int s = 0; s < m->nshape; s++)
            shaped |= m->shapes[s].item == k;
        if (kind == EOMC_DRAW_BODY && !shaped && D) {
            const double *d = D + (size_t)k * EOMC_DRAW_MASS;
            double half[3], R[9];
            anim_equivalent_box(d[0], d + 4, half, R);
            fprintf(f, ",\"mass\":");
            put_num(f, d[0]);
            fprintf(f, ",\"box\":{\"half\":");
            put_nums(f, half, 3);
            fprintf(f, ",\"centre\":");
            put_nums(f, d + 1, 3);
            fprintf(f, ",\"rot\":");
            put_nums(f, R, 9);
            fputc('}', f);
        }
        fputc('}', f);
    }
    free(D);
    fputs("],\"shapes\":[", f);
    for (int s = 0; s < m->nshape; s++) {
        const eomc_shape *sh = &m->shapes[s];
        fprintf(f, "%s{\"item\":%d,\"type\":%d,\"size\":", s ? "," : "", sh->item, sh->type);
        put_nums(f, sh->size, 3);
        fputs(",\"pos\":", f);
        put_nums(f, sh->pos, 3);
        fputs(",\"quat\":", f);
        put_nums(f, sh->quat, 4);
        fputs(",\"rgba\":", f);
        put_nums(f, sh->rgba, 4);
        fputc('}', f);
    }
    fputs("],\"links\":[", f);
    for (int l = 0; l < m->nlink; l++)
        fprintf(f, "%s[%d,%d]", l ? "," : "", m->view_links[2 * l], m->view_links[2 * l + 1]);
    fputs("],\"traces\":[", f);
    for (int l = 0; l < m->ntrace; l++)
        fprintf(f, "%s%d", l ? "," : "", m->view_trace[l]);
    fprintf(f, "],\"axes\":%d,\"planar\":%s,\"outputs\":[", m->view_frames,
            planar ? "true" : "false");
    for (int k = 0; k < m->nout; k++) {
        if (k)
            fputc(',', f);
        put_str(f, m->out_names[k]);
    }
    fputs("],", f);
    /* the camera: the view's, else fitted to the motion's bounding box
     * (planar: looking down -z at the plane, x right, y up) */
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    long nf = a->n + !a->last_kept;
    for (long j = 0; j < nf; j++) {
        const double *fr = j < a->n ? a->frames + j * a->width : a->last;
        int at = 1 + m->nout;
        for (int k = 0; k < m->ndraw; k++) {
            for (int i = 0; i < 3; i++)
                if (isfinite(fr[at + i]))
                    lo[i] = fmin(lo[i], fr[at + i]), hi[i] = fmax(hi[i], fr[at + i]);
            at += pose_width(m, k);
        }
    }
    double c[3], ext = 0;
    for (int i = 0; i < 3; i++) {
        if (!(lo[i] <= hi[i]))
            lo[i] = hi[i] = 0;
        c[i] = (lo[i] + hi[i]) / 2;
        ext = fmax(ext, hi[i] - lo[i]);
    }
    if (!(ext > 0))
        ext = 1;
    const double fov = 45; /* degrees, vertical */
    double dist = 0.5 * ext / TAN_HALF_FOV * 1.35 + (hi[2] - lo[2]) / 2;
    double cam[9];
    if (m->view_camera) {
        memcpy(cam, m->view_camera, sizeof cam);
    } else if (planar) {
        double p[9] = {c[0], c[1], c[2] + dist, c[0], c[1], c[2], 0, 1, 0};
        memcpy(cam, p, sizeof cam);
    } else {
        double dir[3] = {0.55, -0.75, 0.38}, nd = sqrt(0.55 * 0.55 + 0.75 * 0.75 + 0.38 * 0.38);
        double p[9] = {c[0] + dist * dir[0] / nd, c[1] + dist * dir[1] / nd,
                       c[2] + dist * dir[2] / nd, c[0], c[1], c[2], 0, 0, 1};
        memcpy(cam, p, sizeof cam);
    }
    fputs("\"camera\":{\"position\":", f);
    put_nums(f, cam, 3);
    fputs(",\"target\":", f);
    put_nums(f, cam + 3, 3);
    fputs(",\"up\":", f);
    put_nums(f, cam + 6, 3);
    fprintf(f, ",\"fov\":%g},\"extent\":", fov);
    put_num(f, ext);
    fputs(",\"centre\":", f);
    put_nums(f, c, 3);
    fputs(",\"low\":", f); /* the motion's lowest corner: the grid's height */
    put_nums(f, lo, 3);
    fprintf(f, ",\"stride\":%ld,\"rows\":%ld,\"width\":%d,\"frames\":[", a->stride, a->seen,
            a->width);
    for (long j = 0; j < nf; j++) {
        if (j)
            fputs(",\n", f);
        put_nums(f, j < a->n ? a->frames + j * a->width : a->last, a->width);
    }
    fputs("]}", f);
}

int
anim_write(Anim *a, const char *prog)
{
    if (a->seen == 0)
        return EOMC_OK;
    while (a->n > a->max_frames) /* thinned to the budget */
        thin(a);
    /* the last row seen, whether or not its stride kept it */
    a->last_kept = a->n > 0 && a->frames[(a->n - 1) * a->width] == a->last[0];
    size_t len = strlen(a->path) + 5;
    char *tmp = malloc(len), path[4096];
    FILE *f = tmp ? (snprintf(tmp, len, "%s.tmp", a->path), fopen(tmp, "w")) : NULL;
    if (!f) {
        fprintf(io_err(), "%s: --animate: cannot write %s: %s\n", prog, tmp ? tmp : a->path,
                strerror(errno));
        free(tmp);
        return EOMC_EUSAGE;
    }
    int bad = 0;
    fputs("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">\n<title>eomc</title>\n", f);
    /* errors are caught from the first script on */
    fputs("<script>window.eomcErrors=[];(function(){function put(s){window.eomcErrors.push(s);"
          "var e=document.getElementById('errors');if(e)e.textContent+=s+'\\n';}"
          "window.onerror=function(msg,src,line){put(msg+' ('+line+')');};"
          "var ce=console.error;console.error=function(){put(Array.prototype.join.call("
          "arguments,' '));ce.apply(console,arguments);};})();</script>\n", f);
    for (int k = 0; k < 2 && !bad; k++) {
        fputs("<script>\n", f);
        snprintf(path, sizeof path, "%s/%s", anim_three_dir(), three_files[k]);
        if (copy_file(f, path) != 0) {
            fprintf(io_err(), "%s: --animate: cannot read %s\n", prog, path);
            bad = 1;
        }
        fputs("\n</script>\n", f);
    }
    fputs("<script id=\"eomc-data\" type=\"application/json\">\n", f);
    put_json(f, a);
    fputs("\n</script>\n</head><body>\n<pre id=\"errors\"></pre>\n<script>\n", f);
    for (int k = 0; anim_page_js[k]; k++)
        fputs(anim_page_js[k], f);
    fputs("\n</script>\n</body></html>\n", f);
    if (fclose(f) != 0 && !bad) {
        fprintf(io_err(), "%s: --animate: cannot write %s: %s\n", prog, tmp, strerror(errno));
        bad = 1;
    }
    if (!bad && rename(tmp, a->path) != 0) {
        fprintf(io_err(), "%s: --animate: cannot write %s: %s\n", prog, a->path,
                strerror(errno));
        bad = 1;
    }
    if (bad)
        remove(tmp);
    free(tmp);
    return bad ? EOMC_EUSAGE : EOMC_OK;
}
