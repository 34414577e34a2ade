"""The dashboard's server process (``pounding dashboard`` starts it): ``panel serve`` run in this process, which
leads a process group of its own. With several server processes, Bokeh forks them from this one, which then only
waits on them; a SIGTERM to this process (from ``pounding dashboard``, or from the kernel when that one dies)
ends the whole group, so no forked server is left serving the port.

    python -m pounding.dashboard_server APP --port N [panel serve options]
"""

from __future__ import annotations

import os
import signal
import sys

__all__ = ["main"]


def _end_group(signum, frame) -> None:
    """SIGTERM to every process of this group (each forked server stops on it), this one included."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    os.killpg(os.getpgrp(), signal.SIGTERM)


def main(argv: list[str]) -> None:
    """``panel serve`` with ``argv``, this process's SIGTERM ending its whole group."""
    signal.signal(signal.SIGTERM, _end_group)  # the forked servers replace it with Bokeh's graceful stop
    from panel.command import main as panel

    sys.argv = ["panel", "serve", *argv]
    panel()


if __name__ == "__main__":
    main(sys.argv[1:])
