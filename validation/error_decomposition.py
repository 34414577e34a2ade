"""Where the recommended estimate's error sits: the peak force of an impact
of a given speed, or the largest approach speed of the record.

For each case of the accuracy grid (300 records, seed 11), with F(v) the
estimator's peak force of an impact at speed v against the buildings'
braking force at the gap (``Estimate.opposing_force``):

- impact force: the simulated E[F_max] against the mean over records of
  F(V_max), V_max each record's largest simulated approach speed. It tests the
  impact model alone, on the simulated speeds;
- largest speed: the estimate against that same mean. It tests the model of
  the largest approach speed (crossings of the gap, time cut, clumps);
- the two multiply to the estimate's error against Monte Carlo;
- the impact-force column without the braking force, for free masses, shows
  what the braking force corrects.

With ``--free-motion`` it splits the largest-speed column once more, with
the same records integrated without contact (the gap set to 10 m): the
largest speed at which the free relative motion crosses the gap upward in
each record. "impacts" is the simulated E[V_max^p] (p the law's exponent)
against the free motion's, what the impacts themselves add; "Gaussian" is
the free motion's against Rice's count of the linearized pair's crossings
(with Vanmarcke's clumps and no time cut), what the Gaussian
linearized model misses of the free motion; "time cut" is the estimator's
E[V_max^p] (time cut and clumps) against that Rice count, what the estimator
adds for the impacts, to set beside "impacts".

With ``--rates`` it counts, for a few cases (200 records), the approaches
faster than v of the impacting motion against the free motion's upward
crossings of the gap faster than v, beside the time cut's factor 1 / Phi(u).

With ``--mirror`` it compares, on the simulated largest speed
(E[V_max^1.2]), the estimator's count (the time cut: Rice's rate per unit
time below the gap, nu / Phi(d / sigma_X), with the clumps) with the count it
replaced, Zhuravlev's mirror returns (impacts at envelope a recurring at
omega / (2 (pi - arccos(d / a))), with the clumps).

The estimate here is the free count (the largest approach counted on the
free motion, :func:`validation.free_count.free_estimate`), as these tables
were measured before the impacts' damping.

    python3 -m validation.error_decomposition                 # about 30 s on 2 cores
    python3 -m validation.error_decomposition --free-motion   # about 1 min
    python3 -m validation.error_decomposition --mirror        # about 30 s
    python3 -m validation.error_decomposition --rates         # about 10 min
"""

from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np

from pounding import integrate, simulate
from pounding.closed_form.gap_aware import expected_maximum
from pounding.hazard.excitation import ground_accelerations
from pounding.mechanics.contact import impact_peak_force
from pounding.studies.paper_tables import accuracy_cases

from .free_count import free_estimate
from .sizes import first

RECORDS, SEED = 300, 11
RATE_RECORDS = 200


def contact_motion(case, record, contact: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """X = x1 - x2 [m] and V [m/s] of the contact floors over ``record``, with
    contact or without it (the gap moved to 10 m)."""
    model = case if contact else case.with_contact(gap=10.0)
    history = integrate(model, record, case.excitation.time_step)
    level_1, level_2 = case.contact.levels
    velocity = history.velocity[:, history.floor(1, level_1)] - history.velocity[:, history.floor(2, level_2)]
    return history.penetration + model.contact.gap, velocity


def upcrossing_speeds(x, v, level: float) -> np.ndarray:
    """v at each upward crossing of ``level`` by x, interpolated between samples."""
    up = np.flatnonzero((x[:-1] < level) & (x[1:] >= level))
    share = (level - x[up]) / (x[up + 1] - x[up])
    return v[up] + share * (v[up + 1] - v[up])


def largest_expected_power(speeds_by_record, power: float) -> float:
    """E[V_max^p], V_max each record's largest crossing speed (0 without one)."""
    return float(np.mean([max(speeds.max(initial=0.0), 0.0) ** power for speeds in speeds_by_record]))


def free_motion_speeds(case, records: int = RECORDS) -> np.ndarray:
    """Each record's largest upward crossing speed of the gap by X = x1 - x2
    without contact (0 if X never reaches the gap) [m/s]."""
    speeds = np.zeros(records)
    for i, record in enumerate(ground_accelerations(case.excitation, SEED, np.arange(records))):
        crossings = upcrossing_speeds(*contact_motion(case, record, contact=False), case.contact.gap)
        if crossings.size:
            speeds[i] = np.max(crossings)
    return speeds


DOUBLE_BARRIER = math.sqrt(math.pi / 2.0)  # Vanmarcke's constant for crossings of +-d, the estimator's
ONE_SIDED = math.sqrt(2.0 * math.pi)  # the same derivation for crossings of d alone


def vanmarcke_clumps(r, clumping):
    """Vanmarcke's factor min(1, (1 - exp(-clumping r)) / (1 - exp(-r^2 / 2))) at the
    envelope level r [sigma], 1 at r = 0; ``clumping`` is his constant times q^1.2."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(r > 1e-9, np.minimum(1.0, -np.expm1(-clumping * r) / -np.expm1(-0.5 * r * r)), 1.0)


def _expected_power(
    result, power: float, rate, points: int = 400, gap: float | None = None, clumps: bool = True, barrier: float = DOUBLE_BARRIER
) -> float:
    """E[V_max^p] from an impact rate ``rate(u, rho)`` (per unit time, in units of
    sigma_V / sigma_X, for crossings faster than rho sigma_V at u = d / sigma_X)
    with Vanmarcke's clumps (or without, ``clumps=False``; ``barrier`` his
    constant), over the pair's sigma history, at the case's gap or at ``gap`` [m]."""
    crossings = result.crossings
    gap = result.case.contact.gap if gap is None else gap
    clumping = barrier * crossings.bandwidth**1.2 if clumps else math.inf
    speeds = np.linspace(0.0, 10.0 * crossings.sigma_v.max(), points)
    expected = np.zeros(points)
    for sigma_x, sigma_v, weight in zip(crossings.sigma_x, crossings.sigma_v, crossings.weights):
        u, rho = gap / sigma_x, speeds / sigma_v
        expected += weight * sigma_v / sigma_x * rate(u, rho) * vanmarcke_clumps(np.hypot(u, rho), clumping)
    return float(np.trapezoid(-np.expm1(-expected), speeds**power))


def rice_expected_power(result, power: float, gap: float | None = None, clumps: bool = True, barrier: float = DOUBLE_BARRIER) -> float:
    """Rice's count of the free motion's crossings, no returns after an impact:
    exp(-(u^2 + rho^2) / 2) / (2 pi). Only for this diagnosis."""

    def rate(u, rho):
        return np.exp(-0.5 * (u * u + rho * rho)) / (2 * math.pi)

    return _expected_power(result, power, rate, gap=gap, clumps=clumps, barrier=barrier)


def mirror_expected_power(result, power: float) -> float:
    """The mirror returns (the estimator's count before the time cut):
    exp(-u^2 / 2) G(u, rho), G(u, rho) = int_rho^inf R exp(-R^2 / 2) / (2 (pi - atan2(R, u))) dR,
    the Rayleigh envelope a = sqrt(d^2 + R^2 sigma_X^2) and the return rate at it. Only for this diagnosis."""
    grid = np.linspace(0.0, 12.0, 4001)

    def rate(u, rho):
        integrand = grid * np.exp(-0.5 * grid**2) / (2.0 * (math.pi - np.arctan2(grid, u)))
        tail = np.concatenate([np.cumsum((0.5 * (integrand[1:] + integrand[:-1]) * np.diff(grid))[::-1])[::-1], [0.0]])
        return math.exp(-0.5 * u * u) * np.interp(rho, grid, tail)

    return _expected_power(result, power, rate)


def free_motion_table(cases: int | None = None, records: int = RECORDS) -> None:
    print("| case | gap / sigma_X | impacts: simulated / free motion | time cut: estimator / Rice | Gaussian: Rice / free motion "
          "| estimate / simulated |")
    print("|---|---|---|---|---|---|")
    for case in first(accuracy_cases(), cases):
        result = free_estimate(case)
        power = 1.0 if case.contact.model == "linear" else 1.2  # the peak force grows as v^power
        simulated = simulate(case, records=records, seed=SEED)
        with_impacts = np.mean(simulated.impact_velocity_max**power)
        free = np.mean(free_motion_speeds(case, records) ** power)
        rice = rice_expected_power(result, power)
        gap = np.array([case.contact.gap])
        cut = expected_maximum(result.crossings, gap, lambda v: v**power, power, result.crossings.damped(gap))[0]
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {with_impacts / free - 1:+.1%} "
              f"| {cut / rice - 1:+.1%} | {rice / free - 1:+.1%} | {result.force_expected / simulated.force_max_mean - 1:+.1%} |")


def mirror_table(cases: int | None = None, records: int = RECORDS) -> None:
    print("| case | gap / sigma_X | largest speed, time cut (the estimator) | largest speed, mirror returns |")
    print("|---|---|---|---|")
    for case in first(accuracy_cases(), cases):
        result = free_estimate(case)
        power = 1.0 if case.contact.model == "linear" else 1.2
        simulated = np.mean(simulate(case, records=records, seed=SEED).impact_velocity_max ** power)
        gap = np.array([case.contact.gap])
        cut = expected_maximum(result.crossings, gap, lambda v: v**power, power, result.crossings.damped(gap))[0]
        mirror = mirror_expected_power(result, power)
        print(f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {cut / simulated - 1:+.1%} "
              f"| {mirror / simulated - 1:+.1%} |")


RATE_CASES = (
    "section5-T2-0.4", "section5-T2-0.8", "s5-T2-0.8 G0x4pi2", "T1 1.2 T2 2.0", "T2 2.0 G0x0.25 gap0 e0.9",
    "s5-T2-0.8 G0x0.25", "s5-T2-0.4 gap5cm", "elastic 1.2/0.4 gap6cm",
)
SPEED_LEVELS = np.array([0.0, 1.0, 2.0, 2.5, 3.0])  # [sigma_V]


def approach_speeds(case, records: int) -> tuple[list, list]:
    """Each record's upward crossing speeds of the gap by the impacting motion
    (its approaches) and by the free motion (the same record, no contact)."""
    impacting, free_motion = [], []
    for record in ground_accelerations(case.excitation, SEED, np.arange(records)):
        impacting.append(upcrossing_speeds(*contact_motion(case, record), case.contact.gap))
        free_motion.append(upcrossing_speeds(*contact_motion(case, record, contact=False), case.contact.gap))
    return impacting, free_motion


def rates_table(cases: int | None = None, records: int = RATE_RECORDS) -> None:
    """Approaches faster than v per record, impacting over free motion, against the time cut's 1 / Phi(u)."""
    print("| case | q | gap / sigma_X | time cut 1 / Phi(u) | " + " | ".join(f"v > {level:g} sigma_V" for level in SPEED_LEVELS)
          + " | E[V_max^p], impacting / free |")
    print("|---" * (5 + SPEED_LEVELS.size) + "|")
    for case in first((case for case in accuracy_cases() if case.name in RATE_CASES), cases):
        result = free_estimate(case)
        power = 1.0 if case.contact.model == "linear" else 1.2
        impacting, free_motion = approach_speeds(case, records)
        levels = SPEED_LEVELS * result.sigma_relative_velocity
        counts = [sum(int(np.sum(speeds > level)) for speeds in group) for group in (impacting, free_motion) for level in levels]
        ratios = np.array(counts[: levels.size]) / np.maximum(counts[levels.size :], 1)
        largest = [largest_expected_power(group, power) for group in (impacting, free_motion)]
        u = case.contact.gap / result.sigma_relative_displacement
        print(f"| {case.name} | {result.crossings.bandwidth:.2f} | {u:.2f} | {2.0 / math.erfc(-u / math.sqrt(2.0)):.2f} | "
              + " | ".join(f"{r:.2f}" for r in ratios) + f" | {largest[0] / largest[1]:.3f} |", flush=True)


TABLES = ("force", "free-motion", "mirror", "rates")


def main(table: str = "force", cases: int | None = None, records: int = RECORDS, rate_records: int = RATE_RECORDS) -> None:
    """Print ``table`` (one of :data:`TABLES`) over the first ``cases`` of the grid
    (all for None), ``records`` records each (``rate_records`` for the rates)."""
    if table == "free-motion":
        free_motion_table(cases, records)
        return
    if table == "rates":
        rates_table(cases, rate_records)
        return
    if table == "mirror":
        mirror_table(cases, records)
        return
    print("| case | gap / sigma_X | bandwidth q | impact force, free masses | impact force | largest speed | estimate |")
    print("|---|---|---|---|---|---|---|")
    for case in first(accuracy_cases(), cases):
        result = free_estimate(case)
        simulated = simulate(case, records=records, seed=SEED)
        speeds = simulated.impact_velocity_max
        braked = impact_peak_force(case.contact, speeds, case.reduced_mass, result.opposing_force).mean()
        free = impact_peak_force(case.contact, speeds, case.reduced_mass).mean()
        mean = simulated.force_max_mean
        print(
            f"| {case.name} | {case.contact.gap / result.sigma_relative_displacement:.2f} | {result.crossings.bandwidth:.2f} "
            f"| {free / mean - 1:+.1%} | {braked / mean - 1:+.1%} | {result.force_expected / braked - 1:+.1%} "
            f"| {result.force_expected / mean - 1:+.1%} |"
        )
    print("\nimpact force: F(V_max) of the simulated speeds / simulated E[F_max] - 1; largest speed: estimate / that - 1.")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    for name in TABLES[1:]:
        group.add_argument(f"--{name}", dest="table", action="store_const", const=name)
    main(parser.parse_args().table or "force")
