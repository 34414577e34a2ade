"""Clumps of crossings: Vanmarcke's factor against a conditional count.

Reproduces the tables of "Clumps: Vanmarcke's factor against a conditional
count" in validation/HISTORY.md. A diagnosis, not part of the estimator.

The *conditional count* takes an approach faster than v at t (X up-crosses the
gap d with V > v) as the start of a clump when no such approach happened in the
window (t - W, t), W = 1.5 mean periods 2 pi sigma_X / sigma_V. Given
X(t) = d, V(t) = v', the state Z(t - s) = (X, V)(t - s) is Gaussian (the pair's
autocovariance, from its state space), so the expected number N of such
approaches in the window is Rice's formula under that conditional law, and the
window is taken empty with probability exp(-N). As in Vanmarcke's factor,
the rate of clump starts is divided by the probability 1 - exp(-r^2 / 2) of
not being in a clump (r^2 = u^2 + rho^2), capped at Rice's rate.

Vanmarcke's factor is put beside it with the estimator's constant sqrt(pi / 2)
(his, derived for crossings of +-d) and with sqrt(2 pi), what the same
derivation gives for crossings of d alone. The counts are compared on the
free motion (the largest approach counted without the impacts' damping,
:func:`validation.free_count.free_estimate`), but with ``--damped``.

    python3 -m validation.clump_models           # the free motion of 5 elastic pairs, about 3 min
    python3 -m validation.clump_models --grid    # the estimator's grid, about 30 min
    python3 -m validation.clump_models --free-grid   # the grid's free motion, about 3 min
    python3 -m validation.clump_models --draw 2026   # a random draw of validation.out_of_sample, by regime, about 45 min
    python3 -m validation.clump_models --damped 2026 2027 2028   # the conditional count with the impacts' damping,
                                               # the grid and the draws, by regime and by kind of building,
                                               # about 10 min per draw
"""

from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np
from scipy.linalg import expm
from scipy.special import erfc

from pounding import load_case, simulate
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import REGIMES
from pounding.hazard.excitation import ground_accelerations
from pounding.studies.paper_tables import accuracy_cases, random_cases, varied_case

from .error_decomposition import ONE_SIDED, contact_motion, rice_expected_power, upcrossing_speeds, vanmarcke_clumps
from .free_count import free_estimate, linearized
from .impact_damping_study import ORDER, measured_cases
from .sizes import first

SEED = 11
FREE_RECORDS, GRID_RECORDS = 3000, 300
PAIRS = [(1.2, 0.4), (2.0, 0.5), (0.6, 0.3), (0.5, 0.3), (1.2, 0.8)]
LEVELS = [0.0, 1.0, 1.5, 2.0, 2.5]
WINDOW = 1.5  # mean periods
SPEEDS = np.linspace(0.0, 10.0, 201)  # rho' grid [sigma_V]


def normal_tail(x):
    """P(U > x), U standard normal."""
    return 0.5 * erfc(x / math.sqrt(2.0))


def phi(x):
    """The standard normal density."""
    return np.exp(-0.5 * x * x) / math.sqrt(2.0 * math.pi)


@dataclasses.dataclass(frozen=True)
class Lags:
    """Normalized Cov(Z(t - s), Z(t)) of Z = (X / sigma_X, V / sigma_V) at the window's lags s."""

    lags: np.ndarray
    before: np.ndarray  # (lags, 2, 2)
    omega: float

    @property
    def after(self) -> np.ndarray:
        """Cov(Z(t + s), Z(t))."""
        return np.transpose(self.before, (0, 2, 1))


def pair_rows(case_or_pair):
    """The linearized pair's state space, its contact-floor output rows
    (:attr:`~pounding.closed_form.pair.LinearizedPair.contact_outputs`) and the rows of X and V;
    a case is linearized, a :class:`~pounding.closed_form.pair.LinearizedPair` reused."""
    pair = linearized(case_or_pair)
    outputs = pair.contact_outputs
    return pair.state_space, outputs, np.array([outputs[0] - outputs[1], outputs[2] - outputs[3]])


def pair_lags(case_or_pair, periods: float = WINDOW, count: int = 40) -> Lags:
    """The normalized autocovariance at ``count`` lags up to ``periods`` mean periods."""
    model, _, rows = pair_rows(case_or_pair)
    covariance = model.covariance()
    sigma = np.sqrt(np.diag(rows @ covariance @ rows.T))
    omega = sigma[1] / sigma[0]
    lags = np.linspace(0.02, periods, count) * 2.0 * math.pi / omega
    before = np.array([(rows @ expm(model.matrix * s) @ covariance @ rows.T / np.outer(sigma, sigma)).T for s in lags])
    return Lags(lags, before, omega)


def approaches_in_window(lags: Lags, covariance_lagged, u, speeds, rho, crossings: str) -> np.ndarray:
    """Expected crossings of u faster than rho in the window, given Z(t) = (u, speeds);
    ``crossings``: "up", "down" or "both" ways."""
    state = np.stack([np.full_like(speeds, u), speeds])
    mean = np.einsum("sij,jn->sin", covariance_lagged, state)
    cov = np.eye(2)[None] - np.einsum("sij,skj->sik", covariance_lagged, covariance_lagged)
    k11 = np.maximum(cov[:, 0, 0], 1e-12)[:, None]
    k21, k22 = cov[:, 1, 0][:, None], cov[:, 1, 1][:, None]
    density = phi((u - mean[:, 0]) / np.sqrt(k11)) / np.sqrt(k11)
    mu = mean[:, 1] + k21 / k11 * (u - mean[:, 0])
    sd = np.sqrt(np.maximum(k22 - k21**2 / k11, 1e-12))
    up = mu * normal_tail((rho - mu) / sd) + sd * phi((rho - mu) / sd)
    down = -mu * normal_tail((rho + mu) / sd) + sd * phi((rho + mu) / sd)
    rate = {"up": up, "down": down, "both": up + down}[crossings]
    return np.trapezoid(lags.omega * density * rate, lags.lags, axis=0)


def conditional_intensity(crossings, lags: Lags, gaps, velocities, count: str, window_crossings: str = "up") -> np.ndarray:
    """Lambda(gap, v) with the conditional count of clumps; ``count``: "free"
    (the free motion's crossings), "time cut" (the estimator's returns) or
    "mirror" (Zhuravlev's returns: down-crossings count as approaches too, and
    the window counts both ways). ``window_crossings`` ("up", "down", "both"):
    which of the free motion's crossings in the window end a clump, for the
    free motion and the time cut."""
    gaps, velocities = np.atleast_1d(gaps).astype(float), np.atleast_1d(velocities).astype(float)
    mirror = count == "mirror"
    out = np.zeros((gaps.size, velocities.size))
    for i, gap in enumerate(gaps):
        for sigma_x, sigma_v, weight in zip(crossings.sigma_x, crossings.sigma_v, crossings.weights):
            u = gap / sigma_x
            if u > 10.0:
                continue
            scale = 1.0 / (0.5 * erfc(-u / math.sqrt(2.0))) if count == "time cut" else 1.0
            for j, v in enumerate(velocities):
                rho = v / sigma_v
                if rho > 9.5:
                    continue
                speeds = np.concatenate([[rho], SPEEDS[SPEEDS > rho]])
                rice = math.exp(-0.5 * u * u) / (2.0 * math.pi) * speeds * np.exp(-0.5 * speeds**2) * sigma_v / sigma_x
                outside = max(-math.expm1(-0.5 * (u * u + rho * rho)), 1e-12)
                window = "both" if mirror else window_crossings
                start = np.minimum(1.0, np.exp(-approaches_in_window(lags, lags.before, u, speeds, rho, window)) / outside)
                if mirror:  # a down-crossing starts a clump if the window after an up-crossing is empty (reversibility)
                    start = start + np.minimum(1.0, np.exp(-approaches_in_window(lags, lags.after, u, speeds, rho, "both")) / outside)
                out[i, j] += weight * scale * np.trapezoid(rice * start, speeds)
    return out


def one_sided_intensity(crossings, gaps, velocities) -> np.ndarray:
    """Lambda(gap, v) of the estimator (time cut, Vanmarcke's clumps) with the clump
    exponent derived for crossings of d alone at the time cut's rate nu / Phi(u)
    while the envelope is above r: sqrt(2 pi) q^1.2 Phi(u) r (the estimator's
    sqrt(pi / 2) q^1.2 r is the same at u = 0, the double barrier's elsewhere)."""
    gaps, velocities = np.atleast_1d(gaps).astype(float), np.atleast_1d(velocities).astype(float)
    out = np.zeros((gaps.size, velocities.size))
    for sigma_x, sigma_v, weight in zip(crossings.sigma_x, crossings.sigma_v, crossings.weights):
        u, rho = gaps[:, None] / sigma_x, velocities[None, :] / sigma_v
        below = 1.0 - normal_tail(u)
        r = np.hypot(u, rho)
        clumps = vanmarcke_clumps(r, ONE_SIDED * crossings.bandwidth**1.2 * below)
        out += weight * sigma_v / (2.0 * math.pi * sigma_x) * np.exp(-0.5 * (u * u + rho * rho)) / below * clumps
    return out


def expected_power(intensity, speeds, power=1.2):
    return float(np.trapezoid(-np.expm1(-intensity), speeds**power))


def free_speeds(case, gaps, records: int) -> np.ndarray:
    """Each record's largest up-crossing speed of each gap by the free relative motion."""
    out = np.zeros((len(gaps), records))
    for i, record in enumerate(ground_accelerations(case.excitation, SEED, np.arange(records))):
        x, v = contact_motion(case, record, contact=False)
        for k, gap in enumerate(gaps):
            crossings = upcrossing_speeds(x, v, gap)
            if crossings.size:
                out[k, i] = max(np.max(crossings), 0.0)
    return out


def free_motion_table(pairs: int | None = None, records: int = FREE_RECORDS, levels: int | None = None) -> None:
    """The first ``pairs`` of :data:`PAIRS` at the first ``levels`` of :data:`LEVELS` (all for None),
    ``records`` free records each."""
    print("| pair | q | gap / sigma_X | P(crossing), simulated | Vanmarcke | Vanmarcke, one side | no clumps | conditional |")
    print("|---|---|---|---|---|---|---|---|")
    for periods in first(PAIRS, pairs):
        pair = LinearizedPair.of(varied_case(load_case("section5-T2-0.4"), elastic=True, periods=periods))
        case = pair.case
        result = free_estimate(pair)
        crossings = result.crossings
        sigma = crossings.sigma_x[-1]
        gaps = [level * sigma for level in first(LEVELS, levels)]
        simulated = free_speeds(case, gaps, records)
        lags = pair_lags(pair)
        velocities = np.linspace(0.0, 6.0 * crossings.sigma_v.max(), 80)
        for gap, speeds in zip(gaps, simulated):
            target = np.mean(speeds**1.2)
            counts = [rice_expected_power(result, 1.2, gap=gap), rice_expected_power(result, 1.2, gap=gap, barrier=ONE_SIDED)]
            counts.append(rice_expected_power(result, 1.2, gap=gap, clumps=False))
            cells = [f"{count / target - 1:+.1%}" for count in counts]
            conditional = conditional_intensity(crossings, lags, gap, velocities, "free")[0]
            cells.append(f"{expected_power(conditional, velocities) / target - 1:+.1%}")
            print(f"| {periods[0]}/{periods[1]} | {crossings.bandwidth:.2f} | {gap / sigma:.1f} | {np.mean(speeds > 0):.3f} | " + " | ".join(cells) + " |")


COUNT_NAMES = ("Vanmarcke, time cut (the estimator)", "Vanmarcke one side, time cut", "conditional, time cut",
               "conditional, mirror returns", "time cut, window of down-crossings", "time cut, window both ways")


def grid_table(cases=None, by_regime: bool = False, records: int = GRID_RECORDS) -> None:
    """Each count's estimate against Monte Carlo (``records`` records) on ``cases`` (the grid by
    default), and, with ``by_regime``, how many within 10 % in each regime the estimate states.
    Without the impacts' damping the largest approach is counted on the free motion's count, so
    a variant of that count stands in for both (:func:`validation.free_count.free_estimate`)."""
    counts = [("time cut", "up"), ("mirror", "both"), ("time cut", "down"), ("time cut", "both")]
    print("| case | gap / sigma_X | q | Vanmarcke, time cut (the estimator) | Vanmarcke one side, time cut | conditional, time cut "
          "| conditional, mirror returns | time cut, window of down-crossings | time cut, window both ways |")
    print("|---|---|---|---|---|---|---|---|---|")
    errors, regimes = [], []
    for case in accuracy_cases() if cases is None else cases:
        mean = simulate(case, records=records, seed=SEED).force_max_mean
        if mean == 0.0:  # no record pounded: no relative error
            continue
        pair = LinearizedPair.of(case)
        result = free_estimate(pair)
        regimes.append(result.accuracy_regime)
        lags = pair_lags(pair)
        variants = [one_sided_intensity] + [
            lambda crossings, gaps, velocities, count=count, window=window: conditional_intensity(crossings, lags, gaps, velocities, count, window)
            for count, window in counts
        ]
        row = [result.force_expected / mean - 1]
        for variant in variants:
            # The free motion's count (the damped motion's ratios are 1): ``motion`` is not needed.
            counted = free_estimate(pair, count=lambda crossings, gaps, velocities, motion, variant=variant: variant(crossings, gaps, velocities))
            row.append(counted.force_expected / mean - 1)
        errors.append(row)
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {result.crossings.bandwidth:.2f} | "
              + " | ".join(f"{e:+.1%}" for e in row) + " |", flush=True)
    errors = np.abs(np.array(errors))
    print()
    if not errors.size:
        print("no case pounded in any record")
        return
    print("within 10 %: " + ", ".join(str(int(n)) for n in (errors <= 0.10).sum(axis=0)) + f" of {len(errors)}; median: "
          + ", ".join(f"{m:.1%}" for m in np.median(errors, axis=0)))
    if by_regime:
        regimes = np.array(regimes)
        print("\n| regime | cases | " + " | ".join(f"within 10 %: {name}" for name in COUNT_NAMES) + " |")
        print("|---|---|" + "---|" * len(COUNT_NAMES))
        for regime in REGIMES:
            chosen = errors[regimes == regime]
            if chosen.size:
                print(f"| {regime} | {len(chosen)} | " + " | ".join(
                    f"{int(n)} ({m:.1%})" for n, m in zip((chosen <= 0.10).sum(axis=0), np.median(chosen, axis=0))) + " |")


def free_grid_table(cases: int | None = None, records: int = GRID_RECORDS) -> None:
    """The grid's free motion (its first ``cases``, all for None): each count against the simulated
    free relative motion (no contact, ``records`` records)."""
    print("| case | gap / sigma_X | q | Vanmarcke / free motion | conditional / free motion |")
    print("|---|---|---|---|---|")
    for case in first(accuracy_cases(), cases):
        pair = LinearizedPair.of(case)
        result = free_estimate(pair)
        power = 1.0 if case.contact.model == "linear" else 1.2  # the peak force grows as v^power
        gap = case.contact.gap
        target = np.mean(free_speeds(case, [gap], records)[0] ** power)
        velocities = np.linspace(0.0, 6.0 * result.crossings.sigma_v.max(), 80)
        conditional = conditional_intensity(result.crossings, pair_lags(pair), gap, velocities, "free")[0]
        cells = [rice_expected_power(result, power) / target - 1, expected_power(conditional, velocities, power) / target - 1]
        print(f"| {case.name} | {gap / result.sigma_relative_displacement:.2f} | {result.crossings.bandwidth:.2f} | "
              + " | ".join(f"{c:+.1%}" for c in cells) + " |", flush=True)


def damped_conditional_table(seeds, cases: int | None = None, records: int = GRID_RECORDS) -> None:
    """The estimator, and the estimator with the conditional count in place of Vanmarcke's factor
    for the largest approach (its impacts' damping kept: the damped sigmas scale the count; the
    window's law is the free pair's), against Monte Carlo (``records`` records) on the grid and
    ``seeds``' draws (the first ``cases`` of each, all for None), by the regime the estimate states
    and by kind of building (elastic: Gaussian motion)."""

    def conditional(pair):
        lags = pair_lags(pair)

        def count(crossings, gaps, velocities, motion):
            gaps = np.atleast_1d(gaps).astype(float)
            out = np.zeros((gaps.size, np.size(velocities)))
            for i, gap in enumerate(gaps):
                damped = dataclasses.replace(crossings, sigma_x=crossings.sigma_x * motion.ratio_displacement[i],
                                             sigma_v=crossings.sigma_v * motion.ratio_velocity[i])
                out[i] = conditional_intensity(damped, lags, gap, velocities, "time cut")[0]
            return out

        return count

    def variant(pair):
        return free_estimate(pair, count=conditional(pair), damped=True)

    sources = {"grid": first(accuracy_cases(), cases), **{f"draw {seed}": first(random_cases(seed), cases) for seed in seeds}}
    rows = []
    for source, chosen_cases in sources.items():
        for regime, kind, errors in measured_cases(chosen_cases, variant, records):
            rows.append((source, regime, kind, *errors))
    print("| regime | source | Vanmarcke (the estimator) | conditional count |")
    print("|---|---|---|---|")
    for group in [(regime,) for regime in ORDER] + [("elastic",), ("yielding",)]:
        for source in ("grid and draws", *sources):
            chosen = [r for r in rows if group[0] in (r[1], r[2]) and (source == "grid and draws" or r[0] == source)]
            if chosen:
                cells = []
                for column in (3, 4):
                    e = np.array([r[column] for r in chosen])
                    cells.append(f"{int(np.sum(np.abs(e) <= 0.10))} of {e.size}, median {np.median(e):+.1%}, {e.min():+.0%} to {e.max():+.0%}")
                print(f"| {group[0]} | {source} | " + " | ".join(cells) + " |", flush=True)


TABLES = ("free", "grid", "free-grid", "draw", "damped")


def main(table: str = "free", seeds=(), cases: int | None = None, records: int = GRID_RECORDS,
         free_records: int = FREE_RECORDS, levels: int | None = None) -> None:
    """Print ``table`` (one of :data:`TABLES`): ``free``, the free motion of the first ``cases``
    of :data:`PAIRS` at the first ``levels`` of :data:`LEVELS` (``free_records`` records);
    ``grid``, ``free-grid``: the first ``cases`` of
    the grid; ``draw``: of the draw ``seeds[0]``, by regime; ``damped``: the grid and the draws of
    ``seeds``; ``records`` records each (all cases for None)."""
    if table == "free":
        free_motion_table(cases, free_records, levels)
    elif table == "grid":
        grid_table(first(accuracy_cases(), cases), records=records)
    elif table == "free-grid":
        free_grid_table(cases, records)
    elif table == "draw":
        grid_table(first(random_cases(seeds[0]), cases), by_regime=True, records=records)
    elif table == "damped":
        damped_conditional_table(seeds, cases, records)
    else:
        raise ValueError(f"table must be one of {', '.join(TABLES)}, got {table!r}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--grid", dest="table", action="store_const", const="grid", help="the estimator's grid")
    group.add_argument("--free-grid", dest="table", action="store_const", const="free-grid", help="the grid's free motion")
    group.add_argument("--draw", type=int, metavar="SEED", help="a random draw, by regime")
    group.add_argument("--damped", type=int, nargs="+", metavar="SEED", help="the conditional count with the impacts' damping")
    arguments = parser.parse_args()
    if arguments.draw is not None:
        main("draw", [arguments.draw])
    elif arguments.damped:
        main("damped", arguments.damped)
    else:
        main(arguments.table or "free")
