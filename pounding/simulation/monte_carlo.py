"""The "exact method": nonlinear time-history analysis of the two buildings,
pounding included, over many seeded synthetic records (Monte Carlo; the
left column of the paper's Fig. 4, Eq. 10-11).
"""

from __future__ import annotations

import dataclasses
import math
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np
from scipy.special import (  # binomial CDF, Student t quantile; scipy.stats costs a second to import
    bdtr,
)

from pounding import defaults
from pounding.case.case import Case, as_case
from pounding.errors import (
    ArgumentError,
    CaseError,
    check_limit,
    check_probability,
    described,
    finite_number,
    quote,
)
from pounding.mechanics import integrator as kernel
from pounding.simulation.ground_motion import (
    check_suite_range,
    ground_motion_batches,
    record_names,
    samples_per_record,
    suite_size,
)
from pounding.simulation.plan import MonteCarloPlan, as_plan
from pounding.simulation.result import ContactPeaks, SimulationResult
from pounding.simulation.system import (
    Cancelled,
    Settings,
    check_records,
    check_study,
    failure,
    floor_index,
    kernel_system,
)

__all__ = [
    "Cancelled",
    "DesignGap",
    "MonteCarloPlan",
    "Settings",
    "SimulationResult",
    "TimeHistory",
    "design_gap",
    "design_gaps",
    "gap_from_peaks",
    "integrate",
    "records_for_bound",
    "simulate",
    "simulate_record",
]

def simulate(case: Case, plan: MonteCarloPlan | None = None, **options) -> SimulationResult:
    """Monte Carlo estimate of the extreme pounding force.

    Records ``first_record .. first_record + records - 1`` of the study seeded
    ``seed`` are generated (``excitation.record_rng``) and integrated on
    ``settings.n_workers`` threads. A case of recorded motions integrates its
    accelerograms (all of them by default, in the sorted order of their file
    names); ``seed`` does not apply.

    Parameters
    ----------
    case : Case, or a preset name or the path of a TOML file
    plan : MonteCarloPlan, optional
        How the study runs: ``records`` (``defaults.RECORDS``, or the whole suite of a recorded case, when
        None; at most ``defaults.MAX_RECORDS``), ``seed``, ``first_record``, ``settings``, ``progress``
        (called as ``progress(done, total)`` after each chunk of records) and ``cancel`` (when set, the study
        stops at the next chunk and raises :class:`Cancelled`).
    **options
        Fields of the plan given one by one: ``simulate(case, records=200, seed=1)``.

    Returns
    -------
    SimulationResult

    Raises
    ------
    SimulationError
        When a record's integration fails; names the record and the time.
    """
    plan = as_plan(plan, options)
    case = as_case(case)
    plan = plan.with_records(suite_size(case) or defaults.RECORDS)
    records, seed, first_record, settings = plan.records, plan.seed, plan.first_record, plan.settings
    progress, cancel = plan.progress, plan.cancel
    check_suite_range(case, records, first_record)
    # the records of one chunk are held at once by a thread: checked before they are drawn
    check_limit("chunk_size", min(settings.chunk_size, records) * samples_per_record(case), defaults.MAX_CHUNK_SAMPLES,
                "samples held per thread (chunk_size x samples per record)", "lower Settings.chunk_size",
                error=ArgumentError)
    system = kernel_system(case, settings)
    y0 = np.zeros(3 * system.n_floors)
    indices = np.arange(first_record, first_record + records)
    summaries = np.zeros((records, summary_columns(case)))
    chunks = [slice(start, min(start + settings.chunk_size, records)) for start in range(0, records, settings.chunk_size)]

    def run(chunk: slice) -> slice:
        if cancel is not None and cancel.is_set():
            return chunk
        rows = summaries[chunk]
        for batch, accelerations, time_step in ground_motion_batches(case, seed, indices[chunk]):
            kernel.integrate_batch(accelerations, time_step, y0, system.floors, system.below, system.contacts,
                                   system.contact_floors, settings.tolerance, system.atol, settings.displacement_limit, rows[batch])
        return chunk

    done = 0
    with ThreadPoolExecutor(max_workers=min(settings.n_workers, len(chunks))) as pool:
        futures = [pool.submit(run, chunk) for chunk in chunks]
        try:
            for future in as_completed(futures):
                chunk = future.result()
                if cancel is not None and cancel.is_set():
                    raise Cancelled("simulation cancelled")
                failed = np.flatnonzero(summaries[chunk, kernel.S_STATUS] != kernel.OK)
                if failed.size:
                    row = chunk.start + failed[0]
                    raise failure(summaries[row], record_names(case, seed, [indices[row]])[0], settings)
                done += chunk.stop - chunk.start
                if progress is not None:
                    progress(done, records)
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    peaks = contact_blocks(summaries, len(case.contacts))
    contacts = tuple(
        ContactPeaks(
            contact=contact,
            force_max=peaks[:, c, kernel.S_FORCE_MAX].copy(),
            impacts=peaks[:, c, kernel.S_IMPACTS].astype(np.int64),
            penetration_max=peaks[:, c, kernel.S_PENETRATION_MAX].copy(),
            impact_velocity_max=peaks[:, c, kernel.S_IMPACT_VELOCITY_MAX].copy(),
            displacement_max=peaks[:, c, [kernel.S_DISPLACEMENT_MAX_1, kernel.S_DISPLACEMENT_MAX_2]].copy(),
            relative_displacement_max=peaks[:, c, kernel.S_RELATIVE_MAX].copy(),
        )
        for c, contact in enumerate(case.contacts)
    )
    return SimulationResult(case=case, seed=seed, indices=indices, contacts=contacts,
                            steps=summaries[:, kernel.S_STEPS].astype(np.int64), settings=settings)


def summary_columns(case: Case) -> int:
    """Columns of the kernel's per-record summary: the record's, then a block per contact."""
    return kernel.RECORD_COLUMNS + len(case.contacts) * kernel.CONTACT_COLUMNS


def contact_blocks(summaries: np.ndarray, n_contacts: int) -> np.ndarray:
    """The per-contact blocks of kernel summaries (one row, or one per record), indexed [..., contact, S_* column]."""
    return summaries[..., kernel.RECORD_COLUMNS:].reshape(summaries.shape[:-1] + (n_contacts, kernel.CONTACT_COLUMNS))


@dataclass(frozen=True)
class DesignGap:
    """The gap for a target probability of no pounding, by Monte Carlo.

    Until the first contact the buildings move freely, so a record pounds at
    gap d exactly when its free relative displacement X = x1 - x2 at the
    contact floors exceeds d: one simulation without contact gives the
    pounding fraction at every gap.

    Attributes
    ----------
    gap : float
        Smallest gap at which at most 1 - ``target_probability`` of the
        records pound: an order statistic of ``peaks`` [m].
    upper_bound : float
        One-sided 90 % confidence bound on the gap for the target
        probability, from the binomial law of the order statistics [m];
        inf when the records are too few to give one.
    target_probability : float
        Probability of no pounding [-].
    peaks : ndarray
        Each record's peak free relative displacement [m], in record order.
    seed : int
    """

    gap: float
    upper_bound: float
    target_probability: float
    peaks: np.ndarray
    seed: int

    @property
    def n_records(self) -> int:
        return self.peaks.size

    @property
    def records_for_bound(self) -> int:
        """The fewest records that give :attr:`upper_bound` (:func:`records_for_bound`)."""
        return records_for_bound(self.target_probability)

    def pounding_fraction(self, gap: float) -> float:
        """Fraction of the records that pound at ``gap`` [m]."""
        return float(np.mean(self.peaks > gap))

    def to_dict(self) -> dict:
        """JSON-ready, SI units."""
        return {
            "design_gap": self.gap,
            "design_gap_upper_bound_90": self.upper_bound if math.isfinite(self.upper_bound) else None,
            "target_probability": self.target_probability,
            "records": self.n_records,
            "seed": self.seed,
            "peaks": self.peaks.tolist(),
            "units": {"length": "m"},
        }


def records_for_bound(target_probability: float) -> int:
    """The fewest records whose free peaks give a one-sided 90 % confidence
    bound on the gap for ``target_probability`` of no pounding: the largest of
    N peaks bounds it with confidence 1 - p^N."""
    check_probability(target_probability)
    return math.ceil(math.log(0.1) / math.log(target_probability) - 1e-9)


def design_gap(case: Case, target_probability: float = defaults.TARGET_PROBABILITY, plan: MonteCarloPlan | None = None,
               **options) -> DesignGap:
    """The gap giving ``target_probability`` of no pounding, from the free
    motion of the plan's records (when it names none: a recorded suite's records, each once, or
    ``defaults.DESIGN_GAP_RECORDS``; the case's gap is not used). ``plan`` and ``**options`` as
    :func:`simulate`'s, from record 0.

    The records are those :func:`simulate` integrates for the same ``seed``;
    at the gap returned, :func:`simulate` finds the same records pounding.
    """
    case = as_case(case)
    case.contact  # noqa: B018 -- CaseError naming ``contacts`` for several: design_gaps gives each contact's
    return design_gaps(case, target_probability, plan, **options)[0]


def design_gaps(case: Case, target_probability: float = defaults.TARGET_PROBABILITY, plan: MonteCarloPlan | None = None,
                **options) -> tuple[DesignGap, ...]:
    """Each contact's :func:`design_gap`, in the case's order, from one run of the records with every contact apart:
    until the first impact anywhere the buildings move freely, so each contact's gap is that of the free motion."""
    target_probability = check_probability(target_probability)
    case = as_case(case)
    plan = as_plan(plan, options).with_records(suite_size(case) or defaults.DESIGN_GAP_RECORDS)
    records, seed, settings = plan.records, plan.seed, plan.settings
    apart = tuple(dataclasses.replace(c, gap=2.0 * settings.displacement_limit) for c in case.contacts)
    result = simulate(dataclasses.replace(case, contacts=apart), dataclasses.replace(plan, first_record=0))
    # P(ordered[j - 1] >= true gap) = P(Binomial(records, p) <= j - 1); the first j where that reaches 0.9.
    confident = np.flatnonzero(bdtr(np.arange(records), records, target_probability) >= 0.9)
    gaps = []
    for contact in result.contacts:
        peaks = contact.relative_displacement_max
        upper = float(np.sort(peaks)[confident[0]]) if confident.size else math.inf
        gaps.append(DesignGap(gap_from_peaks(peaks, target_probability), upper, float(target_probability), peaks, seed))
    return tuple(gaps)


def gap_from_peaks(peaks, target_probability: float) -> float:
    """The smallest of the records' free peaks [m] at which at most 1 - ``target_probability`` of them pound: the
    order statistic of rank ceil(target_probability x records) (:attr:`DesignGap.gap`). A peak known only to lie
    beyond some gap may be given as inf: the gap is then inf if it depends on one."""
    ordered = np.sort(np.asarray(peaks, dtype=float))
    rank = max(1, math.ceil(target_probability * ordered.size - 1e-9))  # at most records - rank pound at ordered[rank - 1]
    return float(ordered[rank - 1])


@dataclass(frozen=True)
class TimeHistory:
    """The full response to one record, at every accepted integration step.

    Attributes
    ----------
    time : ndarray
        [s], non-uniform: the steps crowd into the impacts.
    ground_acceleration : ndarray
        [m/s^2] at ``time``.
    displacement, velocity, hysteretic : ndarray, shape (steps, floors)
        Floor displacements [m] and velocities [m/s] relative to the ground,
        storey hysteretic displacements z [m]; floors of building 1, then 2, ...
    contact_forces, penetrations : ndarray, one column per contact
        Each contact's pounding force [N] and penetration delta = x_left - x_right - gap [m].
    drift, storey_force : ndarray, shape (steps, floors)
        Storey drifts [m] and restoring forces alpha k u + (1 - alpha) k z [N]
        (Eq. 36), the hysteresis loops.
    summary : dict
        The record's peaks over all contacts (the largest force, the impacts' count) and ``contacts``: each
        contact's.
    """

    case: Case
    time: np.ndarray
    ground_acceleration: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    hysteretic: np.ndarray
    contact_forces: np.ndarray
    drift: np.ndarray
    storey_force: np.ndarray
    penetrations: np.ndarray
    summary: dict

    def floor(self, building: int, level: int) -> int:
        """Column of floor ``level`` of ``building`` (both counted from 1)."""
        return floor_index(self.case, building, level)

    @property
    def contact_force(self) -> np.ndarray:
        """The one contact's pounding force [N] (several contacts: ``contact_forces``)."""
        self.case.contact  # noqa: B018 -- CaseError naming ``contacts`` when the case has several
        return self.contact_forces[:, 0]

    @property
    def penetration(self) -> np.ndarray:
        """The one contact's penetration [m] (several contacts: ``penetrations``)."""
        self.case.contact  # noqa: B018
        return self.penetrations[:, 0]


def integrate(
    case: Case,
    ground_acceleration: np.ndarray,
    time_step: float,
    initial_state: np.ndarray | None = None,
    settings: Settings | None = None,
    label: str = "record",
) -> TimeHistory:
    """Integrate the case under a given ground-acceleration record.

    Parameters
    ----------
    case : Case, or a preset name or the path of a TOML file
        Its excitation is not used: ``ground_acceleration`` is.
    ground_acceleration : ndarray
        Samples at t = k * time_step [m/s^2].
    time_step : float
        [s]
    initial_state : ndarray, optional
        (d, v, z) of all floors; at rest by default.
    label : str
        Names the record in error messages.
    """
    case, settings = check_study(case, settings)
    time_step = finite_number("time_step", time_step, error=ArgumentError)
    if not time_step > 0:
        raise ArgumentError("time_step", f"must be > 0 s, got {quote(time_step)}")
    try:
        record = np.ascontiguousarray(ground_acceleration, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError("ground_acceleration", f"must be an array of numbers, got {described(ground_acceleration)}") from None
    if record.ndim != 1 or record.size < 2:
        raise ArgumentError("ground_acceleration", "must be a 1-D array of at least 2 samples")
    check_limit("ground_acceleration", record.size, defaults.MAX_SAMPLES_PER_RECORD, "samples", "integrate a shorter record", error=ArgumentError)
    if not np.all(np.isfinite(record)):
        raise ArgumentError("ground_acceleration", "must be finite numbers (no NaN or inf)")
    return _integrate(case, record, time_step, initial_state, settings, str(label), "ground_acceleration", ArgumentError)


def _check_history(field: str, samples: int, n_state: int, error=CaseError) -> int | None:
    """The most steps a history of ``n_state`` states may keep (None: no limit). The
    history is kept at every step, at least one per sample: MAX_HISTORY_VALUES bounds it."""
    width = n_state + 2
    check_limit(field, samples * width, defaults.MAX_HISTORY_VALUES, f"history values ({samples:,} samples x {width})",
                "integrate a shorter record", error)
    return defaults.MAX_HISTORY_VALUES // width if defaults.limits_enabled() else None


def _integrate(case: Case, record: np.ndarray, time_step: float, initial_state, settings: Settings, label: str,
               field: str, error=CaseError) -> TimeHistory:
    """:func:`integrate` on checked inputs; ``field`` (an ``error``) names the record's length in a limit's message."""
    system = kernel_system(case, settings)
    n_state = 3 * system.n_floors
    try:
        y0 = np.zeros(n_state) if initial_state is None else np.array(initial_state, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError("initial_state", f"must be an array of numbers, got {described(initial_state)}") from None
    if y0.shape != (n_state,) or not np.all(np.isfinite(y0)):
        raise ArgumentError("initial_state", f"must be {n_state} finite numbers (d, v, z of every floor), got shape {y0.shape}")
    most = _check_history(field, record.size, n_state, error)
    summary = np.zeros(summary_columns(case))
    n_contacts = len(case.contacts)
    capacity = 8 * record.size if most is None else min(8 * record.size, most)
    while True:
        time = np.empty(capacity)
        state = np.empty((capacity, n_state))
        force = np.empty((capacity, n_contacts))
        stored = kernel.integrate_record(record, time_step, y0, system.floors, system.below, system.contacts, system.contact_floors,
                                         settings.tolerance, system.atol, settings.displacement_limit, summary, time, state, force)
        if summary[kernel.S_STATUS] != kernel.HISTORY_FULL:
            break
        if most is not None and capacity >= most:
            raise error(field, f"the time history takes more than {capacity:,} steps, beyond the {defaults.MAX_HISTORY_VALUES:,} values "
                        f"kept; integrate a shorter record ({defaults.LIMITS_VARIABLE}=off lifts it)")
        capacity = capacity * 4 if most is None else min(capacity * 4, most)
    if summary[kernel.S_STATUS] != kernel.OK:
        raise failure(summary, label, settings)
    time, state, force = time[:stored], state[:stored], force[:stored]
    n = system.n_floors
    displacement, velocity, hysteretic = state[:, :n], state[:, n : 2 * n], state[:, 2 * n :]
    below_displacement = np.where(system.below >= 0, displacement[:, np.maximum(system.below, 0)], 0.0)
    drift = displacement - below_displacement
    k, alpha = system.floors[:, kernel.STIFFNESS], system.floors[:, kernel.ALPHA]
    samples = np.arange(record.size) * time_step
    return TimeHistory(
        case=case,
        time=time,
        ground_acceleration=np.interp(time, samples, record),
        displacement=displacement,
        velocity=velocity,
        hysteretic=hysteretic,
        contact_forces=force,
        drift=drift,
        storey_force=alpha * k * drift + (1.0 - alpha) * k * hysteretic,
        penetrations=(displacement[:, system.contact_floors[:, 0]] - displacement[:, system.contact_floors[:, 1]]
                      - system.contacts[:, kernel.C_GAP]),
        summary=_record_summary(case, summary),
    )


def _record_summary(case: Case, summary: np.ndarray) -> dict:
    """One record's peaks: over all contacts, as :class:`SimulationResult`'s, and each contact's (``contacts``)."""
    peaks = contact_blocks(summary, len(case.contacts))
    contacts = [{"force_max": float(p[kernel.S_FORCE_MAX]), "impacts": int(p[kernel.S_IMPACTS]),
                 "penetration_max": float(p[kernel.S_PENETRATION_MAX]), "impact_velocity_max": float(p[kernel.S_IMPACT_VELOCITY_MAX]),
                 "relative_displacement_max": float(p[kernel.S_RELATIVE_MAX])} for p in peaks]
    whole = {key: max(c[key] for c in contacts) for key in ("force_max", "penetration_max", "impact_velocity_max")}
    one = {"relative_displacement_max": contacts[0]["relative_displacement_max"]} if len(contacts) == 1 else {}
    return {**whole, "impacts": sum(c["impacts"] for c in contacts), **one, "steps": int(summary[kernel.S_STEPS]),
            "contacts": contacts}


def simulate_record(case: Case, seed: int = defaults.SEED, index: int = 0, settings: Settings | None = None) -> TimeHistory:
    """Full time histories of record ``index`` of the study seeded ``seed``
    (the same record ``simulate`` integrates under that index)."""
    case, settings = check_study(case, settings)
    _, seed, index = check_records(1, seed, index)
    check_suite_range(case, 1, index)
    _check_history("excitation.duration", samples_per_record(case), 3 * sum(b.n_storeys for b in case.buildings))
    _, records, time_step = next(ground_motion_batches(case, seed, [index]))
    return _integrate(case, records[0], time_step, None, settings, record_names(case, seed, [index])[0], "excitation.duration")
