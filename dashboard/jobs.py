"""A Monte Carlo study of the dashboard as one job (:class:`StudyJob`): run on a worker thread, its progress,
result and error handed back to the session's event loop, cancelled on request. The reduced-sample Monte Carlo,
the Monte Carlo design gap and the check of the headline against simulated records are three instances; the
view binds to their parameters."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from functools import cache

import param

from dashboard.messages import message
from pounding.simulation.monte_carlo import Cancelled

__all__ = ["StudyJob", "check_pool"]

CHECK_NICENESS = 19
"""How much lower than the server's other threads the checks' thread runs (Linux ``nice``, 0 to 19: the lowest):
a check takes the cores that the sessions' closed forms, the server's loop and, on the same machine, the
browsers' renderers (Chromium runs some at nice 10) leave, never the other way round."""


@cache
def _studies_pool() -> ThreadPoolExecutor:
    """Shared by all sessions: at most two studies at a time (each uses every core); made on first use."""
    return ThreadPoolExecutor(max_workers=2, thread_name_prefix="pounding-mc")


def _lower_priority() -> None:
    """Lower the calling thread's scheduling priority by :data:`CHECK_NICENESS` (Linux: a thread's own nice value,
    which the threads it starts inherit); elsewhere nothing."""
    try:
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), CHECK_NICENESS)
    except (AttributeError, OSError):
        pass


@cache
def check_pool() -> ThreadPoolExecutor:
    """Shared by all sessions: the checks of their headlines, one at a time on one thread of the lowest priority
    (each check runs on one core), so that the closed forms of every session keep the other core and what they
    need of this one; made on first use."""
    return ThreadPoolExecutor(max_workers=1, thread_name_prefix="pounding-check", initializer=_lower_priority)


class StudyJob(param.Parameterized):
    """One study run at a time: its state, its progress in records, its result or its error.

    ``schedule(fn)`` (given at construction; default: at once) runs ``fn`` on the session's event loop: every
    change of the job's parameters is made there, so the page's bindings see them in order.
    """

    title = param.String("Monte Carlo", constant=True, doc="The study's name in its messages ('Monte Carlo').")
    detail = param.String("", constant=True, doc="Said after its progress in records (' (free motion)').")
    running = param.Boolean(False, doc="Whether the study runs (or is cancelling).")
    progress = param.Integer(0, bounds=(0, 100), doc="Records done [%].")
    status = param.String("", doc="One sentence on the study's state, shown under its buttons.")
    result = param.Parameter(None, doc="What the last study gave, kept while it holds for the inputs; None before.")
    error = param.String("", doc="Why the last study failed (one sentence naming the input), or ''.")

    def __init__(self, schedule: Callable | None = None, submit: Callable | None = None, **params):
        """``submit(fn)`` runs ``fn`` on a worker thread (default: the studies' pool, two at a time)."""
        super().__init__(**params)
        self._schedule = schedule or (lambda fn: fn())
        self._submit = submit or _studies_pool().submit
        self._cancel: threading.Event | None = None

    def start(self, study: Callable, records: int, keep: Callable | None = None, replace: bool = False) -> bool:
        """Run ``study(progress=..., cancel=...)`` of ``records`` records on a worker thread, unless one runs.

        ``keep(result)``, called on the event loop when the study ends uncancelled, gives the job's new
        :attr:`result` (default: the study's result). ``replace``: a running study is cancelled and this one
        starts at once (whatever the old one still delivers is dropped). Returns whether it started."""
        if self.running and not replace:
            return False
        if self._cancel is not None:
            self._cancel.set()
        cancel = threading.Event()
        self._cancel = cancel  # before submitting: with an inline schedule the study may end before this returns
        self.param.update(running=True, progress=0, error="", status=f"{self.title}: 0 of {records} records{self.detail}")
        keep = keep or (lambda result: result)

        def report(done: int, total: int) -> None:
            if not cancel.is_set():
                self._schedule(lambda: self._progressed(cancel, done, total))

        def work() -> None:
            try:
                result = study(progress=report, cancel=cancel)
            except Cancelled:
                self._schedule(lambda: self._finished(cancel, None, None, keep))
            except Exception as error:  # shown in the page, never a traceback
                text = message(error)  # the except clause unbinds `error` when it ends: take the message now
                self._schedule(lambda: self._finished(cancel, None, text, keep))
            else:
                self._schedule(lambda: self._finished(cancel, result, None, keep))

        self._submit(work)
        return True

    def cancel(self, reason: str = "") -> None:
        """Stop the running study after its current chunk of records, if one runs; ``reason`` (the inputs
        changed...) is said in its status."""
        if self._cancel is None or self._cancel.is_set():
            return
        # The status first: the study may end as soon as its event is set.
        self.status = f"{self.title} cancelled: {reason}" if reason else f"{self.title}: cancelling..."
        self._cancel.set()

    def clear(self, reason: str) -> None:
        """Drop a result that no longer holds, saying why (unless a study runs: its own status stays)."""
        if self.result is not None:
            self.result = None
            if not self.running:
                self.status = f"{self.title} cleared: {reason}"

    def _progressed(self, cancel: threading.Event, done: int, total: int) -> None:
        if cancel is self._cancel and not cancel.is_set():
            self.param.update(progress=int(100 * done / total), status=f"{self.title}: {done} of {total} records{self.detail}")

    def _finished(self, cancel: threading.Event, result, error: str | None, keep: Callable) -> None:
        if cancel is not self._cancel:
            return
        self._cancel = None
        # param sets the values in the order given: `running` last, so whoever sees it go off sees the rest.
        if result is not None and not cancel.is_set():
            self.param.update(progress=100, result=keep(result), status=f"{self.title} done: {_records(result)} records.",
                              running=False)
        elif error is not None:
            self.param.update(error=error, status=f"{self.title} failed: {error}", running=False)
        else:
            said = self.status if self.status.startswith(f"{self.title} cancelled:") else f"{self.title} cancelled."
            self.param.update(progress=0, status=said, running=False)


def _records(result) -> int:
    """How many records a study's result holds (a Monte Carlo result or a design gap: ``n_records``; a check of
    the estimate: ``records``)."""
    count = getattr(result, "n_records", None)
    return result.records if count is None else count
