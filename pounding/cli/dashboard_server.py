"""The dashboard's server supervisor (``pounding dashboard`` starts it in a process group of its own): it runs
``panel serve`` as its child, in the same group. With several server processes, Bokeh forks them from that
child, which then only waits on them; a SIGTERM to this supervisor (from ``pounding dashboard``, or from the
kernel when that one dies) ends the whole group, so no forked server is left serving the port.

    python -m pounding.cli.dashboard_server APP --port N [panel serve options]
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

__all__ = ["main"]


def _end_group(signum, frame) -> None:
    """SIGTERM to every process of this group (each server stops on it), this one included."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    os.killpg(os.getpgrp(), signal.SIGTERM)


def main(argv: list[str]) -> int:
    """``panel serve`` with ``argv`` as a child; this process's SIGTERM ends the whole group. Returns its exit code."""
    signal.signal(signal.SIGTERM, _end_group)
    server = subprocess.Popen([sys.executable, "-m", "panel", "serve", *argv])
    try:
        return server.wait()
    except KeyboardInterrupt:  # Ctrl-C reaches the whole foreground group: the servers stop on their own
        return server.wait()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
