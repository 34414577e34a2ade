"""Browser fixtures: the dashboard served as a user serves it, headless Debian Chromium.

Import the fixtures into a test module (``from tests.browser import ...``).
The tests skip only outside CI (``CI`` unset) when /usr/bin/chromium is
missing; in CI they run (and fail without Chromium). Every request that does
not go to this machine is aborted: the page must need no network.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
]
ROOT = Path(__file__).resolve().parent.parent
LOAD_TIMEOUT = 40_000  # [ms] first page of a fresh server: imports and the first computation
UPDATE_TIMEOUT = 20_000  # [ms]
LOCAL = ("http://localhost", "ws://localhost", "file:", "data:", "blob:")

# Counts canvases of drawn Bokeh plots, through the shadow roots.
CANVAS_COUNT_JS = """() => { let n = 0; const walk = (root) => { for (const el of root.querySelectorAll('*')) {
  if (el.tagName === 'CANVAS' && el.width > 50 && el.height > 50) n++; if (el.shadowRoot) walk(el.shadowRoot); } };
  walk(document); return n; }"""


def require_chromium() -> None:
    if not CHROMIUM.exists():
        if os.environ.get("CI"):
            pytest.fail(f"CI is set but {CHROMIUM} is missing: .ci/run installs it with apt-get install chromium")
        pytest.skip(f"browser tests need Debian's chromium at {CHROMIUM} (apt-get install chromium); not in CI, so skipped")


@pytest.fixture(scope="session")
def browser():
    require_chromium()
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        yield chromium
        chromium.close()


def offline(page, log: list) -> None:
    """Abort every request that leaves this machine, and record it in ``log``."""

    def route(r):
        if r.request.url.startswith(LOCAL):
            r.continue_()
        else:
            log.append(f"blocked request: {r.request.url}")
            r.abort()

    page.route("**/*", route)


@pytest.fixture(scope="session")
def dashboard_url():
    """``panel serve dashboard/app.py --port 0`` in a subprocess; its URL."""
    require_chromium()
    command = [sys.executable, "-m", "panel", "serve", str(ROOT / "dashboard" / "app.py"), "--port", "0"]
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    url = None
    deadline = time.monotonic() + 60
    lines = []
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        if not line:
            break
        lines.append(line)
        match = re.search(r"Bokeh app running at: (http://localhost:\d+/app)", line)
        if match:
            url = match.group(1)
            break
    if url is None:
        process.kill()
        pytest.fail("panel serve did not start:\n" + "".join(lines))
    # Keep draining the log so the server never blocks on a full pipe.
    import threading

    threading.Thread(target=lambda: [None for _ in process.stdout], daemon=True).start()
    yield url
    process.terminate()
    try:
        process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()


@pytest.fixture
def dashboard(browser, dashboard_url):
    """A fresh session of the dashboard, loaded; ``page.errors`` lists console
    errors, page errors and blocked requests."""
    context = browser.new_context(viewport={"width": 1500, "height": 1100}, accept_downloads=True)
    page = context.new_page()
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"page error: {e}"))
    offline(page, errors)
    page.goto(dashboard_url)
    page.locator(".fe-recommended").wait_for(timeout=LOAD_TIMEOUT)
    page.errors = errors
    yield page
    context.close()


# Every drawn Bokeh figure of the page, measured: what does not fit, as sentences (an empty list: all fits). A title
# (in its own font, measured on a canvas) must end inside the plot; an axis label be no longer than the frame's side
# it labels; a legend lie inside the plot and outside the frame (over the frame it hides data). Returns
# {checked: [titles], problems: [...]}.
PLOT_FIT_JS = """() => {
  const ctx = document.createElement('canvas').getContext('2d');
  const measure = (text, style, size, font) => { ctx.font = `${style} ${size} ${font}`; return ctx.measureText(text).width; };
  const checked = [], problems = [];
  for (const view of window.Bokeh.index.query(v => v.model.type === 'Figure')) {
    if (!view.el.isConnected || view.bbox.width === 0 || view.el.getClientRects().length === 0) continue;
    const width = view.bbox.width, height = view.bbox.height, frame = view.frame.bbox;
    const name = view.model.title?.text ?? '';
    checked.push(name);
    for (const child of view.children()) {
      const m = child.model, box = child.bbox;
      if (m.type === 'Title' && m.text) {
        const needed = measure(m.text, m.text_font_style, m.text_font_size, m.text_font);
        if (box.left + needed > width + 1) problems.push(`${name}: its title needs ${Math.round(needed)} px from ${Math.round(box.left)}, the plot is ${width} px wide`);
      } else if (m.type === 'Legend' && box && box.width > 0) {
        if (box.left < -1 || box.top < -1 || box.right > width + 1 || box.bottom > height + 1)
          problems.push(`${name}: its legend (${Math.round(box.left)}..${Math.round(box.right)} x ${Math.round(box.top)}..${Math.round(box.bottom)}) leaves the ${width} x ${height} plot`);
        if (!(box.right <= frame.left || box.left >= frame.right || box.bottom <= frame.top || box.top >= frame.bottom))
          problems.push(`${name}: its legend lies over the frame`);
      } else if (m.axis_label && typeof m.axis_label === 'string') {
        const needed = measure(m.axis_label, m.axis_label_text_font_style, m.axis_label_text_font_size, m.axis_label_text_font);
        const side = box.width > box.height ? frame.width : frame.height;
        if (needed > side + 1) problems.push(`${name}: axis label '${m.axis_label}' needs ${Math.round(needed)} px beside a ${Math.round(side)} px side`);
      }
    }
  }
  return {checked, problems};
}"""
