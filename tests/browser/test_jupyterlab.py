"""Real-browser test: every notebook runs in JupyterLab, in headless Chromium, without errors.

Skipped unless ``LBO_BROWSER_TESTS=1`` (it takes minutes and needs a browser). It installs
nothing: it needs Debian's ``chromium`` package (``apt-get install chromium``; another binary can be
named with ``LBO_CHROMIUM=/path``) and the ``playwright`` Python package, used only as a driver
(never run ``playwright install``: the test launches the system browser through
``executable_path``). Run it with::

    LBO_BROWSER_TESTS=1 .venv/bin/python -m pytest -p no:dash tests/browser -v

What happens: the ``notebooks/`` folder is copied to a temporary directory (so the repository's
notebooks are never saved with outputs; the rest of the repository is linked beside it, so that
relative paths such as ``../benchmarks/...`` resolve), JupyterLab is started on 127.0.0.1 on a free port with a
random token, and for each notebook a fresh browser page opens it, runs *Run > Run All Cells* from
the menu bar, waits until every cell has run and the kernel is idle, and checks that

- no output shows a traceback or a widget that failed to render;
- every plotly figure renders (a ``.js-plotly-plot`` with a WebGL canvas of non-zero size, no
  "WebGL is not supported" message), and notebooks that draw 3D figures show at least one;
- every notebook that builds a slider shows ipywidgets (``.jupyter-widgets``, ``.widget-slider``);
- pressing the arrow keys on the first slider's handle changes the plotly data of its figure and the
  picture itself (screenshots before and after differ);
- the "Build Recommended" dialog never appears (``make.sh`` / ``binder/postBuild`` write a
  ``page_config.json`` that switches the build check off);
- figures are laid out as drawn: subplot titles and colour bars do not overlap each other or
  another panel's scene, and no 3D scene is clipped (the border of every scene is background);
- every 3D shape fills its panel: the drawn (non-background) pixels of each scene span at least
  half of the scene's width or height;
- built-in shapes are upright: every scene whose shape stands on the plane z = 0 (the creatures,
  in every pose) has the camera's up vector along +z and an eye less than 45 degrees above the
  horizon (a side view, not a view from above);
- verification cells are out of the reader's way: every code cell tagged ``hide-input``, and every
  cell that only verifies claims (``scripts/tag_verification_cells.py`` decides which), shows its
  input collapsed (a placeholder bar, no editor);
- the browser console shows no error outside the short allow-list ``CONSOLE_ALLOWED`` below.

The browser has no network: every request to a host other than 127.0.0.1 is aborted (and fails
the test), and the browser's own resolver maps every other name to nowhere.

``test_lab_opens_on_start_here``: JupyterLab started as ``./make.sh lab`` starts it (its
``--LabApp.default_url`` is read from ``make.sh``, and every server here gets ``make.sh``'s
``LAB_OPTIONS``) opens ``00_start_here.ipynb``, not the Launcher, and its kernel starts without
the "running over TCP without encryption" warning (the server provisions CurveZMQ keys).

``test_static_site`` builds the site (``scripts/build_site.py``: Sphinx, myst-nb, numpydoc) for
``SITE_NOTEBOOKS``, a test page ``MANY_SCENES`` with more 3D scenes than Chromium keeps WebGL contexts
for (16), and the API reference (or opens an existing build named by
``LBO_BROWSER_SITE=/path/to/site``), serves it from 127.0.0.1 and checks each notebook page the
same way (each figure scrolled into view and drawn there: the site draws figures only near the
viewport, ``docs/_static/lazy_plotly.js``), plus: formulas typeset by the site's own MathJax (no
``$...$`` left as text), no request that fails, no slider title with a negative zero, no WebGL
context dropped by the browser, the first 3D figure drawn again when scrolled back to.
``test_site_figures_come_back``: a 3D figure scrolled far away is replaced by a picture of it and
comes back as the reader left it (camera, slider step, colours, animation frames).
``test_site_reference_and_search``: the reference page of ``eigenbasis`` shows its docstring (its
summary line and a Parameters section naming every parameter), and a public name typed into the
search page finds that page.

Select notebooks with pytest's ``-k``, e.g. ``-k "laplace or static_site"``.

Screenshots (the page after the run, every figure, the slider before/after) and the browser console
log go to ``artifacts/browser/<notebook>/`` (override with ``LBO_BROWSER_ARTIFACTS``), the static
site's to ``artifacts/browser/site/``.
"""

from __future__ import annotations

import functools
import http.server
import io
import json
import math
import os
import re
import secrets
import shutil
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

if os.environ.get("LBO_BROWSER_TESTS") != "1":
    pytest.skip("browser tests are opt-in: set LBO_BROWSER_TESTS=1", allow_module_level=True)

try:
    from playwright.sync_api import Page, sync_playwright
except ImportError:  # pragma: no cover - only reached when the test was asked for
    raise ImportError("LBO_BROWSER_TESTS=1 needs the playwright Python package: pip install playwright "
                      "(the package only; the test uses the system chromium, never `playwright install`)")

REPO = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((REPO / "notebooks").glob("*.ipynb"))
CHROMIUM = os.environ.get("LBO_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 # WebGL without a GPU is SwiftShader; headless Chromium 156 falls back to it on its
                 # own, newer releases only with this flag.
                 "--enable-unsafe-swiftshader",
                 # No network but this machine: other host names resolve to nowhere (requests are
                 # also aborted, and recorded, by the page's route handler).
                 "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
LOCAL_HOSTS = {"127.0.0.1"}
# Requests to anywhere else. The pattern is matched by the browser driver, so local requests are
# never paused waiting for Python (the sync API runs route handlers only inside Playwright calls).
NOT_LOCAL = re.compile(r"^(https?|wss?)://(?!127\.0\.0\.1[:/])")
# Browser-console errors that are not ours to fix, each with the reason. Everything else fails.
CONSOLE_ALLOWED = [
    # SwiftShader (WebGL without a GPU) reports slow pixel read-backs; a performance note, not a fault.
    (re.compile(r"GL Driver Message .*GPU stall due to ReadPixels"), "software WebGL performance note"),
    # MathJax 2's HTML-CSS output declares `@font-face {font-family: MathJax_Blank; src: url(about:blank)}`
    # to time web-font loading; Chromium reports the (intended) failure.
    (re.compile(r"Access to font at 'about:blank' from origin 'http://127\.0\.0\.1:\d+' has been blocked by CORS"),
     "MathJax 2's font-loading probe"),
]
# Requests that may fail, with the reason; each one also allows one console line "Failed to load
# resource: ..." (the console does not say which resource).
ALLOWED_FAILURES = [
    (re.compile(r"^about:blank$"), "MathJax 2's font-loading probe (above)"),
    # jupyter-server-mathjax ships the STIX-Web fonts only; for a few AMS symbols MathJax first
    # tries its TeX AMS font, then draws the symbol with STIX-Web (typesetting errors are checked).
    (re.compile(r"/mathjax/fonts/HTML-CSS/TeX/otf/MathJax_AMS-Regular\.otf$"), "MathJax 2 AMS font probe"),
]
RESOURCE_FAILURE = "console error: Failed to load resource:"
SITE_NOTEBOOKS = ["00_start_here", "03_laplace_beltrami"]
# A test page the default site build adds (written by _many_scenes_notebook): more 3D scenes than
# Chromium keeps WebGL contexts for (16), a mesh_slider and a figure with animation frames.
MANY_SCENES = "99_many_3d_scenes"
WEBGL_LIMIT_WARNING = "Too many active WebGL contexts"   # Chromium's console warning when it drops one
ARTIFACTS = Path(os.environ.get("LBO_BROWSER_ARTIFACTS", REPO / "artifacts" / "browser"))
RUN_TIMEOUT = float(os.environ.get("LBO_BROWSER_TIMEOUT", "900"))  # seconds for Run All Cells
VIEWPORT = {"width": 1400, "height": 1000}
MIN_FILL = 0.5        # a 3D shape spans at least this fraction of its scene's width or height
DRAWN_BELOW = 250     # grey level under which a pixel is drawn on (the background is white)
# Code that draws a 3D figure or a slider in our notebooks.
PLOT_CALLS = ("plot_mesh", "plot_meshes", "mesh_slider", "go.Figure", "FigureWidget")
SLIDER_CALLS = ("mesh_slider", "IntSlider", "FloatSlider", "SelectionSlider", "interact")
# User settings for the throw-away server: no network calls for news or update checks, and every
# cell kept in the page (JupyterLab's default windowing drops or hides off-screen cells, which
# would hide their outputs from the checks; what is rendered is the same).
SETTINGS = {"@jupyterlab/apputils-extension/notification.jupyterlab-settings":
            {"checkForUpdates": False, "fetchNews": "false"},
            "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none"}}


def _start_url() -> str:
    """The page ``./make.sh lab`` opens (its ``--LabApp.default_url``)."""
    match = re.search(r"--LabApp\.default_url=(\S+)", (REPO / "make.sh").read_text())
    assert match, ("make.sh lab must open the first notebook: pass "
                   "--LabApp.default_url=/lab/tree/notebooks/00_start_here.ipynb")
    return match.group(1)


def _lab_options() -> list[str]:
    """The options ``./make.sh`` starts every JupyterLab with (its ``LAB_OPTIONS``)."""
    match = re.search(r"^LAB_OPTIONS=\((.*)\)$", (REPO / "make.sh").read_text(), re.M)
    assert match, "make.sh must define LAB_OPTIONS=(...), the options of every JupyterLab it starts"
    return match.group(1).split()


def _load_script(name: str):
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, REPO / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _code(nb_path: Path) -> str:
    nb = json.loads(nb_path.read_text())
    return "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code")


def _reader_config(home: Path) -> str:
    """The config directory ``./make.sh lab`` and ``./make.sh student lab`` put ahead of the
    environment's (nbgrader's menus off), written by make.sh's own ``no_grader_menus`` under ``home``."""
    script = (REPO / "make.sh").read_text()
    function = re.search(r"^no_grader_menus\(\) \{\n.*?^\}\n", script, re.M | re.S)
    assert function, "make.sh must define no_grader_menus(), the readers' JupyterLab config"
    made = subprocess.run(["bash", "-c", function.group(0) + "no_grader_menus"], cwd=home, capture_output=True,
                          text=True, check=True)
    return str(home / made.stdout.strip())


class Lab:
    """A JupyterLab server on 127.0.0.1 serving ``root``; the notebooks are under ``root / prefix``
    (``notebooks/`` in a copy of the repository, as ``./make.sh lab`` serves it, or an edition's
    folder itself), and its settings, workspaces and log go to ``home``."""

    def __init__(self, root: Path, prefix: str = "", home: Path | None = None, default_url: str | None = None) -> None:
        self.root, self.prefix = root, prefix
        self.home = home if home is not None else root.parent.parent
        self.port, self.token = _free_port(), secrets.token_hex(16)
        self.url = f"http://127.0.0.1:{self.port}"
        settings = self.home / "settings"
        for name, value in SETTINGS.items():
            (settings / name).parent.mkdir(parents=True, exist_ok=True)
            (settings / name).write_text(json.dumps(value))
        self.log = open(self.home / "jupyterlab.log", "w")
        env = {**os.environ, "JUPYTER_CONFIG_PATH": _reader_config(self.home)}
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "jupyter", "lab", "--no-browser", "--ServerApp.open_browser=False",
             "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={self.port}", "--ServerApp.port_retries=0",
             f"--IdentityProvider.token={self.token}", "--allow-root", f"--ServerApp.root_dir={root}",
             f"--LabApp.user_settings_dir={settings}", f"--LabApp.workspaces_dir={self.home / 'workspaces'}",
             f"--LabApp.default_url={default_url or _start_url()}", *_lab_options()],
            stdout=self.log, stderr=subprocess.STDOUT, cwd=root, env=env)
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"JupyterLab exited: see {self.log.name}")
            try:
                self.api("GET", "/api/status")
                return
            except (urllib.error.URLError, ConnectionError):
                time.sleep(0.5)
        raise RuntimeError(f"JupyterLab did not start in 120 s: see {self.log.name}")

    def api(self, method: str, path: str) -> object:
        request = urllib.request.Request(self.url + path, method=method,
                                         headers={"Authorization": f"token {self.token}"})
        with urllib.request.urlopen(request, timeout=10) as response:
            body = response.read()
        return json.loads(body) if body else None

    def shutdown_kernels(self) -> None:
        for kernel in self.api("GET", "/api/kernels"):
            self.api("DELETE", f"/api/kernels/{kernel['id']}")

    def stop(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.log.close()


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    # The repository, as ./make.sh lab serves it: a copy of notebooks/ (JupyterLab autosaves: the
    # repository's notebooks must stay clean) next to links to the rest of the repository, so that
    # paths like "../benchmarks/x.json" and the link to ../docs/glossary.md still work.
    home = tmp_path_factory.mktemp("lab")
    mirror = home / "repo"
    mirror.mkdir()
    for entry in REPO.iterdir():
        if entry.name not in {"notebooks", ".git", "artifacts"}:
            (mirror / entry.name).symlink_to(entry)
    shutil.copytree(REPO / "notebooks", mirror / "notebooks", ignore=shutil.ignore_patterns(".ipynb_checkpoints"))
    server = Lab(mirror, prefix="notebooks/", home=home)
    yield server
    server.stop()


@pytest.fixture(scope="module")
def browser():
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} not found: apt-get install chromium (or set LBO_CHROMIUM)")
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
        yield b
        b.close()


class Offline:
    """A browser context without network (only 127.0.0.1) that records console errors and
    blocked or failed requests."""

    def __init__(self, browser) -> None:
        self.context = browser.new_context(viewport=VIEWPORT, device_scale_factor=1)
        self.console: list[str] = []
        self.errors: list[str] = []
        self.blocked: list[str] = []
        self.failed: list[str] = []
        self.context.route(NOT_LOCAL, self._block)
        self.page = self.context.new_page()
        self.page.on("console", self._console)
        self.page.on("pageerror", lambda e: self._error(f"pageerror: {e}"))
        self.allowed_failures = 0
        self.page.on("requestfailed", lambda r: self._failed(r.url, str(r.failure)))
        self.page.on("response", lambda r: self._failed(r.url, f"HTTP {r.status}") if r.status >= 400 else None)

    def _failed(self, url: str, why: str) -> None:
        if any(pattern.search(url) for pattern, _ in ALLOWED_FAILURES):
            self.allowed_failures += 1
        elif urllib.parse.urlsplit(url).hostname in LOCAL_HOSTS:
            self.failed.append(f"{url} ({why})")

    def _block(self, route) -> None:
        self.blocked.append(route.request.url)
        route.abort("internetdisconnected")

    def _console(self, message) -> None:
        self.console.append(f"{message.type}: {message.text}")
        if message.type == "error":
            self._error(f"console error: {message.text}")

    def _error(self, text: str) -> None:
        self.console.append(text)
        if not any(pattern.search(text) for pattern, _ in CONSOLE_ALLOWED):
            self.errors.append(text)

    def check(self, what: str) -> None:
        """No unexpected console error, no request left the machine."""
        assert not self.blocked, f"{what}: requests to the network (blocked): {self.blocked[:10]}"
        errors, allowance = [], self.allowed_failures
        for e in self.errors:
            if e.startswith(RESOURCE_FAILURE) and allowance > 0:
                allowance -= 1
            else:
                errors.append(e)
        assert not errors, f"{what}: browser-console errors:\n" + "\n".join(errors[:20])

    def save(self, out: Path) -> None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "console.log").write_text("\n".join(self.console + [f"blocked: {u}" for u in self.blocked]
                                                  + [f"failed: {u}" for u in self.failed]))


@pytest.fixture
def offline(browser, request):
    session = Offline(browser)
    yield session
    name = request.node.callspec.id if hasattr(request.node, "callspec") else request.node.name
    session.save(ARTIFACTS / name)
    session.context.close()


@pytest.fixture
def page(offline, lab):
    offline.page.console_log = offline.console
    yield offline.page
    lab.shutdown_kernels()


def _open(page: Page, lab: Lab, path: str) -> None:
    page.goto(f"{lab.url}/lab/tree/{lab.prefix}{path}?reset&token={lab.token}")
    page.locator(".jp-NotebookPanel .jp-Notebook").first.wait_for(state="visible", timeout=120_000)


def _kernel_ready(page: Page, lab: Lab, timeout: float) -> None:
    """Wait until the notebook's kernel has started, the page is connected to it and it is idle.

    (The toolbar's indicator already reads "idle" before a kernel exists; running cells then
    would open the "Select Kernel" dialog, so the server's view of the kernel is checked too.)
    """
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            kernels = lab.api("GET", "/api/kernels")
        except urllib.error.HTTPError:  # jupyter_server can answer 500 while a kernel is starting
            time.sleep(0.5)
            continue
        ready = any(k["connections"] > 0 and k["execution_state"] == "idle" for k in kernels)
        if ready and page.locator(
                '.jp-NotebookPanel .jp-Notebook-ExecutionIndicator[data-status="idle"]').count() > 0:
            return
        time.sleep(0.5)
    raise AssertionError(f"the notebook's kernel was not ready after {timeout:.0f} s: {lab.api('GET', '/api/kernels')}")


def _build_dialog(page: Page) -> int:
    return page.locator(".jp-Dialog", has_text="Build Recommended").count()


def _run_all(page: Page) -> None:
    """Run > Run All Cells, from the menu bar, as a reader would."""
    page.locator(".lm-MenuBar-itemLabel", has_text=re.compile(r"^Run$")).click()
    page.locator(".lm-Menu-itemLabel", has_text=re.compile(r"^Run All Cells$")).click()


def _wait_until_done(page: Page, timeout: float) -> list[str]:
    """Wait until no cell shows ``[*]`` and the kernel is idle twice in a row; return the prompts."""
    deadline = time.monotonic() + timeout
    stable = 0
    while time.monotonic() < deadline:
        prompts = page.locator(".jp-CodeCell .jp-InputArea-prompt").all_text_contents()
        busy = any("*" in p for p in prompts)
        idle = page.locator('.jp-NotebookPanel .jp-Notebook-ExecutionIndicator[data-status="idle"]').count() > 0
        dialogs = page.locator(".jp-Dialog").all_inner_texts()
        if dialogs:  # e.g. "Kernel Restarting" after the kernel died (out of memory)
            raise AssertionError(f"a dialog interrupted the run: {dialogs}")
        stable = stable + 1 if (idle and not busy and prompts) else 0
        if stable >= 3:
            return prompts
        time.sleep(1.0)
    raise AssertionError(f"Run All Cells did not finish in {timeout:.0f} s")


PLOTLY_STATE = """el => {
    const gd = el.classList.contains('js-plotly-plot') ? el : el.querySelector('.js-plotly-plot');
    if (!gd || !gd.data) return null;
    const pick = a => a ? Array.from(a).slice(0, 400) : null;
    const t = gd.data[0] || {};
    const title = gd.layout && gd.layout.title ? (gd.layout.title.text || gd.layout.title) : null;
    return JSON.stringify([pick(t.intensity), pick(t.x), pick(t.y), pick(t.z), title]);
}"""

FIGURE_INFO = """el => {
    const canvases = Array.from(el.querySelectorAll('canvas'));
    const r = el.getBoundingClientRect();
    return {
        width: r.width, height: r.height,
        canvases: canvases.length,
        glCanvas: canvases.some(c => c.width > 0 && c.height > 0),
        is3d: !!el.querySelector('.gl-container') || (el._fullLayout && !!el._fullLayout.scene),
        noWebGL: /WebGL is not supported|webgl-error|no-webgl/i.test(el.innerText) || !!el.querySelector('.no-webgl'),
    };
}"""


FIGURE_LAYOUT = """el => {
    const gd = el.classList.contains('js-plotly-plot') ? el : el.querySelector('.js-plotly-plot');
    const box = e => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
    const scenes = gd && gd._fullLayout ? Object.keys(gd._fullLayout).filter(k => /^scene\\d*$/.test(k))
        .map(k => gd._fullLayout[k]._scene).filter(s => s && s.container).map(s => box(s.container)) : [];
    // Each scene's camera, and whether its shape stands on the plane z = 0 as the built-in
    // creatures do (lowest point within 2% of the size from it, and not flat).
    const keys = gd && gd._fullLayout ? Object.keys(gd._fullLayout).filter(k => /^scene\\d*$/.test(k))
        .filter(k => gd._fullLayout[k]._scene && gd._fullLayout[k]._scene.container) : [];
    const cameras = keys.map(k => {
        const cam = gd._fullLayout[k].camera;
        const traces = (gd._fullData || []).filter(t => (t.scene || 'scene') === k && t.x && t.x.length);
        let stands = traces.length > 0;
        for (const t of traces) {
            const ext = a => { let lo = Infinity, hi = -Infinity; for (const v of a) { if (v < lo) lo = v; if (v > hi) hi = v; } return [lo, hi]; };
            const [x, y, z] = [ext(t.x), ext(t.y), ext(t.z)];
            const size = Math.max(x[1] - x[0], y[1] - y[0], z[1] - z[0]);
            stands = stands && Math.abs(z[0]) <= 0.02 * size && z[1] - z[0] > 0.02 * size;
        }
        return {up: [cam.up.x, cam.up.y, cam.up.z], eye: [cam.eye.x, cam.eye.y, cam.eye.z], standsOnZ0: stands};
    });
    return {
        scenes: scenes,
        cameras: cameras,
        titles: Array.from(el.querySelectorAll('.infolayer g.annotation')).map(box),
        colorbars: Array.from(el.querySelectorAll('.infolayer g.colorbar')).map(box),
        figure: box(el),
    };
}"""


def _figure_info(page: Page, figure, timeout: float = 60) -> dict:
    """FIGURE_INFO once a 3D figure has drawn its WebGL canvas (a FigureWidget receives its data
    from the kernel after the output appears; under load that takes a while), or at the timeout."""
    deadline = time.monotonic() + timeout
    info = figure.evaluate(FIGURE_INFO)
    while info["is3d"] and not info["glCanvas"] and time.monotonic() < deadline:
        page.wait_for_timeout(1000)
        info = figure.evaluate(FIGURE_INFO)
    return info


def _intersect(a, b, tol: float = 1.0) -> bool:
    return min(a[2], b[2]) - max(a[0], b[0]) > tol and min(a[3], b[3]) - max(a[1], b[1]) > tol


def _check_figure_layout(page: Page, figure, name: str, out: Path) -> None:
    """Titles and colour bars overlap nothing they should not; no scene is clipped.

    Clipping is read from pixels: with titles and colour bars hidden, a band along the border of
    each 3D scene must be background, i.e. the drawn surface ends inside its scene.
    """
    layout = figure.evaluate(FIGURE_LAYOUT)
    titles, bars, scenes = layout["titles"], layout["colorbars"], layout["scenes"]
    for i in range(len(titles)):
        for j in range(i + 1, len(titles)):
            assert not _intersect(titles[i], titles[j]), f"{name}: titles {i} and {j} overlap: {titles[i]} {titles[j]}"
    for i, bar in enumerate(bars):
        for j, scene in enumerate(scenes):
            assert not _intersect(bar, scene), f"{name}: colour bar {i} overlaps scene {j}: {bar} {scene}"
    if not scenes:
        return
    from PIL import Image

    figure.evaluate("el => el.querySelectorAll('.infolayer, .modebar-container').forEach(e => e.style.visibility = 'hidden')")
    try:
        png = page.screenshot(full_page=False, clip=dict(zip(("x", "y", "width", "height"), (
            layout["figure"][0], layout["figure"][1], layout["figure"][2] - layout["figure"][0],
            layout["figure"][3] - layout["figure"][1]))))
    finally:
        figure.evaluate("el => el.querySelectorAll('.infolayer, .modebar-container').forEach(e => e.style.visibility = '')")
    image = Image.open(io.BytesIO(png)).convert("L")
    (out / f"{name}_bare.png").write_bytes(png)
    x0, y0 = layout["figure"][0], layout["figure"][1]
    band = 3
    for j, (left, top, right, bottom) in enumerate(scenes):
        box = (max(round(left - x0) + 1, 0), max(round(top - y0) + 1, 0),
               min(round(right - x0) - 1, image.width), min(round(bottom - y0) - 1, image.height))
        if box[2] - box[0] <= 2 * band or box[3] - box[1] <= 2 * band:
            continue   # a scene without size (or outside the screenshot) cannot be clipped
        crop = image.crop(box)
        w, h = crop.size
        pixels = crop.load()
        edge = [pixels[x, y] for x in range(w) for y in (*range(band), *range(h - band, h))]
        edge += [pixels[x, y] for y in range(h) for x in (*range(band), *range(w - band, w))]
        drawn = sum(v < 235 for v in edge) / len(edge)
        assert drawn < 0.01, f"{name}: scene {j} is clipped ({drawn:.1%} of its border is drawn on); see {name}_bare.png"
        # The shape fills its panel: its drawn pixels span half the scene's width or height.
        fill = _drawn_extent(crop)
        assert max(fill) >= MIN_FILL, (f"{name}: the shape in scene {j} spans only {fill[0]:.0%} of its width and "
                                       f"{fill[1]:.0%} of its height (at least {MIN_FILL:.0%} of one); see {name}_bare.png")
    for j, camera in enumerate(layout["cameras"]):
        if not camera["standsOnZ0"]:
            continue
        up, eye = camera["up"], camera["eye"]
        up_z = up[2] / max(sum(u * u for u in up) ** 0.5, 1e-12)
        elevation = math.degrees(math.asin(eye[2] / max(sum(e * e for e in eye) ** 0.5, 1e-12)))
        assert up_z > 0.99, f"{name}: scene {j} shows a shape standing on z = 0 with camera up {up}: not upright"
        assert elevation < 45, f"{name}: scene {j} looks at an upright shape from {elevation:.0f} degrees above"


def _drawn_extent(crop) -> tuple[float, float]:
    """The fractions of the width and of the height of ``crop`` (greyscale) that drawn pixels span."""
    mask = crop.point(lambda v: 255 if v < DRAWN_BELOW else 0)
    box = mask.getbbox()
    if box is None:
        return 0.0, 0.0
    return (box[2] - box[0]) / crop.width, (box[3] - box[1]) / crop.height


CELL_INPUTS = """() => {
    const panel = Array.from(document.querySelectorAll('.jp-NotebookPanel')).find(p => p.offsetParent !== null);
    const shown = e => !!e && e.offsetParent !== null && e.getBoundingClientRect().height > 0;
    return panel ? Array.from(panel.querySelectorAll('.jp-Notebook .jp-Cell')).map(c => ({
        code: c.classList.contains('jp-CodeCell'),
        collapsed: shown(c.querySelector('.jp-InputPlaceholder')) && !shown(c.querySelector('.jp-InputArea-editor')),
    })) : [];
}"""


def _check_verification_cells_collapsed(page: Page, notebook: Path) -> None:
    """Every cell tagged hide-input, and every cell that only verifies claims, shows a collapsed input."""
    tagging = _load_script("tag_verification_cells")
    cells = json.loads(notebook.read_text())["cells"]
    shown = page.evaluate(CELL_INPUTS)
    assert len(shown) == len(cells), f"{notebook.name}: {len(shown)} cells on the page, {len(cells)} in the file"
    hidden = [i for i, c in enumerate(cells) if c["cell_type"] == "code"
              and (tagging.is_tagged(c) or tagging.is_verification(c))]
    open_ = [i for i in hidden if not shown[i]["collapsed"]]
    assert not open_, (f"{notebook.name}: verification cells {open_} show their code in the lesson; run "
                       f"python3 scripts/tag_verification_cells.py notebooks/{notebook.name}")


def _move_a_slider(page: Page, notebook: Path, out: Path) -> None:
    """Press arrow keys on the first slider that drives a figure; its figure must change.

    The slider sits in a widget box with a plotly figure (``mesh_slider``) or with an output
    (``interact``); the plotly data (if any) and a screenshot of the box are compared.
    """
    boxes = page.locator(".jp-OutputArea-output .jupyter-widgets.widget-vbox:has(.widget-slider):has(.js-plotly-plot)")
    if boxes.count() == 0:
        boxes = page.locator(".jp-OutputArea-output .jupyter-widgets.widget-vbox:has(.widget-slider)")
    assert boxes.count() > 0, f"{notebook.name}: no slider inside a widget box"
    box = boxes.first
    box.scroll_into_view_if_needed()
    page.wait_for_timeout(500)
    figure = box.locator(".js-plotly-plot").first if box.locator(".js-plotly-plot").count() else None
    target = figure or box
    state = (lambda: figure.evaluate(PLOTLY_STATE)) if figure else (lambda: None)
    before_state = state()
    before_png = target.screenshot(path=str(out / "slider_before.png"))
    # The last slider of the box is mesh_slider's own (extra controls come first).
    slider = box.locator(".widget-slider").last
    readout = slider.locator(".widget-readout")
    before_readout = readout.inner_text() if readout.count() else None
    handle = slider.locator(".noUi-handle").first
    for key in ("ArrowRight", "ArrowLeft"):  # ArrowLeft when the slider starts at its maximum
        handle.focus()
        for _ in range(3):
            page.keyboard.press(key)
        page.wait_for_timeout(1000)
        if readout.count() == 0 or readout.inner_text() != before_readout:
            break
    after_readout = readout.inner_text() if readout.count() else None
    assert after_readout != before_readout, f"{notebook.name}: the slider did not move ({before_readout})"
    deadline = time.monotonic() + 120  # the kernel computes the new frame
    after_state = state()
    while figure and time.monotonic() < deadline and after_state == before_state:
        page.wait_for_timeout(500)
        after_state = state()
    page.wait_for_timeout(2000)  # let WebGL / the output redraw
    after_png = target.screenshot(path=str(out / "slider_after.png"))
    if figure:
        assert after_state != before_state, f"{notebook.name}: moving the slider did not change the figure's data"
    assert after_png != before_png, f"{notebook.name}: moving the slider did not change the picture"


#: Words of the glossary's first paragraph: the page that opened is the glossary.
GLOSSARY_WORDS = "The terms the notebooks use"


def check_glossary_opens(page: Page, lab: Lab, stems: list[str], out: Path) -> None:
    """From each notebook, click the glossary link of its first cell (as a reader would): a tab
    titled glossary.md opens and shows the glossary, with no failed request (a 404 is silent in
    JupyterLab otherwise: the link just does nothing)."""
    out.mkdir(parents=True, exist_ok=True)
    for stem in stems:
        _open(page, lab, f"{stem}.ipynb")
        link = page.locator(".jp-NotebookPanel .jp-RenderedMarkdown a", has_text=re.compile(r"^glossary$")).first
        link.wait_for(state="visible", timeout=60_000)
        link.click()
        tab = page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab", has_text="glossary.md")
        tab.first.wait_for(state="visible", timeout=30_000)
        page.wait_for_function("words => document.body.innerText.includes(words)", arg=GLOSSARY_WORDS, timeout=30_000)
        current = page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab.lm-mod-current").all_inner_texts()
        assert any("glossary.md" in t for t in current), f"{stem}: the glossary link opened {current}"
        assert not page.locator(".jp-Dialog").all_inner_texts(), f"{stem}: a dialog instead of the glossary"
        page.screenshot(path=str(out / f"{stem}.png"))
        lab.shutdown_kernels()


def test_the_glossary_opens_from_every_notebook(page: Page, lab: Lab, offline: Offline) -> None:
    check_glossary_opens(page, lab, [p.stem for p in NOTEBOOKS], ARTIFACTS / "glossary")
    assert not [f for f in offline.failed if "glossary" in f], offline.failed
    offline.check("the glossary from every notebook")


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_in_jupyterlab(page: Page, lab: Lab, offline: Offline, notebook: Path) -> None:
    out = ARTIFACTS / notebook.stem
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    code = _code(notebook)

    _open(page, lab, notebook.name)
    _kernel_ready(page, lab, 180)
    _run_all(page)
    prompts = _wait_until_done(page, RUN_TIMEOUT)
    page.wait_for_timeout(2000)  # let widget views and figures finish drawing
    page.screenshot(path=str(out / "notebook.png"))

    # Every code cell ran (Run All stops at the first error and leaves the rest unnumbered).
    not_run = [i for i, p in enumerate(prompts) if not re.search(r"\[\d+\]", p)]
    errors = []
    for output in page.locator(".jp-OutputArea-output").all():
        text = output.text_content() or ""
        stderr = output.get_attribute("data-mime-type") == "application/vnd.jupyter.stderr"
        if "Traceback (most recent call last)" in text or (stderr and re.search(r"^\w*(Error|Exception)\b", text, re.M)) \
                or "Error displaying widget" in text or "Failed to load model class" in text:
            errors.append(text[:1500])
    assert not errors, f"{notebook.name}: error output in the browser:\n" + "\n---\n".join(errors)
    assert not not_run, f"{notebook.name}: code cells {not_run} did not run (prompts {prompts})"

    # 3D figures: every plotly figure drew a WebGL canvas.
    # Plotly's JupyterLab renderer makes the output itself the plot; FigureWidget nests it.
    figures = page.locator(".jp-OutputArea-output.js-plotly-plot, .jp-OutputArea-output .js-plotly-plot")
    infos = []
    for i in range(figures.count()):
        fig = figures.nth(i)
        fig.scroll_into_view_if_needed()
        page.wait_for_timeout(300)
        info = _figure_info(page, fig)
        infos.append(info)
        fig.screenshot(path=str(out / f"figure_{i:02d}.png"))
        if info["is3d"]:
            _check_figure_layout(page, fig, f"figure_{i:02d}", out)
        assert not info["noWebGL"], f"{notebook.name}: figure {i} says WebGL is not supported"
        assert info["width"] > 100 and info["height"] > 100, f"{notebook.name}: figure {i} has no size: {info}"
        if info["is3d"]:
            assert info["glCanvas"], f"{notebook.name}: 3D figure {i} has no WebGL canvas: {info}"
    if any(call in code for call in PLOT_CALLS):
        assert any(i["is3d"] for i in infos), f"{notebook.name} draws 3D figures but none rendered: {infos}"

    # Matplotlib images decoded.
    broken = page.locator(".jp-RenderedImage img").evaluate_all("imgs => imgs.filter(i => !(i.naturalWidth > 0)).length")
    assert broken == 0, f"{notebook.name}: {broken} images did not load"

    # Widgets, and one slider that changes what it drives.
    if any(call in code for call in SLIDER_CALLS):
        assert page.locator(".jp-OutputArea-output .jupyter-widgets").count() > 0, f"{notebook.name}: no widget rendered"
        assert page.locator(".jp-OutputArea-output .widget-slider").count() > 0, f"{notebook.name}: no slider rendered"
        _move_a_slider(page, notebook, out)

    _check_verification_cells_collapsed(page, notebook)
    assert _build_dialog(page) == 0, f"{notebook.name}: the 'Build Recommended' dialog appeared"
    dialogs = page.locator(".jp-Dialog").all_inner_texts()
    assert not dialogs, f"{notebook.name}: unexpected dialog(s): {dialogs}"
    offline.check(notebook.name)


def test_no_build_recommended_dialog(page: Page, lab: Lab, offline: Offline) -> None:
    """JupyterLab must not ask to rebuild (dash's extension triggers it unless page_config.json says no)."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    page.goto(f"{lab.url}/lab?reset&token={lab.token}")
    page.locator(".jp-LauncherCard, .jp-Launcher").first.wait_for(state="visible", timeout=120_000)
    page.wait_for_timeout(8000)  # the build check runs a few seconds after start-up
    page.screenshot(path=str(ARTIFACTS / "lab_start.png"))
    assert _build_dialog(page) == 0, (
        "JupyterLab shows 'Build Recommended': write {\"buildCheck\": false, \"buildAvailable\": false} to "
        "<sys.prefix>/etc/jupyter/labconfig/page_config.json (./make.sh install does this)")
    offline.check("JupyterLab start page")


def test_lab_opens_on_start_here(page: Page, lab: Lab, offline: Offline) -> None:
    """The page JupyterLab opens (and the link it prints) is the first notebook, not the Launcher."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    # A first start: no saved workspace (JupyterLab otherwise reopens what the last session showed).
    workspaces = lab.home / "workspaces"
    shutil.rmtree(workspaces, ignore_errors=True)
    workspaces.mkdir()
    page.goto(f"{lab.url}/?token={lab.token}")
    page.locator(".jp-NotebookPanel .jp-Notebook").first.wait_for(state="visible", timeout=120_000)
    page.wait_for_timeout(3000)
    page.screenshot(path=str(ARTIFACTS / "lab_opens.png"))
    assert urllib.parse.urlsplit(page.url).path == "/lab/tree/notebooks/00_start_here.ipynb", page.url
    current = page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab.lm-mod-current").all_inner_texts()
    assert any("00_start_here.ipynb" in t for t in current), f"the open tab is {current}, not 00_start_here.ipynb"
    launchers = page.locator(".jp-Launcher").evaluate_all("els => els.filter(e => e.offsetParent !== null).length")
    assert launchers == 0, "the Launcher is shown beside the first notebook"
    # Issue 43: a reader's lab has no grader menus (nbgrader is installed with the test extras).
    menus = page.locator(".lm-MenuBar-itemLabel").all_inner_texts()
    assert "Nbgrader" not in menus, f"nbgrader's menu is in the reader's JupyterLab: {menus}"
    assert page.locator(".jp-NotebookPanel-toolbar").get_by_text("Validate", exact=True).count() == 0, (
        "nbgrader's Validate button is in the reader's JupyterLab")
    offline.check("JupyterLab start page (00_start_here)")
    # The notebook's kernel has started: nothing in the server's output a newcomer reads as trouble.
    _kernel_ready(page, lab, 120)
    log = Path(lab.log.name).read_text()
    assert "without encryption" not in log, "a kernel runs over unencrypted TCP: see LAB_OPTIONS in make.sh"


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args) -> None:
        pass


def _many_scenes_notebook(path: Path) -> Path:
    """A notebook for the site test: 8 figures of 3 scenes each, a mesh_slider and a figure whose
    slider steps through animation frames, 26 scenes in all (Chromium keeps 16 WebGL contexts)."""
    import nbformat

    cells = [
        nbformat.v4.new_markdown_cell("# Many 3D scenes on one page\n\nA test page with more 3D scenes than a "
                                      "browser keeps WebGL contexts for: every one must render, $n > 16$."),
        nbformat.v4.new_code_cell(
            "import numpy as np\nimport plotly.graph_objects as go\nfrom lbo_notebooks import shapes\n"
            "from lbo_notebooks.plotting import mesh_slider, plot_mesh, plot_meshes\n\n"
            "sphere = shapes.icosphere(2)\nx, y, z = sphere.vertices.T"),
        nbformat.v4.new_code_cell(
            "mesh_slider(sphere, lambda k: np.cos(k) * x + np.sin(k) * y, range(6), 'k', height=400)"),
        nbformat.v4.new_code_cell(
            "animated = plot_mesh(sphere, x, title='frames', height=400)\n"
            "animated.frames = [go.Frame(name=str(k), data=[go.Mesh3d(intensity=np.cos(k) * x + np.sin(k) * z)]) "
            "for k in range(4)]\n"
            "animated.update_layout(sliders=[dict(active=0, steps=[dict(method='animate', label=str(k), args=[[str(k)], "
            "dict(mode='immediate', frame=dict(duration=0, redraw=True), transition=dict(duration=0))]) "
            "for k in range(4)])])\nanimated"),
    ]
    for i in range(8):
        cells.append(nbformat.v4.new_code_cell(
            f"plot_meshes([sphere] * 3, [x, y, z], titles=['x ({i})', 'y ({i})', 'z ({i})'], height=300)"))
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, path)
    return path


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site, built for SITE_NOTEBOOKS with the reference (or LBO_BROWSER_SITE), served from 127.0.0.1."""
    root = Path(os.environ["LBO_BROWSER_SITE"]) if os.environ.get("LBO_BROWSER_SITE") else None
    if root is None:
        root = tmp_path_factory.mktemp("site") / "site"
        notebooks = [str(REPO / "notebooks" / f"{stem}.ipynb") for stem in SITE_NOTEBOOKS]
        notebooks.append(str(_many_scenes_notebook(root.parent / "extra" / f"{MANY_SCENES}.ipynb")))
        build = subprocess.run([sys.executable, str(REPO / "scripts" / "build_site.py"), "--out", str(root), *notebooks],
                               capture_output=True, text=True, timeout=1800)
        (ARTIFACTS / "site").mkdir(parents=True, exist_ok=True)
        (ARTIFACTS / "site" / "build.log").write_text(build.stdout + build.stderr)
        assert build.returncode == 0, f"build_site.py failed:\n{build.stdout}\n{build.stderr}"
        # The build's own output is for people: no warnings a reader cannot act on.
        assert "without encryption" not in build.stderr, build.stderr
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_QuietHandler, directory=str(root)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield root, f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


MATH_STATE = """() => ({
    typeset: document.querySelectorAll('.MathJax, .MathJax_CHTML, .MathJax_Display, mjx-container').length,
    failed: document.querySelectorAll('.noError, .MathJax_Error, .MathJax .merror').length,
    raw: Array.from(document.querySelectorAll('.jp-MarkdownOutput, .desc, p, li, td'))
        .map(e => e.innerText).filter(t => /\\$[^$\\s][^$]*\\$/.test(t)).slice(0, 5),
    mathjax: window.MathJax && window.MathJax.Hub ? window.MathJax.version : null,
    scripts: Array.from(document.scripts).map(s => s.src).filter(s => s),
})"""


def _wait_for_math(page: Page) -> dict:
    page.wait_for_function("() => window.MathJax && window.MathJax.Hub && MathJax.Hub.queue.pending === 0 "
                           "&& !MathJax.Hub.queue.running", timeout=60_000)
    page.wait_for_timeout(500)
    return page.evaluate(MATH_STATE)


# A site figure has been drawn: plotly's frame is there, with a WebGL canvas per 3D scene.
DRAWN = """el => !!el._fullLayout && !!el.querySelector('.plot-container')
    && el.querySelectorAll('canvas').length >= Object.keys(el._fullLayout).filter(k => /^scene\\d*$/.test(k)).length"""


def _wait_until_drawn(page: Page, figure, what: str, timeout: float = 60) -> None:
    """Wait until a site figure (on screen) has been drawn: plotly's frame, a canvas per 3D scene."""
    try:
        page.wait_for_function(DRAWN, arg=figure.element_handle(), timeout=timeout * 1000)
    except Exception as exc:   # playwright's TimeoutError
        raise AssertionError(f"{what}: not drawn {timeout:.0f} s after it scrolled into view") from exc


def test_static_site(browser, site, offline: Offline) -> None:
    root, url = site
    out = ARTIFACTS / "site"
    out.mkdir(parents=True, exist_ok=True)
    page = offline.page
    page.goto(f"{url}/index.html", timeout=180_000)
    math = _wait_for_math(page)
    page.screenshot(path=str(out / "index.png"), full_page=True)
    assert math["mathjax"], "the index did not load MathJax"
    assert all(s.startswith(url) for s in math["scripts"]), f"scripts from elsewhere: {math['scripts']}"
    assert math["typeset"] > 0 and not math["raw"], f"index: formulas left as LaTeX: {math}"
    assert "W),p" not in page.inner_text("body")
    pages = sorted(p.relative_to(root).as_posix() for p in (root / "notebooks").glob("*.html") if p.name != "index.html")
    assert pages, f"no notebook pages in {root / 'notebooks'}"
    linked = page.locator("article a[href^='notebooks/']").evaluate_all("els => els.map(e => e.getAttribute('href'))")
    assert set(pages) <= set(linked), f"the index does not link every notebook page: {pages} vs {linked}"
    for name in pages:
        page.goto(f"{url}/{name}", timeout=180_000)
        math = _wait_for_math(page)
        stem = Path(name).stem
        page.screenshot(path=str(out / f"{stem}.png"), full_page=True)
        assert math["typeset"] > 0 and not math["raw"] and not math["failed"], f"{name}: formulas left as LaTeX: {math}"
        assert all(s.startswith(url) for s in math["scripts"]), f"{name}: scripts from elsewhere: {math['scripts']}"
        # Every plotly figure (drawn only once near the viewport: docs/_static/lazy_plotly.js).
        figures = page.locator(".plotly-graph-div")
        # Every page shows a figure: interactive plotly, or a static one (matplotlib's PNG, e.g. the warm-up's).
        images = page.locator("article .cell_output img")
        assert figures.count() + images.count() > 0, f"{name}: no figure"
        for i in range(images.count()):
            size = images.nth(i).evaluate("el => [el.naturalWidth, el.naturalHeight]")
            assert min(size) > 50, f"{name}: image {i} did not load ({size})"
        drawn_3d = []
        for i in range(figures.count()):
            fig = figures.nth(i)
            fig.scroll_into_view_if_needed()
            _wait_until_drawn(page, fig, f"{name}: figure {i}")
            page.wait_for_timeout(300)
            info = _figure_info(page, fig)
            assert info["width"] > 100 and info["height"] > 100 and not info["noWebGL"], f"{name}: figure {i}: {info}"
            if info["is3d"]:
                drawn_3d.append(i)
                assert info["glCanvas"], f"{name}: 3D figure {i} has no WebGL canvas: {info}"
                fig.screenshot(path=str(out / f"{stem}_figure_{i:02d}.png"))
                _check_figure_layout(page, fig, f"{stem}_figure_{i:02d}", out)
            titles = fig.evaluate("el => [el.layout && el.layout.title ? (el.layout.title.text || '') : '']"
                                  ".concat((el.layout && el.layout.sliders || []).flatMap(s => s.steps.map("
                                  "st => JSON.stringify(st.args[1] || {}))))")
            assert not any(re.search(r"(?<![\w.])-0\.0*(?!\d)", t) for t in titles), f"{name}: negative zero in {titles}"
        # Scrolling back, the first 3D figure is drawn again (it was released if far enough).
        if drawn_3d:
            first_3d = figures.nth(drawn_3d[0])
            first_3d.scroll_into_view_if_needed()
            _wait_until_drawn(page, first_3d, f"{name}: first 3D figure, scrolled back to")
            _check_figure_layout(page, first_3d, f"{stem}_figure_first_again", out)
        dropped = [line for line in offline.console if WEBGL_LIMIT_WARNING in line]
        assert not dropped, f"{name}: the browser dropped WebGL contexts (some scenes went blank): {dropped[:3]}"
        offline.check(name)
    local_failures = [f for f in offline.failed if f.startswith(url)]
    assert not local_failures, f"requests to the site that failed: {local_failures[:10]}"


def test_site_reference_and_search(browser, site, offline: Offline) -> None:
    """The API reference renders a docstring (numpydoc sections), and Sphinx's search finds a public name."""
    import inspect

    import lbo_notebooks

    root, url = site
    out = ARTIFACTS / "site"
    out.mkdir(parents=True, exist_ok=True)
    page = offline.page
    page.goto(f"{url}/reference.html", timeout=60_000)
    listed = page.locator("article table a code, article table a span").all_inner_texts()
    missing = [n for n in lbo_notebooks.__all__ if n not in listed]
    assert not missing, f"the reference page does not list {missing}"
    page.get_by_role("link", name="eigenbasis", exact=True).first.click()
    page.wait_for_load_state("load")
    assert urllib.parse.urlsplit(page.url).path == "/generated/lbo_notebooks.eigenbasis.html", page.url
    page.screenshot(path=str(out / "reference_eigenbasis.png"), full_page=True)
    body = page.locator("article dl.py.function")
    summary = inspect.getdoc(lbo_notebooks.eigenbasis).splitlines()[0]
    assert body.locator("dd > p").first.inner_text().split() == re.sub(r"``?", "", summary).split()
    fields = body.locator("dl.field-list").first
    assert fields.locator("dt").first.inner_text().strip().rstrip(":") == "Parameters"
    documented = fields.locator("dd dl dt strong").all_inner_texts()
    assert documented == list(inspect.signature(lbo_notebooks.eigenbasis).parameters), documented
    offline.check("reference page of eigenbasis")

    # Type a public name into the search page (no search.html?q= shortcut): the results link its page.
    page.goto(f"{url}/search.html", timeout=60_000)
    box = page.locator(".bd-search-container form.bd-search input[type=search]")
    box.fill("farthest_point_sampling")
    box.press("Enter")
    hit = page.locator("#search-results ul.search li a", has_text="farthest_point_sampling").first
    hit.wait_for(state="visible", timeout=60_000)
    page.screenshot(path=str(out / "search.png"), full_page=True)
    assert hit.get_attribute("href").startswith("generated/lbo_notebooks.farthest_point_sampling.html")
    hit.click()
    page.wait_for_load_state("load")
    assert "farthest_point_sampling" in page.locator("article h1").inner_text()
    offline.check("search page")


# What a reader sees of a drawn site figure: each scene's camera, each slider's step, the colours of
# the first trace and the number of animation frames.
READER_STATE = """el => ({
    cameras: Object.keys(el._fullLayout).filter(k => /^scene\\d*$/.test(k))
        .map(k => JSON.stringify(el._fullLayout[k].camera)),
    sliders: (el._fullLayout.sliders || []).map(s => s.active),
    colours: JSON.stringify(Array.from(el._fullData[0].intensity || []).slice(0, 300)),
    frames: el._transitionData && el._transitionData._frames ? el._transitionData._frames.length : 0,
})"""
# The picture lazy_plotly.js leaves in place of a released figure: for each of its scene pictures,
# the fraction of pixels drawn on (not background).
STAND_IN = """el => {
    const standIn = el.parentNode.querySelector('.lbo-plot-standin');
    if (!standIn || el.querySelector('canvas')) return null;
    return Array.from(standIn.querySelectorAll('img')).map(img => {
        const c = document.createElement('canvas');
        c.width = img.naturalWidth; c.height = img.naturalHeight;
        if (!c.width || !c.height) return 0;
        const g = c.getContext('2d');
        g.drawImage(img, 0, 0);
        const px = g.getImageData(0, 0, c.width, c.height).data;
        let drawn = 0;
        for (let i = 0; i < px.length; i += 4) if (px[i + 3] > 0 && Math.min(px[i], px[i + 1], px[i + 2]) < 235) drawn++;
        return drawn / (px.length / 4);
    });
}"""


def _click_step(page: Page, figure, last: bool = True) -> None:
    """Click an end of the figure's (first) slider rail, as a reader would: its last or first step."""
    box = figure.locator(".slider-rail-touch-rect").first.bounding_box()
    page.mouse.click(box["x"] + (box["width"] - 3 if last else 3), box["y"] + box["height"] / 2)
    page.wait_for_timeout(1000)


def _away_and_back(page: Page, figure, what: str) -> list[float]:
    """Scroll far from the figure until it is released, then back until it is drawn again.

    Returns the drawn fractions of its stand-in's scene pictures, read while it was away.
    """
    page.mouse.move(2, 2)   # no hover label or mode bar in the pictures
    far = figure.evaluate("el => el.getBoundingClientRect().top + window.scrollY > document.body.scrollHeight / 2 ? 0 "
                          ": document.body.scrollHeight")
    page.evaluate(f"window.scrollTo(0, {far})")
    try:
        page.wait_for_function(f"el => ({STAND_IN})(el) !== null", arg=figure.element_handle(), timeout=30_000)
    except Exception as exc:
        raise AssertionError(f"{what}: not released when scrolled far away (a picture in its place)") from exc
    pictures = figure.evaluate(STAND_IN)
    figure.scroll_into_view_if_needed()
    _wait_until_drawn(page, figure, f"{what}, scrolled back to")
    page.mouse.move(2, 2)
    page.wait_for_timeout(500)
    return pictures


def test_site_figures_come_back(browser, site, offline: Offline) -> None:
    """A 3D figure far from view is released (docs/_static/lazy_plotly.js) and drawn again when the
    reader comes back, as the reader left it: the camera they chose, the slider's step and the
    colours it set; a figure with animation frames keeps them. Meanwhile a picture of the figure
    stands in its place, and the browser never drops a WebGL context.

    On the test page MANY_SCENES (default build), or on the notebook page with the most figures
    among those with a slider (a build given by LBO_BROWSER_SITE).
    """
    from PIL import Image, ImageChops, ImageStat

    root, url = site
    out = ARTIFACTS / "site"
    out.mkdir(parents=True, exist_ok=True)
    candidates = [p for p in (root / "notebooks").glob("*.html") if p.name != "index.html"]
    chosen = root / "notebooks" / f"{MANY_SCENES}.html"
    if not chosen.exists():
        with_sliders = [p for p in candidates if '"sliders"' in p.read_text()]
        assert with_sliders, "no notebook page has a figure with a slider"
        chosen = max(with_sliders, key=lambda p: p.read_text().count('class="plotly-graph-div"'))
    name, page = chosen.stem, offline.page
    page.goto(f"{url}/notebooks/{chosen.name}", timeout=180_000)
    _wait_for_math(page)
    figures = page.locator(".plotly-graph-div")
    slider_figure = frames_figure = None
    scenes = 0
    for i in range(figures.count()):
        fig = figures.nth(i)
        fig.scroll_into_view_if_needed()
        _wait_until_drawn(page, fig, f"{name}: figure {i}")
        state = fig.evaluate(READER_STATE)
        scenes += len(state["cameras"])
        if state["cameras"] and state["sliders"]:
            if state["frames"] and frames_figure is None:
                frames_figure = i
            elif not state["frames"] and slider_figure is None:
                slider_figure = i
    assert slider_figure is not None, f"{name}: no 3D figure with a slider"
    if chosen.stem == MANY_SCENES:
        assert scenes > 16 and frames_figure is not None, f"{name}: {scenes} scenes, frames figure {frames_figure}"

    # The reader moves the slider to its last step and turns the first scene (a horizontal drag).
    fig = figures.nth(slider_figure)
    fig.scroll_into_view_if_needed()
    _wait_until_drawn(page, fig, f"{name}: slider figure")
    start = fig.evaluate(READER_STATE)
    _click_step(page, fig)
    scene = fig.evaluate(FIGURE_LAYOUT)["scenes"][0]
    x, y = (scene[0] + scene[2]) / 2, (scene[1] + scene[3]) / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 120, y, steps=8)   # turntable: about the vertical, the view stays upright
    page.mouse.up()
    page.mouse.move(2, 2)
    page.wait_for_timeout(1000)
    left = fig.evaluate(READER_STATE)
    assert left["sliders"] != start["sliders"] and left["colours"] != start["colours"], f"{name}: the slider did not move"
    assert left["cameras"][0] != start["cameras"][0], f"{name}: dragging did not turn the scene"
    before = Image.open(io.BytesIO(fig.screenshot())).convert("L")
    before.save(out / f"{name}_slider_figure_before_leaving.png")

    pictures = _away_and_back(page, fig, f"{name}: slider figure")
    assert pictures and min(pictures) > 0.01, f"{name}: the picture standing in for the figure is blank: {pictures}"
    back = fig.evaluate(READER_STATE)
    assert back == left, f"{name}: the figure came back changed:\n{left}\n{back}"
    after = Image.open(io.BytesIO(fig.screenshot())).convert("L")
    after.save(out / f"{name}_slider_figure_back.png")
    difference = ImageStat.Stat(ImageChops.difference(before, after)).mean[0] if before.size == after.size else 255
    assert difference < 2, f"{name}: the figure looks different after coming back (mean grey difference {difference:.1f})"
    _check_figure_layout(page, fig, f"{name}_slider_figure_back", out)

    if frames_figure is not None:
        fig = figures.nth(frames_figure)
        fig.scroll_into_view_if_needed()
        _wait_until_drawn(page, fig, f"{name}: frames figure")
        start = fig.evaluate(READER_STATE)
        _away_and_back(page, fig, f"{name}: frames figure")
        assert fig.evaluate(READER_STATE) == start, f"{name}: the frames figure came back changed"
        _click_step(page, fig, last=start["sliders"][0] == 0)   # its animation frames still play
        moved = fig.evaluate(READER_STATE)
        assert moved["colours"] != start["colours"] and moved["sliders"] != start["sliders"], (
            f"{name}: the frames figure's slider does nothing after coming back")

    dropped = [line for line in offline.console if WEBGL_LIMIT_WARNING in line]
    assert not dropped, f"{name}: the browser dropped WebGL contexts: {dropped[:3]}"
    offline.check(f"{name} (figures released and drawn again)")
