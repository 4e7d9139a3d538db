#!/usr/bin/env python3
"""scripts/layers.py - the house rules of src/, checked from the toolchain's own output.

The folders of src/ are floors (docs/architecture.md): a file may include and call files of its own folder
and of folders below it, never above, and no two files may depend on each other in a circle, however long.
Two views are checked, because each alone misses something:
  - includes, from the compiler's dependency output (cc -MM): an internal header of a higher folder;
  - calls, from the symbol tables of the built objects (nm): a lower file calling a higher one through a
    public header of include/dashpot/, which an include check cannot see.
Usage: layers.py BUILD_DIR   (the objects of `make all` under BUILD_DIR/src). Prints one line per violation
and a closing 'N passed, M failed' line; exits 1 on any violation."""
import collections
import glob
import os
import subprocess
import sys

# Floors, bottom first. Folders on the same floor are peers: they may not depend on each other.
FLOORS = [
    ["core/base"],
    ["core/laws"],
    ["core/network", "core/lcp", "core/right_hand"],
    ["core/analysis"],
    ["core/rules"],
    ["core/record"],
    ["core/solvers"],
    ["core/runs"],
    ["core/studies"],
    ["json"],
    ["http", "cli"],
]
RANK = {folder: i for i, floor in enumerate(FLOORS) for folder in floor}


def folder_of(path):
    """The floor's folder of a path under src/ (core/solvers/network/x.c is in core/solvers)."""
    rel = os.path.relpath(path, "src")
    parts = rel.split(os.sep)
    for depth in (2, 1):
        f = "/".join(parts[:depth])
        if f in RANK:
            return f
    return None


def allowed(src, dst):
    a, b = folder_of(src), folder_of(dst)
    return a == b or (a in RANK and b in RANK and RANK[b] < RANK[a])


def include_edges(sources):
    out = subprocess.run(["cc", "-MM", "-Iinclude", "-Isrc/core", "-Isrc/http", "-Isrc/json",
                          "-D_POSIX_C_SOURCE=200809L", "-D_DEFAULT_SOURCE"] + sources,
                         capture_output=True, text=True, check=True).stdout.replace("\\\n", " ")
    edges = []
    for line in out.splitlines():
        if ":" not in line:
            continue
        deps = line.split(":", 1)[1].split()
        src = deps[0]
        for d in deps[1:]:
            d = os.path.normpath(d)
            if d.startswith("src/") and d != src:
                edges.append((src, d))
    return edges


def call_edges(build):
    defs, uses = {}, collections.defaultdict(set)
    objs = sorted(glob.glob(os.path.join(build, "src", "**", "*.o"), recursive=True))
    for o in objs:
        for line in subprocess.run(["nm", o], capture_output=True, text=True, check=True).stdout.splitlines():
            p = line.split()
            if len(p) == 3 and p[1] in "TDBR":
                defs[p[2]] = o
            elif len(p) == 2 and p[0] == "U":
                uses[o].add(p[1])
    src = lambda o: os.path.relpath(o, build)[:-2] + ".c"
    edges = set()
    for o in objs:
        for s in uses[o]:
            if s in defs and defs[s] != o:
                edges.add((src(o), src(defs[s]), s))
    return [src(o) for o in objs], edges


def circles(nodes, edges):
    """Strongly connected components of more than one file (Tarjan, iterative)."""
    g = collections.defaultdict(set)
    for a, b in edges:
        g[a].add(b)
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(sorted(g[root])))]
        index[root] = low[root] = counter[0]; counter[0] += 1; stack.append(root); on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]; counter[0] += 1; stack.append(w); on.add(w)
                    work.append((w, iter(sorted(g[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop(); on.discard(w); comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    sources = sorted(glob.glob("src/**/*.c", recursive=True))
    failed = passed = 0
    unknown = [s for s in sources if folder_of(s) is None]
    for s in unknown:
        print(f"not on a floor: {s} (add its folder to FLOORS in scripts/layers.py and docs/architecture.md)")
    failed += len(unknown)
    bad_inc = [(a, b) for a, b in include_edges(sources) if not allowed(a, b)]
    for a, b in bad_inc:
        print(f"include up: {a} ({folder_of(a)}) includes {b} ({folder_of(b)})")
    failed += len(bad_inc)
    passed += not bad_inc
    nodes, calls = call_edges(build)
    bad_calls = sorted({(a, b, s) for a, b, s in calls if not allowed(a, b)})
    for a, b, s in bad_calls:
        print(f"call up: {a} ({folder_of(a)}) calls {s} of {b} ({folder_of(b)})")
    failed += len(bad_calls)
    passed += not bad_calls
    comps = circles(nodes, {(a, b) for a, b, _ in calls})
    for c in comps:
        print(f"circle of {len(c)} files: {' '.join(c)}")
    failed += len(comps)
    passed += not comps
    print(f"layers: {len(sources)} files on {len(FLOORS)} floors, {len(calls)} calls between files")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
