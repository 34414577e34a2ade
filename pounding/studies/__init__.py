"""Studies made of many estimates and simulations: fragility curves, the force spectrum, parametric sweeps on
Dask, and the paper's tables against this project's two methods.

Modules: :mod:`.fragility`, :mod:`.force_spectrum`, :mod:`.monte_carlo_study` (their Monte Carlo side),
:mod:`.sweeps` (resumable parametric studies), :mod:`.paper_tables` (``pounding validate``).
"""
