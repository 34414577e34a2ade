"""Speed of the closed-form estimators, printed as figures.

- one estimate of the Section 5 case (T1 = 1.2 s, T2 = 0.4 s), both estimators,
  linearization included: median of repeated calls after warm-up;
- the response to the linearization's residual alone (the largest part of
  an estimate of a yielding pair), and the impacts' damping of the motion;
- an F_e-versus-gap curve of 100 gaps beyond one estimate (the linearization
  and the response statistics do not depend on the gap: Estimate.gap_curve),
  and from scratch;
- the same for the modulated (non-stationary) case;
- baseline in the same process: the Monte Carlo mean of the same case from
  300 records, to say what the closed form saves.

Run: python3 benchmarks/estimate.py
"""

from __future__ import annotations

import time

import numpy as np

from pounding import load_case, simulate
from pounding.estimator import estimate, force_versus_gap
from pounding.impact_damping import impact_damping
from pounding.linearization import linearize_pair, pair_state_space
from pounding.response import response_lyapunov, response_with_residual


def median_seconds(function, repeats: int = 30) -> float:
    function()  # warm-up (JIT cache load, tables)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main() -> None:
    gaps = np.linspace(0.0, 0.10, 100)
    for name in ("section5-T2-0.4", "section5-T2-0.4-nonstationary"):
        case = load_case(name)
        one = median_seconds(lambda: estimate(case))
        result = estimate(case)
        curve = median_seconds(lambda: result.gap_curve(gaps))
        standalone = median_seconds(lambda: force_versus_gap(case, gaps))
        lin = median_seconds(lambda: linearize_pair(case))
        linearized = linearize_pair(case)
        model = pair_state_space(case, linearized)
        linear = response_lyapunov(case, linearized, model)
        residual = median_seconds(lambda: response_with_residual(case, linearized, model, linear))
        response = response_with_residual(case, linearized, model, linear)
        damping = median_seconds(lambda: impact_damping(case, linearized, model, response).damped([case.contact.gap]))
        print(f"{name}:")
        print(f"  one estimate (both estimators)        {1e3 * one:7.2f} ms   (target 5 ms for the stationary case)")
        print(f"    of which the linearization         {1e3 * lin:7.2f} ms   (the estimate is {one / lin:.1f} times it, "
              "a ratio this shared machine's load moves less)")
        print(f"    of which the residual's response   {1e3 * residual:7.2f} ms")
        print(f"    of which the impacts' damping      {1e3 * damping:7.2f} ms   (its data and the fixed point at the gap)")
        print(f"  F_e versus 100 gaps beyond one estimate {1e3 * curve:5.2f} ms   (target 10 ms; Estimate.gap_curve)")
        print(f"  force_versus_gap from scratch        {1e3 * standalone:7.2f} ms")
    case = load_case("section5-T2-0.4")
    simulate(case, records=4, seed=0)
    start = time.perf_counter()
    simulate(case, records=300, seed=1)
    monte_carlo = time.perf_counter() - start
    print(f"Monte Carlo, 300 records, same case     {1e3 * monte_carlo:7.1f} ms "
          f"({monte_carlo / median_seconds(lambda: estimate(case), 10):.0f}x one estimate)")


if __name__ == "__main__":
    main()
