"""The ranges URScript's ``servoj`` accepts (Universal Robots, *The URScript Programming
Language*, e-Series SW 5.x, ``servoj``): the one source for the URScript writer
(`sloshkit.export.formats.urscript`) and the export settings (`sloshkit.export.settings`)."""

from __future__ import annotations

#: ``servoj``'s accepted ``lookahead_time`` [s].
LOOKAHEAD_TIME_RANGE_S = (0.03, 0.2)
#: ``servoj``'s accepted proportional ``gain`` [-].
GAIN_RANGE = (100.0, 2000.0)
