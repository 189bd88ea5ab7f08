"""CFD of 3-D container motions against the 3-D pendulum model (`sloshkit.sim.spatial`).

A case driven by a `sloshkit.cfd.excitation.PoseExcitation` measures the wall elevation along
the container axis in columns of probes around the circumference (r = 0.98 R); its slosh
height is the largest of them. The model is run on the same pose trajectory (kept in the case
as ``sloshkit-poses.csv``) and read at the same wall angles, so both slosh heights are maxima
over the same columns. With the columns equally spaced around the wall, both are also split
into azimuthal orders (`azimuthal_orders`): a lateral acceleration or a tilt drives only the
order m = 1 in linear theory, and the pendulum model has no other, so the other orders are
what the model leaves out (studies/cfd-planned-moves).
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


#: The azimuthal orders reported (m = 0..3; 12 columns resolve up to m = 5).
ORDERS = 4


def azimuthal_orders(
    elevation_m: np.ndarray, angles_rad: np.ndarray, orders: int = ORDERS
) -> np.ndarray | None:
    """The amplitude of each azimuthal order m = 0..orders - 1 of wall elevations measured in
    equally spaced columns: |mean| for m = 0, else the norm of the discrete Fourier
    coefficients 2 mean(eta cos m theta), 2 mean(eta sin m theta); exact for a wave of orders
    below K / 2 with K columns (the discrete orthogonality of the harmonics).

    Parameters
    ----------
    elevation_m : numpy.ndarray
        (time, K) wall elevations [m].
    angles_rad : numpy.ndarray
        (K,) the columns' angles [rad].
    orders : int
        The orders m = 0..orders - 1.

    Returns
    -------
    numpy.ndarray or None
        (orders, time) amplitudes [m]; None unless the K columns are equally spaced with
        K > 2 (orders - 1).

    Examples
    --------
    >>> import numpy as np
    >>> angles = np.radians(np.arange(12) * 30.0)
    >>> wave = 0.003 * np.cos(angles) + 0.002 * np.sin(2 * angles - 0.4) + 0.001
    >>> np.round(1e3 * azimuthal_orders(wave[None], angles)[:, 0], 6).tolist()
    [1.0, 3.0, 2.0, 0.0]
    >>> azimuthal_orders(wave[None, :2], angles[:2]) is None
    True
    """
    angles = np.asarray(angles_rad, dtype=float)
    count = angles.size
    spacing = np.diff(np.unwrap(np.sort(angles)))
    if count <= 2 * (orders - 1) or not np.allclose(spacing, 2.0 * np.pi / count, atol=1e-6):
        return None
    elevation = np.asarray(elevation_m, dtype=float)
    found = np.empty((orders, elevation.shape[0]))
    found[0] = np.abs(elevation.mean(axis=1))
    for m in range(1, orders):
        cosine = 2.0 * (elevation * np.cos(m * angles)).mean(axis=1)
        sine = 2.0 * (elevation * np.sin(m * angles)).mean(axis=1)
        found[m] = np.hypot(cosine, sine)
    return found


def _order_rows(
    cfd: np.ndarray, model: np.ndarray, during: np.ndarray, after: np.ndarray
) -> list[dict[str, float | int | None]]:
    """Per order: the largest amplitude during the motion and after it, CFD and model."""

    def peak(values: np.ndarray, where: np.ndarray) -> float | None:
        return float(values[where].max()) if np.any(where) else None

    return [
        {
            "order": m,
            "peak_cfd_m": peak(cfd[m], during),
            "peak_model_m": peak(model[m], during),
            "residual_cfd_m": peak(cfd[m], after),
            "residual_model_m": peak(model[m], after),
        }
        for m in range(cfd.shape[0])
    ]


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
        ``wall_correlation`` of the wall elevations of every probe column,
        ``azimuthal_orders`` (with equally spaced columns: per order m = 0..3 the largest
        amplitude during and after the motion, CFD and model; `azimuthal_orders`), and the series
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
    extra: dict[str, object] = {}
    cfd_orders = azimuthal_orders(signals.elevations_m, signals.angles_rad)
    model_orders = azimuthal_orders(model_walls, signals.angles_rad)
    if cfd_orders is not None and model_orders is not None:
        extra["azimuthal_orders"] = _order_rows(cfd_orders, model_orders, during, after)
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
            **extra,
        },
    )
