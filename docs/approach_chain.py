"""What the impacts add to the largest approach speed: a chain of approaches.

Reproduces the table of "A chain of approaches" in docs/estimator.md. A
diagnosis, not part of the estimator.

After an impact at speed v the pair leaves the gap d at e v (the law's
restitution), and the next approach is the first upward crossing of d by the
motion restarting from X = d, V = -e v. Its law is taken from the linearized
pair's Gaussian motion conditioned on (X, V) alone: Z(s) given Z(0) = z is
Gaussian with mean R(s) z and covariance I - R(s) R(s)^T, R(s) the normalized
autocovariance of Z = (X / sigma_X, V / sigma_V) (a Markov approximation: the
other states keep their law given X and V, and the ground keeps forcing).
Rice's intensity of upward crossings of d under that law, times the
probability of none before, gives the first approach's density over
(lag, speed). Sampling that chain over a record's duration gives E[V_max^p]
with impacts; the free motion is the same chain restarting from (d, +v), the
next upward crossing after one. Their ratio, "what the impacts add", is set
against the simulated one (impacting motion over the same records without
contact) and against what the estimator's time cut adds to Rice's count.
Stationary cases only: the chain starts in the stationary state. Beside them,
the linearized pair itself simulated from rest with instantaneous impacts (the
velocity jump at each upward crossing of the gap): what the chains approximate,
and how much of the impacts' effect a Gaussian model can hold at all.

    python3 docs/approach_chain.py         # 8 cases, about 3 min
    python3 docs/approach_chain.py --all   # every stationary case of the grid, about 15 min
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from clump_models import _phi, pair_lags, pair_rows  # noqa: E402  (beside this script)
from error_decomposition import RATE_CASES, approach_speeds, largest_expected_power, rice_expected_power  # noqa: E402

from scipy.linalg import expm  # noqa: E402

from pounding.estimator import _expected_maximum, estimate  # noqa: E402
from pounding.validation import accuracy_cases  # noqa: E402

SPEEDS = np.linspace(0.0, 6.0, 121)  # [sigma_V]
PERIODS, LAGS = 12.0, 480  # the first approach is looked for over 12 mean periods
CHAINS, RECORDS, SEED = 4000, 200, 11


def linearized_pair(case):
    """The linearized pair's state space, the rows of X and V over its state, and
    the impact's change of state per unit approach speed V = v [1/(m/s)]: the
    colliding floors' velocities change by -(1 + e) m2 / (m1 + m2) v and
    +(1 + e) m1 / (m1 + m2) v (momentum kept, V -> -e V)."""
    model, outputs, rows = pair_rows(case)
    m1, m2 = case.contact_masses
    jump = (1.0 + case.contact.restitution) * (-m2 * outputs[2] + m1 * outputs[3]) / (m1 + m2)  # the floors' velocity rows are states
    return model, rows, jump


def jump_response(pair, lags) -> np.ndarray:
    """(X / sigma_X, V / sigma_V) at each lag after the impact's velocity jump, per
    unit approach speed v / sigma_V, carried on by the pair's own dynamics, e^(A s);
    ``pair`` from :func:`linearized_pair`."""
    model, rows, jump = pair
    sigma = np.sqrt(np.diag(rows @ model.covariance() @ rows.T))
    return np.array([rows @ expm(model.matrix * lag) @ jump * sigma[1] for lag in lags.lags]) / sigma


def linear_impacts_expected_power(case, pair, power: float, paths: int = 4000, time_step: float = 0.002) -> tuple[float, float]:
    """E[V_max^p] of the linearized pair simulated from rest (exact discretization
    of its Gaussian motion, filter included) with instantaneous impacts at the gap
    (the velocity jump of :func:`linearized_pair`, ``pair``), and without [(m/s)^p]."""
    model, rows, jump = pair
    transition = expm(model.matrix * time_step)
    covariance = model.covariance()
    values, vectors = np.linalg.eigh(covariance - transition @ covariance @ transition.T)
    noise = vectors * np.sqrt(np.maximum(values, 0.0))  # the step's forcing, rank-deficient
    gap, steps = case.contact.gap, int(round(case.excitation.duration / time_step))
    out = []
    for impacts in (True, False):
        rng = np.random.default_rng(SEED)  # the same forcing with and without impacts
        state, largest = np.zeros((paths, transition.shape[0])), np.zeros(paths)
        for _ in range(steps):
            before = state @ rows[0]
            state = state @ transition.T + rng.standard_normal(state.shape) @ noise.T
            up = (before < gap) & (state @ rows[0] >= gap)
            if up.any():
                speed = np.maximum(state[up] @ rows[1], 0.0)
                largest[up] = np.maximum(largest[up], speed)
                if impacts:
                    state[up] += np.outer(speed, jump)
        out.append(float(np.mean(largest**power)))
    return out[0], out[1]


def first_approach(lags, u: float, start: float, shift: np.ndarray | None = None) -> np.ndarray:
    """Density of the first upward crossing of u after Z(0) = (u, start), over
    (lag, speed) on ``lags.lags`` x :data:`SPEEDS`, per unit lag and speed; ``shift``
    (lags, 2) is added to the conditional mean of Z."""
    after = lags.after
    mean = after @ np.array([u, start]) + (0.0 if shift is None else shift)
    cov = np.eye(2)[None] - np.einsum("sij,skj->sik", after, after)
    k11 = np.maximum(cov[:, 0, 0], 1e-12)
    level = _phi((u - mean[:, 0]) / np.sqrt(k11)) / np.sqrt(k11)
    mu = mean[:, 1] + cov[:, 1, 0] / k11 * (u - mean[:, 0])
    sd = np.sqrt(np.maximum(cov[:, 1, 1] - cov[:, 1, 0] ** 2 / k11, 1e-12))
    speed = SPEEDS[None, :]
    rice = lags.omega * level[:, None] * speed * _phi((speed - mu[:, None]) / sd[:, None]) / sd[:, None]
    total = np.trapezoid(rice, SPEEDS, axis=1)
    steps = np.diff(lags.lags)
    none_before = np.exp(-np.concatenate([[0.0], np.cumsum(0.5 * (total[1:] + total[:-1]) * steps)]))
    return rice * none_before[:, None]


def chain_expected_power(lags, u: float, restart: float, duration: float, power: float, jump: np.ndarray | None = None) -> float:
    """E[V_max^p] / sigma_V^p over ``duration`` [s] of the chain whose motion
    restarts from (u, restart x v) after an approach at v, or, given ``jump``
    (:func:`jump_response`), from the whole state at the approach plus the jump."""
    step = (lags.lags[1] - lags.lags[0]) * (SPEEDS[1] - SPEEDS[0])
    tables = [np.cumsum(first_approach(lags, u, restart * v, None if jump is None else jump * v).ravel() * step) for v in SPEEDS]
    fresh_rate = lags.omega / (2.0 * math.pi) * math.exp(-0.5 * u * u)  # Rice's, for a motion that has forgotten
    rng = np.random.default_rng(SEED)
    largest = np.zeros(CHAINS)
    for k in range(CHAINS):
        time = rng.exponential(1.0 / fresh_rate)
        speed = math.sqrt(-2.0 * math.log(1.0 - rng.random()))  # Rayleigh
        while time < duration:
            largest[k] = max(largest[k], speed)
            table = tables[min(int(round(speed / (SPEEDS[1] - SPEEDS[0]))), SPEEDS.size - 1)]
            draw = rng.random()
            if draw < table[-1]:  # an approach within the lags
                lag, index = divmod(min(int(np.searchsorted(table, draw)), table.size - 1), SPEEDS.size)
                time += lags.lags[lag]
                speed = SPEEDS[index]
            else:  # none: the motion has forgotten the last one
                time += lags.lags[-1] + rng.exponential(1.0 / fresh_rate)
                speed = math.sqrt(-2.0 * math.log(1.0 - rng.random()))
    return float(np.mean(largest**power))


def main() -> None:
    print("| case | q | gap / sigma_X | impacts add, simulated | linearized pair, instantaneous impacts | chain of approaches "
          "| chain, whole state | time cut: estimator / Rice |")
    print("|---|---|---|---|---|---|---|---|")
    for case in accuracy_cases():
        if not case.excitation.stationary or ("--all" not in sys.argv[1:] and case.name not in RATE_CASES):
            continue  # the chains and the linearized simulation are of stationary motion
        result = estimate(case)
        power = 1.0 if case.contact.model == "linear" else 1.2
        u = case.contact.gap / result.sigma_relative_displacement
        impacting, free_motion = approach_speeds(case, RECORDS)
        simulated = [largest_expected_power(group, power) for group in (impacting, free_motion)]
        lags = pair_lags(case, PERIODS, LAGS)
        duration = case.excitation.duration
        free = chain_expected_power(lags, u, 1.0, duration, power)
        chain = chain_expected_power(lags, u, -case.contact.restitution, duration, power) / free
        pair = linearized_pair(case)
        whole = chain_expected_power(lags, u, 1.0, duration, power, jump_response(pair, lags)) / free
        cut = _expected_maximum(result.crossings, np.array([case.contact.gap]), lambda v: v**power, power)[0]
        linear = linear_impacts_expected_power(case, pair, power)
        print(f"| {case.name} | {result.crossings.bandwidth:.2f} | {u:.2f} | {simulated[0] / simulated[1] - 1:+.1%} "
              f"| {linear[0] / linear[1] - 1:+.1%} | {chain - 1:+.1%} "
              f"| {whole - 1:+.1%} | {cut / rice_expected_power(result, power) - 1:+.1%} |", flush=True)


if __name__ == "__main__":
    main()
