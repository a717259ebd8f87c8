#!/usr/bin/env python3
"""usage: sequenced.py [CLANG ARGS...] -- FILE.c...

Fails, naming each place, when an expression of the compiler's sources has
two operands that may each build expression nodes and C leaves their order
unspecified: the arguments of one call, the two sides of an operator other
than && || ?: and the comma, the elements of an initializer.  Node ids are
the order of construction, and the generated C follows the ids: gcc (right
to left) and clang (left to right) would number such nodes differently and
write different C for one spec.  Build them into named locals instead.

"Builds nodes" is found, not listed: a function does when it calls expr.c's
intern, or a function that does, directly or through a pointer (any
function whose address is taken, of the pointer's type).  The syntax trees
are clang's (-ast-dump=json); exit 77 (skipped) without clang.
"""
import json
import re
import shutil
import subprocess
import sys

SEQUENCED_OPS = {",", "&&", "||"}
UNORDERED = {"CallExpr", "InitListExpr", "ArraySubscriptExpr", "CompoundAssignOperator"}
# what reads the order of construction without building: a pool's size
READERS = {"expr_pool_size"}


def locate(node, state):
    """Give each node its source file and line (_f, _l).  clang's JSON
    leaves out a location's file and line when they repeat the previous
    one printed, so walk in printing order and carry them."""
    if isinstance(node, list):
        for x in node:
            locate(x, state)
        return
    if not isinstance(node, dict):
        return
    if "col" in node or "offset" in node:
        state["file"] = node.get("file", state["file"])
        state["line"] = node.get("line", state["line"])
    for k, v in list(node.items()):
        if k == "range" and "begin" in v:
            locate(v["begin"], state)
            if "loc" not in node:
                node["_f"], node["_l"] = state["file"], state["line"]
            locate(v.get("end"), state)
        elif isinstance(v, (dict, list)):
            locate(v, state)
            if k == "loc":
                node["_f"], node["_l"] = state["file"], state["line"]


def walk(n):
    yield n
    for x in n.get("inner", []):
        yield from walk(x)


def bare(n):
    while n.get("kind") in ("ImplicitCastExpr", "ParenExpr") and n.get("inner"):
        n = n["inner"][0]
    return n


def fn_type(t):
    """A function's type as its pointers spell it: no (*), no spaces."""
    return re.sub(r"\(\*(const)?\)", "", t.replace(" ", ""))


def main(argv):
    clang = shutil.which("clang")
    if clang is None:
        print("clang not found: skipped")
        return 77
    sep = argv.index("--")
    flags, files = argv[:sep], argv[sep + 1:]
    units = {}
    for f in files:
        out = subprocess.run([clang, "-Xclang", "-ast-dump=json", "-fsyntax-only"] + flags + [f],
                             check=True, stdout=subprocess.PIPE).stdout
        units[f] = json.loads(out)
        locate(units[f], {"file": f, "line": 0})

    # function definitions of our files, static ones keyed by their file
    defs, statics = {}, {}
    for f, ast in units.items():
        for d in ast["inner"]:
            if (d.get("kind") != "FunctionDecl" or d.get("_f") not in files or
                    not any(i.get("kind") == "CompoundStmt" for i in d.get("inner", []))):
                continue
            if d.get("storageClass") == "static":
                statics.setdefault(f, set()).add(d["name"])
                defs[f + ":" + d["name"]] = (f, d)
            else:
                defs[d["name"]] = (f, d)

    def key(f, name):
        return f + ":" + name if name in statics.get(f, ()) else name

    def callee(f, call):
        c = bare(call["inner"][0])
        r = c.get("referencedDecl", {})
        if c.get("kind") == "DeclRefExpr" and r.get("kind") == "FunctionDecl":
            return key(f, r["name"])
        t = c.get("type", {})
        return "*" + fn_type(t.get("desugaredQualType", t.get("qualType", "?")))

    # the call graph; a pointer type "calls" every function of that type
    # whose address is taken
    calls = {}
    for f, ast in units.items():
        callees = set()
        for n in walk(ast):
            if n.get("kind") == "CallExpr":
                callees.add(id(bare(n["inner"][0])))
        for n in walk(ast):
            r = n.get("referencedDecl", {})
            if (n.get("kind") == "DeclRefExpr" and r.get("kind") == "FunctionDecl" and
                    id(n) not in callees):
                calls.setdefault("*" + fn_type(r["type"]["qualType"]), set()).add(key(f, r["name"]))
    builders = {k for k in defs if k.endswith(":intern")}
    for k, (f, d) in defs.items():
        calls[k] = {callee(f, n) for n in walk(d) if n.get("kind") == "CallExpr"}
        # a pointer with no known target may reach anything
        builders |= {c for c in calls[k] if c.startswith("*") and c not in calls}
    grown = True
    while grown:
        grown = False
        for k, cs in calls.items():
            if k not in builders and cs & builders:
                builders.add(k)
                grown = True
    if not any(k.endswith(":intern") for k in builders):
        print("sequenced.py: expr.c's intern not found among the files")
        return 1

    def reaches(f, n, which):
        return any(m.get("kind") == "CallExpr" and callee(f, m) in which for m in walk(n))

    bad = 0
    for k, (f, d) in sorted(defs.items()):
        for n in walk(d):
            kind = n.get("kind")
            if not (kind in UNORDERED or
                    kind == "BinaryOperator" and n.get("opcode") not in SEQUENCED_OPS):
                continue
            ops = n.get("inner", [])
            build = sum(reaches(f, x, builders) for x in ops)
            touch = sum(reaches(f, x, builders | READERS) for x in ops)
            if build >= 1 and touch >= 2:
                what = callee(f, n) if kind == "CallExpr" else n.get("opcode", kind)
                also = " (and %d read the pool's size)" % (touch - build) if touch > build else ""
                print("%s:%s: %s: %d operands build nodes%s, in an unspecified order" %
                      (n["_f"], n["_l"], what.split(":")[-1], build, also))
                bad += 1
    print("%d functions build nodes; %d unordered places" % (len(builders), bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
