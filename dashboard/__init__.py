"""The pounding dashboard (Panel): :class:`PoundingDashboard`, a ``pn.viewable.Viewer``.

In a notebook::

    import panel as pn
    from dashboard import PoundingDashboard
    pn.extension()
    PoundingDashboard()

Served: ``pounding dashboard`` (or ``panel serve dashboard/app.py``). Importing this package serves nothing and
changes no global state of the caller (thread limits, theme).
"""

from dashboard.model import PoundingModel
from dashboard.view import PoundingDashboard

__all__ = ["PoundingDashboard", "PoundingModel"]
