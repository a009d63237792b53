#!/usr/bin/env python3
"""The include graph of hexcal's layers, checked against docs/architecture.md.

A module is a header and the source of the same name (devices/controller.h
and devices/controller.cc); module A depends on module B when a file of A
includes B's header. The check fails on
  - a cycle between modules (A includes B and B, directly or not, includes A),
  - an include from one layer into another that the "depends on" column of
    docs/architecture.md's layer table does not allow (transitively: app may
    include core because workflow depends on it).
Test files (*_test.cc, ui/tests/) are modules of their own: nothing includes
them, so they sit in no cycle; their includes of tests/ (test support) are
allowed. Prints every finding and exits 1, or a one-line summary and 0.

  tests/include_graph.py [SOURCE_DIR]                # CTest: project/include_graph
  tests/include_graph.py --self-test [SOURCE_DIR]    # CTest: project/include_graph_self_test
"""
import os
import re
import shutil
import sys
import tempfile

LAYERS = ["core", "vision", "charts", "devices", "session", "sim", "report", "workflow", "app", "ui"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SOURCE_SUFFIXES = (".h", ".cc", ".inc", ".c")


def allowed_directions(architecture_md):
    """{layer: layers it may include}, from the layer table's "depends on" column, closed transitively."""
    direct = {}
    for line in open(architecture_md, encoding="utf-8"):
        cells = [c.strip() for c in line.split("|")]
        if len(cells) < 5:
            continue
        match = re.fullmatch(r"`(\w+)/`", cells[1])
        if not match or match.group(1) not in LAYERS:
            continue
        words = set(re.findall(r"[A-Za-z]+", cells[3]))
        direct[match.group(1)] = {layer for layer in LAYERS if layer in words}
    missing = [layer for layer in LAYERS if layer not in direct]
    if missing:
        sys.exit("include_graph: docs/architecture.md's layer table has no row for " + ", ".join(missing))
    closed = {}
    for layer in LAYERS:
        seen, todo = set(), [layer]
        while todo:
            for dep in direct[todo.pop()]:
                if dep not in seen:
                    seen.add(dep)
                    todo.append(dep)
        closed[layer] = seen | {layer}
    return closed


def module_of(path):
    return os.path.splitext(path)[0]


def is_test(path):
    return path.endswith("_test.cc") or "/tests/" in path


def scan(source_dir):
    """[(including file, included path)] of every project include in the layers' files."""
    edges = []
    for layer in LAYERS:
        for root, _, files in os.walk(os.path.join(source_dir, layer)):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                full = os.path.join(root, name)
                path = os.path.relpath(full, source_dir).replace(os.sep, "/")
                text = open(full, encoding="utf-8", errors="replace").read()
                for included in INCLUDE.findall(text):
                    if included.split("/")[0] in LAYERS + ["tests"]:
                        edges.append((path, included))
    return edges


def find_cycles(graph):
    """Each strongly connected component of more than one module (Tarjan), sorted."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []
    counter = [0]

    def visit(node):
        index[node] = low[node] = counter[0]
        counter[0] += 1
        stack.append(node)
        on_stack.add(node)
        for succ in sorted(graph.get(node, ())):
            if succ not in index:
                visit(succ)
                low[node] = min(low[node], low[succ])
            elif succ in on_stack:
                low[node] = min(low[node], index[succ])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    sys.setrecursionlimit(10000)
    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(components)


def shortest_cycle(graph, component):
    """A shortest cycle through the first module of `component` (breadth first), start repeated at the end."""
    members, start = set(component), component[0]
    parents, frontier = {start: None}, [start]
    while frontier:
        following = []
        for node in frontier:
            for succ in sorted(graph.get(node, ())):
                if succ == start:
                    path, at = [start], node
                    while at is not None:
                        path.append(at)
                        at = parents[at]
                    return path[::-1]
                if succ in members and succ not in parents:
                    parents[succ] = node
                    following.append(succ)
        frontier = following
    return component  # unreachable: every module of a strongly connected component is on a cycle


def check(source_dir):
    """(problems, module graph) of the tree at `source_dir`: every wrong include and every cycle, as lines."""
    allowed = allowed_directions(os.path.join(source_dir, "docs", "architecture.md"))
    problems = []
    graph = {}
    for path, included in scan(source_dir):
        source_layer, target_layer = path.split("/")[0], included.split("/")[0]
        if target_layer == "tests":
            if not is_test(path):
                problems.append(f"{path}: includes {included}, test support, outside a test")
            continue
        if target_layer not in allowed[source_layer]:
            problems.append(f"{path}: includes {included}: {source_layer}/ may include only "
                            + ", ".join(sorted(allowed[source_layer])) + " (docs/architecture.md)")
        if not os.path.exists(os.path.join(source_dir, included)):
            continue  # generated (embedded presets) or a typo the compiler reports
        source, target = (path if is_test(path) else module_of(path)), module_of(included)
        if source != target:
            graph.setdefault(source, set()).add(target)
    for component in find_cycles(graph):
        problems.append(f"include cycle ({len(component)} modules include each other): "
                        + " -> ".join(shortest_cycle(graph, component)))
    return problems, graph


def self_test(source_dir):
    """The check must fail on what it is there to catch: a small tree with a cycle through a
    helper header (the shape of the five cycles issue 37 removed) and a core/ include of ui/."""
    with tempfile.TemporaryDirectory() as tree:
        os.makedirs(os.path.join(tree, "docs"))
        shutil.copy(os.path.join(source_dir, "docs", "architecture.md"), os.path.join(tree, "docs"))
        files = {
            "core/fit.h": '#include "core/fit_types.h"\n',
            "core/fit.cc": '#include "core/fit.h"\n#include "core/fit_helper.h"\n',
            "core/fit_helper.h": '#include "core/fit.h"\n',  # the helper includes the main header back
            "core/fit_types.h": "",
            "core/plot.cc": '#include "ui/main_window.h"\n',
            "ui/main_window.h": "",
        }
        for path, text in files.items():
            os.makedirs(os.path.join(tree, os.path.dirname(path)), exist_ok=True)
            with open(os.path.join(tree, path), "w", encoding="utf-8") as out:
                out.write(text)
        problems, _ = check(tree)
    expected = ["core/plot.cc: includes ui/main_window.h: core/ may include only core (docs/architecture.md)",
                "include cycle (2 modules include each other): core/fit -> core/fit_helper -> core/fit"]
    if problems != expected:
        print("include_graph self-test: expected\n  " + "\n  ".join(expected) + "\ngot\n  " + "\n  ".join(problems))
        return 1
    print("include graph self-test: the cycle and the wrong layer include are found")
    return 0


def main():
    arguments = sys.argv[1:]
    testing = "--self-test" in arguments
    arguments = [a for a in arguments if a != "--self-test"]
    source_dir = arguments[0] if arguments else os.path.join(os.path.dirname(__file__), "..")
    if testing:
        return self_test(source_dir)
    problems, graph = check(source_dir)
    for problem in problems:
        print(problem)
    if problems:
        return 1
    print(f"include graph: {len(graph)} modules, {sum(len(v) for v in graph.values())} module includes, "
          "no cycle, every layer include allowed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
