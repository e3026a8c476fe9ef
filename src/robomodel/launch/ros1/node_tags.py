"""``<node>``, ``<test>``, ``<remap>``, ``<env>`` and ``<machine>`` (roslaunch 1.16's
``xmlloader.py``): a node's name, namespace, args, private params, remaps and env."""

from __future__ import annotations

import shlex
from typing import Any

from robomodel.launch.model import NodeSpec
from robomodel.launch.ros1._loader_base import (
    _MACHINE_ATTRS,
    _NODE_ATTRS,
    _TEST_ATTRS,
    _bool,
    _float,
)
from robomodel.launch.ros1.config import MachineSpec
from robomodel.launch.ros1.context import ContextError, LoaderContext
from robomodel.launch.ros1.names import (
    is_legal_name,
    is_private,
)
from robomodel.launch.ros1.param_tags import ParamTags

__all__ = ["NodeTags"]


class NodeTags(ParamTags):
    """The node tags and what nodes collect from their scope."""

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
