"""The linearization's residual as an input: the numbers behind it.

Statistical linearization replaces each Bouc-Wen law z' = g(u', z) by
c_e u' + k_e z and drops the residual r = g - c_e u' - k_e z. Along the
linearized (Gaussian) motion r lies in the higher Wiener chaoses, so it is
uncorrelated at every lag with the ground motion and the linear response: an
extra input to each yielding storey. The recommended estimator adds the
pair's response to it (``pounding.linearization.residual``, one pass). This
script prints, for the contact floors' relative motion:

1. sigma_X, sigma_V and the correlation of the two floors' velocities: the
   linearized pair, the same with the residual's response, and the nonlinear
   pair simulated without contact (150 records of 40 s, statistics after
   10 s). With the Kanai-Tajimi spectrum the records keep its low end
   (synthesis factor 8); the Clough-Penzien spectrum (omega_f = 2 rad/s,
   xi_f = 0.6) has none. Also two weaker intensities (the Section 5 law has
   n = 1, so it yields a little at any amplitude);
2. the residual's response in closed form (chaos expansion, diagram formula,
   FFT) against a Monte Carlo of the linearized pair driven by its own
   residual, evaluated along sampled trajectories (600, started stationary,
   14 s): an independent check of the computation, not of the model.

    python3 docs/residual_input.py        # about 30 s on 2 cores
"""

from __future__ import annotations

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from pounding import load_case  # noqa: E402
from pounding.excitation import CloughPenzien  # noqa: E402
from pounding.linearization import linearize_pair, pair_state_space  # noqa: E402
from pounding.linearization.residual import residual_response, residual_response_sampled  # noqa: E402
from pounding.response import contact_output_matrix, response_lyapunov, response_with_residual  # noqa: E402
from pounding.simulation import simulate_record  # noqa: E402
from pounding.validation import _vary  # noqa: E402

RECORDS, DURATION, SETTLED, SEED = 150, 40.0, 10.0, 3  # [-], [s], [s], [-]
CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.4", "section6-T2-0.8")


def with_excitation(case, **changes):
    return dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, **changes))


def clough_penzien(case):
    s = case.excitation.spectrum
    return with_excitation(case, spectrum=CloughPenzien(s.G0, s.omega_g, s.xi_g, omega_f=2.0, xi_f=0.6))


def simulated_statistics(case):
    """sigma_X [m], sigma_V [m/s] and corr(v1, v2) of the nonlinear pair without contact."""
    free = dataclasses.replace(with_excitation(case, duration=DURATION), contact=dataclasses.replace(case.contact, gap=10.0))
    first = free.contact.levels[0] - 1
    second = free.buildings[0].n_storeys + free.contact.levels[1] - 1
    sums = np.zeros(5)  # X^2, V^2, v1^2, v2^2, v1 v2
    for index in range(RECORDS):
        history = simulate_record(free, SEED, index)
        settled = history.time > SETTLED
        x = history.displacement[settled, first] - history.displacement[settled, second]
        v1, v2 = history.velocity[settled, first], history.velocity[settled, second]
        sums += [np.mean(x * x), np.mean((v1 - v2) ** 2), np.mean(v1 * v1), np.mean(v2 * v2), np.mean(v1 * v2)]
    sums /= RECORDS
    return math.sqrt(sums[0]), math.sqrt(sums[1]), sums[4] / math.sqrt(sums[2] * sums[3])


def velocity_coherence(response):
    c = response.covariance
    return c[2, 3] / math.sqrt(c[2, 2] * c[3, 3])


def against_simulation() -> None:
    print("1. Against the nonlinear pair without contact (errors: model / simulation - 1)")
    print("| case | spectrum | sigma_X linearized | with residual | sigma_V linearized | with residual | corr(v1, v2) lin. / res. / sim. |")
    print("|---|---|---|---|---|---|---|")
    rows = [(name, "Kanai-Tajimi", with_excitation(load_case(name), synthesis_factor=8)) for name in CASES]
    rows += [(name, "Clough-Penzien", clough_penzien(load_case(name))) for name in CASES]
    rows += [(f"section5-T2-0.8 G0 x {g0:g}", "Kanai-Tajimi", with_excitation(_vary(load_case("section5-T2-0.8"), g0=g0), synthesis_factor=8))
             for g0 in (0.1, 0.01)]
    for name, spectrum, case in rows:
        linear, corrected = response_lyapunov(case), response_with_residual(case)
        sigma_x, sigma_v, coherence = simulated_statistics(case)
        print(f"| {name} | {spectrum} | {linear.sigma_relative_displacement / sigma_x - 1:+.1%} | "
              f"{corrected.sigma_relative_displacement / sigma_x - 1:+.1%} | {linear.sigma_relative_velocity / sigma_v - 1:+.1%} | "
              f"{corrected.sigma_relative_velocity / sigma_v - 1:+.1%} | "
              f"{velocity_coherence(linear):.2f} / {velocity_coherence(corrected):.2f} / {coherence:.2f} |", flush=True)


def against_sampling() -> None:
    print("\n2. The residual's response, closed form against sampling (sigma of X and V driven by the residual)")
    print("| case | sigma_X closed form / sampled | sigma_V closed form / sampled |")
    print("|---|---|---|")
    for name in CASES:
        case = load_case(name)
        linearized = linearize_pair(case)
        model = pair_state_space(case, linearized)
        rows = contact_output_matrix(case, model)
        outputs = np.array([rows[0] - rows[1], rows[2] - rows[3]])
        closed = np.sqrt(np.diag(residual_response(model, linearized, outputs)))
        sampled = np.sqrt(residual_response_sampled(model, linearized, outputs))
        print(f"| {name} | {100 * closed[0]:.3f} / {100 * sampled[0]:.3f} cm | {100 * closed[1]:.3f} / {100 * sampled[1]:.3f} cm/s |", flush=True)


def main() -> None:
    against_simulation()
    against_sampling()


if __name__ == "__main__":
    main()
