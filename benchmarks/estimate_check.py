"""Speed of ``pounding estimate --check`` (issue 32), printed as figures.

On the paper's Section 5 case (T1 = 1.2 s, T2 = 0.4 s), through the command line's entry point in process
(``pounding.cli.commands.main``, stdout captured), after a warm-up:

- ``estimate CASE --json``, median of 50 calls, against the linearization alone timed in the same process (the
  ratio benchmarks/estimate.py gives: ``--check`` must leave it as it was);
- ``estimate CASE --check --json`` (the default count: records until the mean is known within 5 %), median of a few
  calls: its wall time and its CPU time (all threads), against the 1 s of one core issue 32 asks;
- the check on one thread through the library (``check_estimate``, ``Settings(workers=1)``), and beside it the
  baseline of a plain ``simulate`` of as many records on one thread: the check's cost over the records it needs.

Run: python3 benchmarks/estimate_check.py [--repeats 5]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
from timing import command_output, median_seconds  # noqa: E402 (this folder is on the path)

from pounding import Settings, load_case, simulate
from pounding.closed_form.estimator import estimate
from pounding.closed_form.linearization import linearize_pair
from pounding.studies.check import check_estimate

CASE = "section5-T2-0.4"
TARGET_CPU = 1.0  # [s] of one core: estimate --check on CASE, the default count (issue 32)


def _wall_and_cpu(function, repeats: int) -> tuple[float, float]:
    """Median wall time and median CPU time of the process (every thread) of ``function()``, after a warm-up."""
    function()
    walls, cpus = [], []
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        function()
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return float(np.median(walls)), float(np.median(cpus))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="calls of each timed check (default 5)")
    args = parser.parse_args()
    case = load_case(CASE)

    plain = ["estimate", CASE, "--json"]
    checked = ["estimate", CASE, "--check", "--json"]
    json.loads(command_output(plain))  # warm-up, and a check that it printed one JSON object
    printed = json.loads(command_output(checked))
    records = printed["check"]["records"]
    estimate_seconds = median_seconds(lambda: command_output(plain), repeats=50)
    linearization = median_seconds(lambda: linearize_pair(case))
    check_wall, check_cpu = _wall_and_cpu(lambda: command_output(checked), args.repeats)

    result = estimate(case)
    one_thread = Settings(workers=1)
    library_wall, _ = _wall_and_cpu(lambda: check_estimate(result, settings=one_thread), args.repeats)
    records_wall, _ = _wall_and_cpu(lambda: simulate(case, records=records, seed=0, settings=one_thread), args.repeats)

    verdict = "within" if check_cpu <= TARGET_CPU else "OVER"
    print(f"case {CASE}: the check ran {records} records (seed 0) and says: {printed['answer_source']} stands, "
          f"{printed['force_answer'] / 1e3:.1f} kN; gap {100 * printed['gap_answer']:.2f} cm from the {printed['gap_source']}")
    print(f"pounding {' '.join(plain)}")
    print(f"  median of 50 calls                    {1e3 * estimate_seconds:7.2f} ms   (the linearization alone "
          f"{1e3 * linearization:.2f} ms; the command is {estimate_seconds / linearization:.1f} times it)")
    print(f"pounding {' '.join(checked)}")
    print(f"  median of {args.repeats} calls, wall              {1e3 * check_wall:7.1f} ms   "
          f"({check_wall / estimate_seconds:.0f}x the estimate alone)")
    print(f"  median of {args.repeats} calls, CPU of all threads {1e3 * check_cpu:7.1f} ms   "
          f"({verdict} the target of {TARGET_CPU:g} s of one core)")
    print("on one thread, through the library")
    print(f"  check_estimate                        {1e3 * library_wall:7.1f} ms")
    print(f"  baseline: simulate, {records} records       {1e3 * records_wall:7.1f} ms   "
          f"(the check is {library_wall / records_wall:.2f} times it: the free run for the gap, the chunks)")


if __name__ == "__main__":
    main()
