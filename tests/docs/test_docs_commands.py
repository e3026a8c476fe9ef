"""The documentation's commands work: runnable blocks run, and every robomodel line parses.

- Each page of docs/ (and README.md) with runnable blocks is one test: its blocks run in order
  as tests/docs/runner.py describes, and shown output is compared.
- Every ``robomodel ...`` line in any shell block of the docs, runnable or not, is parsed by
  robomodel's own parser, so removing or renaming an option that the docs use fails here.
"""

from __future__ import annotations

import argparse
import re
import shlex
from pathlib import Path

import pytest

from robomodel.cli.main import _parse, build_parser
from tests.conftest import unique_domain
from tests.docs.runner import (
    ROOT,
    PageRun,
    background_until,
    blocks,
    commands,
    expected_exit,
    output_matches,
)
from tests.timing import scaled

PAGES = [*sorted((ROOT / "docs").rglob("*.md")), ROOT / "README.md"]
RUNNABLE = [page for page in PAGES if any(b.marker.startswith("run") for b in blocks(page))]
_TIMEOUT_S = 180.0


def _name(page: Path) -> str:
    return str(page.relative_to(ROOT))


# Pages whose nodes import rclpy and rospy: they need robomodel's client libraries
# (robomodel.clientlibs.rclpy and .rospy) and are skipped, naming them, where those are absent.
@pytest.mark.parametrize("page", RUNNABLE, ids=_name)
def test_page_commands_run(page: Path, tmp_path: Path) -> None:
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    run = PageRun(tmp_path, unique_domain())
    problems: list[str] = []
    try:
        for block in blocks(page):
            where = f"{_name(page)}:{block.line}"
            code = expected_exit(block.marker)
            if code is not None:
                for command in commands(block.text):
                    try:
                        run.run(command, scaled(_TIMEOUT_S), exit_code=code)
                    except AssertionError as exc:
                        raise AssertionError(f"{where}: {exc}") from None
            elif block.marker == "run: python":
                try:
                    run.python(block.text, scaled(_TIMEOUT_S))
                except AssertionError as exc:
                    raise AssertionError(f"{where}: {exc}") from None
            elif block.marker.startswith("run:"):
                (command,) = commands(block.text)
                run.start(command, background_until(block.marker), scaled(_TIMEOUT_S))
            elif block.marker == "ctrl-c":
                problems += run.end(timeout_s=scaled(60))
            elif block.marker.startswith("file:"):
                target = tmp_path / block.marker.split(":", 1)[1].strip()
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(block.text)
            elif block.marker.startswith("output"):
                any_numbers = block.marker == "output: figures vary"
                assert output_matches(block.text, run.last_output, any_numbers=any_numbers), (
                    f"{where}: the output shown differs from what the command printed:\n"
                    f"{run.last_output}"
                )
    finally:
        problems += run.end(timeout_s=scaled(60))
    assert not problems, "\n".join(problems)


_SHELL = ("bash", "sh", "console", "shell")
_CODE = (*_SHELL, "python", "py")


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_page_code_blocks_are_run(page: Path) -> None:
    """Every shell and Python block of every page (the README, the newcomer pages and the
    reference) is run by a test (``<!-- run... -->``, the README's quickstart) or says why not
    and which test covers it (``<!-- not run: REASON naming tests/... -->``)."""
    text = page.read_text()
    marked = {block.line for block in blocks(page)}
    unmarked = [
        f"{_name(page)}:{text[: match.start()].count(chr(10)) + 1}"
        for match in re.finditer(r"^```(\w+)[^\n]*\n", text, flags=re.M)
        if match.group(1) in _CODE
        and text[: match.start()].count("\n") + 1 not in marked
        and "<!-- quickstart:" not in text[max(0, match.start() - 100) : match.start()]
    ]
    assert not unmarked, f"code blocks neither run nor marked `not run: REASON`: {unmarked}"
    for block in blocks(page):
        if block.marker.startswith("not run"):
            where = f"{_name(page)}:{block.line}"
            reason = block.marker.split(":", 1)[1].strip()
            named = re.findall(r"tests/[\w/.-]*\w", reason)
            assert named, f"{where}: the reason names no test under tests/: {reason!r}"
            for path in named:
                assert (ROOT / path.split("::")[0]).exists(), f"{where}: {path} does not exist"


def _shell_lines() -> list[tuple[str, str]]:
    """(where, line) for every ``robomodel`` command in the docs' shell blocks and inline code."""
    found: list[tuple[str, str]] = []
    fence = re.compile(r"^```(bash|sh|console|shell)\n(.*?)^```", re.M | re.S)
    for page in PAGES:
        text = page.read_text()
        for match in fence.finditer(text):
            line_no = text[: match.start()].count("\n") + 1
            for line in commands(match.group(2)):
                line = line.removeprefix("$ ")
                if line.startswith("robomodel ") and not _is_synopsis(line):
                    found.append((f"{_name(page)}:{line_no}", line))
    return found


def _inline_mentions() -> list[tuple[str, str]]:
    """(where, text) for inline code that names a robomodel command: `robomodel view --port`."""
    found: list[tuple[str, str]] = []
    for page in PAGES:
        text = page.read_text()
        for match in re.finditer(r"(?<!`)`(robomodel [^`\n]+)`(?!`)", text):
            found.append(
                (f"{_name(page)}:{text[: match.start()].count(chr(10)) + 1}", match.group(1))
            )
    return found


def _is_synopsis(line: str) -> bool:
    """A usage line with placeholders (``FILE``, ``[--x]``, ``a|b``, ``...``), not a command."""
    words = shlex.split(line, posix=True) if line.count("'") % 2 == 0 else line.split()
    return any(
        re.search(r"[\[\]|]|\.\.\.", word) or re.fullmatch(r"[A-Z][A-Z_]+[A-Z](\.\w+)?", word)
        for word in words[1:]
        if "=" not in word and ":" not in word
    )


@pytest.mark.parametrize(("where", "line"), _shell_lines(), ids=[w for w, _ in _shell_lines()])
def test_documented_command_parses(where: str, line: str) -> None:
    argv = shlex.split(line)[1:]
    for index, word in enumerate(argv):
        if word in ("|", ">", "&&", ";"):
            argv = argv[:index]
            break
    verb = next((a for a in argv if not a.startswith("-")), None)
    parser = build_parser(verb)
    try:
        _parse(parser, argv)  # as main() parses: name:=value may follow options
    except SystemExit as exc:
        if exc.code not in (0, None):
            pytest.fail(f"{where}: `{line}` does not parse (exit {exc.code})")


@pytest.mark.parametrize(
    ("where", "text"), _inline_mentions(), ids=[w for w, _ in _inline_mentions()]
)
def test_documented_options_exist(where: str, text: str) -> None:
    """A command named in the text (often incomplete: `robomodel launch --nodes`) names only
    verbs, sub-verbs and options that exist."""
    from robomodel.cli._verbs import VERBS

    words = re.sub(r"[\\|\[\]]", " ", text).split()[1:]
    if not words or words[0] not in {v.name for v in VERBS}:
        return  # a mistyped verb shown on purpose (`robomodel lanch`), or a path
    parser = _subparsers(build_parser(words[0]))[words[0]]
    for word in words[1:]:
        subs = _subparsers(parser)
        if word in subs:
            parser = subs[word]
        elif word.startswith("-") and not re.fullmatch(r"-\d.*", word):
            option = word.split("=", 1)[0]
            assert option in parser._option_string_actions, f"{where}: `{text}`: no {option}"


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}
