/*
 * arena: bump allocation for everything the compiler builds (spec model,
 * names, expression side tables).  Nothing is freed piecemeal; arena_free
 * releases it all at once.
 */
#ifndef EOMC_ARENA_H
#define EOMC_ARENA_H

#include <stddef.h>
#include <stdio.h>

typedef struct Arena Arena;

Arena *arena_new(void);
void arena_free(Arena *a);
/* Zeroed, aligned for any type; never returns NULL (dies on OOM). */
void *arena_alloc(Arena *a, size_t size);
char *arena_strdup(Arena *a, const char *s);
char *arena_strndup(Arena *a, const char *s, size_t n);
char *arena_printf(Arena *a, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

#define arena_new_array(a, T, n) ((T *)arena_alloc((a), sizeof(T) * (size_t)(n)))

/* Die with a message on allocation failure (shared by every module). */
void *xmalloc(size_t n);
void *xrealloc(void *p, size_t n);
/* open_memstream, dying as they do when it cannot. */
FILE *xmemstream(char **buf, size_t *len);

#endif
