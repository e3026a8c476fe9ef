"""docs/reference/limits.md states the bounds the code has: each constant it names, with the
value it gives."""

from __future__ import annotations

import importlib

import pytest

from tests.conftest import ROOT

LIMITS = (ROOT / "docs/reference/limits.md").read_text()

# (module, constant, its value, how the page writes it)
STATED = [
    ("robomodel._yaml_bounded", "MAX_FILE_BYTES", 16 * 2**20, "16 MiB (`MAX_FILE_BYTES`)"),
    ("robomodel._yaml_bounded", "MAX_FILE_DEPTH", 100, "100 levels of nesting (`MAX_FILE_DEPTH`"),
    ("robomodel._yaml_bounded", "MAX_EXPANDED_NODES", 1_000_000, "1,000,000 values once every alias is expanded (`MAX_EXPANDED_NODES`)"),
    ("robomodel.sim.sensors.camera_spec", "MAX_CAMERA_SIDE_PX", 4096, "1..4,096 pixels (`MAX_CAMERA_SIDE_PX`)"),
    ("robomodel.sim.sensors.camera_spec", "MAX_SENSOR_RATE_HZ", 1000.0, "0..1,000 Hz (`MAX_SENSOR_RATE_HZ`)"),
    ("robomodel.viewer.limits", "MAX_TEXT_CHARS", 1000, "1,000 characters and 100 lines (`MAX_TEXT_CHARS`, `MAX_TEXT_LINES`)"),
    ("robomodel.viewer.limits", "MAX_TEXT_LINES", 100, "1,000 characters and 100 lines (`MAX_TEXT_CHARS`, `MAX_TEXT_LINES`)"),
    ("robomodel.viewer.limits", "MAX_MARKER_POINTS", 1_000_000, "1,000,000 (`MAX_MARKER_POINTS`)"),
    ("robomodel.viewer.limits", "MAX_MARKERS_PER_NAMESPACE", 10_000, "10,000 per namespace (`MAX_MARKERS_PER_NAMESPACE`)"),
    ("robomodel.viewer.limits", "MAX_MARKERS", 100_000, "100,000 per Marker or MarkerArray display (`MAX_MARKERS`)"),
    ("robomodel.viewer.limits", "MAX_CLOUD_POINTS", 2_000_000, "2,000,000 (`MAX_CLOUD_POINTS`)"),
    ("robomodel.viewer.limits", "MAX_CLOUDS_KEPT", 1000, "1,000 clouds (`MAX_CLOUDS_KEPT`)"),
    ("robomodel.viewer.limits", "MAX_CLOUD_BYTES_KEPT", 256 * 2**20, "256 MiB of point data (`MAX_CLOUD_BYTES_KEPT`)"),
    ("robomodel.viewer.limits", "MAX_IMAGE_PIXELS", 4096 * 4096, "4096 x 4096 (`MAX_IMAGE_PIXELS`)"),
    ("robomodel.viewer.limits", "MAX_PARAMETERS_SHOWN", 1000, "1,000 (`MAX_PARAMETERS_SHOWN`)"),
    ("robomodel.viewer.limits", "MAX_ODOMETRY_PENDING", 1000, "1,000 (`MAX_ODOMETRY_PENDING`)"),
    ("robomodel.runtime.ros1_action_server", "MAX_ENDED_GOALS", 100, "100 at most (`MAX_ENDED_GOALS`)"),
    ("robomodel.runtime.ros1_action_server", "MAX_EARLY_CANCELS", 100, "100 ids cancelled before their goal came are kept to recall it (`MAX_EARLY_CANCELS`)"),
    ("robomodel.cli.graph", "DOT_TIMEOUT_S", 60.0, "60 s (`DOT_TIMEOUT_S`)"),
    ("robomodel.cli.graph", "MAX_DOT_BYTES", 8 * 2**20, "8 MiB of Graphviz text (`MAX_DOT_BYTES`)"),
    ("robomodel.cli.graph", "DOT_MEMORY_BYTES", 2 * 2**30, "2 GiB of address space (`DOT_MEMORY_BYTES`)"),
    ("robomodel.cli.log", "MAX_MESSAGE_CHARS", 8192, "8,192 characters of message and of file name\n(`MAX_MESSAGE_CHARS`)"),
    ("robomodel.cli.log", "MAX_NAME_CHARS", 256, "256 of node name (`MAX_NAME_CHARS`)"),
    ("robomodel.cli.log", "MAX_NODE_COLUMN", 48, "48 characters (`MAX_NODE_COLUMN`)"),
]  # fmt: skip


@pytest.mark.parametrize(("module", "name", "value", "written"), STATED, ids=[s[1] for s in STATED])
def test_the_limits_page_states_the_bound_the_code_has(
    module: str, name: str, value: float, written: str
) -> None:
    assert getattr(importlib.import_module(module), name) == value
    assert written in LIMITS
