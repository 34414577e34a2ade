"""Issue 33: nothing of a session is left on the server's disk. Uploaded records and exported reports go when the
session closes, and every file of the server goes when ``pounding dashboard``, started as a user starts it, ends
on SIGTERM; nothing uploaded is written to the log. In headless Chromium."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from tests.browser import LOAD_TIMEOUT, ROOT, UPDATE_TIMEOUT, offline
from tests.test_dashboard_uploads import _records

pytestmark = pytest.mark.browser

MARK = "PLANTED-MARK-7f3a"  # a text inside an uploaded file: it must never reach the server's log


def _start(command: list[str], temporary: Path) -> tuple[subprocess.Popen, str, list[str]]:
    """The server started as ``command`` with its temporary files under ``temporary``; its URL and its log."""
    env = {**os.environ, "TMPDIR": str(temporary), "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen(command, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               start_new_session=True)
    log: list[str] = []
    deadline = time.monotonic() + 60
    url = None
    while url is None and time.monotonic() < deadline:
        line = process.stdout.readline()
        if not line:
            break
        log.append(line)
        match = re.search(r"(http://localhost:\d+/app)", line)
        url = match.group(1) if match else None
    if url is None:
        process.kill()
        pytest.fail("the server did not start:\n" + "".join(log))
    threading.Thread(target=lambda: log.extend(process.stdout), daemon=True).start()
    return process, url, log


def _leftovers(temporary: Path) -> list[str]:
    return sorted(str(p.relative_to(temporary)) for p in temporary.rglob("*"))


def _upload_and_export(browser, url: str, folder: Path):
    """A session that uploads two records (one carrying :data:`MARK`) and exports a report; its page."""
    context = browser.new_context(accept_downloads=True)
    page = context.new_page()
    offline(page, [])
    page.goto(url)
    page.locator(".fe-recommended").wait_for(timeout=LOAD_TIMEOUT)
    paths = _records(folder, 2)
    paths[1].write_text(f"{MARK} " + paths[1].read_text())  # in its title line: still a record
    page.locator(".card-header", has_text="Ground motion").first.click()
    page.locator(".bk-input-group", has=page.get_by_text("ground motion")).locator("select").first.select_option("recorded motions")
    page.locator("input[type=file][accept*='AT2']").set_input_files([str(p) for p in paths])
    page.get_by_text("Uploaded: m0.AT2, m1.AT2").wait_for(timeout=UPDATE_TIMEOUT)
    with page.expect_download(timeout=60_000):
        page.get_by_role("button", name="Export report (HTML)").click()
    return context


def test_a_closed_sessions_files_go_and_the_server_leaves_nothing(browser, tmp_path):
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    command = [sys.executable, "-m", "panel", "serve", str(ROOT / "dashboard" / "app.py"), "--port", "0",
               "--check-unused-sessions", "1000", "--unused-session-lifetime", "5000"]
    process, url, log = _start(command, temporary)
    try:
        context = _upload_and_export(browser, url, tmp_path)
        kept = _leftovers(temporary)
        assert any(re.search(r"pounding-records-[^/]+/m1\.AT2$", p) for p in kept), kept
        assert any(re.search(r"pounding-report-[^/]+/pounding-report-.*\.html$", p) for p in kept), kept
        context.close()
        deadline = time.monotonic() + 20
        while any("pounding-records-" in p or "pounding-report-" in p for p in _leftovers(temporary)):
            assert time.monotonic() < deadline, f"left after the session closed: {_leftovers(temporary)}"
            time.sleep(0.2)
    finally:
        process.send_signal(signal.SIGTERM)
        process.wait(timeout=30)
    assert _leftovers(temporary) == []
    assert MARK not in "".join(log)


def test_pounding_dashboard_ended_by_sigterm_leaves_no_file(browser, tmp_path):
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    process, url, log = _start([sys.executable, "-m", "pounding", "dashboard", "--port", "0"], temporary)
    try:
        context = _upload_and_export(browser, url, tmp_path)
        kept = _leftovers(temporary)
        assert any("pounding-records-" in p for p in kept) and any("pounding-report-" in p for p in kept), kept
    finally:
        process.send_signal(signal.SIGTERM)  # the session still open
        code = process.wait(timeout=30)
    context.close()
    assert _leftovers(temporary) == []
    text = "".join(log)
    assert "Traceback" not in text and MARK not in text
    assert code in (0, -signal.SIGTERM)
