"""The one reader of files a user names: regular files only, bounded in size, clear errors.

Every file robomodel reads because a user named it (a URDF, a xacro include, a launch file, a
``textfile=``/``binfile=``/``<rosparam file=>``, ``$(file-content)``, a parameter or controller
YAML, a world) goes through :func:`read_user_bytes` or :func:`read_user_text`. ``/dev/zero``, a
FIFO, a directory or a socket is refused before it is opened for reading, and so is a file over
:data:`MAX_FILE_BYTES`, so no input can make a read grow without bound or block forever.
"""

from __future__ import annotations

import os
import stat

from robomodel.errors import RobomodelError

__all__ = [
    "MAX_FILE_BYTES",
    "UserFileError",
    "check_user_file",
    "decode_utf8",
    "read_user_bytes",
    "read_user_text",
]

MAX_FILE_BYTES = 64 * 1024 * 1024
"""The largest file robomodel reads (64 MiB): far above any robot description or launch file."""

_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a named pipe (FIFO)"),
    (stat.S_ISSOCK, "a socket"),
)


class UserFileError(RobomodelError):
    """A named file that cannot be read: missing, not a regular file, too large, not UTF-8.

    Attributes:
        path: The file as the user named it.
        reason: What is wrong with it.
        line: 1-based line of an undecodable byte, else None.
        column: 1-based column of that byte, else None.
        errno: The OS error number when the file could not be opened (ENOENT: missing).
        too_large: The file is over the size limit.
    """

    def __init__(
        self,
        path: str,
        reason: str,
        *,
        line: int | None = None,
        column: int | None = None,
        errno: int | None = None,
        too_large: bool = False,
    ) -> None:
        self.path = path
        self.errno = errno
        self.too_large = too_large
        self.reason = reason
        self.line = line
        self.column = column
        where = path if line is None else f"{path}:{line}:{column}"
        super().__init__(f"{where}: {reason}")


def _kind(mode: int) -> str:
    for test, name in _KINDS:
        if test(mode):
            return name
    return "not a regular file"


def check_user_file(
    path: str | os.PathLike[str], *, what: str = "file", limit: int = MAX_FILE_BYTES
) -> None:
    """Refuse what :func:`read_user_bytes` refuses, for a file a library reads by its path
    (trimesh, which resolves a mesh's textures and materials next to it).

    Raises:
        UserFileError: missing or unreadable, not a regular file, or larger than ``limit``.
    """
    name = os.fspath(path)
    try:
        info = os.stat(name)
    except OSError as exc:
        raise UserFileError(name, f"cannot read {what}: {exc.strerror}", errno=exc.errno) from None
    if not stat.S_ISREG(info.st_mode):
        raise UserFileError(
            name, f"cannot read {what}: it is {_kind(info.st_mode)}; only regular files are read"
        )
    if info.st_size > limit:
        raise UserFileError(name, _too_large(what, info.st_size, limit), too_large=True)


def read_user_bytes(
    path: str | os.PathLike[str], *, what: str = "file", limit: int = MAX_FILE_BYTES
) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes.

    Args:
        path: The file, as named by the user (relative to the working directory).
        what: What the file is, for the message ("launch file", "textfile").
        limit: The largest size accepted, in bytes.

    Raises:
        UserFileError: missing or unreadable, not a regular file, or larger than ``limit``.
    """
    name = os.fspath(path)
    check_user_file(name, what=what, limit=limit)
    try:
        with open(name, "rb") as handle:
            if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):  # replaced since the stat
                raise UserFileError(name, f"cannot read {what}: not a regular file")
            data = handle.read(limit + 1)
    except OSError as exc:
        raise UserFileError(name, f"cannot read {what}: {exc.strerror}", errno=exc.errno) from None
    if len(data) > limit:  # grew since the stat
        raise UserFileError(name, _too_large(what, len(data), limit), too_large=True)
    return data


def _too_large(what: str, size: int, limit: int) -> str:
    return (
        f"{what} is {size / 2**20:.1f} MiB; files over {limit / 2**20:.0f} MiB are refused "
        "(robot descriptions, launch and parameter files are far smaller)"
    )


def decode_utf8(data: bytes, name: str) -> str:
    """``data`` as UTF-8 text; an undecodable byte is a :class:`UserFileError` at its line."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise UserFileError(
            name,
            f"not UTF-8 text: byte 0x{data[exc.start]:02x} cannot be decoded ({exc.reason}); "
            "save the file as UTF-8",
            line=line,
            column=column,
        ) from None


def read_user_text(
    path: str | os.PathLike[str], *, what: str = "file", limit: int = MAX_FILE_BYTES
) -> str:
    """The UTF-8 text of a regular file (see :func:`read_user_bytes`).

    Raises:
        UserFileError: as :func:`read_user_bytes`, or bytes that are not UTF-8 (with the
            line and column of the first one).
    """
    name = os.fspath(path)
    return decode_utf8(read_user_bytes(name, what=what, limit=limit), name)
