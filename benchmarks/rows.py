"""Speed of cases with several contacts, printed as figures (issue 35).

- the closed form of three 5-storey buildings in a row with 8 contacts (every floor of buildings 1 and 2, three of
  buildings 2 and 3): median of repeated calls after warm-up, beside the one-contact estimate of buildings 1 and 2
  timed in the same process;
- the Monte Carlo cost per record against the number of contacts (1, 2, 4, 8) on the same row and records, as a
  ratio to one contact's: it should grow no more than linearly. Each row of contacts is timed twice, once with the
  gaps out of reach (the cost of carrying the contacts) and once at a gap where they pound.

Run: python3 benchmarks/rows.py
"""

from __future__ import annotations

import dataclasses
import time

from timing import median_seconds  # noqa: E402 (this folder is on the path)

from pounding import estimate, simulate
from pounding.case.case import case_from_dict

RECORDS = 40
ESTIMATE_TARGET = 0.050  # [s] issue 35: three 5-storey buildings with 8 contacts


def row(contacts: int, gap: float):
    """Three 5-storey buildings (0.5, 0.35, 0.45 s) with the first ``contacts`` of the 8 (floors 5..1 of buildings 1-2,
    then floors 5..3 of buildings 2-3), every gap ``gap`` [m]."""
    def building(stiffness):
        return {"storeys": [{"mass": 4.0e4, "stiffness": stiffness}] * 5}

    pairs = [([1, 2], [k, k]) for k in range(5, 0, -1)] + [([2, 3], [k, k]) for k in range(5, 2, -1)]
    data = {
        "units": "SI",
        "excitation": {"spectrum": "kanai-tajimi", "G0": 65.03e-4, "omega_g": 27.02, "xi_g": 0.34, "duration": 10.0},
        "buildings": [building(7.0e7), building(1.4e8), building(1.0e8)],
        "contacts": [{"between": b, "levels": l, "gap": gap, "stiffness": 1.96e9} for b, l in pairs[:contacts]],
    }
    return case_from_dict(data, name=f"row, {contacts} contacts")


def per_record(case) -> float:
    simulate(case, records=2, seed=0)  # warm-up (JIT cache load)
    start = time.perf_counter()
    simulate(case, records=RECORDS, seed=1)
    return (time.perf_counter() - start) / RECORDS


def main() -> None:
    full = row(8, 0.02)
    single = dataclasses.replace(full, contacts=full.contacts[:1])
    eight = median_seconds(lambda: estimate(full), repeats=10)
    one = median_seconds(lambda: estimate(single), repeats=10)
    print(f"closed form, three 5-storey buildings, 8 contacts: {1e3 * eight:.1f} ms "
          f"(target {1e3 * ESTIMATE_TARGET:.0f} ms; one contact of the same row: {1e3 * one:.1f} ms, ratio {eight / one:.1f})")
    print("Monte Carlo per record against the number of contacts (ratio to one contact, same records)")
    print("(the steps are the integrator's accepted steps per record: the work, free of the machine's load)")
    print("| contacts | gaps out of reach (ms) | ratio | gap 20 mm (ms) | ratio | impacts per record | steps per record | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    base = {}
    for count in (1, 2, 4, 8):
        times = []
        for gap in (5.0, 0.02):
            case = row(count, gap)
            times.append(per_record(case))
            base.setdefault(gap, times[-1])
        study = simulate(row(count, 0.02), records=RECORDS, seed=1)
        steps = float(study.steps.mean())
        base.setdefault("steps", steps)
        print(f"| {count} | {1e3 * times[0]:.2f} | {times[0] / base[5.0]:.2f} | {1e3 * times[1]:.2f} | "
              f"{times[1] / base[0.02]:.2f} | {study.impacts_mean:.1f} | {steps:.0f} | {steps / base['steps']:.2f} |")


if __name__ == "__main__":
    main()
