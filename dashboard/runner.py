"""Where the dashboard's work runs: computations off the event loop, the newest
request of a session only, results handed back to the session's loop.

Every session's requests go to one small pool of threads shared by the
server (:func:`shared_pool`: as many threads as cores, so five sessions that
change an input at once share the cores instead of queuing on the event loop).
A request made stale by a newer one of the same session is never started if it
has not started, and stops at its next checkpoint if it has: it is cancelled,
not queued.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from functools import cache

__all__ = ["Latest", "shared_pool"]


@cache
def shared_pool() -> ThreadPoolExecutor:
    """The server's pool for the sessions' computations (made on first use; threads start when work comes)."""
    return ThreadPoolExecutor(max_workers=os.cpu_count() or 2, thread_name_prefix="pounding-dashboard")


class Latest:
    """Runs a session's newest request.

    Parameters
    ----------
    submit : callable, optional
        ``submit(fn)`` runs ``fn`` somewhere (default: at once, in this thread; the served dashboard passes
        :func:`shared_pool`'s ``submit``).
    deliver : callable, optional
        ``deliver(fn)`` runs ``fn`` on the session's event loop (default: at once).
    """

    def __init__(self, submit: Callable | None = None, deliver: Callable | None = None):
        self._submit = submit or (lambda fn: fn())
        self._deliver = deliver or (lambda fn: fn())
        self._lock = threading.Lock()
        self._newest = 0

    def request(self, work: Callable[[Callable[[], bool], Callable[[Callable[[], None]], None]], None]) -> None:
        """Run ``work(current, deliver)``: ``current()`` tells whether this request is still the newest (check it
        between steps), ``deliver(fn)`` runs ``fn`` on the event loop if it still is when ``fn`` runs there."""
        with self._lock:
            self._newest += 1
            mine = self._newest

        def current() -> bool:
            return self._newest == mine

        def deliver(fn: Callable[[], None]) -> None:
            self._deliver(lambda: fn() if current() else None)

        def run() -> None:
            if current():
                work(current, deliver)

        self._submit(run)
