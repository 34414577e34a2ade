"""The units the dashboard's inputs are typed in: SI as engineers read it (mm, kN, t), or the paper's kgf, cm, s
(masses in kgf s^2/cm). The case file the inputs become is SI or kgf-cm-s, coherent, converted here once."""

from __future__ import annotations

from dataclasses import dataclass

from pounding.units import KGF_CM_S

__all__ = ["DisplaySystem", "display_system"]


@dataclass(frozen=True)
class DisplaySystem:
    """Sizes of the units shown, in SI: [m], [N], [kg] per unit; their labels; the case file's unit system."""

    length: float
    force: float
    mass: float
    length_label: str
    force_label: str
    mass_label: str
    file_units: str

    def to_si(self, value: float, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> float:
        return value * self.length**length * self.force**force * self.mass**mass

    def from_si(self, value: float, **dimension) -> float:
        return value / self.to_si(1.0, **dimension)

    def to_file(self, value: float, **dimension) -> float:
        """``value`` shown here, in the case file's units."""
        if self.file_units == "SI":
            return self.to_si(value, **dimension)
        return value

    def from_file(self, value: float, **dimension) -> float:
        """``value`` in the case file's units, as shown here."""
        if self.file_units == "SI":
            return self.from_si(value, **dimension)
        return value

    def label(self, *, length: float = 0, force: float = 0, mass: float = 0, time: float = 0) -> str:
        """The unit of that dimension: "mm", "kN/mm^1.5", "mm^2/s^3"."""
        parts = [(self.force_label, force), (self.mass_label, mass), (self.length_label, length), ("s", time)]
        up = [name if p == 1 else f"{name}^{p:g}" for name, p in parts if p > 0]
        down = [name if p == -1 else f"{name}^{-p:g}" for name, p in parts if p < 0]
        text = "*".join(up) or "1"
        return text + ("/" + "/".join(down) if down else "")


_SYSTEMS = {
    "SI": DisplaySystem(1e-3, 1e3, 1e3, "mm", "kN", "t", "SI"),
    "kgf-cm-s": DisplaySystem(KGF_CM_S.length, KGF_CM_S.force, KGF_CM_S.mass, "cm", "kgf", "kgf*s^2/cm", "kgf-cm-s"),
}


def display_system(units: str) -> DisplaySystem:
    """The :class:`DisplaySystem` of "SI" or "kgf-cm-s"."""
    return _SYSTEMS[units]
