"""Serve the dashboard with Panel's server (``pounding dashboard``)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["dashboard_app_path", "serve_dashboard"]


def dashboard_app_path() -> Path:
    """The dashboard's Panel script (``dashboard/app.py`` beside the package)."""
    return Path(__file__).resolve().parent.parent / "dashboard" / "app.py"


def serve_dashboard(port: int = 5006, show: bool = False, extra_origins: list[str] | None = None) -> None:
    """Run ``panel serve dashboard/app.py`` in this process until interrupted."""
    import subprocess
    import sys

    app = dashboard_app_path()
    if not app.is_file():
        from .errors import CaseError

        raise CaseError("dashboard", f"the dashboard script {app} is missing (install pounding from its source tree)")
    command = [sys.executable, "-m", "panel", "serve", str(app), "--port", str(port), "--num-procs", "1"]
    origins = [f"localhost:{port}", f"127.0.0.1:{port}", *(extra_origins or [])]
    for origin in origins:
        command += ["--allow-websocket-origin", origin]
    if show:
        command.append("--show")
    subprocess.run(command, check=False)
