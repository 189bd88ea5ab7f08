"""Independent minimum-time reference for the 3-D path planner's benchmark (casadi, IPOPT).

The same problem the planner solves, transcribed here without any of its code (only the
problem and path data types are shared): the fastest timing s(t) of a fixed path, optionally
with two tilt angles, under the Cartesian, angular, tilt and linear slosh limits.

Transcription: direct multiple shooting in continuous time (Bock & Plitt, IFAC Proc. 17 (1984)
1603-1608, doi:10.1016/S1474-6670(17)61205-9; Betts, *Practical Methods for Optimal Control
and Estimation Using Nonlinear Programming*, 2nd ed., SIAM (2010) ch. 4): free final time T
split into N equal intervals h = T / N, the path parameter's jerk (and the tilt jerks)
piecewise constant, one classical Runge-Kutta step per interval, the path constraints at every
node (the jerk with the control on either side of it), solved by IPOPT (Waechter & Biegler,
Math. Prog. 106 (2006) 25-57, doi:10.1007/s10107-004-0559-y) with exact second derivatives.

Geometry: the position p(s) of the reference point (container bottom centre), the de-spun
frame D(s) = R_path(s) Rz(-psi(s)) and the spin angle psi(s) are sampled densely from the
`Path` and interpolated by quintic B-splines (casadi ``interpolant``), whose derivatives give
the velocities, accelerations and jerks. psi is the integral of the container's angular
velocity about its own axis (body z component), so that D does not spin about the axis.

Slosh, ``slosh_model="linear"`` (default; Abramson, NASA SP-106 (1966) ch. 6; Dodge, SwRI
(2000) ch. 3; the same definition as the planner's linear screen): every mode n of every model
of the band is a linear spherical pendulum, phi'' + 2 zeta w phi' + w^2 phi = f_lat / L_n, phi
a 2-vector, f = g - a_B the specific force at the bob's rest point B_n = bottom +
bob_height_n * axis, in the container's frame with its spin about the axis removed, f_lat its
first two components; at rest in equilibrium at the start. Limits: |sum_n e_n phi_n| <= max
height at the nodes; at T the residual sum_n e_n sqrt(|A_n|^2 + |B_n|^2) <= max residual,
A_n = phi_n - rest_n, B_n = (phi_n' + zeta w A_n) / w_d (the cosine and sine amplitudes of the
free oscillation); the first mode's angle when ``max_surface_angle_rad`` is set.

Slosh, ``slosh_model="nonlinear"``: the model the planner's verification simulates
(`sloshkit.sim.spatial`, written here again without its code): the first mode
(`sloshkit.sim.spatial_kernels.LARGE_ANGLE_MODES`) a large-angle damped spherical pendulum, the
higher ones small-angle pendulums with the same hinge and drive, theta'' + 2 zeta w theta'
+ (-f_z / L_n) theta + Omega (Omega . theta) = f_lat / L_n + (q', -p') (their slope theta,
their rest f_lat / (-f_z)). Every mode is a pendulum of length L_n hinged on the axis at the
pivot height H_n = bob height + L_n (Abramson ch. 6; Dodge ch. 3), the large-angle one's bob
at L_n u from the hinge, u a unit vector in the frame
N that tilts with the container axis but does not spin about it (the de-spun frame above),
Omega = (p, q, 0) the angular velocity of N in N and Omega' the derivative of its components.
With the constraint force eliminated (relative motion in a non-inertial frame: Goldstein,
*Classical Mechanics*, 3rd ed. (2002) §4.10),

    u'' = (F - (u . F) u) / L_n - |u'|^2 u,
    F = f - Omega' x rho - Omega x (Omega x rho) - 2 Omega x rho' - 2 zeta w rho',  rho = L_n u,

f = kappa_n g_vec - a_hinge in N (kappa_n = w^2 L_n / g), the Euler, centrifugal and Coriolis
terms of N's lateral rotation included. The state is the lateral part x = (u_x, u_y) and x',
u_z = -sqrt(1 - |x|^2) (the bob below the hinge), u_z' = -(x . x') / u_z; the lateral rows of
the equation give x''. At rest at the start along the apparent gravity, x = f_lat / |f|.
Wall height (the verification's "modal" mapping): |sum_n e_n x_n / (-u_z,n)| <= max height at
the nodes (the slope of a mode is the tangent of its deflection). Residual (the verification's
`free_amplitudes_rad`): with A_n = x_n(T) - f_lat / |f| (f at rest in the final pose) and
B_n = (x_n'(T) + zeta w A_n) / w_d, the free oscillation A_n cos + B_n sin traces an ellipse
whose semi-major axis a_n is the square root of the larger eigenvalue of
M_n = A_n A_n^T + B_n B_n^T; sum_n e_n a_n <= max residual. a_n <= b_n is written exactly and
smoothly as b_n^2 I - M_n positive semidefinite: b_n^2 >= M_xx, b_n^2 >= M_yy and
(b_n^2 - M_xx)(b_n^2 - M_yy) >= M_xy^2 (a 2 x 2 matrix is semidefinite iff its diagonal and
determinant are nonnegative), with sum_n e_n b_n <= max residual. The first mode's surface
angle atan2(|x|, -u_z) <= a limit is |x| <= sin(limit).

Tilt (optional): rotation vector r = (rx, ry, 0) about world axes applied before the path's
orientation, R = Rot(r) R_path(s); the reference point is moved so that the tilt centre (height
c on the axis) stays on the path: bottom = p + c R_path e_z - c R e_z. The de-spun frame of R
is Rot(r) D(s) Rz(-chi), chi' = (R e_z) . omega_tilt (the tilt's own spin about the axis).
|r| <= max tilt, |r'| <= the angular velocity limit (else pi rad/s), |r''| <= the angular
acceleration limit (else 1000 deg/s^2), r = r' = r'' = 0 at both ends.

Initial guess: a phase-plane speed profile of the path, averaged over the first slosh period,
slowed until the simulated pendulums and kinematics meet every limit (`initial_guess`, a
feasible start for IPOPT); solved first on a coarse grid, then on the fine one; the tilted
problem starts from the untilted optimum (upright), and its fine solve from the coarse
solution's jerks held on a whole number of fine intervals each (so the fine interval is at
most ``interval_s``) with the states simulated from them, IPOPT's barrier started small.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sloshkit.model.theory import GRAVITY_M_S2
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.motion.sampling import steps_to_reach
from sloshkit.plan.path.geometry import Path
from sloshkit.plan.path.problem import PathProblem
from sloshkit.sim.spatial_kernels import LARGE_ANGLE_MODES

FloatArray = NDArray[np.float64]

#: Tilt rate limit [rad/s] when the problem has no angular velocity limit.
DEFAULT_TILT_RATE_RAD_S = math.pi
#: Tilt acceleration limit [rad/s^2] when the problem has no angular acceleration limit.
DEFAULT_TILT_ACCELERATION_RAD_S2 = math.radians(1000.0)
#: Spacing of the geometry samples the B-splines interpolate [m] (half the path's knot spacing).
GEOMETRY_SPACING_M = 1e-3
#: Upper bound on the path parameter's rate [m/s]: never binding when the Cartesian speed
#: limits it; it only keeps IPOPT bounded on stretches where the container only spins.
MAX_PARAMETER_RATE_M_S = 50.0
#: The first solve's interval, relative to ``interval_s``, on the slowed guess's duration.
COARSE_FACTOR = 2.5
#: Most intervals of the first solve.
MAX_COARSE = 500
#: IPOPT's first barrier parameter and bound push for a solve from a coarser grid's solution.
WARM_MU, WARM_PUSH = 1e-6, 1e-8
#: The slosh models of the reference (module docstring).
SLOSH_MODELS = ("linear", "nonlinear")


@dataclass(frozen=True)
class ReferenceOptimum:
    """The minimum-time solution of one problem.

    Parameters
    ----------
    duration_s : float
        Optimal duration T [s].
    status : str
        IPOPT's return status.
    converged : bool
        Whether IPOPT reports success.
    compute_time_s : float
        Wall time of the whole computation (geometry, initial guess, solve) [s].
    intervals : int
        Shooting intervals N.
    tilt : bool
        Whether the tilt angles were free.
    initial_duration_s : float
        Duration of the feasible initial guess [s].
    peak_height_m : float
        Largest wall height at the nodes of the solution [m].
    residual_height_m : float
        Residual bound at T [m].
    peak_tilt_rad : float
        Largest |r| at the nodes [rad].
    slosh_model : str
        ``"linear"`` or ``"nonlinear"`` (module docstring).
    """

    duration_s: float
    status: str
    converged: bool
    compute_time_s: float
    intervals: int
    tilt: bool
    initial_duration_s: float
    peak_height_m: float
    residual_height_m: float
    peak_tilt_rad: float
    slosh_model: str = "linear"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready fields (keys carry their unit)."""
        return {
            "duration_s": self.duration_s,
            "status": self.status,
            "converged": self.converged,
            "compute_time_s": self.compute_time_s,
            "intervals": self.intervals,
            "tilt": self.tilt,
            "initial_duration_s": self.initial_duration_s,
            "peak_height_m": self.peak_height_m,
            "residual_height_m": self.residual_height_m,
            "peak_tilt_rad": self.peak_tilt_rad,
            "slosh_model": self.slosh_model,
        }


def geometry_interpolant(path: Path, spacing_m: float = GEOMETRY_SPACING_M) -> Any:
    """Quintic B-spline of (p(s), D(s) row-major, psi(s)): 13 outputs (module docstring).

    psi accumulates the body-z components of the rotation vectors between neighbouring
    samples (the spin about the container's own axis); D = R_path Rz(-psi).
    """
    count = max(math.ceil(path.length_m / spacing_m), 64) + 1
    s = np.linspace(0.0, path.length_m, count)
    rotations = path.orientation(s)
    steps = (rotations[:-1].inv() * rotations[1:]).as_rotvec()[:, 2]
    psi = np.concatenate(([0.0], np.cumsum(steps)))
    despun = (rotations * Rotation.from_rotvec(np.c_[0.0 * psi, 0.0 * psi, -psi])).as_matrix()
    values = np.c_[path.position(s), despun.reshape(count, 9), psi]
    return ca.interpolant("path_geometry", "bspline", [s], values.ravel(), {"degree": [5]})


def _series(x: Any, first: int, terms: int) -> Any:
    """sum_k (-x)^k / (2k + first)! by Horner's rule: first 1 gives sin(a)/a, 2 gives
    (1 - cos a)/a^2, 3 gives (a - sin a)/a^3 for x = a^2 (smooth at 0, unlike the closed
    forms)."""
    total = ca.SX(0)
    for k in range(terms - 1, -1, -1):
        total = 1.0 / math.factorial(2 * k + first) - x * total
    return total


def _series_terms(max_angle_rad: float) -> int:
    """Terms of `_series` that leave an error below 1e-13 up to ``max_angle_rad``."""
    x = max(max_angle_rad, 0.1) ** 2
    terms = 1
    while x**terms / math.factorial(2 * terms + 1) > 1e-13:
        terms += 1
    return terms


def _tilt_functions(r: Any, max_angle_rad: float) -> tuple[Any, Any, Any]:
    """For the rotation vector r = (rx, ry, 0) (Rodrigues: R v = v + a r x v + b r x (r x v),
    a = sin|r| / |r|, b = (1 - cos|r|) / |r|^2; its world angular velocity J r' with
    J = I + b [r]x + c [r]x^2, c = (|r| - sin|r|) / |r|^3: Murray, Li & Sastry, *A Mathematical
    Introduction to Robotic Manipulation*, CRC (1994) §2.2): the functions R v, R^T v and
    J r'."""
    x = r[0] ** 2 + r[1] ** 2
    terms = _series_terms(max_angle_rad)
    a, b, c = (_series(x, first, terms) for first in (1, 2, 3))
    vector = ca.vertcat(r[0], r[1], 0)

    def rotate(v: Any) -> Any:
        return v + a * ca.cross(vector, v) + b * ca.cross(vector, ca.cross(vector, v))

    def rotate_back(v: Any) -> Any:
        return v - a * ca.cross(vector, v) + b * ca.cross(vector, ca.cross(vector, v))

    def angular_velocity(rate: Any) -> Any:
        rate = ca.vertcat(rate[0], rate[1], 0)
        return rate + b * ca.cross(vector, rate) + c * ca.cross(vector, ca.cross(vector, rate))

    return rotate, rotate_back, angular_velocity


def _path_tilts(path: Path, spacing_m: float = GEOMETRY_SPACING_M) -> bool:
    """Whether the container axis of ``path`` leaves the vertical anywhere (by 1e-9 rad)."""
    count = max(math.ceil(path.length_m / spacing_m), 64) + 1
    axis = path.orientation(np.linspace(0.0, path.length_m, count)).apply([0.0, 0.0, 1.0])
    return bool(np.max(np.hypot(axis[:, 0], axis[:, 1])) > 1e-9)


def _rotvec_matrix(rotate: Any) -> Any:
    """The matrix of the rotation ``rotate`` (its images of the unit vectors)."""
    return ca.horzcat(*(rotate(ca.DM(column)) for column in np.eye(3)))


def _vee(rate: Any, rotation: Any) -> Any:
    """Angular velocity (world frame) from dR/dt and R: the axial vector of dR/dt R^T."""
    w = rate @ rotation.T
    return 0.5 * ca.vertcat(w[2, 1] - w[1, 2], w[0, 2] - w[2, 0], w[1, 0] - w[0, 1])


def _rz(angle: Any) -> Any:
    c, s = ca.cos(angle), ca.sin(angle)
    return ca.vertcat(ca.horzcat(c, -s, 0), ca.horzcat(s, c, 0), ca.horzcat(0, 0, 1))


@dataclass(frozen=True)
class _Model:
    """The continuous-time model: its casadi functions and the layout of the state."""

    dynamics: Any  # (x, u) -> x'
    path_limits: Any  # (x, u) -> constraint values, each <= 1
    residual: Any  # x -> the squared residual amplitude of every mode of every model
    residual_rows: Any  # (x, b) -> rows <= 0 that say every mode's amplitude <= b_n
    wall: Any  # x -> wall height of every model
    walls: FloatArray  # e_n of every mode of every model (the order of `residual`)
    x0: FloatArray  # state at rest at s = 0
    scale_x: FloatArray
    scale_u: FloatArray
    tilt: bool

    @property
    def nx(self) -> int:
        return int(self.x0.size)

    @property
    def nu(self) -> int:
        return int(self.scale_u.size)


def _frame_rates(frame: Any, chi: Any, rate: Any) -> tuple[Any, Any]:
    """Lateral angular velocity Omega of N = frame Rz(-chi) in N and the derivative of its
    components: with w_b the body angular velocity of ``frame`` (the axial vector of
    frame^T frame'), Omega = [Rz(chi) w_b]_xy, chi' = w_b,z (N does not spin about the axis)
    and Omega' = [Rz(chi) w_b']_xy + chi' (-Omega_y, Omega_x) (Goldstein (2002) §4.9)."""
    body = frame.T @ _vee(rate(frame), frame)
    turned = _rz(chi) @ body
    omega, spin = turned[0:2], turned[2]
    derivative = (_rz(chi) @ rate(body))[0:2]
    return omega, derivative + spin * ca.vertcat(-omega[1], omega[0])


def _free_oscillation_matrix(cosine: Any, rate: Any, w: float, zeta: float) -> Any:
    """M = A A^T + B B^T of a mode's free oscillation as (M_xx, M_yy, M_xy): A the offset from
    rest (``cosine``), B = (x' + zeta w A) / w_d (module docstring)."""
    sine = (rate + zeta * w * cosine) / (w * math.sqrt(1.0 - zeta**2))
    return ca.vertcat(
        cosine[0] ** 2 + sine[0] ** 2,
        cosine[1] ** 2 + sine[1] ** 2,
        cosine[0] * cosine[1] + sine[0] * sine[1],
    )


def _hinged_linear_mode(
    force: Any, rest: Any, omega: Any, omega_rate: Any, mode: Any
) -> tuple[Any, Any, Any, Any, Any, Any]:
    """One higher mode of the nonlinear model (module docstring): the small-angle pendulum
    hinged as the large-angle one, theta'' + 2 zeta w theta' + (-f_z / L) theta
    + Omega (Omega . theta) = f_lat / L + (q', -p'), with f and Omega = (p, q) as there; the
    same outputs as `_nonlinear_mode`, the slope theta."""
    w, zeta, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
    angle, angle_rate = ca.SX.sym("th", 2), ca.SX.sym("thd", 2)
    euler = ca.vertcat(omega_rate[1], -omega_rate[0])
    acceleration = (
        force[0:2] / length
        + euler
        - 2.0 * zeta * w * angle_rate
        + force[2] / length * angle
        - omega * ca.dot(omega, angle)
    )
    equilibrium = rest[0:2] / (-rest[2])
    matrix = _free_oscillation_matrix(angle - equilibrium, angle_rate, w, zeta)
    return (
        ca.vertcat(angle, angle_rate),
        ca.vertcat(angle_rate, acceleration),
        angle,
        equilibrium,
        matrix,
        ca.sumsqr(angle),
    )


def _nonlinear_mode(
    force: Any, rest: Any, omega: Any, omega_rate: Any, mode: Any
) -> tuple[Any, Any, Any, Any, Any, Any]:
    """One mode's large-angle pendulum (module docstring): its states (x, x'), their
    derivatives, the slope x / (-u_z), the start x at rest, and the free-oscillation matrix
    M = A A^T + B B^T at rest in the pose of the state as (M_xx, M_yy, M_xy)."""
    w, zeta, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
    lateral, lateral_rate = ca.SX.sym("x", 2), ca.SX.sym("xd", 2)
    axial = -ca.sqrt(1.0 - ca.sumsqr(lateral))
    axial_rate = -ca.dot(lateral, lateral_rate) / axial
    unit = ca.vertcat(lateral, axial)
    unit_rate = ca.vertcat(lateral_rate, axial_rate)
    rho, rho_rate = length * unit, length * unit_rate
    spin = ca.vertcat(omega, 0)
    spin_rate = ca.vertcat(omega_rate, 0)
    total = (
        force
        - ca.cross(spin_rate, rho)
        - ca.cross(spin, ca.cross(spin, rho))
        - 2.0 * ca.cross(spin, rho_rate)
        - 2.0 * zeta * w * rho_rate
    )
    radial = ca.dot(unit, total)
    speed2 = ca.sumsqr(lateral_rate) + axial_rate**2
    acceleration = (total[0:2] - radial * lateral) / length - speed2 * lateral
    equilibrium = rest[0:2] / ca.norm_2(rest)
    matrix = _free_oscillation_matrix(lateral - equilibrium, lateral_rate, w, zeta)
    return (
        ca.vertcat(lateral, lateral_rate),
        ca.vertcat(lateral_rate, acceleration),
        lateral / (-axial),
        equilibrium,
        matrix,
        ca.sumsqr(lateral),
    )


def _model(problem: PathProblem, tilt: bool, slosh_model: str = "linear") -> _Model:
    """The state x = (s, s', s'', [r, r', r'', chi], then (phi, phi') or (x, x') of every
    mode of every model), the control u = (s''', [r''']), and the limits as functions
    (module docstring)."""
    if slosh_model not in SLOSH_MODELS:
        raise ValueError(f"slosh_model must be one of {SLOSH_MODELS}, not {slosh_model!r}")
    nonlinear = slosh_model == "nonlinear"
    geometry = geometry_interpolant(problem.path)
    machine = problem.machine
    nq = 3 if tilt else 1
    q, qd, qdd, qddd = (ca.SX.sym(n, nq) for n in ("q", "qd", "qdd", "qddd"))
    chi = ca.SX.sym("chi") if tilt else ca.SX(0)
    y = geometry(q[0])
    p, despun, psi = y[0:3], ca.reshape(y[3:12], 3, 3).T, y[12]
    path_axis = despun[:, 2]
    if tilt:
        rotate, rotate_back, tilt_velocity = _tilt_functions(q[1:3], problem.max_tilt_rad)
    else:
        rotate = rotate_back = lambda v: v  # upright: the identity
    axis = rotate(path_axis)
    centre = problem.tilt_centre_height_m
    bottom = p + centre * (path_axis - axis) if tilt and centre != 0.0 else p
    chain, chain_rate = ca.vertcat(q, qd, qdd), ca.vertcat(qd, qdd, qddd)

    def rate(expression: Any) -> Any:
        """Time derivative of an expression of (q, q', q'') along (q', q'', q''')."""
        return ca.jtimes(expression, chain, chain_rate)

    gravity = ca.DM([0.0, 0.0, -GRAVITY_M_S2])

    # The de-spun frame is Rot D Rz(-chi); its transpose takes world vectors into it.
    def to_frame(v: Any) -> Any:
        return _rz(chi) @ (despun.T @ rotate_back(v))

    bottom_acceleration, axis_acceleration = rate(rate(bottom)), rate(rate(axis))
    if nonlinear and (tilt or _path_tilts(problem.path)):
        frame = _rotvec_matrix(rotate) @ despun if tilt else despun
        frame_rate, frame_acceleration = _frame_rates(frame, chi, rate)
    else:  # the container axis stays vertical: N does not rotate
        frame_rate = frame_acceleration = ca.SX.zeros(2)
    models = problem.models()
    states: list[Any] = []
    derivatives: list[Any] = []
    rests: list[Any] = []
    walls_by_model: list[Any] = []
    amplitudes: list[Any] = []
    walls: list[float] = []
    angles: list[Any] = []
    x0_slosh: list[float] = []
    scales: list[float] = []
    first_wall = models[0].modes[0].wall_elevation_factor_m
    angle_scale = problem.slosh.max_height_m / first_wall
    matrices: list[Any] = []
    for model in models:
        wall = ca.SX.zeros(2)
        for index, mode in enumerate(model.modes):
            w, zeta, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
            if nonlinear:
                kappa = w**2 * length / GRAVITY_M_S2
                hinge = bottom_acceleration + mode.pivot_height_m * axis_acceleration
                # the first mode large-angle, the others small-angle (module docstring)
                pendulum = _nonlinear_mode if index < LARGE_ANGLE_MODES else _hinged_linear_mode
                state, derivative, slope, equilibrium, matrix, angle = pendulum(
                    to_frame(kappa * gravity - hinge),
                    to_frame(kappa * gravity),
                    frame_rate,
                    frame_acceleration,
                    mode,
                )
                states.append(state)
                derivatives.append(derivative)
                rests.append(equilibrium)
                matrices.append(matrix)
                half = 0.5 * (matrix[0] + matrix[1])
                spread = ca.sqrt(0.25 * (matrix[0] - matrix[1]) ** 2 + matrix[2] ** 2)
                amplitudes.append(half + spread)
                walls.append(mode.wall_elevation_factor_m)
                wall += mode.wall_elevation_factor_m * slope
                if index == 0:
                    angles.append(angle)
                scales += [angle_scale] * 2 + [angle_scale * w] * 2
                continue
            phi, phid = ca.SX.sym("phi", 2), ca.SX.sym("phid", 2)
            bob_acceleration = bottom_acceleration + mode.bob_height_m * axis_acceleration
            force = to_frame(gravity - bob_acceleration)
            lateral = force[0:2]
            rest = lateral / (length * w**2)
            states += [phi, phid]
            derivatives += [phid, lateral / length - 2 * zeta * w * phid - w**2 * phi]
            rests.append(rest)
            cosine = phi - rest
            sine = (phid + zeta * w * cosine) / (w * math.sqrt(1.0 - zeta**2))
            amplitudes.append(ca.sumsqr(ca.vertcat(cosine, sine)))
            walls.append(mode.wall_elevation_factor_m)
            wall += mode.wall_elevation_factor_m * phi
            if index == 0:
                angles.append(ca.sumsqr(phi))
            scales += [angle_scale] * 2 + [angle_scale * w] * 2
        walls_by_model.append(ca.sumsqr(wall))
    velocity = rate(bottom)
    acceleration = rate(velocity)
    jerk = rate(acceleration)
    limits = [
        ca.sumsqr(velocity) / machine.max_velocity_m_s**2,
        ca.sumsqr(acceleration) / machine.max_acceleration_m_s2**2,
        ca.sumsqr(jerk) / machine.max_jerk_m_s3**2,
        *(wall / problem.slosh.max_height_m**2 for wall in walls_by_model),
    ]
    if problem.slosh.max_surface_angle_rad is not None:
        # nonlinear: atan2(|x|, -u_z) <= limit iff |x| <= sin(limit) (below the hinge)
        bound = problem.slosh.max_surface_angle_rad
        bound = math.sin(min(bound, 0.5 * math.pi)) if nonlinear else bound
        limits += [angle / bound**2 for angle in angles]
    omega_limit = machine.max_angular_velocity_rad_s
    alpha_limit = machine.max_angular_acceleration_rad_s2
    if omega_limit is not None or alpha_limit is not None:
        full = _rotvec_matrix(rotate) @ despun @ _rz(psi)
        omega = _vee(rate(full), full)
        if omega_limit is not None:
            limits.append(ca.sumsqr(omega) / omega_limit**2)
        if alpha_limit is not None:
            limits.append(ca.sumsqr(rate(omega)) / alpha_limit**2)
    kinematic = [q[0], qd[0], qdd[0]]
    kinematic_rate = [qd[0], qdd[0], qddd[0]]
    length = problem.path.length_m
    scale_x = [length, machine.max_velocity_m_s, machine.max_acceleration_m_s2]
    scale_u = [machine.max_jerk_m_s3]
    x0_kinematic = [0.0, 0.0, 0.0]
    if tilt:
        tilt_rate = omega_limit if omega_limit is not None else DEFAULT_TILT_RATE_RAD_S
        tilt_acceleration = (
            alpha_limit if alpha_limit is not None else DEFAULT_TILT_ACCELERATION_RAD_S2
        )
        spin_rate = ca.dot(axis, tilt_velocity(qd[1:3]))
        kinematic = [q[1:3], qd[1:3], qdd[1:3], chi, *kinematic]
        kinematic_rate = [qd[1:3], qdd[1:3], qddd[1:3], spin_rate, *kinematic_rate]
        limits += [
            ca.sumsqr(q[1:3]) / max(problem.max_tilt_rad, 1e-9) ** 2,
            ca.sumsqr(qd[1:3]) / tilt_rate**2,
            ca.sumsqr(qdd[1:3]) / tilt_acceleration**2,
        ]
        tilt_scale = max(problem.max_tilt_rad, 0.05)
        scale_x = [
            tilt_scale,
            tilt_scale,
            tilt_rate,
            tilt_rate,
            tilt_acceleration,
            tilt_acceleration,
            0.1,
            *scale_x,
        ]
        scale_u = [*scale_u, 10 * tilt_acceleration, 10 * tilt_acceleration]
        x0_kinematic = [0.0] * 7 + x0_kinematic
    # Reorder the tilt states as r, r', r'' (2 each) then chi, then s, s', s''.
    x = ca.vertcat(*kinematic, *states)
    xdot = ca.vertcat(*kinematic_rate, *derivatives)
    u = qddd[1:3] if tilt else ca.SX(0, 1)
    u = ca.vertcat(qddd[0], u)
    rest_of = ca.Function("rest", [x], [ca.vertcat(*rests)])
    start = np.asarray(rest_of(np.zeros(x.numel()))).ravel()
    for index in range(len(rests)):
        x0_slosh += [start[2 * index], start[2 * index + 1], 0.0, 0.0]
    dynamics = ca.Function("dynamics", [x, u], [xdot])
    path_limits = ca.Function("path_limits", [x, u], [ca.vertcat(*limits)])
    residual = ca.Function("residual", [x], [ca.vertcat(*amplitudes)])
    bounds = ca.SX.sym("b", len(walls))
    # rows <= 0, in units of (max residual / e_n)^2 (squared for the determinant)
    unit = ca.DM((problem.slosh.max_residual_height_m / np.asarray(walls)) ** 2)
    if nonlinear:
        rows = []
        for index, matrix in enumerate(matrices):
            square = bounds[index] ** 2
            rows += [
                (matrix[0] - square) / unit[index],
                (matrix[1] - square) / unit[index],
                (matrix[2] ** 2 - (square - matrix[0]) * (square - matrix[1])) / unit[index] ** 2,
            ]
        residual_rows = ca.Function("residual_rows", [x, bounds], [ca.vertcat(*rows)])
    else:  # |(A_n, B_n)|^2 <= b_n^2
        amplitude = ca.vertcat(*amplitudes)
        residual_rows = ca.Function("residual_rows", [x, bounds], [(amplitude - bounds**2) / unit])
    wall_height = ca.Function("wall", [x], [ca.sqrt(ca.vertcat(*walls_by_model))])
    return _Model(
        dynamics,
        path_limits,
        residual,
        residual_rows,
        wall_height,
        np.asarray(walls),
        np.asarray(x0_kinematic + x0_slosh),
        np.asarray(scale_x + scales),
        np.asarray(scale_u),
        tilt,
    )


def _rk4_step(model: _Model) -> Any:
    """One classical Runge-Kutta step of length h with the control held (Butcher (2016) §23)."""
    x = ca.SX.sym("x", model.nx)
    u = ca.SX.sym("u", model.nu)
    h = ca.SX.sym("h")
    f = model.dynamics
    k1 = f(x, u)
    k2 = f(x + 0.5 * h * k1, u)
    k3 = f(x + 0.5 * h * k2, u)
    k4 = f(x + h * k3, u)
    return ca.Function("step", [x, u, h], [x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)])


def speed_profile_controls(
    problem: PathProblem, level: float, interval_s: float
) -> tuple[float, FloatArray]:
    """A rest-to-rest timing of the path at the acceleration ``level`` [m/s^2]: its jerks on
    equal intervals of about ``interval_s``, and its duration [s].

    The phase-plane profile (Bobrow, Dubowsky & Gibson, Int. J. Robot. Res. 4 (1985) 3-17,
    doi:10.1177/027836498500400301) of s' under the speed limit
    min(vmax / |dB/ds|, sqrt(level / |d2B/ds2|), (jerk level / |d3B/ds3|)^(1/3)) over the
    reference point and the highest bob's rest point B, reached from rest and braked to rest
    at ``level``; then its speed averaged over the first mode's longest period, a moving
    average whose spectrum has a zero at that frequency (the residual of a move filtered so is
    small: Singer & Seering (1990), doi:10.1115/1.2894142), and its jerks taken from the
    sampled acceleration.
    """
    path, machine = problem.path, problem.machine
    length = path.length_m
    s = np.linspace(0.0, length, max(math.ceil(length / GEOMETRY_SPACING_M), 64) + 1)
    spacing = s[1] - s[0]
    axis = path.orientation(s).apply([0.0, 0.0, 1.0])
    highest = max(m.bob_height_m for model in problem.models() for m in model.modes)
    limit = np.full(s.size, MAX_PARAMETER_RATE_M_S)
    jerk_level = machine.max_jerk_m_s3 * level / machine.max_acceleration_m_s2
    for point in (path.position(s), path.position(s) + highest * axis):
        first = np.gradient(point, spacing, axis=0)
        second = np.gradient(first, spacing, axis=0)
        third = np.gradient(second, spacing, axis=0)
        norms = [np.linalg.norm(d, axis=1) + 1e-12 for d in (first, second, third)]
        limit = np.minimum(limit, machine.max_velocity_m_s / norms[0])
        limit = np.minimum(limit, np.sqrt(level / norms[1]))
        limit = np.minimum(limit, np.cbrt(jerk_level / norms[2]))
    speed = limit.copy()
    speed[0] = speed[-1] = 0.0
    for i in range(1, s.size):
        speed[i] = min(speed[i], math.sqrt(speed[i - 1] ** 2 + 2 * level * spacing))
    for i in range(s.size - 2, -1, -1):
        speed[i] = min(speed[i], math.sqrt(speed[i + 1] ** 2 + 2 * level * spacing))
    times = np.concatenate(([0.0], np.cumsum(2 * spacing / (speed[1:] + speed[:-1]))))
    period = max(2 * math.pi / model.modes[0].omega_rad_s for model in problem.models())
    width = max(round(period / interval_s), 1)
    count = math.ceil(times[-1] / interval_s) + width
    h = (times[-1] + width * interval_s) / count
    grid = np.arange(count + 1) * h
    rate = np.gradient(np.interp(grid, times, s), h)
    rate[0] = rate[-1] = 0.0
    # The moving average delays the move by width / 2 samples and spreads it by width.
    padded = np.concatenate((np.zeros(width), rate))
    averaged = np.convolve(padded, np.ones(width) / width)[width : width + count + 1]
    acceleration = np.gradient(averaged, h)
    acceleration[0] = acceleration[-1] = 0.0
    jerk = np.diff(acceleration) / h
    # s(T) of a piecewise-constant jerk from rest: sum u_k h^3 ((N - k)^3 - (N - k - 1)^3) / 6
    remaining = count - np.arange(count)
    reach = float(np.sum(jerk * h**3 * (remaining**3 - (remaining - 1) ** 3) / 6.0))
    return float(count * h), np.asarray(jerk * length / reach)


def _simulate(model: _Model, step: Any, controls: FloatArray, duration_s: float) -> FloatArray:
    count = controls.shape[1]
    trajectory = step.mapaccum("simulate", count)
    states = trajectory(model.x0, controls, duration_s / count)
    return np.asarray(np.c_[model.x0, np.asarray(states)], dtype=float)


def _feasible(
    model: _Model, problem: PathProblem, states: FloatArray, controls: FloatArray
) -> bool:
    limits = np.asarray(model.path_limits.map(controls.shape[1])(states[:, :-1], controls))
    later = np.asarray(model.path_limits.map(controls.shape[1])(states[:, 1:], controls))
    amplitude = np.sqrt(np.asarray(model.residual(states[:, -1])).ravel())
    residual = _band_residual(model, problem, amplitude)
    return bool(
        max(limits.max(), later.max()) <= 1.0 and residual <= problem.slosh.max_residual_height_m
    )


def _band_residual(model: _Model, problem: PathProblem, amplitude: FloatArray) -> float:
    """The largest over the band of sum_n e_n a_n (a_n: ``amplitude``, the residual
    amplitude of every mode)."""
    per_model = len(problem.models()[0].modes)
    weighted = (model.walls * amplitude).reshape(-1, per_model)
    return float(np.max(np.sum(weighted, axis=1)))


def initial_guess(
    model: _Model, problem: PathProblem, step: Any, interval_s: float, max_tries: int = 40
) -> tuple[float, FloatArray, FloatArray]:
    """`speed_profile_controls` at an acceleration level lowered by 15 % steps (from the
    smaller of amax and the quasi-static level g h_max / e_1 of the first mode) until the
    simulated move meets every limit.

    Returns the duration [s], the states (nx, N + 1) and the controls (nu, N)."""
    first = problem.models()[0].modes[0]
    level = min(
        problem.machine.max_acceleration_m_s2,
        GRAVITY_M_S2 * problem.slosh.max_height_m / first.wall_elevation_factor_m,
    )
    for _ in range(max_tries):
        duration, jerk = speed_profile_controls(problem, level, interval_s)
        controls = np.zeros((model.nu, jerk.size))
        controls[0] = jerk
        states = _simulate(model, step, controls, duration)
        if _feasible(model, problem, states, controls):
            return duration, states, controls
        level *= 0.85
    raise RuntimeError(f"no feasible initial timing down to {level:.3g} m/s^2")


def _solve(
    model: _Model,
    problem: PathProblem,
    step: Any,
    duration: float,
    states: FloatArray,
    controls: FloatArray,
    max_iterations: int,
    print_level: int,
    warm: bool = False,
) -> tuple[float, FloatArray, FloatArray, str, bool]:
    """Multiple shooting NLP from the guess; returns T, states, controls, status, success.
    ``warm``: the guess is a solution of the same problem on a coarser grid, so IPOPT starts
    with a small barrier parameter and pushes the guess off its bounds by little (its
    initialisation: Waechter & Biegler 2006). With the default barrier, 0.1, the first step
    from LE_3D's coarse tilted solution raised the constraint violation from 6e-2 to 3e3."""
    nx, nu, count = model.nx, model.nu, controls.shape[1]
    sx, su = model.scale_x[:, None], model.scale_u[:, None]
    n_modes = model.walls.size
    xs = ca.MX.sym("X", nx, count + 1)
    us = ca.MX.sym("U", nu, count)
    t = ca.MX.sym("T")
    bounds = ca.MX.sym("b", n_modes)
    big_x, big_u = xs * ca.DM(np.repeat(sx, count + 1, 1)), us * ca.DM(np.repeat(su, count, 1))
    h = t / count
    following = step.map(count)(big_x[:, :-1], big_u, ca.repmat(h, 1, count))
    defects = (following - big_x[:, 1:]) / ca.DM(np.repeat(sx, count, 1))
    limits = model.path_limits.map(count)
    before, after = limits(big_x[:, :-1], big_u), limits(big_x[:, 1:], big_u)
    final = big_x[:, -1]
    # every mode's residual amplitude <= b_n, b_n >= 0 (`_Model.residual_rows`)
    residual_rows = model.residual_rows(final, bounds)
    per_model = len(problem.models()[0].modes)
    weighted = ca.reshape(ca.DM(model.walls) * bounds, per_model, -1)
    band = ca.sum1(weighted).T / problem.slosh.max_residual_height_m
    kinematic = 10 if model.tilt else 3
    # At rest at T: everything but s (fixed to L) and chi (free), r, r', r'', s', s'' = 0.
    rest_index = [i for i in range(kinematic) if i not in (kinematic - 3, 6)]
    end_rows = ca.vertcat(
        (final[kinematic - 3] - problem.path.length_m) / problem.path.length_m,
        final[rest_index] / ca.DM(model.scale_x[rest_index]),
    )
    g = ca.vertcat(ca.vec(defects), ca.vec(before), ca.vec(after), residual_rows, band, end_rows)
    n_defects, n_limits = nx * count, 2 * before.numel()
    n_rows = residual_rows.numel()
    lbg = np.r_[np.zeros(n_defects), np.full(n_limits, -np.inf), np.full(n_rows, -np.inf)]
    lbg = np.r_[lbg, np.full(band.numel(), -np.inf), np.zeros(end_rows.numel())]
    ubg = np.r_[np.zeros(n_defects), np.ones(n_limits), np.zeros(n_rows)]
    ubg = np.r_[ubg, np.ones(band.numel()), np.zeros(end_rows.numel())]
    variables = ca.vertcat(ca.vec(xs), ca.vec(us), t, bounds)
    lbx_x = np.full((nx, count + 1), -np.inf)
    ubx_x = np.full((nx, count + 1), np.inf)
    s_row = kinematic - 3
    lbx_x[s_row], ubx_x[s_row] = 0.0, 1.0
    lbx_x[s_row + 1], ubx_x[s_row + 1] = 0.0, MAX_PARAMETER_RATE_M_S / model.scale_x[s_row + 1]
    lbx_x[:, 0] = ubx_x[:, 0] = model.x0 / model.scale_x
    lbx = np.r_[lbx_x.ravel(order="F"), np.full(nu * count, -np.inf), 1e-3, np.zeros(n_modes)]
    ubx = np.r_[
        ubx_x.ravel(order="F"), np.full(nu * count, np.inf), np.inf, np.full(n_modes, np.inf)
    ]
    amplitude0 = np.sqrt(np.asarray(model.residual(states[:, -1])).ravel())
    guess = np.r_[
        (states / sx).ravel(order="F"),
        (controls / su).ravel(order="F"),
        duration,
        amplitude0 * 1.01 + 1e-6,
    ]
    options: dict[str, Any] = {
        "ipopt.print_level": print_level,
        "print_time": False,
        "ipopt.max_iter": max_iterations,
        "ipopt.tol": 1e-8,
        "ipopt.acceptable_tol": 1e-6,
        "ipopt.constr_viol_tol": 1e-9,
        "ipopt.mu_strategy": "adaptive",
    }
    if warm:
        options.update(
            {"ipopt.mu_init": WARM_MU, "ipopt.bound_push": WARM_PUSH, "ipopt.bound_frac": WARM_PUSH}
        )
    program: dict[str, Any] = {"x": variables, "f": t, "g": g}
    solver = ca.nlpsol("reference", "ipopt", program, options)
    solution = solver(x0=guess, lbx=lbx, ubx=ubx, lbg=lbg, ubg=ubg)
    stats = solver.stats()
    values = np.asarray(solution["x"]).ravel()
    x_end = nx * (count + 1)
    solved_states = values[:x_end].reshape((nx, count + 1), order="F") * sx
    solved_controls = values[x_end : x_end + nu * count].reshape((nu, count), order="F") * su
    return (
        float(values[x_end + nu * count]),
        solved_states,
        solved_controls,
        str(stats["return_status"]),
        bool(stats["success"]),
    )


def _regrid(states: FloatArray, controls: FloatArray, count: int) -> tuple[FloatArray, FloatArray]:
    """States (linear interpolation) and piecewise-constant controls on ``count`` equal
    intervals of the same normalised time."""
    old = controls.shape[1]
    nodes_old, nodes_new = np.linspace(0.0, 1.0, old + 1), np.linspace(0.0, 1.0, count + 1)
    moved = np.array([np.interp(nodes_new, nodes_old, row) for row in states])
    middles = (np.arange(count) + 0.5) / count
    held = controls[:, np.minimum((middles * old).astype(int), old - 1)]
    return moved, held


@dataclass(frozen=True, eq=False)
class ReferenceSolution:
    """The minimum-time solution with its trajectory.

    Parameters
    ----------
    optimum : ReferenceOptimum
        The figures.
    states : ndarray
        States at the N + 1 nodes (`_model`'s layout, SI units).
    controls : ndarray
        Jerks of s (and r) on the N intervals.
    """

    optimum: ReferenceOptimum
    states: FloatArray
    controls: FloatArray

    def pose_samples(self, problem: PathProblem, sample_period_s: float) -> PoseTrajectory:
        """The solution sampled at t = k Ts (the planner's export: `sample_path`'s grid, held
        at the end after T): s and r integrated exactly over each interval of constant jerk
        from the node states; pose R = Rot(r) R_path(s), bottom p(s) + c (R_path e_z - R e_z)
        (module docstring)."""
        duration, count = self.optimum.duration_s, self.controls.shape[1]
        h = duration / count
        samples = steps_to_reach(duration, sample_period_s)
        t = np.minimum(np.arange(samples + 1) * sample_period_s, duration)
        index = np.minimum((t / h).astype(int), count - 1)
        tau = t - index * h

        def integrate(rows: tuple[int, int, int], control: int) -> FloatArray:
            x, v, a = (self.states[row, index] for row in rows)
            jerk = self.controls[control, index]
            return np.asarray(x + v * tau + a * tau**2 / 2 + jerk * tau**3 / 6)

        path, tilt = problem.path, self.optimum.tilt
        # rows: (r_x, r_y, r_x', r_y', r_x'', r_y'', chi, s, s', s'') tilted, (s, s', s'')
        s = np.clip(integrate((7, 8, 9) if tilt else (0, 1, 2), 0), 0.0, path.length_m)
        s[-1] = path.length_m
        rotation = path.orientation(s)
        position = path.position(s)
        if tilt:
            vector = np.c_[integrate((0, 2, 4), 1), integrate((1, 3, 5), 2), np.zeros(t.size)]
            vector[-1] = 0.0
            upright = rotation.apply([0.0, 0.0, 1.0])
            rotation = Rotation.from_rotvec(vector) * rotation
            centre = problem.tilt_centre_height_m
            position = position + centre * (upright - rotation.apply([0.0, 0.0, 1.0]))
        grid = np.arange(samples + 1, dtype=float) * sample_period_s
        # PoseTrajectory makes the quaternions sign-continuous.
        return PoseTrajectory(grid, np.asarray(position, dtype=float), rotation.as_quat())


def reference_optimum(
    problem: PathProblem,
    tilt: bool = False,
    interval_s: float = 4e-3,
    max_iterations: int = 3000,
    print_level: int = 0,
    slosh_model: str = "linear",
) -> ReferenceOptimum:
    """The minimum time of ``problem`` (module docstring), with free tilt when ``tilt``:
    `reference_solution`'s figures."""
    return reference_solution(
        problem, tilt, interval_s, max_iterations, print_level, slosh_model
    ).optimum


def reference_solution(
    problem: PathProblem,
    tilt: bool = False,
    interval_s: float = 4e-3,
    max_iterations: int = 3000,
    print_level: int = 0,
    slosh_model: str = "linear",
) -> ReferenceSolution:
    """The minimum time of ``problem`` (module docstring), with free tilt when ``tilt``.

    Parameters
    ----------
    problem : PathProblem
        Path, limits, model band, tilt settings.
    tilt : bool
        Whether the two tilt angles are decision variables (from the untilted optimum).
    interval_s : float
        Target shooting interval [s]: N = ceil(T_guess / interval_s) for the untilted guess.
    max_iterations : int
        IPOPT iteration limit.
    print_level : int
        IPOPT's print level (0: silent).
    slosh_model : str
        ``"linear"`` (default) or ``"nonlinear"`` (the verification's large-angle pendulum).

    Returns
    -------
    ReferenceSolution
    """
    started = time.perf_counter()
    upright = _model(problem, False, slosh_model)
    upright_step = _rk4_step(upright)
    initial, states, controls = initial_guess(upright, problem, upright_step, interval_s)

    def solve(
        model: _Model, step: Any, duration: float, states: Any, controls: Any, warm: bool = False
    ) -> Any:
        return _solve(
            model, problem, step, duration, states, controls, max_iterations, print_level, warm
        )

    # A coarse grid first: the slowed guess can be several times the optimum, and its grid
    # would then be several times finer than ``interval_s`` at the optimum.
    coarse = min(max(math.ceil(initial / (COARSE_FACTOR * interval_s)), 40), MAX_COARSE)
    duration, states, controls, status, success = solve(
        upright, upright_step, initial, *_regrid(states, controls, coarse)
    )
    count = math.ceil(duration / interval_s)
    duration, states, controls, status, success = solve(
        upright, upright_step, duration, *_regrid(states, controls, count)
    )
    model = upright
    if tilt:
        model = _model(problem, True, slosh_model)
        step = _rk4_step(model)
        tilted_states = np.zeros((model.nx, count + 1))
        tilted_states[7:10] = states[0:3]
        tilted_states[10:] = states[3:]
        tilted_controls = np.zeros((model.nu, count))
        tilted_controls[0] = controls[0]
        # Coarse first again: the tilt shortens the move by a quarter or more.
        coarse = max(math.ceil(duration / (COARSE_FACTOR * interval_s)), 40)
        duration, states, controls, status, success = solve(
            model, step, duration, *_regrid(tilted_states, tilted_controls, coarse)
        )
        # the coarse jerks held on a whole number of intervals each, the states simulated from
        # them: an exact start (interpolated states left IPOPT in restoration on LE_3D)
        repeats = math.ceil(duration / interval_s / controls.shape[1])
        controls = np.repeat(controls, repeats, axis=1)
        states = _simulate(model, step, controls, duration)
        duration, states, controls, status, success = solve(
            model, step, duration, states, controls, warm=True
        )
    walls = np.asarray(model.wall.map(states.shape[1])(states))
    amplitude = np.sqrt(np.maximum(np.asarray(model.residual(states[:, -1])).ravel(), 0.0))
    peak_tilt = float(np.max(np.hypot(states[0], states[1]))) if tilt else 0.0
    optimum = ReferenceOptimum(
        duration,
        status,
        success,
        time.perf_counter() - started,
        controls.shape[1],
        tilt,
        initial,
        float(walls.max()),
        _band_residual(model, problem, amplitude),
        peak_tilt,
        slosh_model,
    )
    return ReferenceSolution(optimum, states, controls)
