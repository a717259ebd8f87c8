/*
 * build: run the C compiler on generated code.
 *
 * The runtime is found next to eomc: when eomc runs from its meson build
 * directory, the headers come from the source tree and the library from
 * the build tree; otherwise relative to eomc's own location, as the
 * configured bindir relates to includedir and libdir (so an installed tree
 * can be moved, or staged with DESTDIR).  EOMC_RUNTIME_INCLUDE and
 * EOMC_RUNTIME_LIB override both.
 */
#define _XOPEN_SOURCE 700 /* realpath */
#define _GNU_SOURCE       /* posix_spawn_file_actions_addchdir_np */
#include "build.h"
#include "base/arena.h"
#include "config.h"
#include "emit/emit.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* The directory of the running eomc, or "" if unknown. */
static void
self_dir(char *dir, size_t len)
{
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    dir[0] = '\0';
    if (n <= 0)
        return;
    self[n] = '\0';
    char *slash = strrchr(self, '/');
    if (slash)
        *slash = '\0';
    snprintf(dir, len, "%s", self);
}

static int
running_from_build_dir(const char *self)
{
    char dir[PATH_MAX];
    if (!realpath(EOMC_BUILD_DIR, dir))
        return 0;
    size_t len = strlen(dir);
    return strncmp(self, dir, len) == 0 && (self[len] == '/' || !self[len]);
}

/* `to` relative to `from` (both absolute, normalised): /usr/bin and
 * /usr/include give ../include. */
static void
relative(const char *from, const char *to, char *out, size_t len)
{
    size_t common = 0;
    for (size_t i = 0; from[i] && from[i] == to[i]; i++)
        if (from[i] == '/')
            common = i + 1;
    out[0] = '\0';
    for (const char *p = from + common; *p; p++)
        if (p == from + common || p[-1] == '/')
            strncat(out, "../", len - strlen(out) - 1);
    strncat(out, to + common, len - strlen(out) - 1);
}

static void
runtime_paths(const char **inc, const char **lib)
{
    static char ibuf[PATH_MAX * 2 + 64], lbuf[PATH_MAX * 2 + 64];
    char self[PATH_MAX], rel[PATH_MAX];
    self_dir(self, sizeof self);
    if (running_from_build_dir(self)) {
        *inc = EOMC_SOURCE_DIR "/runtime/include";
        *lib = EOMC_BUILD_DIR "/runtime/libeomcrt.a";
    } else {
        relative(EOMC_BINDIR, EOMC_INCLUDEDIR, rel, sizeof rel);
        snprintf(ibuf, sizeof ibuf, "%s/%s", self, rel);
        relative(EOMC_BINDIR, EOMC_LIBDIR, rel, sizeof rel);
        snprintf(lbuf, sizeof lbuf, "%s/%s/libeomcrt.a", self, rel);
        *inc = ibuf;
        *lib = lbuf;
    }
    if (getenv("EOMC_RUNTIME_INCLUDE"))
        *inc = getenv("EOMC_RUNTIME_INCLUDE");
    if (getenv("EOMC_RUNTIME_LIB"))
        *lib = getenv("EOMC_RUNTIME_LIB");
}

/* Split a flags string like "-L/x -lgsl -lgslcblas -lm" into argv. */
static int
split_flags(char *flags, char **argv, int max)
{
    int n = 0;
    for (char *tok = strtok(flags, " \t\n"); tok && n < max; tok = strtok(NULL, " \t\n"))
        argv[n++] = tok;
    return n;
}

extern char **environ;

/* Start argv[0] (found on $PATH) on argv in directory dir (NULL: this
 * one); its pid, or -1 after printing why.  posix_spawn, where it can set
 * the directory: it does not copy eomc's memory as fork does, whose
 * commit a derivation of several gigabytes can make fail (ENOMEM) while
 * other programs hold the rest. */
static pid_t
start_cc(char **argv, const char *dir)
{
    pid_t pid;
#if EOMC_HAVE_SPAWN_CHDIR
    posix_spawn_file_actions_t fa;
    int rc = posix_spawn_file_actions_init(&fa);
    if (rc == 0 && dir)
        rc = posix_spawn_file_actions_addchdir_np(&fa, dir);
    if (rc == 0)
        rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        fprintf(stderr, "eomc: cannot run %s%s%s: %s\n", argv[0], dir ? " in " : "",
                dir ? dir : "", strerror(rc));
        return -1;
    }
#else
    pid = fork();
    if (pid < 0) {
        fprintf(stderr, "eomc: cannot start %s: %s\n", argv[0], strerror(errno));
        return -1;
    }
    if (pid == 0) {
        if (dir && chdir(dir) != 0) {
            fprintf(stderr, "eomc: cannot enter %s: %s\n", dir, strerror(errno));
            _exit(127);
        }
        execvp(argv[0], argv);
        fprintf(stderr, "eomc: cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
#endif
    return pid;
}

/* The exit status of pid, or -1 if it did not exit. */
static int
exit_status(pid_t pid)
{
    int status;
    if (pid < 0)
        return -1;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Wait for a compiler started by start_cc: 0 if it succeeded, else -1
 * after printing why. */
static int
wait_cc(pid_t pid, const char *cc)
{
    if (pid < 0)
        return -1;
    int st = exit_status(pid);
    if (st != 0) {
        if (st != 127) /* 127: said why */
            fprintf(stderr, "eomc: %s failed on the generated code\n", cc);
        return -1;
    }
    return 0;
}

int
build_is_special(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

/* path's directory and a file name in it: "dir/name". */
static char *
sibling(const char *path, const char *name)
{
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path + 1) : 0, len = strlen(name) + 1;
    char *out = xmalloc(dir + len);
    memcpy(out, path, dir);
    memcpy(out + dir, name, len);
    return out;
}

/* Write text to path; 0, or -1 after printing why. */
static int
write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

/* The reference solution's functions are the same file compiled again
 * in extended precision: a second translation unit that includes it with
 * EOMC_EXTENDED defined.  Returns its path, or NULL after printing why. */
static char *
write_extended_unit(const char *c_file)
{
    char *ext = sibling(c_file, "model_ext.c");
    const char *base = strrchr(c_file, '/');
    char text[PATH_MAX + 64];
    snprintf(text, sizeof text, "#define EOMC_EXTENDED 1\n#include \"%s\"\n",
             base ? base + 1 : c_file);
    if (write_text(ext, text) != 0) {
        free(ext);
        return NULL;
    }
    return ext;
}

/* The simulator's main, or the library's entry points (eomc_main.h), in a
 * unit of their own: the model's units are then the same for a simulator,
 * a library and an MPI sweep, and are compiled once for all of them (the
 * object cache).  Returns its path, or NULL after printing why. */
static char *
write_main_unit(const char *c_file, const char *model)
{
    char *path = sibling(c_file, "main.c");
    size_t len = 6 * strlen(model) + 512;
    char *text = xmalloc(len);
    snprintf(text, len,
             "/* eomc build: the main of %s's simulator (eomc_main.h) */\n"
             "#include \"eomc_main.h\"\n"
             "extern const eomc_model %s_model;\n"
             "#if defined(__GNUC__) /* NULL where the twin is not linked */\n"
             "extern const eomc_model_ext %s_model_ext __attribute__((weak));\n"
             "#else\n"
             "extern const eomc_model_ext %s_model_ext;\n"
             "#endif\n"
             "EOMC_DEFINE_MAIN(%s_model, %s_model_ext)\n",
             model, model, model, model, model, model);
    int rc = write_text(path, text);
    free(text);
    if (rc != 0) {
        free(path);
        return NULL;
    }
    return path;
}

/* A 64-bit hash of bytes, fed in pieces, eight bytes at a time (a cache
 * key hashes eomc and the runtime library, megabytes, on every run):
 * FNV-1a's multiply on words, with the high bits folded back so that a
 * change anywhere reaches every bit of the next word's product. */
static const uint64_t hash_prime = 0x100000001b3u;
static const uint64_t hash_basis = 0xcbf29ce484222325u; /* FNV's offset basis */

static uint64_t
hash_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (; n >= 8; p += 8, n -= 8) {
        uint64_t w;
        memcpy(&w, p, 8);
        h = (h ^ w) * hash_prime;
        h ^= h >> 29;
    }
    for (; n; p++, n--)
        h = (h ^ *p) * hash_prime;
    return h;
}

/* A string and its length: "ab" + "c" never hashes as "a" + "bc". */
static uint64_t
hash_string(uint64_t h, const char *s)
{
    size_t n = strlen(s);
    h = hash_bytes(h, &n, sizeof n);
    return hash_bytes(h, s, n);
}

/* A file's bytes and length; a file that cannot be read hashes as that. */
static uint64_t
hash_file(uint64_t h, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return hash_string(h, "(unreadable)");
    static unsigned char buf[1 << 16];
    size_t n, total = 0;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        h = hash_bytes(h, buf, n);
        total += n;
    }
    int bad = ferror(f);
    fclose(f);
    h = hash_bytes(h, &total, sizeof total);
    return bad ? hash_string(h, "(unreadable)") : h;
}

/* The text of the C file that makes its unit k (1-4, emit.h): all but
 * the banner (a comment: it names the options, which need not change the
 * unit) and the sections of the other units, from their "#if
 * !defined(EOMC_UNIT) || EOMC_UNIT == j" to their "#endif /\* EOMC_UNIT j
 * *\/", with the blank line before them.  A simulator's C and a library's
 * differ in the banner and units 3 and 4 alone, so units 1 and 2 hash the
 * same for both, in double and in the twin. */
static const char unit_if[] = "#if !defined(EOMC_UNIT) || EOMC_UNIT == ";

static uint64_t
hash_unit_text(uint64_t h, const char *path, int k)
{
    FILE *f = fopen(path, "rb");
    char *text = NULL;
    size_t len = 0, cap = 0, n;
    while (f && !ferror(f)) {
        if (len + 1 >= cap)
            text = xrealloc(text, cap = 2 * cap + (1 << 16));
        if ((n = fread(text + len, 1, cap - len - 1, f)) == 0)
            break;
        len += n;
    }
    int bad = !f || ferror(f);
    if (f)
        fclose(f);
    if (bad) {
        free(text);
        return hash_string(h, "(unreadable)");
    }
    text[len] = '\0';
    const char *p = text, *end = text + len;
    if (!strncmp(p, "/*", 2) && (p = strstr(p, "*/")) != NULL)
        p += 2;
    else
        p = text;
    char open[64], close[64];
    const char *kept = p; /* the text since the last section left out */
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *next = nl ? nl + 1 : end;
        int j = !strncmp(p, unit_if, sizeof unit_if - 1) ? atoi(p + sizeof unit_if - 1) : 0;
        if (j > 0 && j != k) {
            snprintf(open, sizeof open, "%s%d\n", unit_if, j);
            snprintf(close, sizeof close, "\n#endif /* EOMC_UNIT %d */\n", j);
            const char *stop = !strncmp(p, open, strlen(open)) ? strstr(p, close) : NULL;
            if (stop) { /* the section left out, with the blank line before it */
                const char *cut = p > kept && p[-1] == '\n' && (p - 1 == kept || p[-2] == '\n')
                                      ? p - 1 : p;
                h = hash_bytes(h, kept, (size_t)(cut - kept));
                kept = next = stop + strlen(close);
            }
        }
        p = next;
    }
    h = hash_bytes(h, kept, (size_t)(end - kept));
    free(text);
    return h;
}

/* The headers of the runtime's include directory, every one, in name
 * order: whatever the generated code or the main includes. */
static uint64_t
hash_headers(uint64_t h, const char *inc)
{
    struct dirent **names;
    int n = scandir(inc, &names, NULL, alphasort);
    if (n < 0)
        return hash_string(h, "(no headers)");
    for (int k = 0; k < n; k++) {
        const char *name = names[k]->d_name;
        size_t len = strlen(name);
        if (len > 2 && !strcmp(name + len - 2, ".h")) {
            char path[PATH_MAX * 2 + 64];
            snprintf(path, sizeof path, "%s/%s", inc, name);
            h = hash_string(h, name);
            h = hash_file(h, path);
        }
        free(names[k]);
    }
    free(names);
    return h;
}

/* What a built simulator depends on besides its spec and options: eomc's
 * version and its own bytes (its generator), the C compiler named by $CC,
 * and the runtime it links: the library's bytes and the headers the
 * generated code includes.  By content, not by modification time: a
 * rebuilt runtime with the same bytes reuses the simulators built with
 * it, a changed one never does, whatever the clocks say.  Computed once
 * per invocation. */
static uint64_t
toolchain_hash(void)
{
    static uint64_t h;
    static int done;
    if (done)
        return h;
    const char *cc = getenv("CC"), *inc, *lib;
    runtime_paths(&inc, &lib);
    h = hash_string(hash_basis, EOMC_VERSION);
    h = hash_string(h, cc ? cc : "cc");
    h = hash_file(h, "/proc/self/exe");
    h = hash_file(h, lib);
    h = hash_headers(h, inc);
    done = 1;
    return h;
}

/* The programs a compiler command names (each word that is a file on
 * $PATH: "ccache cc" names two), by resolved path, size and modification
 * time, as ccache checks its compilers: a compiler upgraded or replaced
 * never serves an object it did not compile.  (Not by content: gcc's
 * programs are tens of megabytes, and its cc1 is not on $PATH.) */
static uint64_t
hash_compiler(uint64_t h, char **argv, int ncc)
{
    const char *path = getenv("PATH");
    for (int k = 0; k < ncc; k++) {
        const char *w = argv[k];
        if (w[0] == '-')
            continue;
        char file[PATH_MAX], real[PATH_MAX];
        struct stat st;
        int found = 0;
        if (strchr(w, '/')) {
            found = stat(w, &st) == 0 && snprintf(file, sizeof file, "%s", w) > 0;
        } else {
            for (const char *p = path ? path : "/usr/bin:/bin"; !found && *p;) {
                size_t len = strcspn(p, ":");
                snprintf(file, sizeof file, "%.*s/%s", (int)len, len ? p : ".", w);
                found = stat(file, &st) == 0 && S_ISREG(st.st_mode);
                p += len + (p[len] == ':');
            }
        }
        h = hash_string(h, found && realpath(file, real) ? real : w);
        if (found) {
            long long id[2] = {(long long)st.st_size, (long long)st.st_mtime};
            h = hash_bytes(h, id, sizeof id);
        }
    }
    return h;
}

/* The directory of eomc's cache, by the variables it is named by. */
static void
cache_root(char *dir, size_t len)
{
    const char *root = getenv("EOMC_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (root && *root)
        snprintf(dir, len, "%s", root);
    else if (xdg && *xdg)
        snprintf(dir, len, "%s/eomc", xdg);
    else
        snprintf(dir, len, "%s/.cache/eomc", home && *home ? home : "/tmp");
}

static int
make_dirs(char *path)
{
    for (char *p = path + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        int rc = mkdir(path, 0755);
        *p = '/';
        if (rc != 0 && errno != EEXIST)
            return -1;
    }
    if (mkdir(path, 0755) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

/* The object cache: each translation unit's object under a key of 128
 * bits (two lanes of hash_bytes, from two seeds) of everything that makes
 * it: toolchain_hash, the compiler (hash_compiler), the command line but
 * the output's name, and the bytes of the files compiled, of the model's
 * C the text its unit compiles (hash_unit_text).  A simulator, a library
 * and an MPI sweep of one model share the objects of its units 1 and 2
 * (a library's C adds to unit 3 alone); any change of what a unit
 * compiles, of the flags, the compiler, eomc or the runtime is another
 * key, so an object is never used for what it was not compiled from.  Objects are
 * written under a temporary name and renamed: two builds at once each
 * write a whole one. */
typedef struct UnitKey {
    char **argv;       /* the compile command, NULL-terminated */
    int ncc;           /* words of it that are the compiler */
    const char *out;   /* its output's name, left out of the key */
    const char *file;  /* the file it compiles, or NULL: the model's C */
    const char *model; /* the model's C it reads (the file or what it includes), or NULL */
    int unit;          /* of which this unit's text (hash_unit_text) */
} UnitKey;

/* The CPU -march=native compiles for: the first processor's lines of
 * /proc/cpuinfo but its clock (a cache shared between machines never
 * serves one an object with instructions it lacks); where there is no
 * such file, its absence. */
static uint64_t
cpu_hash(uint64_t h)
{
    static uint64_t cpu; /* read once per invocation, as toolchain_hash */
    static int done;
    if (!done) {
        FILE *f = fopen("/proc/cpuinfo", "r");
        char line[8192];
        cpu = hash_string(hash_basis, f ? "/proc/cpuinfo" : "(no /proc/cpuinfo)");
        while (f && fgets(line, sizeof line, f) && line[0] != '\n')
            if (strncmp(line, "cpu MHz", 7) != 0)
                cpu = hash_string(cpu, line);
        if (f)
            fclose(f);
        done = 1;
    }
    return hash_bytes(h, &cpu, sizeof cpu);
}

static uint64_t
unit_hash(uint64_t seed, const UnitKey *u)
{
    uint64_t h = hash_bytes(seed, &(uint64_t){toolchain_hash()}, sizeof(uint64_t));
    h = hash_compiler(h, u->argv, u->ncc);
    for (int k = 0; u->argv[k]; k++)
        if (u->argv[k] != u->out)
            h = hash_string(h, u->argv[k]);
    for (int k = 0; u->argv[k]; k++)
        if (strcmp(u->argv[k], "-march=native") == 0)
            h = cpu_hash(h);
    if (u->file)
        h = hash_file(h, u->file);
    if (u->model)
        h = hash_unit_text(h, u->model, u->unit);
    return h;
}

/* The cached object's path for u (a malloc'd name in the object cache,
 * created if need be), or NULL where there is no cache to write to. */
static char *
cached_object(const UnitKey *u)
{
    char dir[PATH_MAX];
    cache_root(dir, sizeof dir - 16);
    strcat(dir, "/objects");
    if (make_dirs(dir) != 0 || access(dir, W_OK) != 0)
        return NULL;
    uint64_t a = unit_hash(hash_basis, u), b = unit_hash(0x9e3779b97f4a7c15u, u);
    size_t len = strlen(dir) + 40;
    char *path = xmalloc(len);
    snprintf(path, len, "%s/%016llx%016llx.o", dir, (unsigned long long)a,
             (unsigned long long)b);
    return path;
}

/* Copy from to to (a new file); 0, or -1. */
static int
copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    static char buf[1 << 16];
    size_t n;
    int bad = !in || !out;
    while (!bad && (n = fread(buf, 1, sizeof buf, in)) > 0)
        bad = fwrite(buf, 1, n, out) != n;
    bad |= in && ferror(in);
    if (in)
        fclose(in);
    if (out && fclose(out) != 0)
        bad = 1;
    return bad ? -1 : 0;
}

/* Keep the object just compiled at obj as cached: moved there whole (a
 * rename, or a copy and a rename across file systems).  0, or -1 (then
 * the build links obj itself). */
static int
keep_object(const char *obj, const char *cached)
{
    if (rename(obj, cached) == 0)
        return 0;
    size_t len = strlen(cached) + 32;
    char *tmp = xmalloc(len);
    snprintf(tmp, len, "%s.tmp%ld", cached, (long)getpid());
    int rc = copy_file(obj, tmp) == 0 && rename(tmp, cached) == 0 ? 0 : -1;
    if (rc != 0)
        unlink(tmp);
    free(tmp);
    return rc;
}

/* The optimization of a model's units.  Straight-line generated code
 * runs as fast at -O1 as at -O2 (measured, gcc 12: chain5 109 against
 * 115 ns, gen_tree 10 1 660 against 1 739, gen_tree 30 5 225 against
 * 5 484), which finds nothing more to do in it, and compiles in two
 * thirds of the time.  A large pair of units (1 and 2, or 3 and 4: emit.h)
 * at -Og, which is -O1
 * without the passes that find little in straight-line code (dead
 * stores, SRA, points-to, if-conversion) and compiles in a fifth less
 * time, as fast to run (docs/benchmarks.md, "Build time").  A small
 * one stays at -O1: its functions are called once and inlined there,
 * which -Og does not do (chain5 110 against 146 ns).  Without
 * -ffast-math the arithmetic is the same to the bit either way.  Neither
 * runs gcc's vectorizer, and that is kept so: gcc 12's basic-block
 * vectorizer (-ftree-slp-vectorize, on at -O2) forms fused multiply-adds
 * (vfmaddsub from a*b - c beside d*e + f) under -march=native whatever
 * -ffp-contract says, which changed bicycle_tree's rows in their last
 * bits, though it took Kepler's series from 1 830 instructions to 1 670.
 * Vectors in generated code are printed as such (taylor_run4's eomc_v4). */
static const char *
opt_flag(int large)
{
    return large ? "-Og" : "-O1";
}

/* For this CPU: its instruction set (-march=native), where the compilers
 * take the flag (gcc and clang on x86-64 and arm64; not gcc on every
 * other architecture).  Straight-line code gains most: with AVX's
 * three-operand instructions and more registers MuJoCo's humanoid runs
 * in 18 % fewer instructions (docs/benchmarks.md).  Without contraction
 * into fused multiply-adds, which would round differently: every result
 * stays the same to the bit as the portable build's (clang contracts
 * within a statement by default).  The object cache keys it by the CPU
 * as well (cpu_hash). */
#if defined(__x86_64__) || defined(__aarch64__)
static const char *const native_flags[] = {"-march=native", "-ffp-contract=off"};
#else
static const char *const native_flags[] = {"-ffp-contract=off"};
#endif
enum { NNATIVE = sizeof native_flags / sizeof native_flags[0] };

int
build_executable(const char *c_file, const char *model, const char *exe, int mpi, int units,
                 int twin, int shared, int native)
{
    const char *inc, *lib, *cc = getenv(mpi ? "EOMC_MPICC" : "CC");
    if (!cc || !*cc)
        cc = mpi ? "mpicc" : "cc";
    runtime_paths(&inc, &lib);
    if (access(lib, R_OK) != 0) {
        fprintf(stderr, "eomc: runtime library not found at %s "
                        "(set EOMC_RUNTIME_LIB)\n", lib);
        return -1;
    }
    /* the model's units 1 to 4 (emit.h), the twin's, the main */
    enum { NMODEL = 4, TWIN = NMODEL, MAIN = 2 * NMODEL, NUNIT };
    char *ext = twin ? write_extended_unit(c_file) : NULL;
    char *main_c = ext || !twin ? write_main_unit(c_file, model) : NULL;
    if (!main_c) {
        if (ext)
            unlink(ext);
        free(ext);
        return -1;
    }
    size_t len = strlen(exe) + 16;
    char *tmp = xmalloc(len);
    int special = build_is_special(exe);
    snprintf(tmp, len, special ? "%s" : "%s.tmp%ld", exe, (long)getpid());
    char *obj[NUNIT] = {sibling(c_file, "model.o"), sibling(c_file, "model2.o"),
                        sibling(c_file, "model3.o"), sibling(c_file, "model4.o"),
                        sibling(c_file, "model_ext.o"), sibling(c_file, "model_ext2.o"),
                        sibling(c_file, "model_ext3.o"), sibling(c_file, "model_ext4.o"),
                        sibling(c_file, "main.o")};
    char incflag[PATH_MAX + 3], ccbuf[256], libs[] = EOMC_GSL_LIBS, incabs[PATH_MAX];
    /* absolute: the units compile in the C file's directory */
    snprintf(incflag, sizeof incflag, "-I%s", realpath(inc, incabs) ? incabs : inc);
    snprintf(ccbuf, sizeof ccbuf, "%s", cc);
    char *argv[64];
    int ncc = split_flags(ccbuf, argv, 8); /* CC may carry flags: "gcc -m64" */
    /* The units compile at once (each is most of the time of a large
     * model's build), then link: the model's (-DEOMC_UNIT=1, a large
     * one's second half 2, and 3 with its second half 4: emit.h), its
     * extended-precision twin's, the same units of model_ext.c, and the
     * main.  Position-independent, each of them: a simulator and a
     * library (--shared) link the same objects. */
    const char *flags[] = {"-std=c11", "-fPIC", "-pthread", incflag};
    const char *main_flags[] = {shared ? "-DEOMC_SHARED" : "-DEOMC_MAIN",
                                mpi ? "-DEOMC_MPI" : NULL};
    static const char *const unit_flag[NMODEL] = {"-DEOMC_UNIT=1", "-DEOMC_UNIT=2",
                                                  "-DEOMC_UNIT=3", "-DEOMC_UNIT=4"};
    static const int unit_bit[NMODEL] = {EMIT_UNIT1, EMIT_UNIT2, EMIT_UNIT3, EMIT_UNIT4};
    /* the pair (3, 4) optimized as the pair (1, 2) is: as large or not */
    int large[NMODEL] = {units & EMIT_UNIT2, units & EMIT_UNIT2, units & EMIT_UNIT4,
                         units & EMIT_UNIT4};
    /* Each unit compiles in the directory of the C, named relative to it,
     * so that the command line of the same C is the same from one build
     * to the next, wherever its directory: a compiler cache (CC="ccache
     * cc") then finds it (ccache hashes the file names it is given).  The
     * objects are siblings of the C, and the link names them in full. */
    const char *slash = strrchr(c_file, '/');
    char *dir = NULL;
    if (slash) {
        dir = xmalloc((size_t)(slash - c_file) + 2);
        memcpy(dir, c_file, (size_t)(slash - c_file) + 1);
        dir[slash - c_file + 1] = '\0';
    }
    char *unit_argv[NUNIT][32], *cached[NUNIT] = {NULL};
    pid_t pid[NUNIT];
    int use[NUNIT];
    for (int u = 0; u < NUNIT; u++) {
        int k = u % NMODEL; /* the model's unit: k + 1 */
        const char *src = u == MAIN ? main_c : u >= TWIN ? ext : c_file;
        use[u] = u == MAIN || ((u < TWIN || twin) && (units & unit_bit[k]));
        if (!use[u])
            continue;
        int n = 0;
        for (int j = 0; j < ncc; j++)
            unit_argv[u][n++] = argv[j];
        unit_argv[u][n++] = (char *)flags[0];
        unit_argv[u][n++] = (char *)opt_flag(u != MAIN && large[k]);
        for (size_t j = 1; j < sizeof flags / sizeof flags[0]; j++)
            unit_argv[u][n++] = (char *)flags[j];
        for (int j = 0; native && j < NNATIVE; j++)
            unit_argv[u][n++] = (char *)native_flags[j];
        for (size_t j = 0; u == MAIN && j < sizeof main_flags / sizeof *main_flags; j++)
            if (main_flags[j])
                unit_argv[u][n++] = (char *)main_flags[j];
        if (u != MAIN)
            unit_argv[u][n++] = (char *)unit_flag[k];
        unit_argv[u][n++] = "-c";
        unit_argv[u][n++] = (char *)(dir ? src + strlen(dir) : src);
        unit_argv[u][n++] = "-o";
        unit_argv[u][n++] = dir ? obj[u] + strlen(dir) : obj[u];
        unit_argv[u][n] = NULL;
        UnitKey key = {unit_argv[u], ncc, unit_argv[u][n - 1], u >= TWIN ? src : NULL,
                       u == MAIN ? NULL : c_file, k + 1};
        cached[u] = cached_object(&key);
        pid[u] = cached[u] && access(cached[u], R_OK) == 0 ? 0 : start_cc(unit_argv[u], dir);
    }
    int rc = 0;
    for (int u = 0; u < NUNIT; u++) { /* each waited for */
        if (!use[u] || pid[u] == 0)
            continue;
        if (wait_cc(pid[u], cc) != 0)
            rc = -1;
        else if (cached[u] && keep_object(obj[u], cached[u]) != 0)
            free(cached[u]), cached[u] = NULL; /* no cache: the object where it is */
    }
    if (rc == 0) {
        int n = ncc;
        for (int u = 0; u < NUNIT; u++)
            if (use[u])
                argv[n++] = cached[u] ? cached[u] : obj[u];
        /* A library holds the whole runtime, not just what the model
         * calls: its caller (Python) reaches the API by name.  libeomcrt.a
         * is built position-independent (meson's b_staticpic). */
        const char *link[] = {"-o", tmp};
        const char *lib_link[] = {"-shared", "-Wl,--whole-archive", lib,
                                  "-Wl,--no-whole-archive", "-o", tmp};
        const char *const *lk = shared ? lib_link : link;
        size_t nlk = shared ? sizeof lib_link / sizeof *lib_link : sizeof link / sizeof *link;
        if (!shared)
            argv[n++] = (char *)lib;
        for (size_t k = 0; k < nlk; k++)
            argv[n++] = (char *)lk[k];
        n += split_flags(libs, argv + n, 40);
        argv[n++] = "-lm";
        argv[n++] = "-pthread"; /* sweeps run on threads */
        argv[n] = NULL;
        rc = wait_cc(start_cc(argv, NULL), cc);
    }
    if (rc == 0 && !special && rename(tmp, exe) != 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", exe, strerror(errno));
        rc = -1;
    }
    if (rc != 0 && !special)
        unlink(tmp);
    if (ext)
        unlink(ext);
    unlink(main_c);
    for (int u = 0; u < NUNIT; u++) {
        if (use[u])
            unlink(obj[u]);
        free(obj[u]);
        free(cached[u]);
    }
    free(ext);
    free(main_c);
    free(tmp);
    free(dir);
    return rc;
}

char *
build_cache_path(const char *name, const char *key, size_t len)
{
    char dir[PATH_MAX];
    cache_root(dir, sizeof dir - 20);
    /* The key: spec and options (the caller's text), and what else the
     * simulator is made of (toolchain_hash). */
    uint64_t h = hash_bytes(toolchain_hash(), &len, sizeof len);
    h = hash_bytes(h, key, len);
    size_t dl = strlen(dir);
    snprintf(dir + dl, sizeof dir - dl, "/%016llx", (unsigned long long)h);
    if (make_dirs(dir) != 0) {
        fprintf(stderr, "eomc: cannot create cache directory %s: %s\n", dir,
                strerror(errno));
        return NULL;
    }
    size_t n = strlen(dir) + strlen(name) + 2;
    char *path = xmalloc(n);
    snprintf(path, n, "%s/%s", dir, name);
    return path;
}
