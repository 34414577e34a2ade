"""Fragility curves and force spectra, closed form against Monte Carlo (issue 23).

Prints, for a few cases and capacities, P(F_max > capacity) at each PGA (closed form, Monte Carlo with its
Wilson interval, the difference) and both lognormal fits; and the force spectra E[F_max] and F_84 against
T1 with the errors of the closed form. docs/fragility.md quotes it.

    python3 -m validation.fragility_accuracy             # about 3 min on 2 cores
"""

from __future__ import annotations

import argparse

import numpy as np

from pounding.simulation.plan import MonteCarloPlan
from pounding.studies.force_spectrum import force_spectrum
from pounding.studies.fragility import fragility_curve
from pounding.units import STANDARD_GRAVITY

RECORDS, SEED = 100, 5
FRAGILITIES = (  # case, capacity [N], PGAs [g]
    ("section5-T2-0.4", 3.0e5, np.linspace(0.05, 0.6, 12)),
    ("section5-T2-0.8", 3.0e5, np.linspace(0.05, 0.6, 12)),
    ("section5-T2-0.4-nonstationary", 3.0e5, np.linspace(0.05, 0.6, 12)),
    ("section6-T2-0.6", 5.0e5, np.linspace(0.05, 0.6, 12)),
)
SPECTRA = (  # case, T1 [s], period ratio or None, T2 [s] or None
    ("section5-T2-0.4", np.linspace(0.2, 2.0, 10), None, 0.4),
    ("section5-T2-0.4", np.linspace(0.3, 2.0, 10), 0.5, None),
)


def fragilities(records: int = RECORDS, seed: int = SEED, cases=FRAGILITIES) -> list[float]:
    """Print each fragility curve; returns the largest |closed form - Monte Carlo| of each."""
    largest = []
    for name, capacity, pga in cases:
        curve = fragility_curve(name, capacity, pga * STANDARD_GRAVITY, MonteCarloPlan(records, seed, scheduler="serial"))
        fractions = curve.monte_carlo.exceeding(capacity) / records
        intervals = curve.monte_carlo.intervals(capacity)
        print(f"\n{name}, capacity {capacity / 1e3:g} kN, {records} records a point, seed {seed}")
        print("| PGA [g] | closed form | Monte Carlo | 95 % interval | difference |")
        print("|---|---|---|---|---|")
        for a, p, f, (low, high) in zip(pga, curve.probability, fractions, intervals):
            print(f"| {a:.3g} | {p:.3f} | {f:.3f} | {low:.3f}-{high:.3f} | {p - f:+.3f} |")
        largest.append(float(np.max(np.abs(curve.probability - fractions))))
        for label, fit in (("closed form", curve.lognormal), ("Monte Carlo", curve.lognormal_monte_carlo)):
            text = "none" if fit is None else f"median {fit.median / STANDARD_GRAVITY:.3f} g, beta {fit.dispersion:.3f}"
            print(f"lognormal fit, {label}: {text}")
        print(f"largest |difference| {largest[-1]:.3f}")
    return largest


def spectra(records: int = RECORDS, seed: int = SEED, cases=SPECTRA) -> None:
    for name, period1, ratio, period2 in cases:
        spectrum = force_spectrum(name, period1, ratio, period2, MonteCarloPlan(records, seed, scheduler="serial"))
        mc = spectrum.monte_carlo
        q84 = mc.quantile(0.84)[0]
        second = f"T2 = {ratio:g} T1" if ratio is not None else f"T2 = {period2:g} s"
        print(f"\n{name}, {second}, {records} records a point, seed {seed}; errors are closed form / Monte Carlo - 1")
        print("| T1 [s] | E[F_max] MC [kN] | closed form | F_84 MC [kN] | closed form |")
        print("|---|---|---|---|---|")
        for t1, mean, cf_mean, q, cf_q in zip(spectrum.period1, mc.force_mean, spectrum.force_mean, q84, spectrum.force_84):
            error = lambda cf, m: "n/a" if m == 0 else f"{100 * (cf / m - 1):+.1f} %"  # noqa: E731
            print(f"| {t1:.3g} | {mean / 1e3:.1f} | {error(cf_mean, mean)} | {q / 1e3:.1f} | {error(cf_q, q)} |")


def main(records: int = RECORDS, seed: int = SEED, cases: int | None = None, points: int | None = None) -> None:
    """``cases``: only the first fragility curves and spectra; ``points``: only the first PGAs and periods of each."""
    fragilities(records, seed, [(name, capacity, pga[:points]) for name, capacity, pga in FRAGILITIES[:cases]])
    spectra(records, seed, [(name, periods[:points], ratio, period2) for name, periods, ratio, period2 in SPECTRA[:cases]])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--seed", type=int, default=SEED)
    arguments = parser.parse_args()
    main(arguments.records, arguments.seed)
