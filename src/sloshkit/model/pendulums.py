"""The equivalent pendulum model's objects: one `SloshMode` per sloshing mode and the
`SloshModel` of a filled container (built by `sloshkit.model.modal.equivalent_model`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

from sloshkit.errors import require_in_range, require_positive
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import Liquid
from sloshkit.model.profile import ProfileContainer
from sloshkit.model.theory import GRAVITY_M_S2, bond_number


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
    container : UprightCylinder or ProfileContainer
        The container (a profile's model comes from finite elements,
        `sloshkit.model.profile_modal`).
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

    container: UprightCylinder | ProfileContainer
    liquid: Liquid
    fill_height_m: float
    modes: tuple[SloshMode, ...]
    gravity_m_s2: float = GRAVITY_M_S2
    damping_law: str = "seed"
    surface_tension_correction: bool = False
    provenance: Mapping[str, str] = field(default_factory=dict)

    @property
    def radius_m(self) -> float:
        """Inner radius R [m]; for a profile, the free surface's radius r(h)."""
        if isinstance(self.container, ProfileContainer):
            return self.container.radius_at(self.fill_height_m)
        return self.container.radius_m

    @property
    def liquid_mass_kg(self) -> float:
        """Liquid mass m_F = rho pi R^2 h (rho V(h) through a profile) [kg]."""
        if isinstance(self.container, ProfileContainer):
            volume = self.container.volume_for_fill_height(self.fill_height_m)
            return self.liquid.density_kg_m3 * volume
        return self.liquid.density_kg_m3 * self.container.cross_section_m2 * self.fill_height_m

    @property
    def rigid_mass_kg(self) -> float:
        """Non-sloshing mass m_0 = m_F - sum(m_n) over the modelled modes [kg]."""
        return self.liquid_mass_kg - sum(mode.slosh_mass_kg for mode in self.modes)

    @property
    def cg_height_m(self) -> float:
        """Height of the static liquid's centre of gravity above the bottom, h/2 (the centroid
        through a profile) [m]."""
        if isinstance(self.container, ProfileContainer):
            return self.container.centroid_height_m(self.fill_height_m)
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
        """JSON-ready summary in SI with unit-suffixed keys (the ``model --json`` format); a
        profile's model adds ``container``, ``surface_radius_m``, ``liquid_volume_m3`` and
        ``brimful_volume_m3``."""
        summary = self._summary()
        if isinstance(self.container, ProfileContainer):
            profile = self.container
            summary = {
                "container": profile.name,
                "container_source": profile.source,
                "surface_radius_m": self.radius_m,
                "liquid_volume_m3": profile.volume_for_fill_height(self.fill_height_m),
                "brimful_volume_m3": profile.brimful_volume_m3,
                **summary,
            }
        return summary

    def _summary(self) -> dict[str, object]:
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
