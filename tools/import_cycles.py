"""List the import circles of src/robomodel: the strongly connected components of its module
import graph.

Every ``import``/``from ... import`` inside the package is an edge from the importing module to
the module it names (``from pkg import name`` names ``pkg.name`` when that is a module, else
``pkg``). Imports at module level and inside functions both count: a function-level import
closes a circle as soon as the function runs. Imports under ``if TYPE_CHECKING:`` never run;
a circle that exists only through them is listed apart, marked ``TYPE_CHECKING only``.

Usage::

    python tools/import_cycles.py [SRC_DIR]        # SRC_DIR defaults to src/ beside tools/

It prints one circle a line, its modules sorted and joined by `` ↔ ``, and exits with 0.
"""

from __future__ import annotations

import argparse
import ast
import sys
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Circle", "ImportEdge", "find_circles", "import_edges", "module_names"]

PACKAGE = "robomodel"


@dataclass(frozen=True, slots=True)
class ImportEdge:
    """``source`` imports ``target``; ``type_checking`` when only under ``if TYPE_CHECKING``."""

    source: str
    target: str
    type_checking: bool


@dataclass(frozen=True, slots=True)
class Circle:
    """One strongly connected component of two or more modules (or one importing itself)."""

    modules: tuple[str, ...]
    type_checking_only: bool

    def label(self) -> str:
        return " ↔ ".join(self.modules)


def module_names(src: Path) -> dict[str, Path]:
    """Every module of the package under ``src``: dotted name → file."""
    names: dict[str, Path] = {}
    for path in sorted((src / PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(src).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        names[".".join(parts)] = path
    return names


# the fields of modules, statements, except clauses and match cases that list statements
_STATEMENT_FIELDS = ("body", "orelse", "finalbody", "handlers", "cases")


def _is_type_checking(test: ast.expr) -> bool:
    if isinstance(test, ast.Name):
        return test.id == "TYPE_CHECKING"
    return isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"


def _imports(tree: ast.AST) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
    """Every import statement with whether it sits under ``if TYPE_CHECKING:``."""

    def walk(node: ast.AST, guarded: bool) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
        if isinstance(node, ast.Import | ast.ImportFrom):
            yield node, guarded
            return
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            for child in node.body:
                yield from walk(child, True)
            for child in node.orelse:
                yield from walk(child, guarded)
            return
        # imports are statements: only the statement lists of a node can hold one
        for field in _STATEMENT_FIELDS:
            for child in getattr(node, field, ()):
                yield from walk(child, guarded)

    yield from walk(tree, False)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join([*base, *([node.module] if node.module else [])])


def import_edges(modules: Mapping[str, Path]) -> list[ImportEdge]:
    """The package-internal import edges of ``modules`` (see the module docstring)."""
    edges: set[ImportEdge] = set()
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        is_package = path.name == "__init__.py"
        for node, guarded in _imports(tree):
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            else:
                base = _resolve(name, is_package, node)
                for alias in node.names:
                    sub = f"{base}.{alias.name}"
                    targets.append(sub if sub in modules else base)
            for target in targets:
                # `import a.b.c` binds a and names a.b.c: the edge goes to the deepest known module
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name:
                    edges.add(ImportEdge(name, target, guarded))
    return sorted(edges, key=lambda e: (e.source, e.target, e.type_checking))


def _components(nodes: list[str], graph: Mapping[str, set[str]]) -> list[tuple[str, ...]]:
    """Tarjan's strongly connected components with more than one module (iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[tuple[str, ...]] = []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work: list[tuple[str, Iterator[str]]] = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
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
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                members = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    members.append(top)
                    if top == node:
                        break
                if len(members) > 1:
                    found.append(tuple(sorted(members)))
    return sorted(found)


def find_circles(src: Path) -> list[Circle]:
    """The import circles under ``src``: those that run, then those only ``TYPE_CHECKING`` makes."""
    modules = module_names(src)
    edges = import_edges(modules)
    nodes = sorted(modules)
    running: dict[str, set[str]] = {}
    every: dict[str, set[str]] = {}
    for edge in edges:
        every.setdefault(edge.source, set()).add(edge.target)
        if not edge.type_checking:
            running.setdefault(edge.source, set()).add(edge.target)
    real = _components(nodes, running)
    circles = [Circle(members, False) for members in real]
    circles += [
        Circle(members, True) for members in _components(nodes, every) if members not in real
    ]
    return circles


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("src", nargs="?", type=Path, default=Path(__file__).parent.parent / "src")
    args = parser.parse_args(argv)
    if not (args.src / PACKAGE).is_dir():
        print(f"import_cycles: no {PACKAGE}/ package in {args.src}", file=sys.stderr)
        return 2
    for circle in find_circles(args.src):
        mark = "  [TYPE_CHECKING only]" if circle.type_checking_only else ""
        print(f"{circle.label()}{mark}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
