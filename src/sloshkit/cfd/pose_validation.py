"""CFD of 3-D container motions against the 3-D pendulum model (`sloshkit.sim.spatial`).

A case driven by a `sloshkit.cfd.excitation.PoseExcitation` measures the wall elevation along
the container axis in columns of probes around the circumference (r = 0.98 R); its slosh
height is the largest of them. The model is run on the same pose trajectory (kept in the case
as ``sloshkit-poses.csv``) and read at the same wall angles, so both slosh heights are maxima
over the same columns.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from sloshkit.cfd.analysis import read_finished_signals
from sloshkit.cfd.case import POSE_FILE
from sloshkit.cfd.validation import CfdValidation, comparison_row, require_model_first
from sloshkit.errors import InputError
from sloshkit.io.poses import read_pose_file
from sloshkit.model.modal import SloshModel
from sloshkit.sim.spatial import simulate_spatial


def _correlation(a: np.ndarray, b: np.ndarray) -> float | None:
    if a.size < 3 or np.std(a) == 0.0 or np.std(b) == 0.0:
        return None
    return float(np.corrcoef(a, b)[0, 1])


def validate_poses(model: SloshModel, case: Path) -> CfdValidation:
    """Compare a finished pose-driven case with `sloshkit.sim.spatial.simulate_spatial`.

    Parameters
    ----------
    model : SloshModel
        The equivalent pendulum model of the same container, fill and liquid.
    case : Path
        A case run by ``sloshkit cfd run --excitation poses``.

    Returns
    -------
    CfdValidation
        ``kind`` ``poses``; ``comparison`` (peak slosh height during the motion, residual slosh height after it:
        CFD, model, relative difference), ``correlation`` of the slosh heights,
        ``wall_correlation`` of the wall elevations of every probe column, and the series
        ``time_s``, ``cfd_elevation_m``, ``model_elevation_m`` (slosh heights) for the figure.

    References
    ----------
    De Simone et al. (2024), the seed paper, Fig. 9 (the 1-D version of this comparison).

    Examples
    --------
    >>> from pathlib import Path
    >>> validate_poses(None, Path("no-such-case"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-such-case' is invalid: is not a sloshkit CFD case ...
    """
    require_model_first(model, case)
    case = Path(case)
    signals = read_finished_signals(case)
    pose_path = case / POSE_FILE
    if not pose_path.is_file():
        raise InputError("case", str(case), "was not driven by a pose trajectory")
    poses = read_pose_file(pose_path)
    t = signals.time_s
    settle = max(float(t[-1]) - poses.duration_s, 0.0)
    response = simulate_spatial(
        model, poses, settle_time_s=settle, sample_period_s=1e-3, height_mapping="planar"
    )
    model_time = response.time_s - poses.start_s
    model_walls = np.column_stack(
        [np.interp(t, model_time, response.wall_elevation_m(a)) for a in signals.angles_rad]
    )
    model_height = model_walls.max(axis=1)
    cfd_height = signals.slosh_height_m
    end = poses.duration_s
    during, after = t <= end, t > end
    rows: dict[str, tuple[float | None, float | None]] = {
        "peak_slosh_height_m": (float(cfd_height[during].max()), float(model_height[during].max()))
    }
    if np.any(after):
        rows["residual_slosh_height_m"] = (
            float(cfd_height[after].max()),
            float(model_height[after].max()),
        )
    comparison = {key: comparison_row(*values) for key, values in rows.items()}
    return CfdValidation(
        case=str(case),
        comparison=comparison,
        correlation=_correlation(cfd_height, model_height),
        time_s=np.asarray(t, dtype=float),
        cfd_elevation_m=np.asarray(cfd_height, dtype=float),
        model_elevation_m=np.asarray(model_height, dtype=float),
        excitation_end_s=end,
        kind="poses",
        extra={
            "wall_correlation": _correlation(signals.elevations_m.ravel(), model_walls.ravel()),
            "probe_angles_deg": [float(np.degrees(a)) for a in signals.angles_rad],
            "quantity_label": "slosh height (max over the probe columns at 0.98 R) [mm]",
        },
    )
