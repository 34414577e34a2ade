"""What a user of the wheel gets: ``pip install .`` (not editable) in a fresh virtual environment installs the
dashboard package beside the library, and ``pounding dashboard`` serves the page from it."""

from __future__ import annotations

import os
import re
import shutil
import site
import subprocess
import sys
import threading
import time
import zipfile
from pathlib import Path

import pytest

from pounding import estimate, load_case
from pounding.display_units import display
from tests.browser import LOAD_TIMEOUT, offline

ROOT = Path(__file__).resolve().parent.parent
_LEFT_OUT = shutil.ignore_patterns(".git", "__pycache__", "*.egg-info", "build", "dist", ".pytest_cache", "*.html", "*.nbi", "*.nbc")


def _site_directories() -> list[str]:
    """Where the running interpreter's packages are installed: its environment's site directories (a virtual
    environment's own, not its base interpreter's) and the user's, where enabled."""
    found = list(site.getsitepackages())
    if site.ENABLE_USER_SITE:
        found.append(site.getusersitepackages())
    return [folder for folder in found if Path(folder).is_dir()]


def _clean_environment() -> dict[str, str]:
    """The environment for the wheel's venv: no PYTHONPATH (it would put a checkout before the installed copy)."""
    return {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "PYTHONHOME")}


@pytest.fixture(scope="module")
def wheel_environment(tmp_path_factory):
    """A venv with pounding installed from its wheel, on the dependencies this test runs with.

    ``python -m venv`` makes a venv of the *base* interpreter even when run from a venv, and
    ``--system-site-packages`` then gives the base's packages: where the tests run in a venv of their own (the
    README's ``pip install -e ".[test]"`` in a fresh one), Panel and the rest are not there. A ``.pth`` file in the
    new venv adds the running interpreter's site directories (with their own ``.pth`` files) after the venv's own,
    so the wheel's copy of pounding is found first and its dependencies are this environment's."""
    folder = tmp_path_factory.mktemp("wheel")
    source = folder / "source"
    shutil.copytree(ROOT, source, ignore=_LEFT_OUT)  # build from a copy: the checkout stays clean
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w",
                    str(folder / "dist"), str(source)], check=True, timeout=600)
    (wheel,) = (folder / "dist").glob("pounding-*.whl")
    venv = folder / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(venv)], check=True, timeout=300)
    python = venv / "bin" / "python"
    purelib = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"], capture_output=True,
                             text=True, check=True, env=_clean_environment()).stdout.strip()
    lines = "".join(f"import site; site.addsitedir({folder!r})\n" for folder in _site_directories())
    (Path(purelib) / "zz_running_environment.pth").write_text(lines)  # read after the venv's own .pth files
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "--quiet", str(wheel)],
                   check=True, timeout=600, env=_clean_environment())
    return wheel, venv


@pytest.mark.slow
def test_the_wheel_holds_the_dashboard(wheel_environment):
    wheel, venv = wheel_environment
    names = zipfile.ZipFile(wheel).namelist()
    for name in ("dashboard/__init__.py", "dashboard/app.py", "dashboard/view.py", "pounding/presets/section5-T2-0.4.toml"):
        assert name in names
    found = subprocess.run([venv / "bin" / "python", "-c", "import dashboard, pounding; print(dashboard.__file__); print(pounding.__file__)"],
                           capture_output=True, text=True, cwd=wheel.parent, check=True, env=_clean_environment()).stdout.split()
    assert all(str(venv) in path for path in found), found  # the installed copies, not this checkout


@pytest.mark.browser
def test_pounding_dashboard_serves_the_page_from_the_wheel(wheel_environment, browser):
    _, venv = wheel_environment
    process = subprocess.Popen([venv / "bin" / "pounding", "dashboard", "--port", "0"], cwd=venv, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, env=_clean_environment())
    try:
        url, lines, deadline = None, [], time.monotonic() + 90
        while url is None and time.monotonic() < deadline:
            line = process.stdout.readline()
            if not line:
                break
            lines.append(line)
            match = re.search(r"(http://localhost:\d+/app)", line)
            url = match.group(1) if match else None
        assert url, "".join(lines)
        threading.Thread(target=lambda: [None for _ in process.stdout], daemon=True).start()
        page = browser.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        offline(page, errors)
        page.goto(url)
        expected = display("SI").force(estimate(load_case("section5-T2-0.4")).force_expected)
        page.wait_for_function(
            """(text) => { const find = (root) => { const el = root.querySelector('.fe-recommended'); if (el) return el;
                 for (const e of root.querySelectorAll('*')) { if (e.shadowRoot) { const f = find(e.shadowRoot); if (f) return f; } } return null; };
                 const el = find(document); return el !== null && el.textContent.trim() === text; }""",
            arg=expected, timeout=LOAD_TIMEOUT)
        assert errors == []
        page.close()
    finally:
        process.terminate()
        process.wait(timeout=20)
