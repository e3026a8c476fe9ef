"""List the import circles of a package: the strongly connected components of its module
import graph, with module-level and function-level imports as edges.

Each edge is marked by where the import stands: ``module`` (at module level), ``function``
(inside a function or method body) or ``typing`` (under ``if TYPE_CHECKING``). A component is
printed with its modules and the edges that hold it together.

Usage:
    python tools/import_cycles.py [--root src] [--prefix robomodel.launch] [--runtime-only]

``--runtime-only`` leaves the ``typing`` edges out (they are never executed). The exit code is
0; the last line gives the number of components found.
"""

from __future__ import annotations

import argparse
import ast
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True, slots=True)
class Edge:
    """One import from ``source`` of ``target`` at ``line``, of kind module/function/typing."""

    source: str
    target: str
    line: int
    kind: str


def module_names(root: Path, package: str) -> dict[str, Path]:
    """Every module under ``root`` whose dotted name starts with ``package``."""
    found: dict[str, Path] = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        name = ".".join(parts)
        if name == package or name.startswith(package + "."):
            found[name] = path
    return found


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(tree: ast.AST, module: str, is_package: bool) -> Iterator[tuple[str, int, str]]:
    """``(imported name, line, kind)`` for every import in ``tree``."""

    def walk(node: ast.AST, kind: str) -> Iterator[tuple[str, int, str]]:
        for child in ast.iter_child_nodes(node):
            child_kind = kind
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                child_kind = "function" if kind == "module" else kind
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                for sub in child.body:
                    yield from walk_one(sub, "typing")
                for sub in child.orelse:
                    yield from walk_one(sub, kind)
                continue
            yield from walk_one(child, child_kind)

    def walk_one(node: ast.AST, kind: str) -> Iterator[tuple[str, int, str]]:
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, node.lineno, kind
        elif isinstance(node, ast.ImportFrom):
            base = _absolute(node, module, is_package)
            for alias in node.names:
                yield f"{base}.{alias.name}" if base else alias.name, node.lineno, kind
        else:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                kind = "function" if kind == "module" else kind
            yield from walk(node, kind)

    yield from walk(tree, "module")


def _absolute(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    if not node.level:
        return node.module or ""
    parts = module.split(".")
    if not is_package:
        parts = parts[:-1]
    parts = parts[: len(parts) - (node.level - 1)]
    return ".".join([*parts, node.module] if node.module else parts)


def edges(modules: dict[str, Path]) -> list[Edge]:
    """The import edges between ``modules``: ``from a.b import c`` names ``a.b.c`` when that
    is a module, else ``a.b``; importing ``a.b.c`` runs ``a`` and ``a.b`` too, except those
    that hold the importing module (Python has started them before it)."""
    found: dict[tuple[str, str], Edge] = {}
    rank = {"module": 0, "function": 1, "typing": 2}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for target, line, kind in _imports(tree, name, path.name == "__init__.py"):
            for hit in _targets(target, modules, name):
                if hit == name:
                    continue
                old = found.get((name, hit))
                if old is None or rank[kind] < rank[old.kind]:
                    found[(name, hit)] = Edge(name, hit, line, kind)
    return sorted(found.values(), key=lambda e: (e.source, e.target))


def _targets(target: str, modules: dict[str, Path], source: str) -> list[str]:
    """The modules that importing ``target`` from ``source`` runs: ``target`` itself (or, for
    a name that is no module, the module that defines it), and its parent packages that are
    not ``source``'s own (those are always set up before ``source`` runs)."""
    parts = target.split(".")
    chain = [".".join(parts[:i]) for i in range(1, len(parts) + 1)]
    chain = [m for m in chain if m in modules]
    if not chain:
        return []
    primary = chain[-1]
    return [m for m in chain[:-1] if not source.startswith(m + ".")] + [primary]


def components(nodes: list[str], graph: list[Edge]) -> list[list[str]]:
    """Tarjan's strongly connected components with more than one module."""
    succ: dict[str, list[str]] = {n: [] for n in nodes}
    for edge in graph:
        succ[edge.source].append(edge.target)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))

    def visit(v: str) -> None:
        nonlocal counter
        index[v] = low[v] = counter
        counter += 1
        stack.append(v)
        on_stack.add(v)
        for w in succ[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp: list[str] = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in nodes:
        if v not in index:
            visit(v)
    return sorted(out, key=lambda c: (-len(c), c))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default="src", help="the folder that holds the package")
    parser.add_argument("--package", default="robomodel", help="the graph's modules")
    parser.add_argument(
        "--prefix",
        action="append",
        default=[],
        help="report only components with a module under this prefix (repeatable)",
    )
    parser.add_argument("--runtime-only", action="store_true", help="leave out TYPE_CHECKING")
    parser.add_argument("--quiet", action="store_true", help="module lists only, no edges")
    args = parser.parse_args(argv)
    modules = module_names(Path(args.root), args.package)
    graph = [e for e in edges(modules) if not (args.runtime_only and e.kind == "typing")]
    found = components(sorted(modules), graph)
    if args.prefix:
        found = [c for c in found if any(m.startswith(p) for m in c for p in args.prefix)]
    for number, comp in enumerate(found, 1):
        members = set(comp)
        inner = [e for e in graph if e.source in members and e.target in members]
        kinds = sorted({e.kind for e in inner})
        print(f"component {number}: {len(comp)} modules ({', '.join(kinds)} edges)")
        for name in comp:
            print(f"  {name}")
        if not args.quiet:
            for e in inner:
                print(f"    {e.source} -> {e.target} ({e.kind}, line {e.line})")
    print(f"{len(found)} import circles")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
