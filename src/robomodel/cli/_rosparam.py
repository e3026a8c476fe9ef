"""``robomodel param`` on a ROS 1 master, as Debian's ``rosparam`` (ros_comm 1.15's
``rosparam/__init__.py``) does it: the same arguments, the same YAML typing, the same output.

- ``set NAME VALUE``: VALUE is YAML (rosparam's loader: ``!degrees``, ``!radians``, ``deg()``,
  ``rad()``); an empty VALUE is the empty string; a dictionary is set leaf by leaf, so it adds to
  a namespace rather than replacing it. ``set NAME -t FILE`` sets the text of FILE, ``-b FILE``
  its bytes.
- ``get NAME``: ``yaml.dump`` of the value (``-p``: rosparam's "pretty" form).
- ``dump [FILE] [NS]``: ``yaml.dump`` of NS (default: the caller's namespace) to FILE or stdout.
- ``load FILE [NS]``: every YAML document of FILE (``-`` for stdin), ``_ns`` keys honoured.
- ``list [NS]``, ``delete NAME`` (``delete /`` empties the server).

Relative names resolve against ``ROS_NAMESPACE`` and ``~name`` against the caller, as
``rosgraph.names.script_resolve_name`` does. A value the master refuses or a name it does not
hold is rosparam's ``ERROR: ...`` line and exit code 1.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any, Protocol

from robomodel.errors import RobomodelError

__all__ = ["ParamServer", "run_rosparam", "script_resolve_name"]

_INT32 = (-(2**31), 2**31 - 1)  # XML-RPC's <int>: what the parameter server can hold


class ParamServer(Protocol):
    """What rosparam needs of a parameter server (MasterParams, ParamTree)."""

    def get(self, name: str) -> Any: ...

    def set(self, name: str, value: Any) -> None: ...

    def delete(self, name: str) -> None: ...

    def names(self) -> list[str]: ...


def _namespace() -> str:
    """rosgraph's get_ros_namespace: ROS_NAMESPACE as a global namespace ending in ``/``."""
    ns = os.environ.get("ROS_NAMESPACE", "/") or "/"
    ns = ns if ns.startswith("/") else "/" + ns
    return ns if ns.endswith("/") else ns + "/"


def script_resolve_name(name: str | None, caller_id: str = "/rosparam") -> str:
    """rosgraph.names.script_resolve_name: empty -> the namespace, ``/x`` as is, ``~x`` under
    the caller, ``x`` in the namespace."""
    if not name:
        return _namespace()
    if name.startswith("/"):
        return name
    if name.startswith("~"):
        return caller_id.rstrip("/") + "/" + name[1:]
    return _namespace() + name


def _ns_join(ns: str, name: str) -> str:
    if name.startswith(("/", "~")):
        return name
    return ns + name if ns.endswith("/") else f"{ns}/{name}"


def _printable(text: str) -> str:
    """A name from the master with control characters escaped (a terminal runs them)."""
    from robomodel._escape import escape_name

    return escape_name(text)


def _yaml_value(text: str, where: str) -> Any:
    """rosparam's ``yaml.safe_load`` with its angle tags; errors as one line."""
    import yaml

    from robomodel.launch.ros1.params import RosparamLoader

    try:
        return _bounded(yaml.load(text, Loader=RosparamLoader), where)
    except RecursionError:
        raise RobomodelError(f"{where} is nested too deeply for YAML") from None
    except yaml.YAMLError as exc:
        raise RobomodelError(f"{where} is not valid YAML: {' '.join(str(exc).split())}") from None


def _bounded(data: Any, what: str) -> Any:
    """``data`` with its aliases expanded, refused past the parameter bound (a YAML bomb)."""
    from robomodel.runtime.transport.ros1.param_bounds import ParamBoundError, expand_bounded

    if not isinstance(data, dict | list):
        return data
    try:
        return expand_bounded(data, what=what)
    except ParamBoundError as exc:
        raise RobomodelError(str(exc)) from None


def set_param_raw(server: ParamServer, name: str, value: Any) -> None:
    """rosparam's set_param_raw: a dictionary leaf by leaf, anything else in one setParam."""
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                raise RobomodelError(
                    f"YAML dictionaries must have string keys; {key!r} in the value of {name} "
                    "is not a string"
                )
            set_param_raw(server, _ns_join(name, key), item)
        return
    _check_ints(value, name)
    server.set(name, value)


def _check_ints(value: Any, name: str) -> None:
    if isinstance(value, bool):
        return
    if isinstance(value, int) and not _INT32[0] <= value <= _INT32[1]:
        raise RobomodelError(
            f"{name}: {value} does not fit the parameter server's 32-bit signed integers "
            f"({_INT32[0]} ... {_INT32[1]}); quote it to set a string"
        )
    if isinstance(value, list):
        for item in value:
            _check_ints(item, name)


def _dump(value: Any) -> str:
    """rosparam's ``yaml.dump`` (the default Dumper: flow style for lists of scalars)."""
    import yaml

    if isinstance(value, bytes):
        from xmlrpc.client import Binary

        value = Binary(value)  # as rosparam's xmlrpclib hands it over
    return str(yaml.dump(value))


_END = "\n...\n"  # PyYAML's end of a document holding a plain scalar


def _pretty(value: dict[str, Any], indent: str = "") -> str:
    """rosparam's ``get -p`` (_pretty_print): keys sorted, nested dicts indented."""
    out = []
    for key in sorted(value):
        item = value[key]
        if isinstance(item, dict):
            out.append(f"{indent}{key}:\n" + _pretty(item, indent + "  "))
        elif isinstance(item, str):
            if "\n" in item:
                out.append(f"{indent}{key}: |\n")
                out.extend(f"{indent}  {line}\n" for line in item.split("\n"))
            else:
                out.append(f"{indent}{key}: {item}\n")
        else:
            text = _dump(item)
            out.append(f"{indent}{key}: {text[:-4] if text.endswith(_END) else text}")
    return "".join(out)


def cmd_get(server: ParamServer, name: str | None, *, pretty: bool = False) -> int:
    if not name:
        raise RobomodelError("param get: give a parameter name, e.g. /robot_description")
    value = server.get(script_resolve_name(name))
    if pretty and isinstance(value, dict):
        sys.stdout.write(_pretty(value))
    elif pretty and isinstance(value, str):
        print(value)
    else:
        text = _dump(value)
        sys.stdout.write((text[:-5] if text.endswith(_END) else text) + "\n")
    return 0


def cmd_set(server: ParamServer, name: str | None, value: str | None, args: Any) -> int:
    if not name:
        raise RobomodelError("param set: give a parameter name, then a YAML value or -t FILE")
    text_file, bin_file = getattr(args, "textfile", None), getattr(args, "binfile", None)
    if text_file and bin_file:
        raise RobomodelError("param set: give only one of -t/--textfile and -b/--binfile")
    resolved = script_resolve_name(name)
    if text_file or bin_file:
        if value is not None:
            raise RobomodelError(f"param set: too many arguments ({value!r} after the file)")
        path = Path(str(text_file or bin_file))
        if not path.is_file():
            raise RobomodelError(f"param set: file '{path}' does not exist")
        try:
            data: Any = path.read_text() if text_file else path.read_bytes()
        except (OSError, UnicodeDecodeError) as exc:
            raise RobomodelError(f"param set: cannot read '{path}': {exc}") from None
        set_param_raw(server, resolved, data)
        return 0
    if value is None:
        raise RobomodelError(f"param set {name}: give a YAML value (or -t FILE for a text file)")
    parsed = _yaml_value(value or "!!str", f"the value of {resolved}")
    set_param_raw(server, resolved, parsed)
    return 0


def cmd_list(server: ParamServer, namespace: str | None) -> int:
    prefix = script_resolve_name(namespace) if namespace else "/"
    prefix = prefix if prefix.endswith("/") else prefix + "/"
    names = sorted(n for n in server.names() if n.startswith(prefix))
    print("\n".join(_printable(n) for n in names))
    return 0


def cmd_delete(server: ParamServer, name: str | None) -> int:
    if not name:
        raise RobomodelError("param delete: give a parameter name")
    resolved = script_resolve_name(name)
    if resolved == "/":
        server.set("/", {})  # rosparam's "delete the ENTIRE parameter server"
    else:
        server.delete(resolved)
    return 0


def cmd_dump(server: ParamServer, file: str | None, namespace: str | None) -> int:
    from robomodel._atomic import atomic_write_text

    if file and os.path.isdir(file):  # `param dump /`: rosparam ends in IsADirectoryError
        raise RobomodelError(
            f"param dump: '{file}' is a folder; dump takes a FILE first, then the namespace: "
            f"`param dump params.yaml {file}` (or `param dump` to print them all)"
        )
    text = _dump(server.get(script_resolve_name(namespace or "")))
    if file:
        try:
            atomic_write_text(file, text)
        except OSError as exc:
            raise RobomodelError(f"param dump: cannot write '{file}': {exc.strerror}") from None
    else:
        sys.stdout.write(text)
    return 0


def load_documents(file: str, namespace: str | None) -> list[tuple[Any, str]]:
    """rosparam's load_file: ``(values, namespace)`` for every YAML document, ``_ns`` applied."""
    import yaml

    from robomodel.launch.ros1.params import RosparamLoader

    default_ns = script_resolve_name(namespace or "")
    if file == "-":
        text = sys.stdin.read()
    else:
        if not Path(file).is_file():
            swapped = (
                f" (did you mean `param load {namespace} {file}`?)"
                if (namespace and Path(namespace).is_file())
                else ""
            )
            raise RobomodelError(f"param load: file [{file}] does not exist{swapped}")
        try:
            text = Path(file).read_text()
        except (OSError, UnicodeDecodeError) as exc:
            raise RobomodelError(f"param load: cannot read '{file}': {exc}") from None
    try:
        documents = [_bounded(d, file) for d in yaml.load_all(text, Loader=RosparamLoader)]
    except (yaml.YAMLError, RecursionError) as exc:
        raise RobomodelError(f"{file}: not valid YAML: {' '.join(str(exc).split())}") from None
    loaded = []
    for doc in documents:
        ns = default_ns
        if isinstance(doc, dict) and "_ns" in doc:
            ns = _ns_join(default_ns, str(doc.pop("_ns")))
        if ns == "/" and not isinstance(doc, dict):
            raise RobomodelError(f"{file}: global / can only be set to a dictionary")
        loaded.append((doc, ns))
    return loaded


def cmd_load(server: ParamServer, file: str | None, namespace: str | None) -> int:
    if not file:
        raise RobomodelError("param load: give a YAML file (or - for stdin), then a namespace")
    documents = load_documents(file, namespace)  # all read and checked before any is set
    for values, ns in documents:
        set_param_raw(server, ns, values)
    return 0


def run_rosparam(verb: str, server: ParamServer, args: Any) -> int:
    """One rosparam command; the positionals are argparse's ``node``, then ``name`` or
    ``file``, then ``value``. The master's refusal (a name not set) is rosparam's ``ERROR:``
    line and exit code 1."""
    from robomodel.runtime.transport.ros1.param_tree import ParamServerError

    first = getattr(args, "node", None)
    second = getattr(args, "file", None) if verb == "load" else getattr(args, "name", None)
    if verb == "set" and getattr(args, "value", None) is not None:
        raise RobomodelError(
            f"param set: too many arguments ({args.value!r}); rosparam's form "
            "is `param set NAME VALUE` on a ROS 1 master"
        )
    try:
        return _dispatch(verb, server, args, first, second)
    except ParamServerError as exc:
        message = str(exc)
        method, sep, rest = message.partition(": ")
        print(f"ERROR: {rest if sep and method.isidentifier() else message}", file=sys.stderr)
        return 1


def _dispatch(verb: str, server: ParamServer, args: Any, first: Any, second: Any) -> int:
    if verb == "get":
        return cmd_get(server, first, pretty=bool(getattr(args, "pretty", False)))
    if verb == "set":
        return cmd_set(server, first, second, args)
    if verb == "list":
        return cmd_list(server, first)
    if verb == "delete":
        return cmd_delete(server, first)
    if verb == "dump":
        return cmd_dump(server, first, second)
    return cmd_load(server, first, second)
