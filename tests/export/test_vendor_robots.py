"""Built-in industrial arms: their URDFs against the manufacturers' published reach (a figure
the data sheets give apart from the link lengths), joint ranges and speeds, and the seed pose."""

from __future__ import annotations

import numpy as np
import pytest

from sloshkit.export.kinematics import load_arm, robot_names

# name: (published reach [m], frame it is measured to, data sheet)
REACH = {
    "lrmate200id": (0.717, "wrist", "FANUC LR Mate 200iD data sheet: reach 717 mm"),
    "irb120": (0.580, "wrist", "ABB IRB 120 product specification: reach 580 mm"),
    "kr6r900": (0.9015, "wrist", "KUKA KR 6 R900 sixx specification: reach 901.5 mm"),
    "tx2_60": (0.670, "flange", "Staubli TX2-60 data sheet: reach 670 mm"),
}
# name: first and last joint ranges [deg] and the fastest joint [deg/s] of the data sheets
RANGES = {
    "lrmate200id": ((-170, 170), (-360, 360), 1000),
    "irb120": ((-165, 165), (-400, 400), 420),
    "kr6r900": ((-170, 170), (-350, 350), 615),
    "tx2_60": ((-180, 180), (-270, 270), 1445),
}


def test_every_industrial_arm_is_built_in() -> None:
    assert set(REACH) <= set(robot_names())


@pytest.mark.parametrize("name", sorted(REACH))
def test_the_stretched_arm_reaches_the_published_reach(name: str) -> None:
    """Largest horizontal distance from the J1 axis to the wrist centre (or the flange) over
    J2 and J3 (Nelder-Mead from a grid of starts, the other joints at zero, the optimum inside
    the joint ranges): the data sheet's reach within 1 mm."""
    from scipy.optimize import minimize

    arm = load_arm(name)
    reach, frame, _ = REACH[name]
    index = 5 if frame == "wrist" else len(arm.chain.links) - 1
    best, where = 0.0, np.zeros(2)
    for start in [(a, b) for a in (-1.0, 0.0, 1.0) for b in (-1.5, 0.0, 1.5)]:
        found = minimize(
            lambda q: -_horizontal(arm, index, q[0], q[1]),
            start,
            method="Nelder-Mead",
            options={"xatol": 1e-7, "fatol": 1e-10},
        )
        if -found.fun > best:
            best, where = -found.fun, found.x
    assert np.all(arm.lower_rad[1:3] <= where) and np.all(where <= arm.upper_rad[1:3])
    assert best == pytest.approx(reach, abs=1e-3)


def _horizontal(arm, index: int, q2: float, q3: float) -> float:
    full = np.zeros(len(arm.chain.links))
    full[np.flatnonzero(arm.chain.active_links_mask)[1:3]] = (q2, q3)
    frame = arm.chain.forward_kinematics(full, full_kinematics=True)[index]
    return float(np.hypot(frame[0, 3], frame[1, 3]))


@pytest.mark.parametrize("name", sorted(RANGES))
def test_joint_ranges_and_speeds_are_the_data_sheets(name: str) -> None:
    arm = load_arm(name)
    first, last, fastest = RANGES[name]
    assert np.degrees([arm.lower_rad[0], arm.upper_rad[0]]) == pytest.approx(first)
    assert np.degrees([arm.lower_rad[-1], arm.upper_rad[-1]]) == pytest.approx(last)
    assert np.degrees(arm.velocity_limit_rad_s.max()) == pytest.approx(fastest)


@pytest.mark.parametrize("name", sorted(RANGES))
def test_the_seed_points_the_flange_down_away_from_singularities(name: str) -> None:
    arm = load_arm(name)
    flange = arm.forward(arm.home_rad[None])[0]
    assert flange[:3, 2] == pytest.approx([0.0, 0.0, -1.0], abs=1e-9)
    assert np.linalg.cond(arm.jacobian(arm.home_rad)) < 30.0
