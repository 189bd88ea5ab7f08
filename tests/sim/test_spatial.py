"""3-D slosh model: closed forms, invariances, the 1-D limit, energy and validity warnings."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from sloshkit.errors import ValidityWarning
from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion.laws import quintic, septic, trapezoidal
from sloshkit.motion.pose_builders import (
    concatenate,
    poses_from_law,
    poses_from_path,
    poses_from_rotation,
)
from sloshkit.motion.poses import PoseTrajectory
from sloshkit.sim.simulate import simulate
from sloshkit.sim.spatial import simulate_spatial


@pytest.fixture(scope="module")
def model() -> SloshModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return equivalent_model(
            UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 3, damping_ratio=0.0066
        )


def _quiet(*args: object, **kwargs: object):  # type: ignore[no-untyped-def]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return simulate_spatial(*args, **kwargs)  # type: ignore[arg-type]


@pytest.mark.parametrize("nonlinear", [False, True])
def test_static_tilt_gives_the_tilted_flat_surface_exactly(
    model: SloshModel, nonlinear: bool
) -> None:
    psi = math.radians(25.0)
    tilt = Rotation.from_rotvec([0.0, psi, 0.0]).as_quat()
    poses = PoseTrajectory(np.linspace(0, 1, 501), np.zeros((501, 3)), np.tile(tilt, (501, 1)))
    response = _quiet(model, poses, nonlinear=nonlinear, height_mapping="planar")
    radius = model.radius_m
    assert np.allclose(response.slosh_height_m, radius * math.tan(psi), rtol=1e-9)
    # the high side is +x in the container frame (axis leaning towards +x)
    assert np.allclose(response.wall_elevation_m(0.0), radius * math.tan(psi), rtol=1e-9)
    assert np.allclose(response.wall_elevation_m(math.pi / 2), 0.0, atol=1e-12)
    assert np.allclose(response.surface_tilt_rad[:, 0], psi, rtol=1e-9)
    assert response.residual_slosh_height_m == pytest.approx(0.0, abs=1e-12)


def test_slow_tilt_ends_in_the_flat_surface(model: SloshModel) -> None:
    psi = math.radians(20.0)
    poses = poses_from_rotation(septic(psi, 4.0), (1, 0, 0), sample_period_s=0.002)
    response = _quiet(model, poses, settle_time_s=1.0, height_mapping="planar")
    # tilt about +x lifts the -y wall
    end = response.wall_elevation_m(-math.pi / 2)[-1]
    assert end == pytest.approx(model.radius_m * math.tan(psi), rel=5e-3)


def test_spin_about_the_own_axis_gives_no_slosh(model: SloshModel) -> None:
    poses = poses_from_rotation(septic(6 * math.pi, 1.5), (0, 0, 1), sample_period_s=0.002)
    for nonlinear in (False, True):
        response = _quiet(model, poses, nonlinear=nonlinear)
        assert response.peak_slosh_height_m < 1e-12
        assert response.drive.spin_angle_rad[-1] == pytest.approx(6 * math.pi, rel=1e-4)


@pytest.mark.parametrize("law_name", ["septic", "trapezoidal"])
def test_a_1d_law_as_poses_equals_the_1d_simulation(model: SloshModel, law_name: str) -> None:
    """Exact data (no smoothing) reproduces the 1-D model to the discretisation error; the
    default 25 Hz differentiator smooths the acceleration jumps of the trapezoid (a few %)."""
    law = septic(0.3, 1.2) if law_name == "septic" else trapezoidal(0.3, duration_s=1.2)
    one_d = simulate(model, law, kind="linear", sample_period_s=1e-3, settle_time_s=1.0)
    smoothed = 2e-3 if law_name == "septic" else 5e-2
    for cutoff, tolerance in ((None, 2e-4), (25.0, smoothed)):
        response = _quiet(
            model, poses_from_law(law), settle_time_s=1.0, sample_period_s=1e-3, cutoff_hz=cutoff
        )
        assert response.time_s.size == one_d.time_s.size
        scale = np.max(np.abs(one_d.angle_rad), axis=1, keepdims=True)
        error = np.max(np.abs(response.angle_rad[:, :, 0] - one_d.angle_rad), axis=1, keepdims=True)
        assert np.all(error < tolerance * scale)
        assert np.max(np.abs(response.angle_rad[:, :, 1])) < 1e-12
        assert response.residual_angle_rad == pytest.approx(one_d.residual_angle_rad, rel=tolerance)
        assert np.allclose(
            response.wall_elevation_m(0.0), one_d.wall_elevation_m, atol=tolerance * 0.02
        )


def test_circular_motion_at_resonance_builds_a_swirl(model: SloshModel) -> None:
    omega = model.modes[0].omega_rad_s
    dt, radius = 0.002, 0.001
    t = np.arange(0.0, 12 * 2 * math.pi / omega, dt)
    ramp = np.minimum(t / (2 * math.pi / omega), 1.0) ** 3  # smooth start from rest
    position = radius * np.column_stack(
        (ramp * np.cos(omega * t) - ramp, ramp * np.sin(omega * t), 0 * t)
    )
    poses = PoseTrajectory(t, position, np.tile([0, 0, 0, 1.0], (t.size, 1)))
    response = _quiet(model, poses, settle_time_s=0.0)
    angle, rate = response.angle_rad[0], response.rate_rad_s[0]
    magnitude = np.hypot(angle[:, 0], angle[:, 1])
    period = round(2 * math.pi / omega / dt)
    late, early = magnitude[-period:], magnitude[5 * period : 6 * period]
    assert late.mean() > 1.6 * early.mean()  # grows (linearly, undamped limit)
    assert late.min() > 0.9 * late.max()  # rotary: |theta| nearly constant over a cycle
    swirl = angle[:, 0] * rate[:, 1] - angle[:, 1] * rate[:, 0]
    assert np.all(swirl[-period:] > 0.0)  # turns with the drive (counter-clockwise)


def test_linear_and_nonlinear_agree_at_small_amplitude(model: SloshModel) -> None:
    law = quintic(0.01, 1.0)
    path = poses_from_path(
        lambda u: np.column_stack((0.02 * np.sin(np.pi * u), 0.01 * u, 0.005 * u)), law
    )
    tilt = poses_from_rotation(septic(math.radians(2), 0.5), (1, 1, 0), sample_period_s=1e-3)
    poses = concatenate([path, tilt])
    linear = _quiet(model, poses, settle_time_s=0.5)
    nonlinear = _quiet(model, poses, settle_time_s=0.5, nonlinear=True)
    peak = linear.peak_slosh_height_m
    assert peak > 1e-4
    assert np.max(np.abs(linear.slosh_height_m - nonlinear.slosh_height_m)) < 0.01 * peak


def _rich_motion() -> PoseTrajectory:
    law = septic(1.0, 3.0)

    def path(u: np.ndarray) -> np.ndarray:
        return np.column_stack((0.1 * np.sin(2 * np.pi * u), 0.1 * u, 0.05 * np.sin(np.pi * u)))

    def orientation(u: np.ndarray) -> Rotation:
        return Rotation.from_euler("zx", np.column_stack((3 * u, 0.3 * np.sin(np.pi * u))))

    return poses_from_path(path, law, sample_period_s=2e-3, orientation=orientation)


@pytest.mark.parametrize("nonlinear", [False, True])
def test_frame_invariance(model: SloshModel, nonlinear: bool) -> None:
    poses = _rich_motion()
    turned = poses.in_world_frame(Rotation.from_euler("z", 0.7), (1.0, -2.0, 0.3))
    first = _quiet(model, poses, nonlinear=nonlinear)
    second = _quiet(model, turned, nonlinear=nonlinear)
    scale = first.peak_slosh_height_m
    assert np.allclose(first.slosh_height_m, second.slosh_height_m, atol=1e-6 * scale)
    assert np.allclose(first.wall_elevation_m(0.3), second.wall_elevation_m(0.3), atol=1e-6 * scale)


def _free_energy(response, model: SloshModel) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Per-mode energy per unit (m L^2) after the motion (container at rest)."""
    after = response.time_s > response.motion_end_s + 0.05
    lengths = np.array([m.length_m for m in model.modes])[:, None]
    force = response.drive.specific_force_m_s2[: len(model.modes), after]
    # the small-angle modes (all of the linear model, the higher ones of the nonlinear one)
    stiffness = -force[..., 2] / lengths  # omega_n^2 |f_z| / (kappa_n g)
    equilibrium = force[..., :2] / -force[..., 2:3]
    offset = response.angle_rad[:, after] - equilibrium
    rate = response.rate_rad_s[:, after]
    small = 0.5 * np.sum(rate**2, axis=-1) + 0.5 * stiffness * np.sum(offset**2, axis=-1)
    # the large-angle ones: kinetic plus the potential of the bob in the specific force
    unit = response.pendulum[:, after]
    rate = response.pendulum_rate[:, after]
    potential = -np.sum(force * unit, axis=-1) / lengths
    large = 0.5 * np.sum(rate**2, axis=-1) + potential
    return np.where(response.large_angle[:, None], large, small)


@settings(max_examples=12, deadline=None)
@given(
    distance=st.floats(0.01, 0.3),
    duration=st.floats(0.3, 1.0),
    heading=st.floats(0.0, 2 * math.pi),
    tilt=st.floats(0.0, 0.4),
    nonlinear=st.booleans(),
)
def test_energy_never_grows_in_free_motion(
    model: SloshModel,
    distance: float,
    duration: float,
    heading: float,
    tilt: float,
    nonlinear: bool,
) -> None:
    law = septic(distance, duration)
    direction = (math.cos(heading), math.sin(heading), 0.3)
    move = poses_from_law(law, direction, sample_period_s=2e-3)
    tilt_move = poses_from_rotation(
        septic(max(tilt, 1e-3), duration),
        (-math.sin(heading), math.cos(heading), 0),
        sample_period_s=2e-3,
    )
    poses = concatenate([move, tilt_move])
    response = _quiet(model, poses, nonlinear=nonlinear, settle_time_s=1.0)
    energy = _free_energy(response, model)
    growth = np.diff(energy, axis=1)
    assert np.all(growth <= 1e-9 * np.max(np.abs(energy)) + 1e-15)


def test_validity_warnings(model: SloshModel) -> None:
    falling = poses_from_law(septic(0.3, 0.3), (0, 0, -1), sample_period_s=1e-3)
    with pytest.warns(ValidityWarning, match="apparent gravity"):
        simulate_spatial(model, falling)
    shake = poses_from_law(septic(0.3, 0.5), sample_period_s=1e-3)
    with pytest.warns(ValidityWarning, match="spill"):
        simulate_spatial(model, shake, wall_height_m=0.09)
    upside = poses_from_rotation(septic(math.radians(80), 2.0), sample_period_s=1e-3)
    with pytest.warns(ValidityWarning, match="tilts"):
        simulate_spatial(model, upside)


def test_response_protocol(model: SloshModel, tmp_path) -> None:  # type: ignore[no-untyped-def]
    response = _quiet(model, _rich_motion())
    metrics = response.to_dict()
    for key in (
        "duration_s",
        "peak_slosh_height_m",
        "residual_slosh_height_m",
        "peak_angle_deg",
        "residual_angle_deg",
    ):
        assert math.isfinite(float(metrics[key]))
    assert metrics["peak_slosh_height_m"] == pytest.approx(np.max(response.slosh_height_m))
    columns = response.columns()
    assert {"t_s", "slosh_height_m", "surface_tilt_x_rad", "surface_tilt_y_rad"} <= set(columns)
    path = response.to_csv(tmp_path / "out.csv")
    header = path.read_text().splitlines()[0].split(",")
    assert header[:2] == ["t_s", "x_m"]
    assert response.slosh_force_n.shape == (response.time_s.size, 3)


def test_plot_draws_path_and_height(model: SloshModel, tmp_path) -> None:  # type: ignore[no-untyped-def]
    response = _quiet(model, _rich_motion())
    figure = response.plot(path=tmp_path / "spatial.png", limit_m=0.01)
    assert len(figure.axes) == 2
    assert (tmp_path / "spatial.png").stat().st_size > 1000


@pytest.mark.parametrize("mapping", ["modal", "planar"])
def test_batch_metrics_equal_single_simulations(model: SloshModel, mapping: str) -> None:
    from sloshkit.sim.spatial_batch import spatial_batch_metrics

    cases = [
        _rich_motion(),
        poses_from_law(septic(0.2, 0.8), (0, 1, 0), sample_period_s=2e-3),
        poses_from_rotation(septic(0.3, 1.0), (1, 0, 0), sample_period_s=2e-3),
    ]
    batch = spatial_batch_metrics(model, cases, settle_time_s=0.5, height_mapping=mapping)  # type: ignore[arg-type]
    for index, poses in enumerate(cases):
        single = _quiet(model, poses, settle_time_s=0.5, height_mapping=mapping)
        assert batch.peak_slosh_height_m[index] == pytest.approx(
            single.peak_slosh_height_m, rel=1e-12
        )
        assert batch.peak_angle_rad[index] == pytest.approx(single.peak_angle_rad, rel=1e-12)
        assert batch.residual_slosh_height_m[index] == pytest.approx(
            single.residual_slosh_height_m, rel=1e-9
        )
        assert batch.residual_angle_rad[index] == pytest.approx(single.residual_angle_rad, rel=1e-9)


def test_coarse_pose_files_and_many_modes_stay_stable() -> None:
    """50 Hz poses, 8 modes (omega_8 h > 2.8 without sub-steps): nonlinear = linear when small."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        many = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 8)
    poses = poses_from_law(septic(0.05, 1.0), sample_period_s=0.02)
    linear = _quiet(many, poses)
    nonlinear = _quiet(many, poses, nonlinear=True)
    assert linear.time_s.size == nonlinear.time_s.size
    peak = linear.peak_slosh_height_m
    assert np.max(np.abs(linear.slosh_height_m - nonlinear.slosh_height_m)) < 0.01 * peak


@pytest.mark.parametrize("nonlinear", [False, True])
def test_pitching_about_the_pivot_leaves_the_pendulum_hanging(nonlinear: bool) -> None:
    """Independent closed form for the rotating-frame terms: a frictionless pendulum whose
    hinge only rotates stays vertical in the inertial frame, so its angle to the tilted
    container axis is the tilt itself, theta(t) = psi(t) (gravity and Euler terms balance)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        undamped = equivalent_model(
            UprightCylinder(0.049), get_liquid("water-20C"), 0.08, 1, damping_ratio=0.0
        )
    pivot = undamped.modes[0].pivot_height_m
    # nonlinear: exact at 25 deg; linear: its first-order form, checked at 2 deg
    law = septic(math.radians(25.0 if nonlinear else 2.0), 0.6)
    poses = poses_from_rotation(law, (0, 1, 0), sample_period_s=1e-3, pivot_m=(0, 0, pivot))
    response = _quiet(undamped, poses, nonlinear=nonlinear, settle_time_s=0.5, cutoff_hz=None)
    psi = law.position(response.time_s)
    tolerance = 1e-4 if nonlinear else 2e-3 * psi.max()
    assert np.max(np.abs(response.angle_rad[0, :, 0] - psi)) < tolerance
    assert np.max(np.abs(response.angle_rad[0, :, 1])) < 1e-12


def test_the_nonlinear_model_keeps_the_higher_modes_linear(model: SloshModel) -> None:
    # a hard stop (0.1 m in 0.3 s) swings the second and third modes past 100 deg in the linear
    # model: the nonlinear one is large-angle in the first mode only (LARGE_ANGLE_MODES)
    poses = poses_from_law(septic(0.1, 0.3), (1.0, 0.0, 0.0), sample_period_s=4e-3)
    nonlinear = _quiet(model, poses, nonlinear=True)
    linear = _quiet(model, poses)
    assert nonlinear.large_angle.tolist() == [True, False, False]
    assert not linear.large_angle.any()
    higher = np.abs(linear.angle_rad[1:]).max()
    assert higher > 1.5  # rad: far beyond small angles
    np.testing.assert_allclose(nonlinear.angle_rad[1:], linear.angle_rad[1:], atol=5e-3 * higher)
    first = np.abs(nonlinear.angle_rad[0] - linear.angle_rad[0]).max()
    assert first > 0.1 * np.abs(linear.angle_rad[0]).max()
