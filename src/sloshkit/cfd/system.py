"""The ``system`` dictionaries of a case: time control and function objects (the
measurements), schemes, solver settings and decomposition (pure: returns file texts).

Choices and the studies behind them are in `sloshkit.cfd.case` and docs/cfd.md.
"""

from __future__ import annotations

import math
from typing import Any

from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.cfd.mesh import probe_angles_rad, probe_columns
from sloshkit.cfd.spec import SCALE, CaseSpec

#: Radius of the probe columns, as a fraction of the container radius.
PROBE_RADIUS_FRACTION = 0.98


def probe_points(spec: CaseSpec) -> list[str]:
    """Probe locations in mm: one column per angle, bottom to top.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    list of str
        ``(x y z)`` in mm.

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> probe_points(spec)[0]
    '(20.09 0 0.319954128)'
    """
    z, _ = probe_columns(spec)
    r = PROBE_RADIUS_FRACTION * spec.radius_m * SCALE
    points = []
    for angle in probe_angles_rad(spec):
        x, y = round(r * math.cos(angle), 9), round(r * math.sin(angle), 9)
        points += [
            f"({format_number(x)} {format_number(y)} {format_number(round(zz * SCALE, 9))})"
            for zz in z
        ]
    return points


def write_interval(spec: CaseSpec) -> float:
    """The write interval, adjusted so that the end time is a write time (an adjustable
    step then lands on it exactly, and the last fields are written there) [s].

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    float

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> write_interval(CaseSpec(0.0205, 0.039, get_liquid("water-25C"), end_time_s=1.2))
    0.6
    """
    count = max(1, round(spec.end_time_s / spec.write_interval_s))
    return spec.end_time_s / count


def _every_step(entries: dict[str, Any]) -> dict[str, Any]:
    return {"writeControl": "timeStep", "writeInterval": 1, **entries}


def control_dict(spec: CaseSpec) -> str:
    """controlDict: adaptive (or fixed) step, fields at write times only, and the function
    objects the calibration needs.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> "adjustTimeStep  yes;" in control_dict(spec)
    True
    """
    entries: dict[str, Any] = {
        "application": "interFoam",
        "startFrom": "latestTime",
        "startTime": 0,
        "stopAt": "endTime",
        "endTime": spec.end_time_s,
        "deltaT": spec.delta_t_s,
        "writeControl": "adjustableRunTime" if spec.adjust_time_step else "runTime",
        "writeInterval": write_interval(spec),
        "purgeWrite": 0,
        "writeFormat": "ascii",
        "writePrecision": 8,
        "writeCompression": "off",
        "timeFormat": "general",
        "timePrecision": 8,
        "runTimeModifiable": "no",
        "adjustTimeStep": "yes" if spec.adjust_time_step else "no",
        "maxCo": spec.max_courant,
        "maxAlphaCo": spec.max_alpha_courant,
        "maxDeltaT": spec.delta_t_s,
        "libs": Raw(
            '("libfvOptions.so" "libforces.so" "libsampling.so" "libfieldFunctionObjects.so")'
        ),
        "functions": {
            "wallProbes": _every_step(
                {
                    "type": "probes",
                    "libs": Raw('("libsampling.so")'),
                    "fields": Raw("(alpha.water)"),
                    "probeLocations": Raw(
                        "\n        (\n            "
                        + "\n            ".join(probe_points(spec))
                        + "\n        )"
                    ),
                }
            ),
            # Computed every step (surfaceTilt integrates it), written at write times only.
            "gradAlpha": {
                "type": "grad",
                "libs": Raw('("libfieldFunctionObjects.so")'),
                "field": "alpha.water",
                "executeControl": "timeStep",
                "executeInterval": 1,
                "writeControl": "writeTime",
                "log": "false",
            },
            "surfaceTilt": _every_step(
                {
                    "type": "volFieldValue",
                    "libs": Raw('("libfieldFunctionObjects.so")'),
                    "writeFields": "false",
                    "log": "false",
                    "regionType": "all",
                    "operation": "volIntegrate",
                    "fields": Raw("(grad(alpha.water))"),
                }
            ),
            "wallForces": _every_step(
                {
                    "type": "forces",
                    "libs": Raw('("libforces.so")'),
                    "patches": Raw("(walls)"),
                    "rho": "rho",
                    "rhoInf": 1,
                    "CofR": Raw("(0 0 0)"),
                    "log": "false",
                }
            ),
        },
    }
    return foam_file("dictionary", "controlDict", entries, "system")


def fv_schemes(spec: CaseSpec) -> str:
    """Schemes: bounded second-order convection, the chosen time scheme (with ``backward``,
    Euler for alpha, the only first-order choice MULES accepts).

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> "Gauss vanLeer" in fv_schemes(spec)
    True
    """
    ddt = {"default": spec.ddt_scheme}
    if spec.ddt_scheme == "backward":
        # interFoam's MULES accepts only Euler and CrankNicolson for alpha ("Only Euler and
        # CrankNicolson ddt schemes are supported", v1912 alphaEqn.H): backward is for U.
        ddt["ddt(alpha)"] = "Euler"
    entries = {
        "ddtSchemes": ddt,
        "gradSchemes": {"default": "Gauss linear"},
        "divSchemes": {
            "div(rhoPhi,U)": "Gauss linearUpwind grad(U)",
            "div(phi,alpha)": "Gauss vanLeer",
            "div(phirb,alpha)": "Gauss linear",
            "div(((rho*nuEff)*dev2(T(grad(U)))))": "Gauss linear",
        },
        "laplacianSchemes": {"default": "Gauss linear corrected"},
        "interpolationSchemes": {"default": "linear"},
        "snGradSchemes": {"default": "corrected"},
    }
    return foam_file("dictionary", "fvSchemes", entries, "system")


def fv_solution(spec: CaseSpec) -> str:
    """Solvers and PIMPLE settings (MULES for alpha, GAMG for p_rgh).

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> "nCorrectors     3;" in fv_solution(spec)
    True
    """
    entries = {
        "solvers": {
            '"alpha.water.*"': {
                "nAlphaCorr": 2,
                "nAlphaSubCycles": 1,
                "cAlpha": 1,
                "MULESCorr": "yes",
                "nLimiterIter": 5,
                "solver": "smoothSolver",
                "smoother": "symGaussSeidel",
                "tolerance": 1e-8,
                "relTol": 0,
            },
            '"pcorr.*"': {"solver": "PCG", "preconditioner": "DIC", "tolerance": 1e-7, "relTol": 0},
            "p_rgh": {"solver": "GAMG", "smoother": "DIC", "tolerance": 1e-7, "relTol": 0.05},
            "p_rghFinal": {"$p_rgh": "", "relTol": 0},
            '"U.*"': {
                "solver": "smoothSolver",
                "smoother": "symGaussSeidel",
                "tolerance": 1e-7,
                "relTol": 0,
            },
        },
        "PIMPLE": {
            "momentumPredictor": "yes" if spec.momentum_predictor else "no",
            "nOuterCorrectors": 1,
            "nCorrectors": spec.pressure_correctors,
            "nNonOrthogonalCorrectors": 0,
        },
        "relaxationFactors": {"equations": {'".*"': 1}},
    }
    text = foam_file("dictionary", "fvSolution", entries, "system")
    return text.replace("$p_rgh          ;", "$p_rgh;")


def decompose_par_dict(spec: CaseSpec) -> str:
    """Decomposition along z (hierarchical: scotch and metis are dummies in this package).

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> "hierarchical" in decompose_par_dict(spec)
    True
    """
    entries = {
        "numberOfSubdomains": spec.processes,
        "method": "hierarchical",
        "coeffs": {"n": Raw(f"(1 1 {spec.processes})"), "order": "xyz"},
    }
    return foam_file("dictionary", "decomposeParDict", entries, "system")
