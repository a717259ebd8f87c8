/*
 * Shared by the fuzz targets: the libFuzzer entry point they define, and
 * how they run one input.
 *
 * Parsing, differentiation and emission recurse as deep as an expression
 * is high (parse.c allows 10 000; derivatives are higher, and sanitizer
 * frames are large), so, like main.c, inputs run on a thread with a
 * 512 MB stack (address space only).  Diagnostics go to /dev/null: almost
 * every input is an error, and formatting it is still exercised.
 */
#ifndef EOMC_FUZZ_H
#define EOMC_FUZZ_H

#include <stddef.h>
#include <stdint.h>

/* Each target defines its entry as FUZZ_ENTRY(name) { ... }: libFuzzer's
 * LLVMFuzzerTestOneInput, or, in the replay program (replay.c, built
 * with -DFUZZ_REPLAY and without libFuzzer), fuzz_NAME, so that one
 * program replays every target's regression inputs. */
#ifdef FUZZ_REPLAY
#define FUZZ_ENTRY(name) int fuzz_##name(const uint8_t *data, size_t size)
FUZZ_ENTRY(spec);
FUZZ_ENTRY(expr);
FUZZ_ENTRY(pipeline);
FUZZ_ENTRY(runtime);
#else
#define FUZZ_ENTRY(name) int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
FUZZ_ENTRY(any);
#endif

/* Run fn(ctx) on the big stack, with diagnostics silenced; returns when
 * it has.  (The compiler's targets; fuzz_runtime calls the simulator's
 * command line directly.) */
void fuzz_run(void (*fn)(void *ctx), void *ctx);

#endif
