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
#include "build.h"
#include "base/arena.h"
#include "config.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
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

/* Start argv[0] on argv in directory dir (NULL: this one; quiet: its
 * output to /dev/null, and nothing said if it cannot run); its pid, or -1
 * after printing why. */
static pid_t
start_cc(char **argv, const char *dir, int quiet)
{
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "eomc: cannot start %s: %s\n", argv[0], strerror(errno));
        return -1;
    }
    if (pid == 0) {
        int null = quiet ? open("/dev/null", O_WRONLY) : -1;
        if (null >= 0)
            dup2(null, STDOUT_FILENO), dup2(null, STDERR_FILENO);
        if (dir && chdir(dir) != 0) {
            if (!quiet)
                fprintf(stderr, "eomc: cannot enter %s: %s\n", dir, strerror(errno));
            _exit(127);
        }
        execvp(argv[0], argv);
        if (!quiet)
            fprintf(stderr, "eomc: cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
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

/* For a large model's two units, where $CC takes them (gcc does, clang
 * does not): gcc's dead-store eliminations find nothing to remove in code
 * that assigns each value once, and one region of register allocation
 * beats its regions on long straight-line functions.  Without them
 * gen_tree 30's units compile in a fifth less time (1.75-2.44 against
 * 1.23-1.53 s, side by side) and run as fast (5 262 against 5 221 ns). */
static const char *const fast_flags[] = {"-fno-tree-dse", "-fno-dse", "-fira-region=one"};
enum { NFAST = sizeof fast_flags / sizeof fast_flags[0] };

/* Whether the compiler argv[0..ncc) accepts fast_flags: it compiles an
 * empty unit with them, silently. */
static int
cc_takes_fast_flags(char **argv, int ncc)
{
    char *probe[32];
    int n = 0;
    for (int k = 0; k < ncc; k++)
        probe[n++] = argv[k];
    for (int k = 0; k < NFAST; k++)
        probe[n++] = (char *)fast_flags[k];
    const char *tail[] = {"-x", "c", "-c", "/dev/null", "-o", "/dev/null"};
    for (size_t k = 0; k < sizeof tail / sizeof tail[0]; k++)
        probe[n++] = (char *)tail[k];
    probe[n] = NULL;
    return exit_status(start_cc(probe, NULL, 1)) == 0;
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

/* The reference solution's functions are the same file compiled again
 * in extended precision: a second translation unit that includes it with
 * EOMC_EXTENDED defined.  Returns its path, or NULL after printing why. */
static char *
write_extended_unit(const char *c_file)
{
    char *ext = sibling(c_file, "model_ext.c");
    const char *base = strrchr(c_file, '/');
    FILE *f = fopen(ext, "w");
    if (!f || fprintf(f, "#define EOMC_EXTENDED 1\n#include \"%s\"\n",
                      base ? base + 1 : c_file) < 0 || fclose(f) != 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", ext, strerror(errno));
        free(ext);
        return NULL;
    }
    return ext;
}

int
build_executable(const char *c_file, const char *exe, int mpi, int units, int twin,
                 int shared)
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
    char *ext = twin ? write_extended_unit(c_file) : NULL;
    if (twin && !ext)
        return -1;
    size_t len = strlen(exe) + 16;
    char *tmp = xmalloc(len);
    int special = build_is_special(exe);
    snprintf(tmp, len, special ? "%s" : "%s.tmp%ld", exe, (long)getpid());
    char *obj[3] = {sibling(c_file, "model.o"), sibling(c_file, "model2.o"),
                    sibling(c_file, "model_ext.o")};
    char incflag[PATH_MAX + 3], ccbuf[256], libs[] = EOMC_GSL_LIBS, incabs[PATH_MAX];
    /* absolute: the units compile in the C file's directory */
    snprintf(incflag, sizeof incflag, "-I%s", realpath(inc, incabs) ? incabs : inc);
    snprintf(ccbuf, sizeof ccbuf, "%s", cc);
    char *argv[64];
    int ncc = split_flags(ccbuf, argv, 8); /* CC may carry flags: "gcc -m64" */
    /* The units compile at once (each is most of the time of a large
     * model's build), then link: a large model's two halves
     * (-DEOMC_UNIT=1, 2: emit.h), and the extended-precision twin.  -O1:
     * straight-line generated code runs as fast as at -O2 (measured, gcc
     * 12: chain5 109 against 115 ns, gen_tree 10 1 660 against 1 739,
     * bicycle_tree 790 against 802, gen_tree 30 5 225 against 5 484),
     * which finds nothing more to do in it, and compiles in two thirds of
     * the time (gen_tree 30: 3.1 against 4.7 s).  Without -ffast-math the
     * arithmetic is the same to the bit. */
    const char *flags[] = {"-std=c11", "-O1", shared ? "-DEOMC_SHARED" : "-DEOMC_MAIN",
                           "-pthread", incflag, shared ? "-fPIC" : mpi ? "-DEOMC_MPI" : NULL};
    const char *unit_flag[3] = {units == 2 ? "-DEOMC_UNIT=1" : NULL, "-DEOMC_UNIT=2", NULL};
    int fast = units == 2 && cc_takes_fast_flags(argv, ncc);
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
    const char *src[3] = {c_file, c_file, ext};
    int use[3] = {1, units == 2, twin};
    char *unit_argv[3][32];
    pid_t pid[3];
    for (int u = 0; u < 3; u++) {
        if (!use[u])
            continue;
        int n = 0;
        for (int k = 0; k < ncc; k++)
            unit_argv[u][n++] = argv[k];
        for (size_t k = 0; k < sizeof flags / sizeof flags[0] && flags[k]; k++)
            unit_argv[u][n++] = (char *)flags[k];
        if (unit_flag[u])
            unit_argv[u][n++] = (char *)unit_flag[u];
        for (int k = 0; fast && k < NFAST; k++)
            unit_argv[u][n++] = (char *)fast_flags[k];
        unit_argv[u][n++] = "-c";
        unit_argv[u][n++] = (char *)(dir ? src[u] + strlen(dir) : src[u]);
        unit_argv[u][n++] = "-o";
        unit_argv[u][n++] = dir ? obj[u] + strlen(dir) : obj[u];
        unit_argv[u][n] = NULL;
        pid[u] = start_cc(unit_argv[u], dir, 0);
    }
    int rc = 0;
    for (int u = 0; u < 3; u++) /* each waited for */
        if (use[u] && wait_cc(pid[u], cc) != 0)
            rc = -1;
    if (rc == 0) {
        int n = ncc;
        for (int u = 0; u < 3; u++)
            if (use[u])
                argv[n++] = obj[u];
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
        rc = wait_cc(start_cc(argv, NULL, 0), cc);
    }
    if (rc == 0 && !special && rename(tmp, exe) != 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", exe, strerror(errno));
        rc = -1;
    }
    if (rc != 0 && !special)
        unlink(tmp);
    if (ext)
        unlink(ext);
    for (int u = 0; u < 3; u++) {
        if (use[u])
            unlink(obj[u]);
        free(obj[u]);
    }
    free(ext);
    free(tmp);
    free(dir);
    return rc;
}

/* A 64-bit hash of bytes, fed in pieces, eight bytes at a time (a cache
 * key hashes eomc and the runtime library, megabytes, on every run):
 * FNV-1a's multiply on words, with the high bits folded back so that a
 * change anywhere reaches every bit of the next word's product. */
static const uint64_t hash_prime = 0x100000001b3u;

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
    h = hash_string(0xcbf29ce484222325u, EOMC_VERSION); /* FNV's offset basis */
    h = hash_string(h, cc ? cc : "cc");
    h = hash_file(h, "/proc/self/exe");
    h = hash_file(h, lib);
    static const char *const headers[] = {"eomc.h", "eomc_model.h", "eomc_main.h", "eomc_mpi.h",
                                          "eomc_tree.h", "eomc_taylor.h"};
    for (size_t k = 0; k < sizeof headers / sizeof headers[0]; k++) {
        char path[PATH_MAX * 2 + 64];
        snprintf(path, sizeof path, "%s/%s", inc, headers[k]);
        h = hash_file(h, path);
    }
    done = 1;
    return h;
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

char *
build_cache_path(const char *name, const char *key, size_t len)
{
    const char *root = getenv("EOMC_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    char dir[PATH_MAX];
    if (root && *root)
        snprintf(dir, sizeof dir, "%s", root);
    else if (xdg && *xdg)
        snprintf(dir, sizeof dir, "%s/eomc", xdg);
    else
        snprintf(dir, sizeof dir, "%s/.cache/eomc", home && *home ? home : "/tmp");
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
