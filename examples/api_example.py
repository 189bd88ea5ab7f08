"""What a notebook user writes: model a vial, compare two laws, plan the fastest safe move.

Run: .venv/bin/python examples/api_example.py
"""

import math

import sloshkit as sk

vial = sk.UprightCylinder(radius_m=0.0205, wall_height_m=0.060)
model = sk.equivalent_model(
    vial, sk.get_liquid("water-25C"), fill_height_m=0.039, damping_ratio=0.03
)
first = model.modes[0]
print(
    f"f1 = {first.frequency_hz:.3f} Hz, L1 = {1e3 * first.length_m:.2f} mm, "
    f"m1 = {1e3 * first.slosh_mass_kg:.2f} g"
)

for law in (sk.quintic(0.5, 1.5), sk.septic(0.5, 1.5)):
    response = sk.simulate(model, law)
    print(
        f"{law.name:>8}: peak {math.degrees(response.peak_angle_rad):.2f} deg, "
        f"residual {math.degrees(response.residual_angle_rad):.3f} deg"
    )

problem = sk.PlanProblem(
    distance_m=0.5,
    machine=sk.MachineLimits(max_velocity_m_s=1.5, max_acceleration_m_s2=20.0, max_jerk_m_s3=500.0),
    slosh=sk.SloshLimits(max_angle_rad=math.radians(5), max_residual_rad=math.radians(0.25)),
    model=model,
    sample_period_s=0.004,
)
result = sk.plan(problem, method="shaped")
print(f"fastest safe move: {result.chosen.method}, {result.chosen.duration_s:.3f} s")
samples = result.samples()  # dict of arrays at the 4 ms controller period
print(f"{samples['t_s'].size} setpoints, ends at {samples['position_m'][-1]:.4f} m")
