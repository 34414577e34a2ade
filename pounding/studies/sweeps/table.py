"""The sweep's table: each point's chunks added up exactly, the Monte Carlo
summary, and the table written as CSV or Parquet."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

from pounding.errors import ArgumentError
from pounding.output import write_atomic
from pounding.studies.sweeps.points import Point
from pounding.studies.sweeps.store import FIELD, Store


def totals(point: Point, chunks: list[tuple[int, int]], store: Store) -> dict:
    """The chunks' sums added up, exactly."""
    n = pounding = impacts = 0
    force = square = velocity = Fraction(0)
    force_max = penetration_max = 0.0
    for first, count in chunks:
        chunk = store.chunk(point, first, count)
        n += chunk["records"]
        force += Fraction(chunk["force_sum"])
        square += Fraction(chunk["force_square_sum"])
        velocity += Fraction(chunk["impact_velocity_sum"])
        pounding += chunk["pounding_records"]
        impacts += chunk["impacts"]
        force_max = max(force_max, chunk["force_max"])
        penetration_max = max(penetration_max, chunk["penetration_max"])
    return dict(n=n, force=force, square=square, velocity=velocity, pounding=pounding, impacts=impacts,
                force_max=force_max, penetration_max=penetration_max)


def monte_carlo_summary(totals: dict) -> dict:
    """Mean, standard error and 95 % CI of F_max [N] from exact sums (see :func:`chunk_sums`).

    The mean is the exact mean correctly rounded; the variance is formed
    exactly, so there is no cancellation in sum(F^2) - sum(F)^2 / n.
    """
    from scipy.special import stdtrit

    n = totals["n"]
    mean = totals["force"] / n
    if n >= 2:
        variance = (totals["square"] - totals["force"] * mean) / (n - 1)
        std_error = math.sqrt(float(variance / n))
        half = float(stdtrit(n - 1, 0.975)) * std_error
    else:
        std_error = half = math.inf
    mean = float(mean)
    return {
        "mc_force_mean_N": mean,
        "mc_force_std_error_N": std_error,
        "mc_force_ci_low_N": mean - half,
        "mc_force_ci_high_N": mean + half,
        "mc_force_max_N": totals["force_max"],
        "mc_pounding_fraction": totals["pounding"] / n,
        "mc_impacts_mean": totals["impacts"] / n,
        "mc_impact_velocity_mean_m_s": float(totals["velocity"] / n),
        "mc_penetration_max_m": totals["penetration_max"],
    }


def table(points: list[Point], paths: list[str], chunks, store: Store, records: int, seed: int):
    import pandas as pd

    def number(value):
        return math.nan if value is None else value

    rows = []
    for point in points:
        estimate = store.estimate(point)
        rows.append({
            "point": point.index,
            **dict(zip(paths, point.values)),
            "records": records,
            "seed": seed,
            "estimate_force_N": number(estimate["force"]),
            "paper_force_N": number(estimate["paper_force"]),
            "estimate_pounding_probability": number(estimate["pounding_probability"]),
            "estimate_impacts": number(estimate["impacts"]),
            "required_gap_m": number(estimate["required_gap"]),
            "sigma_relative_displacement_m": number(estimate["sigma_relative_displacement"]),
            **monte_carlo_summary(totals(point, chunks, store)),
            "estimate_warnings": "; ".join(estimate["warnings"]),
            "key": point.key,
        })
    return pd.DataFrame(rows)


def need_parquet() -> None:
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise ArgumentError("table_format", "parquet needs pyarrow (python -m pip install pyarrow); or use csv") from None


def write_table(table, path: Path, table_format: str) -> None:
    import io

    if table_format == "csv":
        write_atomic(path, table.to_csv(index=False), FIELD, make_parents=True)
    else:
        buffer = io.BytesIO()
        table.to_parquet(buffer, index=False)
        write_atomic(path, buffer.getvalue(), FIELD, make_parents=True)
