"""The equivalent pendulum model of a liquid in an axisymmetric container given by its profile:
the finite-element modes of `sloshkit.model.axisymmetric` turned into a `SloshModel`, with the
damping correlation where one applies and a validity warning where none does.

`sloshkit.model.modal.equivalent_model` calls `profile_equivalent_model` for a
`ProfileContainer`; the upright cylinder keeps its closed form.
"""

from __future__ import annotations

import math

from sloshkit.errors import InputError, require_in_range, require_positive, warn_validity
from sloshkit.model.axisymmetric import axisymmetric_modes
from sloshkit.model.liquids import Liquid
from sloshkit.model.pendulums import SloshMode, SloshModel
from sloshkit.model.profile import ProfileContainer
from sloshkit.model.theory import (
    CAPILLARY_THRESHOLD,
    DAMPING_LAWS,
    GRAVITY_M_S2,
    DampingLaw,
    bessel_roots,
    bond_number,
    checked_correlation_damping,
    damping_ratio_correlation,
    surface_tension_factor,
    warn_capillary,
)

#: Largest relative difference between the liquid's volume and that of the cylinder of the free
#: surface's radius and the fill height for which the cylinder's damping correlations are used
#: without a warning (a heel or a slight taper; a cone, a sphere or a fill in the shoulder
#: exceed it).
CYLINDER_VOLUME_TOLERANCE = 0.05


def equivalent_depth(surface_radius_m: float, eigenvalue_1_m: float) -> float:
    """Depth of the cylinder of radius R_s whose first mode has the same lambda_1 = omega_1^2/g.

    h_eq = (R_s / xi_1) artanh(lambda_1 R_s / xi_1) (inverting Abramson (1966) eq. 2.14); a
    lambda_1 at or above the deep cylinder's xi_1 / R_s gives 100 R_s (deep).

    Parameters
    ----------
    surface_radius_m : float
        Radius of the free surface R_s [m].
    eigenvalue_1_m : float
        lambda_1 = omega_1^2 / g [1/m].

    Returns
    -------
    float
        h_eq [m].

    Examples
    --------
    >>> xi = float(bessel_roots(1)[0])
    >>> lam = xi / 0.01 * math.tanh(xi * 0.6)  # a cylinder R = 10 mm, h = 6 mm
    >>> round(equivalent_depth(0.01, lam) * 1e3, 9)
    6.0
    """
    xi = float(bessel_roots(1)[0])
    ratio = eigenvalue_1_m * surface_radius_m / xi
    if ratio >= 1.0 - 1e-12:
        return 100.0 * surface_radius_m
    return surface_radius_m / xi * math.atanh(ratio)


def profile_equivalent_model(
    container: ProfileContainer,
    liquid: Liquid,
    fill_height_m: float,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool | None = None,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> SloshModel:
    """Equivalent pendulum model of the liquid in an axisymmetric container (finite elements).

    Frequencies, slosh masses, pendulum lengths, bob heights and wall-elevation factors come from
    `sloshkit.model.axisymmetric.axisymmetric_modes`. The damping correlations exist for flat
    upright cylinders only: they are evaluated for the free surface's radius R_s and the
    equivalent depth (`equivalent_depth`), and a `ValidityWarning` says so when the liquid's
    volume differs from pi R_s^2 h by more than `CYLINDER_VOLUME_TOLERANCE`. The capillary
    correction uses the cylinder's xi_n at R_s (an approximation for a profile).

    Parameters
    ----------
    container : ProfileContainer
        The container's inner profile.
    liquid : Liquid
        The liquid.
    fill_height_m : float
        Static fill height above the inner bottom [m].
    n_modes : int
        Number of modes (1 .. `sloshkit.model.axisymmetric.MAX_PROFILE_MODES`).
    damping_law : str
        First-mode damping correlation.
    damping_ratio : float, optional
        Damping ratio for all modes, overriding the correlation.
    surface_tension : bool, optional
        Apply the Bond-number frequency correction: True always, False never, None (the
        default) when it raises omega_1 by more than
        `sloshkit.model.theory.CAPILLARY_THRESHOLD`, with a warning (as for the cylinder).
    gravity_m_s2 : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    SloshModel
        The model; each mode's ``bessel_root`` is the cylinder's xi_n of the same order (a label:
        the profile's modes are not Bessel functions).

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics* (2005) §2.2 and §6.2,
    doi:10.1017/CBO9780511536656; Dodge, F. T., *The New "Dynamic Behavior of Liquids in Moving
    Containers"*, SwRI (2000).

    Examples
    --------
    A flat-bottomed tube as a profile gives the cylinder's closed form (4.72 Hz, seed vial):

    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.profile import cylinder_profile
    >>> model = profile_equivalent_model(cylinder_profile(0.0205, 0.08), get_liquid("water-25C"),
    ...                                  0.039)
    >>> round(model.modes[0].frequency_hz, 3), round(model.modes[0].length_m * 1e3, 2)
    (4.72, 11.15)
    """
    height = container.check_fill_height(fill_height_m)
    gravity = require_positive("gravity", gravity_m_s2, "m/s^2")
    if damping_law not in DAMPING_LAWS:
        raise InputError("damping_law", damping_law, "must be one of " + ", ".join(DAMPING_LAWS))
    modes = axisymmetric_modes(container, height, n_modes)
    radius = modes.surface_radius_m
    xi = bessel_roots(len(modes.eigenvalues_1_m))
    provenance = {
        "omega": "finite elements: linear potential flow, m = 1 harmonic on the profile "
        "(sloshkit.model.axisymmetric, P2 isoparametric, "
        f"{modes.unknowns} unknowns)",
        "slosh_mass": "finite elements: modal force and moment (Ibrahim 2005 §6.2, Dodge 2000)",
        "container": f"{container.name} ({container.source})",
    }
    omega = [math.sqrt(gravity * value) for value in modes.eigenvalues_1_m]
    bond = bond_number(liquid.density_kg_m3, radius, liquid.surface_tension_n_m, gravity)
    capillary = float(surface_tension_factor(xi[:1], bond)[0])
    raise_percent = 100 * (capillary - 1)
    matters = bool(capillary - 1.0 > CAPILLARY_THRESHOLD)
    applied = matters if surface_tension is None else bool(surface_tension)
    if applied:
        factors = surface_tension_factor(xi, bond)
        omega = [w * float(f) for w, f in zip(omega, factors, strict=True)]
        provenance["omega"] += (
            f" with capillary correction sqrt(1 + xi^2/Bo) at the surface radius, Bo = {bond:.3g}"
        )
        if surface_tension is None:
            provenance["omega"] += (
                f" (by default: it raises f_1 by more than {100 * CAPILLARY_THRESHOLD:g} %)"
            )
    warn_capillary(bond, raise_percent, matters, applied, surface_tension)
    if height / radius < 0.2:
        warn_validity(
            f"fill height / surface radius = {height / radius:.3g} < 0.2: shallow liquid sloshes "
            "nonlinearly; linear theory is not trustworthy"
        )
    volume = container.volume_for_fill_height(height)
    cylinder_volume = math.pi * radius * radius * height
    depth = equivalent_depth(radius, modes.eigenvalues_1_m[0])
    if damping_ratio is None:
        zeta = damping_ratio_correlation(
            radius, depth, liquid.kinematic_viscosity_m2_s, damping_law, gravity
        )
        provenance["damping_ratio"] = (
            f"correlation: {damping_law} (mode 1, used for all modes) for the cylinder of the "
            f"surface radius {radius * 1e3:.4g} mm and the equivalent depth {depth * 1e3:.4g} mm"
        )
        deviation = abs(volume - cylinder_volume) / cylinder_volume
        if deviation > CYLINDER_VOLUME_TOLERANCE:
            warn_validity(
                f"no damping correlation for this profile: the liquid's volume differs by "
                f"{100 * deviation:.0f} % from the cylinder of its surface radius and fill height; "
                f"the {damping_law} correlation of that cylinder (equivalent depth "
                f"{depth * 1e3:.3g} mm) is an estimate only; calibrate from data"
            )
        checked_correlation_damping(zeta, liquid.viscosity_pa_s)
    else:
        zeta = require_in_range("damping_ratio", damping_ratio, 0.0, 0.99)
        provenance["damping_ratio"] = "user"
    slosh_modes = tuple(
        SloshMode(
            n=i + 1,
            bessel_root=float(xi[i]),
            omega_rad_s=float(omega[i]),
            slosh_mass_kg=float(liquid.density_kg_m3 * modes.mass_per_density_m3[i]),
            length_m=1.0 / modes.eigenvalues_1_m[i],
            bob_height_m=float(modes.bob_height_m[i]),
            damping_ratio=float(zeta),
            wall_elevation_factor_m=float(modes.wall_elevation_factor_m[i]),
        )
        for i in range(len(modes.eigenvalues_1_m))
    )
    return SloshModel(
        container=container,
        liquid=liquid,
        fill_height_m=height,
        modes=slosh_modes,
        gravity_m_s2=gravity,
        damping_law=damping_law if damping_ratio is None else "user",
        surface_tension_correction=applied,
        provenance=provenance,
    )
