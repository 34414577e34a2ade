"""Dashboard latency in a real browser: an input changed -> the new force on screen, and the plot redrawn.

Serves ``dashboard/app.py`` with ``panel serve`` on a free port, opens it in headless Debian Chromium
(/usr/bin/chromium), types T2 (alternately 0.45 and 0.40 s, Enter) and waits (a MutationObserver on the
headline) until the expected extreme force shown differs from the value before; the time runs from the
page's clock just before the key press to two animation frames after the new text. The plot's time runs to
the frame where the force-against-gap curve's data changed; the verdict's (one session only, where the
dashboard checks its headline against simulated records) to the frame where the new verdict stands under
the headline. Reports one session (changes from a settled page), then 5 sessions changing T2 at once, 1 s
apart: 5 pages, each in its own browser context (its own renderer, websocket and server session) of one
Chromium on this machine, so on 2 cores the 5 renderers compete with the server for the CPU.

Each way of serving is measured in turn (``--args --compute`` of dashboard/app.py and ``--num-procs``):
the sessions' computations on the server's shared thread pool (the default), on the event loop (inline),
and the thread pool in two server processes.

    python3 benchmarks/dashboard_latency.py
"""

from __future__ import annotations

import asyncio
import os
import re
import signal
import statistics
import subprocess
import sys
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


def serve(compute: str = "threads", processes: int = 1):
    process = subprocess.Popen(
        [sys.executable, "-m", "panel", "serve", str(ROOT / "dashboard" / "app.py"), "--port", "0", "--num-procs", str(processes),
         "--args", "--compute", compute],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True,
    )
    for line in process.stdout:
        match = re.search(r"(http://localhost:\d+/app)", line)
        if match:
            threading.Thread(target=lambda: [None for _ in process.stdout], daemon=True).start()
            return process, match.group(1)
    raise RuntimeError("panel serve did not start")


def stop(process) -> None:
    """End the server and every process it forked (``--num-procs``: its children outlive a SIGTERM to it alone)."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(process.pid, sig)
            process.wait(timeout=10)
            return
        except ProcessLookupError:
            return
        except subprocess.TimeoutExpired:
            continue


async def open_session(browser, url):
    context = await browser.new_context(viewport={"width": 1500, "height": 1100})
    page = await context.new_page()
    await page.route("**/*", lambda r: r.continue_() if r.request.url.startswith(("http://localhost", "ws://localhost")) else r.abort())
    await page.goto(url)
    await page.locator(".fe-recommended").wait_for(timeout=60_000)
    await page.locator(".card-header", has_text="Building 2").first.click()
    field = page.locator(".bk-input-group", has=page.get_by_text("fundamental period T2", exact=False)).locator("input").first
    await field.wait_for(timeout=20_000)
    return page, field


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
    // The verdict of the check against simulated records: a new one under the headline (none: NaN at once).
    const verdict = () => { const el = root.querySelector('.check-verdict');
        return el && !el.classList.contains('checking') ? el.textContent.trim() : null; };
    const verdictBefore = verdict();
    window.__verdictChanged = root.querySelector('.check-verdict') === null ? Promise.resolve(NaN) : new Promise((resolve) => {
        const observer = new MutationObserver(() => {
            const now = verdict();
            if (now !== null && now !== verdictBefore) { observer.disconnect(); requestAnimationFrame(() => requestAnimationFrame(() => resolve(performance.now()))); }
        });
        observer.observe(root, {subtree: true, childList: true, characterData: true});
    });
    // The plot: the force-against-gap source's data replaced (its 'paper' column marks it).
    const source = window.Bokeh.documents.flatMap(d => Array.from(d.all_models)).find(
        m => m.data != null && typeof m.data === 'object' && (m.data instanceof Map ? m.data.has('paper') : 'paper' in m.data));
    const data = () => source.data instanceof Map ? source.data.get('force') : source.data.force;
    const first = data();
    window.__plotChanged = new Promise((resolve) => {
        const poll = () => { if (data() !== first) requestAnimationFrame(() => resolve(performance.now())); else setTimeout(poll, 10); };
        poll();
    });
    return performance.now();
}"""


async def measure(page, field, n: int, settle_ms: int = 0, plots: list | None = None, verdicts: list | None = None) -> list[float]:
    """Latencies of ``n`` changes [ms] to the new force (and, into ``plots``, to the redrawn plot; into ``verdicts``,
    to the new verdict, waited for before the next change); ``settle_ms`` is a pause before each change, so that
    the previous change's plots have been drawn (a user who reads the number before changing an input again)."""
    times = []
    for i in range(n):
        if settle_ms:
            await page.wait_for_timeout(settle_ms)
        current = await field.input_value()
        await field.fill("0.4" if current.startswith("0.45") else "0.45")  # always a change
        start_ms = await page.evaluate(WATCH_FE)
        await field.press("Enter")
        end_ms = await page.evaluate("() => Promise.race([window.__feChanged, new Promise(r => setTimeout(() => r(NaN), 30000))])")
        times.append(end_ms - start_ms)
        plotted = await page.evaluate("() => Promise.race([window.__plotChanged, new Promise(r => setTimeout(() => r(NaN), 30000))])")
        if plots is not None:
            plots.append(plotted - start_ms)
        if verdicts is not None:
            checked = await page.evaluate("() => Promise.race([window.__verdictChanged, new Promise(r => setTimeout(() => r(NaN), 30000))])")
            verdicts.append(checked - start_ms)
    return times


def summary(times: list[float]) -> str:
    missed = sum(t != t for t in times)  # NaN: nothing changed within 30 s (a lost update)
    times = [t for t in times if t == t] or [float("nan")]
    over = sum(t > 1000 for t in times) + missed
    return (f"median {statistics.median(times):.0f} ms, 90th percentile {statistics.quantiles(times, n=10)[-1]:.0f} ms, "
            f"max {max(times):.0f} ms, over 1 s: {over} of {len(times)}")


async def run(process, url, label: str) -> None:
    async with async_playwright() as p:
        browser = await p.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        page, field = await open_session(browser, url)
        await measure(page, field, 2)  # warm-up
        await page.wait_for_timeout(1000)
        cpu_before = cpu_seconds(process.pid)
        plots: list[float] = []
        verdicts: list[float] = []
        settled = await measure(page, field, 10, settle_ms=1000, plots=plots, verdicts=verdicts)
        await page.wait_for_timeout(1000)
        server_ms = (cpu_seconds(process.pid) - cpu_before) * 100  # [ms] per change, of 10 (the first process only)
        verdict = f"verdict {summary(verdicts)}; " if any(v == v for v in verdicts) else ""
        print(f"[{label}] one session: new force {summary(settled)}; plot {summary(plots)}; {verdict}"
              f"server CPU {server_ms:.0f} ms per change (the check's included)")
        await page.context.close()

        sessions = [await open_session(browser, url) for _ in range(5)]
        for page, field in sessions:
            await measure(page, field, 1)
        plots = []
        every = [t for times in await asyncio.gather(*(measure(page, field, 10, settle_ms=1000, plots=plots) for page, field in sessions))
                 for t in times]
        print(f"[{label}] 5 concurrent sessions, 10 changes each, 1 s apart: new force {summary(every)}; plot {summary(plots)}")
        await browser.close()


def main() -> None:
    if not CHROMIUM.exists():
        sys.exit(f"needs {CHROMIUM} (apt-get install chromium)")
    for compute, processes in (("threads", 1), ("inline", 1), ("threads", 2)):
        process, url = serve(compute, processes)
        try:
            asyncio.run(run(process, url, f"{compute}, {processes} process(es)"))
        finally:
            stop(process)


if __name__ == "__main__":
    main()
