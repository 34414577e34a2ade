"""The report's style, on screen and on an A4 page: one column as wide as
A4's printable width, so that a figure drawn on screen prints unscaled and
unclipped, and no figure, table row or caption split across pages."""

from __future__ import annotations

__all__ = ["FIGURE_WIDTH", "PAGE_MARGIN_MM", "PRINTABLE_WIDTH_PX", "REPORT_CSS"]

PAGE_MARGIN_MM = 15
"""Margin of the printed A4 page on every side [mm]."""
PRINTABLE_WIDTH_PX = (210 - 2 * PAGE_MARGIN_MM) / 25.4 * 96
"""Width of A4 inside the margins [CSS px] (96 px to the inch): 680 px."""
FIGURE_WIDTH = 660
"""Width of a figure [CSS px]: inside the printable width, so printing neither scales nor clips it."""

REPORT_CSS = f"""
@page {{ size: A4; margin: {PAGE_MARGIN_MM}mm; }}
html {{ background: #fff; }}
body {{ font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; font-size: 13px; line-height: 1.4; color: #111;
        margin: 0; }}
main.report {{ box-sizing: border-box; width: {PRINTABLE_WIDTH_PX:.0f}px; max-width: 100%; margin: 0 auto; padding: 16px 0; }}
h1 {{ font-size: 20px; margin: 0 0 4px 0; }}
h2 {{ font-size: 16px; margin: 18px 0 6px 0; border-bottom: 1px solid #bbb; break-after: avoid; }}
h3 {{ font-size: 14px; margin: 12px 0 4px 0; break-after: avoid; }}
p {{ margin: 4px 0; }}
.made {{ color: #444; font-size: 12px; }}
.made code, td code {{ font-size: 11px; word-break: break-all; }}
table {{ border-collapse: collapse; width: 100%; margin: 4px 0 8px 0; }}
th, td {{ text-align: left; vertical-align: top; padding: 2px 6px; border-bottom: 1px solid #ddd; }}
thead th {{ border-bottom: 1px solid #888; }}
td.number {{ white-space: nowrap; font-variant-numeric: tabular-nums; }}
td.value {{ font-variant-numeric: tabular-nums; }}
tr {{ break-inside: avoid; }}
tr.group th {{ background: #f0f0f0; }}
table.summary td.number {{ font-weight: bold; }}
.verdict-within {{ color: #145a14; }}
.verdict-outside {{ color: #8a4b00; }}
.warning {{ color: #8a4b00; }}
figure.report-figure {{ margin: 10px 0 14px 0; break-inside: avoid; page-break-inside: avoid; width: {FIGURE_WIDTH}px;
                        max-width: 100%; }}
figure.report-figure .plots {{ display: flex; gap: 10px; }}
figure.report-figure figcaption {{ font-size: 12px; color: #222; margin-top: 4px; }}
figure.report-figure .figure-label {{ font-weight: bold; color: inherit; text-decoration: none; }}
.nojs {{ border: 1px dashed #aaa; padding: 6px; color: #555; font-size: 12px; }}
.pounding-result table {{ width: auto; }}
@media print {{
  main.report {{ width: 100%; padding: 0; }}
  a {{ color: inherit; text-decoration: none; }}
  section.figures {{ break-before: page; }}
  section.method {{ break-before: page; }}
}}
"""
