"""The dashboard's inputs that are declared per building, and the unit of
each dimensional input in the unit system shown."""

from __future__ import annotations

import param

from pounding.contact import contact_law

__all__ = ["DIMENSIONS", "MAX_STOREYS", "building_params"]

MAX_STOREYS = 10


def building_params(number: int, period: float) -> dict:
    b = f"building {number}"
    return {
        f"storeys_{number}": param.Integer(1, bounds=(1, MAX_STOREYS), label="storeys", doc=f"Number of storeys of {b}; all alike."),
        f"period_{number}": param.Number(
            period, bounds=(0.05, 5.0), step=0.05, label="period T [s]",
            doc=f"Initial period of {b} [s] (one storey: with the mass it fixes the stiffness; more storeys: the fundamental period, shown).",
        ),
        f"mass_{number}": param.Number(4e4, label="storey mass", doc=f"Floor mass of each storey of {b} [mass unit]."),
        f"stiffness_{number}": param.Number(
            1e6, label="storey stiffness", doc=f"Initial stiffness of each storey of {b} [force/length] (one storey: from the period, shown)."
        ),
        f"damping_ratio_{number}": param.Number(0.05, bounds=(0.0, 0.3), step=0.01, label="damping ratio [-]", doc="Viscous damping ratio of the first mode."),
        f"alpha_{number}": param.Number(0.05, bounds=(0.0, 1.0), step=0.01, label="Bouc-Wen alpha [-]", doc="Post-yield to initial stiffness ratio."),
        f"A_{number}": param.Number(1.0, bounds=(0.1, 3.0), step=0.05, label="Bouc-Wen A [-]", doc="Amplitude of the hysteretic rate."),
        f"beta_{number}": param.Number(200.0, label="Bouc-Wen beta", doc="Shape parameter [1/length^n]; beta + gamma > 0."),
        f"gamma_{number}": param.Number(-100.0, label="Bouc-Wen gamma", doc="Shape parameter [1/length^n]; beta - gamma >= 0."),
        f"n_{number}": param.Number(1.0, bounds=(0.5, 4.0), step=0.5, label="Bouc-Wen n [-]", doc="Smoothness of yielding, >= 1."),
    }


def _dimensions(model) -> dict[str, dict]:
    """Dimension (exponents of length, force, mass) of each dimensional input."""
    exponent = contact_law(model.contact_model).stiffness_exponent
    dims = {
        "G0": {"length": 2},
        "gap": {"length": 1},
        "contact_stiffness": {"force": 1, "length": -exponent},
    }
    for b in (1, 2):
        n = getattr(model, f"n_{b}")
        dims |= {f"mass_{b}": {"mass": 1}, f"stiffness_{b}": {"force": 1, "length": -1}, f"beta_{b}": {"length": -n}, f"gamma_{b}": {"length": -n}}
    return dims


DIMENSIONS = _dimensions
"""``DIMENSIONS(model)``: the dimensional inputs and their dimensions."""
