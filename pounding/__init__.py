"""pounding: the expected extreme pounding force between two adjacent buildings
under random earthquakes, by closed form and by Monte Carlo time histories.

Reference: S. Rahimi and M. Soltani (2016), "Expected extreme value of
pounding force between two adjacent buildings", Structural Engineering and
Mechanics.
"""

from .case import Case, load_case, preset_names
from .contact import Contact
from .errors import CaseError, ConvergenceError, SimulationError
from .excitation import CloughPenzien, Excitation, KanaiTajimi, ShinozukaSato
from .simulation import Settings, SimulationResult, TimeHistory, integrate, simulate, simulate_record
from .structures import BoucWen, Building, Storey

__version__ = "0.1.0"

__all__ = [
    "BoucWen",
    "Building",
    "Case",
    "CaseError",
    "CloughPenzien",
    "Contact",
    "ConvergenceError",
    "Excitation",
    "KanaiTajimi",
    "Settings",
    "ShinozukaSato",
    "SimulationError",
    "SimulationResult",
    "Storey",
    "TimeHistory",
    "integrate",
    "load_case",
    "preset_names",
    "simulate",
    "simulate_record",
]
