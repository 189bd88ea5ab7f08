"""Linear potential-flow theory of lateral sloshing in an upright circular cylinder, formula by
formula: Bessel roots, natural frequencies, slosh masses, pendulum lengths and heights, the wall
elevation per mode, the Bond-number correction and the damping correlations.

References
----------
- Abramson, H. N. (ed.), *The Dynamic Behavior of Liquids in Moving Containers*, NASA SP-106
  (1966), ch. 2 and 6.
- Dodge, F. T., *The New "Dynamic Behavior of Liquids in Moving Containers"*, SwRI (2000), §3.
- Ibrahim, R. A., *Liquid Sloshing Dynamics*, Cambridge UP (2005), §2 and §6,
  doi:10.1017/CBO9780511536656.
"""

from __future__ import annotations

import math
from typing import Literal, get_args

import numpy as np

from sloshkit.errors import InputError, require_in_range, warn_validity

#: Gravitational acceleration used by the seed paper and our defaults [m/s^2].
GRAVITY_M_S2 = 9.81


DampingLaw = Literal["seed", "sp106", "stephens"]


DAMPING_LAWS: tuple[str, ...] = get_args(DampingLaw)


MAX_MODES = 50


#: The capillary correction is applied by default when it raises omega_1 by more than this
#: fraction. Below it the correction is no larger than the gap between the uncorrected theory
#: and the references sloshkit has (the paper's CFD: 3.7 % below theory at Bo = 57, where the
#: correction is +2.9 %; the measured 49 mm glass cylinder: 0.6 % below at Bo = 323, correction
#: +0.5 %): neither supports raising the frequency there. Above it the correction dominates the
#: model's error (a 2 mL vial of radius 8 mm: +17.9 %, and the docs/how-do-i.md plan made
#: without it leaves 2.0-2.6 deg against its 0.25 deg residual limit). See docs/user-guide.md.
#: (Defined here so the profile models of `sloshkit.model.profile_modal` use the same one.)
CAPILLARY_THRESHOLD = 0.05


def bessel_roots(n_modes: int) -> np.ndarray:
    """First ``n_modes`` roots xi_n of J1'(x) = 0 (1.841184, 5.331443, 8.536316, ...) [-].

    The first ten are the tabulated constants (Abramowitz & Stegun, *Handbook of Mathematical
    Functions* (1964) Table 9.5, to 16 digits as `scipy.special.jnp_zeros` gives them, which the
    tests check): importing scipy.special would double the start-up of every command. More
    modes are computed with `scipy.special.jnp_zeros`. Source: Abramson (1966) eq. 2.13.

    Parameters
    ----------
    n_modes : int
        How many roots.

    Returns
    -------
    numpy.ndarray
        xi_1 ... xi_n.

    Examples
    --------
    >>> bessel_roots(3).round(6).tolist()
    [1.841184, 5.331443, 8.536316]
    """
    count = int(require_in_range("modes", n_modes, 1, MAX_MODES))
    if count <= len(_J1_PRIME_ZEROS):
        return np.array(_J1_PRIME_ZEROS[:count])
    from scipy.special import jnp_zeros

    return np.asarray(jnp_zeros(1, count), dtype=float)


#: Zeros of J1'(x) (Abramowitz & Stegun Table 9.5).
_J1_PRIME_ZEROS = (
    1.8411837813406595,
    5.3314427735250325,
    8.536316366346286,
    11.706004902592063,
    14.863588633909034,
    18.015527862681804,
    21.164369859188792,
    24.311326857210776,
    27.457050571059245,
    30.601922972669094,
)


def natural_frequency(
    radius_m: float,
    fill_height_m: float,
    xi: np.ndarray | float,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> np.ndarray:
    """Natural circular frequency omega_n = sqrt(g xi_n / R tanh(xi_n h / R)) [rad/s].

    Source: Abramson (1966) eq. 2.14; De Simone et al. (2024) eq. 1.

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius R and fill height h [m].
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).
    gravity_m_s2 : float
        Gravity [m/s^2].

    Returns
    -------
    numpy.ndarray
        omega_n [rad/s].

    Examples
    --------
    The seed paper's vial: 4.72 Hz for the first mode.

    >>> R, h = 0.0205, 0.039  # the seed paper's vial (De Simone et al. (2024) Table 3)
    >>> omega = natural_frequency(R, h, bessel_roots(2))
    >>> (omega / (2 * np.pi)).round(2).tolist()
    [4.72, 8.04]
    """
    xi = np.asarray(xi, dtype=float)
    return np.sqrt(gravity_m_s2 * xi / radius_m * np.tanh(xi * fill_height_m / radius_m))


def slosh_mass_ratio(radius_m: float, fill_height_m: float, xi: np.ndarray | float) -> np.ndarray:
    """Slosh mass over liquid mass, m_n / m_F = d tanh(2 xi_n h/d) / (xi_n (xi_n^2 - 1) h) [-].

    Source: Abramson (1966) §6.2; Dodge (2000) §3; De Simone et al. (2024) eq. 8 (d = 2R).

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius R and fill height h [m].
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).

    Returns
    -------
    numpy.ndarray
        m_n / m_F.

    Examples
    --------
    Most of the liquid that sloshes does so in the first mode:

    >>> R, h = 0.0205, 0.039  # the seed paper's vial (De Simone et al. (2024) Table 3)
    >>> slosh_mass_ratio(R, h, bessel_roots(2)).round(3).tolist()
    [0.238, 0.007]
    """
    xi = np.asarray(xi, dtype=float)
    d = 2.0 * radius_m
    return d * np.tanh(2.0 * xi * fill_height_m / d) / (xi * (xi**2 - 1.0) * fill_height_m)


def pendulum_length(radius_m: float, fill_height_m: float, xi: np.ndarray | float) -> np.ndarray:
    """Pendulum length L_n = d / (2 xi_n tanh(2 xi_n h / d)) = g / omega_n^2 [m].

    Source: Abramson (1966) §6.2; De Simone et al. (2024) eq. 9 (d = 2R).

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius R and fill height h [m].
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).

    Returns
    -------
    numpy.ndarray
        L_n [m].

    Examples
    --------
    L_1 = g / omega_1^2:

    >>> R, h = 0.0205, 0.039  # the seed paper's vial (De Simone et al. (2024) Table 3)
    >>> xi = bessel_roots(1)
    >>> length = float(pendulum_length(R, h, xi)[0])
    >>> omega = float(natural_frequency(R, h, xi)[0])
    >>> round(length * 1e3, 2), round(9.81 / omega**2 * 1e3, 2)
    (11.15, 11.15)
    """
    xi = np.asarray(xi, dtype=float)
    d = 2.0 * radius_m
    return d / (2.0 * xi * np.tanh(2.0 * xi * fill_height_m / d))


def bob_offset_from_cg(radius_m: float, fill_height_m: float, xi: np.ndarray | float) -> np.ndarray:
    """Height of the slosh mass above the liquid's centre of gravity (z up) [m].

    H_n = h/2 - (d/xi_n) tanh(xi_n h / d), the spring-mass location of Dodge (2000) §3. The seed
    paper's Table 3 prints this value (-0.0015 m) as its "pendulum hinge location"; the pivot is
    in fact L_n above the bob (Dodge (2000) §3: the hinge of the equivalent pendulum).

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius R and fill height h [m].
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).

    Returns
    -------
    numpy.ndarray
        H_n [m].

    Examples
    --------
    The seed paper's Table 3 value:

    >>> R, h = 0.0205, 0.039  # the seed paper's vial (De Simone et al. (2024) Table 3)
    >>> round(float(bob_offset_from_cg(R, h, bessel_roots(1))[0]), 4)
    -0.0015
    """
    xi = np.asarray(xi, dtype=float)
    d = 2.0 * radius_m
    return fill_height_m / 2.0 - (d / xi) * np.tanh(xi * fill_height_m / d)


def wall_elevation_factor(radius_m: float, xi: np.ndarray | float) -> np.ndarray:
    """Linear wall elevation per unit sin(angle), eta_n / sin(theta_n) = 2R / (xi_n^2 - 1) [m].

    Mapping between the pendulum angle and the free-surface elevation at the wall in the plane of
    motion, from matching the pendulum's moment to the linear mode shape J1(xi_n r/R) cos(phi)
    (Dodge 2000 §3; Ibrahim 2005 §6.2). Independent of h. The planar-surface mapping
    eta = R tan(theta) gives larger values for the same angle.

    Parameters
    ----------
    radius_m : float
        Container radius R [m].
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).

    Returns
    -------
    numpy.ndarray
        eta_n / sin(theta_n) [m].

    Examples
    --------
    >>> (wall_elevation_factor(0.0205, bessel_roots(2)) * 1e3).round(3).tolist()
    [17.155, 1.495]
    """
    xi = np.asarray(xi, dtype=float)
    return 2.0 * radius_m / (xi**2 - 1.0)


def bond_number(
    density_kg_m3: float,
    radius_m: float,
    surface_tension_n_m: float,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> float:
    """Bond number Bo = rho g R^2 / sigma [-] (gravity over capillary forces).

    Parameters
    ----------
    density_kg_m3 : float
        Liquid density [kg/m^3].
    radius_m : float
        Container radius [m].
    surface_tension_n_m : float
        Surface tension [N/m].
    gravity_m_s2 : float
        Gravity [m/s^2].

    Returns
    -------
    float

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics*, Cambridge (2005) §8.2,
    doi:10.1017/CBO9780511536656.

    Examples
    --------
    Water in the seed paper's vial: gravity dominates by far.

    >>> round(bond_number(997.0, 0.0205, 0.072))
    57
    """
    return density_kg_m3 * gravity_m_s2 * radius_m**2 / surface_tension_n_m


def surface_tension_factor(xi: np.ndarray | float, bond: float) -> np.ndarray:
    """Frequency factor omega_sigma / omega = sqrt(1 + xi_n^2 / Bo) [-].

    Capillary correction for a free contact line with a flat static meniscus; source:
    Abramson (1966) ch. 11; Ibrahim (2005) §8.2.

    Parameters
    ----------
    xi : numpy.ndarray or float
        Roots of J1' (`bessel_roots`).
    bond : float
        Bond number (`bond_number`).

    Returns
    -------
    numpy.ndarray
        omega_sigma / omega.

    Examples
    --------
    >>> surface_tension_factor(bessel_roots(2), 57.0).round(3).tolist()
    [1.029, 1.224]
    """
    xi = np.asarray(xi, dtype=float)
    return np.sqrt(1.0 + xi**2 / bond)


def damping_ratio_correlation(
    radius_m: float,
    fill_height_m: float,
    kinematic_viscosity_m2_s: float,
    law: DampingLaw = "seed",
    gravity_m_s2: float = GRAVITY_M_S2,
) -> float:
    """First-mode viscous damping ratio zeta_1 from an empirical correlation [-].

    All three use the inverse Galilei-type number Ga = nu / sqrt(g R^3):

    - ``"seed"``: zeta = (2.89/pi) sqrt(Ga) B, with
      B = 1 + 0.318/sinh(1.84 h/R) (1 + (1 - h/R)/cosh(1.84 h/R)); the seed paper's eq. 2 as
      given by Ibrahim (2005) §2.8.
    - ``"sp106"``: Mikishev & Dorozhkin (1961) in NASA SP-106 (1966) ch. 4: log decrement
      4.98 sqrt(Ga) B, i.e. zeta = (4.98/(2 pi)) sqrt(Ga) B.
    - ``"stephens"``: Stephens, Leonard & Perry, NASA TN D-1367 (1962), as quoted by Dodge
      (2000) §3.2: zeta = 0.83 sqrt(Ga) tanh(1.84 h/R) (1 + 2 (1 - h/R)/cosh(3.68 h/R)).

    These are fitted to tanks of decimetre size with clean walls; measured damping in small vials
    is often higher (contact-line and meniscus losses), so calibrate from data when you can.

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius R and fill height h [m].
    kinematic_viscosity_m2_s : float
        nu [m^2/s].
    law : str
        seed, sp106 or stephens.
    gravity_m_s2 : float
        Gravity [m/s^2].

    Returns
    -------
    float
        zeta_1.

    Examples
    --------
    Water (nu = 0.89e-6 m^2/s) in the seed paper's vial:

    >>> R, h = 0.0205, 0.039  # the seed paper's vial (De Simone et al. (2024) Table 3)
    >>> [round(damping_ratio_correlation(R, h, 0.89e-6, law), 4)
    ...  for law in ("seed", "sp106", "stephens")]
    [0.0092, 0.0079, 0.0081]
    """
    if law not in DAMPING_LAWS:
        raise InputError("damping_law", law, "must be one of " + ", ".join(DAMPING_LAWS))
    ga = kinematic_viscosity_m2_s / math.sqrt(gravity_m_s2 * radius_m**3)
    ratio = fill_height_m / radius_m
    if law == "stephens":
        return (
            0.83
            * math.sqrt(ga)
            * math.tanh(1.84 * ratio)
            * (1.0 + 2.0 * (1.0 - ratio) / math.cosh(3.68 * ratio))
        )
    bracket = 1.0 + 0.318 / math.sinh(1.84 * ratio) * (
        1.0 + (1.0 - ratio) / math.cosh(1.84 * ratio)
    )
    prefactor = 2.89 / math.pi if law == "seed" else 4.98 / (2.0 * math.pi)
    return prefactor * math.sqrt(ga) * bracket


def checked_correlation_damping(zeta: float, viscosity_pa_s: float) -> float:
    """A damping ratio from `damping_ratio_correlation`, checked the same way for every model.

    The correlations assume thin viscous boundary layers (Case & Parkinson, J. Fluid Mech. 2
    (1957) 172-184; Ibrahim (2005) §2.8), which holds for zeta well below 0.1: above it the
    correlation is extrapolated (a validity warning), and from 0.99 the liquid does not
    oscillate at all, an input error naming the viscosity.

    Parameters
    ----------
    zeta : float
        The correlation's first-mode damping ratio [-].
    viscosity_pa_s : float
        The liquid's dynamic viscosity [Pa s], for the error message.

    Returns
    -------
    float
        ``zeta``.

    Raises
    ------
    InputError
        When ``zeta`` >= 0.99 (overdamped).

    Examples
    --------
    >>> checked_correlation_damping(0.0092, 1.0e-3)
    0.0092
    >>> try:
    ...     checked_correlation_damping(1.2, 50.0)
    ... except InputError as error:
    ...     print(str(error).split(":")[0])
    viscosity = '50 Pa s' is invalid
    """
    if not zeta < 0.99:
        raise InputError(
            "viscosity",
            f"{viscosity_pa_s:.6g} Pa s",
            f"gives a correlation damping ratio {zeta:.3g} >= 0.99: the liquid does not "
            "oscillate (overdamped)",
            "give --damping-ratio from a measurement",
        )
    if zeta > 0.1:
        warn_validity(
            f"correlation damping ratio {zeta:.3g} > 0.1: viscous boundary layers are no "
            "longer thin, the correlation is extrapolated; calibrate from data"
        )
    return zeta


def warn_capillary(
    bond: float, raise_percent: float, matters: bool, applied: bool, surface_tension: bool | None
) -> None:
    """The validity warnings of the capillary (Bond-number) correction, for every model.

    Parameters
    ----------
    bond : float
        Bond number of the free surface.
    raise_percent : float
        How much the correction raises f_1 [%].
    matters : bool
        The raise is above `CAPILLARY_THRESHOLD`.
    applied : bool
        The correction is applied.
    surface_tension : bool or None
        The caller's choice (None: the default rule).

    Returns
    -------
    None

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_capillary(57.1, 2.9, False, False, None)
    >>> caught
    []
    """
    if bond < 5.0:
        warn_validity(
            f"Bond number {bond:.3g} < 5: surface tension dominates the free surface "
            "(meniscus, contact line); the potential-flow model is not trustworthy here"
        )
    if matters and surface_tension is None:
        warn_validity(
            f"Bond number {bond:.3g}: surface tension raises f_1 by {raise_percent:.1f} % (more "
            f"than {100 * CAPILLARY_THRESHOLD:g} %), so the capillary correction is applied; "
            "--no-surface-tension-correction (surface_tension=False) turns it off"
        )
    elif matters and not applied:
        warn_validity(
            f"Bond number {bond:.3g}: surface tension raises f_1 by {raise_percent:.1f} %; the "
            "capillary correction is off (--no-surface-tension-correction): the frequencies "
            "are too low"
        )
