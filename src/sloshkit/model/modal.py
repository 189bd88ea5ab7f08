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

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

from sloshkit.errors import InputError, require_in_range, require_positive, warn_validity
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid
from sloshkit.model.theory import (  # re-exported: the v1 names of sloshkit.model.modal
    DAMPING_LAWS as DAMPING_LAWS,
)
from sloshkit.model.theory import (
    GRAVITY_M_S2 as GRAVITY_M_S2,
)
from sloshkit.model.theory import (
    MAX_MODES as MAX_MODES,
)
from sloshkit.model.theory import (
    DampingLaw as DampingLaw,
)
from sloshkit.model.theory import (
    bessel_roots as bessel_roots,
)
from sloshkit.model.theory import (
    bob_offset_from_cg as bob_offset_from_cg,
)
from sloshkit.model.theory import (
    bond_number as bond_number,
)
from sloshkit.model.theory import (
    damping_ratio_correlation as damping_ratio_correlation,
)
from sloshkit.model.theory import (
    natural_frequency as natural_frequency,
)
from sloshkit.model.theory import (
    pendulum_length as pendulum_length,
)
from sloshkit.model.theory import (
    slosh_mass_ratio as slosh_mass_ratio,
)
from sloshkit.model.theory import (
    surface_tension_factor as surface_tension_factor,
)
from sloshkit.model.theory import (
    wall_elevation_factor as wall_elevation_factor,
)


@dataclass(frozen=True)
class SloshMode:
    """One sloshing mode of the equivalent pendulum model (SI units).

    Heights are measured from the container bottom. ``length_m`` is the geometric pendulum length;
    with a surface-tension or calibrated frequency, omega_n^2 differs from g / L_n and the pendulum
    equation uses omega_n (an effective gravity) while the forcing keeps 1/L_n.

    Parameters
    ----------
    n : int
        Mode number (1 = fundamental lateral mode).
    bessel_root : float
        xi_n, the n-th root of J_1'(xi) = 0.
    omega_rad_s : float
        Natural circular frequency omega_n [rad/s].
    slosh_mass_kg : float
        Sloshing (pendulum) mass m_n [kg].
    length_m : float
        Pendulum length L_n [m].
    bob_height_m : float
        Height of the bob above the bottom [m].
    damping_ratio : float
        Damping ratio zeta_n [-].
    wall_elevation_factor_m : float
        Wall elevation per radian of pendulum angle, 2R/(xi_n^2 - 1) [m/rad].

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics*, Cambridge University Press (2005),
        doi:10.1017/CBO9780511536656.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> mode = model.modes[0]
    >>> mode.n, round(mode.frequency_hz, 3)
    (1, 4.72)
    """

    n: int
    bessel_root: float
    omega_rad_s: float
    slosh_mass_kg: float
    length_m: float
    bob_height_m: float
    damping_ratio: float
    wall_elevation_factor_m: float

    @property
    def frequency_hz(self) -> float:
        """Natural frequency f_n = omega_n / (2 pi) [Hz]."""
        return self.omega_rad_s / (2.0 * math.pi)

    @property
    def damped_omega_rad_s(self) -> float:
        """Damped circular frequency omega_n sqrt(1 - zeta^2) [rad/s]."""
        return self.omega_rad_s * math.sqrt(max(0.0, 1.0 - self.damping_ratio**2))

    @property
    def pivot_height_m(self) -> float:
        """Pivot (hinge) height above the container bottom: bob height + L_n [m]."""
        return self.bob_height_m + self.length_m

    @property
    def stiffness_n_m(self) -> float:
        """Spring-mass equivalent stiffness k_n = m_n omega_n^2 [N/m]."""
        return self.slosh_mass_kg * self.omega_rad_s**2

    @property
    def damping_coefficient_n_s_m(self) -> float:
        """Spring-mass equivalent damper c_n = 2 zeta_n m_n omega_n [N s/m] (paper's sigma)."""
        return 2.0 * self.damping_ratio * self.slosh_mass_kg * self.omega_rad_s


@dataclass(frozen=True)
class SloshModel:
    """Equivalent mechanical model of a filled upright cylinder: rigid mass plus pendulums.

    Build it with `equivalent_model`; `with_mode` returns a calibrated copy. ``provenance`` says
    where each value came from (theory, correlation, calibration).

    Parameters
    ----------
    container : UprightCylinder
        The container.
    liquid : Liquid
        The liquid.
    fill_height_m : float
        Static fill height h [m].
    modes : tuple of SloshMode
        The modelled modes, fundamental first.
    gravity_m_s2 : float
        Gravitational acceleration g [m/s^2].
    damping_law : str
        Name of the damping correlation used.
    surface_tension_correction : bool
        Whether the Bond-number frequency correction was applied.
    provenance : mapping of str to str
        Where each value came from.

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics*, Cambridge University Press (2005),
        doi:10.1017/CBO9780511536656.

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"),
    ...                             fill_height_m=0.039)
    >>> len(model.modes), round(model.liquid_mass_kg * 1e3, 1)  # g
    (3, 51.3)
    """

    container: UprightCylinder
    liquid: Liquid
    fill_height_m: float
    modes: tuple[SloshMode, ...]
    gravity_m_s2: float = GRAVITY_M_S2
    damping_law: str = "seed"
    surface_tension_correction: bool = False
    provenance: Mapping[str, str] = field(default_factory=dict)

    @property
    def radius_m(self) -> float:
        """Inner radius R [m]."""
        return self.container.radius_m

    @property
    def liquid_mass_kg(self) -> float:
        """Liquid mass m_F = rho pi R^2 h [kg]."""
        return self.liquid.density_kg_m3 * self.container.cross_section_m2 * self.fill_height_m

    @property
    def rigid_mass_kg(self) -> float:
        """Non-sloshing mass m_0 = m_F - sum(m_n) over the modelled modes [kg]."""
        return self.liquid_mass_kg - sum(mode.slosh_mass_kg for mode in self.modes)

    @property
    def cg_height_m(self) -> float:
        """Height of the static liquid's centre of gravity above the bottom, h/2 [m]."""
        return self.fill_height_m / 2.0

    @property
    def bond_number(self) -> float:
        """Bond number rho g R^2 / sigma [-]."""
        return bond_number(
            self.liquid.density_kg_m3,
            self.radius_m,
            self.liquid.surface_tension_n_m,
            self.gravity_m_s2,
        )

    def with_mode(
        self,
        n: int = 1,
        *,
        omega_rad_s: float | None = None,
        damping_ratio: float | None = None,
        source: str = "user",
    ) -> SloshModel:
        """Copy with mode ``n``'s frequency and/or damping replaced (e.g. calibrated values)."""
        index = int(require_in_range("mode", n, 1, len(self.modes))) - 1
        mode = self.modes[index]
        provenance = dict(self.provenance)
        if omega_rad_s is not None:
            mode = replace(mode, omega_rad_s=require_positive("omega", omega_rad_s, "rad/s"))
            provenance[f"omega_{n}"] = source
        if damping_ratio is not None:
            mode = replace(
                mode, damping_ratio=require_in_range("damping_ratio", damping_ratio, 0.0, 0.99)
            )
            provenance[f"damping_ratio_{n}"] = source
        modes = (*self.modes[:index], mode, *self.modes[index + 1 :])
        return replace(self, modes=modes, provenance=provenance)

    def to_dict(self) -> dict[str, object]:
        """JSON-ready summary in SI with unit-suffixed keys (the ``model --json`` format)."""
        return {
            "radius_m": self.radius_m,
            "wall_height_m": self.container.wall_height_m,
            "fill_height_m": self.fill_height_m,
            "liquid": self.liquid.name,
            "density_kg_m3": self.liquid.density_kg_m3,
            "viscosity_pa_s": self.liquid.viscosity_pa_s,
            "surface_tension_n_m": self.liquid.surface_tension_n_m,
            "gravity_m_s2": self.gravity_m_s2,
            "bond_number": self.bond_number,
            "damping_law": self.damping_law,
            "surface_tension_correction": self.surface_tension_correction,
            "liquid_mass_kg": self.liquid_mass_kg,
            "rigid_mass_kg": self.rigid_mass_kg,
            "cg_height_m": self.cg_height_m,
            "modes": [
                {
                    "n": mode.n,
                    "bessel_root": mode.bessel_root,
                    "omega_rad_s": mode.omega_rad_s,
                    "frequency_hz": mode.frequency_hz,
                    "slosh_mass_kg": mode.slosh_mass_kg,
                    "length_m": mode.length_m,
                    "pivot_height_m": mode.pivot_height_m,
                    "bob_height_m": mode.bob_height_m,
                    "bob_offset_from_cg_m": mode.bob_height_m - self.cg_height_m,
                    "stiffness_n_m": mode.stiffness_n_m,
                    "damping_ratio": mode.damping_ratio,
                    "damping_coefficient_n_s_m": mode.damping_coefficient_n_s_m,
                    "wall_elevation_factor_m": mode.wall_elevation_factor_m,
                }
                for mode in self.modes
            ],
            "provenance": dict(self.provenance),
        }


def equivalent_model(
    container: UprightCylinder,
    liquid: Liquid,
    fill_height_m: float,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool = False,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> SloshModel:
    """Equivalent pendulum model of the first ``n_modes`` antisymmetric (lateral) modes.

    The correlation's first-mode damping ratio is used for every mode: the correlations exist for
    mode 1 only, and higher modes carry under 2 % of the slosh moment. Warns (`ValidityWarning`)
    for very shallow fills, capillary-dominated containers and damping so high that the
    boundary-layer correlations no longer hold.

    Parameters
    ----------
    container : UprightCylinder
        The upright cylinder (radius, optional wall height).
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
    surface_tension : bool
        Apply the Bond-number frequency correction
        (`sloshkit.model.modal.surface_tension_factor`).
    gravity_m_s2 : float
        Gravitational acceleration g [m/s^2].

    Returns
    -------
    SloshModel
        The model, with the provenance of every value.

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
    """
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
    if surface_tension:
        omega = omega * surface_tension_factor(xi, bond)
        provenance["omega"] += f" with capillary correction sqrt(1 + xi^2/Bo), Bo = {bond:.3g}"
    if bond < 5.0:
        warn_validity(
            f"Bond number {bond:.3g} < 5: surface tension dominates the free surface "
            "(meniscus, contact line); the potential-flow model is not trustworthy here"
        )
    elif not surface_tension and capillary > 1.05:
        warn_validity(
            f"Bond number {bond:.3g}: surface tension raises f_1 by {100 * (capillary - 1):.1f} %; "
            "consider the surface-tension correction"
        )
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
        if zeta > 0.1:
            warn_validity(
                f"correlation damping ratio {zeta:.3g} > 0.1: viscous boundary layers are no "
                "longer thin, the correlation is extrapolated; calibrate from data"
            )
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
        surface_tension_correction=surface_tension,
        provenance=provenance,
    )


def model_family(
    container: UprightCylinder,
    liquid: Liquid,
    *,
    n_modes: int = 3,
    damping_law: DampingLaw = "seed",
    damping_ratio: float | None = None,
    surface_tension: bool = False,
    gravity_m_s2: float = GRAVITY_M_S2,
) -> Callable[[float], SloshModel]:
    """The `equivalent_model` of one container and liquid as a function of the fill height.

    Parameters
    ----------
    container : UprightCylinder
        The container.
    liquid : Liquid
        The liquid.
    n_modes : int
        Number of modes.
    damping_law : str
        Damping correlation (see `equivalent_model`).
    damping_ratio : float, optional
        Damping ratio overriding the correlation [-].
    surface_tension : bool
        Apply the Bond-number frequency correction.
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
