"""The impacts' damping of the relative motion, measured.

Reproduces the tables of "The impacts' damping, measured" in docs/estimator.md:

- by regime, the estimate with the impacts' damping (the estimator) and
  without it (``estimate(case, impact_damping=False)``, the free count it
  replaced) against this project's Monte Carlo (300 records, seed 11), on the
  grid and on random draws of cases (``validation.random_cases``);
- for one elastic pair of close periods, Monte Carlo and both counts at five
  gaps: the force grows with a small gap, as fewer impacts damp the motion less.

    python3 docs/impact_damping.py                    # the grid and draws 2026-2028, about 7 min on 2 cores
    python3 docs/impact_damping.py --seeds 2029       # other draws (the grid too)
    python3 docs/impact_damping.py --gap-curve        # the pair at five gaps, 400 records each, about 1 min
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from pounding import simulate  # noqa: E402
from pounding.estimator import _yielding, estimate  # noqa: E402
from pounding.linearization import linearize_pair  # noqa: E402
from pounding.validation import _vary, accuracy_cases, random_cases  # noqa: E402

ORDER = ("frequent", "moderate gap", "narrow band", "large residual", "rare, yielding", "rare, elastic")


def measured(cases) -> list[tuple[str, float, float]]:
    """(regime, error with the damping, error without) per case where some record pounded."""
    return [(regime, *errors) for regime, _, errors in measured_cases(cases, lambda case: estimate(case, impact_damping=False))]


def measured_cases(cases, variant) -> list[tuple[str, str, tuple[float, float]]]:
    """(regime, kind, (error of the estimator, error of ``variant(case)``)) per case where some of
    300 records (seed 11) pounded; kind "elastic" or "yielding", the "rare" regime split by it."""
    out = []
    for case in cases:
        mean = simulate(case, records=300, seed=11).force_max_mean
        if mean <= 0.0:
            continue
        result, other = estimate(case), variant(case)
        kind = "yielding" if _yielding(linearize_pair(case)) else "elastic"
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


def gap_curve_table(records: int = 400) -> None:
    """The elastic pair 0.61 / 0.48 s, G0 x 5.86, e = 0.42 at five gaps."""
    from pounding import load_case

    base = _vary(load_case("section5-T2-0.4"), elastic=True, periods=(0.61, 0.48), g0=5.86, restitution=0.42)
    sigma = estimate(base).sigma_relative_displacement
    print(f"sigma_X = {100 * sigma:.2f} cm\n")
    print("| gap (cm) | gap / sigma_X | Monte Carlo E[F_max] (MN) | with the impacts' damping | free count | sigma_V before an approach / free | memory |")
    print("|---|---|---|---|---|---|---|")
    for gap in (0.0, 0.0083, 0.0166, 0.0333, 0.05):
        case = _vary(base, gap=gap)
        study = simulate(case, records=records, seed=5)
        damped, free = estimate(case), estimate(case, impact_damping=False)
        mean = study.force_max_mean
        print(f"| {100 * gap:.2f} | {gap / sigma:.2f} | {mean / 1e6:.3f} ± {study.force_max_std_error / 1e6:.3f} | "
              f"{damped.force_expected / 1e6:.3f} ({damped.force_expected / mean - 1:+.1%}) | "
              f"{free.force_expected / 1e6:.3f} ({free.force_expected / mean - 1:+.1%}) | "
              f"{damped.impacting_velocity_ratio:.2f} | {damped.impact_memory:.2f} |", flush=True)


def main(seeds) -> None:
    sources = {"grid": measured(accuracy_cases())}
    for seed in seeds:
        sources[f"draw {seed}"] = measured(random_cases(seed))
    regime_table(sources)
    everything = [row for rows in sources.values() for row in rows]
    print()
    regime_table({"all": everything})


if __name__ == "__main__":
    arguments = sys.argv[1:]
    if "--gap-curve" in arguments:
        gap_curve_table()
    else:
        seeds = [int(a) for a in arguments[arguments.index("--seeds") + 1:]] if "--seeds" in arguments else [2026, 2027, 2028]
        main(seeds)
