"""pounding: the expected extreme pounding force between two adjacent buildings
under random earthquakes, by closed form and by Monte Carlo time histories.

Reference: S. Rahimi and M. Soltani (2016), "Expected extreme value of
pounding force between two adjacent buildings", Structural Engineering and
Mechanics.

The public names are imported lazily, so that ``import pounding.cli.commands`` (and
``pounding cases``) stays light.
"""

from importlib import import_module

__version__ = "0.1.0"

_EXPORTS = {
    "Case": "case.case",
    "load_case": "case.case",
    "preset_names": "case.case",
    "Contact": "mechanics.contact",
    "ArgumentError": "errors",
    "CaseError": "errors",
    "InputError": "errors",
    "ConvergenceError": "errors",
    "SimulationError": "errors",
    "CloughPenzien": "hazard.excitation",
    "Excitation": "hazard.excitation",
    "KanaiTajimi": "hazard.excitation",
    "ShinozukaSato": "hazard.excitation",
    "Settings": "simulation.monte_carlo",
    "SimulationResult": "simulation.monte_carlo",
    "TimeHistory": "simulation.monte_carlo",
    "DesignGap": "simulation.monte_carlo",
    "design_gap": "simulation.monte_carlo",
    "integrate": "simulation.monte_carlo",
    "simulate": "simulation.monte_carlo",
    "simulate_record": "simulation.monte_carlo",
    "LinearizedPair": "closed_form.pair",
    "MonteCarloPlan": "simulation.plan",
    "estimate": "closed_form.estimator",
    "force_versus_gap": "closed_form.estimator",
    "BoucWen": "mechanics.structures",
    "Building": "mechanics.structures",
    "Storey": "mechanics.structures",
    "sweep": "studies.sweeps",
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
