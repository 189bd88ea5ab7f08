"""The fused kernel (law sampled inside) against the array kernel and the scalar
discretisation."""

from __future__ import annotations

import numpy as np
import pytest

from sloshkit import UprightCylinder, equivalent_model, get_liquid
from sloshkit.motion import make_law
from sloshkit.motion.sampling import steps_for
from sloshkit.motion.scaling import scaled_velocity_samples, unit_duration_shape
from sloshkit.sim.batch import batch_metrics
from sloshkit.sim.batch_kernel import kernel_rows, law_metrics
from sloshkit.sim.discretisation import velocity_driven_discretisation


@pytest.mark.parametrize("sample_period", [1e-3, 4e-3, 0.05, 0.3])
def test_vectorised_discretisation_equals_scipy_expm(sample_period):
    """The numpy scaling-and-squaring exponential against scipy.linalg.expm of the augmented
    matrix (first-order hold, Franklin, Powell & Workman §6.3.2)."""
    from scipy.linalg import expm

    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, n_modes=5)
    rows = kernel_rows(model, sample_period)
    for row, mode in zip(rows, model.modes, strict=True):
        w, z, length = mode.omega_rad_s, mode.damping_ratio, mode.length_m
        augmented = np.zeros((4, 4))
        augmented[:2, :2] = [[0.0, 1.0], [-(w**2), -2.0 * z * w]]
        augmented[:2, 2] = [-1.0 / length, 2.0 * z * w / length]
        augmented[2, 3] = 1.0
        exponential = expm(augmented * sample_period)
        phi = exponential[:2, :2]
        ramp = exponential[:2, 3] / sample_period
        gamma = phi @ ramp + exponential[:2, 2] - ramp
        expected = np.concatenate((phi.ravel(), gamma, ramp))
        np.testing.assert_allclose(row[:8], expected, rtol=0, atol=1e-13 * np.abs(expected).max())
        scalar = velocity_driven_discretisation(w, z, length, sample_period)
        np.testing.assert_array_equal(np.concatenate([a.ravel() for a in scalar]), row[:8])


@pytest.mark.parametrize("law", ["trapezoidal", "septic", "s-curve"])
@pytest.mark.parametrize("modes", [1, 3, 4])
def test_fused_kernel_equals_sampling_then_array_kernel(law, modes):
    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039, n_modes=modes)
    motion = make_law(
        law,
        0.3,
        duration_s=1.0,
        max_velocity_m_s=1.0,
        max_acceleration_m_s2=4.0,
        max_jerk_m_s3=60.0,
    )
    shape = unit_duration_shape(motion).derivative_pp(1)
    rng = np.random.default_rng(3)
    # unsorted durations, some on the grid (T = k dt), more cases than one block
    durations = np.concatenate(([0.5, 0.7, 0.7005], rng.uniform(0.4, 0.9, 150)))
    dt = 1e-3
    velocity = scaled_velocity_samples(shape, durations, dt, steps_for(durations.max(), dt))
    expected = batch_metrics(model, velocity, durations, dt)
    fused = law_metrics(model, shape, durations, dt, chunk_cases=64)
    for name in (
        "peak_angle_rad",
        "residual_angle_rad",
        "peak_wall_elevation_m",
        "residual_wall_elevation_m",
    ):
        np.testing.assert_allclose(
            getattr(fused, name), getattr(expected, name), rtol=1e-9, atol=1e-15, err_msg=name
        )


def test_sweep_csv_from_arrays_equals_the_rows(tmp_path):
    import csv

    import sloshkit as sk
    from sloshkit.model.modal import model_family

    result = sk.run_sweep(
        model_family(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C")),
        ["quintic", "septic"],
        0.1,
        [0.6, 0.9, 1.4],
        fill_heights_m=[0.02, 0.03],
        max_angle_rad=0.1,
    )
    path = result.to_csv(tmp_path / "sweep.csv")
    with path.open() as stream:
        written = list(csv.DictReader(stream))
    rows = result.rows()
    assert len(written) == len(rows) == 12
    for got, want in zip(written, rows, strict=True):
        assert got == {key: str(value) for key, value in want.items()}


def test_fused_kernel_pads_a_high_order_law_and_single_cases():
    """A degree-9 velocity (10 coefficients, padded to 12 with leading zeros) and blocks of one
    case (the other lanes of the vector repeat it): still equal to sampling + array kernel."""
    from scipy.interpolate import PPoly

    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    # rest to rest: v = tau^2 (1 - tau)^2 q(tau), q of degree 5, is zero at both ends
    coefficients = np.polymul([1.0, -2.0, 1.0, 0.0, 0.0], [0.1, 0.3, 1.0, -2.0, 0.5, 1.0])
    coefficients = 3.0 * coefficients[:, None]
    shape = PPoly(coefficients, np.array([0.0, 1.0]))
    dt = 2e-3
    for durations in (np.array([0.9]), np.array([1.3, 0.45, 0.7])):
        velocity = scaled_velocity_samples(shape, durations, dt, steps_for(durations.max(), dt))
        expected = batch_metrics(model, velocity, durations, dt)
        fused = law_metrics(model, shape, durations, dt)
        for name in ("peak_angle_rad", "residual_angle_rad", "peak_wall_elevation_m"):
            np.testing.assert_allclose(
                getattr(fused, name), getattr(expected, name), rtol=1e-9, err_msg=name
            )


def test_fused_kernel_memory_is_bounded_by_the_cases():
    """No velocity array and no time history: the arrays allocated for 20,000 cases of 2 s at
    1 kHz stay far below one (cases x samples) array (336 MB); the compiled loop itself holds
    only 64 lanes of state."""
    import tracemalloc

    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    shape = unit_duration_shape(make_law("septic", 0.5, duration_s=1.0)).derivative_pp(1)
    law_metrics(model, shape, np.array([1.0]), 1e-3)  # compiled or loaded before measuring
    tracemalloc.start()
    try:
        law_metrics(model, shape, np.linspace(1.9, 2.1, 20_000), 1e-3)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 10e6


@pytest.mark.parametrize("bad", [0.0, -1.0, np.inf, np.nan])
def test_fused_kernel_refuses_durations_it_cannot_step(bad):
    from sloshkit.errors import InputError

    model = equivalent_model(UprightCylinder(0.0205), get_liquid("water-25C"), 0.039)
    shape = unit_duration_shape(make_law("quintic", 0.1, duration_s=1.0)).derivative_pp(1)
    with pytest.raises(InputError, match="durations"):
        law_metrics(model, shape, np.array([1.0, bad]), 1e-3)
