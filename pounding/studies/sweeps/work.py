"""The work, done on Dask workers: a chunk of Monte Carlo records reduced to
exact sums (:func:`chunk_sums`), a point's closed-form figures
(:func:`point_estimate`), and the warm-up of a worker process (:func:`warm`)."""

from __future__ import annotations

from fractions import Fraction

from pounding import defaults
from pounding.errors import CaseError


def _fraction_text(value: Fraction) -> str:
    return f"{value.numerator}/{value.denominator}"


def _case(data: dict, adjustment: dict | None):
    from pounding.case.case import case_from_dict
    from pounding.case.scaling import adjusted

    return adjusted(case_from_dict(data, name=str(data.get("name", "case"))), adjustment)


def chunk_sums(data: dict, seed: int, first: int, count: int, tolerance: float = defaults.INTEGRATOR_TOLERANCE,
               adjustment: dict | None = None) -> dict:
    """Monte Carlo over records ``first .. first + count - 1`` of one point, reduced to sums.

    Runs on one thread (a Dask worker runs one task per thread).

    Parameters
    ----------
    data : dict
        The point's case file (parsed TOML).
    seed, first, count : int
        Seed of the study, first record, number of records.
    tolerance : float
        Relative tolerance of the integrator [-].
    adjustment : dict, optional
        Applied to the loaded case (:func:`pounding.case.scaling.adjusted`: another PGA, other periods).

    Returns
    -------
    dict
        JSON-ready: ``records``; every record's F_max [N] in record order (``force_max_values``); exact sums (as ``"p/q"`` strings) of F_max
        [N], F_max^2 [N^2] and of the peak approach velocity at impact [m/s];
        the number of records with pounding and of impacts; the largest
        F_max [N] and penetration [m]. Sums of exact rationals do not depend
        on the order of addition: any chunking gives the same totals.
    """
    from pounding.simulation.monte_carlo import Settings, simulate

    case = _case(data, adjustment)
    result = simulate(case, records=count, seed=seed, settings=Settings(tolerance=tolerance, workers=1), first_record=first)
    forces = [Fraction(float(f)) for f in result.force_max]
    return {
        "first": first,
        "records": count,
        "force_sum": _fraction_text(sum(forces, Fraction(0))),
        "force_square_sum": _fraction_text(sum((f * f for f in forces), Fraction(0))),
        "impact_velocity_sum": _fraction_text(sum((Fraction(float(v)) for v in result.impact_velocity_max), Fraction(0))),
        "pounding_records": int((result.impacts > 0).sum()),
        "impacts": int(result.impacts.sum()),
        "force_max": float(result.force_max.max()),
        "penetration_max": float(result.penetration_max.max()),
        "force_max_values": [float(f) for f in result.force_max],
    }


def point_estimate(data: dict, adjustment: dict | None = None) -> dict:
    """The closed-form figures of one point (``pounding.closed_form.estimator.estimate``), JSON-ready, SI.

    An estimate that cannot be made (e.g. a record too short for Davenport's
    peak factor) gives None figures and its reason in ``warnings``. A case of several contacts gives the largest
    force over all contacts, the probability that any pounds, the impacts of all, the widest of the contacts' gaps
    for the target and the governing contact's sigma_X; the paper's force is None (its method has one contact).
    """
    from pounding.closed_form.estimator import estimate
    from pounding.errors import ConvergenceError

    case = _case(data, adjustment)
    try:
        result = estimate(case)
    except (CaseError, ConvergenceError) as error:
        return {"force": None, "paper_force": None, "pounding_probability": None, "impacts": None,
                "required_gap": None, "sigma_relative_displacement": None, "warnings": [f"estimate failed: {error}"]}
    if len(result.contacts) > 1:
        return {
            "force": result.force_expected,
            "paper_force": None,
            "pounding_probability": result.pounding_probability,
            "impacts": sum(c.impacts_expected for c in result.contacts),
            "required_gap": max(c.required_gap for c in result.contacts),
            "sigma_relative_displacement": result.contacts[result.governing].sigma_relative_displacement,
            "warnings": list(result.warnings),
        }
    return {
        "force": result.force_expected,
        "paper_force": result.paper.force_expected,
        "pounding_probability": result.pounding_probability,
        "impacts": result.impacts_expected,
        "required_gap": result.required_gap,
        "sigma_relative_displacement": result.sigma_relative_displacement,
        "warnings": list(result.warnings),
    }


_WARM = False


def warm(data: dict, adjustment: dict | None = None) -> None:
    """Load the numba kernels in this process once (about 1 s from the disk cache)."""
    global _WARM
    if not _WARM:
        try:
            point_estimate(data, adjustment)
            chunk_sums(data, 0, 0, 1, defaults.INTEGRATOR_TOLERANCE, adjustment)
        except Exception:  # noqa: BLE001  warming is best effort: the task itself will report the error
            return
        _WARM = True
