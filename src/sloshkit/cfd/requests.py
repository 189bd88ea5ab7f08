"""The CFD case a command asks for: values in SI turned into a checked `CaseSpec`.

The command line parses the case options (units, the pose file, the move of ``--excitation
law``; `sloshkit.cli.cfd_options`) into a `CaseRequest`; this module checks what they mean for
a case (a meshable container, at least one process), chooses the defaults that depend on the
excitation and builds the specification through `sloshkit.cfd.pipeline.case_spec`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sloshkit.cfd.pipeline import RECOMMENDED, case_spec, excitation_from_options
from sloshkit.cfd.spec import CaseSpec
from sloshkit.errors import InputError
from sloshkit.model.modal import SloshModel
from sloshkit.model.profile import ProfileContainer

#: Probe columns around the wall of a pose-driven case (its slosh height is their maximum).
POSE_PROBE_ANGLES = 12


def require_cylinder(slosh_model: SloshModel) -> None:
    """Refuse a model of a container given by its profile: the CFD cases are meshes of upright
    cylinders only.

    Parameters
    ----------
    slosh_model : SloshModel
        The model the CFD case would be built from or compared with.

    Returns
    -------
    None
        When the model's container is an upright cylinder.

    Raises
    ------
    InputError
        Naming ``--container`` or ``--profile`` (the option that gave the profile).

    Examples
    --------
    >>> from sloshkit.model.catalogue import catalogue_container
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(catalogue_container("iso8362-10R"), get_liquid("water-25C"), 0.01)
    >>> require_cylinder(model)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: container = 'iso8362-10R' is invalid: ...
    """
    container = slosh_model.container
    if isinstance(container, ProfileContainer):
        from_catalogue = container.name.startswith("iso8362-")
        raise InputError(
            "container" if from_catalogue else "profile",
            container.name,
            "CFD meshes upright cylinders only (--radius, --wall-height); a container given by "
            "its profile is modelled by finite elements, not by CFD",
        )


def require_processes(processes: int | None) -> int:
    """The MPI processes of a case: at least 1 (None: 1, serial).

    Parameters
    ----------
    processes : int or None
        The requested process count (``--np``).

    Returns
    -------
    int

    Raises
    ------
    InputError
        Below 1, naming ``np``.

    Examples
    --------
    >>> require_processes(None), require_processes(4)
    (1, 4)
    >>> require_processes(0)
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: np = 0 is invalid: must be at least 1 (1 runs serially)
    """
    if processes is not None and processes < 1:
        raise InputError("np", processes, "must be at least 1 (1 runs serially)")
    return 1 if processes is None else processes


@dataclass(frozen=True)
class CaseRequest:
    """The options of a CFD case in SI, before they are checked and made a `CaseSpec`.

    Parameters
    ----------
    excitation : str
        ``free-decay``, ``harmonic``, ``law`` or ``poses``.
    tilt_rad : float
        Initial tilt of a free decay [rad].
    amplitude_m, frequency_hz, excite_time_s : float
        The harmonic excitation [m], [Hz], [s].
    motion : Motion or None
        The motion law of ``law``.
    poses : PoseTrajectory or None
        The pose trajectory of ``poses``.
    end_time_s, delta_t_s : float
        Simulated time and largest (or fixed) step [s].
    cells_per_radius : int
        Mesh resolution.
    ddt_scheme : str
        Time scheme.
    processes : int or None
        MPI processes (None: 1, serial).
    surface_tension : bool
        Include surface tension.
    max_courant : float
        Courant and interface-Courant limit of the adaptive step.
    fixed_step : bool
        A fixed step of ``delta_t_s`` (no Courant limit).
    probe_angles : int or None
        Probe columns around the wall (None: `POSE_PROBE_ANGLES` for poses, else 0, two on
        the x axis).
    wall_grading : float
        Wall refinement (1: uniform; see `CaseSpec`).
    radial_cells : int or None
        Cells across the ring blocks or the graded wall annulus.
    surface_refinement : int
        Vertical refinement near the free surface (see `CaseSpec`).

    Returns
    -------
    CaseRequest

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    >>> request = CaseRequest("harmonic", 0.05, 0.01, 1.0, 2.0, None, None, 4.0, 2e-3, 11,
    ...                       "Euler", None, False, 0.5, False, None)
    >>> spec = request.spec(model)
    >>> spec.end_time_s, spec.processes, spec.probe_angles
    (4.0, 1, 0)
    """

    excitation: str
    tilt_rad: float
    amplitude_m: float
    frequency_hz: float
    excite_time_s: float
    motion: Any
    poses: Any
    end_time_s: float
    delta_t_s: float
    cells_per_radius: int = RECOMMENDED["cells_per_radius"]
    ddt_scheme: str = RECOMMENDED["ddt_scheme"]
    processes: int | None = None
    surface_tension: bool = False
    max_courant: float = RECOMMENDED["max_courant"]
    fixed_step: bool = False
    probe_angles: int | None = None
    wall_grading: float = 1.0
    radial_cells: int | None = None
    surface_refinement: int = 2

    def spec(self, model: SloshModel) -> CaseSpec:
        """The checked case for ``model``'s container, fill and liquid.

        Parameters
        ----------
        model : SloshModel
            The container (an upright cylinder), fill and liquid.

        Returns
        -------
        CaseSpec

        Raises
        ------
        InputError
            ``np`` below 1, an unknown or incomplete excitation, or a case that
            `sloshkit.cfd.pipeline.case_spec` refuses (a pose trajectory too short or too long
            for the case's grid among them).

        Examples
        --------
        >>> from sloshkit.model.geometry import UprightCylinder
        >>> from sloshkit.model.liquids import get_liquid
        >>> from sloshkit.model.modal import equivalent_model
        >>> model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
        >>> CaseRequest("free-decay", 0.05, 0.0, 0.0, 0.0, None, None, 2.0, 2e-3,
        ...             processes=0).spec(model)
        Traceback (most recent call last):
        ...
        sloshkit.errors.InputError: np = 0 is invalid: must be at least 1 (1 runs serially)
        """
        require_cylinder(model)
        processes = require_processes(self.processes)
        excitation = excitation_from_options(
            self.excitation,
            self.tilt_rad,
            self.amplitude_m,
            self.frequency_hz,
            self.excite_time_s,
            self.motion,
            self.poses,
        )
        angles = self.probe_angles
        if angles is None:
            angles = POSE_PROBE_ANGLES if self.poses is not None else 0
        return case_spec(
            model,
            excitation,
            cells_per_radius=self.cells_per_radius,
            end_time_s=self.end_time_s,
            delta_t_s=self.delta_t_s,
            ddt_scheme=self.ddt_scheme,
            processes=processes,
            surface_tension=self.surface_tension,
            max_courant=self.max_courant,
            max_alpha_courant=self.max_courant,
            adjust_time_step=not self.fixed_step,
            probe_angles=angles,
            wall_grading=self.wall_grading,
            radial_cells=self.radial_cells,
            surface_refinement=self.surface_refinement,
        )
