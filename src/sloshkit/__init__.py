"""sloshkit: sloshing of liquids in moving containers.

Model (`equivalent_model`), simulate, plan and calibrate the slosh of a liquid in an upright
cylinder moved by a robot or a slide. SI units throughout the Python API.
"""

from sloshkit.errors import InputError, ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import LIQUIDS, Liquid, get_liquid
from sloshkit.model.modal import SloshMode, SloshModel, equivalent_model

__version__ = "0.1.0"

__all__ = [
    "LIQUIDS",
    "InputError",
    "Liquid",
    "SloshMode",
    "SloshModel",
    "UprightCylinder",
    "ValidityWarning",
    "__version__",
    "equivalent_model",
    "get_liquid",
]
