"""The accuracy grid's storeys given the engineer's way: a yield drift, a post-yield ratio, Wen's n and
the loop's shape (``beta_share``), instead of the paper's beta = 2, gamma = -1 (docs/accuracy.md).

One pair of one-storey buildings, 1.0 s beside 0.5 s, under three hazards: the paper's Kanai-Tajimi
soil (Section 5), the same as a Clough-Penzien spectrum (high-pass 2 rad/s, xi_f 0.6) and the EC8
type 1, ground C, 0.30 g design spectrum's compatible bank. Under each, both storeys take one law of
every beta_share in :data:`LOOP_SHARES` and n in :data:`EXPONENTS`, with a yield drift of each of
:data:`YIELD_LEVELS` times the elastic floor's sigma (from well below to above the elastic response) and
the post-yield ratios of :data:`POST_YIELD_RATIOS` in turn (shifted by one from one loop to the next, so
that each yield level meets each ratio), plus the elastic pair and one elastic-perfectly plastic pair
(post-yield ratio 0: the closed form refuses it, having no steady state); each at the gaps of
:data:`GAP_LEVELS` times the elastic pair's sigma_X (pounding frequent, and rare). 120 cases.
"""

from __future__ import annotations

import dataclasses
import itertools

from pounding.case.case import Case, case_from_dict
from pounding.closed_form.pair import LinearizedPair
from pounding.hazard.excitation import CloughPenzien
from pounding.mechanics.structures import BoucWen

__all__ = ["EXPONENTS", "GAP_LEVELS", "LOOP_SHARES", "POST_YIELD_RATIOS", "STOREY_HAZARDS", "YIELD_LEVELS",
           "engineer_storey_cases"]

STOREY_HAZARDS = ("kanai-tajimi", "clough-penzien", "design")
LOOP_SHARES = (0.5, 1.0, 2.0)
"""beta / (beta + gamma): Wen's symmetric loop (a case's default), gamma = 0, and the paper's loop [-]."""
EXPONENTS = (1.0, 2.0)
"""Wen's n: a smooth and a sharper yield [-]."""
YIELD_LEVELS = (0.5, 1.0, 2.0)
"""Yield drift over the elastic floor's sigma [-]: storeys that yield often, sometimes, rarely."""
POST_YIELD_RATIOS = (0.02, 0.1, 0.2)
"""Post-yield stiffness over the elastic one [-], taken in turn with the yield levels."""
GAP_LEVELS = (0.25, 1.25)
"""Gap over the elastic pair's sigma_X [-]: pounding frequent, and rare."""
_PERIODS = (1.0, 0.5)  # [s]
_MASS = 4.0e4  # [kg] a floor: the paper's scale (40 kgf s^2/cm)
_SOIL = {"spectrum": "kanai-tajimi", "G0": 65.03e-4, "omega_g": 27.02, "xi_g": 0.34, "duration": 20.0}  # Section 5 [m^2/s^3]
_DESIGN = {"spectrum": "design", "code": "ec8", "spectrum_type": 1, "ground_type": "C", "ag": 0.30, "duration": 20.0}
_CONTACT = {"model": "jankowski", "stiffness": 1.96e9, "restitution": 0.65, "levels": [1, 1]}  # 2e5 kgf/cm^1.5


def _elastic_pair(hazard: str) -> Case:
    """The elastic 1.0 s / 0.5 s pair under ``hazard`` (one of :data:`STOREY_HAZARDS`), gap 0."""
    excitation = _DESIGN if hazard == "design" else _SOIL
    buildings = [{"damping_ratio": 0.05, "storeys": [{"period": period, "mass": _MASS}]} for period in _PERIODS]
    case = case_from_dict({"units": "SI", "excitation": excitation, "buildings": buildings,
                           "contact": {**_CONTACT, "gap": 0.0}}, name=hazard)
    if hazard == "clough-penzien":
        soil = case.excitation.spectrum
        spectrum = CloughPenzien(soil.G0, soil.omega_g, soil.xi_g, omega_f=2.0, xi_f=0.6)
        case = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=spectrum))
    return case


def _storey_laws(floor_sigmas) -> list[tuple[str, tuple[BoucWen, BoucWen]]]:
    """(label, both buildings' laws): the elastic pair, the elastic-perfectly plastic one, then every loop
    share, n and yield level."""
    def law(share, n, level, ratio):
        pair = tuple(BoucWen.from_yield_drift(level * sigma, ratio, n, share) for sigma in floor_sigmas)
        return f"beta_share {share:g}, n {n:g}, yield {level:g} sigma, post-yield {ratio:g}", pair

    laws = [("elastic", (BoucWen(alpha=1.0), BoucWen(alpha=1.0))), law(0.5, 1.0, 1.0, 0.0)]
    for shift, (share, n) in enumerate(itertools.product(LOOP_SHARES, EXPONENTS)):
        ratios = POST_YIELD_RATIOS[shift % 3:] + POST_YIELD_RATIOS[:shift % 3]
        laws += [law(share, n, level, ratio) for level, ratio in zip(YIELD_LEVELS, ratios)]
    return laws


def engineer_storey_cases() -> list[Case]:
    """The grid's cases of storeys given the engineer's way (see the module's docstring), named by
    hazard, storey law and gap."""
    cases = []
    for hazard in STOREY_HAZARDS:
        base = _elastic_pair(hazard)
        elastic = LinearizedPair.of(base)
        floor_sigmas = [float(sigma[0]) for sigma in elastic.floor_statistics.displacement]
        sigma_x = elastic.stationary_response.sigma_relative_displacement
        for label, laws in _storey_laws(floor_sigmas):
            buildings = tuple(dataclasses.replace(building, storeys=tuple(dataclasses.replace(s, bouc_wen=law) for s in building.storeys))
                              for building, law in zip(base.buildings, laws))
            for level in GAP_LEVELS:
                contact = dataclasses.replace(base.contact, gap=level * sigma_x)
                name = f"{hazard}, {label}, gap {level:g} sigma_X"
                cases.append(dataclasses.replace(base, buildings=buildings, contacts=(contact,), name=name))
    return cases
