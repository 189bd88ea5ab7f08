"""Initial state and fluid properties of a case: the fill (setFields), water and air, and the
boundary conditions of alpha.water, U and p_rgh (pure: returns file texts, in mm units)."""

from __future__ import annotations

import math

from sloshkit.cfd.excitation import FreeDecay
from sloshkit.cfd.foam import Raw, foam_file, format_number
from sloshkit.cfd.spec import AIR_DENSITY_KG_M3, AIR_VISCOSITY_PA_S, SCALE, CaseSpec


def rest_surface_normal(spec: CaseSpec) -> tuple[float, float, float]:
    """Unit normal of the initial free surface in the container frame: tilted by a free
    decay's ``tilt_rad`` about y, or normal to gravity in the first pose of a 3-D motion.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    tuple of float
        (nx, ny, nz).

    Examples
    --------
    >>> from sloshkit.cfd.excitation import FreeDecay
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), FreeDecay(0.0))
    >>> rest_surface_normal(spec)
    (-0.0, 0.0, 1.0)
    """
    excitation = spec.excitation
    if isinstance(excitation, FreeDecay):
        return (-math.sin(excitation.tilt_rad), 0.0, math.cos(excitation.tilt_rad))
    up = getattr(excitation, "initial_up_body", None)
    if up is not None:
        x, y, z = (float(v) for v in up)
        norm = math.sqrt(x * x + y * y + z * z)
        return (x / norm, y / norm, z / norm)
    return (0.0, 0.0, 1.0)


def _cross(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def set_fields_dict(spec: CaseSpec) -> str:
    """setFieldsDict: water below the (possibly tilted) static free surface, a plane through
    the axis at the fill height (so the liquid volume is unchanged while it cuts the wall
    only).

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
    >>> "rotatedBoxToCell" in set_fields_dict(spec)
    True
    """
    radius, height, fill = spec.radius_m * SCALE, spec.height_m * SCALE, spec.fill_height_m * SCALE
    normal = rest_surface_normal(spec)
    if abs(normal[2] - 1.0) < 1e-12:
        region = f"""    boxToCell
    {{
        box (-{2 * radius} -{2 * radius} -1) ({2 * radius} {2 * radius} {format_number(fill)});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    else:
        # A right-handed box (u, v, n) whose top face lies on the surface plane through
        # (0, 0, fill); it reaches `depth` below it.
        u = _cross((0.0, 1.0, 0.0), normal)
        norm_u = math.sqrt(sum(c * c for c in u))
        u = (u[0] / norm_u, u[1] / norm_u, u[2] / norm_u)
        v = _cross(normal, u)
        depth, span = 2 * height, 4 * radius
        origin = tuple(
            p - 0.5 * span * a - 0.5 * span * b - depth * n
            for p, a, b, n in zip((0.0, 0.0, fill), u, v, normal, strict=True)
        )

        def vector(values: tuple[float, ...], scale: float = 1.0) -> str:
            return " ".join(format_number(round(scale * c, 9)) for c in values)

        region = f"""    rotatedBoxToCell
    {{
        origin ({vector(origin)});
        i ({vector(u, span)});
        j ({vector(v, span)});
        k ({vector(normal, depth)});
        fieldValues ( volScalarFieldValue alpha.water 1 );
    }}"""
    entries = {
        "defaultFieldValues": Raw("( volScalarFieldValue alpha.water 0 )"),
        "regions": Raw("\n(\n" + region + "\n)"),
    }
    return foam_file("dictionary", "setFieldsDict", entries, "system")


def transport_properties(spec: CaseSpec) -> str:
    """Water and air (the paper's Table 1 for air), in mm units.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    str

    References
    ----------
    De Simone et al. (2024), the seed paper, Table 1 (air).

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> [line.split()[-1] for line in transport_properties(spec).splitlines() if "sigma" in line]
    ['0;']
    """
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
    """0/alpha.water, 0/U, 0/p_rgh: no-slip walls, an open top (atmosphere).

    Returns
    -------
    dict of str to str
        Path in the case -> file text.

    Examples
    --------
    >>> sorted(initial_fields())
    ['0/U', '0/alpha.water', '0/p_rgh']
    """
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
