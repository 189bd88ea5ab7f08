"""Natural frequency and damping from measured records: free decays and forced responses.

- `calibrate`: a free decay, found by itself in a record that starts with the forced motion
  (`find_free_decay`), analysed by independent estimators (fit, logdec regression, fft, the
  paper's two-peak logdec) and by the amplitude-dependent `backbone`.
- `identify_forced`: omega, zeta (and a force signal's slosh mass) fitted by simulating the
  model against a record of the applied motion's response, free decay or not;
  `identify_simulated` does the same with any simulator and a clock offset; `identify_line`
  and `identify_spatial` put sloshkit's 1-D and 3-D models in its loop.
"""

from sloshkit.calibration.applied import AppliedMotion, applied_from_poses
from sloshkit.calibration.backbone import Backbone, backbone
from sloshkit.calibration.decay import FALLBACKS, METHODS, Method, calibrate
from sloshkit.calibration.decrement import estimate_logdec, estimate_logdec_2peak
from sloshkit.calibration.estimators import (
    Estimate,
    estimate_fft,
    estimate_fit,
    log_decrement_from_zeta,
    spectral_guess,
    zeta_from_log_decrement,
)
from sloshkit.calibration.forced import (
    SIGNAL_KINDS,
    ForcedIdentification,
    SignalKind,
    identify_forced,
)
from sloshkit.calibration.model_in_loop import identify_line, identify_spatial
from sloshkit.calibration.result import CalibrationResult, disagreements, relative_spread
from sloshkit.calibration.signals import (
    PreparedSignal,
    interpolated_peaks,
    noise_level,
    spectral_peak,
    uniform_signal,
    usable_peaks,
)
from sloshkit.calibration.simulated import Simulator, identify_simulated
from sloshkit.calibration.window import DecayWindow, find_free_decay, prepare_signal

__all__ = [
    "FALLBACKS",
    "METHODS",
    "SIGNAL_KINDS",
    "AppliedMotion",
    "Backbone",
    "CalibrationResult",
    "DecayWindow",
    "Estimate",
    "ForcedIdentification",
    "Method",
    "PreparedSignal",
    "SignalKind",
    "Simulator",
    "applied_from_poses",
    "backbone",
    "calibrate",
    "disagreements",
    "estimate_fft",
    "estimate_fit",
    "estimate_logdec",
    "estimate_logdec_2peak",
    "find_free_decay",
    "identify_forced",
    "identify_line",
    "identify_simulated",
    "identify_spatial",
    "interpolated_peaks",
    "log_decrement_from_zeta",
    "noise_level",
    "prepare_signal",
    "relative_spread",
    "spectral_guess",
    "spectral_peak",
    "uniform_signal",
    "usable_peaks",
    "zeta_from_log_decrement",
]
