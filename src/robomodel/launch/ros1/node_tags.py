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
)
from robomodel.launch.ros1.attr_values import (
    check_machine,
    check_node,
    check_test,
    strict_bool,
    strict_float,
)
from robomodel.launch.ros1.config import MachineSpec
from robomodel.launch.ros1.context import ContextError, LoaderContext
from robomodel.launch.ros1.names import (
    is_legal_name,
    is_private,
)
from robomodel.launch.ros1.param_tags import ParamTags

__all__ = ["NodeTags"]

_NODE_OPTS = (
    "machine", "args", "output", "respawn", "respawn_delay", "cwd", "launch-prefix", "required",
)  # fmt: skip


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
        default, timeout, ssh_port = (
            self.attr(element, a, ctx) for a in ("default", "timeout", "ssh-port")
        )
        try:
            check_machine(default=default, timeout=timeout, ssh_port=ssh_port)
        except ValueError as exc:
            raise self.error(f"Invalid <machine> tag: {exc}", element, ctx) from None
        self.machines.append(MachineSpec(name, address, self.where(element, ctx.filename)))

    def tag_node(self, element: Any, ctx: LoaderContext, is_test: bool = False) -> None:
        self.check_attrs(element, ctx, _TEST_ATTRS if is_test else _NODE_ATTRS)
        name = self._node_name(element, ctx, is_test)
        child = self.ns_clear_params("node", element, ctx, node_name=name)
        param_ns = child.child(name)
        param_ns.params = []
        pkg = self.required(element, "pkg", ctx)
        node_type = self.required(element, "type", ctx)
        opts = {a: self.attr(element, a, ctx) for a in _NODE_OPTS}
        try:
            required = strict_bool(opts["required"], False, "required")
            respawn = strict_bool(opts["respawn"], False, "respawn")
            respawn_delay = strict_float(opts["respawn_delay"], 0.0, "respawn_delay")
            if respawn and required:
                raise ValueError("respawn and required cannot both be set to true")
            output = "log" if is_test else opts["output"]  # roslaunch: a test's output is log
            check_node(pkg=pkg, node_type=node_type, output=output, cwd=opts["cwd"])
        except ValueError as exc:
            raise self.error(f"Invalid <node> tag: {exc}", element, ctx) from None
        remap_ctx = ctx.child("")
        env_ctx = ctx.child("")
        self._node_children(element, ctx, param_ns, remap_ctx, env_ctx)
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
            clear_params=(self.attr(element, "clear_params", ctx) or "").lower() == "true",
            location=self.where(element, ctx.filename),
            extra={"machine": opts["machine"], "raw_args": opts["args"] or ""},
        )
        (self.tests if is_test else self.nodes).append(spec)

    def _node_children(
        self,
        element: Any,
        ctx: LoaderContext,
        param_ns: LoaderContext,
        remap_ctx: LoaderContext,
        env_ctx: LoaderContext,
    ) -> None:
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

    def _node_name(self, element: Any, ctx: LoaderContext, is_test: bool) -> str:
        if is_test:
            test_name = self.required(element, "test-name", ctx)
            for banned in ("respawn", "respawn_delay", "output"):
                if element.get(banned) is not None:
                    raise self.error(f"<test> tags cannot have '{banned}' attribute", element, ctx)
            time_limit, retry = (self.attr(element, a, ctx) for a in ("time-limit", "retry"))
            try:
                check_test(time_limit=time_limit, retry=retry)
            except ValueError as exc:
                raise self.error(f"Invalid <test> tag: {exc}", element, ctx) from None
            name = self.attr(element, "name", ctx) or test_name
        else:
            name = self.required(element, "name", ctx)
        if not is_legal_name(name):
            self.warnings.append(
                f"{self.where(element, ctx.filename, 'name')}: WARN: illegal <node> name '{name}'"
            )
        return name

    def tag_test(self, element: Any, ctx: LoaderContext) -> None:
        self.tag_node(element, ctx, is_test=True)
