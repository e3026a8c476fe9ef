"""Execute a Python launch file as ``ros2 launch`` does: run it with its own ``__file__``, then
call ``generate_launch_description()``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from robomodel._files import UserFileError, read_user_bytes
from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.shim.action import LaunchDescription, user_error
from robomodel.launch.ros2.shim.context import current_session
from robomodel.launch.ros2.shim.sources import FileLoader

__all__ = ["PYTHON_LOADER", "load_python_description"]


def load_python_description(path: Path) -> LaunchDescription:
    """Run the file and return its LaunchDescription (errors as LaunchError at file:line)."""
    session = current_session()
    # as given, like launch's SourceFileLoader: in a --symlink-install prefix, __file__ is the
    # prefix's path and not the source file the symlink points at
    filename = os.path.abspath(path)
    if session is not None:
        session.python_files.add(filename)
    try:
        source = read_user_bytes(path, what="launch file")
        code = compile(source, filename, "exec")
        namespace: dict[str, Any] = {"__file__": filename, "__name__": "__robomodel_launch__"}
        exec(code, namespace)
        generate = namespace.get("generate_launch_description")
        if generate is None:
            raise LaunchError(
                "launch file has no generate_launch_description() function",
                location=SourceLocation(filename),
                include_stack=tuple(session.include_stack) if session else (),
            )
        description = generate()
    except LaunchError:
        raise
    except UserFileError as exc:
        raise LaunchError(str(exc), location=SourceLocation(filename)) from None
    except OSError as exc:
        raise LaunchError(
            f"cannot read launch file: {exc.strerror}", location=SourceLocation(filename)
        ) from None
    except (Exception, SystemExit) as exc:
        raise user_error(exc, SourceLocation(filename)) from None
    if not isinstance(description, LaunchDescription):
        raise LaunchError(
            "generate_launch_description() must return a launch.LaunchDescription, got "
            f"{type(description).__name__}",
            location=SourceLocation(filename),
            include_stack=tuple(session.include_stack) if session else (),
        )
    return description


PYTHON_LOADER = FileLoader("python", (".py",), load_python_description)
