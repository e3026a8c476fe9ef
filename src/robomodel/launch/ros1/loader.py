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
import shlex
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from lxml import etree

from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError, PathEscapeError, RobomodelError, SourceLocation
from robomodel.launch.model import LaunchError, NodeSpec
from robomodel.launch.packages import launch_package_index
from robomodel.launch.ros1.config import MachineSpec, ParamDump, Ros1Launch
from robomodel.launch.ros1.context import ContextError, LoaderContext
from robomodel.launch.ros1.names import (
    canonicalize_name,
    is_legal_name,
    is_private,
    make_global_ns,
    namespaces_of,
    ns_join,
)
from robomodel.launch.ros1.params import (
    ParamValueError,
    convert_value,
    flatten_params,
    load_rosparam_yaml,
    read_binary_file,
    read_text_file,
    run_command,
)
from robomodel.launch.ros1.substitution import (
    ArgNotSet,
    SubstitutionContext,
    SubstitutionError,
    resolve,
)

__all__ = ["load_launch"]

_MAX_INCLUDE_DEPTH = 64
_NODE_ATTRS = (
    "pkg", "type", "machine", "name", "args", "output", "respawn", "respawn_delay", "cwd",
    "ns", "clear_params", "launch-prefix", "required",
)  # fmt: skip
_TEST_ATTRS = (*_NODE_ATTRS, "test-name", "time-limit", "retry")
_PARAM_ATTRS = ("name", "value", "type", "textfile", "binfile", "command")
_ROSPARAM_ATTRS = ("command", "ns", "file", "param", "subst_value")
_ARG_ATTRS = ("name", "value", "default", "doc")
_INCLUDE_ATTRS = ("file", "ns", "clear_params", "pass_all_args")
_GROUP_ATTRS = ("ns", "clear_params")
_MACHINE_ATTRS = (
    "name", "address", "env-loader", "ssh-port", "user", "password", "default", "timeout",
)  # fmt: skip


def _bool(value: str | None, default: bool, label: str) -> bool:
    if value is None:
        return default
    if value.lower() == "true":
        return True
    if value.lower() == "false":
        return False
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    raise ValueError(f"invalid bool value for {label}: {value}")


def _float(value: str | None, default: float, label: str) -> float:
    if value is None:
        return default
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    try:
        return float(value)
    except ValueError:
        raise ValueError(f"invalid float value for {label}: {value}") from None


class _Loader:
    def __init__(self, packages: PackageIndex, environ: Mapping[str, str]) -> None:
        self.packages = packages
        self.environ = environ
        self.params: dict[str, Any] = {}
        self.nodes: list[NodeSpec] = []
        self.tests: list[NodeSpec] = []
        self.clear_params: list[str] = []
        self.deletes: list[str] = []
        self.dumps: list[ParamDump] = []
        self.machines: list[MachineSpec] = []
        self.files: list[Path] = []
        self.warnings: list[str] = []
        self.stack: list[SourceLocation] = []
        self.anons: dict[str, str] = {}
        self.sources: dict[str, list[str]] = {}
        self.root: LoaderContext | None = None

    # -- locations and errors -------------------------------------------------------------
    def where(self, element: Any, filename: str | None, attr: str | None = None) -> SourceLocation:
        line = element.sourceline if element is not None else None
        column = None
        lines = self.sources.get(filename or "")
        if line is not None and lines and 0 < line <= len(lines):
            text = lines[line - 1]
            tag = f"<{element.tag}"
            col = text.find(tag)
            if attr is not None:
                at = text.find(f"{attr}=", max(col, 0))
                col = at if at >= 0 else col
            column = col + 1 if col >= 0 else 1
        return SourceLocation(filename, line, column)

    def error(
        self, message: str, element: Any, ctx: LoaderContext, attr: str | None = None
    ) -> LaunchError:
        return LaunchError(
            message,
            location=self.where(element, ctx.filename, attr),
            include_stack=tuple(self.stack),
        )

    # -- attributes -----------------------------------------------------------------------
    def subst(self, text: str | None, ctx: LoaderContext) -> str | None:
        sub = SubstitutionContext(
            ctx.args, self.find, self.environ, filename=ctx.filename, anons=self.anons
        )
        return resolve(text, sub)

    def find(self, name: str) -> str:
        try:
            return str(self.packages.find(name))
        except PackageNotFoundError as exc:
            raise SubstitutionError(str(exc)) from None

    def attr(self, element: Any, name: str, ctx: LoaderContext) -> str | None:
        value = element.get(name)
        try:
            return self.subst(value, ctx)
        except ArgNotSet:
            raise
        except SubstitutionError as exc:
            raise self.error(str(exc), element, ctx, name) from None

    def required(self, element: Any, name: str, ctx: LoaderContext) -> str:
        if element.get(name) is None:
            raise self.error(
                f"<{element.tag}> tag is missing required attribute: '{name}'", element, ctx
            )
        value = self.attr(element, name, ctx)
        assert value is not None
        return value

    def check_attrs(self, element: Any, ctx: LoaderContext, allowed: tuple[str, ...]) -> None:
        for name in element.attrib:
            if name not in allowed and name not in ("if", "unless"):
                self.warnings.append(
                    f"{self.where(element, ctx.filename, name)}: unknown <{element.tag}> "
                    f"attribute '{name}'; valid attributes are {', '.join(allowed)}"
                )

    def enabled(self, element: Any, ctx: LoaderContext) -> bool:
        """roslaunch's ``ifunless``: ``if`` and ``unless`` together is an error."""
        if_value, unless_value = element.get("if"), element.get("unless")
        if if_value is not None and unless_value is not None:
            raise self.error("cannot set both 'if' and 'unless' on the same tag", element, ctx)
        try:
            if if_value is not None:
                return _bool(self.attr(element, "if", ctx), False, "if")
            if unless_value is not None:
                return not _bool(self.attr(element, "unless", ctx), False, "unless")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx) from None
        return True

    # -- files ----------------------------------------------------------------------------
    def parse(self, filename: str, element: Any, ctx: LoaderContext | None) -> Any:
        path = Path(filename)
        try:
            data = path.read_bytes()
        except OSError as exc:
            message = f"cannot read launch file '{filename}': {exc.strerror}"
            if ctx is None or element is None:
                raise LaunchError(message, include_stack=tuple(self.stack)) from None
            raise self.error(message, element, ctx, "file") from None
        if b"<!ENTITY" in data and b"<!DOCTYPE" in data:
            line = data[: data.find(b"<!ENTITY")].count(b"\n") + 1
            raise LaunchError(
                "entity declarations are not allowed in launch files (expansion bombs, "
                "reading local files)",
                location=SourceLocation(filename, line, 1),
                include_stack=tuple(self.stack),
            )
        parser = etree.XMLParser(
            resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False
        )
        try:
            root = etree.fromstring(data, parser)
        except etree.XMLSyntaxError as exc:
            line, column = exc.position if exc.position else (1, 1)
            message = (exc.msg or "malformed XML").rsplit(", line ", 1)[0]
            raise LaunchError(
                f"Invalid roslaunch XML syntax: {message}",
                location=SourceLocation(filename, line, column),
                include_stack=tuple(self.stack),
            ) from None
        self.sources[filename] = data.decode("utf-8", "replace").splitlines()
        if root.tag != "launch":
            raise LaunchError(
                f"Invalid roslaunch XML syntax: no root <launch> tag (the root is <{root.tag}>)",
                location=SourceLocation(filename, root.sourceline, 1),
                include_stack=tuple(self.stack),
            )
        self.files.append(path)
        return root

    # -- tags -----------------------------------------------------------------------------
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

    def ns_clear_params(
        self,
        tag: str,
        element: Any,
        ctx: LoaderContext,
        node_name: str | None = None,
        include_filename: str | None = None,
    ) -> LoaderContext:
        ns = None
        if element.get("ns") is not None:
            ns = self.attr(element, "ns", ctx)
            if not ns:
                raise self.error(f"<{tag}> tag has an empty 'ns' attribute", element, ctx, "ns")
        try:
            child = (
                ctx.include_child(ns, include_filename)
                if include_filename is not None
                else ctx.child(ns)
            )
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "ns") from None
        clear = self.attr(element, "clear_params", ctx)
        try:
            if clear and _bool(clear, False, "clear_params"):
                if tag == "node":
                    if not node_name:
                        raise ValueError(
                            f"<{tag}> tag must have a 'name' attribute to use 'clear_params'"
                        )
                    self.clear_params.append(make_global_ns(ns_join(child.ns, node_name)))
                else:
                    if not ns:
                        raise ValueError(
                            "'ns' attribute must be set in order to use 'clear_params'"
                        )
                    self.clear_params.append(child.ns)
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "clear_params") from None
        return child

    def add_param(self, key: str, value: Any, element: Any, ctx: LoaderContext) -> None:
        key = canonicalize_name(key)  # roslaunch's Param() does this: "/n//x" -> "/n/x"
        for parent in namespaces_of(key):
            if parent in self.params:
                self.warnings.append(
                    f"{self.where(element, ctx.filename)}: parameter [{key}] conflicts with "
                    f"parent parameter [{parent}]"
                )
        self.params.pop(key, None)  # a later setting moves to the end, as the server's order
        self.params[key] = value

    def param_value(self, element: Any, ctx: LoaderContext, name: str) -> Any:
        ptype = (element.get("type") or "auto").lower().strip()
        value, textfile, binfile, command = (
            self.attr(element, a, ctx) for a in ("value", "textfile", "binfile", "command")
        )
        given = [v for v in (value, textfile, binfile, command) if v is not None]
        if len(given) != 1:
            raise self.error(
                "<param> tag must have one and only one of value/textfile/binfile/command.",
                element,
                ctx,
            )
        try:
            if value is not None:
                return convert_value(value.strip(), ptype)
            if textfile is not None:
                return convert_value(read_text_file(textfile), ptype)
            if binfile is not None:
                return read_binary_file(binfile)
            assert command is not None
            # roslaunch runs the command in its own working directory.
            return convert_value(run_command(name, command, self.packages), ptype)
        except ParamValueError as exc:
            error = self.error(f"Invalid <param> tag: {exc}", element, ctx)
            error.notes = exc.notes  # type: ignore[attr-defined]
            raise error from None

    def tag_param(self, element: Any, ctx: LoaderContext, force_local: bool = False) -> None:
        self.check_attrs(element, ctx, _PARAM_ATTRS)
        if element.get("name") is None:
            raise self.error("<param> tag is missing required attribute: 'name'", element, ctx)
        name = (self.attr(element, "name", ctx) or "").strip()
        value = self.param_value(element, ctx, name)
        if is_private(name) or force_local:
            ctx.add_param(name, value)
        else:
            self.add_param(ns_join(ctx.ns, name), value, element, ctx)

    def tag_rosparam(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _ROSPARAM_ATTRS)
        cmd, ns, file, param, subst_value = (self.attr(element, a, ctx) for a in _ROSPARAM_ATTRS)
        try:
            substitute = _bool(subst_value, False, "subst_value")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "subst_value") from None
        param = ns_join(ns or "", param or "")
        cmd = cmd or "load"
        if cmd not in ("load", "dump", "delete"):
            raise self.error("command must be 'load', 'dump', or 'delete'", element, ctx, "command")
        if file is not None and cmd == "load" and not os.path.isfile(file):
            raise self.error(f"file does not exist [{file}]", element, ctx, "file")
        if file is not None and cmd == "delete":
            raise self.error(
                "'file' attribute is invalid with 'delete' command.", element, ctx, "file"
            )
        full = ns_join(ctx.ns, param) if param else ctx.ns
        if cmd == "dump":
            self.dumps.append(ParamDump(file or "", full))
            return
        if cmd == "delete":
            self.deletes.append(full)
            return
        text = Path(file).read_text(encoding="utf-8") if file else (element.text or "")
        if substitute:
            try:
                text = self.subst(text, ctx) or ""
            except SubstitutionError as exc:
                raise self.error(str(exc), element, ctx) from None
        try:
            data = load_rosparam_yaml(text)
        except Exception as exc:
            where = f"file {file} contains invalid YAML" if file else "Error within YAML block"
            mark = getattr(exc, "problem_mark", None)
            error = self.error(f"{where}: {exc}", element, ctx)
            if file and mark is not None:
                error = LaunchError(
                    f"invalid YAML: {getattr(exc, 'problem', exc)}",
                    location=SourceLocation(file, mark.line + 1, mark.column + 1),
                    include_stack=(*self.stack, self.where(element, ctx.filename)),
                )
            raise error from None
        if not param and not isinstance(data, dict):
            raise self.error(
                "'param' attribute must be set for non-dictionary values", element, ctx
            )
        if full == "/" and not isinstance(data, dict):
            raise self.error(
                "Cannot load non-dictionary types into global namespace '/'", element, ctx
            )
        flat: dict[str, Any] = {}
        flatten_params(full, data, flat, ns_join)
        if is_private(full):
            for key, value in flat.items():
                ctx.add_param(key, value)
            return
        for key, value in flat.items():
            self.add_param(key, value, element, ctx)

    def tag_remap(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, ("from", "to"))
        source = self.required(element, "from", ctx)
        target = self.required(element, "to", ctx)
        try:
            ctx.add_remap(source, target)
        except ContextError as exc:
            raise self.error(f"Invalid <remap> tag: {exc}", element, ctx) from None

    def tag_env(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, ("name", "value"))
        name = self.required(element, "name", ctx)
        value = self.required(element, "value", ctx)
        if not name:
            raise self.error("'name' attribute must be non-empty", element, ctx, "name")
        ctx.env_args.append((name, value))

    def tag_machine(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _MACHINE_ATTRS)
        name = self.required(element, "name", ctx)
        address = self.required(element, "address", ctx)
        self.machines.append(MachineSpec(name, address, self.where(element, ctx.filename)))

    def tag_node(self, element: Any, ctx: LoaderContext, is_test: bool = False) -> None:
        self.check_attrs(element, ctx, _TEST_ATTRS if is_test else _NODE_ATTRS)
        if is_test:
            test_name = self.required(element, "test-name", ctx)
            for banned in ("respawn", "respawn_delay", "output"):
                if element.get(banned) is not None:
                    raise self.error(f"<test> tags cannot have '{banned}' attribute", element, ctx)
            name = self.attr(element, "name", ctx) or test_name
        else:
            name = self.required(element, "name", ctx)
        if not is_legal_name(name):
            self.warnings.append(
                f"{self.where(element, ctx.filename, 'name')}: WARN: illegal <node> name '{name}'"
            )
        child = self.ns_clear_params("node", element, ctx, node_name=name)
        param_ns = child.child(name)
        param_ns.params = []
        pkg = self.required(element, "pkg", ctx)
        node_type = self.required(element, "type", ctx)
        opts = {
            a: self.attr(element, a, ctx)
            for a in (
                "machine",
                "args",
                "output",
                "respawn",
                "respawn_delay",
                "cwd",
                "launch-prefix",
                "required",
            )
        }
        try:
            required = _bool(opts["required"], False, "required")
            respawn = _bool(opts["respawn"], False, "respawn")
            respawn_delay = _float(opts["respawn_delay"], 0.0, "respawn_delay")
        except ValueError as exc:
            raise self.error(f"Invalid <node> tag: {exc}", element, ctx) from None
        remap_ctx = ctx.child("")
        env_ctx = ctx.child("")
        for sub in element:
            if not isinstance(sub.tag, str):
                continue
            if not self.enabled(sub, ctx):
                continue
            if sub.tag == "remap":
                self.tag_remap(sub, remap_ctx)
            elif sub.tag == "param":
                self.tag_param(sub, param_ns, force_local=True)
            elif sub.tag == "rosparam":
                self.tag_rosparam(sub, param_ns)
            elif sub.tag == "env":
                self.tag_env(sub, env_ctx)
            else:
                self.warnings.append(
                    f"{self.where(sub, ctx.filename)}: WARN: unrecognized '{sub.tag}' child tag "
                    f"in <{element.tag}>"
                )
        for key, value in (*ctx.params, *param_ns.params):
            pkey = key[1:] if is_private(key) else key
            self.add_param(param_ns.ns + pkey, value, element, ctx)
        try:
            args = tuple(shlex.split(opts["args"] or ""))
        except ValueError as exc:
            raise self.error(f"Invalid <node> tag: args: {exc}", element, ctx, "args") from None
        spec = NodeSpec(
            dialect="ros1",
            package=pkg,
            executable=node_type,
            name=name,
            namespace=child.ns,
            args=args,
            remaps=tuple(remap_ctx.remap_args()),
            env=tuple(env_ctx.env_args),
            required=required,
            respawn=respawn,
            respawn_delay_s=respawn_delay,
            output=opts["output"],
            launch_prefix=opts["launch-prefix"],
            cwd=opts["cwd"],
            clear_params=bool(element.get("clear_params")),
            location=self.where(element, ctx.filename),
            extra={"machine": opts["machine"], "raw_args": opts["args"] or ""},
        )
        (self.tests if is_test else self.nodes).append(spec)

    def tag_test(self, element: Any, ctx: LoaderContext) -> None:
        self.tag_node(element, ctx, is_test=True)

    def tag_include(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _INCLUDE_ATTRS)
        filename = self.required(element, "file", ctx)
        try:
            pass_all = _bool(self.attr(element, "pass_all_args", ctx), False, "pass_all_args")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "pass_all_args") from None
        if not os.path.isabs(filename) and ctx.filename:
            filename = os.path.join(os.getcwd(), filename)
        child = self.ns_clear_params("include", element, ctx, include_filename=filename)
        if pass_all:
            for name, value in ctx.args.items():
                child.add_arg(name, value=value, default=None, doc=None)
            child.pass_all_args = True
        child.filename = ctx.filename  # the include's own <arg>s resolve in the parent's file
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
            warnings=tuple(self.warnings),
        )


def load_launch(
    path: str | os.PathLike[str],
    *,
    args: Mapping[str, str] | None = None,
    packages: PackageIndex | None = None,
    environ: Mapping[str, str] | None = None,
) -> Ros1Launch:
    """Load a ROS 1 launch file as roslaunch 1.16 does (nothing is started).

    Args:
        path: The launch file.
        args: Command-line ``name:=value`` args (they set the top-level file's args).
        packages: Where ``$(find pkg)`` looks (robomodel's built-in packages are added last).
        environ: The environment for ``$(env)``/``$(optenv)`` (default: ``os.environ``).

    Raises:
        LaunchError: with the file:line:column of the offending element and the include stack.
    """
    source = Path(path)
    index = packages or PackageIndex()
    index = launch_package_index(index.with_workspace_of(source) if source.exists() else index)
    loader = _Loader(index, os.environ if environ is None else environ)
    try:
        return loader.load(Path(os.path.abspath(source)), dict(args or {}))
    except (PackageNotFoundError, PathEscapeError) as exc:
        raise LaunchError(str(exc), include_stack=tuple(loader.stack)) from None
    except RobomodelError:
        raise
