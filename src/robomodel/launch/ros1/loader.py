"""The roslaunch XML loader (roslaunch 1.16's ``xmlloader.py``), producing a :class:`Ros1Launch`.

Every rule of the reference is kept: args (value/default, command line only at the top level,
include args and ``pass_all_args``, "unused args" errors), ``if``/``unless``, namespaces of
groups, includes and nodes, ``~private`` params collected for the next nodes of their scope,
remaps and env at every scope, ``clear_params``, ``<rosparam>`` load/dump/delete with
``subst_value``, ``<machine>`` and ``<test>``. Errors are :class:`LaunchError` with the
element's file:line:column and the include stack.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError, PathEscapeError, RobomodelError, SourceLocation
from robomodel.launch.bounds import INCLUDE_WORK
from robomodel.launch.model import LaunchError
from robomodel.launch.packages import launch_package_index
from robomodel.launch.processes import COMMAND_TIMEOUT_S
from robomodel.launch.ros1._loader_base import (
    _ARG_ATTRS,
    _GROUP_ATTRS,
    _INCLUDE_ATTRS,
    _MAX_INCLUDE_DEPTH,
)
from robomodel.launch.ros1.attr_values import strict_bool
from robomodel.launch.ros1.config import Ros1Launch
from robomodel.launch.ros1.context import ContextError, LoaderContext
from robomodel.launch.ros1.node_tags import NodeTags
from robomodel.launch.ros1.substitution import (
    ArgNotSet,
    SubstitutionError,
)

__all__ = ["load_launch"]


class _Loader(NodeTags):
    """The whole loader: recursion, args, groups, includes and the entry point."""

    def recurse(self, elements: Any, ctx: LoaderContext) -> None:
        for element in elements:
            if not isinstance(element.tag, str):
                continue  # comments, processing instructions
            handler = getattr(self, "tag_" + element.tag.replace("-", "_"), None)
            if handler is None:
                self.warnings.append(
                    f"{self.where(element, ctx.filename)}: unrecognized tag <{element.tag}>"
                )
                continue
            self.charge(1, element, ctx)
            try:
                if element.tag not in ("group",) and not self.enabled(element, ctx):
                    continue
                handler(element, ctx)
            except ArgNotSet as exc:  # the innermost element that used the arg
                if exc.location is None:
                    exc.location = self.where(element, ctx.filename)
                raise

    def tag_master(self, element: Any, ctx: LoaderContext) -> None:
        self.warnings.append("WARNING: ignoring defunct <master /> tag")

    def tag_arg(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _ARG_ATTRS)
        try:
            name = self.required(element, "name", ctx)
            value = self.attr(element, "value", ctx)
            default = self.attr(element, "default", ctx)
            doc = self.attr(element, "doc", ctx)
        except ArgNotSet as exc:
            raise self.error(f"arg '{exc.name}' is not defined. {exc}", element, ctx) from None
        if value is not None and default is not None:
            raise self.error("<arg> tag must have one and only one of value/default.", element, ctx)
        self.declared_args[name] = None
        try:
            ctx.add_arg(name, value=value, default=default, doc=doc)
        except ContextError as exc:
            raise self.error(str(exc), element, ctx) from None

    def tag_group(self, element: Any, ctx: LoaderContext) -> None:
        if not self.enabled(element, ctx):
            return
        self.check_attrs(element, ctx, _GROUP_ATTRS)
        child = self.ns_clear_params("group", element, ctx)
        child.params = list(child.params)  # a group encloses the ~params set inside it
        self.recurse(element, child)

    def _include_children(self, element: Any, ctx: LoaderContext, child: LoaderContext) -> None:
        """An include's ``<env>`` and ``<arg>`` children, resolved in the parent's file."""
        child.filename = ctx.filename
        for sub in element:
            if not isinstance(sub.tag, str) or not self.enabled(sub, ctx):
                continue
            if sub.tag == "env":
                self.tag_env(sub, child)
            elif sub.tag == "arg":
                self.tag_arg(sub, child)
            else:
                self.warnings.append(
                    f"{self.where(sub, ctx.filename)}: WARN: unrecognized '{sub.tag}' tag in "
                    "<include> tag"
                )

    def tag_include(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _INCLUDE_ATTRS)
        filename = self.required(element, "file", ctx)
        try:
            pass_all = strict_bool(self.attr(element, "pass_all_args", ctx), False, "pass_all_args")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "pass_all_args") from None
        if not os.path.isabs(filename) and ctx.filename:
            filename = os.path.join(os.getcwd(), filename)
        child = self.ns_clear_params("include", element, ctx, include_filename=filename)
        if pass_all:
            for name, value in ctx.args.items():
                child.add_arg(name, value=value, default=None, doc=None)
            child.pass_all_args = True
        self._include_children(element, ctx, child)
        child.filename = filename
        try:
            child.process_include_args()
        except ContextError as exc:
            raise self.error(str(exc), element, ctx) from None
        if len(self.stack) >= _MAX_INCLUDE_DEPTH:
            raise self.error(
                f"includes nested deeper than {_MAX_INCLUDE_DEPTH} levels; does a file include "
                "itself?",
                element,
                ctx,
            )
        self.charge(INCLUDE_WORK, element, ctx)
        self.stack.append(self.where(element, ctx.filename, "file"))
        try:
            root = self.parse(filename, element, ctx)
            try:
                self.recurse(root, child)
            except ArgNotSet as exc:
                raise LaunchError(
                    f"included file [{filename}] requires the '{exc.name}' arg to be set; "
                    f'pass it with <arg name="{exc.name}" value="..."/> inside the <include>',
                    location=self.where(element, ctx.filename),
                    include_stack=tuple(self.stack[:-1]),
                ) from None
            if not pass_all:
                unused = child.unused_include_args()
                if unused:
                    raise LaunchError(
                        f"unused args [{', '.join(unused)}] for include of [{filename}]",
                        location=self.where(element, ctx.filename),
                        include_stack=tuple(self.stack[:-1]),
                    )
        finally:
            self.stack.pop()

    # -- entry ----------------------------------------------------------------------------
    def load(self, path: Path, argv: Mapping[str, str]) -> Ros1Launch:
        filename = str(path)
        root = self.parse(filename, None, None)
        ctx = LoaderContext(self.environ.get("ROS_NAMESPACE", "/") or "/", filename)
        ctx.resolve_dict["arg"] = dict(argv)
        self.root = ctx
        try:
            self.recurse(root, ctx)
        except ArgNotSet as exc:
            raise LaunchError(
                f"[{filename}] requires the '{exc.name}' arg to be set: pass {exc.name}:=VALUE",
                location=exc.location or SourceLocation(filename),
            ) from None
        except (SubstitutionError, ContextError) as exc:
            raise LaunchError(str(exc), location=SourceLocation(filename)) from None
        docs = dict(ctx.resolve_dict.get("arg_doc", {}))
        return Ros1Launch(
            path=path,
            params=dict(self.params),
            nodes=tuple(self.nodes),
            tests=tuple(self.tests),
            clear_params=tuple(self.clear_params),
            param_deletes=tuple(self.deletes),
            param_dumps=tuple(self.dumps),
            machines=tuple(self.machines),
            files=tuple(self.files),
            arg_docs=docs,
            declared_args=tuple(self.declared_args),
            warnings=tuple(self.warnings),
        )


def load_launch(
    path: str | os.PathLike[str],
    *,
    args: Mapping[str, str] | None = None,
    packages: PackageIndex | None = None,
    environ: Mapping[str, str] | None = None,
    command_timeout_s: float = COMMAND_TIMEOUT_S,
) -> Ros1Launch:
    """Load a ROS 1 launch file as roslaunch 1.16 does (nothing is started).

    Args:
        path: The launch file.
        args: Command-line ``name:=value`` args (they set the top-level file's args).
        packages: Where ``$(find pkg)`` looks (robomodel's built-in packages are added last).
        environ: The environment for ``$(env)``/``$(optenv)`` (default: ``os.environ``).
        command_timeout_s: The longest a ``<param command=...>`` may run.

    Raises:
        LaunchError: with the file:line:column of the offending element and the include stack.
    """
    source = Path(path)
    index = packages or PackageIndex()
    index = launch_package_index(index.with_workspace_of(source) if source.exists() else index)
    loader = _Loader(
        index, os.environ if environ is None else environ, command_timeout_s=command_timeout_s
    )
    try:
        return loader.load(Path(os.path.abspath(source)), dict(args or {}))
    except (PackageNotFoundError, PathEscapeError) as exc:
        raise LaunchError(str(exc), include_stack=tuple(loader.stack)) from None
    except RobomodelError:
        raise
