"""The mechanics of two buildings that pound: Bouc-Wen storeys and shear buildings (Eq. 1-2, 31-32, 36-39), the
contact laws (Eq. 3-6) and the compiled integrator that every time history runs on.

Modules: :mod:`.structures` (``BoucWen``, ``Storey``, ``Building``), :mod:`.contact` (``Contact`` and the
registry of contact laws), :mod:`.integrator` (every compiled function of the mechanics).
"""
