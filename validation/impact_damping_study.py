"""The impacts' damping of the relative motion, measured.

Reproduces the tables of "The impacts' damping, measured" in validation/HISTORY.md:

- by regime, the estimate with the impacts' damping (the estimator) and
  without it (the free count it replaced, :func:`validation.free_count.free_estimate`)
  against this project's Monte Carlo (300 records, seed 11), on the
  grid and on random draws of cases (``validation.random_cases``);
- for one elastic pair of close periods, Monte Carlo and both counts at five
  gaps: the force grows with a small gap, as fewer impacts damp the motion less.

    python3 -m validation.impact_damping_study                    # the grid and draws 2026-2028, about 7 min on 2 cores
    python3 -m validation.impact_damping_study --seeds 2029       # other draws (the grid too)
    python3 -m validation.impact_damping_study --gap-curve        # the pair at five gaps, 400 records each, about 1 min
"""

from __future__ import annotations

import argparse

import numpy as np

from pounding import load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.closed_form.pair import LinearizedPair
from pounding.studies.paper_tables import accuracy_cases, random_cases, varied_case

from .free_count import free_estimate
from .sizes import first

ORDER = ("frequent", "moderate gap", "narrow band", "large residual", "rare, yielding", "rare, elastic")
RECORDS, SEED = 300, 11
SEEDS = (2026, 2027, 2028)
GAP_CURVE_RECORDS = 400


def measured(cases, records: int = RECORDS) -> list[tuple[str, float, float]]:
    """(regime, error with the damping, error without) per case where some record pounded."""
    return [(regime, *errors) for regime, _, errors in measured_cases(cases, free_estimate, records)]


def measured_cases(cases, variant, records: int = RECORDS) -> list[tuple[str, str, tuple[float, float]]]:
    """(regime, kind, (error of the estimator, error of ``variant(pair)``, ``pair`` the case's
    :class:`~pounding.closed_form.pair.LinearizedPair`)) per case where some of ``records`` records (seed 11)
    pounded; kind "elastic" or "yielding", the "rare" regime split by it."""
    out = []
    for case in cases:
        mean = simulate(case, records=records, seed=SEED).force_max_mean
        if mean <= 0.0:
            continue
        pair = LinearizedPair.of(case)
        result, other = estimate(pair), variant(pair)
        kind = "yielding" if pair.yielding else "elastic"
        regime = result.accuracy_regime if result.accuracy_regime != "rare" else f"rare, {kind}"
        out.append((regime, kind, (result.force_expected / mean - 1, other.force_expected / mean - 1)))
    return out


def _cell(errors) -> str:
    errors = np.asarray(errors)
    if errors.size == 0:
        return "-"
    return (f"{int(np.sum(np.abs(errors) <= 0.10))} of {errors.size}, {np.median(np.abs(errors)):.1%}, "
            f"{errors.min():+.0%} to {errors.max():+.0%}")


def regime_table(sources: dict) -> None:
    print("| regime | source | with the impacts' damping: within 10 %, median, range | free count (before) |")
    print("|---|---|---|---|")
    for regime in ORDER:
        for source, rows in sources.items():
            selected = [r for r in rows if r[0] == regime]
            if selected:
                print(f"| {regime} | {source} | {_cell([r[1] for r in selected])} | {_cell([r[2] for r in selected])} |")


def gap_curve_table(records: int = GAP_CURVE_RECORDS, gaps: int | None = None) -> None:
    """The elastic pair 0.61 / 0.48 s, G0 x 5.86, e = 0.42 at five gaps (the first ``gaps`` of them)."""
    base = varied_case(load_case("section5-T2-0.4"), elastic=True, periods=(0.61, 0.48), g0=5.86, restitution=0.42)
    sigma = estimate(base).sigma_relative_displacement
    print(f"sigma_X = {100 * sigma:.2f} cm\n")
    print("| gap (cm) | gap / sigma_X | Monte Carlo E[F_max] (MN) | with the impacts' damping | free count | sigma_V before an approach / free | memory |")
    print("|---|---|---|---|---|---|---|")
    for gap in first((0.0, 0.0083, 0.0166, 0.0333, 0.05), gaps):
        pair = LinearizedPair.of(varied_case(base, gap=gap))
        study = simulate(pair.case, records=records, seed=5)
        damped, free = estimate(pair), free_estimate(pair)
        mean = study.force_max_mean
        print(f"| {100 * gap:.2f} | {gap / sigma:.2f} | {mean / 1e6:.3f} ± {study.force_max_std_error / 1e6:.3f} | "
              f"{damped.force_expected / 1e6:.3f} ({damped.force_expected / mean - 1:+.1%}) | "
              f"{free.force_expected / 1e6:.3f} ({free.force_expected / mean - 1:+.1%}) | "
              f"{damped.impacting_velocity_ratio:.2f} | {damped.impact_memory:.2f} |", flush=True)


TABLES = ("regimes", "gap-curve")


def main(table: str = "regimes", seeds=SEEDS, cases: int | None = None, records: int = RECORDS,
         gap_curve_records: int = GAP_CURVE_RECORDS, gaps: int | None = None) -> None:
    """Print ``table`` (one of :data:`TABLES`): the regime tables over the first ``cases``
    (all for None) of the grid and of each draw of ``seeds``, ``records`` records each; or
    the gap curve at the first ``gaps`` gaps, ``gap_curve_records`` records each."""
    if table == "gap-curve":
        gap_curve_table(gap_curve_records, gaps)
        return
    sources = {"grid": measured(first(accuracy_cases(), cases), records)}
    for seed in seeds:
        sources[f"draw {seed}"] = measured(first(random_cases(seed), cases), records)
    regime_table(sources)
    everything = [row for rows in sources.values() for row in rows]
    print()
    regime_table({"all": everything})


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=list(SEEDS), help="the random draws (besides the grid)")
    parser.add_argument("--gap-curve", dest="table", action="store_const", const="gap-curve", default="regimes",
                        help="the elastic pair at five gaps")
    arguments = parser.parse_args()
    main(arguments.table, arguments.seeds)
