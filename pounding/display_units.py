"""Display units: how numbers are shown and typed on a page or a terminal (:class:`Display`), one per unit
system of the inputs: results as text in the units an engineer reads them in (kN, mm), and the dashboard's
inputs converted between those units, SI and the case file's. Light: the command line imports it."""

from __future__ import annotations

import math
from dataclasses import dataclass

from pounding.units import KGF_CM_S, SI, UNIT_SYSTEMS, UnitSystem

__all__ = ["DISPLAY_UNITS", "Display", "display"]


@dataclass(frozen=True)
class Display:
    """How numbers are shown: a unit system for inputs, and the units an engineer reads and types them in.

    Attributes
    ----------
    system : UnitSystem
        Units of the case's inputs (and of the case file the dashboard writes).
    force_unit, force_scale : str, float
        Force unit and its size [N] (``kN`` = 1e3): every force is shown in it, however large (12,340 kN, not
        12.34 MN), so that the numbers of one page or one command compare at a glance.
    length_unit, length_scale : str, float
        Unit of displacements, gaps, penetrations and its size [m].
    velocity_unit, velocity_scale : str, float
        [m/s] per unit.
    mass_unit, mass_scale : str, float
        Unit of masses typed in and its size [kg] (``t`` = 1e3).
    """

    system: UnitSystem
    force_unit: str
    force_scale: float
    length_unit: str
    length_scale: float
    velocity_unit: str
    velocity_scale: float
    mass_unit: str
    mass_scale: float

    # --- results as text -------------------------------------------------------------

    def force(self, value: float | None) -> str:
        """A force [N] as text with its unit, 4 significant digits."""
        if value is None or not math.isfinite(value):
            return "n/a"
        shown = value / self.force_scale
        if 1e4 <= abs(shown) < 1e15:  # 31,540 kgf or 12,340 kN, not 3.154e+04 kgf
            return f"{shown:,.0f} {self.force_unit}"
        return f"{shown:.4g} {self.force_unit}"

    def length(self, value: float | None) -> str:
        """A length [m] as text with its unit, 4 significant digits."""
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.length_scale:.4g} {self.length_unit}"

    def velocity(self, value: float | None) -> str:
        """A velocity [m/s] as text with its unit, 4 significant digits."""
        if value is None or not math.isfinite(value):
            return "n/a"
        return f"{value / self.velocity_scale:.4g} {self.velocity_unit}"

    # --- inputs: a value of a dimension (exponents of length, force, mass, time) ------

    def to_si(self, value: float, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> float:
        """``value`` typed in these units, in SI (time is in seconds in every system)."""
        return value * self.length_scale**length * self.force_scale**force * self.mass_scale**mass

    def from_si(self, value: float, **dimension) -> float:
        """An SI ``value``, in these units."""
        return value / self.to_si(1.0, **dimension)

    def to_file(self, value: float, **dimension) -> float:
        """``value`` typed in these units, in the case file's (:attr:`system`)."""
        if self._is_system():
            return value
        return self.system.from_si(self.to_si(value, **dimension), **dimension)

    def from_file(self, value: float, **dimension) -> float:
        """``value`` in the case file's units (:attr:`system`), in these units."""
        if self._is_system():
            return value
        return self.from_si(self.system.to_si(value, **dimension), **dimension)

    def _is_system(self) -> bool:
        """Whether the units typed in are the system's own (no conversion at all)."""
        system = self.system
        return (self.length_scale, self.force_scale, self.mass_scale) == (system.length, system.force, system.mass)

    def label(self, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> str:
        """The unit of that dimension: "mm", "kN/mm^1.5", "mm^2/s^3"; "1" when dimensionless."""
        parts = [(self.force_unit, force), (self.mass_unit, mass), (self.length_unit, length), ("s", time)]
        up = [name if p == 1 else f"{name}^{p:g}" for name, p in parts if p > 0]
        down = [name if p == -1 else f"{name}^{-p:g}" for name, p in parts if p < 0]
        text = "*".join(up) or "1"
        return text + ("/" + "/".join(down) if down else "")


DISPLAY_UNITS = {
    SI.name: Display(SI, "kN", 1e3, "mm", 1e-3, "m/s", 1.0, "t", 1e3),
    KGF_CM_S.name: Display(KGF_CM_S, "kgf", KGF_CM_S.force, "cm", KGF_CM_S.length, "cm/s", KGF_CM_S.length,
                           "kgf*s^2/cm", KGF_CM_S.mass),
}
"""The display units of each unit system, by its name: SI shown in kN, mm, t; the paper's kgf, cm, s as they are."""


def display(units: str) -> Display:
    """The :class:`Display` of a unit system's name ("SI" or "kgf-cm-s")."""
    if units not in UNIT_SYSTEMS:
        from pounding.errors import ArgumentError

        raise ArgumentError("units", f"unknown unit system {units!r}; allowed: {', '.join(UNIT_SYSTEMS)}")
    return DISPLAY_UNITS[units]
