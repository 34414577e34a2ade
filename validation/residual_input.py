"""The linearization's residual as an input: the numbers behind it.

Statistical linearization replaces each Bouc-Wen law z' = g(u', z) by
c_e u' + k_e z and drops the residual r = g - c_e u' - k_e z. Along the
linearized (Gaussian) motion r lies in the higher Wiener chaoses, so it is
uncorrelated at every lag with the ground motion and the linear response: an
extra input to each yielding storey. The recommended estimator adds the
pair's response to it (``pounding.closed_form.linearization.residual``, one pass). This
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

    python3 -m validation.residual_input        # about 30 s on 2 cores
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pounding import load_case, simulate_record
from pounding.closed_form.linearization.residual import residual_response
from pounding.closed_form.pair import LinearizedPair
from pounding.studies.paper_tables import varied_case
from validation.residual_sampled import residual_response_sampled

from .record_synthesis import clough_penzien, with_excitation
from .sizes import first

RECORDS, DURATION, SETTLED, SEED = 150, 40.0, 10.0, 3  # [-], [s], [s], [-]
TRAJECTORIES = 600
CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.4", "section6-T2-0.8")


def simulated_statistics(case, records: int = RECORDS):
    """sigma_X [m], sigma_V [m/s] and corr(v1, v2) of the nonlinear pair without contact (``records`` records)."""
    free = with_excitation(case, duration=DURATION).with_contact(gap=10.0)
    first = free.contact.levels[0] - 1
    second = free.buildings[0].n_storeys + free.contact.levels[1] - 1
    sums = np.zeros(5)  # X^2, V^2, v1^2, v2^2, v1 v2
    for index in range(records):
        history = simulate_record(free, SEED, index)
        settled = history.time > SETTLED
        x = history.displacement[settled, first] - history.displacement[settled, second]
        v1, v2 = history.velocity[settled, first], history.velocity[settled, second]
        sums += [np.mean(x * x), np.mean((v1 - v2) ** 2), np.mean(v1 * v1), np.mean(v2 * v2), np.mean(v1 * v2)]
    sums /= records
    return math.sqrt(sums[0]), math.sqrt(sums[1]), sums[4] / math.sqrt(sums[2] * sums[3])


def velocity_coherence(response):
    c = response.covariance
    return c[2, 3] / math.sqrt(c[2, 2] * c[3, 3])


def against_simulation(cases: int | None = None, records: int = RECORDS) -> None:
    """Part 1 over the first ``cases`` rows (all for None), ``records`` records each."""
    print("1. Against the nonlinear pair without contact (errors: model / simulation - 1)")
    print("| case | spectrum | sigma_X linearized | with residual | sigma_V linearized | with residual | corr(v1, v2) lin. / res. / sim. |")
    print("|---|---|---|---|---|---|---|")
    rows = [(name, "Kanai-Tajimi", with_excitation(load_case(name), synthesis_factor=8)) for name in CASES]
    rows += [(name, "Clough-Penzien", clough_penzien(load_case(name))) for name in CASES]
    rows += [(f"section5-T2-0.8 G0 x {g0:g}", "Kanai-Tajimi", with_excitation(varied_case(load_case("section5-T2-0.8"), g0=g0), synthesis_factor=8))
             for g0 in (0.1, 0.01)]
    for name, spectrum, case in first(rows, cases):
        pair = LinearizedPair.of(case)
        linear, corrected = pair.stationary_response, pair.response_with_residual
        sigma_x, sigma_v, coherence = simulated_statistics(case, records)
        print(f"| {name} | {spectrum} | {linear.sigma_relative_displacement / sigma_x - 1:+.1%} | "
              f"{corrected.sigma_relative_displacement / sigma_x - 1:+.1%} | {linear.sigma_relative_velocity / sigma_v - 1:+.1%} | "
              f"{corrected.sigma_relative_velocity / sigma_v - 1:+.1%} | "
              f"{velocity_coherence(linear):.2f} / {velocity_coherence(corrected):.2f} / {coherence:.2f} |", flush=True)


def against_sampling(cases: int | None = None, trajectories: int = TRAJECTORIES) -> None:
    """Part 2 over the first ``cases`` of :data:`CASES` (all for None), ``trajectories`` sampled paths."""
    print("\n2. The residual's response, closed form against sampling (sigma of X and V driven by the residual)")
    print("| case | sigma_X closed form / sampled | sigma_V closed form / sampled |")
    print("|---|---|---|")
    for name in first(CASES, cases):
        pair = LinearizedPair.of(load_case(name))
        model, rows = pair.state_space, pair.contact_outputs
        outputs = np.array([rows[0] - rows[1], rows[2] - rows[3]])
        closed = np.sqrt(np.diag(residual_response(model, pair.buildings, outputs)))
        sampled = np.sqrt(residual_response_sampled(model, pair.buildings, outputs, trajectories=trajectories))
        print(f"| {name} | {100 * closed[0]:.3f} / {100 * sampled[0]:.3f} cm | {100 * closed[1]:.3f} / {100 * sampled[1]:.3f} cm/s |", flush=True)


def main(cases: int | None = None, records: int = RECORDS, trajectories: int = TRAJECTORIES) -> None:
    """Both parts over the first ``cases`` of each (all for None)."""
    against_simulation(cases, records)
    against_sampling(cases, trajectories)


if __name__ == "__main__":
    main()
