"""Where an estimate lies among the regimes in which the recommended
estimator's accuracy was measured against Monte Carlo, what was measured
there, and the warnings it carries (docs/accuracy.md; the residual's share: docs/theory.md, G26).

The measured numbers are read from ``pounding/data/accuracy.json``, which
``validation/accuracy_data.py`` writes (with its seeds, cases and commit).

The thresholds below decide the regime, and so the accuracy statement and
the warnings an estimate carries. They were chosen by looking at Monte Carlo
results (the force formula itself has no fitted constant); docs/theory.md,
"Constants chosen by looking at Monte Carlo results", says which draw and
which value before.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np

from pounding.hazard.excitation import CloughPenzien
from pounding.mechanics.contact import undamped_peak_force
from pounding.units import STANDARD_GRAVITY

__all__ = [
    "CHECK_ADVICE",
    "ROW_KINDS",
    "without_check_advice",
    "error_span",
    "row_kind",
    "row_measured_range",
    "CUTOFF_SHARE_LIMIT",
    "FORCE_WEIGHT_LIMIT",
    "MODERATE_GAP",
    "SOFT_CONTACT_LIMIT",
    "MOVING_TOGETHER",
    "NARROW_BAND_LIMIT",
    "REGIMES",
    "RESIDUAL_SHARE_LIMIT",
    "Assessment",
    "MeasuredRange",
    "accuracy_band",
    "accuracy_data",
    "accuracy_regime",
    "assess",
    "force_entry_key",
    "force_table",
    "extreme_warnings",
    "hazard_warnings",
    "measured_range",
]

MODERATE_GAP = 0.5
"""gap / sigma_X above which pounding is no longer frequent [-]. Chosen by looking at Monte Carlo results: set
on the grid and draws 2026-2027, where the yielding pairs' heavier-than-Gaussian tail starts to show; checked on
draw 2028. No earlier value."""
NARROW_BAND_LIMIT = 0.55
"""Bandwidth q of X below which the relative motion counts as narrow band [-]. Chosen by looking at Monte Carlo
results: 0.35 before (three elastic pairs of close periods), raised to 0.55 on the grid and draws 2026-2027,
where errors over 10 % reached q = 0.55; checked on draw 2028."""
RESIDUAL_SHARE_LIMIT = 0.2
"""Share the residual's response adds to sigma_X or sigma_V above which it counts as large [-]. Chosen by
looking at Monte Carlo results: set on the grid and draws 2026-2027, where the errors of storeys near
elastic-perfectly plastic grew past 10 %; checked on draw 2028. No earlier value."""
MOVING_TOGETHER = 0.9
"""Correlation of the contact floors' x1, x2 from which a yielding pair's design gap was measured unsafe [-].
Chosen by looking at Monte Carlo results: set on draw 2026, where every unsafe pair lay at 0.92 or above; held
on draws 2027 and 2028 and on the pairs of tests/test_estimator_accuracy.py. No earlier value."""

REGIMES = ("frequent", "moderate gap", "narrow band", "large residual", "rare")

# --- extreme inputs (docs/accuracy.md, "Extreme inputs") ---------------------------------------------------
CUTOFF_SHARE_LIMIT = 0.01
"""Share of the linearized sigma_V^2 above the records' cutoff beyond which an estimate warns [-] (sigma_X^2
loses less): the estimate is cut there too, but that cut was measured -19 % to +7,900 % off (docs/accuracy.md)."""
SOFT_CONTACT_LIMIT = 1.0
"""Penetration of the undamped impact at the expected largest approach speed, in sigma_X, beyond which the
contact counts as soft [-]: the estimate takes an impact as a short shock. The measured cases reach 0.56; on
the Section 5 pair with softer contacts the estimate was +34 % to +630 % off beyond 1 (docs/accuracy.md)."""
FORCE_WEIGHT_LIMIT = 1000.0
"""Force over the lighter colliding floor's weight beyond which an estimate warns [-]: the measured cases and
the presets reach 24, and no building takes a thousand times a floor's weight."""


def accuracy_regime(gap: float, sigma_x: float, residual_share: float, bandwidth: float) -> str:
    """Which of :data:`REGIMES` ``gap`` [m] lies in: the first that applies of
    rare pounding (gap > sigma_X [m], with the residual's response: the oldest
    boundary, sigma_X being X's own scale, kept after looking at Monte Carlo
    results, docs/theory.md), a large
    residual (``residual_share`` over :data:`RESIDUAL_SHARE_LIMIT`), a narrow
    band (``bandwidth`` q of X below :data:`NARROW_BAND_LIMIT`), a moderate gap
    (gap > sigma_X / 2), else frequent pounding."""
    if gap > sigma_x:
        return "rare"
    if residual_share > RESIDUAL_SHARE_LIMIT:
        return "large residual"
    if bandwidth < NARROW_BAND_LIMIT:
        return "narrow band"
    if gap > MODERATE_GAP * sigma_x:
        return "moderate gap"
    return "frequent"


SIGNABLE_ERROR = 0.30
"""The widest error [-] a measured range may span, either side, to be printed as an estimate's accuracy without a Monte
Carlo verdict beside it (issue 32): a wider range sizes no gap or connection. Beyond it the estimate says how often it
was within 10 % and that the case needs its Monte Carlo check; with the check (``estimate --check``, the report, the
dashboard) the range is printed in full."""


GRID_LOOP_SHARE = 1.5
"""The smallest loop shape beta_share = beta / (beta + gamma) [-] of the accuracy grid's yielding storeys (Section 6's
beta = -3 gamma; Section 5's is 2). A yielding storey below it (Wen's symmetric 0.5, the default of a storey given by
its yield drift, or 1) takes its measured accuracy from the cases of such storeys (accuracy.json's "other loops": the
grid's storeys given the engineer's way, pounding.studies.storey_grid, and validation/storey_accuracy.py's draws).
The value is the grid's own: no Monte Carlo result chose it."""


def other_loop(case) -> bool:
    """Whether a yielding storey of ``case`` has a loop outside the grid's (beta_share below :data:`GRID_LOOP_SHARE`)."""
    for building in case.buildings:
        for storey in building.storeys:
            law = storey.bouc_wen
            if law.alpha < 1.0 and law.beta + law.gamma > 0 and law.beta / (law.beta + law.gamma) < GRID_LOOP_SHARE:
                return True
    return False


def _signable(low: float, high: float) -> bool:
    """Whether a range of errors [-] lies within :data:`SIGNABLE_ERROR` either side."""
    return -SIGNABLE_ERROR <= low and high <= SIGNABLE_ERROR


@lru_cache(maxsize=1)
def accuracy_data() -> dict:
    """The measured accuracy (``pounding/data/accuracy.json``), read once."""
    return json.loads(resources.files("pounding").joinpath("data/accuracy.json").read_text())


@dataclass(frozen=True)
class Assessment:
    """What an estimate says of its own accuracy.

    Attributes
    ----------
    regime : str
        One of :data:`REGIMES`.
    measured_accuracy : str
        How far from Monte Carlo the recommended force was measured on cases like this one (one sentence).
    warnings : tuple of str
        What is wrong, how large the error can be, what to do (each at most 200 characters).
    accuracy : MeasuredRange
        The numbers behind ``measured_accuracy``.
    """

    regime: str
    measured_accuracy: str
    warnings: tuple[str, ...]
    accuracy: MeasuredRange


def force_entry_key(table: str, regime: str, yielding: bool) -> str:
    """The key of accuracy.json's ``force[table]`` a case of ``regime`` counts in: rare pounding split by whether a
    storey yields, the Clough-Penzien gap below sigma_X as one, else the regime."""
    if regime == "rare":
        return "rare, yielding" if yielding else "rare, elastic"
    return "gap below sigma_X" if table == "clough-penzien" else regime


def _force_entry(spectrum: str, regime: str, yielding: bool) -> dict:
    """accuracy.json's ``force`` entry of a table (``spectrum``) and regime; where the "other loops" or the "recorded
    suites" table has no case of that regime, the Kanai-Tajimi one."""
    entry = accuracy_data()["force"][spectrum][force_entry_key(spectrum, regime, yielding)]
    if spectrum in ("other loops", "recorded suites") and not entry["cases"]:
        return _force_entry("kanai-tajimi", regime, yielding)
    return entry


@dataclass(frozen=True)
class MeasuredRange:
    """How far the recommended E[F_max] was measured from Monte Carlo on cases like one (``pounding/data/accuracy.json``,
    :func:`measured_range`): the error, closed form / Monte Carlo - 1, from ``low`` to ``high`` [-].

    Attributes
    ----------
    regime : str
        One of :data:`REGIMES`, or "moving alike" (two buildings that never pound: F_max = 0 exactly, ``low`` =
        ``high`` = 0).
    low, high : float
        The smallest and the largest error measured there [-]; ``low`` = -1 where the closed form gave 0 and the records
        pounded.
    cases, within_10_percent : int
        Cases measured there, and how many of them within 10 %.
    where : str
        Where that is, in words ("where pounding is frequent").
    median_abs_error : float
        The median of ``|error|`` there [-].
    """

    regime: str
    low: float
    high: float
    cases: int
    within_10_percent: int
    where: str = ""
    median_abs_error: float = 0.0

    def band(self, force):
        """Where the Monte Carlo mean lay for a closed-form E[F_max] ``force`` [N] (a number or an array), given
        the errors measured: ``force / (1 + high)`` to ``force / (1 + low)`` [N]; the upper edge is inf where
        ``low`` is -1 (nothing bounds the records' mean from above)."""
        force = np.asarray(force, dtype=float)
        upper = force / (1.0 + self.low) if self.low > -1.0 else np.full(force.shape, math.inf)
        return force / (1.0 + self.high), upper

    def to_dict(self) -> dict:
        """JSON-ready: the regime and the range of closed form / Monte Carlo - 1 [-]."""
        return {"regime": self.regime, "low": self.low, "high": self.high}

    @property
    def signable(self) -> bool:
        """Whether the range lies within :data:`SIGNABLE_ERROR` either side."""
        return _signable(self.low, self.high)

    def statement(self, with_verdict: bool = False) -> str:
        """The estimate's one sentence (``Estimate.measured_accuracy``): the range where it is :attr:`signable` or a
        Monte Carlo verdict stands beside it (``with_verdict``); otherwise how often it was within 10 % and that
        this case needs its check."""
        if with_verdict or self.signable:
            return (f"Measured {error_span(self)} off Monte Carlo {self.where} (within 10 % on {self.within_10_percent} "
                    f"of {self.cases} cases).")
        return (f"Within 10 % of Monte Carlo on {self.within_10_percent} of {self.cases} cases {self.where} (median "
                f"{100 * self.median_abs_error:.0f} %), more than {100 * SIGNABLE_ERROR:.0f} % off on some: check this "
                "case against Monte Carlo.")


def _spectrum(pair) -> str:
    """The spectrum's kind as accuracy.json names it: "clough-penzien" or "kanai-tajimi"."""
    return "clough-penzien" if isinstance(pair.case.excitation.spectrum, CloughPenzien) else "kanai-tajimi"


def force_table(case, yielding: bool) -> str:
    """The table of accuracy.json's ``force`` a case reads (``yielding``: whether a storey yields): "recorded suites"
    for recorded motions, "other loops" for a yielding storey outside the grid's loops (:func:`other_loop`), else its
    spectrum's ("clough-penzien" or "kanai-tajimi")."""
    if case.recorded:
        return "recorded suites"
    if yielding and other_loop(case):
        return "other loops"
    return "clough-penzien" if isinstance(case.excitation.spectrum, CloughPenzien) else "kanai-tajimi"


def measured_range(pair, gap: float | None = None, sigma_x: float | None = None) -> MeasuredRange:
    """The measured accuracy of the recommended E[F_max] of a :class:`~pounding.closed_form.pair.LinearizedPair` at
    ``gap`` [m] (default the case's), ``sigma_x`` [m] the relative displacement's with the residual's response
    (default the pair's): the regime :func:`accuracy_regime` places it in and that regime's row of accuracy.json.
    The numbers behind ``Estimate.measured_accuracy``, and behind a curve's band at each of its points."""
    if pair.moves_alike:
        return MeasuredRange("moving alike", 0.0, 0.0, 0, 0, "where the buildings move alike (no pounding, exactly)")
    gap = pair.case.contact.gap if gap is None else float(gap)
    sigma_x = pair.response_with_residual.sigma_relative_displacement if sigma_x is None else sigma_x
    spectrum = force_table(pair.case, pair.yielding)
    regime = accuracy_regime(gap, sigma_x, pair.residual_share, pair.bandwidth)
    entry = _force_entry(spectrum, regime, pair.yielding)
    if spectrum == "other loops":  # measured on the storeys given the engineer's way, under any spectrum
        where = _WHERE[regime] + ", on storey loops like these"
    elif spectrum == "recorded suites":  # measured on generated and real suites, against their own records
        where = _WHERE[regime] + ", on recorded suites"
    else:
        where = _WHERE[regime] + (" under a Clough-Penzien spectrum" if spectrum == "clough-penzien" else "")
    return MeasuredRange(regime, float(entry["low"]), float(entry["high"]), int(entry["cases"]),
                         int(entry["within_10_percent"]), where, float(entry["median_abs_error"]))


ROW_KINDS = ("aligned floors", "unequal heights", "three in a row")
"""The kinds of cases of several contacts whose largest force was measured (accuracy.json's ``force["several
contacts"]``, :mod:`pounding.studies.row_grid`)."""
_ROW_WHERE = {
    "aligned floors": "on two buildings meeting at every floor they share",
    "unequal heights": "on a taller building meeting a shorter one at several floors",
    "three in a row": "on rows of three buildings",
}


def row_kind(case) -> str:
    """The kind of a case of several contacts (:data:`ROW_KINDS`): three or more buildings are a row; two of the same
    storeys meeting floor to floor, aligned floors; any other two, unequal heights."""
    if len(case.buildings) > 2:
        return "three in a row"
    aligned = all(c.levels[0] == c.levels[1] for c in case.contacts)
    same = case.buildings[0].n_storeys == case.buildings[1].n_storeys
    return "aligned floors" if aligned and same else "unequal heights"


def row_measured_range(case, each_contact: bool = False) -> MeasuredRange:
    """The measured accuracy of the largest force over all contacts of a case of several contacts (``each_contact``:
    of each contact's force): its kind's row of accuracy.json's ``force["several contacts"]`` (``force["several
    contacts, each contact"]``)."""
    kind = row_kind(case)
    table = "several contacts, each contact" if each_contact else "several contacts"
    entry = accuracy_data()["force"][table][kind]
    where = ("at each contact " if each_contact else "") + _ROW_WHERE[kind]
    return MeasuredRange(kind, float(entry["low"]), float(entry["high"]), int(entry["cases"]), int(entry["within_10_percent"]),
                         where, float(entry["median_abs_error"]))


def accuracy_band(force, ranges) -> tuple[np.ndarray, np.ndarray]:
    """A closed-form curve's band of measured accuracy: at each point, :meth:`MeasuredRange.band` of its ``force``
    [N] by its own :class:`MeasuredRange` (``ranges``, one a point: the regime may change along a curve)."""
    force = np.asarray(force, dtype=float).ravel()
    if len(ranges) != force.size:
        raise ValueError(f"{len(ranges)} measured ranges for {force.size} points")
    edges = np.array([r.band(f) for f, r in zip(force, ranges)], dtype=float).reshape(force.size, 2)
    return edges[:, 0], edges[:, 1]


_SPREAD = "the RMS relative displacement"
"""sigma_X in words, as every text the user reads says it (the symbols are docs/theory.md's)."""
_WHERE = {
    "frequent": "where pounding is frequent",
    "moderate gap": f"where the gap is 0.5 to 1 times {_SPREAD}",
    "narrow band": "where the buildings sway at nearly one frequency",
    "large residual": "where storeys are near elastic-perfectly plastic",
    "rare": f"where the gap exceeds {_SPREAD}",
}
CHECK_ADVICE = "Check it with `pounding estimate --check`."
"""The advice of a warning where the closed form may be off: the Monte Carlo of the same case, beside it
(the dashboard's headline, dashboard/headline.py, says it in the page's terms)."""


def without_check_advice(warning: str) -> str:
    """``warning`` without :data:`CHECK_ADVICE`: where the Monte Carlo check stands beside it already."""
    return warning.replace(CHECK_ADVICE, "").strip()


def assess(pair, gap: float, sigma_x: float, required_gap: float, target_probability: float) -> Assessment:
    """The regime, measured accuracy and warnings of an estimate on a
    :class:`~pounding.closed_form.pair.LinearizedPair` at ``gap`` [m], ``sigma_x`` [m]
    the relative displacement's with the residual's response, and the gap it
    gives for ``target_probability`` [m]."""
    spectrum = _spectrum(pair)
    yielding, share, bandwidth = pair.yielding, pair.residual_share, pair.bandwidth
    measured = measured_range(pair, gap, sigma_x)
    regime = measured.regime
    warnings = []
    if spectrum == "clough-penzien" and yielding:
        drift = accuracy_data()["required_gap"]["clough-penzien, yielding"]
        warnings.append("A building yields and the spectrum has no low frequencies: the estimate misses its plastic "
                        f"drift; up to {100 * drift['max']:.0f} % of records pounded at the gap for 95 %. {CHECK_ADVICE}")
    table = force_table(pair.case, pair.yielding)
    if share > RESIDUAL_SHARE_LIMIT:
        warnings.append(f"Storeys near elastic-perfectly plastic sway {100 * share:.0f} % more than their linear equivalent: the "
                        f"force may be off by {_bounded_span(_force_entry(table, 'large residual', yielding))}. {CHECK_ADVICE}")
    if bandwidth < NARROW_BAND_LIMIT:
        warnings.append("The buildings sway at nearly one frequency: the force may be off by "
                        f"{_bounded_span(_force_entry(table, 'narrow band', yielding))}. {CHECK_ADVICE}")
    if MODERATE_GAP * sigma_x < gap <= sigma_x:
        warnings.append(f"The gap is 0.5 to 1 times {_SPREAD}: the force may be off by "
                        f"{_bounded_span(_force_entry(table, 'moderate gap', yielding))}. {CHECK_ADVICE}")
    if gap > sigma_x:
        warnings.append(f"Only the largest swings close this gap (it exceeds {_SPREAD}): the force may be off by "
                        f"{_bounded_span(measured)}. {CHECK_ADVICE}")
    if required_gap > sigma_x:  # where pairs like this one were measured to pound more often than 1 - 0.95
        warning = _required_gap_warning(pair, spectrum, yielding, target_probability)
        if warning:
            warnings.append(warning)
    return Assessment(regime, measured.statement(), tuple(warnings), measured)


def _required_gap_warning(pair, spectrum: str, yielding: bool, target_probability: float) -> str:
    """The warning on the gap for the target probability where, on pairs like this one (by spectrum, yielding
    and, for yielding pairs under Kanai-Tajimi, whether the floors move together: :data:`MOVING_TOGETHER`), more
    than 5 % of simulated records pounded on average at the gap given for 95 %; "" elsewhere."""
    correlation = pair.stationary_response.correlation_displacement
    kind = f"{spectrum}, {'yielding' if yielding else 'elastic'}"
    together = spectrum == "kanai-tajimi" and yielding and correlation >= MOVING_TOGETHER
    measured = accuracy_data()["required_gap"][kind + (", floors moving together" if together else "")]
    if measured["mean"] <= 0.05:
        return ""  # on average no more records pounded than the target allows
    cause = f", and the floors move together (correlation {correlation:.2f})" if together else ""
    return (f"The gap for {100 * target_probability:.8g} % lies in the motion's tail{cause}: up to {100 * measured['max']:.0f} % "
            f"of records pounded at such a gap for 95 %. Use `pounding simulate --design-gap {target_probability:.8g}`.")


def error_span(entry: dict | MeasuredRange) -> str:
    """A measured range of errors (accuracy.json's entry, or a :class:`MeasuredRange`) as the estimate prints it:
    ``-19 % to +13 %``."""
    low, high = (entry["low"], entry["high"]) if isinstance(entry, dict) else (entry.low, entry.high)
    return f"{100 * low:+,.0f} % to {100 * high:+,.0f} %"


def _bounded_span(entry: dict | MeasuredRange) -> str:
    """:func:`error_span` where the range lies within :data:`SIGNABLE_ERROR` either side, else "more than 30 %": a warning
    prints no wider range (the Monte Carlo check gives this case's own error)."""
    low, high = (entry["low"], entry["high"]) if isinstance(entry, dict) else (entry.low, entry.high)
    return error_span(entry) if _signable(low, high) else f"more than {100 * SIGNABLE_ERROR:.0f} %"


def extreme_warnings(pair, force: float, paper_force: float | None, velocity: float, sigma_x: float) -> tuple[str, ...]:
    """The warnings of an estimate on a :class:`~pounding.closed_form.pair.LinearizedPair` whose inputs lie beyond what it
    was measured on: records cut below the motion's own frequencies, a contact too soft for short impacts, a
    force no building takes. ``force``, ``paper_force`` [N], ``velocity`` the expected largest approach
    speed [m/s], ``sigma_x`` [m] with the residual's response."""
    case, warnings = pair.case, []
    share = float(pair.cutoff_shares[5])  # of the linearized sigma_V^2, which loses more than sigma_X^2 (w^2 G_X)
    measured = accuracy_data()["extreme_inputs"]
    if share > CUTOFF_SHARE_LIMIT:
        cuts = (measured["cutoff_above_frequencies"], measured["cutoff_below_frequencies"])  # either side of the modes
        either = {"low": min(c["low"] for c in cuts), "high": max(c["high"] for c in cuts)}
        warnings.append(f"The records stop at {case.excitation.cutoff_frequency:.3g} rad/s, cutting {100 * share:.0f} % of the "
                        f"relative velocity's power: the force may be off by {_bounded_span(either)}. {CHECK_ADVICE}")
    contact = case.contact
    if velocity > 0.0:
        impact = float(undamped_peak_force(contact, velocity, case.reduced_mass))
        penetration = (impact / contact.stiffness) ** (1.0 / contact.stiffness_exponent) / sigma_x
        if penetration > SOFT_CONTACT_LIMIT:
            warnings.append(f"The contact is soft: the largest impact would penetrate {penetration:.2g} times {_SPREAD}; "
                            f"measured {_bounded_span(measured['soft_contact'])} off, more if softer. {CHECK_ADVICE}")
    weight = min(case.contact_masses) * STANDARD_GRAVITY
    largest = max(force, paper_force or 0.0)
    if largest > FORCE_WEIGHT_LIMIT * weight:
        warnings.append(f"The force is {largest / weight:.2g} times the lighter colliding floor's weight: no building takes "
                        "that, and the model knows no failure. Check the contact stiffness and the ground motion's intensity.")
    return tuple(warnings)


def hazard_warnings(case) -> tuple[str, ...]:
    """The warnings of a recorded case on the spectrum fitted to its records: the closed form's process off the
    records' mean Sa or PGA by more than 10 % (S8, :mod:`pounding.hazard.fit_quality`), a Kanai-Tajimi or
    Clough-Penzien description that stops on a bound of its range (R5), and the measured error of the closed
    form's gap on recorded suites (unsafe on yielding pairs, accuracy.json: the gap is the Monte Carlo's to give)."""
    if not case.recorded:
        return ()
    from pounding.case.engineering import fundamental_periods

    motions, warnings = case.hazard, []
    if motions.suite is not None:
        warnings.append(motions.fit_quality(fundamental_periods(case)).warning())
    warnings.append(motions.fitted.bound_warning())
    measured = accuracy_data()["extreme_inputs"]["recorded_suite_gap"]
    warnings.append(f"The closed-form gap for recorded motions was measured {_bounded_span(measured)} off the records' own. "
                    "Use `pounding simulate --design-gap 0.95`.")
    return tuple(warning for warning in warnings if warning)
