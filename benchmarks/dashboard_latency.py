"""Dashboard latency in a real browser: slider change -> new F_e on screen.

Serves ``dashboard/app.py`` with ``panel serve`` on a free port, opens it in
headless Debian Chromium (/usr/bin/chromium) and, presses an arrow key on
the T2 slider (alternately right and left, so T2 stays near 0.4 s) and
polls, every animation frame, until the recommended F_e shown differs from
the value before; the time runs from the page's clock just before the key
press to two animation frames after the new text. Reports the median of 10
in one session, each change from a settled page and back to back, then
with 5 sessions changing sliders at once (each in its own Chromium on this
same machine: on 2 cores the browsers' rendering competes with the server).

    python3 benchmarks/dashboard_latency.py
"""

from __future__ import annotations

import re
import statistics
import subprocess
import sys
import threading
from pathlib import Path

from playwright.sync_api import sync_playwright

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from tests.browser import CHROMIUM, CHROMIUM_ARGS  # noqa: E402

def serve():
    process = subprocess.Popen(
        [sys.executable, "-m", "panel", "serve", str(ROOT / "dashboard" / "app.py"), "--port", "0"],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )
    for line in process.stdout:
        match = re.search(r"(http://localhost:\d+/app)", line)
        if match:
            threading.Thread(target=lambda: [None for _ in process.stdout], daemon=True).start()
            return process, match.group(1)
    raise RuntimeError("panel serve did not start")


def open_session(browser, url):
    page = browser.new_page(viewport={"width": 1500, "height": 1100})
    page.route("**/*", lambda r: r.continue_() if r.request.url.startswith(("http://localhost", "ws://localhost")) else r.abort())
    page.goto(url)
    page.locator(".fe-recommended").wait_for(timeout=60_000)
    handle = page.locator(".bk-input-group", has=page.get_by_text("period T2", exact=False)).locator(".noUi-handle").first
    handle.focus()
    return page, handle


FE_CHANGED = """([before]) => {
    // The result card sits in a pane's shadow root, found once and kept: a
    // search of the whole page on every animation frame would load the
    // browser being measured.
    const find = (root) => {
        if (root.querySelector('.fe-recommended')) return root;
        for (const e of root.querySelectorAll('*')) { if (e.shadowRoot) { const f = find(e.shadowRoot); if (f) return f; } }
        return null;
    };
    let el = window.__feRoot && window.__feRoot.querySelector('.fe-recommended');
    if (!el) { window.__feRoot = find(document); el = window.__feRoot && window.__feRoot.querySelector('.fe-recommended'); }
    return el && el.textContent.trim() !== before;
}"""


def measure(page, handle, n: int, settle_ms: int = 0) -> list[float]:
    """Latencies of ``n`` changes [ms]; ``settle_ms`` is a pause before each
    change, so that the previous change's plots have been drawn (a user who
    reads the number before moving the slider again)."""
    times = []
    for i in range(n):
        if settle_ms:
            page.wait_for_timeout(settle_ms)
        key = "ArrowRight" if i % 2 == 0 else "ArrowLeft"
        before = page.locator(".fe-recommended").inner_text()
        handle.focus()
        start_ms = page.evaluate("() => performance.now()")
        page.keyboard.press(key)
        page.wait_for_function(FE_CHANGED, arg=[before], polling="raf", timeout=30_000)
        end_ms = page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(performance.now()))))")
        times.append(end_ms - start_ms)
    return times


def main() -> None:
    if not CHROMIUM.exists():
        sys.exit(f"needs {CHROMIUM} (apt-get install chromium)")
    process, url = serve()
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
            page, handle = open_session(browser, url)
            measure(page, handle, 2)  # warm-up
            settled = measure(page, handle, 10, settle_ms=1000)
            print(f"one session, each change from a settled page: slider -> new F_e on screen, median of 10: "
                  f"{statistics.median(settled):.0f} ms (min {min(settled):.0f}, max {max(settled):.0f})")
            single = measure(page, handle, 10)
            print(f"one session, changes back to back (the previous plots still arriving): median of 10: "
                  f"{statistics.median(single):.0f} ms (min {min(single):.0f}, max {max(single):.0f})")
            page.close()
            browser.close()
        # 5 sessions at once, each in its own browser process and thread.
        results: dict[int, list[float]] = {}

        def session(k: int, ready: threading.Barrier):
            with sync_playwright() as p:
                b = p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
                pg, h = open_session(b, url)
                measure(pg, h, 1)
                ready.wait()
                results[k] = measure(pg, h, 10, settle_ms=1000)
                b.close()

        barrier = threading.Barrier(5)
        threads = [threading.Thread(target=session, args=(k, barrier)) for k in range(5)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        every = [t for times in results.values() for t in times]
        print(f"5 concurrent sessions (5 Chromium processes on the same machine), 10 changes each, 1 s apart: median {statistics.median(every):.0f} ms, "
              f"90th percentile {statistics.quantiles(every, n=10)[-1]:.0f} ms, max {max(every):.0f} ms")
    finally:
        process.terminate()
        process.wait(timeout=10)


if __name__ == "__main__":
    main()
