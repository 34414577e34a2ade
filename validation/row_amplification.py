"""Rows of buildings (issue 35): are the end buildings' responses amplified by pounding and the interior ones'
reduced, as Anagnostopoulos (1988, "Pounding of buildings in series during earthquakes", Earthquake Engng
Struct. Dyn. 16:443-456) found for SDOF structures in a row?

The row: N one-storey (SDOF) buildings side by side, equal masses (5e5 kg), 5 % damping, equal gaps
(0, touching as in a continuous block, and 1 cm; the first row size also 2 cm) and equal contacts (Jankowski's law, 2.75e9 N/m^1.5, e = 0.65), under the Kanai-Tajimi records of
firm soil (omega_g 15.6 rad/s, xi_g 0.6) with an expected PGA of 0.3 g, 15 s stationary. Buildings that
are exactly alike never pound: under one ground motion they move as one, record for record (the first
table shows it). So the buildings are alike but for their periods: each record draws every building's
period log-uniformly within 0.5 s x exp(+-0.2) (0.41 to 0.61 s, about +-20 %), a new row per record
(seeded), so that the answer is about a position in the row, not one arrangement of periods; the first row
size also within exp(+-0.4) (0.34 to 0.75 s). The same
record is integrated twice: with the contacts, and with the gaps set to 10 m (no contact).

Each building's response is its peak displacement (relative to the ground) over the record: |x|, and for
the end buildings also outward (away from the row: -x for building 1, +x for building N) and inward. The
amplification ratio of a building is the mean over the records of its peak with contacts over the mean of
its peak without; its 95 % interval is the ratio estimator's (the delta method on the records' pairs,
Student t). Elastic storeys, and mildly yielding ones (Bouc-Wen from a yield drift of 2 cm, post-yield
ratio 0.1: about half the elastic buildings' mean peak of 4 cm). The per-contact tables give the mean
F_max and its 95 % interval.

    python3 -m validation.row_amplification            # N = 5 and 3, 300 records a run, about 1.5 min on 2 cores
    python3 -m validation.row_amplification --quick    # 40 records a run, about 10 s
"""

from __future__ import annotations

import argparse
import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from scipy.special import stdtrit

from pounding.case.case import Case, case_from_dict
from pounding.simulation.monte_carlo import simulate_record
from pounding.simulation.result import mean_interval

RECORDS, QUICK_RECORDS, SEED, ROW_SEED = 300, 40, 2035, 88
PERIOD, SPREAD, MASS, GAP, APART = 0.5, 0.2, 5.0e5, 0.01, 10.0  # s, log-spread of the periods, kg, m, m (a gap never closed)
YIELD_DRIFT = 0.02  # m: the yielding storeys'
EXCITATION = {"spectrum": "kanai-tajimi", "pga": 0.3, "omega_g": 15.6, "xi_g": 0.6, "duration": 15.0}
CONTACT = {"model": "jankowski", "stiffness": 2.75e9, "restitution": 0.65}


def row_case(periods, gap: float = GAP, yield_drift: float | None = None) -> Case:
    """The row of one-storey buildings of ``periods`` [s], left to right, ``gap`` [m] between neighbours."""
    buildings = []
    for period in periods:
        storey = {"mass": MASS, "stiffness": MASS * (2.0 * math.pi / period) ** 2}
        if yield_drift is not None:
            storey["hysteresis"] = {"yield_drift": yield_drift, "post_yield_ratio": 0.1}
        buildings.append({"damping_ratio": 0.05, "storeys": [storey]})
    contacts = [{"between": [b, b + 1], "levels": [1, 1], "gap": gap, **CONTACT} for b in range(1, len(periods))]
    return case_from_dict({"name": f"row of {len(periods)}", "units": "SI", "excitation": EXCITATION,
                           "buildings": buildings, "contacts": contacts})


def draw_rows(buildings: int, records: int, spread: float = SPREAD, seed: int = ROW_SEED) -> np.ndarray:
    """(records, buildings) periods [s]: each record's row, log-uniform within PERIOD x exp(+-spread)."""
    return PERIOD * np.exp(np.random.default_rng(seed).uniform(-spread, spread, (records, buildings)))


@dataclass(frozen=True)
class RowRun:
    """Per-record peaks of the rows, with contacts (``*_with``) and without (``*_free``).

    right_*, left_* : (records, buildings) peak +x and -x of each roof [m]; final_* : (records, buildings) each
    roof's displacement at the record's end [m]; force, impacts : (records, contacts)."""

    right_with: np.ndarray
    left_with: np.ndarray
    right_free: np.ndarray
    left_free: np.ndarray
    final_with: np.ndarray
    final_free: np.ndarray
    force: np.ndarray
    impacts: np.ndarray

    @property
    def buildings(self) -> int:
        return self.right_with.shape[1]

    def peak(self, contacts: bool) -> np.ndarray:
        """(records, buildings) peak |x| of each roof [m]."""
        return np.maximum(self.right_with, self.left_with) if contacts else np.maximum(self.right_free, self.left_free)

    def outward(self, contacts: bool) -> np.ndarray:
        """(records, 2) the end buildings' peak away from the row (building 1: -x, building N: +x) [m]."""
        right, left = (self.right_with, self.left_with) if contacts else (self.right_free, self.left_free)
        return np.column_stack([left[:, 0], right[:, -1]])

    def inward(self, contacts: bool) -> np.ndarray:
        """(records, 2) the end buildings' peak toward the row [m]."""
        right, left = (self.right_with, self.left_with) if contacts else (self.right_free, self.left_free)
        return np.column_stack([right[:, 0], left[:, -1]])

    def residual_outward(self, contacts: bool) -> np.ndarray:
        """(records, 2) the end buildings' displacement at the record's end, positive away from the row [m]."""
        final = self.final_with if contacts else self.final_free
        return np.column_stack([-final[:, 0], final[:, -1]])


def _record(periods, index: int, seed: int, yield_drift, gap: float):
    """One record on one row, with and without contacts: the roofs' peaks and the contacts' forces and impacts."""
    out = []
    for spacing in (gap, APART):
        case = row_case(periods, spacing, yield_drift)
        history = simulate_record(case, seed=seed, index=index)
        roofs = [history.floor(b + 1, len(building.storeys)) for b, building in enumerate(case.buildings)]
        displacement = history.displacement[:, roofs]
        out.append((displacement.max(axis=0), -displacement.min(axis=0), displacement[-1], history.summary["contacts"]))
    (right, left, final, contacts), (right_free, left_free, final_free, apart) = out
    assert all(c["impacts"] == 0 for c in apart), "the free row pounded: widen APART"
    return (right, left, right_free, left_free, final, final_free, [c["force_max"] for c in contacts],
            [c["impacts"] for c in contacts])


def run_rows(buildings: int, records: int, yield_drift: float | None = None, seed: int = SEED, gap: float = GAP,
             spread: float = SPREAD, rows: np.ndarray | None = None) -> RowRun:
    """Record ``i`` of the study seeded ``seed`` on row ``i`` of :func:`draw_rows` (or of ``rows``), with and
    without contacts, on the machine's cores."""
    rows = draw_rows(buildings, records, spread) if rows is None else np.asarray(rows, dtype=float)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        results = list(pool.map(lambda i: _record(rows[i], i, seed, yield_drift, gap), range(len(rows))))
    columns = [np.array(column, dtype=float) for column in zip(*results)]
    return RowRun(*columns)


def ratio_interval(with_contacts: np.ndarray, without: np.ndarray) -> tuple[float, float, float]:
    """Ratio of the means of paired samples, mean(a) / mean(b), and its 95 % interval: the delta method on the
    pairs (the residuals a - r b), Student t with n - 1 degrees of freedom."""
    a, b = np.asarray(with_contacts, dtype=float), np.asarray(without, dtype=float)
    ratio = float(a.mean() / b.mean())
    half = stdtrit(a.size - 1, 0.975) * float(np.std(a - ratio * b, ddof=1)) / (math.sqrt(a.size) * float(b.mean()))
    return ratio, ratio - half, ratio + half


def _cell(values) -> str:
    ratio, low, high = values
    return f"{ratio:.3f} ({low:.3f}-{high:.3f})"


def _storeys(yield_drift) -> str:
    return "elastic" if yield_drift is None else f"yielding ({100 * yield_drift:g} cm)"


def building_ratios(run: RowRun) -> list[tuple[float, float, float]]:
    """Each building's mean peak |x| with contacts over without, with its 95 % interval."""
    return [ratio_interval(run.peak(True)[:, b], run.peak(False)[:, b]) for b in range(run.buildings)]


def pooled_ratios(run: RowRun) -> dict:
    """The buildings pooled by position (the rows are drawn alike at both ends): the end buildings' |x|, outward
    and inward peaks, the interior buildings' |x|, each with contacts over without and its 95 % interval (a
    record's buildings of one position summed as one sample); the end buildings' mean displacement at the
    record's end, away from the row, without and with contacts [m]."""
    ends = [0, run.buildings - 1]
    pooled = {"end |x|": ratio_interval(run.peak(True)[:, ends].sum(1), run.peak(False)[:, ends].sum(1)),
              "end outward": ratio_interval(run.outward(True).sum(1), run.outward(False).sum(1)),
              "end inward": ratio_interval(run.inward(True).sum(1), run.inward(False).sum(1))}
    if run.buildings > 2:
        inner = slice(1, run.buildings - 1)
        pooled["interior |x|"] = ratio_interval(run.peak(True)[:, inner].sum(1), run.peak(False)[:, inner].sum(1))
    pooled["end residual outward"] = (float(run.residual_outward(False).mean()), float(run.residual_outward(True).mean()))
    return pooled


def contact_forces(run: RowRun) -> list[dict]:
    """Each contact's mean F_max [N] and its 95 % interval, the fraction of records that pound, the mean impacts."""
    return [{"force_max_mean": float(run.force[:, c].mean()), "interval": mean_interval(run.force[:, c]),
             "pounding_fraction": float(np.mean(run.impacts[:, c] > 0)), "impacts_mean": float(run.impacts[:, c].mean())}
            for c in range(run.force.shape[1])]


def building_table(runs: dict, buildings: int, gap: float) -> None:
    """Per building: the mean peak |x| without contacts [cm] and the ratio with / without, each storey kind."""
    kinds = [kind for kind in KINDS if (buildings, SPREAD, gap, kind) in runs]
    print(f"\n{buildings} buildings, gap {100 * gap:g} cm, periods 0.5 s x exp(+-{SPREAD}): mean peak roof |x| "
          "without contacts, and with / without contacts (95 % interval)\n")
    print("| building | position | " + " | ".join(f"{_storeys(k)}: without (cm) | {_storeys(k)}: ratio" for k in kinds) + " |")
    print("|---|---|" + "---|---|" * len(kinds))
    for b in range(buildings):
        position = "end" if b in (0, buildings - 1) else "interior"
        cells = []
        for kind in kinds:
            run = runs[buildings, SPREAD, gap, kind]
            cells += [f"{100 * run.peak(False)[:, b].mean():.2f}", _cell(building_ratios(run)[b])]
        print(f"| {b + 1} | {position} | " + " | ".join(cells) + " |")
    print("\n| contact | " + " | ".join(f"{_storeys(k)}: mean F_max (kN, 95 % interval) | pounding | impacts" for k in kinds)
          + " |\n|---|" + "---|---|---|" * len(kinds))
    forces = {kind: contact_forces(runs[buildings, SPREAD, gap, kind]) for kind in kinds}
    for c in range(buildings - 1):
        cells = []
        for kind in kinds:
            f = forces[kind][c]
            low, high = f["interval"]
            cells += [f"{f['force_max_mean'] / 1e3:.0f} ({low / 1e3:.0f}-{high / 1e3:.0f})", f"{f['pounding_fraction']:.0%}",
                      f"{f['impacts_mean']:.1f}"]
        print(f"| {c + 1}-{c + 2} | " + " | ".join(cells) + " |")


def pooled_table(runs: dict) -> None:
    """Every run's pooled ratios, one line each."""
    print("\nBy position, with / without contacts (95 % interval); both ends pooled, outward = away from the row\n")
    print("| buildings | spread | gap (cm) | storeys | end \\|x\\| | end outward | end inward | interior \\|x\\| | "
          "end at the record's end, outward (cm): without, with |\n|---|---|---|---|---|---|---|---|---|")
    for (buildings, spread, gap, kind), run in runs.items():
        pooled = pooled_ratios(run)
        interior = _cell(pooled["interior |x|"]) if "interior |x|" in pooled else "-"
        free, contacts = pooled["end residual outward"]
        print(f"| {buildings} | +-{spread:g} | {100 * gap:g} | {_storeys(kind)} | {_cell(pooled['end |x|'])} | "
              f"{_cell(pooled['end outward'])} | {_cell(pooled['end inward'])} | {interior} | {100 * free:+.2f}, {100 * contacts:+.2f} |")


def identical_row(buildings: int, records: int, seed: int = SEED) -> float:
    """The most impacts at any contact of a row of identical buildings (0.5 s) over ``records`` records."""
    run = run_rows(buildings, records, seed=seed, gap=0.0, rows=np.full((records, buildings), PERIOD))
    return float(run.impacts.max())


KINDS = (None, YIELD_DRIFT)  # the storeys: elastic, mildly yielding
MAIN_GAPS, MORE_GAPS, MORE_SPREAD = (0.0, 0.01), (0.02,), 0.4


def plan(buildings=(5, 3)) -> list[tuple]:
    """(buildings, spread, gap, yield drift) of each run: each row size at the main gaps; the first size also at
    the other gaps, and at the wider spread."""
    keys = [(n, SPREAD, gap, kind) for n in buildings for gap in MAIN_GAPS for kind in KINDS]
    if buildings:
        first = buildings[0]
        keys += [(first, SPREAD, gap, kind) for gap in MORE_GAPS for kind in KINDS]
        keys += [(first, MORE_SPREAD, gap, kind) for gap in (*MAIN_GAPS, *MORE_GAPS) for kind in KINDS]
    return sorted(keys, key=lambda k: (-k[0], k[1], k[2], k[3] is not None))


def main(buildings=(5, 3), records: int = RECORDS, quick: bool = False, seed: int = SEED) -> dict:
    """The tables: a row of identical buildings, then per building and per contact for each row size at the main
    gaps, then the pooled ratios of every run. Returns the runs by (buildings, spread, gap, yield drift)."""
    records = QUICK_RECORDS if quick else records
    print(f"Rows of SDOF buildings (5e5 kg, 5 %), Kanai-Tajimi PGA 0.3 g 15 s, {records} records (seed {seed}), "
          f"periods drawn per record (seed {ROW_SEED}) log-uniform in 0.5 s x exp(+-spread)")
    print("\n| row of identical buildings (0.5 s), gap 0 | records | most impacts at a contact |\n|---|---|---|")
    for n in buildings:
        print(f"| {n} | {min(records, 20)} | {identical_row(n, min(records, 20), seed):.0f} |")
    runs = {key: run_rows(key[0], records, key[3], seed, key[2], key[1]) for key in plan(buildings)}
    for n in buildings:
        for gap in MAIN_GAPS:
            building_table(runs, n, gap)
    pooled_table(runs)
    return runs


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=RECORDS)
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--buildings", type=int, nargs="+", default=[5, 3])
    parser.add_argument("--quick", action="store_true", help=f"{QUICK_RECORDS} records a run")
    arguments = parser.parse_args()
    main(tuple(arguments.buildings), arguments.records, arguments.quick, arguments.seed)
