"""The ``pounding`` command line: :mod:`.parser` (its options), :mod:`.commands` (what each command runs),
:mod:`.arguments` (argument types), the commands of their own modules (:mod:`.curves`, :mod:`.hazard`,
:mod:`.export`, :mod:`.sweep`), and the dashboard's server (:mod:`.serve`, :mod:`.dashboard_server`).
The command line is the only layer that names options (``--records``); the library names its arguments."""

from pounding.cli.commands import main

__all__ = ["main"]
