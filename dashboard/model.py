"""The dashboard's model: the case's inputs as parameters, and what they give.

The inputs mirror the case file (README.md): they are assembled into the
file's schema, in the unit system chosen for display, and handed to
``pounding.case.case_from_dict``, so the library converts units, derives
stiffness from period and validates, and its ``CaseError`` names the field
exactly as a case file would. Every output comes from
``pounding.report.compute_snapshot`` (one linearization per change). The
reduced-sample Monte Carlo, and the Monte Carlo design gap
(``pounding.simulation.design_gap``), run on a worker thread; their progress
and results come back to the session's event loop.

No Panel here: the view (``app.py``) builds widgets from these parameters.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import threading
from concurrent.futures import ThreadPoolExecutor
from functools import partial
from typing import Callable

import param

from pounding import simulate
from pounding import defaults
from pounding.case import case_from_dict, load_case, preset_names
from pounding.contact import CONTACT_MODELS
from pounding.errors import CaseError, ConvergenceError, SimulationError
from pounding.excitation import CloughPenzien
from pounding.report import DEFAULT_SEED, MonteCarloPoint, compute_snapshot
from pounding.simulation import Cancelled, DesignGap, design_gap
from pounding.units import UNIT_SYSTEMS, unit_system

from dashboard.inputs import DIMENSIONS, MAX_STOREYS, building_params

__all__ = ["DIMENSIONS", "PoundingModel"]

_EXECUTOR = ThreadPoolExecutor(max_workers=2, thread_name_prefix="pounding-mc")
"""Shared by all sessions: at most two studies at a time (each uses every core)."""

class PoundingModel(param.Parameterized):
    """Inputs of a case (in the display unit system) and the results for it."""

    preset = param.Selector(default=defaults.CASE, objects=preset_names(), doc="A built-in case (the paper's Sections 5 and 6).")
    units = param.Selector(default="SI", objects=list(UNIT_SYSTEMS), label="units", doc="Unit system of the inputs and results.")

    locals().update(building_params(1, 1.2))
    locals().update(building_params(2, 0.4))

    level_1 = param.Integer(1, bounds=(1, MAX_STOREYS), label="contact storey of building 1", doc="Floor of building 1 that meets building 2.")
    level_2 = param.Integer(1, bounds=(1, MAX_STOREYS), label="contact storey of building 2", doc="Floor of building 2 that meets building 1.")
    gap = param.Number(0.01, label="gap", doc="Separation at rest [length].")
    contact_stiffness = param.Number(2e9, label="contact stiffness", doc="Impact stiffness [force/length^1.5], linear law [force/length].")
    restitution = param.Number(0.65, bounds=(0.0, 1.0), step=0.05, label="restitution e [-]", doc="Coefficient of restitution, 0 < e <= 1.")
    contact_model = param.Selector(default="jankowski", objects=list(CONTACT_MODELS), label="contact model")

    G0 = param.Number(6.503e-3, label="G0", doc="Two-sided white-noise intensity of the Kanai-Tajimi filter [length^2/s^3].")
    omega_g = param.Number(27.02, bounds=(1.0, 80.0), step=0.5, label="omega_g [rad/s]", doc="Ground frequency.")
    xi_g = param.Number(0.34, bounds=(0.05, 1.0), step=0.01, label="xi_g [-]", doc="Ground damping ratio.")
    duration = param.Number(20.0, bounds=(2.0, 60.0), step=1.0, label="duration [s]", doc="Record duration.")
    envelope = param.Selector(default="none", objects=["none", "shinozuka-sato"], label="envelope", doc="Stationary, or the Shinozuka-Sato envelope (Eq. 9).")
    B1 = param.Number(0.085, bounds=(0.005, 2.0), step=0.005, label="envelope B1 [1/s]", doc="Shinozuka-Sato decay constant B1 (Eq. 9), below B2.")
    B2 = param.Number(0.17, bounds=(0.01, 5.0), step=0.005, label="envelope B2 [1/s]", doc="Shinozuka-Sato decay constant B2 (Eq. 9), above B1.")

    records = param.Integer(defaults.DASHBOARD_RECORDS, bounds=(10, 500), step=10, label="records", doc="Records of the reduced-sample Monte Carlo study and of the Monte Carlo design gap.")
    seed = param.Integer(DEFAULT_SEED, bounds=(0, None), label="seed", doc="Seed of the study and of the design gap's records.")

    # --- outputs (not inputs) ---
    snapshot = param.Parameter(None, precedence=-1, doc="pounding.report.Snapshot of the current case, or None when the inputs are invalid.")
    error = param.String("", precedence=-1, doc="Why there is no snapshot (names the input).")
    mc_running = param.Boolean(False, precedence=-1)
    mc_progress = param.Integer(0, bounds=(0, 100), precedence=-1)
    mc_status = param.String("", precedence=-1)
    mc_points = param.List([], precedence=-1, doc="MonteCarloPoint of the current case (any gap).")
    design_gap_running = param.Boolean(False, precedence=-1)
    design_gap_progress = param.Integer(0, bounds=(0, 100), precedence=-1)
    design_gap_status = param.String("", precedence=-1)
    design_gap_result = param.Parameter(
        None, precedence=-1, doc="pounding.simulation.DesignGap of the current case (it holds at any gap), or None."
    )

    def __init__(self, schedule: Callable[[Callable[[], None]], None] | None = None, batch=None, **params):
        """``schedule(fn)`` runs ``fn`` on the session's event loop (default: at once);
        ``batch()`` is a context manager around each update of the outputs (the
        view batches the page's updates with it)."""
        super().__init__(**params)
        self._schedule = schedule or (lambda fn: fn())
        self._batch = batch or contextlib.nullcontext
        self._syncing = False
        self._extra_excitation: dict = {}
        self._cancel: threading.Event | None = None
        self._mc_case_key = None
        self._mc_gap: float | None = None
        self._design_gap_cancel: threading.Event | None = None
        self._design_gap_key = None
        self._load_preset()

    # --- inputs <-> case ---------------------------------------------------------

    def case_data(self) -> dict:
        """The inputs as a case file's contents (README.md schema), in ``units``."""
        buildings = []
        for b in (1, 2):
            get = lambda name: getattr(self, f"{name}_{b}")  # noqa: E731
            bouc_wen = {"alpha": get("alpha"), "A": get("A"), "beta": get("beta"), "gamma": get("gamma"), "n": get("n")}
            if get("storeys") == 1:
                storeys = [{"mass": get("mass"), "period": get("period"), "bouc_wen": bouc_wen}]
            else:
                storeys = [{"mass": get("mass"), "stiffness": get("stiffness"), "bouc_wen": dict(bouc_wen)} for _ in range(get("storeys"))]
            buildings.append({"damping_ratio": get("damping_ratio"), "storeys": storeys})
        excitation = {"G0": self.G0, "omega_g": self.omega_g, "xi_g": self.xi_g, "duration": self.duration, "envelope": self.envelope}
        excitation |= self._extra_excitation
        if self.envelope == "shinozuka-sato":
            excitation |= {"B1": self.B1, "B2": self.B2}
        return {
            "units": self.units,
            "name": self.preset,
            "description": self._description,
            "excitation": excitation,
            "buildings": buildings,
            "contact": {
                "model": self.contact_model,
                "gap": self.gap,
                "stiffness": self.contact_stiffness,
                "restitution": self.restitution,
                "levels": [self.level_1, self.level_2],
            },
        }

    def _values_from_case(self, case) -> dict:
        """Input values showing ``case`` (SI) in the current unit system."""
        u = unit_system(self.units)
        values = {}
        for b, building in enumerate(case.buildings, start=1):
            storey = building.storeys[0]
            bw = storey.bouc_wen
            values |= {
                f"storeys_{b}": building.n_storeys,
                f"period_{b}": float(building.periods[0]),
                f"mass_{b}": u.from_si(storey.mass, mass=1),
                f"stiffness_{b}": u.from_si(storey.stiffness, force=1, length=-1),
                f"damping_ratio_{b}": building.damping_ratio,
                f"alpha_{b}": bw.alpha,
                f"A_{b}": bw.A,
                f"beta_{b}": u.from_si(bw.beta, length=-bw.n),
                f"gamma_{b}": u.from_si(bw.gamma, length=-bw.n),
                f"n_{b}": bw.n,
            }
        contact = case.contact
        spectrum = case.excitation.spectrum
        values |= {
            "level_1": contact.levels[0],
            "level_2": contact.levels[1],
            "gap": u.from_si(contact.gap, length=1),
            "contact_stiffness": u.from_si(contact.stiffness, force=1, length=-contact.stiffness_exponent),
            "restitution": contact.restitution,
            "contact_model": contact.model,
            "G0": u.from_si(spectrum.G0, length=2),
            "omega_g": spectrum.omega_g,
            "xi_g": spectrum.xi_g,
            "duration": case.excitation.duration,
            "envelope": "none" if case.excitation.stationary else "shinozuka-sato",
        }
        if case.excitation.envelope is not None:
            values |= {"B1": case.excitation.envelope.B1, "B2": case.excitation.envelope.B2}
        return values

    def _load_preset(self) -> None:
        case = load_case(self.preset)
        self._description = case.description
        excitation = case.excitation
        extra = {"time_step": excitation.time_step, "cutoff_frequency": excitation.cutoff_frequency, "synthesis_factor": excitation.synthesis_factor}
        if isinstance(excitation.spectrum, CloughPenzien):
            extra |= {"spectrum": "clough-penzien", "omega_f": excitation.spectrum.omega_f, "xi_f": excitation.spectrum.xi_f}
        self._extra_excitation = extra
        self._syncing = True
        try:
            self.param.update(**self._values_from_case(case))
        finally:
            self._syncing = False
        self.recompute()

    @param.depends("preset", watch=True)
    def _on_preset(self):
        self._load_preset()

    @param.depends("units", watch=True)
    def _on_units(self):
        """Convert the dimensional inputs to the new unit system (the case is unchanged)."""
        old = unit_system(self._shown_units)
        new = unit_system(self.units)
        values = {}
        for name, dims in DIMENSIONS(self).items():
            values[name] = new.from_si(old.to_si(getattr(self, name), **dims), **dims)
        self._syncing = True
        try:
            self.param.update(**values)
        finally:
            self._syncing = False
        self.recompute()

    # --- outputs -------------------------------------------------------------------

    def build_case(self):
        """The case of the current inputs (raises CaseError naming the input)."""
        return case_from_dict(self.case_data(), name=self.preset)

    def recompute(self) -> None:
        """Recompute every output for the current inputs."""
        self._shown_units = self.units
        try:
            case = self.build_case()
            snapshot = compute_snapshot(case, seed=self.seed, monte_carlo=())
        except (CaseError, ConvergenceError, SimulationError) as error:
            with self._batch():
                self._invalidate_studies(None)
                self.param.update(snapshot=None, error=_message(error))
            return
        self._invalidate_studies(case)
        # Show the derived storey data (stiffness for one storey, period for more).
        derived = {}
        for b, building in enumerate(case.buildings, start=1):
            if building.n_storeys == 1:
                derived[f"stiffness_{b}"] = unit_system(self.units).from_si(building.storeys[0].stiffness, force=1, length=-1)
            else:
                derived[f"period_{b}"] = min(max(float(building.periods[0]), 0.05), 5.0)
        with self._batch():
            self._syncing = True
            try:
                self.param.update(**derived)
            finally:
                self._syncing = False
            self.param.update(snapshot=snapshot, error="")

    @param.depends(
        *[f"{name}_{b}" for b in (1, 2) for name in ("storeys", "period", "mass", "stiffness", "damping_ratio", "alpha", "A", "beta", "gamma", "n")],
        "level_1", "level_2", "gap", "contact_stiffness", "restitution", "contact_model",
        "G0", "omega_g", "xi_g", "duration", "envelope", "B1", "B2", "seed",
        watch=True,
    )
    def _on_input(self):
        if not self._syncing:
            self.recompute()

    # --- Monte Carlo ---------------------------------------------------------------

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
                message = _message(error)
                self._schedule(lambda: finished(cancel, None, message))
            else:
                self._schedule(lambda: finished(cancel, result, None))

        _EXECUTOR.submit(work)

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
            partial(simulate, case, records, seed), self._cancel, self._progress,
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
        """Start ``pounding.simulation.design_gap`` for the current case on a
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
            partial(design_gap, case, target, records, seed), self._design_gap_cancel, self._design_gap_progress,
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


_LABELS = {
    "period": "period", "mass": "storey mass", "stiffness": "storey stiffness", "damping_ratio": "damping ratio",
    "bouc_wen.alpha": "Bouc-Wen alpha", "bouc_wen.A": "Bouc-Wen A", "bouc_wen.beta": "Bouc-Wen beta",
    "bouc_wen.gamma": "Bouc-Wen gamma", "bouc_wen.n": "Bouc-Wen n",
}


def _message(error: Exception) -> str:
    """One line naming the input: the case file's field, then the widget's name."""
    if isinstance(error, CaseError):
        field = error.field
        parts = field.split(".")
        where = ""
        if parts[0] == "buildings" and len(parts) >= 2:
            rest = ".".join(parts[4:]) if len(parts) >= 4 and parts[2] == "storeys" else ".".join(parts[2:])
            where = f"building {parts[1]}, {_LABELS.get(rest, rest)}" if rest else f"building {parts[1]}"
        elif parts[0] == "contact":
            where = f"contact {'.'.join(parts[1:])}"
        elif parts[0] == "excitation":
            where = f"excitation {'.'.join(parts[1:])}"
        prefix = f"{where} ({field})" if where else field
        return f"Invalid input: {prefix}: {error.message}"
    return f"{type(error).__name__}: {error}"
