"""What defines a CFD case: container, liquid, excitation, mesh and time-stepping (SI units).

The case itself is written in millimetres (`SCALE`): interFoam on O-grid cylinders in metres
diverged within a few steps on v1912, the same mesh scaled by 1000 ran stably.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from sloshkit.cfd.excitation import Excitation, FreeDecay
from sloshkit.errors import InputError, require_in_range, require_positive
from sloshkit.model.liquids import Liquid

SCALE = 1000.0  # metres -> millimetres
#: Air at 25 degC, 1 atm: the seed paper's Table 1.
AIR_DENSITY_KG_M3 = 1.185
AIR_VISCOSITY_PA_S = 1.831e-5
DDT_SCHEMES = ("Euler", "CrankNicolson 0.9", "backward")


@dataclass(frozen=True)
class CaseSpec:
    """Everything that defines a case (SI units; the case itself is written in mm).

    ``wall_grading`` is the ratio of the cell at the wall to the innermost cell of the O-grid's
    ring blocks (1: uniform), with ``radial_cells`` across the ring (default from
    ``cells_per_radius``): wall refinement for the oscillating boundary layer.

    With ``adjust_time_step`` (the default) interFoam chooses its step from the Courant limits
    ``max_courant`` and ``max_alpha_courant`` and never exceeds ``delta_t_s``; without it the
    step is fixed at ``delta_t_s``. Fields are written every ``write_interval_s`` only.

    Examples
    --------
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=11)
    >>> round(spec.height_m, 5)
    0.06975

    Parameters
    ----------
    radius_m, fill_height_m : float
        Container radius and fill height [m].
    liquid : Liquid
        The liquid (air is the seed paper's Table 1).
    excitation : Excitation
        The container motion.
    domain_height_m : float, optional
        Wall height [m] (default: fill plus 1.5 R).
    cells_per_radius : int
        Mesh resolution N (see `sloshkit.cfd.mesh`).
    end_time_s, delta_t_s : float
        Simulated time and largest (or fixed) step [s].
    ddt_scheme : str
        One of `DDT_SCHEMES`.
    write_interval_s : float
        Interval of the field output [s].
    surface_tension : bool
        Include surface tension.
    probes_per_column : int, optional
        Probes in each column (default from the mesh).
    processes : int
        MPI processes.
    adjust_time_step : bool
        Adaptive step (else fixed).
    max_courant, max_alpha_courant : float
        Courant and interface-Courant limits of the adaptive step.
    probe_angles : int
        Probe columns around the wall (0: two on the x axis).
    pressure_correctors : int
        PIMPLE pressure correctors per step.
    wall_grading : float
        Wall cell / innermost cell of the graded wall annulus (1: uniform).
    radial_cells : int, optional
        Cells across the ring blocks (uniform) or the wall annulus (graded).
    surface_refinement : int
        Vertical cells within +-0.3 R of the free surface are R/(surface_refinement x N)
        high (R/N elsewhere): 2 by default. 4 lowered the damping of the 12/radius graded mesh
        by 12 % and left the 16/radius one unchanged (studies/cfd-damping/README.md).
    momentum_predictor : bool
        Solve the momentum equation before the pressure correctors (PIMPLE
        ``momentumPredictor``). Off by default: on wall-graded meshes at 0.5 ms it cut the
        step-to-step pressure oscillation about fourfold without removing it, and the 16/radius
        graded mesh blew up with it at 1 ms (studies/cfd-damping/README.md).

    Returns
    -------
    CaseSpec
    """

    radius_m: float
    fill_height_m: float
    liquid: Liquid
    excitation: Excitation = field(default_factory=FreeDecay)
    domain_height_m: float | None = None
    cells_per_radius: int = 10
    end_time_s: float = 3.0
    delta_t_s: float = 2e-3
    ddt_scheme: str = "Euler"
    write_interval_s: float = 0.5
    surface_tension: bool = False
    probes_per_column: int | None = None
    processes: int = 1
    adjust_time_step: bool = True
    max_courant: float = 0.5
    max_alpha_courant: float = 0.5
    probe_angles: int = 0
    pressure_correctors: int = 3
    wall_grading: float = 1.0
    radial_cells: int | None = None
    momentum_predictor: bool = False
    surface_refinement: int = 2

    def __post_init__(self) -> None:
        require_positive("radius", self.radius_m, "m")
        require_positive("fill_height", self.fill_height_m, "m")
        require_in_range("cells_per_radius", self.cells_per_radius, 3, 60)
        require_in_range("end_time", self.end_time_s, 1e-4, 3600.0, "s")
        require_in_range("delta_t", self.delta_t_s, 1e-6, 0.05, "s")
        require_in_range("write_interval", self.write_interval_s, 1e-4, 3600.0, "s")
        require_in_range("np", self.processes, 1, 256)
        require_in_range("max_courant", self.max_courant, 0.01, 5.0)
        require_in_range("max_alpha_courant", self.max_alpha_courant, 0.01, 5.0)
        require_in_range("pressure_correctors", self.pressure_correctors, 1, 5)
        require_in_range("wall_grading", self.wall_grading, 0.005, 1.0)
        require_in_range("surface_refinement", self.surface_refinement, 1, 8)
        if self.radial_cells is not None:
            require_in_range("radial_cells", self.radial_cells, 2, 200)
        if self.probe_angles:
            require_in_range("probe_angles", self.probe_angles, 4, 64)
        if self.height_m <= self.fill_height_m:
            raise InputError("domain_height", self.height_m, "must exceed the fill height")
        if self.ddt_scheme not in DDT_SCHEMES:
            raise InputError("ddt_scheme", self.ddt_scheme, "must be " + ", ".join(DDT_SCHEMES))

    @property
    def height_m(self) -> float:
        """Domain height: the given wall height, else the fill plus 1.5 R of headspace [m]."""
        if self.domain_height_m is not None:
            return self.domain_height_m
        return self.fill_height_m + 1.5 * self.radius_m
