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
/* tan and sin of 45 / 2 degrees: the camera's vertical field of view is
 * 45 degrees. */
#define TAN_HALF_FOV 0.41421356237309503
#define SIN_HALF_FOV 0.38268343236508978

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
    const double *u = m->nu ? sim_inputs_at(a->sim, t, x, x + m->nq) : NULL;
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

/* Two principal moments are the same when they differ by less than this
 * fraction of the trace: far above the eigensolver's rounding, far below
 * a difference one could see. */
#define SAME_MOMENT 1e-9
/* A flat or thin solid's least half-size, as a fraction of its largest:
 * still something to see. */
#define THIN 0.02
/* A principal moment below zero by this fraction of the trace is
 * rounding, not a body that no mass could have. */
#define ROUNDING 1e-12

/* The uniform solid of the same mass and inertia.  For a box of
 * half-sizes a_1, a_2, a_3 and mass m, the principal moments are
 * I_1 = m (a_2^2 + a_3^2) / 3 (and cyclically), so
 * a_i^2 = 3 (I_j + I_k - I_i) / (2 m).  For a cylinder of radius r and
 * half-length h, I_axis = m r^2 / 2 and I_across = m (r^2 / 4 + h^2 / 3),
 * so r^2 = 2 I_axis / m and h^2 = 3 (I_across - I_axis / 2) / m; a
 * planar body's moment J about z alone is a disk's, r^2 = 2 J / m. */
int
anim_equivalent_solid(double mass, const double *I, double *half, double *R)
{
    for (int i = 0; i < 9; i++)
        R[i] = i % 4 == 0;
    half[0] = half[1] = half[2] = 0;
    int planar = 1;
    for (int i = 0; i < 8; i++)
        planar &= I[i] == 0;
    if (planar) {
        if (!(mass > 0 && I[8] > 0 && isfinite(I[8] / mass)))
            return -1;
        double r = sqrt(2 * I[8] / mass);
        half[0] = half[1] = r, half[2] = THIN * r;
        return EOMC_SHAPE_CYLINDER;
    }
    double A[9], ev[3];
    memcpy(A, I, sizeof A);
    gsl_matrix_view Av = gsl_matrix_view_array(A, 3, 3);
    gsl_vector_view evv = gsl_vector_view_array(ev, 3);
    gsl_matrix_view Rv = gsl_matrix_view_array(R, 3, 3);
    gsl_eigen_symmv_workspace *w = gsl_eigen_symmv_alloc(3);
    int bad = !w || gsl_eigen_symmv(&Av.matrix, &evv.vector, &Rv.matrix, w) != 0;
    gsl_eigen_symmv_free(w);
    double tr = fabs(ev[0]) + fabs(ev[1]) + fabs(ev[2]);
    bad = bad || !(mass > 0) || !isfinite(tr / mass);
    if (!bad) /* a rotation: det R = +1 */ {
        double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                     R[2] * (R[3] * R[7] - R[4] * R[6]);
        if (det < 0)
            for (int i = 0; i < 3; i++)
                R[3 * i + 2] = -R[3 * i + 2];
    }
    int axis = -1; /* the moment unlike the other two */
    for (int i = 0; i < 3 && !bad; i++) {
        double a = ev[i], b = ev[(i + 1) % 3], c = ev[(i + 2) % 3];
        if (fabs(b - c) <= SAME_MOMENT * tr && fabs(a - b) > SAME_MOMENT * tr)
            axis = i;
    }
    int type = axis >= 0 ? EOMC_SHAPE_CYLINDER : EOMC_SHAPE_BOX;
    if (axis >= 0) {
        double Ia = ev[axis], Ip = (ev[(axis + 1) % 3] + ev[(axis + 2) % 3]) / 2;
        double r2 = 2 * Ia / mass, h2 = 3 * (Ip - Ia / 2) / mass;
        bad = !(r2 > 0) || !(h2 >= -ROUNDING * tr / mass);
        half[0] = half[1] = sqrt(fmax(r2, 0)), half[2] = sqrt(fmax(h2, 0));
        double P[9]; /* the axis as the third column: a cyclic turn of the columns */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                P[3 * i + j] = R[3 * i + (axis + 1 + j) % 3];
        memcpy(R, P, sizeof P);
    } else {
        for (int i = 0; i < 3 && !bad; i++) {
            double s = 3 * (ev[(i + 1) % 3] + ev[(i + 2) % 3] - ev[i]) / (2 * mass);
            bad = !(s >= -ROUNDING * tr / mass);
            half[i] = sqrt(fmax(s, 0));
        }
    }
    if (bad) {
        for (int i = 0; i < 9; i++)
            R[i] = i % 4 == 0;
        half[0] = half[1] = half[2] = 0;
        return -1;
    }
    double big = fmax(half[0], fmax(half[1], half[2]));
    for (int i = 0; i < 3; i++)
        half[i] = fmax(half[i], THIN * big);
    return type;
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

/* How far a shape of type type and size z reaches from its centre. */
static double
shape_reach(int type, const double *z)
{
    switch (type) {
    case EOMC_SHAPE_BOX: return sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    case EOMC_SHAPE_SPHERE: return z[0];
    case EOMC_SHAPE_CAPSULE: return z[0] + z[1];
    case EOMC_SHAPE_CYLINDER: return hypot(z[0], z[1]);
    default: return fmax(z[0], fmax(z[1], z[2]));
    }
}

static double
norm3(const double *x)
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

/* What the page draws of each item besides its pose, with the run's
 * parameters: the shapes' sizes and positions, each unshaped body's
 * equivalent solid, and how far the drawing reaches from the pose. */
typedef struct Look {
    double *S;      /* [nshape EOMC_SHAPE_NUMS] each shape's size and position */
    char *shown;    /* [nshape] its numbers can be drawn */
    int *solid;     /* [ndraw] an unshaped body's EOMC_SHAPE_*, else -1 */
    double *half;   /* [ndraw 3] and its half-sizes (animate.h) */
    double *rot;    /* [ndraw 9] its axes */
    double *centre; /* [ndraw 3] its centre in the body's frame */
    double *mass;   /* [ndraw] */
    double *reach;  /* [ndraw] */
    int follow;     /* the item the camera follows, or -1 */
} Look;

static void
look_free(Look *l)
{
    free(l->S), free(l->shown), free(l->solid), free(l->half), free(l->rot);
    free(l->centre), free(l->mass), free(l->reach);
}

/* The look of a's model with its parameters, saying on stderr what will
 * not be drawn as the model has it: a body drawn unturned, a shape whose
 * numbers cannot be drawn, a followed item that is not drawn.  0, or -1
 * when out of memory. */
static int
look_at(Look *l, const Anim *a, const char *prog)
{
    const eomc_model *m = a->m;
    int nd = m->ndraw, ns = m->nshape;
    *l = (Look){
        .S = malloc(((size_t)ns * EOMC_SHAPE_NUMS + 1) * sizeof(double)),
        .shown = calloc((size_t)ns + 1, 1),
        .solid = malloc(((size_t)nd + 1) * sizeof(int)),
        .half = calloc((size_t)nd * 3 + 1, sizeof(double)),
        .rot = calloc((size_t)nd * 9 + 1, sizeof(double)),
        .centre = calloc((size_t)nd * 3 + 1, sizeof(double)),
        .mass = calloc((size_t)nd + 1, sizeof(double)),
        .reach = calloc((size_t)nd + 1, sizeof(double)),
        .follow = -1};
    double *D = m->draw_mass ? calloc((size_t)nd * EOMC_DRAW_MASS, sizeof *D) : NULL;
    if (!l->S || !l->shown || !l->solid || !l->half || !l->rot || !l->centre || !l->mass ||
        !l->reach || (m->draw_mass && !D)) {
        free(D);
        look_free(l);
        return -1;
    }
    const double *p = sim_p(a->sim);
    if (D)
        m->draw_mass(p, D);
    for (int k = 0; k < ns; k++) {
        double *z = l->S + (size_t)k * EOMC_SHAPE_NUMS;
        memcpy(z, m->shapes[k].size, 3 * sizeof *z);
        memcpy(z + 3, m->shapes[k].pos, 3 * sizeof *z);
    }
    if (m->draw_shapes && ns)
        m->draw_shapes(p, l->S);
    static const int nsize[] = {[EOMC_SHAPE_BOX] = 3, [EOMC_SHAPE_SPHERE] = 1,
                                [EOMC_SHAPE_CAPSULE] = 2, [EOMC_SHAPE_CYLINDER] = 2,
                                [EOMC_SHAPE_ELLIPSOID] = 3};
    for (int k = 0; k < ns; k++) {
        const double *z = l->S + (size_t)k * EOMC_SHAPE_NUMS;
        int type = m->shapes[k].type;
        int ok = m->shapes[k].item >= 0 && m->shapes[k].item < nd && type >= 0 && type < 5;
        for (int i = 0; i < 3 && ok; i++)
            ok &= (i >= nsize[type] || (z[i] > 0 && isfinite(z[i]))) && isfinite(z[3 + i]);
        l->shown[k] = (char)ok;
        if (!ok)
            fprintf(io_err(), "%s: --animate: warning: a shape of '%s' has size [%g, %g, %g] at "
                    "[%g, %g, %g] with these parameters (a size must be positive): it is not "
                    "drawn (its body is drawn as its uniform solid if none is)\n", prog,
                    m->shapes[k].item >= 0 && m->shapes[k].item < nd
                        ? m->draw_items[m->shapes[k].item].name : "no item",
                    z[0], z[1], z[2], z[3], z[4], z[5]);
        else
            l->reach[m->shapes[k].item] = fmax(l->reach[m->shapes[k].item],
                                               norm3(z + 3) + shape_reach(m->shapes[k].type, z));
    }
    for (int k = 0; k < nd; k++) {
        const eomc_draw_item *it = &m->draw_items[k];
        int shaped = 0;
        for (int s = 0; s < ns; s++) /* else its solid stands for it */
            shaped |= m->shapes[s].item == k && l->shown[s];
        l->solid[k] = -1;
        if (it->kind == EOMC_DRAW_BODY && !shaped && D) {
            const double *d = D + (size_t)k * EOMC_DRAW_MASS;
            l->solid[k] = anim_equivalent_solid(d[0], d + 4, l->half + 3 * k, l->rot + 9 * k);
            l->mass[k] = d[0];
            memcpy(l->centre + 3 * k, d + 1, 3 * sizeof(double));
            l->reach[k] = norm3(d + 1) + norm3(l->half + 3 * k);
        }
        if (it->kind == EOMC_DRAW_BODY && it->unturned)
            fprintf(io_err(), "%s: --animate: warning: body '%s' is drawn unturned: the model "
                    "gives its angular velocity (`omega:`) but not its orientation; give it a "
                    "`frame:` or a `rotation:` to see it turn\n", prog, it->name);
        if (m->view_follow && it->name && !strcmp(it->name, m->view_follow) && l->follow < 0)
            l->follow = k;
    }
    if (m->view_follow && l->follow < 0)
        fprintf(io_err(), "%s: --animate: warning: the camera cannot follow '%s': it is not "
                "drawn\n", prog, m->view_follow);
    free(D);
    return 0;
}

/* The scene and the trajectory: the page's JSON. */
static void
put_json(FILE *f, const Anim *a, const Look *l)
{
    const eomc_model *m = a->m;
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
        fprintf(f, ",\"kind\":\"%s\",\"dim\":%d,\"reach\":", kind_names[kind], it->dim);
        put_num(f, l->reach[k]);
        if (kind == EOMC_DRAW_BODY && it->unturned)
            fputs(",\"unturned\":true", f);
        if (l->solid[k] >= 0) {
            fprintf(f, ",\"mass\":");
            put_num(f, l->mass[k]);
            fprintf(f, ",\"solid\":{\"type\":\"%s\",\"half\":",
                    l->solid[k] == EOMC_SHAPE_CYLINDER ? "cylinder" : "box");
            put_nums(f, l->half + 3 * k, 3);
            fprintf(f, ",\"centre\":");
            put_nums(f, l->centre + 3 * k, 3);
            fprintf(f, ",\"rot\":");
            put_nums(f, l->rot + 9 * k, 9);
            fputc('}', f);
        }
        fputc('}', f);
    }
    fputs("],\"shapes\":[", f);
    for (int s = 0, n = 0; s < m->nshape; s++) {
        const eomc_shape *sh = &m->shapes[s];
        if (!l->shown[s])
            continue;
        fprintf(f, "%s{\"item\":%d,\"type\":%d,\"size\":", n++ ? "," : "", sh->item, sh->type);
        put_nums(f, l->S + (size_t)s * EOMC_SHAPE_NUMS, 3);
        fputs(",\"pos\":", f);
        put_nums(f, l->S + (size_t)s * EOMC_SHAPE_NUMS + 3, 3);
        fputs(",\"quat\":", f);
        put_nums(f, sh->quat, 4);
        fputs(",\"rgba\":", f);
        put_nums(f, sh->rgba, 4);
        fputc('}', f);
    }
    fputs("],\"links\":[", f);
    for (int i = 0; i < m->nlink; i++)
        fprintf(f, "%s[%d,%d]", i ? "," : "", m->view_links[2 * i], m->view_links[2 * i + 1]);
    fputs("],\"traces\":[", f);
    for (int i = 0; i < m->ntrace; i++)
        fprintf(f, "%s%d", i ? "," : "", m->view_trace[i]);
    fprintf(f, "],\"axes\":%d,\"planar\":%s,\"outputs\":[", m->view_frames,
            planar ? "true" : "false");
    for (int k = 0; k < m->nout; k++) {
        if (k)
            fputc(',', f);
        put_str(f, m->out_names[k]);
    }
    fputs("],", f);
    /* the camera: the view's, else fitted from outside to the bounding box
     * of everything drawn over the motion, each item's drawing as a ball
     * of its reach about its pose, and (3-D) the ground's height (planar:
     * looking down -z at the plane, x right, y up) */
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    long nf = a->n + !a->last_kept;
    for (long j = 0; j < nf; j++) {
        const double *fr = j < a->n ? a->frames + j * a->width : a->last;
        int at = 1 + m->nout;
        for (int k = 0; k < m->ndraw; k++) {
            for (int i = 0; i < 3; i++)
                if (isfinite(fr[at + i]))
                    lo[i] = fmin(lo[i], fr[at + i] - l->reach[k]),
                    hi[i] = fmax(hi[i], fr[at + i] + l->reach[k]);
            at += pose_width(m, k);
        }
    }
    if (!planar) /* and the ground under it, which the grid draws */
        lo[2] = fmin(lo[2], m->view_floor), hi[2] = fmax(hi[2], m->view_floor);
    double c[3], ext = 0, ball = 0;
    for (int i = 0; i < 3; i++) {
        if (!(lo[i] <= hi[i]))
            lo[i] = hi[i] = 0;
        c[i] = (lo[i] + hi[i]) / 2;
        ext = fmax(ext, hi[i] - lo[i]);
    }
    if (!(ext > 0))
        ext = 1;
    if (!planar)
        ball = fabs(c[2] - m->view_floor);
    for (long j = 0; j < nf && !planar; j++) { /* the ball about c that holds it all */
        const double *fr = j < a->n ? a->frames + j * a->width : a->last;
        int at = 1 + m->nout;
        for (int k = 0; k < m->ndraw; k++) {
            double d[3] = {fr[at] - c[0], fr[at + 1] - c[1], fr[at + 2] - c[2]};
            if (isfinite(norm3(d)))
                ball = fmax(ball, norm3(d) + l->reach[k]);
            at += pose_width(m, k);
        }
    }
    const double fov = 45; /* degrees, vertical */
    double dist;
    if (planar) /* the plane's box fills 1 / 1.35 of the view's height */
        dist = 0.5 * ext / TAN_HALF_FOV * 1.35 + (hi[2] - lo[2]) / 2;
    else /* that ball in the view's cone, and a tenth more: the page's bar
          * covers the bottom of the view */
        dist = 1.1 * fmax(ball, 0.5 * ext) / SIN_HALF_FOV;
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
    fprintf(f, ",\"fov\":%g,\"given\":%s},\"extent\":", fov, m->view_camera ? "true" : "false");
    put_num(f, ext);
    fputs(",\"centre\":", f);
    put_nums(f, c, 3);
    fputs(",\"floor\":", f); /* the view's: the grid's height (3-D) */
    put_num(f, m->view_floor);
    fprintf(f, ",\"follow\":%d,\"stride\":%ld,\"rows\":%ld,\"width\":%d,\"frames\":[", l->follow,
            a->stride, a->seen, a->width);
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
    Look look;
    if (look_at(&look, a, prog) != 0) {
        fprintf(io_err(), "%s: --animate: out of memory\n", prog);
        fclose(f);
        remove(tmp);
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
    put_json(f, a, &look);
    look_free(&look);
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
