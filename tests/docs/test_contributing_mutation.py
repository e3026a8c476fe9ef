"""CONTRIBUTING.md's "Mutation testing" section names the groups and files that
``make mutate`` (tools/mutate.py) really mutates, and the tool lists them."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from tests.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
SECTION = re.compile(r"^## Mutation testing\n(.*?)(?=^## |\Z)", re.S | re.M)
ROW = re.compile(r"^\| (\w+) \| `([\w/.]+\.py)` \|", re.M)


def _groups() -> dict[str, tuple[tuple[str, ...], tuple[str, ...]]]:
    done = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "mutate.py"), "--list"],
        capture_output=True, text=True, timeout=scaled(60), check=True,
    )  # fmt: skip
    groups = {}
    for head, tests in zip(*[iter(done.stdout.splitlines())] * 2, strict=True):
        name, sources = head.split(": ", 1)
        groups[name.split(" (")[0]] = (  # "cdr (1 mutant in 10)": a sampled group
            tuple(sources.split(", ")),
            tuple(tests.strip().removeprefix("tests: ").split(", ")),
        )
    return groups


def test_the_scores_table_names_each_group_s_files_and_they_exist() -> None:
    section = SECTION.search((ROOT / "CONTRIBUTING.md").read_text())
    assert section is not None, "CONTRIBUTING.md has no '## Mutation testing' section"
    groups = _groups()
    rows = ROW.findall(section.group(1))
    assert rows, "the section has no scores table"
    for group, source in rows:
        assert group in groups, f"CONTRIBUTING.md names group {group}; tools/mutate.py has {list(groups)}"  # fmt: skip
        assert source in groups[group][0], f"{source} is not mutated in group {group}"
    for name, (sources, tests) in groups.items():
        assert all((ROOT / "src" / "robomodel" / s).is_file() for s in sources), name
        assert all((ROOT / "tests" / t.split("::")[0]).is_file() for t in tests), name


def test_an_unknown_group_is_one_line_and_exit_code_2() -> None:
    done = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "mutate.py"), "inproc", "nosuch"],
        capture_output=True, text=True, timeout=scaled(60), check=False,
    )  # fmt: skip
    assert done.returncode == 2
    assert done.stderr.strip().startswith("mutate: unknown group nosuch; groups are: inproc, ")
    assert "\n" not in done.stderr.strip()


def test_sampled_groups_say_so_and_a_sample_must_divide_ten() -> None:
    done = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "mutate.py"), "--list"],
        capture_output=True, text=True, timeout=scaled(60), check=True,
    )  # fmt: skip
    assert "\ncdr (1 mutant in 10): " in "\n" + done.stdout
    assert "\ninproc: " in "\n" + done.stdout
    refused = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "mutate.py"), "cdr", "--sample", "3"],
        capture_output=True, text=True, timeout=scaled(60), check=False,
    )  # fmt: skip
    assert refused.returncode == 2 and "invalid choice: 3" in refused.stderr


def test_a_group_s_folder_runs_its_tests_with_xdist_off(tmp_path: Path) -> None:
    """A group's pyproject.toml is the project's without xdist's options in pytest's addopts
    (``--dist loadgroup``): mutmut runs the tests with ``-p no:xdist``, and pytest refuses an
    option of a plugin it did not load, so no mutant would run."""
    sys.path.insert(0, str(ROOT / "tools"))
    try:
        import mutate
    finally:
        sys.path.remove(str(ROOT / "tools"))
    text = mutate._without_xdist_options(ROOT / "pyproject.toml")
    (tmp_path / "pyproject.toml").write_text(text)
    (tmp_path / "test_one.py").write_text("def test_one():\n    pass\n")
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:xdist", "test_one.py"],
        capture_output=True, text=True, timeout=scaled(60), check=False, cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    assert "--dist" in (ROOT / "pyproject.toml").read_text()  # what the function takes out
    assert "--strict-markers" in text
