"""What the impacts add to the largest approach speed: a chain of approaches.

Reproduces the table of "A chain of approaches" in validation/HISTORY.md. A
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

With ``--first-return`` it measures the chain's two approximations on that
linearized pair with instantaneous impacts, for a few cases: the law of the next
approach after an impact (Rice's intensity times Poisson's probability of none
before, from the exact state just after the impact, against the exact first
crossing simulated from the same states), and the state before an impact (the
free motion's given X = d, V = v, against the impacting pair's own: its states
just before its impacts, regressed on the approach speed). Here the gap is
taken in the linearized pair's own sigma_X, as the simulation sees it.

The estimator's count is taken on the free motion (without the impacts'
damping, :func:`validation.free_count.free_estimate`), as it was measured.

    python3 -m validation.approach_chain         # 8 cases, about 3 min
    python3 -m validation.approach_chain --all   # every stationary case of the grid, about 15 min
    python3 -m validation.approach_chain --first-return   # the chain's two approximations, 8 cases, about 20 min
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from scipy.linalg import expm

from pounding.closed_form.gap_aware import expected_maximum
from pounding.closed_form.pair import LinearizedPair
from pounding.studies.paper_tables import accuracy_cases

from .clump_models import pair_lags, pair_rows, phi
from .error_decomposition import RATE_CASES, approach_speeds, largest_expected_power, rice_expected_power
from .free_count import free_estimate, linearized
from .sizes import first

SPEEDS = np.linspace(0.0, 6.0, 121)  # [sigma_V]
PERIODS, LAGS = 12.0, 480  # the first approach is looked for over 12 mean periods
CHAINS, RECORDS, SEED = 4000, 200, 11


def linearized_pair(case_or_pair):
    """The linearized pair's state space, the rows of X and V over its state, and
    the impact's change of state per unit approach speed V = v [1/(m/s)]: the
    colliding floors' velocities change by -(1 + e) m2 / (m1 + m2) v and
    +(1 + e) m1 / (m1 + m2) v (momentum kept, V -> -e V)."""
    pair = linearized(case_or_pair)
    case = pair.case
    model, outputs, rows = pair_rows(pair)
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


def _linear_pair_paths(case, pair, impacts: bool, paths: int, time_step: float, keep_after: float | None = None):
    """The linearized pair simulated from rest (exact discretization of its Gaussian
    motion, filter included), with instantaneous impacts at the gap or without.
    Returns each path's largest upward crossing speed of the gap [m/s] and, given
    ``keep_after`` [s], the states just before the impacts after that time and
    their approach speeds."""
    model, rows, jump = pair
    transition = expm(model.matrix * time_step)
    covariance = model.covariance()
    values, vectors = np.linalg.eigh(covariance - transition @ covariance @ transition.T)
    noise = vectors * np.sqrt(np.maximum(values, 0.0))  # the step's forcing, rank-deficient
    gap, steps = case.contact.gap, int(round(case.excitation.duration / time_step))
    rng = np.random.default_rng(SEED)  # the same forcing with and without impacts
    state, largest = np.zeros((paths, transition.shape[0])), np.zeros(paths)
    kept, speeds = [], []
    for index in range(steps):
        before = state @ rows[0]
        state = state @ transition.T + rng.standard_normal(state.shape) @ noise.T
        up = (before < gap) & (state @ rows[0] >= gap)
        if up.any():
            speed = np.maximum(state[up] @ rows[1], 0.0)
            largest[up] = np.maximum(largest[up], speed)
            if impacts:
                if keep_after is not None and index * time_step > keep_after:
                    kept.append(state[up].copy())
                    speeds.append(speed)
                state[up] += np.outer(speed, jump)
    if keep_after is None:
        return largest
    return largest, np.concatenate(kept), np.concatenate(speeds)


def linear_impacts_expected_power(case, pair, power: float, paths: int = 4000, time_step: float = 0.002) -> tuple[float, float]:
    """E[V_max^p] of the linearized pair simulated from rest with instantaneous
    impacts at the gap (the velocity jump of :func:`linearized_pair`, ``pair``),
    and without [(m/s)^p]."""
    return tuple(float(np.mean(_linear_pair_paths(case, pair, impacts, paths, time_step) ** power)) for impacts in (True, False))


def first_approach(lags, u: float, start: float, shift: np.ndarray | None = None) -> np.ndarray:
    """Density of the first upward crossing of u after Z(0) = (u, start), over
    (lag, speed) on ``lags.lags`` x :data:`SPEEDS`, per unit lag and speed; ``shift``
    (lags, 2) is added to the conditional mean of Z."""
    after = lags.after
    mean = after @ np.array([u, start]) + (0.0 if shift is None else shift)
    return first_crossing(lags, u, mean, np.eye(2)[None] - np.einsum("sij,skj->sik", after, after))


def first_crossing(lags, u: float, mean: np.ndarray, cov: np.ndarray) -> np.ndarray:
    """The same for a Gaussian Z with ``mean`` (lags, 2) and ``cov`` (lags, 2, 2) at
    each lag: Rice's intensity of upward crossings of u times the probability of
    none before (Poisson)."""
    k11 = np.maximum(cov[:, 0, 0], 1e-12)
    level = phi((u - mean[:, 0]) / np.sqrt(k11)) / np.sqrt(k11)
    mu = mean[:, 1] + cov[:, 1, 0] / k11 * (u - mean[:, 0])
    sd = np.sqrt(np.maximum(cov[:, 1, 1] - cov[:, 1, 0] ** 2 / k11, 1e-12))
    speed = SPEEDS[None, :]
    rice = lags.omega * level[:, None] * speed * phi((speed - mu[:, None]) / sd[:, None]) / sd[:, None]
    total = np.trapezoid(rice, SPEEDS, axis=1)
    steps = np.diff(lags.lags)
    none_before = np.exp(-np.concatenate([[0.0], np.cumsum(0.5 * (total[1:] + total[:-1]) * steps)]))
    return rice * none_before[:, None]


def chain_expected_power(lags, u: float, restart: float, duration: float, power: float, jump: np.ndarray | None = None,
                         chains: int = CHAINS) -> float:
    """E[V_max^p] / sigma_V^p over ``duration`` [s] of ``chains`` chains whose motion
    restarts from (u, restart x v) after an approach at v, or, given ``jump``
    (:func:`jump_response`), from the whole state at the approach plus the jump."""
    return sampled_chain([first_approach(lags, u, restart * v, None if jump is None else jump * v) for v in SPEEDS], lags, u,
                         duration, power, chains)


def sampled_chain(densities, lags, u: float, duration: float, power: float, chains: int = CHAINS) -> float:
    """E[V_max^p] / sigma_V^p of the chain whose next approach after one at
    SPEEDS[i] (in sigma_V) has the density ``densities[i]`` over (lag, speed)."""
    step = (lags.lags[1] - lags.lags[0]) * (SPEEDS[1] - SPEEDS[0])
    tables = [np.cumsum(density.ravel() * step) for density in densities]
    fresh_rate = lags.omega / (2.0 * math.pi) * math.exp(-0.5 * u * u)  # Rice's, for a motion that has forgotten
    rng = np.random.default_rng(SEED)
    largest = np.zeros(chains)
    for k in range(chains):
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


FIRST_RETURN_CASES = (
    "section5-T2-0.4", "section6-T2-0.4", "section6-T2-0.8", "mdof-3+2-floor2", "s5-T2-0.8 G0x4pi2", "T1 1.2 T2 2.0",
    "s5-T2-0.4 G0x0.25", "elastic 1.2/0.4 gap6cm",
)
SETTLED = 5.0  # [s] impacts before this are left out of the pre-impact states


def exact_first_returns(case, pair, states, horizon: float, time_step: float = 0.002) -> tuple[np.ndarray, np.ndarray]:
    """Lag [s] and speed [m/s] of the first upward crossing of the gap after each
    post-impact state (rows of ``states``), the linearized pair simulated exactly
    (NaN if none within ``horizon`` [s])."""
    model, rows, _ = pair
    transition = expm(model.matrix * time_step)
    covariance = model.covariance()
    values, vectors = np.linalg.eigh(covariance - transition @ covariance @ transition.T)
    noise = vectors * np.sqrt(np.maximum(values, 0.0))
    rng = np.random.default_rng(SEED)
    state = states.copy()
    lag, speed = np.full(len(state), np.nan), np.full(len(state), np.nan)
    waiting = np.ones(len(state), dtype=bool)
    for index in range(int(horizon / time_step)):
        before = state @ rows[0]
        state = state @ transition.T + rng.standard_normal(state.shape) @ noise.T
        up = waiting & (before < case.contact.gap) & (state @ rows[0] >= case.contact.gap)
        lag[up], speed[up] = (index + 1) * time_step, state[up] @ rows[1]
        waiting &= ~up
        if not waiting.any():
            break
    return lag, speed


def _whole_state_density(pair, lags, propagators, u: float, start: np.ndarray, spread: np.ndarray) -> np.ndarray:
    """:func:`first_crossing` for the pair's state at the impact, after its jump,
    Gaussian with mean ``start`` and covariance ``spread``, carried on by e^(A s)."""
    model, rows, _ = pair
    covariance = model.covariance()
    sigma = np.sqrt(np.diag(rows @ covariance @ rows.T))
    mean = np.einsum("ij,ljk,k->li", rows, propagators, start) / sigma
    # optimize: the five factors contracted pairwise (the naive loop took 25 ms a call; the same to 1e-15).
    lagged = np.einsum("ij,ljk,km,lnm,pn->lip", rows, propagators, spread - covariance, propagators, rows, optimize=True)
    lagged = lagged + rows @ covariance @ rows.T
    return first_crossing(lags, u, mean, lagged / np.outer(sigma, sigma))


def first_return_table(records: int = 4000, cases: int | None = None, chains: int = CHAINS) -> None:
    """The chain's two approximations, measured on the linearized pair with
    instantaneous impacts: the law of the next approach after an impact
    (Poisson, from the exact state after the impact, against the exact first
    crossing) and the state before an impact (the free motion's given X = d,
    V = v, against the impacting pair's own, a regression on v of the states
    sampled before its impacts after the first 5 s). ``records`` paths of the linearized pair,
    the first ``cases`` of :data:`FIRST_RETURN_CASES` (all for None), ``chains`` chains."""
    print("| case | gap / sigma_X | first return, median (mean periods) | P(return faster than sigma_V): exact / chain's law "
          "| P(faster than 2 sigma_V): exact / chain's law | impacts add: linearized pair | whole-state chain "
          "| whole-state chain, the impacting pair's own state before an impact |")
    print("|---|---|---|---|---|---|---|---|")
    for case in first((case for case in accuracy_cases() if case.name in FIRST_RETURN_CASES), cases):
        power = 1.0 if case.contact.model == "linear" else 1.2
        linearization = LinearizedPair.of(case)
        pair = linearized_pair(linearization)
        model, rows, jump = pair
        covariance = model.covariance()
        sigma = np.sqrt(np.diag(rows @ covariance @ rows.T))
        u = case.contact.gap / sigma[0]
        largest, before, speeds = _linear_pair_paths(case, pair, True, records, 0.002, keep_after=SETTLED)
        free_largest = _linear_pair_paths(case, pair, False, records, 0.002)
        linear = np.mean(largest**power) / np.mean(free_largest**power)
        lags = pair_lags(linearization, PERIODS, LAGS)
        propagators = np.array([expm(model.matrix * lag) for lag in lags.lags])
        pick = np.random.default_rng(SEED).choice(len(speeds), min(1500, len(speeds)), replace=False)
        after = before[pick] + np.outer(speeds[pick], jump)
        lag, exact = exact_first_returns(case, pair, after, lags.lags[-1])
        laws = [_whole_state_density(pair, lags, propagators, u, state, np.zeros_like(covariance)) for state in after[:300]]
        law = np.mean([np.trapezoid(density, lags.lags, axis=0) for density in laws], axis=0)  # over speed
        faster = [(np.mean(exact > level * sigma[1]), np.trapezoid(law[SPEEDS >= level], SPEEDS[SPEEDS >= level])) for level in (1.0, 2.0)]
        duration = case.excitation.duration
        free = chain_expected_power(lags, u, 1.0, duration, power, chains=chains)
        whole = chain_expected_power(lags, u, 1.0, duration, power, jump_response(pair, lags), chains) / free
        design = np.column_stack([np.ones_like(speeds), speeds])
        fit, *_ = np.linalg.lstsq(design, before, rcond=None)
        residual = before - design @ fit
        spread = residual.T @ residual / len(speeds)
        own = sampled_chain([_whole_state_density(pair, lags, propagators, u, fit[0] + (fit[1] + jump) * v * sigma[1], spread) for v in SPEEDS],
                            lags, u, duration, power, chains) / free
        period = 2.0 * math.pi / lags.omega
        print(f"| {case.name} | {u:.2f} | {np.nanmedian(lag) / period:.3f} | " + " | ".join(f"{e:.3f} / {c:.3f}" for e, c in faster)
              + f" | {linear - 1:+.1%} | {whole - 1:+.1%} | {own - 1:+.1%} |", flush=True)


TABLES = ("chain", "first-return")


def main(table: str = "chain", cases: int | None = None, every_case: bool = False, records: int = RECORDS,
         chains: int = CHAINS, paths: int = 4000) -> None:
    """Print ``table`` (one of :data:`TABLES`) over the first ``cases`` (all for None) of the
    stationary :data:`~validation.error_decomposition.RATE_CASES` (``every_case``: of every
    stationary case of the grid) or of :data:`FIRST_RETURN_CASES`; ``records`` simulated
    records, ``chains`` chains and ``paths`` paths of the linearized pair with instantaneous impacts."""
    if table == "first-return":
        first_return_table(paths, cases, chains)
        return
    print("| case | q | gap / sigma_X | impacts add, simulated | linearized pair, instantaneous impacts | chain of approaches "
          "| chain, whole state | time cut: estimator / Rice |")
    print("|---|---|---|---|---|---|---|---|")
    # The chains and the linearized simulation are of stationary motion.
    chosen = (case for case in accuracy_cases() if case.excitation.stationary and (every_case or case.name in RATE_CASES))
    for case in first(chosen, cases):
        linearization = LinearizedPair.of(case)
        result = free_estimate(linearization)
        power = 1.0 if case.contact.model == "linear" else 1.2
        u = case.contact.gap / result.sigma_relative_displacement
        impacting, free_motion = approach_speeds(case, records)
        simulated = [largest_expected_power(group, power) for group in (impacting, free_motion)]
        lags = pair_lags(linearization, PERIODS, LAGS)
        duration = case.excitation.duration
        free = chain_expected_power(lags, u, 1.0, duration, power, chains=chains)
        chain = chain_expected_power(lags, u, -case.contact.restitution, duration, power, chains=chains) / free
        pair = linearized_pair(linearization)
        whole = chain_expected_power(lags, u, 1.0, duration, power, jump_response(pair, lags), chains) / free
        gap = np.array([case.contact.gap])
        cut = expected_maximum(result.crossings, gap, lambda v: v**power, power, result.crossings.damped(gap))[0]
        linear = linear_impacts_expected_power(case, pair, power, paths)
        print(f"| {case.name} | {result.crossings.bandwidth:.2f} | {u:.2f} | {simulated[0] / simulated[1] - 1:+.1%} "
              f"| {linear[0] / linear[1] - 1:+.1%} | {chain - 1:+.1%} "
              f"| {whole - 1:+.1%} | {cut / rice_expected_power(result, power) - 1:+.1%} |", flush=True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--all", action="store_true", help="every stationary case of the grid")
    group.add_argument("--first-return", dest="table", action="store_const", const="first-return", default="chain",
                       help="the chain's two approximations")
    arguments = parser.parse_args()
    main(arguments.table, every_case=arguments.all)
