"""The page's File folder: RViz's File > Open Config, Save Config and Save Config As.

Save Config writes the ``-d`` file (RViz's ``display_config_file_``), Save Config As asks for a
path in a dialog and makes it the file later saves write, as RViz does. What is saved is what
the page shows (see :mod:`robomodel.viewer.rviz_state`), in RViz's own format, ROS 1 or ROS 2
class names as the launch or bus is. The outcome is one line in the folder: the path written,
or why it could not be written.
"""

from __future__ import annotations

import logging
import os
import threading
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from robomodel.viewer.displays.attach import config_with_displays, open_config_displays
from robomodel.viewer.markup import Markup, code, md, safe_markdown
from robomodel.viewer.rviz_apply import apply_rviz_document, viewer_state
from robomodel.viewer.rviz_config import RvizConfigError
from robomodel.viewer.rviz_document import RvizDocument, open_rviz_document
from robomodel.viewer.rviz_model import RvizConfig, RvizDialect
from robomodel.viewer.rviz_open import reopen_rviz_document
from robomodel.viewer.rviz_state import ViewerState, config_with_state
from robomodel.viewer.rviz_write import RvizSaveError, write_rviz_config

__all__ = ["ConfigPanel", "PagePathError", "attach_rviz", "page_path"]

DisplaysHook = Callable[[RvizConfig, RvizDialect], tuple[RvizConfig, Callable[[], None]]]

log = logging.getLogger("robomodel.viewer")


class PagePathError(ValueError):
    """A path typed in the page that the viewer does not read or write."""


def page_path(text: str, roots: tuple[Path, ...]) -> Path:
    """The file a page's Save Config As or Open Config dialog names, if the viewer lets a
    page use it: an ``.rviz`` file inside one of ``roots`` (real paths: the ``-d`` config's
    folder, the working folder), reached through no symbolic link. Anyone who can open the page can
    type a path, so the page cannot overwrite ``~/.bashrc`` or read ``/etc/shadow`` through
    the viewer; the ``-d`` file itself (a command-line choice) is not restricted.

    Raises:
        PagePathError: outside the roots, through a link, or not an ``.rviz`` file.
    """
    typed = Path(text).expanduser()
    target = Path(os.path.abspath(typed if typed.is_absolute() else roots[0] / typed))
    if target.suffix != ".rviz":
        raise PagePathError(f"{target}: the page reads and writes .rviz files only")
    if os.path.realpath(target) != str(target):
        raise PagePathError(f"{target}: a symbolic link is in the way; give the real path")
    if not any(target.is_relative_to(root) for root in roots):
        folders = " or ".join(str(root) for root in roots)
        raise PagePathError(f"{target} is outside {folders}, where the page may save and open")
    return target


def _nothing() -> None:
    pass


class ConfigPanel:
    """The File folder.

    Args:
        server: The viser server.
        document: The config the viewer opened (its ``path`` is Save Config's target).
        state: The page's state to save, given the browser (its camera) that asked.
        frame_rate_hz: The viewer's Frame Rate when the config gives none.
        displays: Puts the Displays panel's displays into a config; returns it and what to
            call once it is written (see :func:`~robomodel.viewer.displays.attach.
            config_with_displays`).
        reopen: Applies a document opened with Open Config to the viewer (None: no Open).
    """

    def __init__(
        self,
        server: Any,
        document: RvizDocument,
        state: Callable[[Any], ViewerState],
        *,
        frame_rate_hz: float = 60.0,
        displays: DisplaysHook | None = None,
        reopen: Callable[[RvizDocument], None] | None = None,
    ) -> None:
        self.document = document
        folder = Path(document.path).expanduser().absolute().parent if document.path else None
        self.roots = tuple(
            dict.fromkeys(Path(os.path.realpath(p)) for p in (folder, Path.cwd()) if p is not None)
        )
        self._displays = displays
        self._reopen = reopen
        self._frame_rate_hz = frame_rate_hz
        self._state = state
        self._server = server
        self._lock = threading.Lock()
        gui = server.gui
        with gui.add_folder("File"):
            self.status = safe_markdown(gui, self._opened_text())
            self.save_button = gui.add_button("Save Config", icon="device-floppy")
            self.save_as_button = gui.add_button("Save Config As")
            self.open_button = gui.add_button("Open Config", visible=reopen is not None)
        self.save_button.on_click(lambda event: self._on_save(event.client))
        self.save_as_button.on_click(lambda event: self.ask_path(event.client))
        self.open_button.on_click(
            lambda event: self.ask_path(event.client, title="Open Config", action=self.open)
        )

    def _opened_text(self) -> Markup:
        path = self.document.path
        if path is None:
            return md("RViz config: none (Save Config As writes one)")
        if self.document.missing:
            return md("RViz config {} does not exist yet: Save Config writes it", code(path))
        return md("RViz config {}", code(path))

    def _on_save(self, client: Any) -> None:
        if self.document.path is None:
            self.ask_path(client)
        else:
            self.save(self.document.path, client)

    def save(self, path: str, client: Any = None) -> bool:
        """Write what ``client``'s page shows to ``path``; whether it was written (the folder
        says where, or why not)."""
        with self._lock:
            # Without a browser (a script, a test): the page's initial camera.
            camera = client.camera if client is not None else self._server.initial_camera
            state = self._state(camera)
            config = config_with_state(self.document, state, frame_rate_hz=self._frame_rate_hz)
            saved: Callable[[], None] = _nothing
            if self._displays is not None:
                config, saved = self._displays(config, self.document.dialect)
            try:
                written = write_rviz_config(path, config)
            except RvizSaveError as exc:
                self.status.content = md("**Not saved**: {}", exc)
                log.warning("%s", exc)
                return False
            self.document = replace(self.document, path=str(path), config=config, missing=False)
            saved()
            self.status.content = md("Saved RViz config {}", code(written))
            log.info("saved RViz config %s", written)
            return True

    def open(self, path: str, client: Any = None) -> bool:
        """Open Config: read ``path`` and apply it to the viewer (on its loop thread); whether
        it was read (the folder says which file, or why not)."""
        if self._reopen is None:
            return False
        with self._lock:
            try:
                document, _ = open_rviz_document(path, self.document.dialect)
            except RvizConfigError as exc:
                self.status.content = md("**Not opened**: {}", exc)
                return False
            if document.missing:
                self.status.content = md("**Not opened**: {} does not exist", code(path))
                return False
            self.document = document
            self._reopen(document)
            self.status.content = md("Opened RViz config {}", code(path))
            log.info("opened RViz config %s", path)
            return True

    def ask_path(self, client: Any, *, title: str = "Save Config As", action: Any = None) -> None:
        """A dialog on ``client``'s page asking for the file to save (or to open, with the
        ``action`` ``open``)."""
        if client is None:
            return
        act = self.save if action is None else action
        verb = title.split()[0]
        with client.gui.add_modal(title) as modal:
            path = client.gui.add_text("Path", self.document.path or "robomodel.rviz")
            ok = client.gui.add_button(verb)
            cancel = client.gui.add_button("Cancel")

        def on_ok(_event: Any) -> None:
            text = str(path.value).strip()
            done = "opened" if verb == "Open" else "saved"
            if not text:
                self.status.content = md("**Not {}**: give a file path", done)
            else:
                try:
                    act(str(page_path(text, self.roots)), client)
                except PagePathError as exc:
                    self.status.content = md("**Not {}**: {}", done, exc)
                    log.warning("not %s: %s", done, exc)
            modal.close()

        ok.on_click(on_ok)
        cancel.on_click(lambda _event: modal.close())


def attach_rviz(viewer: Any, panel: Any) -> ConfigPanel:
    """Apply the viewer's ``-d`` config (``options.rviz``) to ``panel`` and its displays to the
    Displays panel, and add the File folder; without one, RViz's defaults (its Grid) with
    RobotModel (one per robot) and TF (ROS 1 class names on a ROS 1 bus, else ROS 2's), which
    Save Config As starts from."""
    document = viewer.options.rviz
    displays = viewer.displays_panel
    if document is not None:
        apply_rviz_document(viewer, panel, document)
    else:
        dialect = RvizDialect.ROS1 if viewer.options.bus == "ros1" else RvizDialect.ROS2
        document, _ = open_rviz_document(None, dialect)
    if displays is not None:  # a missing file's are the defaults: Grid, RobotModel, TF
        for problem in open_config_displays(displays, document, viewer.sessions):
            log.warning("RViz config %s: %s", document.path, problem)
    return ConfigPanel(
        viewer.server,
        document,
        lambda camera: viewer_state(panel, camera),
        frame_rate_hz=viewer.options.frame_rate_hz,
        displays=None
        if displays is None
        else lambda config, dialect: config_with_displays(
            list(displays.manager.displays), config, dialect
        ),
        reopen=lambda document: viewer._post(lambda: reopen_rviz_document(viewer, panel, document)),
    )
