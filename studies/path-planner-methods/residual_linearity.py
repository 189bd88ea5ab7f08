"""How far the path program's linearisation of the residual holds, with the large-angle
pendulums the verification simulates and with the small-angle ones the tilted search starts
with (`sloshkit.plan.path.pendulums.linear_track`).

On the benchmark's TRD_2D case (15 mm / 2 mm, 2 m/s, 10 m/s^2, 100 m/s^3, 4 ms, tilt up to
30 deg): the upright minimum-time splines, then one tilted program's step from them (trust
region 0.3 % of the path's length, 0.43 deg of tilt per coefficient). Along that step,
scaled by alpha, each model's exact free-oscillation amplitudes A(alpha) against their tangent
A(0) + alpha A'(0) (A' from alpha = 0.01): the departure as a fraction of the change, for the
whole step and for its timing and tilt parts alone.

Run: ``PYTHONPATH=src python studies/path-planner-methods/residual_linearity.py`` (about a
minute on the 2-core machine).
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from bench_plan3d import reference_cases

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import equivalent_model
from sloshkit.plan.path.minimum_time import shortest
from sloshkit.plan.path.program import PathProgram, ProgramLimits
from sloshkit.plan.path.splines import SplineTiming
from sloshkit.plan.path.starts import capped_start
from sloshkit.plan.path.transcription import SplineTranscription


def main() -> None:
    """Print the departures for both models."""
    model = equivalent_model(
        UprightCylinder(0.049), get_liquid("water-20C"), 0.08, damping_ratio=0.0066
    )
    problem = dict(reference_cases(model))["TRD_2D"]
    machine, slosh = problem.machine, problem.slosh
    limits = ProgramLimits(
        machine.max_velocity_m_s,
        machine.max_acceleration_m_s2,
        machine.max_jerk_m_s3,
        None,
        None,
        slosh.max_height_m,
        slosh.max_residual_height_m,
        max_tilt_rad=problem.max_tilt_rad,
    )

    def transcription(tilt: bool, linear: bool) -> SplineTranscription:
        return SplineTranscription(
            PathProgram(
                problem.path,
                problem.models(),
                limits,
                problem.sample_period_s,
                tilt=tilt,
                linear=linear,
            )
        )

    upright, _, _ = shortest(transcription(False, False), capped_start(problem))
    tilted = transcription(True, False)
    step = tilted.step(upright, tilted.iterate(upright), 3e-3)
    assert step is not None
    print(
        f"upright minimum {upright.steps * problem.sample_period_s:.3f} s; step of "
        f"{step.size:.2g} of the trust region's unit"
    )
    delta_s = step.timing.coefficients_m - upright.coefficients_m
    delta_tilt = step.timing.tilt_rad - upright.tilt_rad
    for linear in (False, True):
        evaluated = transcription(True, linear)
        name = "small-angle" if linear else "large-angle"
        for part, scale_s, scale_tilt in (("both", 1, 1), ("timing", 1, 0), ("tilt", 0, 1)):
            moves = (scale_s * delta_s, scale_tilt * delta_tilt)
            start = _amplitudes(evaluated, upright, moves, 0.0)
            tangent = (_amplitudes(evaluated, upright, moves, 0.01) - start) / 0.01
            cells = []
            for alpha in (1.0, 0.3, 0.1):
                moved = _amplitudes(evaluated, upright, moves, alpha)
                change = np.abs(moved - start).max()
                departure = np.abs(moved - start - alpha * tangent).max()
                cells.append(f"alpha {alpha}: {departure / change:6.1%}")
            print(f"{name:12s} {part:7s} " + "   ".join(cells))


def _amplitudes(
    evaluated: SplineTranscription,
    timing: SplineTiming,
    moves: tuple[np.ndarray, np.ndarray],
    alpha: float,
) -> np.ndarray:
    """The exact free-oscillation amplitudes of ``timing`` moved by alpha ``moves``."""
    moved = SplineTiming(
        timing.coefficients_m + alpha * moves[0], timing.tilt_rad + alpha * moves[1], timing.steps
    )
    return np.asarray(evaluated.iterate(moved).evaluation.amplitude)


if __name__ == "__main__":
    main()
