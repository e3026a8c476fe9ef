"""``robomodel run tf view_frames`` (seed 000's "Tree of tf") against Debian's tf view_frames
(tf-tools) on the same ROS 1 graph: the printed lines and frames.gv in tf's ``allFramesAsDot``
form, equal once the measured numbers and the broadcaster's name are left out. Debian's script
ends in a TypeError under Python 3 after writing frames.gv (no pdf); robomodel's writes the pdf.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import ROBOMODEL
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled

VIEW_FRAMES = Path("/usr/lib/tf/view_frames")


def _shape(gv: str) -> list[str]:
    """frames.gv's lines without numbers and broadcasters, sorted (the edges' order is the
    order the frames first arrived in, which two publishers do not fix)."""
    text = re.sub(r"Broadcaster: [^\\]*", "Broadcaster: B", gv)
    return sorted(re.sub(r"-?\d+\.\d+", "N", text).splitlines())


def test_tf_view_frames_writes_what_debian_s_writes(ros1: Ros1, tmp_path: Path) -> None:
    if not VIEW_FRAMES.exists():
        pytest.fail("Debian's tf view_frames is missing: tools/system-deps test installs tf-tools")
    ros1.robomodel("master", "--port", str(ros1.port))
    ros1.wait_for_master()
    for argv in (("1", "0", "0", "world", "base"), ("0", "0", "0.5", "base", "tool")):
        x, y, z, parent, child = argv
        ros1.robomodel("run", "tf", "static_transform_publisher", x, y, z, "0", "0", "0",
                       parent, child, "50")  # fmt: skip
    ros1.until(
        lambda: "tool" in ros1.run("/usr/bin/rostopic", "echo", "-n", "2", "/tf").stdout,
        "both transforms on /tf",
    )
    theirs_dir, ours_dir = tmp_path / "debian", tmp_path / "robomodel"
    theirs_dir.mkdir()
    ours_dir.mkdir()
    theirs = ros1.run("/usr/bin/python3", str(VIEW_FRAMES), cwd=theirs_dir, timeout=scaled(60))
    ours = ros1.run(*ROBOMODEL, "run", "tf", "view_frames", cwd=ours_dir, timeout=scaled(60))
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout.splitlines()[:2] == theirs.stdout.splitlines()[:2] == [
        "Listening to /tf for 5.0 seconds", "Done Listening",
    ]  # fmt: skip
    assert "TypeError" in theirs.stderr  # Debian's dot version check under Python 3
    assert ours.stdout.splitlines()[-1] == "frames.pdf generated"
    assert (ours_dir / "frames.pdf").read_bytes().startswith(b"%PDF")
    their_gv = (theirs_dir / "frames.gv").read_text()
    our_gv = (ours_dir / "frames.gv").read_text()
    assert '"world" -> "base"' in our_gv and '"base" -> "tool"' in our_gv
    assert _shape(our_gv) == _shape(their_gv), (our_gv, their_gv)
