"""Bokeh plots in a self-contained HTML file: the script that draws them, their divs, and only the parts of
Bokeh's library they use, inline; never a ``<script src>`` or stylesheet link (a file opened offline cannot
load one). Bokeh is imported when called."""

from __future__ import annotations

import re

__all__ = ["embedded", "without_external"]

_EXTERNAL = re.compile(
    r'<script[^>]*\bsrc="(?!data:)[^"]*"[^>]*>\s*</script>\s*|<link[^>]*\brel="stylesheet"[^>]*\bhref="(?!data:)[^"]*"[^>]*>\s*'
)


def without_external(text: str) -> str:
    """``text`` without ``<script src=...>`` and stylesheet ``<link>`` tags: with Panel imported (as in the
    dashboard's server, or after the dashboard in one process), Bokeh's bundle still names server-relative files
    of Panel's (an ES-module shim, Tabulator's CSS), unused by these plots, that a file cannot load."""
    return _EXTERNAL.sub("", text)


def embedded(models: list) -> tuple[str, tuple[str, ...], str]:
    """The drawing ``<script>``, one ``<div>`` per model, and the inline Bokeh library they need."""
    if not models:
        return "", (), ""
    from bokeh.embed import components
    from bokeh.embed.bundle import bundle_for_objs_and_resources
    from bokeh.resources import INLINE

    for model in models:  # the tools show on hover only: a printed page carries no toolbar over its plots
        toolbar = getattr(model, "toolbar", None)
        if toolbar is not None and hasattr(toolbar, "autohide"):
            toolbar.autohide = True
    script, divs = components(models)
    return script, tuple(divs), without_external(bundle_for_objs_and_resources(models, INLINE).scripts())
