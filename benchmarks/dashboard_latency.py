"""Dashboard latency in a real browser: slider change -> new F_e on screen.

Serves ``dashboard/app.py`` with ``panel serve`` on a free port, opens it in
headless Debian Chromium (/usr/bin/chromium) and, presses an arrow key on
the T2 slider (alternately right and left, so T2 stays near 0.4 s) and
waits (a MutationObserver on the result card) until the recommended F_e
shown differs from the value before; the time runs from the page's clock
just before the key press to two animation frames after the new text. Reports the median of 10
in one session, each change from a settled page and back to back, then
with 5 sessions changing sliders at once: 5 pages, each in its own browser
context (its own renderer process, websocket and server session) of one
Chromium on this same machine, so on 2 cores the 5 renderers compete with
the server for the CPU.

    python3 benchmarks/dashboard_latency.py
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import sys
import asyncio
import threading
from pathlib import Path

from playwright.async_api import async_playwright

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from tests.browser import CHROMIUM, CHROMIUM_ARGS  # noqa: E402

def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process so far [s] (Linux)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


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


async def open_session(browser, url):
    context = await browser.new_context(viewport={"width": 1500, "height": 1100})
    page = await context.new_page()
    await page.route("**/*", lambda r: r.continue_() if r.request.url.startswith(("http://localhost", "ws://localhost")) else r.abort())
    await page.goto(url)
    await page.locator(".fe-recommended").wait_for(timeout=60_000)
    handle = page.locator(".bk-input-group", has=page.get_by_text("period T2", exact=False)).locator(".noUi-handle").first
    return page, handle


WATCH_FE = """() => {
    // Resolves with the page's clock two animation frames (the new text
    // painted) after the recommended F_e shown changes. The card sits in a
    // pane's shadow root, found once; a MutationObserver on it (not polling
    // every frame, which would itself load the browser being measured).
    const find = (root) => {
        if (root.querySelector('.fe-recommended')) return root;
        for (const e of root.querySelectorAll('*')) { if (e.shadowRoot) { const f = find(e.shadowRoot); if (f) return f; } }
        return null;
    };
    if (!window.__feRoot || !window.__feRoot.querySelector('.fe-recommended')) window.__feRoot = find(document);
    const root = window.__feRoot, before = root.querySelector('.fe-recommended').textContent.trim();
    window.__feChanged = new Promise((resolve) => {
        const changed = () => { const el = root.querySelector('.fe-recommended'); return el && el.textContent.trim() !== before; };
        const observer = new MutationObserver(() => {
            if (changed()) { observer.disconnect(); requestAnimationFrame(() => requestAnimationFrame(() => resolve(performance.now()))); }
        });
        observer.observe(root, {subtree: true, childList: true, characterData: true});
    });
    return performance.now();
}"""


async def measure(page, handle, n: int, settle_ms: int = 0) -> list[float]:
    """Latencies of ``n`` changes [ms]; ``settle_ms`` is a pause before each
    change, so that the previous change's plots have been drawn (a user who
    reads the number before moving the slider again)."""
    times = []
    for i in range(n):
        if settle_ms:
            await page.wait_for_timeout(settle_ms)
        await handle.focus()
        start_ms = await page.evaluate(WATCH_FE)
        await page.keyboard.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
        end_ms = await page.evaluate("() => window.__feChanged")
        times.append(end_ms - start_ms)
    return times


def summary(times: list[float]) -> str:
    over = sum(t > 1000 for t in times)
    return (f"median {statistics.median(times):.0f} ms, 90th percentile {statistics.quantiles(times, n=10)[-1]:.0f} ms, "
            f"max {max(times):.0f} ms, over 1 s: {over} of {len(times)}")


async def run(process, url) -> None:
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        page, handle = await open_session(browser, url)
        await measure(page, handle, 2)  # warm-up
        await page.wait_for_timeout(1000)
        cpu_before = cpu_seconds(process.pid)
        settled = await measure(page, handle, 10, settle_ms=1000)
        await page.wait_for_timeout(1000)
        server_ms = (cpu_seconds(process.pid) - cpu_before) * 100  # [ms] per change, of 10
        print(f"one session, each change from a settled page: slider -> new F_e on screen, {summary(settled)}; "
              f"server CPU {server_ms:.0f} ms per change")
        back_to_back = await measure(page, handle, 10)
        print(f"one session, changes back to back (the previous plots still arriving): {summary(back_to_back)}")
        await page.context.close()

        sessions = [await open_session(browser, url) for _ in range(5)]
        for page, handle in sessions:
            await measure(page, handle, 1)
        every = [t for times in await asyncio.gather(*(measure(page, handle, 10, settle_ms=1000) for page, handle in sessions)) for t in times]
        print(f"5 concurrent sessions (5 pages in one Chromium on the same machine), 10 changes each, 1 s apart: {summary(every)}")
        await browser.close()


def main() -> None:
    if not CHROMIUM.exists():
        sys.exit(f"needs {CHROMIUM} (apt-get install chromium)")
    process, url = serve()
    try:
        asyncio.run(run(process, url))
    finally:
        process.terminate()
        process.wait(timeout=10)


if __name__ == "__main__":
    main()
