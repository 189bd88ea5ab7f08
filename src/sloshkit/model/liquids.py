"""Liquids and cited property presets.

Every preset names its source. Values are at the stated temperature and 1 atm.
"""

from __future__ import annotations

from dataclasses import dataclass

from sloshkit.errors import InputError, require_positive


@dataclass(frozen=True)
class Liquid:
    """Newtonian liquid.

    Parameters
    ----------
    name : str
        Short identifier, e.g. ``"water-25C"``.
    density_kg_m3 : float
        Density rho [kg/m^3].
    viscosity_pa_s : float
        Dynamic viscosity mu [Pa s].
    surface_tension_n_m : float
        Liquid-air surface tension sigma [N/m].
    source : str
        Where the values come from.

    Examples
    --------
    >>> from sloshkit import Liquid
    >>> glycerol_water = Liquid("glycerol-50", 1126.0, 6.0e-3, 0.070, source="user")
    >>> round(glycerol_water.kinematic_viscosity_m2_s * 1e6, 3)  # mm^2/s
    5.329
    """

    name: str
    density_kg_m3: float
    viscosity_pa_s: float
    surface_tension_n_m: float
    source: str = "user"

    def __post_init__(self) -> None:
        require_positive("density", self.density_kg_m3, "kg/m^3")
        require_positive("viscosity", self.viscosity_pa_s, "Pa s")
        require_positive("surface_tension", self.surface_tension_n_m, "N/m")

    @property
    def kinematic_viscosity_m2_s(self) -> float:
        """nu = mu / rho [m^2/s]."""
        return self.viscosity_pa_s / self.density_kg_m3


_IAPWS_SIGMA = "IAPWS R1-76(2014), surface tension of ordinary water substance"

LIQUIDS: dict[str, Liquid] = {
    liquid.name: liquid
    for liquid in (
        Liquid(
            "water-25C",
            997.0,
            8.899e-4,
            0.07197,
            "De Simone et al., Appl. Sci. 14 (2024) 4522, Table 1 (rho, mu); " + _IAPWS_SIGMA,
        ),
        Liquid(
            "water-20C",
            998.21,
            1.0016e-3,
            0.07274,
            "IAPWS-95 (rho); IAPWS R12-08 (mu); " + _IAPWS_SIGMA,
        ),
        Liquid(
            "ethanol-25C",
            785.1,
            1.074e-3,
            0.02197,
            "CRC Handbook of Chemistry and Physics, 97th ed. (rho, mu, sigma of ethanol)",
        ),
        Liquid(
            "glycerol-50wt-20C",
            1126.3,
            6.00e-3,
            0.0700,
            "Segur & Oberstar, Ind. Eng. Chem. 43 (1951) 2117 (rho, mu); sigma approximate, "
            "Takamura et al., J. Pet. Sci. Eng. 98 (2012) 50",
        ),
        Liquid(
            "glycerol-80wt-20C",
            1208.5,
            60.1e-3,
            0.0660,
            "Segur & Oberstar, Ind. Eng. Chem. 43 (1951) 2117 (rho, mu); sigma approximate, "
            "Takamura et al., J. Pet. Sci. Eng. 98 (2012) 50",
        ),
        Liquid(
            "saline-0.9-20C",
            1004.6,
            1.02e-3,
            0.0729,
            "0.9 % w/v NaCl: CRC Handbook, concentrative properties of aqueous NaCl "
            "(rho, mu); sigma from water + NaCl increment",
        ),
    )
}


def get_liquid(name: str) -> Liquid:
    """The preset `Liquid` called ``name``.

    Parameters
    ----------
    name : str
        A key of `LIQUIDS`, e.g. ``"water-25C"``.

    Returns
    -------
    Liquid
        The preset, with its source.

    Raises
    ------
    InputError
        For an unknown name (the message lists the known ones).

    Examples
    --------
    >>> from sloshkit import get_liquid
    >>> get_liquid("water-25C").density_kg_m3
    997.0
    """
    try:
        return LIQUIDS[name]
    except KeyError:
        raise InputError("liquid", name, "must be one of " + ", ".join(sorted(LIQUIDS))) from None
