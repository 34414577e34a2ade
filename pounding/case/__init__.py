"""A case: the excitation, two buildings and the contact between them, read from a TOML file or a preset, units
converted once at load; and the same case in an engineer's terms or moved along one engineering axis.

Modules: :mod:`.case` (``Case``, ``load_case``), :mod:`.fields` (each number of a case file checked as written),
:mod:`.excitation` (the ``[excitation]`` table in its three forms), :mod:`.scaling` (a case at another PGA or
other periods), :mod:`.engineering` (yield drifts, PGA and periods of a case).
"""
