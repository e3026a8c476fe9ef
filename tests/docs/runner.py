"""Runs the documentation's shell blocks as a reader types them.

A fenced block is runnable when the line before it is an HTML comment (invisible on the site):

- ``<!-- run -->``: each line is a command, run in order in the page's working folder (a fresh
  folder holding a link to ``examples/``), and must exit 0. ``export NAME=VALUE`` sets the
  variable for the page's later commands (``$PWD`` is the working folder); ``unset NAME``
  removes it.
- ``<!-- run: background until "TEXT" -->``: the block's one command keeps running (a second
  terminal in the text); it must print TEXT, and it is ended with Ctrl-C when the page is done.
- ``<!-- run: exit N -->``: as ``run``, but each command must exit with N (an error shown).
- ``<!-- run: python -->``: the block is a Python script, run in the working folder with the
  venv's Python; it must exit 0, and its output is what a following ``output`` block shows.
- ``<!-- file: NAME -->``: the block is a file the reader saves as NAME (in the working folder).
- ``<!-- output -->`` before a block: what the previous ``run`` block's last command printed
  (standard output; for ``run: exit N``, then standard error), or, after a ``background`` block,
  what that command printed up to and including its TEXT line.
  Lines must match in order; a line ``...`` stands for any lines, and ``...`` inside a line for
  any text.
- ``<!-- output: figures vary -->``: as ``output``, but each number shown stands for any number
  (a count, a size, a time; a month's name for any month): the reader sees real figures, the
  test checks everything else.
- ``<!-- ctrl-c -->`` on a line of its own: the reader ends what runs in the background (the
  text says so); every background command is ended with Ctrl-C and must end cleanly.
- ``<!-- not run: REASON -->``: a shell block no test can run as typed here (a second machine,
  ``make demo``, a ROS 2 install); REASON says why, or which test covers it instead.
Every command runs with the venv's ``bin/`` first on PATH, a Zenoh domain of its own (a page's
``export ROS_DOMAIN_ID=N`` keeps it, and what is printed shows N, or 0, the default), any free
viewer port, no browser tab (``BROWSER=true``), and the ROS 1 master port of the page (when a page sets ``ROS_MASTER_URI`` to
port 11311, a free port takes its place in every command of that page).
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from tests.conftest import free_port

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent

_FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```\s*$", re.M | re.S)
_MARK = re.compile(
    r"<!--\s*(run(?::[^>]*)?|output(?::[^>]*)?|file:[^>]*|not run:[^>]*)\s*-->\s*\n$"
)
_CTRL_C = re.compile(r"^<!--\s*ctrl-c\s*-->\s*$", re.M)
_NUMBER = re.compile(r"(\d+(?:\.\d+)?|Jan|Feb|Mar|Apr|May|Jun|Jul|Aug|Sep|Oct|Nov|Dec)")
_FIGURE = r"(?:\d+(?:\.\d+)?|Jan|Feb|Mar|Apr|May|Jun|Jul|Aug|Sep|Oct|Nov|Dec)"


@dataclass(frozen=True)
class Block:
    """One fenced block of a page, with its marker (``run``, ``run: ...``, ``output``)."""

    page: Path
    line: int
    marker: str
    text: str


def blocks(page: Path) -> list[Block]:
    """The marked blocks of a page, in order."""
    text = page.read_text()
    found: list[Block] = []
    for match in _FENCE.finditer(text):
        before = text[: match.start()]
        mark = _MARK.search(before[-400:]) if before.endswith("\n") else None
        if mark is None:
            continue
        line = before.count("\n") + 1
        found.append(Block(page, line, mark.group(1).strip(), match.group(2)))
    for match in _CTRL_C.finditer(text):  # the reader stops what runs, between two blocks
        found.append(Block(page, text[: match.start()].count("\n") + 1, "ctrl-c", ""))
    return sorted(found, key=lambda block: block.line)


def _without_comment(line: str) -> str:
    """The line up to a ``#`` that starts a shell comment (outside quotes, after a blank)."""
    quote = ""
    for index, char in enumerate(line):
        if quote:
            quote = "" if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char == "#" and (index == 0 or line[index - 1].isspace()):
            return line[:index].rstrip()
    return line.rstrip()


def commands(text: str) -> list[str]:
    """A block's command lines: comments dropped, backslash continuations joined."""
    out: list[str] = []
    pending = ""
    for raw in text.splitlines():
        line = _without_comment(raw)
        if not line.strip():
            continue
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        out.append((pending + line).strip())
        pending = ""
    return out


def _literal(text: str, *, any_numbers: bool) -> str:
    """A pattern for ``text`` as shown; with ``any_numbers``, each number matches any number."""
    if not any_numbers:
        return re.escape(text)
    pieces = _NUMBER.split(text)  # literal, number, literal, ...
    return "".join(_FIGURE if index % 2 else re.escape(piece) for index, piece in enumerate(pieces))


def output_matches(expected: str, actual: str, *, any_numbers: bool = False) -> bool:
    """``expected`` with ``...`` lines (any lines) and ``...`` in lines (any text); with
    ``any_numbers``, every number shown matches any number."""
    parts: list[str] = []
    for line in expected.rstrip("\n").splitlines():
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            pieces = line.rstrip().split("...")
            parts.append(
                ".*?".join(_literal(p, any_numbers=any_numbers) for p in pieces) + r"[ \t]*\n"
            )
    pattern = "".join(parts)
    text = "\n".join(line.rstrip() for line in actual.rstrip("\n").splitlines()) + "\n"
    return re.fullmatch(pattern, text, flags=re.S) is not None


@dataclass
class PageRun:
    """The state of one page being run: its folder, environment and background commands."""

    workdir: Path
    domain: str
    env: dict[str, str] = field(default_factory=dict)
    background: list[tuple[str, subprocess.Popen[str], list[str]]] = field(default_factory=list)
    master_port: int = field(default_factory=free_port)
    shown_domain: str = "0"  # the domain the reader has: the default, or what the page exports
    last_output: str = ""

    def __post_init__(self) -> None:
        self.env = dict(os.environ)
        self.env["PATH"] = f"{BIN}{os.pathsep}{self.env.get('PATH', '')}"
        self.env["ROS_DOMAIN_ID"] = self.domain
        self.env["ROBOMODEL_VIEWER_PORT"] = "0"
        self.env["PYTHONUNBUFFERED"] = "1"
        self.env["PYTHONFAULTHANDLER"] = "1"  # a command stuck on Ctrl-C shows where (SIGABRT)
        self.env["BROWSER"] = "true"  # webbrowser.open runs `true URL`: no tab in the tests
        self.env.pop("ROS_MASTER_URI", None)

    def _typed(self, command: str) -> str:
        return command.replace(":11311", f":{self.master_port}").replace(
            "-p 11311", f"-p {self.master_port}"
        )

    def _as_typed(self, output: str) -> str:
        """Output as the reader sees it: the page's master port is 11311 again, and its Zenoh
        domain the reader's."""
        output = output.replace(f":{self.master_port}", ":11311")
        return output.replace(f"domain {self.domain} (", f"domain {self.shown_domain} (")

    def run(self, command: str, timeout_s: float, *, exit_code: int = 0) -> None:
        command = self._typed(command)
        if command == "source .venv/bin/activate":
            assert (BIN / "robomodel").exists()
            return
        export = re.fullmatch(r"export (\w+)=(.*)", command)
        if export:
            value = export.group(2).replace("$PWD", str(self.workdir)).strip("'\"")
            if export.group(1) == "ROS_DOMAIN_ID":  # the tests' own domain, kept apart
                self.shown_domain = value
                return
            self.env[export.group(1)] = value
            return
        unset = re.fullmatch(r"unset (\w+)", command)
        if unset:
            self.env.pop(unset.group(1), None)
            return
        done = subprocess.run(
            ["bash", "-c", command],
            cwd=self.workdir,
            env=self.env,
            capture_output=True,
            text=True,
            timeout=timeout_s,
        )
        # what a shown output holds: standard output, and standard error for an error shown
        self.last_output = self._as_typed(done.stdout + (done.stderr if exit_code else ""))
        if done.returncode != exit_code:
            raise AssertionError(
                f"`{command}` exited {done.returncode}\n{done.stdout}\n{done.stderr}"
            )

    def python(self, script: str, timeout_s: float) -> None:
        path = self.workdir / "docs_example.py"
        path.write_text(script)
        self.run(f"{sys.executable} {path.name}", timeout_s)

    def start(self, command: str, until: str, timeout_s: float) -> None:
        command = self._typed(command)
        proc = subprocess.Popen(
            ["bash", "-c", f"exec {command}"],
            cwd=self.workdir,
            env=self.env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,
        )
        seen: list[str] = []
        self.background.append((command, proc, seen))
        deadline = time.monotonic() + timeout_s
        assert proc.stdout is not None
        os.set_blocking(proc.stdout.fileno(), False)
        while time.monotonic() < deadline:
            line = proc.stdout.readline()
            if line:
                seen.append(line)
                if until in line:
                    self.last_output = self._as_typed("".join(seen))  # an ``output`` block
                    return
            elif proc.poll() is not None:
                break
            else:
                time.sleep(0.05)
        raise AssertionError(f"`{command}` did not print {until!r}:\n{''.join(seen)}")

    def end(self, timeout_s: float) -> list[str]:
        """Ctrl-C to every background command, newest first; the problems seen."""
        problems: list[str] = []
        for command, proc, seen in reversed(self.background):
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
            try:
                proc.wait(timeout=timeout_s)
            except subprocess.TimeoutExpired:
                # it may end between the timeout and these signals (it did not end in time all
                # the same): a process already gone is no error here
                with contextlib.suppress(ProcessLookupError):
                    os.kill(proc.pid, signal.SIGABRT)  # faulthandler prints every thread's stack
                with contextlib.suppress(subprocess.TimeoutExpired):
                    proc.wait(timeout=10)
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                assert proc.stdout is not None
                os.set_blocking(proc.stdout.fileno(), True)
                stacks = proc.stdout.read()
                problems.append(
                    f"`{command}` did not end on Ctrl-C; its threads:\n{stacks[-6000:]}"
                )
                continue
            assert proc.stdout is not None
            os.set_blocking(proc.stdout.fileno(), True)
            rest = proc.stdout.read()
            if "Traceback" in "".join(seen) + rest:
                problems.append(f"`{command}` printed a traceback:\n{''.join(seen)}{rest}")
        self.background.clear()
        return problems


def expected_exit(marker: str) -> int | None:
    """N for ``run: exit N``, 0 for ``run``, None for the other markers."""
    if marker == "run":
        return 0
    match = re.fullmatch(r"run:\s*exit\s+(\d+)", marker)
    return int(match.group(1)) if match else None


def background_until(marker: str) -> str:
    match = re.fullmatch(r'run:\s*background\s+until\s+"([^"]+)"', marker)
    if match is None:
        raise AssertionError(f'bad marker {marker!r}: use run: background until "TEXT"')
    return match.group(1)
