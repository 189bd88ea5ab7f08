"""Write the example input files that README.md and docs/how-do-i.md use (synthetic records).

Every file is made by sloshkit's own linear model with a fixed random seed, so the examples run
as written on any machine; they are stand-ins for what a station produces (an axis profile, a
camera's wall-elevation record, a force sensor's record, a robot's poses), not measurements.
Measured 3-D series are in tests/data/measured-3d (MIT licence).

Run from the repository root: python examples/make_example_data.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import sloshkit as sk
from sloshkit.files import write_columns_csv
from sloshkit.motion.pose_builders import poses_from_law

HERE = Path(__file__).resolve().parent
NOISE = np.random.default_rng(20241202)


def record(
    model: sk.SloshModel, motion: sk.Motion, total_s: float, step_s: float
) -> sk.SloshResponse:
    """The response to ``motion`` and the free slosh after it, until ``total_s``."""
    return sk.simulate(
        model, motion, sample_period_s=step_s, settle_time_s=total_s - motion.duration_s
    )


def main() -> None:
    water = sk.get_liquid("water-25C")
    vial_8mm = sk.UprightCylinder(0.008)
    small_vial = sk.equivalent_model(
        vial_8mm,
        sk.get_liquid("water-20C"),
        vial_8mm.fill_height_for_volume(2e-6),
        surface_tension=True,
    )

    # An axis profile as a drive exports it: 150 mm in 0.4 s, millimetres and milliseconds.
    slide = sk.quintic(0.15, 0.4)
    t = np.arange(0.0, 0.4 + 1e-12, 0.002)
    write_columns_csv(
        HERE / "slide-move.csv", {"t [ms]": 1e3 * t, "x [mm]": 1e3 * slide.position(t)}
    )

    # A camera record of the paper's vial: a 0.5 m trapezoid in 1.5 s, then 8.5 s of free slosh.
    paper_vial = sk.equivalent_model(sk.UprightCylinder(0.0205), water, fill_height_m=0.039)
    camera = record(paper_vial, sk.trapezoidal(0.5, duration_s=1.5), 10.0, 0.002)
    eta = camera.wall_elevation_m + 2e-5 * NOISE.standard_normal(camera.time_s.size)
    write_columns_csv(HERE / "decay.csv", {"t": camera.time_s, "eta": eta})

    # The same kind of record for a 2 mL vial, in milliseconds (a high-speed camera's export).
    small = record(small_vial, sk.septic(0.15, 0.8), 4.0, 0.001)
    eta = small.wall_elevation_m + 5e-6 * NOISE.standard_normal(small.time_s.size)
    write_columns_csv(HERE / "vial-decay-ms.csv", {"t [ms]": 1e3 * small.time_s, "eta": eta})

    # A force sensor under a 40 mm bottle (the liquid's force): the move, the free slosh after
    # it; and the move itself.
    bottle = sk.equivalent_model(sk.UprightCylinder(0.04), water, fill_height_m=0.06)
    move = sk.trapezoidal(0.15, duration_s=1.0)
    sensor = record(bottle, move, 10.0, 0.002)
    after = sensor.time_s > move.duration_s
    noise = 0.02 * float(np.max(np.abs(sensor.slosh_force_n[after])))  # 2 % of the free slosh
    # The liquid's lateral force on the container: -m_F x'' plus the slosh (SloshResponse).
    liquid = -bottle.liquid_mass_kg * move.evaluate(sensor.time_s, 2) + sensor.slosh_force_n
    force = liquid + noise * NOISE.standard_normal(sensor.time_s.size)
    write_columns_csv(HERE / "record.csv", {"t": sensor.time_s, "fy": force})
    t = np.arange(0.0, 1.0 + 1e-12, 0.002)
    write_columns_csv(HERE / "record-move.csv", {"t": t, "x": move.position(t)})

    # Robot poses of a 49 mm water cylinder: 0.3 m along x in 1.2 s, upright.
    poses = poses_from_law(sk.quintic(0.3, 1.2), (1.0, 0.0, 0.0), sample_period_s=0.004)
    columns = {"t": poses.time_s}
    columns.update(zip("xyz", poses.position_m.T, strict=True))
    columns.update(zip(("qx", "qy", "qz", "qw"), poses.quaternion_xyzw.T, strict=True))
    write_columns_csv(HERE / "robot-poses.csv", columns)


if __name__ == "__main__":
    main()
