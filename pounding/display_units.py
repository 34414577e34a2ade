"""Display units: how numbers are shown on a page or a terminal (:class:`Display`),
one per unit system of the inputs; results in the units an engineer reads them in.
Light: the command line imports it."""

from __future__ import annotations

import math
from dataclasses import dataclass

from pounding.units import KGF_CM_S, SI, UNIT_SYSTEMS, UnitSystem

# --- display units -------------------------------------------------------------


@dataclass(frozen=True)
class Display:
    """How numbers are shown: a unit system for inputs, and the units an
    engineer reads results in.

    Attributes
    ----------
    system : UnitSystem
        Units of the case's inputs.
    force_unit, force_scale : str, float
        Force unit and its size [N] (``kN`` = 1e3; switched to MN above 1 MN).
    length_unit, length_scale : str, float
        Unit of displacements, gaps, penetrations and its size [m].
    velocity_unit, velocity_scale : str, float
        [m/s] per unit.
    """

    system: UnitSystem
    force_unit: str
    force_scale: float
    length_unit: str
    length_scale: float
    velocity_unit: str
    velocity_scale: float

    def force(self, value: float | None) -> str:
        """A force [N] as text with its unit, 4 significant digits."""
        if value is None or not math.isfinite(value):
            return "n/a"
        if self.force_unit == "kN" and abs(value) >= 1e6:
            return f"{value / 1e6:.4g} MN"
        shown = value / self.force_scale
        if 1e4 <= abs(shown) < 1e15:  # 31,540 kgf, not 3.154e+04 kgf
            return f"{shown:,.0f} {self.force_unit}"
        return f"{shown:.4g} {self.force_unit}"

    def length(self, value: float | None) -> str:
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.length_scale:.4g} {self.length_unit}"

    def velocity(self, value: float | None) -> str:
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.velocity_scale:.4g} {self.velocity_unit}"


DISPLAY_UNITS = {
    SI.name: Display(SI, "kN", 1e3, "mm", 1e-3, "m/s", 1.0),
    KGF_CM_S.name: Display(KGF_CM_S, "kgf", KGF_CM_S.force, "cm", KGF_CM_S.length, "cm/s", KGF_CM_S.length),
}


def display(units: str) -> Display:
    """The :class:`Display` of a unit system's name ("SI" or "kgf-cm-s")."""
    if units not in UNIT_SYSTEMS:
        from pounding.errors import CaseError

        raise CaseError("units", f"unknown unit system {units!r}; allowed: {', '.join(UNIT_SYSTEMS)}")
    return DISPLAY_UNITS[units]
