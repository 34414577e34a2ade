"""The dashboard's Monte Carlo studies: the check of the headline against simulated records, run by itself after
each change (``pounding.studies.check.check_estimate``), the reduced-sample study of the current case and its
Monte Carlo design gap (``pounding.simulation.monte_carlo.design_gap``), each a :class:`~dashboard.jobs.StudyJob`;
a change of inputs cancels a running study and drops results that no longer hold."""

from __future__ import annotations

import dataclasses
import math
from functools import partial

import param

from dashboard.jobs import StudyJob, check_pool
from pounding import defaults, simulate
from pounding.report import MonteCarloPoint
from pounding.simulation.monte_carlo import Cancelled, DesignGap, design_gap
from pounding.simulation.plan import MonteCarloPlan
from pounding.simulation.system import Settings
from pounding.studies.check import EstimateCheck, RowCheck, check_estimate, check_row

__all__ = ["MAX_STUDY_RECORDS", "ONE_CONTACT_STUDIES", "Studies"]

MAX_STUDY_RECORDS = 2000
"""Most records of one study of the page (about a minute of two cores); the command line takes more."""
CHANGED = "the inputs changed."
"""Why a result was dropped."""
CHANGED_WHILE_RUNNING = "the inputs changed while it ran."
"""Why a study was cancelled by the inputs."""
CHECK_DELAY = 0.25
"""Seconds a check waits after the headline before it starts, so that typing (a change every few tenths of a
second) starts one check, not one a keystroke; a newer change ends the wait at once."""
CHECK_THREADS = 1
ONE_CONTACT_STUDIES = ("The Monte Carlo study at a chosen number of records and the Monte Carlo design gap take a case of one "
                       "contact; this case has several. The page checks it against simulated records by itself, every "
                       "contact acting: the headline's verdict and the table's Monte Carlo column.")
"""What the Monte Carlo tab says for a case of several contacts (its studies take one contact)."""
"""Threads of one check: one core, whatever the machine has; the sessions' closed forms keep the others."""


class Studies(param.Parameterized):
    """The studies' inputs and their three jobs; mixed into the dashboard's model, which provides ``result``,
    ``snapshot`` and ``_schedule`` (run on the session's loop) before calling :meth:`_make_jobs`, calls
    :meth:`_inputs_changed` on every change of input, :meth:`_invalidate_studies` on every new case and
    :meth:`_check` on every new estimate."""

    records = param.Integer(defaults.DASHBOARD_RECORDS, bounds=(1, MAX_STUDY_RECORDS), label="records",
                            doc="Records of the Monte Carlo study and of the Monte Carlo design gap (recorded motions: "
                            "each of them once, whatever this says).")
    seed = param.Integer(defaults.SEED, bounds=(0, None), label="seed", doc="Seed of the records (the same seed, the same records).")

    monte_carlo_job = param.ClassSelector(class_=StudyJob, precedence=-1, doc="The reduced-sample Monte Carlo of the current "
                                          "case: its result the MonteCarloPoint of each gap run (a tuple), or None.")
    design_gap_job = param.ClassSelector(class_=StudyJob, precedence=-1, doc="The Monte Carlo design gap of the current case: "
                                         "its result a pounding.simulation.monte_carlo.DesignGap (it holds at any gap), or None.")
    check_job = param.ClassSelector(class_=StudyJob, precedence=-1, doc="The check of the estimate shown against simulated "
                                    "records, run after each change: its result (the Estimate checked, its EstimateCheck), or None.")

    def _make_jobs(self, check: bool) -> None:
        """The three jobs; ``check``: whether each new estimate is checked against simulated records by itself
        (kept as :attr:`checks`)."""
        self.monte_carlo_job = StudyJob(schedule=self._schedule, title="Monte Carlo")
        self.design_gap_job = StudyJob(schedule=self._schedule, title="Monte Carlo design gap", detail=" (free motion)")
        self.check_job = StudyJob(schedule=self._schedule, submit=check_pool().submit, title="Check against simulated records")
        self.checks = check
        self._mc_case_key = None
        self._mc_gap: tuple | None = None  # the gap of each contact of the study running
        self._design_gap_key = None
        self._checked: tuple | None = None  # (_check_key of the last check that ended, its EstimateCheck)
        self._checking = None  # the Estimate whose check was started last

    # --- the check of the headline ------------------------------------------------------

    def current_check(self) -> EstimateCheck | RowCheck | None:
        """The check of exactly the estimate shown (``result``), once it has ended; None before, and for any other."""
        found = self.check_job.result
        if found is None or self.result is None:
            return None
        checked, check = found
        return check if checked is self.result else None

    def check_error(self) -> str:
        """Why the check of the estimate shown failed, or ''."""
        return self.check_job.error if self.result is not None and self._checking is self.result else ""

    def _inputs_changed(self) -> None:
        """A change of input, on the event loop, before its estimate: the check running is of other inputs; it
        stops after its current chunk of records, and nothing it gives is kept or shown."""
        self.check_job.cancel(CHANGED_WHILE_RUNNING)
        self.check_job.clear(CHANGED)

    def _check(self, result) -> None:
        """Check the estimate ``result`` (about to be shown) against simulated records on the checks' thread: seeded
        as the other studies of the page (``seed``), as many records as the precision asks, one core; after
        :data:`CHECK_DELAY`. A check of the same case, target and seed already done is shown at once."""
        if not self.checks:
            return
        self._checking = result
        key = _check_key(result, self.seed)
        if key is not None and self._checked is not None and _same(key, self._checked[0]):
            self.check_job.param.update(result=(result, self._checked[1]), error="")
            return
        plan = MonteCarloPlan(seed=self.seed, settings=Settings(workers=CHECK_THREADS))
        check = check_row if len(result.case.contacts) > 1 else check_estimate  # several contacts: one study of them all

        def study(progress, cancel):  # no progress: the page shows none, and each report would cost the loop a callback
            if cancel.wait(CHECK_DELAY):
                raise Cancelled("a newer change came first")
            return check(result, dataclasses.replace(plan, cancel=cancel))

        def keep(check: EstimateCheck):
            self._checked = (key, check)
            return result, check

        self.check_job.start(study, defaults.CHECK_FIRST_RECORDS, keep=keep, replace=True)

    def monte_carlo_points(self) -> tuple[MonteCarloPoint, ...]:
        """The studies of the current case, one per gap run (any gap)."""
        return self.monte_carlo_job.result or ()

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
        gap = None if case is None else tuple(contact.gap for contact in case.contacts)
        if not (_same(study, self._mc_case_key) and _same(gap, self._mc_gap)):
            self.monte_carlo_job.cancel(CHANGED_WHILE_RUNNING)
        if not _same(study, self._mc_case_key):
            self._mc_case_key = study
            self.monte_carlo_job.clear(CHANGED)
        if not _same(free, self._design_gap_key):
            self._design_gap_key = free
            self.design_gap_job.cancel(CHANGED_WHILE_RUNNING)
            self.design_gap_job.clear(CHANGED)

    def monte_carlo_for_current_gap(self) -> MonteCarloPoint | None:
        """The latest study of exactly the case of the estimate shown (``result``: the plots may still be of the
        inputs before), if any."""
        if self.result is None or len(self.result.case.contacts) > 1:
            return None
        gap = self.result.case.contact.gap
        matching = [m for m in self.monte_carlo_points() if _same(m.gap, gap)]
        return matching[-1] if matching else None

    def run_monte_carlo(self) -> None:
        """Start a study of the current case on a worker thread."""
        if self.monte_carlo_job.running or self.snapshot is None:
            return
        case = self.snapshot.case
        if len(case.contacts) > 1:
            self.monte_carlo_job.status = ONE_CONTACT_STUDIES
            return
        self._mc_gap = (case.contact.gap,)
        records = _records_of(case, self.records)
        self.monte_carlo_job.start(partial(simulate, case, records=records, seed=self.seed), records,
                               keep=lambda result: (*self.monte_carlo_points(), MonteCarloPoint.from_result(result)))

    def current_design_gap(self) -> DesignGap | None:
        """The Monte Carlo design gap of the current case, for the target probability of the estimate shown, if
        one was run."""
        result = self.design_gap_job.result
        if self.result is None or result is None or result.target_probability != self.result.target_probability:
            return None
        return result

    def run_design_gap(self) -> None:
        """Start ``pounding.simulation.monte_carlo.design_gap`` for the current case on a
        worker thread: ``records`` records seeded ``seed``, for the target
        probability of no pounding of the closed-form required gap.

        Nothing runs if the result shown is already that one.
        """
        if self.design_gap_job.running or self.snapshot is None:
            return
        case = self.snapshot.case
        if len(case.contacts) > 1:
            self.design_gap_job.status = ONE_CONTACT_STUDIES
            return
        target = self.snapshot.estimate.target_probability
        records, seed = _records_of(case, self.records), self.seed
        shown = self.current_design_gap()
        if shown is not None and (shown.n_records, shown.seed) == (records, seed):
            self.design_gap_job.status = f"Monte Carlo design gap: already computed for these inputs ({records} records, seed {seed})."
            return
        self.design_gap_job.start(partial(design_gap, case, target, records=records, seed=seed), records)


def _records_of(case, records: int) -> int:
    """The records of a study of ``case``: ``records`` synthetic ones, or each recorded motion of the case once."""
    return len(case.hazard.records) if case.recorded else records


def _study_key(case):
    """What a study with contact depends on apart from the gap (its points share one plot)."""
    return None if case is None else (case.buildings, case.excitation, tuple(dataclasses.replace(c, gap=0.0) for c in case.contacts))


def _check_key(result, seed: int):
    """What a check of the estimate ``result`` depends on: its case (synthetic records: drawn from its excitation),
    its target probability and the seed. A case of recorded motions has none (its records are not compared): it
    is checked anew."""
    case = result.case
    if case.recorded:
        return None
    return (case.buildings, case.excitation, case.contacts, result.target_probability, seed)


def _free_motion_key(case):
    """What the records' free motion, and so the design gap, depends on: not the contact law or the gap."""
    return None if case is None else (case.buildings, case.excitation, tuple((c.between, c.levels) for c in case.contacts))


def _same(a, b) -> bool:
    """Equal, floats within a rounding error (the unit round trip), through dataclasses and tuples."""
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-15)
    if dataclasses.is_dataclass(a) and type(a) is type(b):
        return all(_same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, tuple | list) and isinstance(b, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b
