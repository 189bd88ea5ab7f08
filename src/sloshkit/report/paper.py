"""The seed paper's printed reference values, in one place.

M. C. De Simone et al., *Multibody Analysis of Sloshing Effect in a Glass Cylinder Container
for Visual Inspection Activities*, Appl. Sci. 14 (2024) 4522, doi:10.3390/app14114522,
Tables 3 and 4; and its case as a scenario.
"""

from __future__ import annotations

from sloshkit.io.scenario import PAPER_SCENARIO, Scenario, parse_scenario

PAPER_TABLE3 = {
    "omega": 29.7,
    "stiffness": 11.3,
    "damping_coefficient": 0.023,
    "slosh_mass": 0.0132,
    "length": 0.011,
    "hinge": -0.0015,
    "damping_rate": 1.841,
}


PAPER_TABLE4 = {
    "cfd_omega": 28.56,
    "cfd_f": 4.55,
    "cfd_zeta": 0.03,
    "mb_omega": 29.7,
    "mb_f": 4.76,
    "mb_zeta": 0.03,
    "log_decrement": 0.163,
}


def paper_scenario() -> Scenario:
    """The seed paper's case as a `Scenario`.

    Returns
    -------
    Scenario
        The vial of De Simone et al. (2024), as ``sloshkit reproduce`` runs it.

    References
    ----------
    De Simone, M. C. et al., Appl. Sci. 14 (2024) 4522, doi:10.3390/app14114522.

    Examples
    --------
    >>> scenario = paper_scenario()
    >>> scenario.distance_m, round(scenario.model.modes[0].omega_rad_s, 1)
    (0.5, 29.7)
    """

    return parse_scenario(PAPER_SCENARIO, "built in: De Simone et al. (2024)")
