"""Speed of the closed-form estimators, printed as figures.

- one estimate of the Section 5 case (T1 = 1.2 s, T2 = 0.4 s), both estimators,
  linearization included: median of repeated calls after warm-up;
- the linearization alone, the response to the linearization's residual alone
  (the largest part of an estimate of a yielding pair), and the impacts'
  damping of the motion (its data and the fixed point at the gap);
- an estimate on a pair already linearized (``estimate(pair)``: the pair's
  cached response, FRFs and history reused);
- an F_e-versus-gap curve of 100 gaps beyond one estimate (the linearization
  and the response statistics do not depend on the gap: Estimate.gap_curve),
  and from scratch;
- the same for the modulated (non-stationary) case;
- ``pounding estimate section5-T2-0.4 --json`` through the command line's
  entry point, in process (``pounding.cli.commands.main``: argument parsing, case
  load, estimate, JSON; stdout redirected), median of repeated calls after
  warm-up, beside baselines timed in the same process: the linearization
  alone and the Monte Carlo mean of the same case from 300 records (what the
  closed form saves).

Run: python3 benchmarks/estimate.py
"""

from __future__ import annotations

import json
import time

import numpy as np
from timing import command_output, median_seconds  # noqa: E402 (this folder is on the path)

from pounding import load_case, simulate
from pounding.closed_form.estimator import estimate, force_versus_gap
from pounding.closed_form.linearization import linearize_pair
from pounding.closed_form.linearization.residual import residual_response
from pounding.closed_form.pair import LinearizedPair

CLI_CASE = "section5-T2-0.4"
CLI_TARGET = 5e-3  # [s] median of one in-process `pounding estimate CASE --json`


def _monte_carlo_seconds(case, records: int = 300) -> float:
    simulate(case, records=4, seed=0)  # warm-up (JIT cache load)
    start = time.perf_counter()
    simulate(case, records=records, seed=1)
    return time.perf_counter() - start


def main() -> None:
    gaps = np.linspace(0.0, 0.10, 100)
    for name in ("section5-T2-0.4", "section5-T2-0.4-nonstationary"):
        case = load_case(name)
        one = median_seconds(lambda: estimate(case))
        result = estimate(case)
        curve = median_seconds(lambda: result.gap_curve(gaps))
        standalone = median_seconds(lambda: force_versus_gap(case, gaps))
        lin = median_seconds(lambda: linearize_pair(case))
        buildings = linearize_pair(case)

        def solved_pair():
            """A fresh pair with its state space and stationary response, untimed."""
            pair = LinearizedPair(case, buildings)
            pair.stationary_response
            return pair

        def with_residual():
            pair = solved_pair()
            pair.response_with_residual
            return pair

        residual = median_seconds(lambda pair: residual_response(pair.state_space, pair.buildings, pair.contact_outputs),
                                  setup=solved_pair)
        damping = median_seconds(lambda pair: pair.impact_damping.damped([case.contact.gap]), setup=with_residual)
        pair = LinearizedPair.of(case)
        estimate(pair)  # its cached quantities filled
        reused = median_seconds(lambda: estimate(pair))
        print(f"{name}:")
        print(f"  one estimate (both estimators)        {1e3 * one:7.2f} ms   (target 5 ms for the stationary case)")
        print(f"    of which the linearization         {1e3 * lin:7.2f} ms   (the estimate is {one / lin:.1f} times it, "
              "a ratio this shared machine's load moves less)")
        print(f"    of which the residual's response   {1e3 * residual:7.2f} ms")
        print(f"    of which the impacts' damping      {1e3 * damping:7.2f} ms   (its data and the fixed point at the gap)")
        print(f"  estimate on a pair already linearized {1e3 * reused:6.2f} ms   (estimate(pair): its response, FRFs and history reused)")
        print(f"  F_e versus 100 gaps beyond one estimate {1e3 * curve:5.2f} ms   (target 10 ms; Estimate.gap_curve)")
        print(f"  force_versus_gap from scratch        {1e3 * standalone:7.2f} ms")

    argv = ["estimate", CLI_CASE, "--json"]
    printed = json.loads(command_output(argv))  # the warm-up, and a check that it printed one JSON object
    assert printed["force_expected"] > 0.0, printed
    command = median_seconds(lambda: command_output(argv), repeats=50)
    case = load_case(CLI_CASE)
    lin = median_seconds(lambda: linearize_pair(case))
    monte_carlo = _monte_carlo_seconds(case)
    verdict = "within" if command <= CLI_TARGET else "OVER"
    print(f"pounding {' '.join(argv)} (in process, pounding.cli.commands.main; parse, load, estimate, JSON):")
    print(f"  median of 50 calls                   {1e3 * command:7.2f} ms   ({verdict} the target of {1e3 * CLI_TARGET:g} ms)")
    print(f"  baseline: the linearization alone    {1e3 * lin:7.2f} ms   (the command is {command / lin:.1f} times it)")
    print(f"  baseline: Monte Carlo, 300 records   {1e3 * monte_carlo:7.1f} ms   ({monte_carlo / command:.0f}x the command)")
    print(f"Monte Carlo, 300 records, same case     {1e3 * monte_carlo:7.1f} ms "
          f"({monte_carlo / median_seconds(lambda: estimate(case), 10):.0f}x one estimate)")


if __name__ == "__main__":
    main()
