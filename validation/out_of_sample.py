"""The recommended estimator on cases it was not developed on.

Reproduces the table of "Out of sample" in validation/HISTORY.md. The grid of
``pounding validate --grid`` was chosen by hand, and every model in the
estimator was judged on it; this draws cases at random from the ranges the
estimator claims (periods 0.2-2 s, gaps 0-5 cm, restitution 0.4-0.9, G0 x 0.25
to x 40, stationary and modulated records, SDOF pairs, the Section 6 frames,
the three-storey against two-storey pair, elastic buildings) and puts the
estimate against this project's Monte Carlo (300 records, seed 11), sorted by
the regime the estimate states (``Estimate.accuracy_regime``): the ranges that
``pounding estimate`` prints as its measured accuracy come from this table.

``validation.accuracy_data`` writes what these tables measure to
``pounding/data/accuracy.json``, where the estimate reads it.

    python3 -m validation.out_of_sample                  # the grid and three draws of 100 cases, about 7 min on 2 cores
    python3 -m validation.out_of_sample --seeds 2029     # other draws
    python3 -m validation.out_of_sample --required-gap   # the gap for 95 % no pounding against Monte Carlo, about 4 min
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

import numpy as np

from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import MOVING_TOGETHER, REGIMES
from pounding.simulation.monte_carlo import design_gap
from pounding.studies.paper_tables import RANDOM_FAMILIES, accuracy, accuracy_cases, random_cases

from .sizes import first

SEEDS = (2026, 2027, 2028)
RECORDS, SEED = 300, 11  # the force's Monte Carlo
GAP_RECORDS, GAP_SEED = 400, 9  # the required gap's
LABELS = (*(r for r in REGIMES if r != "rare"), "rare, yielding", "rare, elastic")
"""The regimes the estimate states, rare pounding split by whether a storey yields."""


def _label(case, row) -> str:
    """The estimator's own regime (``AccuracyRow.accuracy_regime``), rare pounding split by yielding."""
    if row.accuracy_regime != "rare":
        return row.accuracy_regime
    return "rare, yielding" if LinearizedPair.of(case).yielding else "rare, elastic"


def measured(cases, records: int = RECORDS, seed: int = SEED) -> list[tuple[str, object, float]]:
    """(regime, accuracy row, error) of each case against Monte Carlo (``records`` records, ``seed``); cases
    where no record pounded, or that the closed form refused, have no relative error and are left out."""
    out = []
    for case, row in zip(cases, accuracy(cases, records=records, seed=seed)):
        if row.recommended_error is not None:
            out.append((_label(case, row), row, row.recommended_error))
    return out


def case_table(results) -> None:
    print("| case | regime | gap / sigma_X | Monte Carlo E[F_max] (kN) | s.e. | recommended | paper |")
    print("|---|---|---|---|---|---|---|")
    for regime, row, error in results:
        paper = "-" if row.paper_error is None else f"{row.paper_error:+.1%}"
        print(f"| {row.case} | {regime} | {row.gap_over_sigma:.2f} | {row.monte_carlo / 1e3:.1f} | "
              f"{row.monte_carlo_std_error / row.monte_carlo:.1%} | {error:+.1%} | {paper} |")


def regime_table(sources: dict) -> None:
    """Within 10 % per source, and the range over all of them, for each regime."""
    names = list(sources)
    print("| regime | " + " | ".join(f"within 10 %: {name}" for name in names) + " | all: within 10 % | all: median | all: range |")
    print("|---|" + "---|" * (len(names) + 3))
    for label in LABELS:
        cells, every = [], []
        for name in names:
            errors = np.array([e for regime, _, e in sources[name] if regime == label])
            every += list(errors)
            cells.append(f"{(np.abs(errors) <= 0.10).sum()} of {errors.size}" if errors.size else "-")
        every = np.array(every)
        if every.size:
            print(f"| {label} | " + " | ".join(cells) + f" | {(np.abs(every) <= 0.10).sum()} of {every.size} | "
                  f"{np.median(np.abs(every)):.1%} | {every.min():+.0%} to {every.max():+.0%} |")


@dataclass(frozen=True)
class RequiredGap:
    """The closed-form gap for the target of one drawn case against Monte Carlo."""

    family: str
    """Its kind of pair, one of :data:`~pounding.studies.paper_tables.RANDOM_FAMILIES`."""
    moving_together: bool
    """Whether the contact floors' linearized x1, x2 correlate at least :data:`~pounding.closed_form.regimes.MOVING_TOGETHER`."""
    fraction: float
    """Of the records, the fraction pounding at the closed-form gap [-]."""
    ratio: float
    """The closed-form gap over the Monte Carlo gap for the target [-]."""


def required_gaps(seeds, records: int = GAP_RECORDS, target: float = 0.95, cases: int | None = None) -> list[RequiredGap]:
    """The gap given for ``target`` probability of no pounding on the draws of ``seeds`` (the first ``cases``
    of each, all for None) against ``records`` simulated records (seed 9). Both come from the records' free
    motion (``simulation.design_gap``): a record pounds at a gap exactly when its free peak exceeds it."""
    out = []
    for seed in seeds:
        families = [family for family, count in RANDOM_FAMILIES for _ in range(count)]
        for family, case in first(zip(families, random_cases(seed)), cases):
            pair = LinearizedPair.of(case)
            result = estimate(pair, target_probability=target)
            monte_carlo = design_gap(case, target_probability=target, records=records, seed=GAP_SEED)
            moving = result.response.correlation_displacement >= MOVING_TOGETHER
            out.append(RequiredGap(family, bool(moving), monte_carlo.pounding_fraction(result.required_gap),
                                   result.required_gap / monte_carlo.gap))
    return out


def required_gap_table(seeds, records: int = GAP_RECORDS, target: float = 0.95, cases: int | None = None) -> None:
    """The fraction of ``records`` records pounding at the gap given for ``target`` and that gap over the
    Monte Carlo one, by kind of pair (:func:`required_gaps`), then the yielding pairs by whether their
    floors move together."""
    limit = 1.0 - target + 2.0 * math.sqrt(target * (1.0 - target) / records)  # two standard errors above the target
    fractions: dict[str, list[float]] = {}
    ratios: dict[str, list[float]] = {}
    together: dict[tuple[str, bool], list[float]] = {}  # yielding pairs, by whether their floors move together
    for row in required_gaps(seeds, records, target, cases):
        fractions.setdefault(row.family, []).append(row.fraction)
        ratios.setdefault(row.family, []).append(row.ratio)
        if not row.family.startswith("elastic"):
            kind = "one-storey" if row.family.startswith("SDOF") else row.family
            together.setdefault((kind, row.moving_together), []).append(row.fraction)
    print(f"| pairs | cases | fraction pounding at the gap for {target:.0%}: mean | largest | above {limit:.3f} | "
          "closed-form gap / Monte Carlo gap: median | smallest |")
    print("|---|---|---|---|---|---|---|")
    for family, values in fractions.items():
        values, ratio = np.array(values), np.array(ratios[family])
        print(f"| {family} | {values.size} | {values.mean():.3f} | {values.max():.3f} | {(values > limit).sum()} | "
              f"{np.median(ratio):.2f} | {ratio.min():.2f} |")
    print(f"\nYielding pairs by whether the contact floors move together (linearized correlation of x1 and x2 at least "
          f"{MOVING_TOGETHER}):\n")
    print(f"| pairs | floors move together | cases | fraction pounding: mean | largest | above {limit:.3f} |")
    print("|---|---|---|---|---|---|")
    for (kind, moving), values in sorted(together.items(), key=lambda item: (item[0][0], not item[0][1])):
        values = np.array(values)
        print(f"| {kind} | {'yes' if moving else 'no'} | {values.size} | {values.mean():.3f} | {values.max():.3f} | {(values > limit).sum()} |")


def main(seeds=SEEDS, cases: int | None = None, records: int = RECORDS, required_gap: bool = False,
         gap_records: int = GAP_RECORDS) -> None:
    """The regime table over the grid and the draws of ``seeds`` (the first ``cases`` of each, all for
    None; ``records`` records), or with ``required_gap`` the required-gap tables (``gap_records`` records)."""
    if required_gap:
        required_gap_table(seeds, gap_records, cases=cases)
        return
    sources = {"grid": measured(first(accuracy_cases(), cases), records)}
    for seed in seeds:
        results = measured(first(random_cases(seed), cases), records)
        print(f"Draw {seed}:\n")
        case_table(results)
        print()
        sources[f"draw {seed}"] = results
    regime_table(sources)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=list(SEEDS), help="the random draws (besides the grid)")
    parser.add_argument("--required-gap", action="store_true", help="the gap for 95 %% no pounding against Monte Carlo")
    arguments = parser.parse_args()
    main(arguments.seeds, required_gap=arguments.required_gap)
