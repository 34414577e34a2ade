"""Why the recommended estimator is low for pairs that both yield: the numbers.

Reproduces the diagnosis in ``validation/HISTORY.md`` ("Where it is low"). For
each case, the buildings are simulated *without contact* (gap 10 m), 200
records of 100 s (seed 7), and compared after the first 10 s with the
statistically linearized pair the estimators stand on:

- the standard deviations of the contact floors' displacements x1, x2, of
  the relative displacement X = x1 - x2 and velocity V = v1 - v2, and the
  correlation of x1 and x2;
- the kurtosis of V, v1 and v2 (3 for a Gaussian process, which the
  linearized pair is);
- the fraction of upcrossings of the gap by X whose velocity exceeds
  r sigma_V, against Rice's Rayleigh law exp(-r^2 / 2).

    python3 -m validation.yielding_pairs            # about 1 min on 2 cores
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pounding import load_case, simulate_record
from pounding.closed_form.pair import LinearizedPair

from .sizes import first

CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.4", "section6-T2-0.8")
RECORDS, DURATION, SKIP, SEED, STEP = 200, 100.0, 10.0, 7, 0.002  # [-], [s], [s], [-], [s]
LEVELS = (1.5, 2.0, 2.5, 3.0)  # crossing velocities, in sigma_V


def kurtosis(a: np.ndarray) -> float:
    a = a - a.mean()
    return float(np.mean(a**4) / np.mean(a**2) ** 2)


def diagnose(name: str, records: int = RECORDS, duration: float = DURATION) -> None:
    """The table of the case ``name``: ``records`` records of ``duration`` [s] without contact."""
    case = load_case(name)
    gap = case.contact.gap
    free = replace(case.with_contact(gap=10.0), excitation=replace(case.excitation, duration=duration))
    first = free.contact.levels[0] - 1
    second = free.buildings[0].n_storeys + free.contact.levels[1] - 1
    times = np.arange(SKIP, duration, STEP)
    x1, x2, v1, v2, crossing_velocities = [], [], [], [], []
    for index in range(records):
        history = simulate_record(free, SEED, index)
        columns = [np.interp(times, history.time, values[:, floor]) for values in (history.displacement, history.velocity) for floor in (first, second)]
        d1, d2, u1, u2 = columns
        relative = d1 - d2
        up = np.flatnonzero((relative[:-1] < gap) & (relative[1:] >= gap))
        crossing_velocities.extend((u1 - u2)[up + 1])
        for store, values in zip((x1, x2, v1, v2), columns):
            store.append(values[::25])  # every 50 ms for the moments
    x1, x2, v1, v2 = (np.concatenate(s) for s in (x1, x2, v1, v2))
    X, V = x1 - x2, v1 - v2
    crossing_velocities = np.asarray(crossing_velocities)

    covariance = LinearizedPair.of(free).covariance_history(np.array([0.0, duration]), modulation="ground")[-1]
    lin = {
        "x1": np.sqrt(covariance[0, 0]), "x2": np.sqrt(covariance[1, 1]),
        "X": np.sqrt(covariance[0, 0] + covariance[1, 1] - 2 * covariance[0, 1]),
        "V": np.sqrt(covariance[2, 2] + covariance[3, 3] - 2 * covariance[2, 3]),
        "rho": covariance[0, 1] / np.sqrt(covariance[0, 0] * covariance[1, 1]),
    }
    mc = {"x1": x1.std(), "x2": x2.std(), "X": X.std(), "V": V.std(), "rho": np.corrcoef(x1, x2)[0, 1]}
    print(f"\n{name} (gap {100 * gap:g} cm), Monte Carlo without contact / linearized:")
    for key, label, scale, unit in [("x1", "sigma x1", 100, "cm"), ("x2", "sigma x2", 100, "cm"), ("X", "sigma X", 100, "cm"),
                                    ("V", "sigma V", 100, "cm/s"), ("rho", "corr(x1, x2)", 1, "")]:
        print(f"  {label:13s} {scale * mc[key]:7.3f} / {scale * lin[key]:7.3f} {unit:5s} ({mc[key] / lin[key] - 1:+.1%})")
    print(f"  kurtosis of V {kurtosis(V):.2f}, of v1 {kurtosis(v1):.2f}, of v2 {kurtosis(v2):.2f} (Gaussian: 3)")
    sigma_v = V.std()
    tail = ", ".join(f"{r:g}: {np.mean(crossing_velocities > r * sigma_v):.4f} / {np.exp(-0.5 * r * r):.4f}" for r in LEVELS)
    print(f"  upcrossings of the gap faster than r sigma_V, Monte Carlo / Rayleigh: {tail} ({crossing_velocities.size} crossings)")


def main(cases: int | None = None, records: int = RECORDS, duration: float = DURATION) -> None:
    """The tables of the first ``cases`` of :data:`CASES` (all for None), ``records`` records of ``duration`` [s]."""
    for name in first(CASES, cases):
        diagnose(name, records, duration)


if __name__ == "__main__":
    main()
