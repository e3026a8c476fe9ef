"""Interface packages as Python modules: ``std_msgs.msg``, ``example_interfaces.srv``,
``my_interfaces.action``, with no build step.

A package is known when robomodel has its types: its own classes, its copies of the common
interfaces, the ``msg/``, ``srv/`` and ``action/`` folders of the packages on the package path
(``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``), or rosbags' type stores. Each module gives its
types by name on first access (``from std_msgs.msg import String``), and lists them in
``__all__`` (``from std_srvs.srv import *``). The classes are of the process's flavour when the
module is first imported (:func:`robomodel.clientlibs.messages.flavour`): rclpy's or rospy's.
"""

from __future__ import annotations

import functools
import importlib.machinery
import os
from pathlib import Path
from types import ModuleType
from typing import Any

TYPE_CHECKING = False
if TYPE_CHECKING:
    from importlib.abc import Loader as _LoaderBase
else:
    _LoaderBase = object  # importlib.abc would import importlib.resources at every start

__all__ = ["KINDS", "find_spec", "module_names", "package_names", "type_names"]

KINDS = ("msg", "srv", "action")


def _all_type_names() -> frozenset[str]:
    """Every ``pkg/kind/Name`` robomodel can give a class for (found again when the resolver's
    sources change: ``robomodel run --package-path``)."""
    from robomodel.runtime.msg import _resolver

    _use_workspace_src()
    return _type_names_of(_resolver.generation())


@functools.cache
def _type_names_of(generation: int) -> frozenset[str]:
    from robomodel.runtime.msg import _resolver
    from robomodel.runtime.msg.action import _ACTIONS
    from robomodel.runtime.msg.schema import message_type_names, service_type_names

    names = {*message_type_names(), *service_type_names(), *_ACTIONS}
    return frozenset(names | _resolver.definition_names())


_workspace_checked: list[str] = []


def _use_workspace_src() -> None:
    """Add the interface packages of the working folder's workspace ``src/`` (at
    ``src/<name>`` or ``src/<group>/<name>``, with ``msg/``, ``srv/`` or ``action/`` folders)
    to the resolver's package path, once: a node run from its workspace's root finds them with
    no build step, as after ``colcon build`` and sourcing the install."""
    from robomodel.clientlibs._workspace import src_folders
    from robomodel.runtime.msg import _resolver

    here = os.path.abspath("src")
    if here in _workspace_checked:
        return
    _workspace_checked.append(here)
    found = [
        Path(folder)
        for folder in src_folders()
        if any(os.path.isdir(os.path.join(folder, kind)) for kind in KINDS)
    ]
    paths = _resolver.package_paths()
    new = [folder for folder in found if folder not in paths]
    if new:
        _resolver.configure(package_paths=(*paths, *new))


def not_found(package: str, close: list[str]) -> str:
    """The message of the ModuleNotFoundError for an interface package robomodel lacks."""
    from robomodel.runtime.msg._resolver import searched

    _use_workspace_src()
    hint = f" (did you mean {', '.join(close)}?)" if close else ""
    return (
        f"No module named '{package}'{hint}: neither Python's path nor robomodel has it; "
        f"robomodel looked for an interface package of that name in {searched()}"
    )


def package_names() -> frozenset[str]:
    """The interface packages robomodel knows."""
    return frozenset(name.split("/", 1)[0] for name in _all_type_names())


def type_names(package: str, kind: str) -> tuple[str, ...]:
    """The type names (``String``) of ``package``'s ``kind`` (``msg``, ``srv``, ``action``)
    that a module lists; the parts that rosidl and genpy derive (``Foo_Request``,
    ``FooRequest``, ``Bar_Goal``) are left out, as they are reached through their parent."""
    prefix = f"{package}/{kind}/"
    names = {name[len(prefix) :] for name in _all_type_names() if name.startswith(prefix)}
    if kind == "msg":
        services = set(type_names(package, "srv"))
        names = {n for n in names if not _derived_service_half(n, services)}
    return tuple(sorted(n for n in names if "_" not in n or not n.rsplit("_", 1)[1][:1].isupper()))


def _derived_service_half(name: str, services: set[str]) -> bool:
    for suffix in ("Request", "Response"):
        if name.endswith(suffix) and name[: -len(suffix)] in services:
            return True
    return False


def _type_of(package: str, kind: str, name: str, flavour: str) -> Any:
    """The ``flavour``'s class of ``package``'s ``kind`` type ``name`` (genpy's service
    module also has the halves, ``AddTwoIntsRequest``)."""
    from robomodel.clientlibs import messages

    key = f"{package}/{kind}/{name}"
    if kind == "msg":
        return messages.message_class(key, flavour)
    if kind == "srv":
        for suffix in ("Request", "Response"):
            service = name.removesuffix(suffix)
            if flavour == "genpy" and service != name and service in type_names(package, kind):
                found = messages.service_class(f"{package}/srv/{service}", flavour)
                return found.Request if suffix == "Request" else found.Response
        return messages.service_class(key, flavour)
    return messages.action_class(key, flavour)


def module_names(package: str, kind: str, flavour: str) -> list[str]:
    """The names a ``flavour``'s module ``package.kind`` lists: the types, and for genpy's
    service modules the halves (``AddTwoInts``, ``AddTwoIntsRequest``, ``AddTwoIntsResponse``)."""
    names = list(type_names(package, kind))
    if kind == "srv" and flavour == "genpy":
        names += [f"{n}{suffix}" for n in names for suffix in ("Request", "Response")]
    if kind == "msg" and flavour == "genpy":  # genaction's messages of the package's actions
        names += [f"{a}{suffix}" for a in type_names(package, "action") for suffix in _GENACTION]
    return sorted(set(names))


_GENACTION = (
    "Action",
    "ActionGoal",
    "ActionResult",
    "ActionFeedback",
    "Goal",
    "Result",
    "Feedback",
)


class _InterfaceModule(ModuleType):
    """``pkg.msg`` / ``pkg.srv`` / ``pkg.action``: types made on first access."""

    __all__: list[str]
    __flavour__: str

    def __getattr__(self, name: str) -> Any:
        package, _, kind = self.__name__.partition(".")
        if name.startswith("__") or name not in self.__all__:
            raise AttributeError(
                f"module '{self.__name__}' has no attribute '{name}'"
                f" (it has {', '.join(self.__all__) or 'no types'})"
            )
        found = _type_of(package, kind, name, self.__flavour__)
        setattr(self, name, found)
        return found

    def __dir__(self) -> list[str]:
        return sorted({*super().__dir__(), *self.__all__})


class _InterfacePackage(ModuleType):
    """``import pkg`` of an interface package: its msg, srv and action modules. A ROS package
    may also be a Python library of the same name (``dynamic_reconfigure``'s client), which
    robomodel does not offer (``actionlib`` it does: :mod:`robomodel.clientlibs.actionlib`): asking for one of its names says so instead of a bare
    AttributeError far from the import."""

    def __getattr__(self, name: str) -> object:
        if name.startswith("__"):
            raise AttributeError(name)
        raise AttributeError(
            f"module '{self.__name__}' has no attribute '{name}': robomodel serves the "
            f"{self.__name__} interface package's msg, srv and action modules, not a Python "
            f"library of that name (a ROS installation on the path provides it)"
        )


class _InterfaceLoader(_LoaderBase):
    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        package, _, kind = spec.name.partition(".")
        if not kind:
            return _InterfacePackage(spec.name, f"The {package} interface package (robomodel).")
        from robomodel.clientlibs.messages import flavour

        chosen = flavour()
        module = _InterfaceModule(
            spec.name, f"The {kind} types of {package}, {chosen}-flavoured (robomodel)."
        )
        module.__flavour__ = chosen
        module.__all__ = module_names(package, kind, chosen)
        return module

    def exec_module(self, module: ModuleType) -> None:
        """Nothing to run: the module's types are made on first access."""


def find_spec(fullname: str) -> importlib.machinery.ModuleSpec | None:
    """The spec of ``pkg`` or ``pkg.msg``/``pkg.srv``/``pkg.action`` if robomodel knows the
    package; else None (the import goes on to fail as Python's own), or ModuleNotFoundError
    naming where robomodel looked when the name is close to a package it knows, or when a
    package it knows is asked for a module other than msg, srv and action."""
    parts = fullname.split(".")
    if len(parts) > 2:
        return None
    known = package_names()
    if len(parts) == 2 and parts[1] not in KINDS:
        if parts[0] in known:
            raise ModuleNotFoundError(
                f"No module named '{fullname}': the interface package {parts[0]} has the "
                f"modules {', '.join(KINDS)} (robomodel)",
                name=fullname,
            )
        return None
    if parts[0] not in known:
        import difflib

        close = difflib.get_close_matches(parts[0], sorted(known), n=3, cutoff=0.8)
        if close:
            raise ModuleNotFoundError(not_found(parts[0], close), name=fullname)
        return None
    spec = importlib.machinery.ModuleSpec(fullname, _InterfaceLoader(), is_package=len(parts) == 1)
    if len(parts) == 1:
        spec.submodule_search_locations = []
    return spec
