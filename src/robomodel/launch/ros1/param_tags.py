"""``<param>`` and ``<rosparam>`` (roslaunch 1.16's ``xmlloader.py`` ``_param_tag`` and
``_rosparam_tag``): values with type inference, textfile/binfile/command, load/dump/delete."""

from __future__ import annotations

import os
from typing import Any

from robomodel._yaml_bounded import YamlNestingError
from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros1._loader_base import _PARAM_ATTRS, _ROSPARAM_ATTRS, LoaderBase
from robomodel.launch.ros1.attr_values import strict_bool
from robomodel.launch.ros1.config import ParamDump
from robomodel.launch.ros1.context import LoaderContext
from robomodel.launch.ros1.names import (
    canonicalize_name,
    is_private,
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
    SubstitutionError,
)
from robomodel.runtime.transport.ros1.param_bounds import ParamBoundError, expand_bounded

__all__ = ["ParamTags"]


class ParamTags(LoaderBase):
    """The parameter tags."""

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
            return convert_value(
                run_command(name, command, self.packages, timeout_s=self.command_timeout_s),
                ptype,
            )
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

    def _rosparam_data(
        self, element: Any, ctx: LoaderContext, file: str | None, substitute: bool
    ) -> Any:
        """The YAML of a ``<rosparam>`` (its file or its text), substituted if asked, parsed,
        and expanded apart from its aliases under the parameter server's bound."""
        try:
            text = read_text_file(file, "rosparam file") if file else (element.text or "")
        except ParamValueError as exc:
            raise self.error(str(exc), element, ctx, "file") from None
        if substitute:
            try:
                text = self.subst(text, ctx) or ""
            except SubstitutionError as exc:
                raise self.error(str(exc), element, ctx) from None
        try:
            data = load_rosparam_yaml(text, where=file or "the <rosparam> block")
        except YamlNestingError as exc:  # past the size, nesting or alias bound
            if not (file and exc.line):
                raise self.error(str(exc), element, ctx) from None
            raise LaunchError(
                f"invalid YAML: {exc.problem}",
                location=SourceLocation(file, exc.line, exc.column),
                include_stack=(*self.stack, self.where(element, ctx.filename)),
            ) from None
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
        try:  # aliases expanded once, here, under the server's bound (not on every get)
            return expand_bounded(data, what=f"the <rosparam> {file or 'block'}")
        except ParamBoundError as exc:
            raise self.error(str(exc), element, ctx, "file" if file else None) from None

    def tag_rosparam(self, element: Any, ctx: LoaderContext) -> None:
        self.check_attrs(element, ctx, _ROSPARAM_ATTRS)
        cmd, ns, file, param, subst_value = (self.attr(element, a, ctx) for a in _ROSPARAM_ATTRS)
        try:
            substitute = strict_bool(subst_value, False, "subst_value")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "subst_value") from None
        param = ns_join(ns or "", param or "")
        cmd = cmd or "load"
        if cmd not in ("load", "dump", "delete"):
            raise self.error("command must be 'load', 'dump', or 'delete'", element, ctx, "command")
        if file is not None and cmd == "load" and not os.path.exists(file):
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
        data = self._rosparam_data(element, ctx, file, substitute)
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
