"""Unit systems accepted at the edges; SI (N, m, kg, s) everywhere inside.

The paper works in kgf, cm and s, with masses in kgf*s^2/cm. A case file
says which system it uses; :func:`to_si` converts each quantity once, at load.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["KGF_CM_S", "SI", "STANDARD_GRAVITY", "UNIT_SYSTEMS", "UnitSystem", "unit_system"]

STANDARD_GRAVITY = 9.80665
"""[m/s^2], the kilogram-force is this many newtons."""


@dataclass(frozen=True)
class UnitSystem:
    """A coherent unit system given by its length and force units in SI.

    Mass is derived (force * s^2 / length), time is always the second.
    """

    name: str
    length: float  # [m] per unit of length
    force: float  # [N] per unit of force
    length_label: str
    force_label: str

    @property
    def mass(self) -> float:
        """[kg] per unit of mass (force*s^2/length)."""
        return self.force / self.length

    @property
    def mass_label(self) -> str:
        return "kg" if self.name == "SI" else f"{self.force_label}*s^2/{self.length_label}"

    def to_si(self, value: float, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> float:
        """Convert ``value`` of dimension length^length * force^force * mass^mass
        (* s^time, the same in every system) to SI."""
        return value * self.length**length * self.force**force * self.mass**mass

    def from_si(self, value: float, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> float:
        """Convert an SI ``value`` of the given dimension to this system."""
        return value / self.to_si(1.0, length=length, force=force, mass=mass)

    def label(self, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> str:
        """The unit of that dimension in this system, e.g. ``"kgf/cm^1.5"``,
        ``"kgf*s^2/cm"`` (a mass), ``"cm^2/s^3"``; ``""`` when dimensionless."""
        if mass == 1 and not (length or force or time):
            return self.mass_label
        # a mass is force * s^2 / length here
        powers = ((self.length_label, length - mass), (self.force_label, force + mass), ("s", time + 2 * mass))
        if self.name == "SI" and mass:
            powers = ((self.length_label, length), (self.force_label, force), ("kg", mass), ("s", time))

        def product(parts):
            return "*".join(name if power == 1 else f"{name}^{power:g}" for name, power in parts)

        above = [(name, power) for name, power in powers if power > 0]
        below = [(name, -power) for name, power in powers if power < 0]
        if not below:
            return product(above)
        return f"{product(above) or '1'}/{product(below) if len(below) == 1 else '(' + product(below) + ')'}"


SI = UnitSystem("SI", length=1.0, force=1.0, length_label="m", force_label="N")
KGF_CM_S = UnitSystem("kgf-cm-s", length=0.01, force=STANDARD_GRAVITY, length_label="cm", force_label="kgf")
UNIT_SYSTEMS = {SI.name: SI, KGF_CM_S.name: KGF_CM_S}


def unit_system(name: str) -> UnitSystem:
    """The unit system called ``name`` ("SI" or "kgf-cm-s")."""
    from pounding.errors import CaseError, quote

    if isinstance(name, str) and name in UNIT_SYSTEMS:
        return UNIT_SYSTEMS[name]
    raise CaseError("units", f"unknown unit system {quote(name)}; allowed: {', '.join(UNIT_SYSTEMS)}")
