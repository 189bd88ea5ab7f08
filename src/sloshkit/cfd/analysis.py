"""Calibration of a finished CFD case: its signals, and frequency and damping of its free
decay (the seed paper's Table 4), from the wall force when the case has one
(`sloshkit.cfd.force_signal`), else from the wall elevation."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sloshkit.calibration import CalibrationResult, calibrate
from sloshkit.cfd.force_signal import (
    NOISE_CUTOFF_FACTOR,
    NOISE_RATIO_LIMIT,
    STEP_ALTERNATION_LIMIT,
    noise_ratio,
    step_alternation,
    usable_force,
)
from sloshkit.cfd.results import CfdSignals, read_function_object, read_signals
from sloshkit.cfd.summary import read_case_summary, read_run_record
from sloshkit.errors import InputError, ValidityWarning


def excitation_end(summary: dict[str, Any]) -> float:
    """When the container stops moving in this case [s] (0 for a free decay).

    Parameters
    ----------
    summary : dict
        The case's ``sloshkit-case.json``.

    Returns
    -------
    float

    Examples
    --------
    >>> excitation_end({"excitation": {"type": "Harmonic", "duration_s": 2.0}})
    2.0
    >>> excitation_end({"excitation": {"type": "FreeDecay", "tilt_deg": 3.0}})
    0.0
    """
    excitation = summary["excitation"]
    if excitation["type"] == "Harmonic":
        return float(excitation["duration_s"])
    if excitation["type"] in ("MotionExcitation", "PoseExcitation"):
        return float(excitation.get("duration_s", 0.0))
    return 0.0


@dataclass(frozen=True, eq=False)
class CfdAnalysis:
    """A case's signals and their calibration.

    Parameters
    ----------
    case : Path
        The case folder.
    signals : CfdSignals
        Its signals.
    calibration : CalibrationResult
        Frequency and damping of its free decay.
    run_record : dict
        ``sloshkit-run.json`` (wall clock, processes), or empty.
    damping_signal : str
        The signal calibrated: ``wall_force`` or ``wall_elevation``.
    force_noise_ratio : float or None
        High-frequency noise ratio of the wall force (`sloshkit.cfd.force_signal.noise_ratio`)
        when the case has a usable wall force (even if it failed to calibrate).
    force_step_alternation : float or None
        Step-to-step alternation of the wall force over the window
        (`sloshkit.cfd.force_signal.step_alternation`), when the force is usable.
    warnings : tuple of str
        Doubts about the calibration (also issued as `ValidityWarning`).

    Returns
    -------
    CfdAnalysis

    Examples
    --------
    >>> import numpy as np
    >>> from pathlib import Path
    >>> from sloshkit.calibration import calibrate
    >>> from sloshkit.cfd.results import CfdSignals
    >>> t = np.arange(0.0, 3.0, 0.002)
    >>> y = 1e-3 * np.exp(-0.15 * t) * np.cos(29.66 * t)
    >>> signals = CfdSignals(t, np.column_stack((y, -y)), np.array([0.0, np.pi]), 0 * t, 0 * t,
    ...                      {"cells": 100})
    >>> analysis = CfdAnalysis(Path("c"), signals, calibrate(t, y, start_s=0.0), {})
    >>> round(analysis.to_dict()["damping_ratio"], 4), analysis.to_dict()["cells"]
    (0.0051, 100)
    >>> analysis.to_dict()["damping_signal"]
    'wall_elevation'
    """

    case: Path
    signals: CfdSignals
    calibration: CalibrationResult
    run_record: dict[str, Any]
    damping_signal: str = "wall_elevation"
    force_noise_ratio: float | None = None
    force_step_alternation: float | None = None
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The calibrate keys plus cells, simulated_s, wall_clock_s, damping_signal,
        force_noise_ratio and force_step_alternation (this analysis's warnings appended to
        ``warnings``)."""
        payload = self.calibration.to_dict()
        payload.update(
            cells=self.signals.summary["cells"],
            simulated_s=float(self.signals.time_s[-1]),
            wall_clock_s=self.run_record.get("wall_clock_s"),
            processes=self.run_record.get("processes"),
            case=str(self.case),
            damping_signal=self.damping_signal,
            force_noise_ratio=self.force_noise_ratio,
            force_step_alternation=self.force_step_alternation,
        )
        payload["warnings"] = list(payload.get("warnings", [])) + list(self.warnings)
        return payload


def analyse(case: Path, method: str = "fit", start_s: float | None = None) -> CfdAnalysis:
    """Calibrate frequency and damping of a case's free decay from its wall force, or from its
    antisymmetric wall elevation when the case has no usable force output.

    In free decay the lateral wall force of the first mode oscillates at the same frequency
    and decays at the same rate as the wall elevation: in linear modal theory both are
    proportional to the modal amplitude (Abramson, NASA SP-106, ch. 2 and 6). So the force
    gives the same quantity from a signal that integrates the pressure over the whole wall
    instead of the volume fraction along a thin column of probes; on coarse meshes the
    probe elevation's estimators disagree by up to 6.4x, the force's within 20 % (the damping
    study, docs/cfd.md). The force is used when it is finite and not constant
    (`sloshkit.cfd.force_signal.usable_force`) and calibrates; otherwise the elevation is,
    with a warning when a usable force failed to calibrate. A usable force whose high-frequency
    noise ratio (above three times the measured frequency, over the window) exceeds
    `sloshkit.cfd.force_signal.NOISE_RATIO_LIMIT` carries parasitic currents: a
    `ValidityWarning` says so; so does a step-to-step alternation of the force
    (`sloshkit.cfd.force_signal.step_alternation`) above
    `sloshkit.cfd.force_signal.STEP_ALTERNATION_LIMIT`, the signature of interFoam's
    step-to-step pressure oscillation, which made the damping erratic where it appeared.

    The window starts at ``start_s`` when given; otherwise, for a forced case, one damped
    period after the excitation ends (``forcing_end_s`` of `sloshkit.calibration.calibrate`:
    the forcing's end is known exactly, so it is not searched for in the signal), and for a
    free decay from the largest peak.

    Parameters
    ----------
    case : Path
        A case run by ``sloshkit cfd run``.
    method : str
        The estimator reported (``fit``, ``logdec``, ``fft``, ...).
    start_s : float, optional
        Window start [s].

    Returns
    -------
    CfdAnalysis
        With ``damping_signal`` (``wall_force`` or ``wall_elevation``) and, when the case
        has a usable wall force, its ``force_noise_ratio`` and ``force_step_alternation``.

    Raises
    ------
    InputError
        A folder that is not a sloshkit case, an unfinished run (saying how far it got), or a
        forced run that ends too soon after its excitation to calibrate a free decay.

    References
    ----------
    Seed paper eqs. 11-12 (the calibration of frequency and damping from a free decay);
    H. N. Abramson (ed.), *The Dynamic Behavior of Liquids in Moving Containers*, NASA SP-106
    (1966), ch. 2 and 6 (wall force and elevation of a mode share its frequency and decay).

    Examples
    --------
    >>> from pathlib import Path
    >>> analyse(Path("no-such-case"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-such-case' is invalid: is not a sloshkit CFD case ...
    """
    signals = read_finished_signals(case)
    end = excitation_end(dict(signals.summary))
    forcing_end = end if start_s is None and end > 0 else None
    doubts: list[str] = []

    def calibrated(values: Any, label: str) -> CalibrationResult:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            return calibrate(
                signals.time_s,
                values,
                method=method,  # type: ignore[arg-type]
                start_s=start_s,
                forcing_end_s=forcing_end,
                source=f"{case} (CFD {label})",
            )

    result: CalibrationResult | None = None
    signal = "wall_elevation"
    if usable_force(signals.force_x_n):
        try:
            result = calibrated(signals.force_x_n, "wall force")
            signal = "wall_force"
        except InputError as error:
            doubts.append(
                f"the wall force gave no calibration ({error}); frequency and damping are "
                "from the probe wall elevation, which is unreliable on coarse meshes"
            )
    try:
        if result is None:
            result = calibrated(signals.elevation_m, "wall elevation")
    except InputError as error:
        if forcing_end is None:
            raise
        after = float(signals.time_s[-1]) - forcing_end
        raise InputError(
            "case",
            str(case),
            f"has only {after:.3g} s of free decay after the excitation ends at "
            f"{forcing_end:g} s, too short to calibrate ({error})",
            "run it longer with --end-time (at least 4 periods after the excitation)",
        ) from error
    ratio, alternation, force_doubts = _force_quality(signals, result)
    doubts += force_doubts + list(signals.notes)
    for doubt in doubts:
        warnings.warn(doubt, ValidityWarning, stacklevel=2)
    record = read_run_record(case)
    return CfdAnalysis(case, signals, result, record, signal, ratio, alternation, tuple(doubts))


def _force_quality(
    signals: CfdSignals, result: CalibrationResult
) -> tuple[float | None, float | None, list[str]]:
    """The wall force's noise ratio and step alternation over the calibration window (None
    each when the force is unusable or the measure undefined), and the doubts they raise."""
    if not usable_force(signals.force_x_n):
        return None, None, []
    ratio, alternation = _force_noise(signals, result), _force_alternation(signals, result)
    checks = (
        (
            ratio,
            NOISE_RATIO_LIMIT,
            f"the wall force's noise above {NOISE_CUTOFF_FACTOR:g}x the slosh frequency is "
            f"{ratio or 0.0:.2f} of the slosh signal (above {NOISE_RATIO_LIMIT:g}: clean runs of "
            "the damping study stay at or below 0.23, runs with parasitic currents reach 0.88 "
            "or more); the damping is not trustworthy (the study saw this on wall-graded meshes "
            "at small time steps: use a uniform mesh or a longer step)",
        ),
        (
            alternation,
            STEP_ALTERNATION_LIMIT,
            f"the wall force changes sign from step to step: its alternating part is "
            f"{alternation or 0.0:.3f} of the signal (above {STEP_ALTERNATION_LIMIT:g}; clean "
            "runs of the damping study stay at or below 0.004); where interFoam's step-to-step "
            "pressure oscillation appeared in the study, the damping moved by up to a third "
            "between neighbouring steps, so it is not trustworthy (it appears on wall-graded "
            "meshes at small steps: use a longer step or a finer mesh)",
        ),
    )
    doubts = [text for value, limit, text in checks if value is not None and value > limit]
    return ratio, alternation, doubts


def _force_alternation(signals: CfdSignals, result: CalibrationResult) -> float | None:
    """The wall force's step alternation over the calibration window (None when not
    measurable)."""
    inside = signals.time_s >= float(result.signal.window_s[0])
    value = step_alternation(signals.force_x_n[inside])
    return value if math.isfinite(value) else None


def _force_noise(signals: CfdSignals, result: CalibrationResult) -> float | None:
    """The wall force's noise ratio over the calibration window, cut off at
    `NOISE_CUTOFF_FACTOR` times the calibrated frequency (of whichever signal was calibrated;
    None when not measurable)."""
    omega = result.omega_n_rad_s
    if omega is None or not math.isfinite(omega) or omega <= 0:
        return None
    ratio = noise_ratio(
        signals.time_s,
        signals.force_x_n,
        cutoff_hz=NOISE_CUTOFF_FACTOR * omega / (2 * math.pi),
        start_s=float(result.signal.window_s[0]),
    )
    return ratio if math.isfinite(ratio) else None


def read_finished_signals(case: Path) -> CfdSignals:
    """The signals of a finished case; `InputError` when the case is missing or unfinished.

    Parameters
    ----------
    case : Path
        The case folder.

    Returns
    -------
    CfdSignals

    Raises
    ------
    InputError
        Not a sloshkit case, or unfinished (saying how far it got and how to continue).

    Examples
    --------
    >>> from pathlib import Path
    >>> read_finished_signals(Path("no-such-case"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sloshkit.errors.InputError: case = 'no-such-case' is invalid: is not a sloshkit CFD case ...
    """
    summary = read_case_summary(case)
    end = float(summary["end_time_s"])
    resume = f"continue it with: sloshkit cfd run --case {case} --resume"
    if not (case / "postProcessing" / "wallProbes").is_dir():
        raise InputError("case", str(case), f"is unfinished (simulated 0 of {end:g} s)", resume)
    try:
        probes = read_function_object(case, "wallProbes", "alpha.water")
    except InputError as error:  # probe files created but nothing written in them yet
        raise InputError(
            "case",
            str(case),
            f"is unfinished (no probe data yet; simulated 0 of {end:g} s)",
            resume,
        ) from error
    # The solver's own last probe time, not the resampled grid's (which may stop a step short):
    # a finished run's last line is at the end time itself (8 significant digits), or up to
    # half a fixed step short of it (interFoam stops at endTime - deltaT/2), and a run stopped
    # one step early is unfinished, not nearly finished.
    simulated = float(probes[-1, 0])
    if simulated < end - 0.5 * float(summary.get("delta_t_s", 0.0)) - 1e-6:
        raise InputError(
            "case", str(case), f"is unfinished (simulated {simulated:.4g} of {end:g} s)", resume
        )
    return read_signals(case)  # a finished case: every signal read and checked
