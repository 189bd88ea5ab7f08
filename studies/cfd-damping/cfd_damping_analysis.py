"""Analysis of the CFD damping study (cfd_damping_study.py): Richardson extrapolation in
time step and mesh, GCI, boundary-layer theory, figure and the section of README.md.

Reads data/cfd-damping-study.json and data/cfd-damping-graded.json (session 2),
data/cfd-damping-converge.json (session 3) and data/cfd-damping-estimators.json (every run
re-estimated from its wall force), extrapolates (studies/cfd-damping/cfd_damping_converged.py), and
writes data/cfd-damping.json (every number of the section), the figure
figures/cfd_damping_study.png, and the text between the markers
``<!-- damping-study:start -->`` and ``<!-- damping-study:end -->`` of README.md.

Run: PYTHONPATH=src python studies/cfd-damping/cfd_damping_analysis.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from cfd_damping_converged import SAFETY, analyse
from cfd_damping_converged_report import figure, render
from cfd_damping_report import render_noise, render_stability
from scipy import integrate
from scipy.special import j1, jvp

from sloshkit.model.liquids import get_liquid
from sloshkit.model.theory import GRAVITY_M_S2, damping_ratio_correlation

STUDY = Path(__file__).resolve().parent
DATA = STUDY / "data"
RADIUS_M, FILL_M, GRAVITY = 0.0205, 0.039, GRAVITY_M_S2
XI_1 = 1.8411837813406593  # first zero of J1'
START, END = "<!-- damping-study:start -->", "<!-- damping-study:end -->"
WALL_START, WALL_END = "<!-- wall-stability:start -->", "<!-- wall-stability:end -->"
NOISE_START, NOISE_END = "<!-- parasitic-noise:start -->", "<!-- parasitic-noise:end -->"


def stokes_layer_damping(radius_m: float, fill_m: float, nu_m2_s: float) -> dict[str, float]:
    """First-mode damping ratio of a clean upright cylinder from laminar boundary-layer
    theory: Stokes layers on the side wall and the bottom, free-slip (clean) surface, plus the
    weak dissipation of the irrotational flow in the bulk.

    The mean dissipation of a Stokes layer per unit wall area is rho U^2 sqrt(nu omega / 8)
    for a tangential slip velocity of amplitude U (Landau & Lifshitz, *Fluid Mechanics*,
    2nd ed., §24), so zeta = sqrt(nu / (8 omega)) S / V with S the wall integral of the
    squared tangential velocity of the inviscid mode and V its volume integral (Case &
    Parkinson, J. Fluid Mech. 2 (1957) 172, doi:10.1017/S0022112057000063; Miles, J. Fluid
    Mech. 3 (1958) 233, doi:10.1017/S0022112058000032). The bulk term is Lamb's 2 nu k^2 decay
    rate of the amplitude (Lamb, *Hydrodynamics*, 6th ed., §348), with k = xi_1 / R.
    """
    k = XI_1 / radius_m
    omega = math.sqrt(GRAVITY * k * math.tanh(k * fill_m))

    def f(z: float) -> float:
        return math.cosh(k * z) / math.cosh(k * fill_m)

    def df(z: float) -> float:
        return k * math.sinh(k * z) / math.cosh(k * fill_m)

    jr = float(j1(XI_1))
    side = (
        math.pi
        * radius_m
        * jr**2
        * integrate.quad(lambda z: df(z) ** 2 + f(z) ** 2 / radius_m**2, 0.0, fill_m)[0]
    )
    bottom = (
        math.pi
        * f(0.0) ** 2
        * integrate.quad(
            lambda r: (k**2 * jvp(1, k * r) ** 2 + (j1(k * r) / r) ** 2) * r, 1e-12, radius_m
        )[0]
    )
    volume = (
        math.pi
        * k
        * math.tanh(k * fill_m)
        * integrate.quad(lambda r: j1(k * r) ** 2 * r, 0.0, radius_m)[0]
    )
    factor = math.sqrt(nu_m2_s / (8.0 * omega)) / volume
    bulk = 2.0 * nu_m2_s * k**2 / omega
    return {
        "omega_rad_s": omega,
        "stokes_layer_thickness_m": math.sqrt(2.0 * nu_m2_s / omega),
        "side_wall": factor * side,
        "bottom": factor * bottom,
        "bulk": bulk,
        "total": factor * (side + bottom) + bulk,
    }


def main() -> None:
    nu = get_liquid("water-25C").kinematic_viscosity_m2_s
    layer = stokes_layer_damping(RADIUS_M, FILL_M, nu)
    theory = {
        "boundary_layer_theory": layer["total"],
        "seed_eq2": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "seed"),
        "sp106": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "sp106"),
        "stephens": damping_ratio_correlation(RADIUS_M, FILL_M, nu, "stephens"),
    }
    document = {
        "case": "seed vial R 20.5 mm, h 39 mm, water 25 C / air, 3 deg tilt, 2 s free decay, "
        "fixed step, 3 pressure correctors, serial; damping from the wall force",
        **analyse(theory),
        "boundary_layer_terms": layer,
        "safety": SAFETY,
    }
    (DATA / "cfd-damping.json").write_text(json.dumps(document, indent=2) + "\n")
    figure(document, STUDY / "figures" / "cfd_damping_study.png")
    section = render(document)
    grading = json.loads((DATA / "cfd-wall-grading.json").read_text())
    wall_section = render_stability(grading.get("instability_diagnosis", []))
    noise_path = DATA / "cfd-parasitic-noise.json"
    noise_section = render_noise(json.loads(noise_path.read_text()) if noise_path.is_file() else [])
    text = (STUDY / "README.md").read_text()
    blocks = (
        (START, END, section),
        (WALL_START, WALL_END, wall_section),
        (NOISE_START, NOISE_END, noise_section),
    )
    for start, end, body in blocks:
        if start in text:
            head, rest = text.split(start, 1)
            text = head + start + "\n" + body + "\n" + end + rest.split(end, 1)[1]
    (STUDY / "README.md").write_text(text)
    print(section)


if __name__ == "__main__":
    main()
