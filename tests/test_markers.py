"""The README's fast subset, ``-m "not browser and not slow and not opensees"``, leaves out every test that drives
Chromium (marked by its module, or by the fixtures it takes: tests/conftest.py) and keeps the quick ones."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FAST = "not browser and not slow and not opensees"


def _collected(marks: str) -> list[str]:
    out = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", "-m", marks],
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return [line for line in out.stdout.splitlines() if "::" in line]


@pytest.mark.slow  # two collections of the whole suite, 10 to 20 s
def test_the_fast_subset_drives_no_browser_and_runs_no_long_study():
    fast = _collected(FAST)
    browser = _collected("browser")
    assert fast and browser and not set(fast) & set(browser)
    for module in ("test_dashboard.py::", "test_notebook_inline.py::", "test_opensees.py::", "test_notebooks.py::test_notebook_runs"):
        assert not [test for test in fast if f"/{module}" in test], module
    assert "tests/test_wheel.py::test_pounding_dashboard_serves_the_page_from_the_wheel" in browser
    assert any(test.startswith("tests/test_structure.py::test_no_module_imports_from_a_layer") for test in fast)
