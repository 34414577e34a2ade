"""Speed of the Monte Carlo engine ("exact method"), printed as figures.

The Section 5 case T1 = 1.2 s, T2 = 0.4 s, 20 s stationary records:
- one-off costs: a new process's import + cached-kernel load, and the numba
  compile with an empty cache (both in fresh subprocesses);
- 300 records after warm-up, on 1 thread and on every core;
- the gap for 95 % no pounding from the same number of records' free motion
  (``simulation.design_gap``), as a ratio to the study with contact;
- the same few records through scipy's solve_ivp (RK45, same tolerance, the
  equations in plain Python: tests/reference.py) as the in-process baseline.

Run: python3 benchmarks/simulate.py [--records 300] [--baseline-records 2]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from pounding import Settings, integrate, load_case, simulate  # noqa: E402
from pounding.hazard.excitation import ground_accelerations  # noqa: E402
from pounding.simulation.monte_carlo import design_gap  # noqa: E402
from tests.reference import solve_reference  # noqa: E402

CASE = "section5-T2-0.4"
OPENSEES_CPU_SECONDS_PER_RECORD = 0.65  # JankowskiImpact, 1 ms step, 20 s record (issue 2)


def fresh_process_seconds(env_extra: dict[str, str]) -> float:
    code = (
        "import time; t = time.perf_counter();"
        "from pounding import load_case, simulate;"
        f"simulate(load_case('{CASE}'), records=1, seed=0, settings=__import__('pounding').Settings(workers=1));"
        "print(time.perf_counter() - t)"
    )
    env = {**os.environ, **env_extra}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    return float(out.stdout.strip())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=300)
    parser.add_argument("--baseline-records", type=int, default=2)
    args = parser.parse_args()
    case = load_case(CASE)
    print(f"case {CASE}: {args.records} records x {case.excitation.duration:g} s, {os.cpu_count()} cores")

    with tempfile.TemporaryDirectory() as cache:
        cold = fresh_process_seconds({"NUMBA_CACHE_DIR": cache})
        warm = fresh_process_seconds({"NUMBA_CACHE_DIR": cache})
    cached = fresh_process_seconds({})
    print(f"new process, 1 record, empty numba cache (compile): {cold:6.2f} s")
    print(f"new process, 1 record, cache filled                : {warm:6.2f} s")
    print(f"new process, 1 record, the package's own cache     : {cached:6.2f} s")

    simulate(case, records=4, seed=0)  # warm-up in this process
    timings = {}
    for workers in (1, os.cpu_count() or 1):
        best = np.inf
        for _ in range(3):
            start = time.perf_counter()
            result = simulate(case, records=args.records, seed=1, settings=Settings(workers=workers))
            best = min(best, time.perf_counter() - start)
        timings[workers] = best
        print(
            f"{args.records} records on {workers} thread(s): {best:6.3f} s wall, {args.records / best:7.1f} records/s, "
            f"{result.steps.mean():.0f} steps/record, mean F_max {result.force_max_mean / 1e6:.4f} MN"
        )

    start = time.perf_counter()
    gap = design_gap(case, target_probability=0.95, records=args.records, seed=1)
    seconds = time.perf_counter() - start
    print(f"design gap for 95 %, {args.records} records (free motion): {seconds:6.3f} s wall, "
          f"{seconds / timings[max(timings)]:.2f}x the study with contact; {100 * gap.gap:.2f} cm")

    records = ground_accelerations(case.excitation, seed=1, indices=range(args.baseline_records))
    start = time.perf_counter()
    for record in records:
        integrate(case, record, case.excitation.time_step)
    kernel_seconds = (time.perf_counter() - start) / len(records)
    start = time.perf_counter()
    for record in records:
        solve_reference(case, record, case.excitation.time_step, rtol=1e-6)
    scipy_seconds = (time.perf_counter() - start) / len(records)
    best_wall_per_record = min(timings.values()) / args.records
    print(f"scipy solve_ivp (DOP853, rtol 1e-6), same records : {scipy_seconds:7.3f} s/record")
    print(f"pounding kernel, one record with full history     : {kernel_seconds:7.4f} s/record "
          f"({scipy_seconds / kernel_seconds:.0f}x solve_ivp)")
    print(f"pounding Monte Carlo, wall per record              : {best_wall_per_record:7.4f} s/record "
          f"({scipy_seconds / best_wall_per_record:.0f}x solve_ivp, "
          f"{OPENSEES_CPU_SECONDS_PER_RECORD / 2 / best_wall_per_record:.0f}x OpenSees on 2 cores)")


if __name__ == "__main__":
    main()
