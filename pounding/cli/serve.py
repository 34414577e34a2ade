"""Serve the dashboard with Panel's server (``pounding dashboard``).

The server runs as a child process (``python -m panel serve``) in this
process's group. SIGINT (Ctrl-C), SIGTERM and SIGHUP received here are passed
on to it as SIGTERM (Bokeh's server shuts down on it), and this process waits
for it to end before it acts on the signal itself; on Linux the child also
gets SIGTERM if this process is killed outright. Nothing is left serving the
port once ``pounding dashboard`` has ended, nor any of its temporary files: the server keeps them in one folder
that this process makes, names to it (:data:`TEMPORARY_FOLDER_VARIABLE`) and removes once it has ended, whatever
ended it.
"""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["TEMPORARY_FOLDER_VARIABLE", "WEBSOCKET_MESSAGE_BYTES", "dashboard_app_path", "port_number", "serve_dashboard"]

TEMPORARY_FOLDER_VARIABLE = "POUNDING_DASHBOARD_TMP"
"""Environment variable naming the folder where the dashboard's server keeps its sessions' files (uploaded records,
exported reports); ``pounding dashboard`` makes it and removes it when the server has ended."""
WEBSOCKET_MESSAGE_BYTES = 10_000_000
"""The server's largest websocket message [bytes]: a file uploaded within the page's limit (5 MB, sent as base64)
fits; a larger message closes the connection before it is read whole."""

SERVER_PROCESSES = 1
"""Server processes of ``pounding dashboard``. One: the sessions' computations share its thread pool (one thread a
core). Two processes answered five busy sessions faster (benchmarks/dashboard_latency.py), but with Panel 1.9 a
forked server process may load Panel's style sheets from its CDN, which an offline page cannot reach."""
_STOP_TIMEOUT = 5.0  # [s] the child's time to shut down after SIGTERM, before SIGKILL


def dashboard_app_path() -> Path:
    """The dashboard's Panel script (``dashboard/app.py`` beside the package)."""
    return Path(__file__).resolve().parents[2] / "dashboard" / "app.py"


def _port_error(value) -> str | None:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 65535:
        return f"must be a whole number in [0, 65535] (0 picks a free one), got {value!r}"
    return None


def port_number(text: str) -> int:
    """An argparse type: a TCP port in [0, 65535]."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number in [0, 65535] (0 picks a free one), got {text!r}") from None
    problem = _port_error(value)
    if problem:
        raise argparse.ArgumentTypeError(problem)
    return value


def _free_port() -> int:
    """A port free now (the server's allowed websocket origins must name the real port, not 0)."""
    import socket

    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("", 0))
        return probe.getsockname()[1]


def _die_with_parent() -> None:
    """In the child, before exec: SIGTERM when the parent dies (Linux; elsewhere nothing)."""
    try:
        import ctypes
        import signal

        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def _stop(process, deadline: float | None = None) -> None:
    """SIGTERM to ``process`` if it runs; SIGKILL if it has not ended by ``deadline``."""
    import time

    if process.poll() is not None:
        return
    if deadline is None:
        process.terminate()
    elif time.monotonic() >= deadline:
        process.kill()


def _end_group(group: int) -> None:
    """Wait for the server's process group to end (its forked servers stop on the SIGTERM their leader sent);
    SIGKILL what is left after a few seconds."""
    import os
    import signal
    import time

    deadline = time.monotonic() + _STOP_TIMEOUT
    while time.monotonic() < deadline:
        try:
            os.killpg(group, 0)
        except ProcessLookupError:
            return
        time.sleep(0.05)
    try:
        os.killpg(group, signal.SIGKILL)
    except ProcessLookupError:
        pass


def serve_dashboard(port: int = 5006, show: bool = False, extra_origins: list[str] | None = None) -> int:
    """Run ``panel serve dashboard/app.py`` until it ends or is interrupted.

    ``port`` 0 picks a free port. A SIGINT, SIGTERM or SIGHUP received while it
    serves stops the server (SIGTERM, then SIGKILL after a few seconds), waits
    for it, and then takes its usual effect here (SIGINT: KeyboardInterrupt).

    Returns
    -------
    int
        The server's exit status (0 when it ended normally).

    Raises
    ------
    ArgumentError
        ``port`` is not in [0, 65535] (field ``port``).
    FileNotFoundError
        The dashboard script is missing.
    """
    import errno
    import signal
    import subprocess
    import sys
    import threading
    import time

    from pounding.errors import ArgumentError

    problem = _port_error(port)
    if problem:
        raise ArgumentError("port", problem)
    app = dashboard_app_path()
    if not app.is_file():
        raise FileNotFoundError(errno.ENOENT, "the dashboard script is missing; reinstall pounding (python3 -m pip install pounding)", str(app))
    port = port or _free_port()
    command = [sys.executable, "-m", "pounding.cli.dashboard_server", str(app), "--port", str(port), "--num-procs", str(SERVER_PROCESSES),
               "--websocket-max-message-size", str(WEBSOCKET_MESSAGE_BYTES)]
    origins = [f"localhost:{port}", f"127.0.0.1:{port}", *(extra_origins or [])]
    for origin in origins:
        command += ["--allow-websocket-origin", origin]
    if show:
        command.append("--show")
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    linux = sys.platform.startswith("linux")
    import os
    import shutil
    import tempfile

    folder = tempfile.mkdtemp(prefix="pounding-dashboard-")
    environment = {**os.environ, TEMPORARY_FOLDER_VARIABLE: folder}
    # Its own process group: the server's forked processes are ended with it (pounding/cli/dashboard_server.py).
    try:
        process = subprocess.Popen(command, preexec_fn=_die_with_parent if linux else None, start_new_session=linux, env=environment)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    received: list[int] = []
    deadline = None

    def forward(signum, frame) -> None:
        nonlocal deadline
        received.append(signum)
        if deadline is None:
            deadline = time.monotonic() + _STOP_TIMEOUT
            _stop(process)

    watched = [getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)]
    previous = {}
    if threading.current_thread() is threading.main_thread():
        previous = {signum: signal.signal(signum, forward) for signum in watched}
    try:
        while process.poll() is None:
            try:
                process.wait(timeout=0.2)
            except subprocess.TimeoutExpired:
                if deadline is not None:
                    _stop(process, deadline)
    finally:
        if process.poll() is None:  # an exception here (not a signal): the server goes too
            process.terminate()
            try:
                process.wait(timeout=_STOP_TIMEOUT)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        if linux:
            _end_group(process.pid)
        shutil.rmtree(folder, ignore_errors=True)  # the sessions' files, however the server ended
        for signum, handler in previous.items():
            signal.signal(signum, signal.SIG_DFL if handler is None else handler)
    if received:
        if received[0] == signal.SIGINT:
            raise KeyboardInterrupt
        signal.raise_signal(received[0])  # its usual effect now that the server is gone (by default: the end)
    return process.returncode
