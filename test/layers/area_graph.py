#!/usr/bin/env python3
"""The dependency graph between rosmill's areas, from the includes of their files, checked against the areas the
build declares (CMakeLists.txt: `rosmill_area(NAME DEPENDS A B ... [LIBS ...])`, see cmake/areas.cmake).

Fails (exit 1) when the include graph between areas has a cycle, or when an area includes from an area it does
not declare (directly or through its declared dependencies). Prints the graph, one area per line.

Usage: area_graph.py SOURCE_DIR [--dot]"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"(?:rosmill/)?([a-z_]+)/[^"]+"', re.M)
AREA_CALL = re.compile(r"rosmill_area\(\s*(\w+)(.*?)\)", re.S)


def file_area(root, path):
    rel = path.relative_to(root).parts
    if rel[0] == "include" and len(rel) > 3:
        return rel[2]
    if rel[0] == "include":
        return "base"  # rosmill/error.hpp, units.hpp, ...
    return rel[1]


def include_graph(root):
    graph = {}
    areas = {p.name for p in (root / "src").iterdir() if p.is_dir()} | {
        p.name for p in (root / "include" / "rosmill").iterdir() if p.is_dir()}
    for path in list((root / "src").rglob("*.[ch]pp")) + list((root / "include" / "rosmill").rglob("*.hpp")):
        area = file_area(root, path)
        deps = graph.setdefault(area, set())
        for target in INCLUDE.findall(path.read_text(errors="replace")):
            if target in areas and target != area:
                deps.add(target)
    return graph


def declared(root):
    text = "\n".join(p.read_text() for p in [root / "CMakeLists.txt", *sorted((root / "cmake").glob("*.cmake"))])
    decl = {}
    for name, rest in AREA_CALL.findall(text):
        m = re.search(r"DEPENDS\s+((?:(?!LIBS)\w+\s*)*)", rest)
        decl[name] = set(m.group(1).split()) if m else set()
    return decl


def closure(decl, area, seen=None):
    seen = set() if seen is None else seen
    for d in decl.get(area, ()):
        if d not in seen:
            seen.add(d)
            closure(decl, d, seen)
    return seen


def cycle(graph):
    state, stack = {}, []

    def visit(a):
        state[a] = 1
        stack.append(a)
        for b in sorted(graph.get(a, ())):
            if state.get(b) == 1:
                return stack[stack.index(b):] + [b]
            if b not in state:
                found = visit(b)
                if found:
                    return found
        state[a] = 2
        stack.pop()
        return None

    for a in sorted(graph):
        if a not in state:
            found = visit(a)
            if found:
                return found
    return None


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    graph = include_graph(root)
    decl = declared(root)
    for a in sorted(graph):
        print(f"{a:10s} -> {' '.join(sorted(graph[a])) or '-'}")
    problems = []
    loop = cycle(graph)
    if loop:
        problems.append("include cycle between areas: " + " -> ".join(loop))
    if decl:
        for a in sorted(graph):
            if a in ("cli", "nodes", "ros"):
                continue
            undeclared = graph[a] - closure(decl, a) - {"base"}
            if undeclared:
                problems.append(f"{a} includes from {', '.join(sorted(undeclared))}, which it does not declare")
    for p in problems:
        print("area_graph: " + p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
