"""What the scripts that write accuracy.json share: an entry of measured errors and the commit measured at."""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np

__all__ = ["DEFAULT_OUTPUT", "ROOT", "force_entry", "git_commit"]

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUTPUT = ROOT / "pounding" / "data" / "accuracy.json"
"""The data file the estimate reads (pounding.closed_form.regimes.accuracy_data)."""


def force_entry(errors) -> dict:
    """cases, within 10 %, median |error| and the range of ``errors`` (estimate / Monte Carlo - 1);
    None where there is no case (only in a reduced run)."""
    errors = np.asarray(errors, dtype=float)
    if not errors.size:
        return {"cases": 0, "within_10_percent": 0, "median_abs_error": None, "low": None, "high": None}
    return {
        "cases": int(errors.size),
        "within_10_percent": int(np.sum(np.abs(errors) <= 0.10)),
        "median_abs_error": round(float(np.median(np.abs(errors))), 3),
        "low": round(float(errors.min()), 2),
        "high": round(float(errors.max()), 2),
    }


def git_commit() -> str:
    """``git rev-parse --short HEAD`` of the repository, or "unknown"."""
    try:
        out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True, check=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return out.stdout.strip() or "unknown"
