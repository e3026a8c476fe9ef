"""Save Config As and Open Config take only ``.rviz`` paths inside the config's folder or the
working folder, through no symbolic link: anyone who can open the page types the path."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from robomodel.viewer.config_panel import ConfigPanel, PagePathError, page_path
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.viewer.test_markup import _PanelGui


def test_paths_inside_the_roots_are_taken(tmp_path: Path) -> None:
    roots = (Path(os.path.realpath(tmp_path)),)
    assert page_path("view.rviz", roots) == roots[0] / "view.rviz"
    assert page_path(str(roots[0] / "new/sub/view.rviz"), roots) == roots[0] / "new/sub/view.rviz"


@pytest.mark.parametrize(
    ("typed", "said"),
    [
        ("~/.bashrc", "the page reads and writes .rviz files only"),
        ("/etc/passwd", "the page reads and writes .rviz files only"),
        ("/etc/x.rviz", "is outside"),
        ("../escape.rviz", "is outside"),
        ("inner/../../escape.rviz", "is outside"),
        ("link.rviz", "a symbolic link is in the way"),
        ("linked_dir/x.rviz", "a symbolic link is in the way"),
    ],
)
def test_paths_outside_through_links_or_not_rviz_are_refused(
    tmp_path: Path, typed: str, said: str
) -> None:
    root = Path(os.path.realpath(tmp_path)) / "config"
    root.mkdir()
    (root / "link.rviz").symlink_to(tmp_path / "elsewhere.rviz")
    (root / "linked_dir").symlink_to(tmp_path)
    with pytest.raises(PagePathError, match=said):
        page_path(typed, (root,))


class _Client:
    def __init__(self) -> None:
        self.gui = self
        self.buttons: dict[str, Any] = {}
        self.text = ""
        self.camera = None

    def add_modal(self, _title: str) -> Any:
        return _Modal()

    def add_text(self, _label: str, _value: str) -> Any:
        client = self

        class _Box:
            @property
            def value(self) -> str:
                return client.text

        return _Box()

    def add_button(self, label: str) -> Any:
        client = self

        class _Button:
            def on_click(self, callback: Any) -> None:
                client.buttons[label] = callback

        return _Button()


class _Modal:
    def __enter__(self) -> _Modal:
        return self

    def __exit__(self, *_args: object) -> None:
        return None

    def close(self) -> None:
        return None


def test_save_config_as_from_a_page_cannot_write_outside(tmp_path: Path) -> None:
    folder = tmp_path / "pkg" / "config"
    folder.mkdir(parents=True)
    document, _ = open_rviz_document(str(folder / "view.rviz"), RvizDialect.ROS2)

    class _Server:
        gui = _PanelGui()
        initial_camera = None

    from robomodel.viewer.rviz_state import ViewerState

    panel = ConfigPanel(_Server(), document, lambda _camera: ViewerState("base_link", 30.0))
    client = _Client()
    outside = tmp_path / "victim.rviz"
    panel.ask_path(client)
    client.text = str(outside)
    client.buttons["Save"](None)
    assert not outside.exists()
    assert "Not saved" in panel.status.content and "is outside" in panel.status.content
    panel.ask_path(client, title="Open Config", action=panel.open)
    client.text = "/etc/passwd"
    client.buttons["Open"](None)
    assert "Not opened" in panel.status.content and ".rviz files only" in panel.status.content
    panel.ask_path(client)
    client.text = "copy/view.rviz"  # beside the -d file: saved
    client.buttons["Save"](None)
    assert (folder / "copy/view.rviz").read_text().count("Fixed Frame: base_link") == 1
