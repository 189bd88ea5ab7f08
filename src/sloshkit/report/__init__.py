"""The reproduction report: a scenario's analyses as report.html, figures and tables.

- `sloshkit.report.build`: `build_report` (staging, sections in order, atomic finish).
- `sloshkit.report.writer`: the writer (tables, figures, page) over jinja2 templates in
  ``templates/``.
- `sloshkit.report.model_sections`, `sloshkit.report.motion_sections`: the sections.
- `sloshkit.report.paper`: the seed paper's printed values and its scenario.
"""

from sloshkit.report.build import build_report
from sloshkit.report.paper import paper_scenario

__all__ = ["build_report", "paper_scenario"]
