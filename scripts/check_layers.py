#!/usr/bin/env python3
"""Check adjoin's layering (SPEC §4): no file includes a higher layer, no include cycle.

Every file under include/adjoin/<layer>/ and src/<layer>/ belongs to <layer>; src/ mirrors
include/adjoin/, src/detail/ holds private helpers at the core level, and src/cli/ is the top.
The layers, low to high, are LAYERS below. A file may include its own layer and any lower one,
through "adjoin/..." (public headers) or a path relative to itself (its layer's private
headers). A file outside every layer, an include that names no file, or a cycle between files
is an error too.

Usage: scripts/check_layers.py [project root]   (exit 0 when clean, 1 otherwise)
"""
import os
import re
import sys

LAYERS = ["core", "structure", "ground", "fractional", "solver",
          "observe", "post", "study", "io", "cli"]
# Folders of src/ that are not a layer's own name, and the layer they sit at.
SRC_ALIASES = {"detail": "core"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
SUFFIXES = (".hpp", ".cpp", ".h", ".inl")


def layer_of(rel):
    """The layer of a project-relative path, or None when it is in no layer."""
    parts = rel.split("/")
    if parts[:2] == ["include", "adjoin"] and len(parts) > 3:
        name = parts[2]
    elif parts[0] == "src" and len(parts) > 2:
        name = SRC_ALIASES.get(parts[1], parts[1])
    else:
        return None
    return name if name in LAYERS else None


def project_files(root):
    for top in ("include/adjoin", "src"):
        for folder, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if name.endswith(SUFFIXES):
                    yield os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")


def resolve(root, rel, target):
    """The project-relative file an #include "target" in rel names, or None."""
    if target.startswith("adjoin/"):
        candidate = "include/" + target
    else:
        candidate = os.path.normpath(os.path.join(os.path.dirname(rel), target)).replace(os.sep, "/")
    return candidate if os.path.isfile(os.path.join(root, candidate)) else None


def find_cycles(graph):
    """Every strongly connected component with more than one file (Tarjan), or a self-include."""
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []
    counter = [0]

    def visit(start):
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1 or node in graph.get(node, ()):
                    cycles.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return cycles


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    root = os.path.abspath(root)
    problems, graph, files, edges = [], {}, 0, 0
    for rel in project_files(root):
        files += 1
        own = layer_of(rel)
        if own is None:
            problems.append(f"{rel}: not in a layer (put it under one of: {', '.join(LAYERS)})")
        with open(os.path.join(root, rel), encoding="utf-8") as handle:
            text = handle.read()
        graph[rel] = set()
        for match in INCLUDE.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            target = match.group(1)
            found = resolve(root, rel, target)
            if found is None:
                problems.append(f'{rel}:{line}: #include "{target}" names no file of the project')
                continue
            graph[rel].add(found)
            edges += 1
            theirs = layer_of(found)
            if own is not None and theirs is not None and LAYERS.index(theirs) > LAYERS.index(own):
                problems.append(f'{rel}:{line}: {own} includes the higher layer {theirs} ("{target}")')
    for cycle in find_cycles(graph):
        problems.append("include cycle between: " + ", ".join(cycle))
    for problem in problems:
        print("error: " + problem)
    print(f"check_layers: {files} files, {edges} project includes, layers "
          f"{' < '.join(LAYERS)}: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
