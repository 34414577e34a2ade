"""Speed of the hazard in an engineer's terms (issue 22), printed as figures,
each beside a baseline timed in the same process:

- one estimate on a design-spectrum case (EN 1998-1, type 1, ground C, its
  compatible filter bank of G27 already built), against one on the same
  buildings under a Kanai-Tajimi spectrum (the bank adds states to the
  linear system); target 10 ms;
- loading that case (the compatible PSD included) against loading the
  Kanai-Tajimi one; the PSD alone is in benchmarks/design_spectrum.py;
- the Monte Carlo of 20 recorded motions (files read at load) against 20
  synthetic records of the same case: the cost per record should be the same.

Run: python3 benchmarks/hazard.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from timing import median_seconds  # noqa: E402 (this folder is on the path)

from pounding import estimate, simulate
from pounding.case.case import case_from_dict
from pounding.hazard.accelerograms import Accelerogram, write_at2
from pounding.hazard.excitation import ground_accelerations

BUILDINGS = [
    {"damping_ratio": 0.05, "storeys": [{"period": 1.0, "mass": 4.0e4, "hysteresis": {"yield_drift": 0.02, "post_yield_ratio": 0.05}}]},
    {"damping_ratio": 0.05, "storeys": [{"period": 0.5, "mass": 4.0e4, "hysteresis": {"yield_drift": 0.01, "post_yield_ratio": 0.05}}]},
]
CONTACT = {"model": "jankowski", "gap": 0.02, "stiffness": 1.96e9, "restitution": 0.65}
DESIGN = {"spectrum": "design", "code": "ec8", "spectrum_type": 1, "ground_type": "C", "ag": 0.3, "duration": 20.0}
KANAI_TAJIMI = {"spectrum": "kanai-tajimi", "pga": 0.3, "omega_g": 15.6, "xi_g": 0.6, "duration": 20.0}
RECORDS = 20


def data(excitation: dict) -> dict:
    return {"units": "SI", "excitation": excitation, "buildings": BUILDINGS, "contact": CONTACT}


def main() -> None:
    design = case_from_dict(data(DESIGN))
    kanai_tajimi = case_from_dict(data(KANAI_TAJIMI))
    print(f"filter bank: {len(design.excitation.spectrum.frequencies)} components")
    on_design = median_seconds(lambda: estimate(design))
    on_kt = median_seconds(lambda: estimate(kanai_tajimi))
    print(f"estimate, design-spectrum case   {1e3 * on_design:7.2f} ms   (target 10 ms)")
    print(f"estimate, Kanai-Tajimi baseline  {1e3 * on_kt:7.2f} ms   ratio {on_design / on_kt:.2f}")
    load_design = median_seconds(lambda: case_from_dict(data(DESIGN)), repeats=5)
    load_kt = median_seconds(lambda: case_from_dict(data(KANAI_TAJIMI)), repeats=5)
    print(f"load, design-spectrum case       {1e3 * load_design:7.2f} ms   (Kanai-Tajimi by its PGA {1e3 * load_kt:.2f} ms)")

    folder = Path(tempfile.mkdtemp())
    excitation = kanai_tajimi.excitation
    for index, record in enumerate(ground_accelerations(excitation, 1, range(RECORDS))):
        write_at2(folder / f"r{index:02d}.AT2", Accelerogram(f"r{index}", excitation.time_step, record))
    recorded = case_from_dict({**data({"records": ["*.AT2"]})}, base_directory=folder)
    on_records = median_seconds(lambda: simulate(recorded), repeats=5)
    on_synthetic = median_seconds(lambda: simulate(kanai_tajimi, records=RECORDS, seed=1), repeats=5)
    print(f"Monte Carlo, {RECORDS} recorded motions     {1e3 * on_records / RECORDS:7.2f} ms a record")
    print(f"Monte Carlo, {RECORDS} synthetic records    {1e3 * on_synthetic / RECORDS:7.2f} ms a record   ratio {on_records / on_synthetic:.2f}")


if __name__ == "__main__":
    main()
