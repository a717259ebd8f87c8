/*
 * emit_taylor: the model's taylor member (eomc_model.h) and its tables,
 * printed from the program lower_taylor made (lower.h's LowTaylor): one
 * call of runtime/eomc_taylor.h per step, slot s being the series at
 * T + s * S.  Compiled in double only.
 */
#include "emit_func.h"

/* A slot's series, "T + s * S". */
static void
print_slot(FILE *f, int s)
{
    if (s == 0)
        fputs("T", f);
    else
        fprintf(f, "T + %d * S", s);
}

/* "static const int NAME[n] = {...};", twenty a line. */
static void
print_ints(Printer *pr, const char *name, const int *x, int n)
{
    fprintf(pr->f, "static const int %s[%d] = {", name, n);
    for (int i = 0; i < n; i++)
        fprintf(pr->f, "%s%d", i == 0 ? "" : i % 20 ? ", " : ",\n    ", x[i]);
    emit_line(pr, "};");
}

void
emit_taylor(Printer *pr, const LowTaylor *ty)
{
    if (ty->why)
        return;
    const LowModel *md = pr->md;
    FILE *f = pr->f;
    int n = md->nq;
    emit_line(pr, "/* Taylor's method (eomc_taylor.h): coefficient k of the series about t0");
    emit_line(pr, " * of every value mass_bias and events compute, slot s's at T[s (K + 1)");
    emit_line(pr, " * ...], from their orders 0 .. k-1 and the caller's coefficient k of q");
    emit_line(pr, " * and q' (taylor_q, taylor_v): %d slots, %d calls. */", ty->nslot,
              ty->nstep);
    char fname[128];
    snprintf(fname, sizeof fname, "%s_taylor", md->name);
    emit_head(pr, "static void", fname,
              "int k, int K, double t0, const double *p, const double *u, double *T");
    emit_line(pr, "    const int S = K + 1;");
    if (!ty->nstep)
        emit_line(pr, "    (void)k, (void)S, (void)T;");
    if (!ty->reads_t)
        emit_line(pr, "    (void)t0;");
    if (!ty->reads_p)
        emit_line(pr, "    (void)p;");
    if (!ty->reads_u)
        emit_line(pr, "    (void)u;");
    for (int i = 0; i < ty->nstep; i++) {
        const LowTayStep *st = &ty->step[i];
        fprintf(f, "    eomc_tay_%s(", st->call);
        for (int j = 0; j < st->nslot; j++) {
            if (j)
                fputs(", ", f);
            print_slot(f, st->slot[j]);
        }
        char num[40];
        switch (st->src) {
        case LOW_TAY_SRC_CONST:
            emit_const(num, sizeof num, st->value);
            fprintf(f, ", %s", num);
            break;
        case LOW_TAY_SRC_P:
            fprintf(f, ", p[%d]", st->index);
            break;
        case LOW_TAY_SRC_U:
            fprintf(f, ", u[%d]", st->index);
            break;
        case LOW_TAY_SRC_T:
            fputs(", t0", f);
            break;
        }
        emit_line(pr, ", k);");
    }
    emit_line(pr, "}\n");
    emit_line(pr, "/* The slots of q and q' the caller writes, and those of M (row-major),");
    emit_line(pr, " * h and the event functions g (-1: none, or zero at every order). */");
    print_ints(pr, "taylor_q", ty->q_slot, n);
    print_ints(pr, "taylor_v", ty->v_slot, n);
    print_ints(pr, "taylor_M", ty->M_slot, n * n);
    print_ints(pr, "taylor_h", ty->h_slot, n);
    if (ty->nevent)
        print_ints(pr, "taylor_g", ty->g_slot, ty->nevent);
    emit_line(pr, "");
}
