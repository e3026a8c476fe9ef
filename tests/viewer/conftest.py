"""Fixtures for the viewer tests: a `robomodel view` process, headless Chromium, screenshots.

The browser is Debian's Chromium (``apt-get install chromium``; `.ci/run` installs it), driven
by playwright's Python package through ``executable_path`` (``playwright install`` is never
needed). WebGL renders in software.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
import subprocess
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import ROBOMODEL, end_process, unique_domain
from tests.timing import scaled, wait_until

CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
# WebGL through ANGLE on Mesa's llvmpipe (EGL, no display or GPU needed): a viewer page's first
# frames (shader compilation) cost about two thirds of the CPU they cost in Chromium's own
# SwiftShader, and llvmpipe draws on several threads. Where Mesa's EGL does not start, the
# browser is started again on SwiftShader (--disable-gpu). The page is composited on the CPU
# (--disable-gpu-compositing; WebGL still draws on llvmpipe): compositing through llvmpipe cost
# the GPU process about twice the CPU a page load (1.8 against 0.85 s) and a screenshot 115
# against 80 ms, for the same picture (0.02% of pixels differing by more than 30 levels).
MESA_WEBGL_ARGS = [
    "--use-angle=gl-egl",
    "--ignore-gpu-blocklist",
    "--enable-gpu",
    "--disable-gpu-compositing",
]
SWIFTSHADER_ARGS = ["--disable-gpu"]
# WebGL without multisampling, unless ROBOMODEL_TEST_ANTIALIAS=1 (tools/docs_screenshots.py sets
# it: the documentation's pictures keep their smooth edges). Software GL draws every sample of a
# multisampled canvas: an idle UR5 page (viser draws a frame a second) cost the GPU process 0.19-
# 0.23 CPU-s a second with it and 0.09 without, and three UR5 page loads 16-21 against 14-15
# CPU-s. What the tests look at (colours inside shapes, what is drawn where) is the same; only
# the edges of shapes are not blended.
ANTIALIAS_ARGS = (
    [] if os.environ.get("ROBOMODEL_TEST_ANTIALIAS") == "1" else ["--webgl-antialiasing-mode=none"]
)
VIEWPORT = {"width": 1024, "height": 576}


def chromium_path() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        pytest.fail("Chromium is not installed: apt-get install chromium (.ci/run does)")
    return path


def wait_for(
    condition: Callable[[], Any],
    timeout_s: float = 20.0,
    what: str | Callable[[], str] = "",
) -> Any:
    """``wait_until`` with the viewer tests' pace and default: 20 s (scaled), a check every
    0.1 s (a screenshot takes longer than that), ``what`` defaulting to the condition."""
    return wait_until(condition, timeout_s, what=what or repr(condition), interval_s=0.1)


class ViewerProcess:
    """A ``robomodel view`` subprocess on an ephemeral port."""

    def __init__(self, args: list[str], cwd: Path | None = None) -> None:
        env = dict(os.environ, PYTHONUNBUFFERED="1")
        self.proc = subprocess.Popen(
            [*ROBOMODEL, "view", *args, "--no-browser", "--port", "0"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
            cwd=cwd,
        )
        assert self.proc.stdout is not None
        line = self.proc.stdout.readline()
        if "serving" not in line:
            self.stop()
            pytest.fail(f"robomodel view did not start: {line}{self.stderr}")
        self.url = line.split("serving ")[1].split()[0]
        self.stderr = ""

    def stop(self) -> None:
        end_process(self.proc)
        assert self.proc.stderr is not None
        self.stderr = self.proc.stderr.read()


@pytest.fixture
def viewer() -> Iterator[Callable[..., ViewerProcess]]:
    started: list[ViewerProcess] = []

    def start(*args: str, cwd: Path | None = None) -> ViewerProcess:
        process = ViewerProcess([str(a) for a in args], cwd=cwd)
        started.append(process)
        return process

    yield start
    for process in started:
        process.stop()


@pytest.fixture(scope="session")
def browser() -> Iterator[Any]:
    from playwright.sync_api import sync_playwright

    # launch() gives every browser a fresh temporary profile (it refuses --user-data-dir).
    with sync_playwright() as pw:
        instance = pw.chromium.launch(
            executable_path=chromium_path(),
            headless=True,
            args=CHROMIUM_ARGS + MESA_WEBGL_ARGS + ANTIALIAS_ARGS,
        )
        if "llvmpipe" not in webgl_renderer(instance):
            instance.close()
            instance = pw.chromium.launch(
                executable_path=chromium_path(),
                headless=True,
                args=CHROMIUM_ARGS + SWIFTSHADER_ARGS + ANTIALIAS_ARGS,
            )
        yield instance
        instance.close()


def webgl_renderer(browser: Any) -> str:
    """The renderer a page of ``browser`` gets for WebGL 2 ("" when it gets none)."""
    page = browser.new_page()
    try:
        return str(
            page.evaluate(
                """() => {
                  const gl = document.createElement("canvas").getContext("webgl2");
                  if (!gl) return "";
                  const info = gl.getExtension("WEBGL_debug_renderer_info");
                  return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
                }"""
            )
        )
    finally:
        page.close()


@contextlib.contextmanager
def new_page(browser: Any) -> Iterator[Any]:
    """A page in a browser context of its own, closed at the end."""
    context = browser.new_context(viewport=VIEWPORT)
    # playwright's 30 s default (clicks, wait_for, screenshots), scaled with the machine: a
    # loaded one ran out of it on folder clicks and screenshots (tests/timing.py)
    context.set_default_timeout(scaled(30_000))
    page = context.new_page()
    said: list[str] = []  # the page's console and crashes, printed with a failure's report
    page.on("console", lambda message: said.append(f"console {message.type}: {message.text}"))
    page.on("crash", lambda _page: said.append("the page crashed"))
    try:
        yield page
    finally:
        context.close()
        print("\n".join(said))


@pytest.fixture
def page(browser: Any) -> Iterator[Any]:
    with new_page(browser) as opened:
        yield opened


def open_viewer(page: Any, url: str) -> None:
    """Load the page and wait until the GUI arrived over the websocket."""
    page.goto(url)
    # .first: the Status may name the Fixed Frame too ("Fixed Frame `world` does not exist")
    page.get_by_text("Fixed Frame", exact=True).first.wait_for(timeout=scaled(30_000))


def page_client(viewer: Any) -> Any:
    """The viser client of the one page open on ``viewer`` (an in-process Viewer), once it is
    connected: the GUI can arrive over a websocket that then closes, and the page connects
    again (seen on a loaded machine), so for a moment there is none."""
    (client,) = wait_for(
        lambda: (
            clients if len(clients := tuple(viewer.server.get_clients().values())) == 1 else None
        ),
        what="the page connected to the viewer",
    )
    return client


def screenshot(page: Any) -> np.ndarray:
    """The page as an (H, W, 3) uint8 array."""
    from PIL import Image

    data = page.screenshot()
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))


def scene_region(image: np.ndarray) -> np.ndarray:
    """The 3D view without the GUI panel (right) and the notification corner (top left)."""
    h, w, _ = image.shape
    return image[int(0.25 * h) : int(0.95 * h), int(0.05 * w) : int(0.58 * w)]


def changed_fraction(a: np.ndarray, b: np.ndarray, threshold: int = 30) -> float:
    """Fraction of pixels whose colour differs by more than ``threshold`` in some channel."""
    diff = np.abs(a.astype(np.int16) - b.astype(np.int16)).max(axis=2)
    return float((diff > threshold).mean())


def drawn(image: np.ndarray) -> bool:
    """Whether the scene shows anything (the grid's lines at least): a canvas that has not
    painted its first frame yet is one flat colour."""
    return bool((np.abs(image.astype(np.int16) - image[0, 0]).max(axis=2) > 30).any())


def settle(page: Any, timeout_s: float | None = None) -> np.ndarray:
    """Screenshot once the scene shows something and two consecutive shots of it agree
    (rendering has caught up), or after ``timeout_s`` (default ``scaled(15)``)."""
    deadline = time.monotonic() + (scaled(15.0) if timeout_s is None else timeout_s)
    last = scene_region(screenshot(page))
    while time.monotonic() < deadline:
        time.sleep(0.3)
        current = scene_region(screenshot(page))
        if changed_fraction(last, current) < 0.0005 and drawn(current):
            return current
        last = current
    if not drawn(last):  # for the failure's reader: the whole page as it was
        print(
            f"settle: nothing drawn; the page is in {save_shot(page, f'nothing_drawn_{os.getpid()}')}"
        )
    return last


def changed_view(
    page: Any, before: np.ndarray, at_least: float = 0.002, what: str = "the scene to change"
) -> np.ndarray:
    """The settled scene once it differs from ``before`` in more than ``at_least`` of its
    pixels: an action's effect reaches the canvas after a websocket round trip, which a
    loaded machine can make longer than the 0.3 s between two agreeing shots of settle()."""

    def failed() -> str:  # for the failure's reader: the page as it was
        return f"{what} (the page is in {save_shot(page, f'unchanged_{os.getpid()}')})"

    (image,) = wait_for(
        lambda: (shot,) if changed_fraction(before, shot := settle(page, 5)) > at_least else None,
        what=failed,
    )
    return image  # type: ignore[no-any-return]


def gui_row(page: Any, label: str) -> Any:
    """The GUI row of the control labelled ``label`` (its inputs, slider, ...)."""
    # Not text-is: viser breaks labels after "_" with <wbr>, which text-is does not see through.
    exact = re.compile(f"^{re.escape(label)}$")
    return (
        page.locator("label")
        .filter(has_text=exact)
        .locator("xpath=ancestor::div[.//input[not(@type='hidden')]][1]")
    )


def type_into(page: Any, label: str, text: str, server: Any = None) -> None:
    """Type ``text`` into the text box ``label`` and press Enter; with ``server`` (the
    in-process viewer's ``viser.ViserServer``), wait until the server holds the value.

    viser's page (1.1.1, ``makeThrottledMessageSender`` in ``WebsocketUtils.ts``) sends every
    GUI update of a panel through one 50 ms throttle that keeps only the latest message: a value
    typed less than 50 ms before another control's update never reaches the server. A person is
    slower than that; a test that goes on to the next control waits for the server instead."""
    box = gui_row(page, label).locator("input:not([type=hidden])").first
    box.fill(text)
    box.press("Enter")
    if server is None:
        return
    handles = server.gui._gui_input_handle_from_uuid.values()  # viser keeps no public index
    wait_for(
        lambda: any(h.label == label and str(h.value) == text for h in list(handles)),
        what=f"the server to hold {label} = {text!r}",
    )


def toggle_checkbox(page: Any, label: str, folder: str = "RobotModel") -> None:
    """Toggle the checkbox ``label`` of the display ``folder`` (opened first: the Displays
    panel's folders start collapsed, as RViz's tree), and wait until the page shows it flipped.

    The click is a DOM click on the checkbox itself, not the pointer at the label's place: the
    panel scrolls to bring a control at the bottom of a folder into view while the folder is
    still opening, and under ``stress-ng`` a pointer click there left the box as it was (1 in
    3 runs of the browser tests, its picture kept)."""
    box = page.locator(f"label:text-is('{label}')").filter(visible=True)
    if box.count() == 0:
        page.get_by_text(folder, exact=True).filter(visible=True).first.click()
    box.first.wait_for()
    flip_checkbox(page, gui_row(page, label).locator("input[type=checkbox]").filter(visible=True).first, label)  # fmt: skip


def flip_checkbox(page: Any, checkbox: Any, label: str) -> None:
    """Send a DOM click to ``checkbox`` (a locator) and wait until the page shows it flipped
    (see :func:`toggle_checkbox` for why not the pointer)."""
    was = checkbox.is_checked()
    checkbox.dispatch_event("click")

    def failed() -> str:  # for the failure's reader: the page as it was
        shot = save_shot(page, f"unclicked_{os.getpid()}")
        return f"{label} {'un' if was else ''}checked on the page (the page is in {shot})"

    wait_for(lambda: checkbox.is_checked() != was, what=failed)


def slider_input(page: Any, label: str) -> Any:
    """The editable value box next to the slider labelled ``label``."""
    return gui_row(page, label).locator("input:not([type=hidden])").first


def slider_thumb(page: Any, label: str) -> Any:
    """The thumb of the slider labelled ``label`` (takes arrow keys, Home and End)."""
    return gui_row(page, label).locator("[role=slider]").first


def save_shot(page: Any, name: str) -> Path:
    """Keep a screenshot for people to look at (build/viewer-screenshots/)."""
    out = Path(__file__).resolve().parents[2] / "build" / "viewer-screenshots"
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.png"
    # headless Chromium renders WebGL in software, and viser says so in a toast over the scene:
    # true here, but not what a reader of the documentation sees on their machine
    page.evaluate(
        """() => { for (const toast of document.querySelectorAll('.mantine-Notification-root'))
            if (toast.textContent.includes('Software WebGL rendering')) toast.remove(); }"""
    )
    page.screenshot(path=str(path))
    return path


def domain_id(_offset: int = 0) -> str:
    """A Zenoh domain of its own per test (see tests.conftest.unique_domain)."""
    return unique_domain()


def start_launch_viewer(
    *argv: str, domain: str, env: dict[str, str]
) -> tuple[subprocess.Popen[str], str, list[str]]:
    """``robomodel launch ARGV`` serving its viewer on a free port: the process, the viewer's
    URL and its output lines so far (drained in a thread: a full pipe would block it)."""
    import threading

    launch = subprocess.Popen(
        [*ROBOMODEL, "launch", *argv, "--domain-id", domain, "--port", "0", "--no-browser"],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env,
    )  # fmt: skip
    lines: list[str] = []
    started = threading.Event()

    def drain() -> None:
        assert launch.stderr is not None
        for line in launch.stderr:
            lines.append(line)
            if "viewer: serving" in line:
                started.set()
        started.set()

    threading.Thread(target=drain, daemon=True).start()
    started.wait(scaled(60))
    url = next((x.rsplit(" ", 1)[1].strip() for x in lines if "viewer: serving" in x), None)
    if not url:
        launch.terminate()
        launch.wait(scaled(30))
        raise AssertionError(f"robomodel launch did not start its viewer: {''.join(lines)}")
    return launch, url, lines
