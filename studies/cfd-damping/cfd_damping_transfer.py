"""Transfer of a reference mesh's step-error shape to a mesh run at fewer steps (the damping
study of studies/cfd-damping/cfd_damping_converged.py): a straight line z_M(dt) = a + c z_ref(dt)
through the mesh's runs, evaluated at the reference's zero-step value."""

from __future__ import annotations

import itertools
import math
import statistics
from typing import Any

from convergence import combined_uncertainty


def transfer(
    mesh: dict[float, float], reference: dict[float, float], z8: float, u8: float
) -> dict[str, Any]:
    """Zero-step value of a mesh from the step-error shape of the reference mesh."""
    steps = sorted(s for s in mesh if s in reference)
    if len(steps) < 2:
        return {"steps_s": steps, "points": len(steps)}
    x = [reference[s] for s in steps]
    y = [mesh[s] for s in steps]
    slope, intercept = _line(x, y)
    value = intercept + slope * z8
    pairs = [
        _line([reference[a], reference[b]], [mesh[a], mesh[b]])
        for a, b in itertools.combinations(steps, 2)
    ]
    predictions = [i + c * z8 for c, i in pairs]
    spread = 0.5 * (max(predictions) - min(predictions)) if len(pairs) > 1 else math.nan
    return {
        "steps_s": steps,
        "points": len(steps),
        "slope": slope,
        "slopes_of_pairs": [c for c, _ in pairs],
        "extrapolated": value,
        "distance": mesh[steps[0]] - value,
        "fit_spread": spread,
        "propagated": abs(slope) * u8,
    }


def _line(x: list[float], y: list[float]) -> tuple[float, float]:
    """Least-squares line y = c x + a: (c, a)."""
    mx, my = statistics.fmean(x), statistics.fmean(y)
    sxx = sum((a - mx) ** 2 for a in x)
    c = sum((a - mx) * (b - my) for a, b in zip(x, y, strict=True)) / sxx
    return c, my - c * mx


def finish_transfers(
    results: dict[str, dict[str, Any]],
    reference: dict[float, float],
    z_ref: float,
    u_ref: float,
    meshes: dict[str, dict[float, float]],
    worst: float,
) -> None:
    """Uncertainties of the transferred values of one kind of mesh (in place): the fit spread
    where measured, else ``worst`` (the largest relative spread seen) times the distance; a
    one-step mesh takes the mean slope of the others (a slope of 1 +- 0.25, the same step
    error as its reference, when there is none), unless one of them has a slope of zero or
    less: then it has no zero-step value (``invalid``)."""
    measured = [x["slope"] for x in results.values() if x.get("points", 0) >= 2]
    slopes = [c for c in measured if c > 0]
    for name, r in results.items():
        if r.get("points", 0) == 1 and len(slopes) < len(measured):
            # Session 4: a one-step mesh among meshes whose step error runs against the
            # reference's (graded 16 and 20/radius) cannot borrow the others' mean slope.
            r["invalid"] = (
                "one step only, and meshes of its kind run at two steps do not take the "
                "reference's step-error shape (slopes "
                + ", ".join(f"{c:.2f}" for c in measured)
                + ")"
            )
            continue
        if r.get("points", 0) == 1:
            step = r["steps_s"][0]
            c = statistics.fmean(slopes) if slopes else 1.0
            spread_c = 0.5 * (max(slopes) - min(slopes)) if slopes else 0.25
            value = meshes[name][step] - c * (reference[step] - z_ref)
            r.update(
                slope=c,
                extrapolated=value,
                distance=meshes[name][step] - value,
                fit_spread=spread_c * abs(reference[step] - z_ref),
                propagated=c * u_ref,
                slope_from="mean of the meshes of its kind with two steps or more"
                if slopes
                else "1 ± 0.25 assumed (no other mesh of its kind with two steps)",
            )
        elif r.get("points", 0) == 2:
            r["fit_spread"] = worst * abs(r["distance"])
            r["fit_spread_from"] = "largest relative spread of the meshes with three steps"
        if r.get("slope", 1.0) <= 0.0:  # its step error runs against the reference's
            r["invalid"] = (
                f"its damping rises as the step shrinks (slope c = {r['slope']:.2f}), against "
                "the reference mesh: the step-error shape does not transfer"
            )
            for key in ("extrapolated", "distance", "fit_spread", "propagated"):
                r.pop(key, None)
        if "extrapolated" in r:
            r["uncertainty"] = combined_uncertainty(r["propagated"], r["fit_spread"])
