"""The equivalent mechanical model: container geometry, liquids, sloshing modes and damping.

- `sloshkit.model.geometry`: `UprightCylinder`, fill height and volume.
- `sloshkit.model.liquids`: `Liquid` and cited presets.
- `sloshkit.model.modal`: modes of the upright cylinder, equivalent pendulums, damping
  correlations and surface mappings.
"""

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import LIQUIDS, Liquid, get_liquid
from sloshkit.model.modal import SloshMode, SloshModel, equivalent_model

__all__ = [
    "LIQUIDS",
    "Liquid",
    "SloshMode",
    "SloshModel",
    "UprightCylinder",
    "equivalent_model",
    "get_liquid",
]
