"""The path programs' linearisation of the drive (`sloshkit.plan.path.program.PathProgram.
jacobians`, `sloshkit.plan.path.axial_turn`) against central differences of the forces."""

from __future__ import annotations

import math

import numpy as np

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.axial_turn import axial_turn
from sloshkit.plan.path.geometry import path_from_waypoints
from sloshkit.plan.path.program import HOLD, PathProgram, ProgramLimits
from sloshkit.plan.path.samples import PathSamples

MODEL = equivalent_model(UprightCylinder(0.049), get_liquid("water-20C"), 0.08)
STEPS, PERIOD_S = 90, 0.01


def _tilting_turn() -> tuple[PathProgram, PathSamples]:
    """A pick-and-place (0.3 m, 0.1 m up, a quarter turn about the vertical) tilted by up to
    about 20 deg about both axes on a smooth timing."""
    path = path_from_waypoints(
        [[0.0, 0.0, 0.0], [0.3, 0.0, 0.1]], yaw_rad=[0.0, math.pi / 2], name="pick"
    )
    limits = ProgramLimits(2.0, 10.0, 100.0, None, None, 0.015, 0.002, max_tilt_rad=0.6)
    program = PathProgram(path, [MODEL], limits, PERIOD_S, tilt=True)
    tau = np.linspace(0.0, 1.0, STEPS + 1)
    s = path.length_m * tau**3 * (10 - 15 * tau + 6 * tau**2)
    bump = np.sin(np.pi * tau) ** 3
    tilt = np.column_stack((0.35 * bump * np.sin(2 * np.pi * tau), 0.3 * bump))
    return program, PathSamples(s, tilt, PERIOD_S)


def _predicted(bands: list, blocks: list, turn_blocks: list, direction: np.ndarray) -> tuple:
    """The forces' and N's rates' change along ``direction`` (one value per variable) that the
    bands (and the axial turn's pseudo-block) predict."""
    n = blocks[0][1].shape[0]
    force = np.zeros(bands[0].force.shape[1:])
    rates = np.zeros((n, 4))
    for band, dz in [*zip(bands, (dz for _, dz in blocks), strict=True), *turn_blocks]:
        moved = dz @ direction
        for offset in (-1, 0, 1):
            source = np.arange(n) + offset
            inside = (source >= 0) & (source < n)
            force[:, inside] += band.force[offset + 1][:, inside] * moved[source[inside]][:, None]
            rates[inside] += band.rates[offset + 1][inside] * moved[source[inside]][:, None]
    return force, rates


def test_the_bands_and_the_axial_turn_predict_the_drive_of_a_tilting_move():
    program, samples = _tilting_turn()
    bands = program.jacobians(samples)
    n = STEPS + 1 + HOLD
    # the variables: every sample's s and two tilt angles, then one turn per segment start
    starts = [40, 80]
    columns = 3 * (STEPS + 1) + len(starts)
    blocks = []
    for block in range(3):
        dz = np.zeros((n, columns))
        dz[np.arange(1, STEPS), block * (STEPS + 1) + np.arange(1, STEPS)] = 1.0
        blocks.append((bands[block], dz))
    force, kinematic = program.forces(program_samples(samples))
    turn = axial_turn(blocks, force, kinematic["tilt_rates"], starts, 3 * (STEPS + 1))
    assert turn is not None  # the axis tilts while the container turns: N turns
    rng = np.random.default_rng(7)
    direction = np.zeros(columns)
    direction[: STEPS + 1] = 1e-6 * rng.standard_normal(STEPS + 1)
    direction[STEPS + 1 : 3 * (STEPS + 1)] = 1e-5 * rng.standard_normal(2 * (STEPS + 1))
    # the segments' turns as their equality rows tie them to the samples
    direction[3 * (STEPS + 1) :] = turn.starts @ direction
    moved = [dz @ direction for _, dz in blocks]
    forward = PathSamples(
        samples.s_m + moved[0][: STEPS + 1],
        samples.tilt_rad + np.column_stack((moved[1], moved[2]))[: STEPS + 1],
        PERIOD_S,
    )
    backward = PathSamples(
        samples.s_m - moved[0][: STEPS + 1],
        samples.tilt_rad - np.column_stack((moved[1], moved[2]))[: STEPS + 1],
        PERIOD_S,
    )
    (force_up, kinematic_up), (force_down, kinematic_down) = map(
        program.forces, (program_samples(forward), program_samples(backward))
    )
    exact_force = 0.5 * (force_up - force_down)
    exact_rates = 0.5 * (kinematic_up["tilt_rates"] - kinematic_down["tilt_rates"])
    banded_force, banded_rates = _predicted(bands, blocks, [], direction)
    full_force, full_rates = _predicted(bands, blocks, turn.blocks, direction)
    # the low-frequency part the pendulums respond to: the forces summed over the move
    exact_sum = np.cumsum(exact_force, axis=1)
    error_full = np.abs(np.cumsum(full_force, axis=1) - exact_sum).max()
    error_banded = np.abs(np.cumsum(banded_force, axis=1) - exact_sum).max()
    scale = np.abs(exact_sum).max()
    assert error_full < 1e-4 * scale
    assert error_banded > 10 * error_full  # the turn is what the bands alone leave out
    np.testing.assert_allclose(full_rates, exact_rates, atol=1e-5 * np.abs(exact_rates).max())
    assert np.abs(banded_rates - exact_rates).max() > 10 * np.abs(full_rates - exact_rates).max()


def program_samples(samples: PathSamples) -> PathSamples:
    """The samples as `PathProgram.jacobians` sees them: held at rest `HOLD` samples after the
    move."""
    return PathSamples(
        np.concatenate((samples.s_m, np.repeat(samples.s_m[-1:], HOLD))),
        np.concatenate((samples.tilt_rad, np.repeat(samples.tilt_rad[-1:], HOLD, axis=0))),
        samples.period_s,
    )


def test_an_upright_move_has_no_axial_turn():
    program, samples = _tilting_turn()
    upright = PathSamples(samples.s_m, np.zeros_like(samples.tilt_rad), PERIOD_S)
    bands = program.jacobians(upright)
    n = STEPS + 1 + HOLD
    dz = np.zeros((n, STEPS + 1))
    dz[np.arange(1, STEPS), np.arange(1, STEPS)] = 1.0
    force, kinematic = program.forces(program_samples(upright))
    # only the s block: the container turns about the vertical, its own axis
    turn = axial_turn([(bands[0], dz)], force, kinematic["tilt_rates"], [], STEPS)
    assert turn is None
