"""pounding: the expected extreme pounding force between two adjacent buildings
under random earthquakes, by closed form and by Monte Carlo time histories.

Reference: S. Rahimi and M. Soltani (2016), "Expected extreme value of
pounding force between two adjacent buildings", Structural Engineering and
Mechanics.

The public names are imported lazily, so that ``import pounding.cli`` (and
``pounding cases``) stays light.
"""

from importlib import import_module

__version__ = "0.1.0"

_EXPORTS = {
    "Case": "case",
    "load_case": "case",
    "preset_names": "case",
    "Contact": "contact",
    "CaseError": "errors",
    "ConvergenceError": "errors",
    "SimulationError": "errors",
    "CloughPenzien": "excitation",
    "Excitation": "excitation",
    "KanaiTajimi": "excitation",
    "ShinozukaSato": "excitation",
    "Settings": "simulation",
    "SimulationResult": "simulation",
    "TimeHistory": "simulation",
    "DesignGap": "simulation",
    "design_gap": "simulation",
    "integrate": "simulation",
    "simulate": "simulation",
    "simulate_record": "simulation",
    "LinearizedPair": "pair",
    "estimate": "estimator",
    "force_versus_gap": "estimator",
    "BoucWen": "structures",
    "Building": "structures",
    "Storey": "structures",
    "sweep": "sweeps",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name in _EXPORTS:
        value = getattr(import_module(f".{_EXPORTS[name]}", __name__), name)
    else:
        raise AttributeError(f"module 'pounding' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(list(globals()) + __all__)
