/*
 * lowered: the lookups on a lowered model (lowered.h).
 */
#include "lowered.h"

#include <stdlib.h>
#include <string.h>

void
lower_args(const LowSig *sig, LowArgs *a)
{
    a->n = 0;
    a->nin = -1;
    for (const char *p = sig->args; *p;) {
        p += strspn(p, " ");
        if (*p == '>') {
            a->nin = a->n;
            p++;
            continue;
        }
        size_t len = strcspn(p, " ?");
        if (len == 0)
            break;
        if (a->n == LOW_MAX_ARGS || len >= sizeof a->name[0])
            abort(); /* the signatures are ours */
        memcpy(a->name[a->n], p, len);
        a->name[a->n][len] = '\0';
        p += len;
        a->optional[a->n] = *p == '?';
        p += *p == '?';
        a->n++;
    }
    if (a->nin < 0)
        a->nin = a->n;
}

int
lower_size(const LowFunc *f, int arg)
{
    int size = f->fill[arg];
    for (int k = 0; k < f->nout; k++)
        if (f->out[k].arg == arg && f->out[k].index + 1 > size)
            size = f->out[k].index + 1;
    int copied = f->copy ? lower_size(f->copy, arg) : 0;
    const int *d = f->dv ? f->dv : f->dq; /* the outputs' shifts */
    for (int c = 0; copied && c < f->ncopy; c++)
        if (copied + d[c] > size)
            size = copied + d[c];
    return size;
}

const LowFunc *
lower_find(const Lowered *L, const char *name)
{
    for (int k = 0; k < L->nfunc; k++)
        if (!strcmp(L->func[k]->sig->name, name))
            return L->func[k];
    return NULL;
}
