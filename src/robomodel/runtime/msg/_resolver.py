"""Where robomodel finds the message, service and action types it has no class of its own
for (its own are generated into modules by tools/gen_msgs.py).

:func:`~.schema.get_message_type` asks here when a name is not one of robomodel's own
classes. The definition is taken from, in this order:

1. the interface packages on the package path (``--package-path``, ``ROS_PACKAGE_PATH``,
   ``AMENT_PREFIX_PATH``): a package's ``msg/*.msg``, ``srv/*.srv`` and ``action/*.action``
   files, as ROS's own overlays let a workspace's package win. An action gives the types
   rosidl derives from it (:mod:`.action`: ``pkg/action/Name_Goal``, ``_SendGoal``,
   ``_FeedbackMessage``, ...) and those ROS 1's genaction derives (``pkg/NameGoal``,
   ``pkg/NameActionGoal``, ``pkg/NameActionFeedback``, ...: :mod:`._actions`);
   Then robomodel's copies of the common interfaces rosbags' stores lack (their services and
   actions, control_msgs, ...: ``runtime/msg/interfaces/``, Jazzy's);
2. the common interfaces of the ROS 2 distribution in rosbags' type stores, chosen by
   ``ROS_DISTRO`` (``jazzy`` when unset, or when it names a ROS 1 distribution);
3. rosbags' ROS 1 Noetic store, for names only ROS 1 has;
4. definitions learned at run time: a ROS 1 publisher's ``message_definition`` connection
   header, a bag's stored schema (:func:`learn_definition`).

:mod:`.definition` parses the ``.msg``/``.srv``/``.action`` text; :mod:`._from_definition` makes
the class. Nested types go through :func:`get_message_type` again, so robomodel's own classes are
used wherever robomodel has them. rosbags is imported only when a type is first looked for
here, so that verbs which never need one do not pay for it.
"""

from __future__ import annotations

import functools
import logging
import os
import re
import threading
import weakref
from pathlib import Path
from typing import Any

from robomodel.runtime.msg._actions import action_part, ros1_wrapper_text
from robomodel.runtime.msg._from_definition import build_message_class, build_service_class
from robomodel.runtime.msg.definition import (
    LIMITS,
    FieldDef,
    check_limits,
    nested_type,
    parse_message,
    recursion_in,
    split_parts,
)
from robomodel.runtime.msg.schema import (
    Action,
    Array,
    DefinitionResolver,
    Message,
    MessageTypeError,
    Seq,
    Service,
    get_message_type,
    install_definition_resolver,
)

__all__ = [
    "configure",
    "definitions_outside",
    "distro",
    "generation",
    "learn_definition",
    "learn_fielddefs",
    "package_definitions",
    "package_paths",
    "package_source",
    "resolve_action",
    "resolve_message",
    "resolve_service",
]

DEFAULT_DISTRO = "jazzy"
SHIPPED = Path(__file__).parent / "interfaces"  # see its README.md
# Packages of SHIPPED whose services ROS 1 defines alike (common_interfaces' noetic-devel).
ROS1_SHARED = frozenset({"nav_msgs", "sensor_msgs"})
_ROS2_DISTROS = ("humble", "iron", "jazzy", "kilted", "lyrical")

_lock = threading.RLock()
_messages: dict[str, type[Message]] = {}
_services: dict[str, type[Service]] = {}
_actions: dict[str, type[Action]] = {}
_learned: dict[str, FieldDef] = {}
_conflicts: set[str] = set()
_local = threading.local()  # .building: the types this thread is building
_generation = 0  # counts configure() calls: a class built across one is not kept
_log = logging.getLogger("robomodel.msg")
_package_paths: tuple[Path, ...] = ()
_distro: str | None = None


def configure(
    *, package_paths: tuple[str | os.PathLike[str], ...] | None = None, distro: str | None = None
) -> None:
    """Set the extra package folders (``--package-path``) and the distribution (``--distro``);
    classes already built from definitions are forgotten."""
    global _package_paths, _distro, _generation
    with _lock:
        paths = _package_paths if package_paths is None else tuple(Path(p) for p in package_paths)
        wanted = _distro if distro is None else distro
        if (paths, wanted) == (_package_paths, _distro) and (package_paths, distro) != (None, None):
            return  # nothing changes: the classes built so far stay (one class per type)
        _package_paths, _distro = paths, wanted
        _generation += 1
        _messages.clear()
        _services.clear()
        _actions.clear()
        _package_path_files.cache_clear()
        _package_files.cache_clear()


def package_paths() -> tuple[Path, ...]:
    """The extra package folders set by :func:`configure` (``--package-path``)."""
    return _package_paths


def generation() -> int:
    """How many times :func:`configure` changed the sources: what was found before is stale
    when this has changed."""
    return _generation


def definition_names() -> set[str]:
    """Every ``pkg/kind/Name`` this resolver can build from a definition: the package path's
    (and robomodel's copies'), rosbags' ROS 2 store of :func:`distro` and its ROS 1 store.
    Without rosbags (only the ``ros1`` and ``bag`` extras bring it) the stores' are left out,
    so that ``from std_msgs.msg import String`` still gives robomodel's own class."""
    names: set[str] = set(_package_files())
    try:
        stores = (_distro_store(), _store("ROS1_NOETIC"))
    except ImportError:
        return names
    for store in stores:
        names.update(store.fielddefs)
    return names


def distro() -> str:
    """The ROS 2 distribution whose common interfaces are used (``ROS_DISTRO``, else jazzy)."""
    name = (_distro or os.environ.get("ROS_DISTRO") or DEFAULT_DISTRO).strip().lower()
    return name if name in _ROS2_DISTROS else DEFAULT_DISTRO


@functools.cache
def _store(name: str) -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores[name])


def _distro_store() -> Any:
    from rosbags.typesys import Stores

    key = f"ROS2_{distro().upper()}"
    return _store(key if key in Stores.__members__ else f"ROS2_{DEFAULT_DISTRO.upper()}")


def _index() -> Any:
    from robomodel.description.packages import PackageIndex

    return PackageIndex(package_paths=_package_paths)


@functools.cache
def _package_path_files() -> dict[str, Path]:
    """``pkg/msg/Name``, ``pkg/srv/Name`` and ``pkg/action/Name`` -> the ``.msg``/``.srv``/
    ``.action`` file on the package path (the package index's crawl, once a configuration)."""
    index = _index()
    return _interface_files([(package, index.find(package)) for package in index.names()])


@functools.cache
def _package_files(shipped: bool = True) -> dict[str, Path]:
    """:func:`_package_path_files`, then (``shipped``) robomodel's copies of the common
    interfaces that rosbags' stores lack, services, actions, control_msgs...: a workspace's own
    package of the same name wins."""
    if not shipped:
        return _package_path_files()
    files = dict(_package_path_files())
    shipped_files = _interface_files([(r.name, r) for r in sorted(SHIPPED.iterdir()) if r.is_dir()])
    for key, path in shipped_files.items():
        files.setdefault(key, path)
    return files


def _interface_files(roots: list[tuple[str, Path]]) -> dict[str, Path]:
    """The ``.msg``/``.srv``/``.action`` files of packages ``(name, folder)`` by their keys (the
    first package of a name wins)."""
    files: dict[str, Path] = {}
    for package, root in roots:
        for kind in ("msg", "srv", "action"):
            for path in sorted((root / kind).glob(f"*.{kind}")):
                files.setdefault(f"{package}/{kind}/{path.stem}", path)
    return files


def package_definitions(name: str, *, shipped: bool = True) -> dict[str, FieldDef] | None:
    """The definition of message ``pkg/msg/Name``, of a service half (``pkg/srv/Name_Request``,
    or ROS 1's ``pkg/msg/NameRequest``) or of an action part (``pkg/action/Name_Goal``, or
    ROS 1's ``pkg/msg/NameGoal`` and ``pkg/msg/NameActionGoal``) from the package path; None
    if no package has it (``shipped``: or robomodel's copies of the common interfaces)."""
    files = _package_files(shipped)
    path = files.get(name)
    if path is not None:
        return parse_message(path.read_text(), name, where=str(path))
    part = action_part(name, files)
    if part is not None:
        action, index, ros1 = part
        path = files[action]
        text = split_parts(path.read_text(), "action", where=str(path))[index]
        if ros1 is not None:
            text = ros1_wrapper_text(name, text, ros1)
        return parse_message(text, name, where=str(path))
    half = re.fullmatch(r"(\w+)/srv/(\w+)_(Request|Response)", name) or re.fullmatch(
        r"(\w+)/msg/(\w+?)(Request|Response)", name
    )
    path = files.get(f"{half[1]}/srv/{half[2]}") if half is not None else None
    if half is None or path is None:
        return None
    halves = split_parts(path.read_text(), "srv", where=str(path))
    return parse_message(halves[0 if half[3] == "Request" else 1], name, where=str(path))


def _messages_shipped(key: str) -> bool:
    """Whether robomodel ships the messages of ``key``'s package (control_msgs,
    controller_manager_msgs, gazebo_msgs...): it does for packages that rosbags' ROS 2 stores
    have none of, so a type its copy lacks (ROS 1's
    ``controller_manager_msgs/msg/HardwareInterfaceResources``) is not in the ROS 2 store
    either, and is not looked for there: importing a ROS 2 store takes 0.1-0.2 s."""
    return (SHIPPED / key.split("/", 1)[0] / "msg").is_dir()


def _definition(key: str) -> tuple[FieldDef, bool] | None:
    """The definition of ``key`` and whether it is a ROS 1 one (rosbags' Noetic store)."""
    if _DERIVED.fullmatch(key):
        # derived from an action's parts by make_action, unless a bag's schema taught it
        learned = _learned.get(key)
        return None if learned is None else (learned, False)
    found = package_definitions(key)
    if found is not None:
        return found[key], False
    stores = [(_store("ROS1_NOETIC"), True)]
    if not _messages_shipped(key):
        stores.insert(0, (_distro_store(), False))
    for store, ros1 in stores:
        if key in store.fielddefs:
            return store.fielddefs[key], ros1
    learned = _learned.get(key)
    return None if learned is None else (learned, False)


def definitions_outside(key: str, known: Any) -> dict[str, FieldDef]:
    """The definitions of ``key`` and of the types it uses that ``known`` (a set of names,
    e.g. the ROS 1 store's) lacks, from the package path and learned definitions; for a bus
    whose own table of types (ROS 1's) needs them registered."""
    out: dict[str, FieldDef] = {}
    pending = [key]
    while pending:
        name = pending.pop()
        if name in out or name in known:
            continue
        # robomodel's copies of ROS 2's common interfaces only for the packages whose services
        # ROS 1 has the same: a ROS 2-only type (rcl_interfaces, lifecycle_msgs, the
        # controller_manager_msgs services) has no ROS 1 counterpart and stays in the process.
        shared = name.split("/", 1)[0] in ROS1_SHARED
        found = package_definitions(name, shipped=shared)
        definition = found[name] if found is not None else _learned.get(name)
        if definition is None:
            continue
        out[name] = definition
        for _, desc in definition[1]:
            nested = nested_type(desc)
            if nested is not None:
                pending.append(nested)
    return out


def learn_definition(name: str, text: str) -> None:
    """Remember the types of a full definition (a ROS 1 ``message_definition`` or a bag's
    ``ros2msg`` schema: the type's fields, then ``===`` / ``MSG: pkg/Name`` sections) so that
    ``name`` and the types it uses resolve even where no package or store has them."""
    key = _canonical(name)
    _remember(parse_message(text, key, where=f"the definition of {name}"))


def learn_fielddefs(found: dict[str, FieldDef]) -> None:
    """Remember definitions already parsed (a peer's ``GetTypeDescription`` answer, see
    :mod:`robomodel.runtime.type_descriptions`), as :func:`learn_definition` does for text."""
    _remember(found)


def _remember(found: dict[str, FieldDef]) -> None:
    """The first definition learned of a name stays for the process's life: its classes and
    codecs may be in use. A different one learned later (a publisher rebuilt with a changed
    ``.msg``) is refused with one warning per name, as ROS 1 refuses a mismatched md5sum.
    Definitions that nest themselves are refused whole (MessageTypeError, one line)."""
    with _lock:
        graph = {**_learned, **found}
        chain = recursion_in(graph)
        if chain is not None:
            raise MessageTypeError(_recursive(chain))
        check_limits(graph)
        for type_name, definition in found.items():
            known = _learned.setdefault(type_name, definition)
            if known != definition and type_name not in _conflicts:
                _conflicts.add(type_name)
                _log.warning(
                    "%s: a peer or bag defines it differently from the definition learned "
                    "earlier in this process; the earlier one stays (restart to use the new one)",
                    type_name,
                )


def package_source(key: str) -> Path | None:
    """The ``.msg``/``.srv`` file of ``pkg/msg/Name`` or ``pkg/srv/Name`` on the package path,
    if robomodel read the type from one (a type description's source text)."""
    return _package_files().get(key)


def _canonical(name: str) -> str:
    parts = name.strip().strip("/").split("/")
    return f"{parts[0]}/msg/{parts[1]}" if len(parts) == 2 else "/".join(parts)


def searched() -> str:
    """Where this resolver looks, as one phrase for an error message."""
    places = [f"--package-path {p}" for p in _package_paths]
    for variable in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"):
        places += [f"{variable} {p}" for p in os.environ.get(variable, "").split(os.pathsep) if p]
    packages = (
        f"the msg/, srv/ and action/ folders of the packages under {', '.join(places)}"
        if places
        else "no package path (--package-path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH are unset)"
    )
    return (
        f"robomodel's own types and copies of the common services and actions, rosbags' ROS 2 "
        f"{distro()} and ROS 1 noetic stores, {packages}"
    )


class UnknownMessageTypeError(MessageTypeError):
    """No source has message type ``key`` (``name`` as the user wrote it). The close names it
    suggests are looked for when the message is first read, as Python's own "Did you mean"
    is, because they cost every class robomodel ships (their modules imported) and the package
    path's crawl: a caller that asks whether a type exists and catches this pays for neither."""

    def __init__(self, key: str, name: str) -> None:
        super().__init__(key, name)
        self.key, self.name = key, name
        self._searched = searched()
        self._text: str | None = None

    def __str__(self) -> str:
        if self._text is None:
            self._text = f"unknown message type '{self.name}'{_hint(self.key)}: looked in "
            self._text += self._searched
        return self._text


def _hint(key: str) -> str:
    from robomodel.errors import close_matches
    from robomodel.runtime.msg.schema import message_type_names

    known = {*message_type_names(), *_distro_store().fielddefs, *_package_files()}
    hint = close_matches(key, sorted(known))
    return f" (did you mean {', '.join(hint)}?)" if hint else ""


def resolve_message(key: str, name: str) -> type[Message]:
    """The class of message type ``key`` (``pkg/msg/Name``) from its definition; ``name`` is
    what the user wrote. MessageTypeError, in one line, if no source has it."""
    derived = _DERIVED.fullmatch(key)
    if (
        derived is not None
        and (derived[3] == "FeedbackMessage") == (derived[4] is None)
        and _action_known(f"{derived[1]}/action/{derived[2]}")
    ):
        action = resolve_action(f"{derived[1]}/action/{derived[2]}", name)
        kind = getattr(action, derived[3])
        return kind if derived[4] is None else getattr(kind, derived[4])  # type: ignore[no-any-return]
    with _lock:
        found = _messages.get(key)
        if found is not None:
            return found
        definition = _definition(key)
        generation = _generation
    if definition is None:
        raise UnknownMessageTypeError(key, name)
    # Built with no lock held, so that a large type does not hold up every other lookup; the
    # nested types it asks for take the lock for their own look-up only.
    building = _building_stack()
    if key in building:  # a package's .msg files that nest a type in itself
        raise MessageTypeError(_recursive((*building[building.index(key) :], key)))
    if len(building) >= LIMITS.max_depth:
        raise MessageTypeError(
            f"{building[0]}: message types nested more than {LIMITS.max_depth} deep "
            "(robomodel's bound, docs/reference/limits.md)"
        )
    fields, ros1 = definition
    building.append(key)
    try:
        built = build_message_class(key, fields, get_message_type, ros1=ros1)
    finally:
        building.pop()
    _check_flattened(built)
    with _lock:
        if generation != _generation:  # configure() ran meanwhile: not kept
            return built
        return _messages.setdefault(key, built)  # another thread's, if it finished first


def _building_stack() -> list[str]:
    """The types this thread is building, outermost first."""
    stack: list[str] | None = getattr(_local, "building", None)
    if stack is None:
        stack = _local.building = []
    return stack


def _check_flattened(cls: type[Message]) -> None:
    """Refuse a class whose fields, nested types expanded, are more than LIMITS allows."""
    size = _flat_size(cls)
    if size > LIMITS.max_flattened:
        raise MessageTypeError(
            f"{cls.__typename__}: more than {LIMITS.max_flattened} fields once its nested types "
            "are expanded (robomodel's bound, docs/reference/limits.md)"
        )


def _flat_size(cls: type[Message]) -> int:
    found = _FLAT.get(cls)
    if found is None:
        found = 0
        for _, spec in cls.__fields__:
            count = 1
            while isinstance(spec, (Seq, Array)):
                count *= spec.size if isinstance(spec, Array) else 1
                spec = spec.item
            found += count * _flat_size(spec) if isinstance(spec, type) else 1
        _FLAT[cls] = found
    return found


_FLAT: weakref.WeakKeyDictionary[type[Message], int] = weakref.WeakKeyDictionary()


def _recursive(chain: tuple[str, ...]) -> str:
    return (
        f"{chain[0]}: its definition contains itself ({' -> '.join(chain)}); a ROS message "
        "type cannot nest itself, not even through an array"
    )


def resolve_service(key: str, name: str) -> type[Service]:
    """The class of service type ``key`` (``pkg/srv/Name``) from the package path."""
    derived = _DERIVED.fullmatch(f"{key}_Service")
    if derived is not None and derived[3] in ("SendGoal", "GetResult"):
        action = resolve_action(f"{derived[1]}/action/{derived[2]}", name)
        return getattr(action, derived[3])  # type: ignore[no-any-return]
    with _lock:
        found = _services.get(key)
        if found is None:
            if key not in _package_files():
                raise MessageTypeError(f"unknown service type '{name}': looked in {searched()}")
            halves = [resolve_message(f"{key}_{part}", name) for part in ("Request", "Response")]
            found = _services[key] = build_service_class(key, *halves)
        return found


# The types rosidl derives from an action (rosidl_parser's Action): the two services, their
# halves and the feedback message. "_Service" is appended by resolve_service to tell a service
# from a message of the same name.
_DERIVED = re.compile(
    r"(\w+)/action/(\w+?)_(SendGoal|GetResult|FeedbackMessage)(?:_(Request|Response|Service))?"
)


def _action_known(key: str) -> bool:
    """Whether action ``key`` is robomodel's own or on the package path."""
    from robomodel.runtime.msg.action import _ACTIONS
    from robomodel.runtime.msg.schema import import_package

    import_package(key)
    return key in _ACTIONS or key in _package_files()


def resolve_action(key: str, name: str) -> type[Action]:
    """The action ``key`` (``pkg/action/Name``): robomodel's own if it has it, else the one
    built from the package path's ``.action`` file, with the types rosidl derives from it."""
    from robomodel.runtime.msg.action import _ACTIONS, make_action
    from robomodel.runtime.msg.schema import import_package

    import_package(key)
    with _lock:
        found = _ACTIONS.get(key) or _actions.get(key)
        if found is None:
            if key not in _package_files():
                of = "" if name == key else f" (of '{name}')"
                raise MessageTypeError(f"unknown action type '{key}'{of}: looked in {searched()}")
            goal, result, feedback = (
                resolve_message(f"{key}_{part}", name) for part in ("Goal", "Result", "Feedback")
            )
            found = _actions[key] = make_action(key, goal, result, feedback, register=False)
        return found


install_definition_resolver(DefinitionResolver(resolve_message, resolve_service))
