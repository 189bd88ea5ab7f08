"""Equivalent mechanical model of lateral sloshing in an upright circular cylinder: the mode and
model objects, `equivalent_model` and `model_family` (the formulas are in
`sloshkit.model.theory`).

Linear potential-flow theory of an inviscid, incompressible liquid with a free surface, in a
rigid upright cylinder of radius R filled to height h, replaced mode by mode by a pendulum (or
spring-mass) with the same frequency, mass and moment.

References
----------
- H. N. Abramson (ed.), *The Dynamic Behavior of Liquids in Moving Containers*, NASA SP-106
  (1966), ch. 2 and 6.
- F. T. Dodge, *The New "Dynamic Behavior of Liquids in Moving Containers"*, SwRI (2000), §3.
- R. A. Ibrahim, *Liquid Sloshing Dynamics*, Cambridge UP (2005), §2 and §6.
  doi:10.1017/CBO9780511536656
- M. C. De Simone et al., Appl. Sci. 14 (2024) 4522, eqs. 1, 2, 8, 9 and Table 3.
  doi:10.3390/app14114522

Conventions
-----------
Heights are measured upward from the inside of the container bottom [m]. The liquid's centre of
gravity is at h/2. Each mode's bob (slosh mass) hangs at ``bob_height_m``, its pivot is
``length_m`` above the bob. Angles are in radians, positive when the bob swings towards +x.
"""

from __future__ import annotations

from collections.abc import Callable

from sloshkit.errors import InputError, require_in_range, require_positive, warn_validity
from sloshkit.model.liquids import Liquid
from sloshkit.model.pendulums import SloshMode, SloshModel
from sloshkit.model.profile import Container, ProfileContainer
from sloshkit.model.profile_modal import profile_equivalent_model
from sloshkit.model.theory import (
    CAPILLARY_THRESHOLD,
    DAMPING_LAWS,
    GRAVITY_M_S2,
    MAX_MODES,
    DampingLaw,
    bessel_roots,
    bob_offset_from_cg,
    bond_number,
    checked_correlation_damping,
    damping_ratio_correlation,
    natural_frequency,
    pendulum_length,
    slosh_mass_ratio,
    surface_tension_factor,
    wall_elevation_factor,
    warn_capillary,
)


def equivalent_model(
    container: Container,
    liquid: Liquid,
    fill_height_m: float,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool | None = None,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> SloshModel:
    """Equivalent pendulum model of the first ``n_modes`` antisymmetric (lateral) modes.

    The correlation's first-mode damping ratio is used for every mode: the correlations exist for
    mode 1 only, and higher modes carry under 2 % of the slosh moment. Warns (`ValidityWarning`)
    for very shallow fills, capillary-dominated containers and damping so high that the
    boundary-layer correlations no longer hold.

    A `ProfileContainer` (any axisymmetric container, e.g. a catalogued vial) is modelled by
    finite elements instead (`sloshkit.model.profile_modal.profile_equivalent_model`); the
    upright cylinder keeps the closed form.

    Parameters
    ----------
    container : UprightCylinder or ProfileContainer
        The upright cylinder (radius, optional wall height) or an inner profile.
    liquid : Liquid
        Density, viscosity, surface tension.
    fill_height_m : float
        Static fill height h [m].
    n_modes : int
        Number of modes (1..50).
    damping_law : str
        First-mode correlation, see `sloshkit.model.modal.damping_ratio_correlation`.
    damping_ratio : float, optional
        If given, overrides the correlation (all modes) [-].
    surface_tension : bool, optional
        Apply the Bond-number frequency correction
        (`sloshkit.model.modal.surface_tension_factor`): True always, False never, None (the
        default) when it raises omega_1 by more than `CAPILLARY_THRESHOLD`, with a
        `ValidityWarning` that says so.
    gravity_m_s2 : float
        Gravitational acceleration g [m/s^2].

    Returns
    -------
    SloshModel
        The model, with the provenance of every value (``surface_tension_correction`` says
        whether the correction was applied).

    References
    ----------
    Abramson, H. N. (ed.), *The Dynamic Behavior of Liquids in Moving Containers*, NASA SP-106
    (1966), ch. 2 and 6; R. A. Ibrahim, *Liquid Sloshing Dynamics*, Cambridge University Press
    (2005), doi:10.1017/CBO9780511536656; M. C. De Simone et al., Appl. Sci. 14 (2024) 4522,
    eqs. 1, 2, 8, 9, doi:10.3390/app14114522.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> round(model.modes[0].frequency_hz, 3), round(model.modes[0].length_m * 1e3, 2)  # Hz, mm
    (4.72, 11.15)

    A 2 mL vial of radius 8 mm: surface tension raises f_1 by 17.9 %, so the correction is on.

    >>> import warnings
    >>> vial = sk.UprightCylinder(0.008)
    >>> with warnings.catch_warnings(record=True):
    ...     small = sk.equivalent_model(vial, sk.get_liquid("water-25C"),
    ...                                 vial.fill_height_for_volume(2e-6))
    >>> small.surface_tension_correction
    True
    """
    if isinstance(container, ProfileContainer):
        return profile_equivalent_model(
            container,
            liquid,
            fill_height_m,
            n_modes,
            damping_law=damping_law,
            damping_ratio=damping_ratio,
            surface_tension=surface_tension,
            gravity_m_s2=gravity_m_s2,
        )
    radius = container.radius_m
    height = container.check_fill_height(fill_height_m)
    gravity = require_positive("gravity", gravity_m_s2, "m/s^2")
    if damping_law not in DAMPING_LAWS:
        raise InputError("damping_law", damping_law, "must be one of " + ", ".join(DAMPING_LAWS))
    xi = bessel_roots(n_modes)
    provenance = {
        "omega": "theory: linear potential flow, Abramson (1966) eq. 2.14",
        "slosh_mass": "theory: Abramson (1966) §6.2 / Dodge (2000) §3",
    }

    omega = natural_frequency(radius, height, xi, gravity)
    bond = bond_number(liquid.density_kg_m3, radius, liquid.surface_tension_n_m, gravity)
    capillary = surface_tension_factor(xi[:1], bond)[0]
    raise_percent = 100 * (capillary - 1)
    matters = bool(capillary - 1.0 > CAPILLARY_THRESHOLD)
    applied = matters if surface_tension is None else bool(surface_tension)
    if applied:
        omega = omega * surface_tension_factor(xi, bond)
        provenance["omega"] += f" with capillary correction sqrt(1 + xi^2/Bo), Bo = {bond:.3g}"
        if surface_tension is None:
            provenance["omega"] += (
                f" (by default: it raises f_1 by more than {100 * CAPILLARY_THRESHOLD:g} %)"
            )
    warn_capillary(bond, raise_percent, matters, applied, surface_tension)
    if height / radius < 0.2:
        warn_validity(
            f"fill height / radius = {height / radius:.3g} < 0.2: shallow liquid sloshes "
            "nonlinearly (travelling waves, hydraulic jumps); linear theory is not trustworthy"
        )

    if damping_ratio is None:
        zeta = damping_ratio_correlation(
            radius, height, liquid.kinematic_viscosity_m2_s, damping_law, gravity
        )
        provenance["damping_ratio"] = f"correlation: {damping_law} (mode 1, used for all modes)"
        checked_correlation_damping(zeta, liquid.viscosity_pa_s)
    else:
        zeta = require_in_range("damping_ratio", damping_ratio, 0.0, 0.99)
        provenance["damping_ratio"] = "user"

    masses = (
        liquid.density_kg_m3
        * container.cross_section_m2
        * height
        * slosh_mass_ratio(radius, height, xi)
    )
    lengths = pendulum_length(radius, height, xi)
    bobs = height / 2.0 + bob_offset_from_cg(radius, height, xi)
    factors = wall_elevation_factor(radius, xi)
    modes = tuple(
        SloshMode(
            n=i + 1,
            bessel_root=float(xi[i]),
            omega_rad_s=float(omega[i]),
            slosh_mass_kg=float(masses[i]),
            length_m=float(lengths[i]),
            bob_height_m=float(bobs[i]),
            damping_ratio=float(zeta),
            wall_elevation_factor_m=float(factors[i]),
        )
        for i in range(len(xi))
    )
    return SloshModel(
        container=container,
        liquid=liquid,
        fill_height_m=height,
        modes=modes,
        gravity_m_s2=gravity,
        damping_law=damping_law if damping_ratio is None else "user",
        surface_tension_correction=applied,
        provenance=provenance,
    )


def model_family(
    container: Container,
    liquid: Liquid,
    *,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool | None = None,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> Callable[[float], SloshModel]:
    """The `equivalent_model` of one container and liquid as a function of the fill height.

    Parameters
    ----------
    container : UprightCylinder or ProfileContainer
        The container (a profile's fills are cached: each solved once).
    liquid : Liquid
        The liquid.
    n_modes : int
        Number of modes.
    damping_law : str
        Damping correlation (see `equivalent_model`).
    damping_ratio : float, optional
        Damping ratio overriding the correlation [-].
    surface_tension : bool, optional
        Apply the Bond-number frequency correction (None: where it matters, see
        `equivalent_model`).
    gravity_m_s2 : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    callable
        ``family(fill_height_m) -> SloshModel``, e.g. for `sloshkit.run_sweep`.

    Examples
    --------
    >>> import sloshkit as sk
    >>> family = model_family(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"))
    >>> family(0.039).fill_height_m
    0.039
    """

    def family(fill_height_m: float) -> SloshModel:
        return equivalent_model(
            container,
            liquid,
            fill_height_m,
            n_modes=n_modes,
            damping_law=damping_law,
            damping_ratio=damping_ratio,
            surface_tension=surface_tension,
            gravity_m_s2=gravity_m_s2,
        )

    return family


# The v1 names of this module (the formulas now live in sloshkit.model.theory, the objects in
# sloshkit.model.pendulums) stay importable from here.
__all__ = [
    "CAPILLARY_THRESHOLD",
    "DAMPING_LAWS",
    "GRAVITY_M_S2",
    "MAX_MODES",
    "DampingLaw",
    "SloshMode",
    "SloshModel",
    "bessel_roots",
    "bob_offset_from_cg",
    "bond_number",
    "damping_ratio_correlation",
    "equivalent_model",
    "model_family",
    "natural_frequency",
    "pendulum_length",
    "slosh_mass_ratio",
    "surface_tension_factor",
    "wall_elevation_factor",
]
