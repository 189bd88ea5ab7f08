"""Slosh of an upright cylinder under any rigid-body motion (3-D pose trajectories).

Model
-----
Each lateral mode n of the equivalent model (`sloshkit.model.modal.SloshModel`: omega_n, zeta_n,
L_n, bob height, unchanged) is a spherical pendulum of length L_n hinged on the container
axis at the pivot height H_n = bob height + L_n (Abramson, NASA SP-106 (1966) ch. 6; Dodge,
SwRI (2000) §3: the same pendulum reproduces the slosh forces and moments for translation
and pitching). It is driven by the specific force at its hinge,

    f = kappa_n g_vec - a_hinge,  a_hinge = a_O + alpha x r_n + omega x (omega x r_n),

with r_n = H_n times the container axis, g_vec = (0, 0, -g) and kappa_n = omega_n^2 L_n / g
(1 for theory; honours a calibrated or surface-tension-corrected omega_n as the 1-D model
does). Everything is written in a frame N that tilts with the container axis but does **not
spin about it**: N = C Rz(-phi), phi' = omega_z (body). An ideal liquid in an axisymmetric
container is not dragged by rotation about the axis: the Stokes-Joukowski potential for that
rotation is zero: the wall and bottom move tangentially, no normal velocity is imposed, so
irrotational flow stays at rest (Stokes 1880, Zhukovsky 1885; Lamb, *Hydrodynamics*, 6th ed.
(1932), ch. III on liquid in rotating vessels). Viscous spin-up takes t ~ h / sqrt(nu Omega)
(Greenspan & Howard, J. Fluid Mech. 17 (1963) 385, doi:10.1017/S0022112063001415), tens of
seconds for vials and beakers (36 s for h = 80 mm of water at 5 rad/s), so rotations about
the axis during a move leave the slosh unchanged.
N has the angular velocity Omega = (p, q, 0) (lateral part of the container's).

Linear (per mode, theta = 2-D pendulum angle in N, positive when the bob swings to +x/+y)::

    theta'' + 2 zeta omega theta' + (-f_z / L) theta + Omega (Omega . theta)
        = f_lat / L + (q', -p')

(-f_z / L = omega^2 at rest: vertical acceleration and tilt change the stiffness
parametrically; (q', -p') is the Euler term of the tilt acceleration acting on the rod; the
Coriolis term has no lateral part in N; centrifugal and tension terms combine into
Omega Omega^T). A static tilt psi gives f_lat / |f_z| = tan psi: the pendulums hang along
gravity and the surface stays horizontal. Nonlinear: the first mode is the damped spherical
pendulum with the same drive (`sloshkit.sim.spatial_kernels`), damping on the motion relative
to N; the higher modes stay linear (`sloshkit.sim.spatial_kernels.LARGE_ANGLE_MODES`). The
large-angle pendulum stands for the fundamental mode's finite-amplitude slosh (its softening
and rotary motion); the pendulum parameters of the higher modes are those of linear theory,
and the multimodal theory carries those modes at a higher order of the amplitude (Faltinsen &
Timokha, *Sloshing*, Cambridge University Press (2009) ch. 8-9). Their pendulums are short
(9 mm and 6 mm for R = 49 mm), so that the jerks of a minimum-time plan swing them past 50
deg, where the spherical pendulum's tan(deflection) would read wall heights that jump with a
sample's change of the timing (14 mm against 46 mm on a 20-waypoint plan 4 ms shorter;
studies/path-planner-methods, "The higher modes").

Wall elevation (mode-shape mapping of the 1-D model, `sloshkit.model.modal.wall_elevation_factor`)::

    eta(alpha) = sum_n F_n theta_n . e(alpha),   F_n = 2R/(xi_n^2 - 1)     ("modal", default)
    eta(alpha) += (R - sum_n F_n) s_qs . e(alpha)                          ("planar")

with e(alpha) the wall direction and s_qs = f_lat / |f_z| the quasi-static slope at the
free-surface centre. Over all modes sum_n 2/(xi_n^2 - 1) = 1, so the "planar" remainder (the
static-correction or mode-acceleration term of the modes not simulated) makes a slow or static
tilt of the apparent gravity give exactly the planar surface R tan psi. With three modes the
remainder is 6 % of R s_qs and, by the slow convergence of the Bessel series, it is
concentrated in a wall layer about R / xi_4 wide (4 mm for R = 49 mm, 1.5 capillary lengths),
where the meniscus and the moving contact line, not potential flow, set the surface. The
measured camera heights of `docs/validation-3d.md` (six robot moves, R 49 mm) agree better
with the "modal" mapping (median |peak error| 8 % against 9 %, 90th percentile 21 % against
28 %), so it is the default; "planar" is the exact ideal-fluid statics. The slosh height is
the maximum over the circumference, |eta vector|. The nonlinear pendulum's slope is
tan(deflection) (exact for a static tilt).
"""

from __future__ import annotations

import math
import time as _time

import numpy as np
from numpy.typing import NDArray

from sloshkit.budget import require_samples
from sloshkit.errors import InputError, require_positive, warn_validity
from sloshkit.model.modal import SloshModel
from sloshkit.motion.pose_kinematics import DEFAULT_CUTOFF_HZ, pose_kinematics
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.metrics import default_settle_time
from sloshkit.sim.simulate import LARGE_ANGLE_DEG
from sloshkit.sim.spatial_amplitude import AmplitudeDependence, amplitude_pendulums
from sloshkit.sim.spatial_drive import SpatialDrive, spatial_drive
from sloshkit.sim.spatial_kernels import LARGE_ANGLE_MODES, linear_pendulums, nonlinear_pendulums
from sloshkit.sim.spatial_response import HEIGHT_MAPPINGS, HeightMapping, SpatialResponse

FloatArray = NDArray[np.float64]

#: Below this fraction of g along the container axis the model is doubtful.
LOW_AXIAL_GRAVITY_FRACTION = 0.5
#: Tilt of the container axis from the vertical beyond which we warn [deg].
LARGE_TILT_DEG = 60.0


def simulate_spatial(
    model: SloshModel,
    poses: PoseTrajectory,
    *,
    nonlinear: bool = False,
    settle_time_s: float | None = None,
    sample_period_s: float | None = None,
    cutoff_hz: float | None = DEFAULT_CUTOFF_HZ,
    height_mapping: HeightMapping = "modal",
    wall_height_m: float | None = None,
    amplitude_dependence: AmplitudeDependence | None = None,
) -> SpatialResponse:
    """Slosh of every mode of ``model`` for the container poses ``poses`` (3-D motion).

    Parameters
    ----------
    model : equivalent pendulum model (`sloshkit.model.modal.equivalent_model`)
    poses : pose trajectory of the container's bottom centre; at rest before the first and
        after the last pose
    nonlinear : large-angle spherical pendulums (RK4) instead of the linear 2-D oscillators
        (closed-form steps)
    settle_time_s : time simulated after the last pose, the final pose held [s] (default
        `sloshkit.sim.metrics.default_settle_time`)
    sample_period_s : simulation step [s] (default: the poses' step if uniform, else 1 ms)
    cutoff_hz : cut-off of the pose differentiation (`sloshkit.motion.pose_kinematics`);
        None for exact (unsmoothed) data
    height_mapping : ``"modal"`` (default: sum_n 2R/(xi_n^2-1) times each simulated mode's
        slope vector, the 1-D mapping) or ``"planar"`` (plus the quasi-static remainder of
        the modes not simulated, exact for static tilt); see the module docstring. The slope
        of a nonlinear pendulum is tan of its deflection (exact for a static tilt).
    wall_height_m : wall height above the bottom for the spill warning (default: the
        container's)
    amplitude_dependence : optional backbone (omega(A), zeta(A) of the wave about its
        quasi-static equilibrium, e.g. from a free decay) for the linear model
        (`sloshkit.sim.spatial_amplitude`); None (default): amplitude-independent

    Returns
    -------
    SpatialResponse

    References
    ----------
    See the module docstring (Abramson 1966; Dodge 2000; Lamb 1932; Greenspan & Howard 1963).

    Examples
    --------
    >>> from sloshkit.model.geometry import UprightCylinder
    >>> from sloshkit.model.liquids import get_liquid
    >>> from sloshkit.model.modal import equivalent_model
    >>> from sloshkit.motion.laws import septic
    >>> from sloshkit.motion.pose_builders import poses_from_law
    >>> model = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08,
    ...                          damping_ratio=0.0066)
    >>> response = simulate_spatial(model, poses_from_law(septic(0.3, 1.5)))
    >>> 0.0 < response.peak_slosh_height_m < 0.01
    True
    """
    if amplitude_dependence is not None and nonlinear:
        raise InputError(
            "amplitude_dependence",
            amplitude_dependence.source,
            "applies to the linear model (nonlinear=False)",
        )
    if height_mapping not in HEIGHT_MAPPINGS:
        raise InputError(
            "height_mapping", height_mapping, "must be one of " + ", ".join(HEIGHT_MAPPINGS)
        )
    settle = default_settle_time(model) if settle_time_s is None else float(settle_time_s)
    if not math.isfinite(settle) or settle < 0.0:
        raise InputError("settle_time", settle, "must be >= 0 s")
    if sample_period_s is None:
        dt = poses.sample_period_s if poses.is_uniform else 1e-3
    else:
        dt = require_positive("sample_period", sample_period_s, "s")
    _check_step(model, poses, dt, sample_period_s is None)
    _warn_pose_range(poses)
    started = _time.perf_counter()
    # RK4 sub-steps keep omega_max h <= 0.5 (accurate, far inside RK4's stability limit 2.8);
    # the drive is sampled at half sub-steps
    large = min(LARGE_ANGLE_MODES, len(model.modes)) if nonlinear else 0
    substeps = max(
        1, math.ceil(max(m.omega_rad_s for m in model.modes[: max(large, 1)]) * dt / 0.5)
    )
    grid_dt = dt / (2.0 * substeps) if nonlinear else dt
    # size before allocation (sloshkit.budget): the drive, kinematics and states of every mode
    require_samples(
        "poses",
        f"{poses.duration_s + settle:.4g} s at {grid_dt:.3g} s steps",
        (poses.duration_s + settle) / grid_dt,
        24 + 12 * len(model.modes),
        "3-D time samples",
    )
    extended = poses.extended(settle, dt)
    kinematics = pose_kinematics(extended, grid_dt, cutoff_hz=cutoff_hz)
    drive = spatial_drive(model, kinematics)
    modes = model.modes
    length = np.array([mode.length_m for mode in modes])
    omega = np.array([mode.omega_rad_s for mode in modes])
    zeta = np.array([mode.damping_ratio for mode in modes])
    count = len(modes)
    if nonlinear:
        unit, unit_rate = nonlinear_pendulums(
            drive.specific_force_m_s2[:large],
            drive.rest_force_m_s2[:large],
            drive.tilt_rate_rad_s,
            drive.tilt_acceleration_rad_s2,
            length[:large],
            omega[:large],
            zeta[:large],
            dt / substeps,
        )
        # the higher modes linear (`LARGE_ANGLE_MODES`), on the same drive's half-step grid
        angle, rate = linear_pendulums(
            drive.specific_force_m_s2[large:count],
            drive.rest_force_m_s2[large:count],
            drive.tilt_rate_rad_s,
            drive.tilt_acceleration_rad_s2,
            length[large:],
            omega[large:],
            zeta[large:],
            grid_dt,
        )
        full = slice(None, None, 2 * substeps)
        drive = SpatialDrive(
            drive.time_s[full],
            drive.specific_force_m_s2[:, full],
            drive.tilt_rate_rad_s[full],
            drive.tilt_acceleration_rad_s2[full],
            drive.spin_angle_rad[full],
            kinematics,
            drive.rest_force_m_s2,
        )
        size = drive.time_s.size
        unit, unit_rate = unit[:, ::substeps][:, :size], unit_rate[:, ::substeps][:, :size]
        angle, rate = angle[:, full][:, :size], rate[:, full][:, :size]
        unit = np.concatenate(
            (unit, np.concatenate((angle, -np.ones((*angle.shape[:2], 1))), axis=2)), axis=0
        )
        unit_rate = np.concatenate(
            (unit_rate, np.concatenate((rate, np.zeros((*rate.shape[:2], 1))), axis=2)), axis=0
        )
    else:
        if amplitude_dependence is None:
            angle, rate = linear_pendulums(
                drive.specific_force_m_s2[:count],
                drive.rest_force_m_s2[:count],
                drive.tilt_rate_rad_s,
                drive.tilt_acceleration_rad_s2,
                length,
                omega,
                zeta,
                dt,
            )
        else:
            angle, rate = amplitude_pendulums(
                drive.specific_force_m_s2[:count],
                drive.rest_force_m_s2[:count],
                drive.tilt_rate_rad_s,
                drive.tilt_acceleration_rad_s2,
                model,
                amplitude_dependence,
                dt,
            )
        unit = np.concatenate((angle, -np.ones((*angle.shape[:2], 1))), axis=2)
        unit_rate = np.concatenate((rate, np.zeros((*rate.shape[:2], 1))), axis=2)
    response = SpatialResponse(
        model=model,
        drive=drive,
        pendulum=unit,
        pendulum_rate=unit_rate,
        nonlinear=nonlinear,
        motion_end_s=poses.end_s,
        height_mapping=height_mapping,
        amplitude_model="none" if amplitude_dependence is None else amplitude_dependence.source,
        motion_name=poses.name,
        elapsed_s=_time.perf_counter() - started,
    )
    _warn_beyond_validity(response, wall_height_m)
    return response


def _check_step(model: SloshModel, poses: PoseTrajectory, dt: float, from_poses: bool) -> None:
    """Refuse a step that cannot resolve the fastest mode (more than half its period)."""
    fastest = max(mode.omega_rad_s for mode in model.modes)
    half_period = math.pi / fastest
    if dt > half_period:
        raise InputError(
            "sample_period",
            f"{dt:.4g} s" + (" (the pose file's own step)" if from_poses else ""),
            f"must be below half the period of the fastest mode ({half_period:.4g} s)",
            "give --sample-period, e.g. 1ms" if from_poses else "",
        )


def _warn_pose_range(poses: PoseTrajectory) -> None:
    tilt = math.degrees(float(np.max(poses.tilt_rad)))
    if tilt > LARGE_TILT_DEG:
        warn_validity(
            f"container tilts {tilt:.1f} deg from the vertical (> {LARGE_TILT_DEG:g} deg): "
            "the slosh model of an upright cylinder is not trustworthy there"
        )


def _warn_beyond_validity(response: SpatialResponse, wall_height_m: float | None) -> None:
    model = response.model
    g = model.gravity_m_s2
    axial = -response.drive.specific_force_m_s2[0, :, 2]
    kappa = model.modes[0].omega_rad_s ** 2 * model.modes[0].length_m / g
    lowest = float(np.min(axial)) / (kappa * g)
    if lowest <= 0.0:
        warn_validity(
            f"apparent gravity along the container axis reverses (down to {lowest:.2f} g): "
            "the liquid leaves the bottom; the slosh model does not hold"
        )
    elif lowest < LOW_AXIAL_GRAVITY_FRACTION:
        warn_validity(
            f"apparent gravity along the container axis drops to {lowest:.2f} g "
            f"(< {LOW_AXIAL_GRAVITY_FRACTION:g} g): large, nonlinear slosh; model doubtful"
        )
    peak = math.degrees(response.peak_angle_rad)
    if peak > LARGE_ANGLE_DEG:
        warn_validity(
            f"slosh angle reaches {peak:.1f} deg (> {LARGE_ANGLE_DEG:g} deg): beyond "
            "small-amplitude theory; swirl, wave breaking and bubbles are not modelled"
        )
    wall = model.container.wall_height_m if wall_height_m is None else float(wall_height_m)
    if wall is not None:
        highest = model.fill_height_m + response.peak_slosh_height_m
        if highest > wall:
            warn_validity(
                f"free surface reaches {1e3 * highest:.1f} mm at the wall, above the "
                f"{1e3 * wall:.1f} mm wall: the liquid may spill"
            )
