"""The dashboard's Monte Carlo studies: the reduced-sample study of the current
case and its Monte Carlo design gap (``pounding.simulation.monte_carlo.design_gap``), each
on a worker thread, their progress and results handed back to the session's
event loop; a change of inputs cancels a running study and drops results that
no longer hold."""

from __future__ import annotations

import dataclasses
import math
import threading
from concurrent.futures import ThreadPoolExecutor
from functools import cache, partial

import param

from pounding import defaults, simulate
from pounding.report import DEFAULT_SEED, MonteCarloPoint
from pounding.simulation.monte_carlo import Cancelled, DesignGap, design_gap

from dashboard.messages import message

__all__ = ["Studies"]


@cache
def _studies_pool() -> ThreadPoolExecutor:
    """Shared by all sessions: at most two studies at a time (each uses every core); made on first use."""
    return ThreadPoolExecutor(max_workers=2, thread_name_prefix="pounding-mc")


class Studies(param.Parameterized):
    """The studies' inputs, state and results; mixed into the dashboard's model, which provides ``snapshot``,
    ``_schedule`` (run on the session's loop) and calls :meth:`_invalidate_studies` on every new case."""

    records = param.Integer(defaults.DASHBOARD_RECORDS, bounds=(10, 2000), label="records",
                            doc="Records of the Monte Carlo study and of the Monte Carlo design gap.")
    seed = param.Integer(DEFAULT_SEED, bounds=(0, None), label="seed", doc="Seed of the records (the same seed, the same records).")

    mc_running = param.Boolean(False, precedence=-1)
    mc_progress = param.Integer(0, bounds=(0, 100), precedence=-1)
    mc_status = param.String("", precedence=-1)
    mc_points = param.List([], precedence=-1, doc="MonteCarloPoint of the current case (any gap).")
    design_gap_running = param.Boolean(False, precedence=-1)
    design_gap_progress = param.Integer(0, bounds=(0, 100), precedence=-1)
    design_gap_status = param.String("", precedence=-1)
    design_gap_result = param.Parameter(
        None, precedence=-1, doc="pounding.simulation.monte_carlo.DesignGap of the current case (it holds at any gap), or None."
    )

    def __init__(self, **params):
        super().__init__(**params)
        self._cancel: threading.Event | None = None
        self._mc_case_key = None
        self._mc_gap: float | None = None
        self._design_gap_cancel: threading.Event | None = None
        self._design_gap_key = None

    def _invalidate_studies(self, case) -> None:
        """A change of inputs: cancel a running study and drop results of another case.

        A study with contact is for one case at one gap: a change of either
        cancels it, and a change of the case (not of the gap) drops its points.
        The design gap (free motion) depends on neither the gap nor the contact
        law: only a change of the buildings, the excitation or the contact
        floors cancels or drops it. Switching the unit system changes nothing:
        the case is SI, and its round trip through the display units moves a
        value by a rounding error at most (compared with a tolerance).
        """
        study, free = _study_key(case), _free_motion_key(case)
        gap = None if case is None else case.contact.gap
        # The status first: the study may end as soon as its event is set.
        if self._cancel is not None and not self._cancel.is_set() and not (_same(study, self._mc_case_key) and _same(gap, self._mc_gap)):
            self.mc_status = "Monte Carlo cancelled: the inputs changed while it ran."
            self._cancel.set()
        if not _same(study, self._mc_case_key):
            self._mc_case_key = study
            if self.mc_points:
                self.mc_points = []
                if not self.mc_running:
                    self.mc_status = "Monte Carlo results cleared: the inputs changed."
        if not _same(free, self._design_gap_key):
            self._design_gap_key = free
            if self._design_gap_cancel is not None and not self._design_gap_cancel.is_set():
                self.design_gap_status = "Monte Carlo design gap cancelled: the inputs changed while it ran."
                self._design_gap_cancel.set()
            if self.design_gap_result is not None:
                self.design_gap_result = None
                if not self.design_gap_running:
                    self.design_gap_status = "Monte Carlo design gap cleared: the inputs changed."

    def _submit(self, study, cancel: threading.Event, progress, finished) -> None:
        """Run ``study(progress=..., cancel=cancel)`` on the worker executor.

        ``progress(cancel, done, total)`` and ``finished(cancel, result,
        error)`` run on the session's event loop; ``result`` is None when the
        study was cancelled or failed, ``error`` the failure's message. The
        caller keeps ``cancel`` before this call: with an inline schedule the
        study may finish before this returns.
        """

        def report(done: int, total: int) -> None:
            if not cancel.is_set():
                self._schedule(lambda: progress(cancel, done, total))

        def work():
            try:
                result = study(progress=report, cancel=cancel)
            except Cancelled:
                self._schedule(lambda: finished(cancel, None, None))
            except Exception as error:  # shown in the page, never a traceback
                # The except clause unbinds `error` when it ends: take the message now.
                text = message(error)
                self._schedule(lambda: finished(cancel, None, text))
            else:
                self._schedule(lambda: finished(cancel, result, None))

        _studies_pool().submit(work)

    def monte_carlo_for_current_gap(self) -> MonteCarloPoint | None:
        """The latest study of exactly the current case, if any."""
        if self.snapshot is None:
            return None
        gap = self.snapshot.case.contact.gap
        matching = [m for m in self.mc_points if _same(m.gap, gap)]
        return matching[-1] if matching else None

    def run_monte_carlo(self) -> None:
        """Start a study of the current case on a worker thread."""
        if self.mc_running or self.snapshot is None:
            return
        case = self.snapshot.case
        key = _study_key(case)
        records, seed = self.records, self.seed
        self._cancel, self._mc_gap = threading.Event(), case.contact.gap
        self.param.update(mc_running=True, mc_progress=0, mc_status=f"Monte Carlo: 0 of {records} records")
        self._submit(
            partial(simulate, case, records=records, seed=seed), self._cancel, self._progress,
            lambda cancel, result, error: self._finished(cancel, result, error, key),
        )

    def cancel_monte_carlo(self) -> None:
        """Cancel the running study, if any (it stops after its current chunk of records)."""
        if self._cancel is not None and not self._cancel.is_set():
            self.mc_status = "Monte Carlo: cancelling..."  # before the event: the study may end at once
            self._cancel.set()

    def _progress(self, cancel, done, total):
        if cancel is self._cancel and not cancel.is_set():
            self.param.update(mc_progress=int(100 * done / total), mc_status=f"Monte Carlo: {done} of {total} records")

    def _finished(self, cancel, result, error, key):
        if cancel is not self._cancel:
            return
        self._cancel = None
        if result is not None and not cancel.is_set() and _same(key, self._mc_case_key):
            point = MonteCarloPoint.from_result(result)
            # param sets the values in this order: `running` last, so whoever sees it off sees the rest.
            self.param.update(
                mc_progress=100, mc_points=[*self.mc_points, point], mc_status=f"Monte Carlo done: {result.n_records} records.",
                mc_running=False,
            )
        elif error is not None:
            self.param.update(mc_status=f"Monte Carlo failed: {error}", mc_running=False)
        else:
            self.param.update(mc_progress=0, mc_status=self.mc_status if "changed" in self.mc_status else "Monte Carlo cancelled.", mc_running=False)

    # --- Monte Carlo design gap ----------------------------------------------------

    def current_design_gap(self) -> DesignGap | None:
        """The Monte Carlo design gap of the current case, for the closed form's
        target probability, if one was run."""
        result = self.design_gap_result
        if self.snapshot is None or result is None or result.target_probability != self.snapshot.estimate.target_probability:
            return None
        return result

    def run_design_gap(self) -> None:
        """Start ``pounding.simulation.monte_carlo.design_gap`` for the current case on a
        worker thread: ``records`` records seeded ``seed``, for the target
        probability of no pounding of the closed-form required gap.

        Nothing runs if the result shown is already that one.
        """
        if self.design_gap_running or self.snapshot is None:
            return
        case = self.snapshot.case
        target = self.snapshot.estimate.target_probability
        records, seed = self.records, self.seed
        shown = self.current_design_gap()
        if shown is not None and (shown.n_records, shown.seed) == (records, seed):
            self.design_gap_status = f"Monte Carlo design gap: already computed for these inputs ({records} records, seed {seed})."
            return
        key = _free_motion_key(case)
        self._design_gap_cancel = threading.Event()
        self.param.update(
            design_gap_running=True, design_gap_progress=0, design_gap_status=f"Monte Carlo design gap: 0 of {records} records (free motion)"
        )
        self._submit(
            partial(design_gap, case, target, records=records, seed=seed), self._design_gap_cancel, self._design_gap_progress,
            lambda cancel, result, error: self._design_gap_finished(cancel, result, error, key),
        )

    def cancel_design_gap(self) -> None:
        """Cancel the running design gap, if any (it stops after its current chunk of records)."""
        if self._design_gap_cancel is not None and not self._design_gap_cancel.is_set():
            self.design_gap_status = "Monte Carlo design gap: cancelling..."  # before the event: the study may end at once
            self._design_gap_cancel.set()

    def _design_gap_progress(self, cancel, done, total):
        if cancel is self._design_gap_cancel and not cancel.is_set():
            self.param.update(
                design_gap_progress=int(100 * done / total), design_gap_status=f"Monte Carlo design gap: {done} of {total} records (free motion)"
            )

    def _design_gap_finished(self, cancel, result, error, key):
        if cancel is not self._design_gap_cancel:
            return
        self._design_gap_cancel = None
        if result is not None and not cancel.is_set() and _same(key, self._design_gap_key):
            self.param.update(  # `running` last, as in _finished
                design_gap_progress=100, design_gap_result=result,
                design_gap_status=f"Monte Carlo design gap done: {result.n_records} records.", design_gap_running=False,
            )
        elif error is not None:
            self.param.update(design_gap_status=f"Monte Carlo design gap failed: {error}", design_gap_running=False)
        else:
            status = self.design_gap_status
            self.param.update(
                design_gap_progress=0, design_gap_status=status if "changed" in status else "Monte Carlo design gap cancelled.",
                design_gap_running=False,
            )


def _study_key(case):
    """What a study with contact depends on apart from the gap (its points share one plot)."""
    return None if case is None else (case.buildings, case.excitation, dataclasses.replace(case.contact, gap=0.0))


def _free_motion_key(case):
    """What the records' free motion, and so the design gap, depends on: not the contact law or the gap."""
    return None if case is None else (case.buildings, case.excitation, case.contact.levels)


def _same(a, b) -> bool:
    """Equal, floats within a rounding error (the unit round trip), through dataclasses and tuples."""
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-15)
    if dataclasses.is_dataclass(a) and type(a) is type(b):
        return all(_same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, tuple | list) and isinstance(b, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b
