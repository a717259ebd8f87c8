#!/usr/bin/env python3
"""usage: check_layout.py includes SOURCE_ROOT
       check_layout.py calls NM ARCHIVE...
       check_layout.py selftest

The source tree's layout, as TAP.  compiler/ is a staircase of folders and
runtime/ a stack of layers (compiler/README.md, runtime/README.md); a file
may use its own folder and the folders below it, never one above.

includes: every source file of compiler/ and runtime/ lies in a folder of
  its staircase, and that folder has a README.md saying what it holds; each
  `#include "..."` resolves to a file of the tree (or to a header the build
  generates), is spelled as the folder rules say (a header of the same
  folder by its name, of another folder as "folder/name.h", an installed
  header of the runtime as "eomc.h", the runtime's base from the compiler
  as "runtime/base/name.h"), and points down or across, never up; and the
  modules (NAME.c with NAME.h, in one folder) include one another without
  a circle.
calls: the same rules on what the object files of the compiler's and the
  runtime's static libraries call (a global symbol one object leaves
  undefined and another defines): down or across, and no circle.  This
  catches what includes cannot see, a function declared in one module's
  header and defined in another's file.
selftest: both checks on small trees made to break them, each must fail.
"""
import os
import re
import subprocess
import sys
import tempfile

# Bottom first.  A file may use its own folder and those before it.
STAIRS = {
    "compiler": ["base", "expr", "spec", "mechanics", "forms", "lower", "emit", "driver"],
    "runtime": ["include", "base", "model", "step", "analysis", "front"],
}
# Headers the build writes (meson: compiler/meson.build, runtime/meson.build)
# and the one folder each may be included from.
GENERATED = {"config.h": ("compiler", "driver"), "animate_page.h": ("runtime", "front")}
SOURCES = (".c", ".h", ".def")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


class Tap:
    def __init__(self):
        self.n = 0
        self.failed = 0

    def ok(self, good, what, details=()):
        self.n += 1
        print("%sok %d - %s" % ("" if good else "not ", self.n, what))
        if not good:
            self.failed += 1
            for d in details:
                print("# " + d)

    def end(self):
        print("1..%d" % self.n)
        return 1 if self.failed else 0


def place(rel):
    """(side, folder, name) of a path relative to the source root, or None
    outside compiler/ and runtime/."""
    parts = rel.split("/")
    if parts[0] not in STAIRS:
        return None
    if len(parts) == 2:
        return (parts[0], None, parts[1])
    return (parts[0], parts[1], "/".join(parts[2:]))


def rank(side, folder):
    stairs = STAIRS[side]
    return stairs.index(folder) if folder in stairs else None


def find_cycle(graph):
    """One circle of graph (node -> set of nodes) as a list, or None."""
    color = {}
    stack = []

    def visit(u):
        color[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, ())):
            if color.get(v) == 1:
                return stack[stack.index(v):] + [v]
            if v not in color:
                c = visit(v)
                if c:
                    return c
        stack.pop()
        color[u] = 2
        return None

    for u in sorted(graph):
        if u not in color:
            c = visit(u)
            if c:
                return c
    return None


def sources(root):
    out = []
    for side in STAIRS:
        for d, dirs, files in os.walk(os.path.join(root, side)):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(SOURCES):
                    out.append(os.path.relpath(os.path.join(d, f), root))
    return out


def resolve(root, rel, inc):
    """The file `#include "inc"` in rel names, relative to root, as the
    build's include paths find it: the file's own folder first, then
    compiler/ and the source root for the compiler, runtime/include and
    runtime/ for the runtime (compiler/meson.build, runtime/meson.build)."""
    side = rel.split("/")[0]
    dirs = [os.path.dirname(rel)]
    dirs += ["compiler", ""] if side == "compiler" else ["runtime/include", "runtime"]
    for d in dirs:
        p = os.path.normpath(os.path.join(d, inc))
        if not p.startswith("..") and os.path.isfile(os.path.join(root, p)):
            return p
    return None


def spelling(frm, to):
    """How rel `frm` must spell an include of rel `to`."""
    fs, ff, _ = place(frm)
    ts, tf, tn = place(to)
    if ts == "runtime" and tf == "include":
        return tn
    if (fs, ff) == (ts, tf):
        return tn
    if fs == "compiler" and ts == "runtime":
        return to
    return tf + "/" + tn


def check_includes(root, tap):
    files = sources(root)
    # every file in a folder of its staircase, each folder with its README
    loose = [f for f in files if rank(place(f)[0], place(f)[1]) is None]
    tap.ok(not loose, "every source file of compiler/ and runtime/ is in a folder of its staircase",
           ["%s: not in any of %s/{%s}" % (f, place(f)[0], ",".join(STAIRS[place(f)[0]]))
            for f in loose])
    missing = ["%s/README.md" % d for d in ["compiler", "runtime"] if not
               os.path.isfile(os.path.join(root, d, "README.md"))]
    for side, stairs in sorted(STAIRS.items()):
        for folder in stairs:
            d = os.path.join(root, side, folder)
            if os.path.isdir(d) and not os.path.isfile(os.path.join(d, "README.md")):
                missing.append("%s/%s/README.md" % (side, folder))
    tap.ok(not missing, "every folder of the staircases says what it holds (README.md)",
           ["missing: " + m for m in missing])

    bad_spelling, unresolved, upward = [], [], []
    modules = {}
    for f in files:
        side, folder, name = place(f)
        if rank(side, folder) is None:
            continue
        text = open(os.path.join(root, f), encoding="utf-8", errors="replace").read()
        mod = (side, folder, os.path.splitext(name)[0])
        modules.setdefault(mod, set())
        for m in INCLUDE.finditer(text):
            inc = m.group(1)
            line = text.count("\n", 0, m.start()) + 1
            where = "%s:%d: " % (f, line)
            to = resolve(root, f, inc)
            if to is None:
                gen = GENERATED.get(os.path.basename(inc))
                if gen == (side, folder) and inc == os.path.basename(inc):
                    continue
                unresolved.append(where + '"%s" is no file of the tree' % inc)
                continue
            ts, tf, tn = place(to) or (None, None, None)
            if ts is None or rank(ts, tf) is None:
                unresolved.append(where + '"%s" is %s, outside the staircases' % (inc, to))
                continue
            want = spelling(f, to)
            if inc != want:
                bad_spelling.append(where + '"%s" should be spelled "%s"' % (inc, want))
            if ts != side:
                # across the two: the compiler takes the runtime's base and
                # nothing else; the runtime nothing of the compiler
                if not (side == "compiler" and tf == "base"):
                    upward.append(where + "%s/ includes %s (only runtime/base/ is shared)" %
                                  (side, to))
            elif rank(ts, tf) > rank(side, folder):
                upward.append(where + "%s/%s/ includes %s, a stage above it" % (side, folder, to))
            tmod = (ts, tf, os.path.splitext(tn)[0])
            if tmod != mod:
                modules[mod].add(tmod)
    tap.ok(not unresolved, "every include names a file of the staircases", unresolved)
    tap.ok(not bad_spelling, "every include is spelled by the folder rules", bad_spelling)
    tap.ok(not upward, "no include points up a staircase", upward)
    cycle = find_cycle(modules)
    tap.ok(cycle is None, "no two modules include each other, directly or around a circle",
           ["circle: " + " -> ".join("%s/%s/%s" % m for m in cycle)] if cycle else [])
    return len(files)


def object_place(member):
    """(side, folder, file) of a static library's member, from the path
    meson gives it: compiler/libeomccore.a.p/lower_lower_schedule.c.o."""
    base = os.path.basename(member)
    lib = os.path.basename(os.path.dirname(member))
    side = "runtime" if lib.startswith("libeomcrt") else "compiler"
    stem = base[:-len(".o")] if base.endswith(".o") else base
    m = re.match(r"^(?:\.\._)+runtime_(\w+?)_(.*)$", stem)
    if m:  # a runtime file compiled into the compiler: ../runtime/base/numfmt.c
        return ("runtime", m.group(1), m.group(2))
    for folder in STAIRS[side]:
        if stem.startswith(folder + "_"):
            return (side, folder, stem[len(folder) + 1:])
    return (side, None, stem)


def check_calls(nm, archives, tap):
    defined, undefined = {}, {}
    for a in archives:
        out = subprocess.run([nm, "-A", a], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            # archive:member:[value] type name
            fields = line.split()
            if len(fields) < 2:
                continue
            loc = fields[0]
            parts = loc.split(":")
            if len(parts) < 3:
                continue
            member = parts[1]
            typ, sym = fields[-2], fields[-1]
            obj = object_place(member)
            if typ == "U":
                undefined.setdefault(obj, set()).add(sym)
            elif typ.isupper() and typ not in "U":
                defined[sym] = obj
    loose = sorted({"%s/%s" % (o[0], o[2]) for o in list(defined.values()) + list(undefined)
                    if rank(o[0], o[1]) is None})
    tap.ok(not loose, "every object of the libraries comes from a folder of its staircase",
           ["%s: no folder" % o for o in loose])
    graph, upward = {}, []
    for obj, syms in sorted(undefined.items()):
        for s in sorted(syms):
            to = defined.get(s)
            if to is None or to == obj:
                continue
            graph.setdefault(obj, set()).add(to)
            if rank(obj[0], obj[1]) is None or rank(to[0], to[1]) is None:
                continue
            if to[0] != obj[0]:
                if not (obj[0] == "compiler" and to[1] == "base"):
                    upward.append("%s/%s/%s calls %s of %s/%s/%s" % (obj + (s,) + to))
            elif rank(to[0], to[1]) > rank(obj[0], obj[1]):
                upward.append("%s/%s/%s calls %s of %s/%s/%s, a stage above it" %
                              (obj + (s,) + to))
    tap.ok(bool(defined), "the libraries define symbols (%d)" % len(defined))
    tap.ok(not upward, "no call goes up a staircase", upward)
    cycle = find_cycle(graph)
    tap.ok(cycle is None, "no two files call each other, directly or around a circle",
           ["circle: " + " -> ".join("%s/%s/%s" % c for c in cycle)] if cycle else [])


def write(root, rel, text):
    p = os.path.join(root, rel)
    os.makedirs(os.path.dirname(p), exist_ok=True)
    with open(p, "w") as f:
        f.write(text)


def selftest(tap):
    """The checks must catch what they are for: a good tree passes, and
    each breakage fails exactly its check."""
    def tree(tmp, extra):
        for side, stairs in STAIRS.items():
            write(tmp, side + "/README.md", "x\n")
            for folder in stairs:
                write(tmp, "%s/%s/README.md" % (side, folder), "x\n")
        write(tmp, "compiler/expr/expr.h", "")
        write(tmp, "compiler/expr/expr.c", '#include "expr.h"\n#include "base/arena.h"\n')
        write(tmp, "compiler/base/arena.h", "")
        write(tmp, "compiler/lower/lower.h", '#include "expr/expr.h"\n')
        write(tmp, "compiler/lower/lower.c", '#include "lower.h"\n#include "runtime/base/numfmt.h"\n')
        write(tmp, "runtime/base/numfmt.h", "")
        write(tmp, "runtime/include/eomc.h", "")
        write(tmp, "runtime/model/sim.c", '#include "eomc.h"\n#include "base/numfmt.h"\n')
        for rel, text in extra.items():
            write(tmp, rel, text)

    def run(extra):
        with tempfile.TemporaryDirectory() as tmp:
            tree(tmp, extra)
            t = Tap()
            sys_stdout = sys.stdout
            with open(os.devnull, "w") as sink:
                sys.stdout = sink
                try:
                    check_includes(tmp, t)
                finally:
                    sys.stdout = sys_stdout
            return t.failed

    cases = [
        ("a tree by the rules", {}, 0),
        ("an include up the staircase", {"compiler/base/arena.h": '#include "lower/lower.h"\n'}, 2),
        ("two modules that include each other",
         {"compiler/lower/repeat.h": '#include "lower.h"\n',
          "compiler/lower/lower.c": '#include "lower.h"\n#include "repeat.h"\n',
          "compiler/lower/repeat.c": '#include "repeat.h"\n',
          "compiler/lower/lower.h": '#include "expr/expr.h"\n#include "repeat.h"\n'}, 1),
        ("a file outside every folder", {"compiler/loose.c": ""}, 1),
        ("a header alone in its folder", {"compiler/emit/x.h": ""}, 0),
        ("a relative include", {"compiler/lower/lower.c": '#include "../expr/expr.h"\n'}, 1),
        ("the runtime including the compiler",
         {"runtime/model/sim.c": '#include "../../compiler/expr/expr.h"\n'}, 2),
        ("the compiler including the runtime above its base",
         {"runtime/model/sim.h": "", "compiler/lower/lower.c": '#include "runtime/model/sim.h"\n'}, 1),
    ]
    for what, extra, want in cases:
        got = run(extra)
        tap.ok(got == want if want == 0 else got >= want,
               "selftest: %s fails %d check(s) (%d)" % (what, want, got))
    # a folder without its README
    with tempfile.TemporaryDirectory() as tmp:
        tree(tmp, {})
        os.remove(os.path.join(tmp, "compiler/emit/README.md"))
        t = Tap()
        sys_stdout = sys.stdout
        with open(os.devnull, "w") as sink:
            sys.stdout = sink
            try:
                check_includes(tmp, t)
            finally:
                sys.stdout = sys_stdout
        tap.ok(t.failed == 1, "selftest: a folder without its README fails 1 check (%d)" % t.failed)
    # calls: a circle and a call up, through a fake nm's listing
    with tempfile.TemporaryDirectory() as tmp:
        fake = os.path.join(tmp, "nm")
        listing = os.path.join(tmp, "listing")
        write(tmp, "listing",
              "compiler/libeomccore.a:compiler/libeomccore.a.p/lower_lower.c.o: U lower_schedule\n"
              "compiler/libeomccore.a:compiler/libeomccore.a.p/lower_lower.c.o:0000 T lower_find\n"
              "compiler/libeomccore.a:compiler/libeomccore.a.p/lower_lower_schedule.c.o:0000 T lower_schedule\n"
              "compiler/libeomccore.a:compiler/libeomccore.a.p/lower_lower_schedule.c.o: U lower_find\n"
              "compiler/libeomccore.a:compiler/libeomccore.a.p/base_arena.c.o: U emit_line\n"
              "compiler/libeomccore.a:compiler/libeomccore.a.p/emit_emit.c.o:0000 T emit_line\n")
        write(tmp, "nm", "#!/bin/sh\ncat '%s'\n" % listing)
        os.chmod(fake, 0o755)
        t = Tap()
        sys_stdout = sys.stdout
        with open(os.devnull, "w") as sink:
            sys.stdout = sink
            try:
                check_calls(fake, ["lib.a"], t)
            finally:
                sys.stdout = sys_stdout
        tap.ok(t.failed == 2, "selftest: a call up and a circle of calls fail 2 checks (%d)" % t.failed)


def main(argv):
    tap = Tap()
    if len(argv) == 3 and argv[1] == "includes":
        n = check_includes(argv[2], tap)
        print("# %d source files" % n)
    elif len(argv) >= 4 and argv[1] == "calls":
        check_calls(argv[2], argv[3:], tap)
    elif len(argv) == 2 and argv[1] == "selftest":
        selftest(tap)
    else:
        sys.stderr.write(__doc__)
        return 2
    return tap.end()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
