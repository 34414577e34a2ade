"""The closed form on storeys given the engineer's way (issue 32): Bouc-Wen laws from a yield drift, a
post-yield ratio, Wen's n and the loop shape beta_share, instead of the paper's beta = 2, gamma = -1.

Draws (``storey_cases(seed)``, a seeded generator): two one-storey buildings with periods 0.2-2 s
(log-uniform), under one of three hazards, a third each: the paper's Kanai-Tajimi soil with G0 x 0.25 to
x 4 pi^2 (log-uniform); the same as a Clough-Penzien spectrum with a high-pass at 2 rad/s (xi_f 0.6); or a
design spectrum's compatible bank (one of validation/design_spectrum_accuracy.py's EC8 and ASCE 7-16
hazards). Both buildings' storeys from ``BoucWen.from_yield_drift`` with one beta_share of 0.5 (Wen's
symmetric loop, the default of a case), 1 or 2 (the paper's), n of 1 or 2, a post-yield ratio 0-0.2 and,
for each building, a yield drift of 0.25 to 4 times its elastic floor's sigma (log-uniform, the same
ratio for both: from well below to above the elastic response); a sixth of the draws elastic. The gap is
0 to 2 sigma_X of the elastic pair, the restitution 0.4-0.9. Each draw is set against Monte Carlo (300
records, seed 11). The yielding level is the records' mean peak storey drift over the yield drift, the
larger of the two buildings.

    python3 -m validation.storey_accuracy                 # 90 draws, seed 3201, about 5 min on 2 cores
    python3 -m validation.storey_accuracy --cases 12      # a quick look
    python3 -m validation.storey_accuracy --json out.json
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from pounding import estimate, load_case, simulate
from pounding.case.case import case_from_dict
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import GRID_LOOP_SHARE, force_entry_key
from pounding.errors import ConvergenceError, InputError
from pounding.hazard.excitation import CloughPenzien
from pounding.mechanics.structures import BoucWen
from pounding.studies.paper_tables import varied_case

from .design_spectrum_accuracy import HAZARDS, case_data

SEED, CASES, RECORDS, MONTE_CARLO_SEED = 3201, 90, 300, 11
SHARES, EXPONENTS = (0.5, 1.0, 2.0), (1.0, 2.0)
SPECTRA = ("kanai-tajimi", "clough-penzien", "design")


def _base(spectrum: str, periods, rng: np.random.Generator):
    """The elastic pair under the drawn hazard, and the hazard's description."""
    if spectrum == "design":
        name = str(rng.choice(sorted(HAZARDS)))
        return case_from_dict(case_data(HAZARDS[name], (tuple(periods), (None, None), 0.02))), name
    g0 = math.exp(rng.uniform(math.log(0.25), math.log(4 * math.pi**2)))
    case = varied_case(load_case("section5-T2-0.4"), g0=g0, periods=tuple(periods), elastic=True)
    if spectrum == "clough-penzien":
        s = case.excitation.spectrum
        case = dataclasses.replace(case, excitation=dataclasses.replace(
            case.excitation, spectrum=CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6)))
        return case, f"CP G0x{g0:.2f}"
    return case, f"KT G0x{g0:.2f}"


def storey_case(rng: np.random.Generator, index: int):
    """One draw (see the module's docstring) and its description."""
    periods = np.exp(rng.uniform(math.log(0.2), math.log(2.0), 2))
    spectrum = SPECTRA[int(rng.integers(len(SPECTRA)))]
    base, hazard = _base(spectrum, periods, rng)
    share, n = float(rng.choice(SHARES)), float(rng.choice(EXPONENTS))
    ratio, over_sigma = rng.uniform(0.0, 0.2), math.exp(rng.uniform(math.log(0.25), math.log(4.0)))
    gap_over_sigma, restitution = rng.uniform(0.0, 2.0), rng.uniform(0.4, 0.9)
    elastic = bool(rng.uniform() < 1.0 / 6.0)
    pair = LinearizedPair.of(base)
    floors = pair.floor_statistics.displacement
    drifts = [float(floors[b][0]) * over_sigma for b in range(2)]
    buildings = []
    for building, drift in zip(base.buildings, drifts):
        law = BoucWen(alpha=1.0) if elastic else BoucWen.from_yield_drift(drift, ratio, n, share)
        buildings.append(dataclasses.replace(building, storeys=tuple(dataclasses.replace(s, bouc_wen=law) for s in building.storeys)))
    gap = gap_over_sigma * pair.stationary_response.sigma_relative_displacement
    contact = dataclasses.replace(base.contact, gap=gap, restitution=restitution)
    storey = "elastic" if elastic else f"beta_share {share:g}, n {n:g}, alpha {ratio:.2f}, yield {over_sigma:.2f} sigma"
    name = (f"{index:2d} T {periods[0]:.2f}/{periods[1]:.2f} s {hazard}, gap {gap_over_sigma:.2f} sigma_X e {restitution:.2f}, "
            f"{storey}")
    case = dataclasses.replace(base, buildings=tuple(buildings), contacts=(contact,), name=name)
    return case, {"share": None if elastic else share, "n": None if elastic else n, "alpha": None if elastic else ratio,
                  "yield_drift": None if elastic else drifts, "yield_over_sigma": None if elastic else over_sigma,
                  "spectrum": spectrum}


def storey_cases(seed: int = SEED, count: int = CASES):
    rng = np.random.default_rng(seed)
    return [storey_case(rng, index + 1) for index in range(count)]


def rows(seed: int = SEED, count: int = CASES, records: int = RECORDS) -> list[dict]:
    out = []
    for case, kind in storey_cases(seed, count):
        try:
            closed = estimate(case)
        except (InputError, ConvergenceError) as error:  # refused: said, not counted
            print(f"{case.name[:110]:110s} refused: {str(error)[:80]}", flush=True)
            continue
        study = simulate(case, records=records, seed=MONTE_CARLO_SEED)
        yielding = None
        if kind["yield_drift"] is not None:
            peaks = np.asarray(study.displacement_max)  # (records, 2): each building's contact floor, its storey
            yielding = float(np.max(np.mean(peaks, axis=0) / np.asarray(kind["yield_drift"])))
        mean = study.force_max_mean
        out.append({**kind, "case": case.name, "regime": closed.accuracy_regime, "monte_carlo": mean,
                    "std_error": study.force_max_std_error, "closed_form": closed.force_expected,
                    "error": closed.force_expected / mean - 1.0 if mean > 0 else None,
                    "fraction": study.pounding_fraction, "probability": closed.pounding_probability,
                    "peak_over_yield": yielding})
        print(f"{case.name[:110]:110s} {closed.accuracy_regime:15s} MC {mean / 1e3:9.1f} kN  "
              + ("err   n/a" if out[-1]["error"] is None else f"err {out[-1]['error']:+7.1%}")
              + ("" if yielding is None else f"  peak/yield {yielding:5.2f}"), flush=True)
    return out


def other_loop_errors(table: list[dict]) -> list[tuple[str, float]]:
    """(label, error) of the yielding draws whose loop lies outside the grid's (beta_share below
    ``regimes.GRID_LOOP_SHARE``), labelled by the estimate's regime, rare pounding as "rare, yielding"
    (accuracy.json's "other loops")."""
    return [(force_entry_key("other loops", row["regime"], True), row["error"]) for row in table
            if row["error"] is not None and row["share"] is not None and row["share"] < GRID_LOOP_SHARE]


def _kind(row) -> str:
    if row["share"] is None:
        return "elastic"
    level = row["peak_over_yield"]
    band = "peak below yield" if level < 1.0 else ("peak 1-3 x yield" if level < 3.0 else "peak beyond 3 x yield")
    return f"beta_share {row['share']:g}, {band}"


def _table(groups: dict) -> None:
    for key, errors in sorted(groups.items()):
        e = np.array(errors)
        print(f"| {' | '.join(key)} | {e.size} | {int(np.sum(np.abs(e) <= 0.1))} | {np.median(np.abs(e)):.1%} | "
              f"{e.min():+.0%} to {e.max():+.0%} |")


def summary(table: list[dict]) -> None:
    """Two tables: by storey kind and regime (rare or not), and by spectrum and yielding level."""
    measured = [row for row in table if row["error"] is not None]
    print("\n| storeys | regime | cases | within 10 % | median \\|error\\| | range |\n|---|---|---|---|---|---|")
    groups: dict = {}
    for row in measured:
        groups.setdefault((_kind(row), "rare" if row["regime"] == "rare" else "gap below sigma_X"), []).append(row["error"])
    _table(groups)
    print("\n| spectrum | storeys | cases | within 10 % | median \\|error\\| | range |\n|---|---|---|---|---|---|")
    groups = {}
    for row in measured:
        level = "elastic" if row["share"] is None else _kind(row).split(", ", 1)[1]
        groups.setdefault((row["spectrum"], level), []).append(row["error"])
    _table(groups)


def main(seed: int = SEED, cases: int = CASES, records: int = RECORDS, json_path=None) -> list[dict]:
    """The case lines and the summary by storey kind and regime; with ``json_path`` the rows as JSON too."""
    table = rows(seed, cases, records)
    summary(table)
    if json_path:
        Path(json_path).write_text(json.dumps(table, indent=1) + "\n")
    return table


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--cases", type=int, default=CASES)
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--json", metavar="PATH")
    arguments = parser.parse_args()
    main(arguments.seed, arguments.cases, arguments.records, arguments.json)
