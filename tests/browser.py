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
