"""The yielding pairs' heavy tail: a kurtosis from the residual, and a count that uses it.

Reproduces the tables of "The free motion's heavy tail" in validation/HISTORY.md.
A diagnosis, not part of the estimator.

The linearized motion Y1 of an output (X or V) is Gaussian; the response Yr to
the linearization's residual r is not. To first order in r the fourth
cumulant of Y = Y1 + Yr is 4 E[Y1^3 Yr] (E[Y1 Yr] = 0, and the other terms are
of order r^2). Only the third Wiener chaos of r meets Y1^3, so with the
storey's chaos coefficients t_(3,a) (``pounding.closed_form.linearization.residual``),
c_i(tau) = Cov(Y1(t), xi_i(t - tau)) in the storey's whitened coordinates xi
and h(tau) the impulse response from the storey's z equation to Y,

    E[Y1^3 Yr] = sum over storeys int_0^inf h(tau) sum_a t_(3,a) 3! / (a! (3-a)!) 3! c_1^a c_2^(3-a) d tau

(the diagram formula: E[He_3(eta) He_a(xi_1) He_b(xi_2)] = 3! rho_1^a rho_2^b).
The excess kurtosis is that over (sigma_Y1^2 + sigma_Yr^2)^2.

A count that uses it: Winterstein's Hermite model Y / sigma = kappa (U + h (U^3 - 3 U)),
U standard normal, h matched to the kurtosis exactly (Gauss-Hermite moments)
and kappa = (1 + 6 h^2)^-1/2, applied to X and to V. An upward crossing of the
gap d faster than v comes at sigma_X p_X(d) E[V; V > v] / sigma_V per unit
of omega = sigma_V / sigma_X, in closed form:
p_X(d) sigma_X = phi(a_d) / (kappa (1 + 3 h (a_d^2 - 1))) and
E[V; V > v] / sigma_V = kappa phi(a_v) (1 + h (a_v^2 - 1)), a the Gaussian
levels of d and v (the Gaussian count is h = 0). Vanmarcke's clumps are taken
at r^2 = a_d^2 + a_v^2. A negative excess (a lighter tail) is left Gaussian.

The estimator's count is taken on the free motion (without the impacts'
damping, :func:`validation.free_count.free_estimate`), as it was measured.

    python3 -m validation.non_gaussian            # the check and the grid's free motion, about 2 min
    python3 -m validation.non_gaussian --whole    # the one-pass model's whole kurtosis, sampled, 4 cases, about 15 s
    python3 -m validation.non_gaussian --impacts  # both counts with the time cut and with the linearized
                                            # pair's instantaneous impacts, stationary grid, about 10 min
    python3 -m validation.non_gaussian --design-gap 2026   # the gap for 95 % of the one-storey pairs of a random
                                            # draw whose closed-form gap is unsafe, with the Hermite
                                            # count, first-order and simulated kurtosis, about 1.5 min
"""

from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import ndtr

from pounding import integrate, load_case
from pounding.closed_form.estimator import estimate
from pounding.closed_form.linearization.residual import residual_response, residual_storeys
from pounding.closed_form.pair import LinearizedPair
from pounding.hazard.excitation import ground_accelerations
from pounding.simulation.monte_carlo import design_gap
from pounding.studies.paper_tables import RANDOM_FAMILIES, accuracy_cases, random_cases
from validation.residual_sampled import sampled_residual_paths

from .approach_chain import linear_impacts_expected_power, linearized_pair
from .clump_models import pair_rows, phi
from .error_decomposition import (
    DOUBLE_BARRIER,
    approach_speeds,
    contact_motion,
    largest_expected_power,
    upcrossing_speeds,
    vanmarcke_clumps,
)
from .free_count import free_estimate, linearized
from .sizes import first

RECORDS, IMPACT_RECORDS, SEED = 300, 200, 11
KURTOSIS_RECORDS, DESIGN_RECORDS, TRAJECTORIES, PATHS = 240, 400, 2000, 4000
DESIGN_SEED = 2026
SETTLED = 5.0  # [s] the build-up from rest left out of the simulated kurtosis
CHECK_CASES = ("section5-T2-0.4", "section5-T2-0.8", "section6-T2-0.4", "section6-T2-0.8")
_NODES, _WEIGHTS = np.polynomial.hermite_e.hermegauss(40)
_WEIGHTS = _WEIGHTS / _WEIGHTS.sum()


def fourth_cumulant_first_order(model, linearized, outputs, count: int = 6000) -> np.ndarray:
    """4 E[Y1^3 Yr] of each output row (over the pair's state) [output unit^4]."""
    storeys = residual_storeys(model, linearized)
    covariance = model.covariance()
    values, vectors = np.linalg.eig(model.matrix)
    span = min(60.0, 25.0 / float(np.min(-values.real)))  # e^-25: the slowest mode has died out
    lags = np.linspace(0.0, span, count)
    propagators = ((vectors[None] * np.exp(np.outer(lags, values))[:, None, :]) @ np.linalg.inv(vectors)).real  # e^(A tau)
    total = np.zeros(outputs.shape[0])
    for storey in storeys:
        loads = np.linalg.solve(storey.whitening, storey.rows @ covariance)  # L^-1 R P
        lagged = np.einsum("an,tmn,om->toa", loads, propagators, outputs)  # c(tau) = L^-1 R P e^(A^T tau) out^T
        impulse = np.einsum("om,tm->to", outputs, propagators[:, :, storey.input_state])
        third = storey.chaos[0]  # t_(3, a)
        moment = sum(third[a] * 36.0 / (math.factorial(a) * math.factorial(3 - a)) * lagged[..., 0] ** a * lagged[..., 1] ** (3 - a)
                     for a in range(4))
        total += np.trapezoid(impulse * moment, lags, axis=0)
    return 4.0 * total


def excess_kurtosis(case_or_pair) -> np.ndarray:
    """First-order excess kurtosis of X and V of the linearized pair with the residual's response."""
    pair = linearized(case_or_pair)
    model, _, rows = pair_rows(pair)
    variance = np.einsum("ki,ij,kj->k", rows, model.covariance(), rows) + np.diag(residual_response(model, pair.buildings, rows))
    return fourth_cumulant_first_order(model, pair.buildings, rows) / variance**2


def hermite_coefficient(excess: float) -> float:
    """h of Y = kappa (U + h He_3(U)) with the given excess kurtosis (0 if not positive)."""
    if excess <= 0.0:
        return 0.0
    he3 = _NODES**3 - 3.0 * _NODES

    def mismatch(h):
        y = _NODES + h * he3
        return np.sum(_WEIGHTS * y**4) / (1.0 + 6.0 * h * h) ** 2 - 3.0 - excess

    return brentq(mismatch, 0.0, 0.3)  # below 1/3 the transform is monotone


def gaussian_level(y, h: float):
    """a with (a + h (a^3 - 3 a)) / sqrt(1 + 6 h^2) = y (Cardano: one real root for 0 <= h < 1/3)."""
    y = np.asarray(y, dtype=float) * math.sqrt(1.0 + 6.0 * h * h)
    if h == 0.0:
        return y
    p, q = (1.0 - 3.0 * h) / h, -y / h
    root = np.sqrt(0.25 * q * q + p**3 / 27.0)
    return np.cbrt(-0.5 * q + root) + np.cbrt(-0.5 * q - root)


def expected_power(result, power: float, h_x: float = 0.0, h_v: float = 0.0, time_cut: bool = False, points: int = 600) -> float:
    """E[V_max^p] from the Hermite count (Gaussian for h = 0) over the estimator's sigma
    history, with Vanmarcke's clumps, and with the time cut 1 / P(X < d) or without."""
    crossings = result.crossings
    gap = result.case.contact.gap
    kappa_x, kappa_v = 1.0 / math.sqrt(1.0 + 6.0 * h_x * h_x), 1.0 / math.sqrt(1.0 + 6.0 * h_v * h_v)
    clumping = DOUBLE_BARRIER * crossings.bandwidth**1.2
    speeds = np.linspace(0.0, 12.0 * crossings.sigma_v.max(), points)
    expected = np.zeros(points)
    for sigma_x, sigma_v, weight in zip(crossings.sigma_x, crossings.sigma_v, crossings.weights):
        a_d, a_v = float(gaussian_level(gap / sigma_x, h_x)), gaussian_level(speeds / sigma_v, h_v)
        level = phi(a_d) / (kappa_x * (1.0 + 3.0 * h_x * (a_d * a_d - 1.0)))
        faster = kappa_v * phi(a_v) * (1.0 + h_v * (a_v * a_v - 1.0))
        below = ndtr(a_d) if time_cut else 1.0
        expected += weight * sigma_v / sigma_x * level * faster / below * vanmarcke_clumps(np.hypot(a_d, a_v), clumping)
    return float(np.trapezoid(-np.expm1(-expected), speeds**power))


def hermite_required_gap(result, h_x: float, h_v: float) -> float:
    """The estimator's design rule (every approach counted, time cut, no clumps: Lambda(0; d) = -ln p)
    with the Hermite count in place of the Gaussian one; h = 0 gives ``result.required_gap``."""
    crossings = result.crossings
    kappa_x, kappa_v = 1.0 / math.sqrt(1.0 + 6.0 * h_x * h_x), 1.0 / math.sqrt(1.0 + 6.0 * h_v * h_v)
    faster = kappa_v * phi(0.0) * (1.0 - h_v)  # E[V; V > 0] / sigma_V

    def approaches(gap):
        total = 0.0
        for sigma_x, sigma_v, weight in zip(crossings.sigma_x, crossings.sigma_v, crossings.weights):
            a_d = float(gaussian_level(gap / sigma_x, h_x))
            level = phi(a_d) / (kappa_x * (1.0 + 3.0 * h_x * (a_d * a_d - 1.0)))
            total += weight * sigma_v / sigma_x * level * faster / ndtr(a_d)
        return total

    return brentq(lambda gap: approaches(gap) + math.log(result.target_probability), 0.0, 10.0 * crossings.sigma_x.max())


def simulated_excess_kurtosis(case, records: int = KURTOSIS_RECORDS) -> np.ndarray:
    """Excess kurtosis of X, V and of the two contact floors' displacements x1, x2 of the free motion, each
    sample over the ensemble's RMS at its time (so a modulated record's envelope does not count), where that
    RMS exceeds half its largest value and after the first SETTLED seconds."""
    free = case.with_contact(gap=10.0)
    step = case.excitation.time_step
    level_1, level_2 = case.contact.levels
    paths = []
    for record in ground_accelerations(case.excitation, SEED, np.arange(records)):
        history = integrate(free, record, step)
        time = np.arange(record.size) * step
        velocity = history.velocity[:, history.floor(1, level_1)] - history.velocity[:, history.floor(2, level_2)]
        floors = [history.displacement[:, history.floor(b, level)] for b, level in ((1, level_1), (2, level_2))]
        paths.append([np.interp(time, history.time, y) for y in (history.penetration + 10.0, velocity, *floors)])
    paths = np.array(paths)  # (records, X V x1 x2, time)
    rms = np.sqrt(np.mean(paths**2, axis=0))
    excess = []
    for output in range(4):
        keep = (rms[output] > 0.5 * rms[output].max()) & (np.arange(rms.shape[1]) * step >= SETTLED)
        standard = paths[:, output, keep] / rms[output, keep]
        excess.append(float(np.mean(standard**4) - 3.0))
    return np.array(excess)


def design_gap_table(seed: int, records: int = DESIGN_RECORDS, limit: float = 0.072, cases: int | None = None,
                     kurtosis_records: int = KURTOSIS_RECORDS) -> None:
    """The one-storey pairs of ``random_cases(seed)`` (the first ``cases`` of them, all for None) whose
    closed-form gap for 95 % lets more than ``limit`` of ``records`` free records (seed 9) reach it, with
    the Hermite design rule under the first-order and the simulated kurtosis (``kurtosis_records``
    records): the fraction of the records that reach each gap."""
    print("| case | excess kurtosis of X: first order / simulated | of V: first order / simulated | of x1, x2: simulated "
          "| Monte Carlo gap (cm) | Gaussian: gap, fraction | Hermite, first order | Hermite, simulated kurtosis |")
    print("|---|---|---|---|---|---|---|---|")
    families = [family for family, count in RANDOM_FAMILIES for _ in range(count)]
    one_storey = (case for case, family in zip(random_cases(seed), families) if family in ("SDOF", "SDOF modulated"))
    for case in first(one_storey, cases):
        pair = LinearizedPair.of(case)
        result = estimate(pair, target_probability=0.95)
        free = design_gap(case, 0.95, records=records, seed=9)
        if free.pounding_fraction(result.required_gap) <= limit:
            continue
        assert abs(hermite_required_gap(result, 0.0, 0.0) / result.required_gap - 1.0) < 1e-4  # the estimator's rule (its bisection tolerance)
        first_order, simulated = excess_kurtosis(pair), simulated_excess_kurtosis(case, kurtosis_records)
        cells = []
        for excess in (np.zeros(2), first_order, simulated[:2]):
            gap = hermite_required_gap(result, *(hermite_coefficient(e) for e in excess))
            cells.append(f"{100 * gap:.2f}, {free.pounding_fraction(gap):.3f}")
        print(f"| {case.name.strip()} | {first_order[0]:+.2f} / {simulated[0]:+.2f} | {first_order[1]:+.2f} / {simulated[1]:+.2f} "
              f"| {simulated[2]:+.2f}, {simulated[3]:+.2f} | {100 * free.gap:.2f} | " + " | ".join(cells) + " |", flush=True)


def _kurtosis(samples) -> float:
    samples = samples - samples.mean()
    return float(np.mean(samples**4) / np.mean(samples**2) ** 2)


def check_table(trajectories: int = TRAJECTORIES, duration: float = 30.0, step: float = 0.004, cases: int | None = None) -> None:
    """E[Y1^3 Yr] / sigma_Y1^4 in closed form against the linearized pair driven by its own
    residual, sampled (three seeds: the sampled fourth moments of the Section 6 frames' heavy Yr scatter);
    the first ``cases`` of :data:`CHECK_CASES` (all for None)."""
    print("| case | X: closed form | X: sampled, 3 seeds | V: closed form | V: sampled, 3 seeds |")
    print("|---|---|---|---|---|")
    for name in first(CHECK_CASES, cases):
        pair = LinearizedPair.of(load_case(name))
        model, _, rows = pair_rows(pair)
        variance = np.einsum("ki,ij,kj->k", rows, model.covariance(), rows)
        closed = fourth_cumulant_first_order(model, pair.buildings, rows) / 4.0 / variance**2
        sampled = np.array([_sampled_third_moment(model, pair.buildings, rows, trajectories, duration, step, seed) for seed in (2, 5, 9)])
        print(f"| {name} | {closed[0]:+.3f} | " + ", ".join(f"{s:+.3f}" for s in sampled[:, 0])
              + f" | {closed[1]:+.3f} | " + ", ".join(f"{s:+.3f}" for s in sampled[:, 1]) + " |", flush=True)


def _sampled_third_moment(model, linearized, rows, trajectories, duration, step, seed) -> np.ndarray:
    """E[Y1^3 Yr] / sigma_Y1^4 by the sampling of ``residual_response_sampled``
    (the linearized pair stepped exactly, stationary start, and a copy driven by
    the residual evaluated along it, from rest); the last 6 s are kept."""
    linear, response = [], []
    for state, driven in sampled_residual_paths(model, linearized, trajectories, duration, step, seed, kept=6.0, every=5):
        linear.append(state @ rows.T)
        response.append(driven @ rows.T)
    linear, response = np.concatenate(linear), np.concatenate(response)
    return np.mean(linear**3 * response, axis=0) / np.mean(linear**2, axis=0) ** 2


WHOLE_CASES = ("section5-T2-0.8", "T1 1.2 T2 2.0", "s6-T2-0.6 G0x10 e0.4", "s5-T2-0.8 G0x0.25")


def whole_kurtosis_table(trajectories: int = TRAJECTORIES, duration: float = 20.0, step: float = 0.004,
                         cases: int | None = None) -> None:
    """The one-pass model's own kurtosis of X and V, Y1 + Yr sampled whole, beside the first order;
    the first ``cases`` of :data:`WHOLE_CASES` (all for None)."""
    print("| case | X: first order / sampled whole | V: first order / sampled whole |")
    print("|---|---|---|")
    for case in first((case for case in accuracy_cases() if case.name in WHOLE_CASES), cases):
        pair = LinearizedPair.of(case)
        model, _, rows = pair_rows(pair)
        total = np.concatenate([(state + driven) @ rows.T for state, driven in
                                sampled_residual_paths(model, pair.buildings, trajectories, duration, step, 2, kept=6.0, every=5)])
        whole = np.mean(total**4, axis=0) / np.mean(total**2, axis=0) ** 2
        first_order = 3.0 + excess_kurtosis(pair)
        print(f"| {case.name} | {first_order[0]:.2f} / {whole[0]:.2f} | {first_order[1]:.2f} / {whole[1]:.2f} |", flush=True)


def free_grid_table(cases: int | None = None, records: int = RECORDS) -> None:
    """The grid's free motion (its first ``cases``, all for None; no contact, ``records`` records):
    kurtosis simulated and predicted; the Gaussian and the Hermite count's E[V_max^p] against the simulated one."""
    print("| case | gap / sigma_X | kurtosis of X: simulated / first order | kurtosis of V: simulated / first order "
          "| Gaussian count / free motion | Hermite count / free motion |")
    print("|---|---|---|---|---|---|")
    errors = []
    for case in first(accuracy_cases(), cases):
        pair = LinearizedPair.of(case)
        result = free_estimate(pair)
        power = 1.0 if case.contact.model == "linear" else 1.2
        excess = excess_kurtosis(pair)
        largest, x_samples, v_samples = [], [], []
        settled = int(SETTLED / case.excitation.time_step)
        for record in ground_accelerations(case.excitation, SEED, np.arange(records)):
            x, v = contact_motion(case, record, contact=False)
            largest.append(max(upcrossing_speeds(x, v, case.contact.gap).max(initial=0.0), 0.0))
            x_samples.append(x[settled::5])
            v_samples.append(v[settled::5])
        target = float(np.mean(np.array(largest) ** power))
        gaussian = expected_power(result, power) / target - 1.0
        hermite = expected_power(result, power, *(hermite_coefficient(e) for e in excess)) / target - 1.0
        errors.append((case.excitation.stationary, gaussian, hermite))
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} "
              f"| {_kurtosis(np.concatenate(x_samples)):.2f} / {3.0 + excess[0]:.2f} | {_kurtosis(np.concatenate(v_samples)):.2f} / {3.0 + excess[1]:.2f} "
              f"| {gaussian:+.1%} | {hermite:+.1%} |", flush=True)
    _summary(np.array([e[1:] for e in errors if e[0]]), ("Gaussian", "Hermite"), "stationary cases")


def impacts_table(cases: int | None = None, records: int = IMPACT_RECORDS, paths: int = PATHS) -> None:
    """E[V_max^p] of the approaches, 2 x 2: the Gaussian or the Hermite count, with the time cut
    (the estimator's count) or with what the linearized pair's instantaneous impacts add
    (``approach_chain.linear_impacts_expected_power``, ``paths`` paths), against the simulated
    impacting motion (``records`` records); the first ``cases`` stationary cases of the grid (all for None)."""
    print("| case | gap / sigma_X | Gaussian, time cut (the estimator) | Hermite, time cut | Gaussian x linearized impacts "
          "| Hermite x linearized impacts |")
    print("|---|---|---|---|---|---|")
    errors = []
    # The linearized pair is simulated in its stationary law.
    for case in first((case for case in accuracy_cases() if case.excitation.stationary), cases):
        pair = LinearizedPair.of(case)
        result = free_estimate(pair)
        power = 1.0 if case.contact.model == "linear" else 1.2
        h = [hermite_coefficient(e) for e in excess_kurtosis(pair)]
        impacting, _ = approach_speeds(case, records)
        target = largest_expected_power(impacting, power)
        with_impacts, without = linear_impacts_expected_power(case, linearized_pair(pair), power, paths)
        added = with_impacts / without
        row = [expected_power(result, power, time_cut=True), expected_power(result, power, *h, time_cut=True),
               expected_power(result, power) * added, expected_power(result, power, *h) * added]
        row = [value / target - 1.0 for value in row]
        errors.append(row)
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | " + " | ".join(f"{e:+.1%}" for e in row) + " |",
              flush=True)
    _summary(np.array(errors), ("Gaussian, time cut", "Hermite, time cut", "Gaussian x impacts", "Hermite x impacts"), "cases")


def _summary(errors: np.ndarray, labels, what: str) -> None:
    errors = np.abs(errors)
    print()
    for label, column in zip(labels, errors.T):
        print(f"{label}: within 10 % on {int(np.sum(column <= 0.10))} of {column.size} {what}, within 5 % on {int(np.sum(column <= 0.05))}, "
              f"median {np.median(column):.1%}")


TABLES = ("check", "whole", "impacts", "design-gap")


def main(table: str = "check", cases: int | None = None, records: int | None = None, trajectories: int = TRAJECTORIES,
         seed: int = DESIGN_SEED, paths: int = PATHS, kurtosis_records: int = KURTOSIS_RECORDS, limit: float = 0.072) -> None:
    """Print ``table`` (one of :data:`TABLES`) over its first ``cases`` (all for None):

    - ``check``: the closed form against sampling (``trajectories`` paths), then the grid's free motion;
    - ``whole``: the one-pass model's whole kurtosis (``trajectories`` paths);
    - ``impacts``: the counts with the linearized pair's instantaneous impacts (``paths`` paths);
    - ``design-gap``: the unsafe one-storey pairs of the draw ``seed`` (``limit``: the fraction above
      which a gap is unsafe; ``kurtosis_records`` records for the simulated kurtosis).

    ``records``: the Monte Carlo records (None: each table's own, 300, 200 or 400)."""
    if table == "design-gap":
        design_gap_table(seed, records or DESIGN_RECORDS, limit, cases, kurtosis_records)
    elif table == "impacts":
        impacts_table(cases, records or IMPACT_RECORDS, paths)
    elif table == "whole":
        whole_kurtosis_table(trajectories, cases=cases)
    elif table == "check":
        check_table(trajectories, cases=cases)
        print()
        free_grid_table(cases, records or RECORDS)
    else:
        raise ValueError(f"table must be one of {', '.join(TABLES)}, got {table!r}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--design-gap", type=int, metavar="SEED", help="the unsafe one-storey pairs of a random draw")
    group.add_argument("--impacts", dest="table", action="store_const", const="impacts", help="with the linearized pair's impacts")
    group.add_argument("--whole", dest="table", action="store_const", const="whole", help="the one-pass model's whole kurtosis")
    arguments = parser.parse_args()
    if arguments.design_gap is not None:
        main("design-gap", seed=arguments.design_gap)
    else:
        main(arguments.table or "check")
