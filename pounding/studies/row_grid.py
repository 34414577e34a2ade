"""The accuracy grid of cases with several contacts (docs/accuracy.md, "Several contacts"): two buildings
meeting at every floor they share, a taller beside a shorter one meeting at the shorter's floors, and three
buildings in a row.

Each kind comes in two geometries (:data:`GEOMETRIES`: storeys and fundamental periods), each building a uniform
shear building (equal floors of :data:`FLOOR_MASS`, equal storeys), every contact at aligned floors. Each case is
taken elastic and yielding (every storey's yield drift the elastic first floor's sigma, post-yield ratio 0.1, Wen's
symmetric loop: :data:`YIELDING`), under the Section 5 Kanai-Tajimi soil and the same as a Clough-Penzien spectrum,
at the storey grid's gaps (:data:`~pounding.studies.storey_grid.GAP_LEVELS`) times the contacts' median elastic
sigma_X (pounding frequent, and rare). 48
cases. No number here was chosen from a Monte Carlo result.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from pounding.case.case import Case, case_from_dict
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.regimes import ROW_KINDS
from pounding.hazard.excitation import CloughPenzien
from pounding.mechanics.structures import BoucWen
from pounding.studies.storey_grid import GAP_LEVELS

__all__ = ["FLOOR_MASS", "GEOMETRIES", "YIELDING", "row_cases"]

GEOMETRIES = {  # the kinds of pounding.closed_form.regimes.ROW_KINDS
    "aligned floors": (((3, 0.5), (3, 0.35)), ((5, 0.9), (5, 0.6))),
    "unequal heights": (((5, 0.8), (3, 0.4)), ((4, 0.6), (2, 0.3))),
    "three in a row": (((3, 0.5), (2, 0.3), (4, 0.6)), ((5, 0.9), (3, 0.45), (5, 0.8))),
}
"""Each kind's two rows: (storeys, fundamental period [s]) of each building, left to right."""
FLOOR_MASS = 4.0e4
"""[kg] every floor: the paper's scale (40 kgf s^2/cm)."""
YIELDING = {"post_yield_ratio": 0.1, "beta_share": 0.5, "n": 1.0}
"""The yielding storeys' law, with a yield drift of the elastic first floor's sigma."""
_HAZARDS = ("kanai-tajimi", "clough-penzien")
_SOIL = {"spectrum": "kanai-tajimi", "G0": 65.03e-4, "omega_g": 27.02, "xi_g": 0.34, "duration": 20.0}  # Section 5 [m^2/s^3]
_CONTACT = {"model": "jankowski", "stiffness": 1.96e9, "restitution": 0.65, "levels": "aligned"}


def _storey_stiffness(storeys: int, period: float) -> float:
    """Storey stiffness [N/m] of a uniform shear building of ``storeys`` floors of :data:`FLOOR_MASS` whose
    fundamental period is ``period`` [s]: omega_1 = 2 sqrt(k / m) sin(pi / (2 (2 n + 1)))."""
    omega = 2.0 * math.pi / period
    return FLOOR_MASS * (omega / (2.0 * math.sin(math.pi / (2.0 * (2 * storeys + 1))))) ** 2


def _elastic_row(geometry, hazard: str) -> Case:
    buildings = [{"damping_ratio": 0.05, "storeys": [{"mass": FLOOR_MASS, "stiffness": _storey_stiffness(n, period)}] * n}
                 for n, period in geometry]
    contacts = [{**_CONTACT, "between": [b, b + 1], "gap": 0.0} for b in range(1, len(geometry))]
    case = case_from_dict({"units": "SI", "excitation": _SOIL, "buildings": buildings, "contacts": contacts}, name=hazard)
    if hazard == "clough-penzien":
        soil = case.excitation.spectrum
        spectrum = CloughPenzien(soil.G0, soil.omega_g, soil.xi_g, omega_f=2.0, xi_f=0.6)
        case = dataclasses.replace(case, excitation=dataclasses.replace(case.excitation, spectrum=spectrum))
    return case


def _yielding(case: Case) -> tuple:
    """Every building with each storey's yield drift the elastic first floor's sigma (:data:`YIELDING`)."""
    buildings = []
    for index, building in enumerate(case.buildings):
        neighbour = index + 1 if index + 1 < len(case.buildings) else index - 1
        pair = dataclasses.replace(case, buildings=(building, case.buildings[neighbour]),
                                   contacts=(dataclasses.replace(case.contacts[0], between=(1, 2), levels=(1, 1)),))
        sigma = float(LinearizedPair.of(pair).floor_statistics.displacement[0][0])
        law = BoucWen.from_yield_drift(sigma, **YIELDING)
        buildings.append(dataclasses.replace(building, storeys=tuple(dataclasses.replace(s, bouc_wen=law) for s in building.storeys)))
    return tuple(buildings)


def row_cases() -> list[Case]:
    """The grid's cases (see the module's docstring), named by kind, geometry, storeys, hazard and gap."""
    cases = []
    for kind, hazard in itertools.product(ROW_KINDS, _HAZARDS):
        for geometry in GEOMETRIES[kind]:
            base = _elastic_row(geometry, hazard)
            sigma_x = float(np.median([LinearizedPair.of(base.pair(i)).stationary_response.sigma_relative_displacement
                                       for i in range(len(base.contacts))]))
            shape = " / ".join(f"{n} storeys {period:g} s" for n, period in geometry)
            for storeys, buildings in (("elastic", base.buildings), ("yielding", _yielding(base))):
                for level in GAP_LEVELS:
                    contacts = tuple(dataclasses.replace(c, gap=level * sigma_x) for c in base.contacts)
                    name = f"{kind}: {shape}, {storeys}, {hazard}, gap {level:g} sigma_X"
                    cases.append(dataclasses.replace(base, buildings=buildings, contacts=contacts, name=name))
    return cases
