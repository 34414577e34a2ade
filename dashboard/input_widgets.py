"""The widget of one of the dashboard's inputs: :class:`InputField`.

A choice (a selector, a switch) is linked to its parameter both ways. A number is not: what is typed goes to
``PoundingModel.offer``, which takes it or refuses it; a refused value stays in the box, shown red with the reason
under it (in the input's units), and the parameter, and so the results, keep the last value taken. A value the
model sets (a preset, a unit switch) replaces what is in the box.
"""

from __future__ import annotations

import html

import panel as pn
import param

__all__ = ["REFUSED_CSS", "InputField"]

REFUSED_CSS = """
:host(.refused) input { border: 2px solid #c62828 !important; background: #fff1f1 !important; }
"""
"""Inside a number's shadow root: the box of a refused value."""

_FORMATS = {"G0": "0,0.[000]", "contact_stiffness": "0,0.[000]", "capacity": "0,0.[00]", "mass": "0,0.[000]", "stiffness": "0,0.[00]",
            "target_probability": "0.[0000]", "pga": "0.[000]", "gap": "0,0.[000]"}


class InputField:
    """The widget of input ``name`` of ``owner`` (the model, or one of its buildings), and ``panel``: the widget
    with, for a number, the reason it was refused under it."""

    def __init__(self, model, owner: param.Parameterized, name: str, key: str, **options):
        self.owner, self.name, self.key = owner, name, key
        parameter = owner.param[name]
        self.number = isinstance(parameter, param.Number) and not isinstance(parameter, param.Boolean)
        options.setdefault("sizing_mode", "stretch_width")
        if isinstance(parameter, param.Boolean):
            kind = pn.widgets.Switch
        elif isinstance(parameter, param.Selector):
            kind = pn.widgets.Select  # labelled, unlike a group of toggles
        elif isinstance(parameter, param.Integer):
            kind = pn.widgets.IntInput
        else:
            kind = pn.widgets.FloatInput
            options.setdefault("format", _FORMATS.get(name, "0.[0000]"))
        if "description" in kind.param:
            options.setdefault("description", parameter.doc)
        if not self.number:
            self.widget = kind.from_param(parameter, **options)
            self.panel = self.widget
            self.reason = None
            return
        # not from_param: the box takes any number, and the model says whether it is taken
        self.widget = kind(name=parameter.label or name, value=getattr(owner, name), stylesheets=[REFUSED_CSS], **options)
        self.reason = pn.pane.HTML("", visible=False, css_classes=["input-refused"], margin=(0, 10, 6, 10),
                                   styles={"color": "#c62828", "font-size": "12px"}, sizing_mode="stretch_width")
        self.panel = pn.Column(self.widget, self.reason, sizing_mode="stretch_width", margin=0)
        self.widget.param.watch(lambda event: model.offer(owner, name, event.new), "value")
        owner.param.watch(self._taken, name)

    def _taken(self, event) -> None:
        """The model set the input (a value taken, a preset, a unit switch): the box shows it."""
        self.widget.value = event.new

    def show_refusal(self, refused: dict) -> None:
        """Show the input red with its reason if ``refused`` (the model's :attr:`refused`) holds it; plain if not."""
        if self.reason is None:
            return
        reason = refused.get(self.key, "")
        taken = getattr(self.owner, self.name)
        if not reason and self.widget.value != taken:  # a refusal dropped (a preset, a unit switch): the box shows the value taken
            self.widget.value = taken
        self.widget.css_classes = ["refused"] if reason else []
        self.reason.object = html.escape(reason)
        self.reason.visible = bool(reason)

    @property
    def visible(self) -> bool:
        return self.panel.visible

    @visible.setter
    def visible(self, shown: bool) -> None:
        self.panel.visible = shown
