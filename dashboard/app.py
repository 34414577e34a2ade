"""The served dashboard: ``pounding dashboard`` (or ``panel serve dashboard/app.py``) runs this script once per
browser session. It sets up the server process (the Panel extension, one BLAS thread, no web font) and serves a
:class:`~dashboard.PoundingDashboard` in its template; none of this happens on ``import dashboard``."""

from __future__ import annotations

import sys
from pathlib import Path

if __package__ in (None, ""):  # `panel serve dashboard/app.py` from a source tree: the package beside it
    root = str(Path(__file__).resolve().parent.parent)
    if root not in sys.path:
        sys.path.insert(0, root)

import panel as pn  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from dashboard.view import PoundingDashboard  # noqa: E402

pn.extension(notifications=False)

# One BLAS thread in the server process: its matrices have a few dozen rows, and an idle OpenBLAS worker spins
# after every call (measured on 2 cores: 110 ms of CPU per change of input, more than the rest of the work).
threadpool_limits(limits=1, user_api="blas")

# Panel's Fast design links its web font (Open Sans) from Google: the page must load with no network.
pn.theme.Fast._resources = {**pn.theme.Fast._resources, "font": {}}

# `panel serve dashboard/app.py --args --compute inline` computes on the session's event loop instead of the shared
# thread pool: only benchmarks/dashboard_latency.py asks for it, to measure the choice.
inline = sys.argv[1:3] == ["--compute", "inline"]
dashboard = PoundingDashboard(compute_inline=inline)
page = dashboard.template()
page.model = dashboard.model  # for tests and benchmarks
page.servable()
