"""Initial state and fluid properties of a case: the fill (setFields), water and air, and the
boundary conditions of alpha.water, U and p_rgh (pure: returns file texts, in mm units)."""

from __future__ import annotations

import math

from sloshkit.cfd.excitation import FreeDecay
from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.cfd.spec import AIR_DENSITY_KG_M3, AIR_VISCOSITY_PA_S, SCALE, CaseSpec


def set_fields_dict(spec: CaseSpec) -> str:
    """setFieldsDict: water below the (possibly tilted) static free surface."""
    radius, height, fill = spec.radius_m * SCALE, spec.height_m * SCALE, spec.fill_height_m * SCALE
    tilt = spec.excitation.tilt_rad if isinstance(spec.excitation, FreeDecay) else 0.0
    if tilt == 0.0:
        region = f"""    boxToCell
    {{
        box (-{2 * radius} -{2 * radius} -1) ({2 * radius} {2 * radius} {format_number(fill)});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    else:
        c, s = math.cos(tilt), math.sin(tilt)
        depth = 2 * height
        span = 4 * radius
        # Top face of the box lies on the plane z = fill + x tan(tilt) (through the axis, so
        # the liquid volume is unchanged); the box reaches `depth` below it.
        p0 = (-2 * radius * c, -2 * radius, fill - 2 * radius * s)
        origin = (p0[0] + depth * s, p0[1], p0[2] - depth * c)
        region = f"""    rotatedBoxToCell
    {{
        origin ({" ".join(format_number(round(v, 9)) for v in origin)});
        i ({format_number(round(span * c, 9))} 0 {format_number(round(span * s, 9))});
        j (0 {format_number(span)} 0);
        k ({format_number(round(-depth * s, 9))} 0 {format_number(round(depth * c, 9))});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    entries = {
        "defaultFieldValues": Raw("( volScalarFieldValue alpha.water 0 )"),
        "regions": Raw("\n(\n" + region + "\n)"),
    }
    return foam_file("dictionary", "setFieldsDict", entries, "system")


def transport_properties(spec: CaseSpec) -> str:
    """Water and air (the paper's Table 1 for air), in mm units."""
    liquid = spec.liquid
    sigma = liquid.surface_tension_n_m * SCALE**3 if spec.surface_tension else 0.0
    entries = {
        "phases": Raw("(water air)"),
        "water": {
            "transportModel": "Newtonian",
            "nu": liquid.kinematic_viscosity_m2_s * SCALE**2,
            "rho": liquid.density_kg_m3,
        },
        "air": {
            "transportModel": "Newtonian",
            "nu": AIR_VISCOSITY_PA_S / AIR_DENSITY_KG_M3 * SCALE**2,
            "rho": AIR_DENSITY_KG_M3,
        },
        "sigma": sigma,
    }
    return foam_file("dictionary", "transportProperties", entries, "constant")


def initial_fields() -> dict[str, str]:
    """0/alpha.water, 0/U, 0/p_rgh: no-slip walls, an open top (atmosphere)."""
    alpha = foam_file(
        "volScalarField",
        "alpha.water",
        {
            "dimensions": Raw("[0 0 0 0 0 0 0]"),
            "internalField": Raw("uniform 0"),
            "boundaryField": {
                "walls": {"type": "zeroGradient"},
                "atmosphere": {
                    "type": "inletOutlet",
                    "inletValue": Raw("uniform 0"),
                    "value": Raw("uniform 0"),
                },
            },
        },
        "0",
    )
    velocity = foam_file(
        "volVectorField",
        "U",
        {
            "dimensions": Raw("[0 1 -1 0 0 0 0]"),
            "internalField": Raw("uniform (0 0 0)"),
            "boundaryField": {
                "walls": {"type": "noSlip"},
                "atmosphere": {
                    "type": "pressureInletOutletVelocity",
                    "value": Raw("uniform (0 0 0)"),
                },
            },
        },
        "0",
    )
    pressure = foam_file(
        "volScalarField",
        "p_rgh",
        {
            "dimensions": Raw("[1 -1 -2 0 0 0 0]"),
            "internalField": Raw("uniform 0"),
            "boundaryField": {
                "walls": {"type": "fixedFluxPressure", "value": Raw("uniform 0")},
                "atmosphere": {
                    "type": "totalPressure",
                    "p0": Raw("uniform 0"),
                    "value": Raw("uniform 0"),
                },
            },
        },
        "0",
    )
    return {"0/alpha.water": alpha, "0/U": velocity, "0/p_rgh": pressure}
