"""Lateral sloshing modes of a liquid in any axisymmetric container, by finite elements.

The linear potential-flow eigenproblem (Ibrahim 2005 §2.2; Faltinsen & Timokha 2009 ch. 4): the
velocity potential is harmonic in the liquid, dphi/dn = 0 on the wetted wall and
omega^2 phi = g dphi/dz on the flat free surface z = h. Lateral excitation drives only the first
azimuthal harmonic, phi = psi(r, z) cos(theta), for which Laplace's equation on the meridian
section reads psi_rr + psi_r / r + psi_zz - psi / r^2 = 0. Its weak form, with the volume element
r dr dz and the factor pi of the theta integral dropped on both sides,

    K(psi, v) = int (psi_r v_r + psi_z v_z) r + psi v / r  dr dz,
    M(psi, v) = int_surface psi v r dr,                      K psi = lambda M psi,

gives lambda_n = omega_n^2 / g (a Steklov eigenproblem). It is discretised with quadratic
isoparametric triangles (scikit-fem) on a structured, boundary-fitted mesh of the meridian
section (`meridian_mesh`: rows at the profile's corners and graded with depth; the curved wall
edges pass through the profile at their ends and midpoints), with psi = 0 on the axis
(regularity of the m = 1 harmonic), and condensed exactly onto the free-surface unknowns (Schur
complement of the interior), a small dense generalised symmetric eigenproblem.

The equivalent pendulums follow from matching the modal force and moment on the container for
an arbitrary lateral motion X(t), as Dodge (2000) §3 and Ibrahim (2005) ch. 6 do for the
cylinder, here for any profile. With the surface elevation eta = sum a_n phi_n|_S and
C_n = int_S x phi_n dS, N_n = int_S phi_n^2 dS, D_n = int_V (z phi_x - x phi_z) dV, the modal
equations are a_n'' + omega_n^2 a_n = -lambda_n (C_n / N_n) X''; the liquid's lateral momentum
(Green's identity with x) is rho sum C_n a_n' and its angular momentum about the bottom's centre
rho sum (a_n' / lambda_n) D_n. A pendulum of mass m_n, length L_n and bob height z_n reproduces
both for a_n = (C_n / N_n) theta_n when

    L_n = g / omega_n^2,  m_n = rho lambda_n C_n^2 / N_n,  z_n = D_n / (lambda_n C_n),

and the wall elevation per radian is f_n = (C_n / N_n) psi_n(R_s, h).

For the upright cylinder these reduce to the closed forms of `sloshkit.model.theory`
(m_n / m_F = 2R tanh(xi_n h/R) / (xi_n (xi_n^2 - 1) h), z_n = h - (2R/xi_n) tanh(xi_n h/(2R)),
f_n = 2R / (xi_n^2 - 1)); the tests hold the solver to them within 0.1 %.

References
----------
- Ibrahim, R. A., *Liquid Sloshing Dynamics*, Cambridge UP (2005), §2.2, §6.2,
  doi:10.1017/CBO9780511536656.
- Dodge, F. T., *The New "Dynamic Behavior of Liquids in Moving Containers"*, SwRI (2000).
- Faltinsen, O. M., Timokha, A. N., *Sloshing*, Cambridge UP (2009), ch. 4-5.
- McIver, P., Sloshing frequencies for cylindrical and spherical containers filled to an
  arbitrary depth, J. Fluid Mech. 201 (1989) 243-257, doi:10.1017/S0022112089000923.
- Gustafsson, T., McBain, G. D., scikit-fem: A Python package for finite element assembly,
  J. Open Source Softw. 5 (2020) 2369, doi:10.21105/joss.02369.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from sloshkit.errors import InputError
from sloshkit.model.profile import ProfileContainer

#: Radial cells of the meridian mesh (quadratic triangles) for up to three modes: every
#: quantity of the cylinder's first three modes within 0.1 % of the closed form
#: (docs/validation.md has the convergence table).
DEFAULT_RADIAL_CELLS = 24

#: Extra radial cells per requested mode beyond the third (the n-th mode has about n
#: half-wavelengths across the radius; eight cells per mode keep it as accurate as the third).
CELLS_PER_EXTRA_MODE = 8

#: Quadrature degree: the 1/r term is not polynomial on elements touching the axis at a vertex.
QUADRATURE_ORDER = 6

#: Profile points where the wall turns by more than this (a heel's or a shoulder's corner) are
#: rows of the mesh; elsewhere the rows follow the spacing rule and the quadratic
#: (isoparametric) wall edges pass through the profile at their ends and midpoints, so an arc of
#: fine chords needs no row per chord.
CORNER_ANGLE_RAD = math.radians(10.0)

#: Depth of the mesh below the free surface, in free-surface radii: the first mode's potential
#: falls as exp(-1.84 depth / R_s), to 4e-7 at 8 radii (the cylinder's eigenvalue changes by
#: 2 exp(-3.68 depth / R_s) = 3e-13); deeper liquid only makes the elements long and thin.
MESH_DEPTH = 8.0

#: Row spacing relative to the radial spacing at the free surface.
ROW_SPACING = 1.0

#: Most modes of a profile model (each costs a finer mesh; 10 modes take about 1.5 s).
MAX_PROFILE_MODES = 10


@dataclass(frozen=True)
class AxisymmetricModes:
    """The lateral (m = 1) sloshing modes of a liquid in an axisymmetric container, per unit
    density, from `axisymmetric_modes`.

    Parameters
    ----------
    fill_height_m : float
        Static fill height h [m].
    surface_radius_m : float
        Radius of the free surface R_s = r(h) [m].
    eigenvalues_1_m : tuple of float
        lambda_n = omega_n^2 / g [1/m], ascending.
    mass_per_density_m3 : tuple of float
        Slosh mass over density, lambda_n C_n^2 / N_n [m^3].
    bob_height_m : tuple of float
        Height of each pendulum's bob above the bottom, D_n / (lambda_n C_n) [m].
    wall_elevation_factor_m : tuple of float
        Wall elevation at the free surface's edge per radian of pendulum angle [m/rad].
    unknowns : int
        Number of finite-element unknowns (the discretisation's size).
    surface_unknowns : int
        Unknowns on the free surface (the condensed eigenproblem's size).

    Examples
    --------
    >>> from sloshkit.model.profile import cylinder_profile
    >>> modes = axisymmetric_modes(cylinder_profile(0.0205, 0.08), 0.039, 1)
    >>> round(modes.eigenvalues_1_m[0] * 0.0205, 5)  # xi_1 tanh(xi_1 h / R) = 1.837847
    1.83785
    """

    fill_height_m: float
    surface_radius_m: float
    eigenvalues_1_m: tuple[float, ...]
    mass_per_density_m3: tuple[float, ...]
    bob_height_m: tuple[float, ...]
    wall_elevation_factor_m: tuple[float, ...]
    unknowns: int
    surface_unknowns: int


def axisymmetric_modes(
    profile: ProfileContainer,
    fill_height_m: float,
    n_modes: int = 3,
    *,
    radial_cells: int | None = None,
) -> AxisymmetricModes:
    """The first ``n_modes`` lateral sloshing modes of the liquid in ``profile`` filled to ``h``.

    Solves the m = 1 eigenproblem of the module docstring with quadratic triangles and returns
    the equivalent-pendulum quantities per unit density. Results are cached per profile, fill
    height, mode count and mesh (a sweep over fills of one vial solves each fill once).

    Parameters
    ----------
    profile : ProfileContainer
        The container's inner profile.
    fill_height_m : float
        Static fill height h [m].
    n_modes : int
        Number of modes.
    radial_cells : int, optional
        Radial cells of the mesh (default `DEFAULT_RADIAL_CELLS`, more for many modes);
        the rows follow the profile's points and the same spacing.

    Returns
    -------
    AxisymmetricModes

    References
    ----------
    Ibrahim, R. A., *Liquid Sloshing Dynamics* (2005) §2.2 and §6.2,
    doi:10.1017/CBO9780511536656; Gustafsson, T., McBain, G. D., J. Open Source Softw. 5 (2020)
    2369, doi:10.21105/joss.02369.

    Examples
    --------
    The 45-degree cone standing on its vertex: omega_1^2 h / g = 1 exactly (phi = x z).

    >>> from sloshkit.model.profile import cone_profile
    >>> modes = axisymmetric_modes(cone_profile(0.02, 0.02), 0.01, 1)
    >>> round(modes.eigenvalues_1_m[0] * 0.01, 9)
    1.0
    """
    height = profile.check_fill_height(fill_height_m)
    if profile.radius_at(height) <= 0.0:
        raise InputError(
            "fill_height", f"{height:.6g} m", "must leave a free surface of radius > 0"
        )
    count = int(n_modes)
    if not 1 <= count <= MAX_PROFILE_MODES:
        raise InputError(
            "modes", count, f"must be 1 .. {MAX_PROFILE_MODES} for a profile container"
        )
    cells = (
        DEFAULT_RADIAL_CELLS + CELLS_PER_EXTRA_MODE * max(0, count - 3)
        if radial_cells is None
        else int(radial_cells)
    )
    if cells < 2:
        raise InputError("radial_cells", cells, "must be >= 2")
    return _solve(profile, float(height), count, cells)


def meridian_mesh(
    profile: ProfileContainer, fill_height_m: float, radial_cells: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Structured triangulation of the liquid's meridian section 0 <= r <= r(z), 0 <= z <= h.

    Node (i, j) sits at r = (i / n) r(z_j), z = z_j; the rows z_j are the bottom, the profile's
    corners below the fill height (`CORNER_ANGLE_RAD`) and the fill height, subdivided so
    that the row spacing is at most R_s / n (1 + depth / R_s) (the modes decay with depth). A
    bottom that is a point on the axis (cone, sphere) collapses the first row into that point.
    Deeper than `MESH_DEPTH` free-surface radii the liquid is left out (a flat mesh bottom).

    Parameters
    ----------
    profile : ProfileContainer
        The container.
    fill_height_m : float
        Fill height [m].
    radial_cells : int
        Cells across the radius.

    Returns
    -------
    points : numpy.ndarray
        (2, nodes) coordinates r, z [m].
    triangles : numpy.ndarray
        (3, cells) node indices, counter-clockwise in the (r, z) plane.
    surface_nodes : numpy.ndarray
        The free surface's nodes from the axis to the wall.
    axis_nodes : numpy.ndarray
        The nodes on the axis r = 0.
    wall_nodes : numpy.ndarray
        The nodes on the wall r = r(z), from the bottom up.

    Examples
    --------
    >>> from sloshkit.model.profile import cylinder_profile
    >>> mesh = meridian_mesh(cylinder_profile(0.01, 0.05), 0.01, 4)
    >>> points, triangles, surface, axis, wall = mesh
    >>> points.shape, triangles.shape, len(surface), len(axis), len(wall)
    ((2, 20), (3, 24), 5, 4, 4)
    """
    z_points, r_points = profile.wetted(fill_height_m)
    surface_radius = float(r_points[-1])
    # Below MESH_DEPTH free-surface radii the first mode has decayed to 4e-7: the mesh ends there
    # on a flat (natural-condition) bottom.
    cut = fill_height_m - MESH_DEPTH * surface_radius
    if cut > 0.0:
        below = z_points > cut
        z_points = np.concatenate(([cut], z_points[below]))
        r_points = np.concatenate(([np.interp(cut, profile.z_m, profile.r_m)], r_points[below]))
    spacing = ROW_SPACING * surface_radius / radial_cells
    corners = z_points[_corner_mask(z_points, r_points)]

    # Rows uniform in the graded coordinate u = ln(1 + depth / R_s) R_s / spacing, whose
    # step is the local spacing R_s / n (1 + depth / R_s) [ROW_SPACING], between corners.
    def graded(depth: np.ndarray) -> np.ndarray:
        return np.asarray(np.log1p(depth / surface_radius) * surface_radius / spacing)

    rows = [corners[-1]]
    for upper, lower in zip(corners[::-1][:-1], corners[::-1][1:], strict=True):
        top, bottom = graded(np.array([fill_height_m - upper, fill_height_m - lower]))
        pieces = max(1, math.ceil(bottom - top - 1e-9))
        u = top + (bottom - top) * np.arange(1, pieces + 1) / pieces
        rows.extend(fill_height_m - surface_radius * np.expm1(u * spacing / surface_radius))
    z_rows = np.array(rows[::-1])
    z_rows[0] = z_points[0]
    r_rows = np.interp(z_rows, z_points, r_points)
    fractions = np.linspace(0.0, 1.0, radial_cells + 1)
    columns = radial_cells + 1
    vertex = r_rows[0] <= 0.0
    # Node numbering: a collapsed bottom row is the single node 0.
    r_nodes = np.outer(r_rows, fractions)
    z_nodes = np.repeat(z_rows[:, None], columns, axis=1)
    index = np.arange(len(z_rows) * columns).reshape(len(z_rows), columns)
    if vertex:
        index = index - (columns - 1)
        index[0, :] = 0
        r_flat = np.concatenate(([0.0], r_nodes[1:].ravel()))
        z_flat = np.concatenate(([z_rows[0]], z_nodes[1:].ravel()))
    else:
        r_flat, z_flat = r_nodes.ravel(), z_nodes.ravel()
    triangles = []
    for j in range(len(z_rows) - 1):
        for i in range(radial_cells):
            a, b = index[j, i], index[j, i + 1]
            c, d = index[j + 1, i + 1], index[j + 1, i]
            if not (vertex and j == 0):
                triangles.append((a, b, c))
            triangles.append((a, c, d))
    return (
        np.vstack((r_flat, z_flat)),
        np.ascontiguousarray(np.array(triangles, dtype=np.int64).T),
        index[-1, :].copy(),
        np.unique(index[:, 0]),
        np.unique(index[:, -1]),
    )


def _corner_mask(z: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The polyline's ends and the points where it turns by more than `CORNER_ANGLE_RAD`."""
    direction = np.arctan2(np.diff(r), np.diff(z))
    mask = np.ones(len(z), dtype=bool)
    mask[1:-1] = np.abs(np.diff(direction)) > CORNER_ANGLE_RAD
    return mask


def _curved_mesh(
    profile: ProfileContainer, mesh: Any, wall_nodes: np.ndarray, height: float, radius: float
) -> Any:
    """The quadratic (isoparametric) mesh whose wall edges pass through the profile at their
    midpoints (the other edges stay straight); coordinates scaled as in `_solve_unthreaded`."""
    from dataclasses import replace

    from skfem import MeshTri2

    curved = MeshTri2.from_mesh(mesh)
    pairs = np.sort(np.vstack((wall_nodes[:-1], wall_nodes[1:])), axis=0)
    facet_of = {tuple(f): i for i, f in enumerate(np.sort(mesh.facets, axis=0).T)}
    facets = np.array([facet_of[(int(a), int(b))] for a, b in pairs.T])
    dofs = mesh.nvertices + facets  # the quadratic mesh numbers its vertices, then its edges
    doflocs = curved.doflocs.copy()
    z_middle = height + radius * doflocs[1, dofs]
    doflocs[0, dofs] = np.interp(z_middle, profile.z_m, profile.r_m) / radius
    return replace(curved, doflocs=doflocs)


@lru_cache(maxsize=512)
def _solve(
    profile: ProfileContainer, fill_height_m: float, n_modes: int, radial_cells: int
) -> AxisymmetricModes:
    from threadpoolctl import threadpool_limits

    # One BLAS thread: the factorisation's small dense blocks run three times slower with
    # OpenBLAS's threads (measured on two shared cores, benchmarks/bench_container.py).
    with threadpool_limits(limits=1, user_api="blas"):
        return _solve_unthreaded(profile, fill_height_m, n_modes, radial_cells)


def _solve_unthreaded(
    profile: ProfileContainer, fill_height_m: float, n_modes: int, radial_cells: int
) -> AxisymmetricModes:
    import scipy.linalg
    from scipy.sparse.linalg import splu
    from skfem import Basis, BilinearForm, ElementTriP2, FacetBasis, LinearForm, MeshTri, asm

    points, triangles, surface_nodes, _, wall_nodes = meridian_mesh(
        profile, fill_height_m, radial_cells
    )
    # Solved in units of the free surface's radius with the surface at z' = 0 (scale-free: the
    # isoparametric inverse mapping works to an absolute tolerance), then scaled back.
    radius = float(points[0, surface_nodes[-1]])
    scaled = np.vstack((points[0] / radius, (points[1] - fill_height_m) / radius))
    mesh = _curved_mesh(profile, MeshTri(scaled, triangles), wall_nodes, fill_height_m, radius)
    element = ElementTriP2()
    basis = Basis(mesh, element, intorder=QUADRATURE_ORDER)
    tolerance = 1e-9
    surface_facets = mesh.facets_satisfying(lambda x: x[1] > -tolerance, boundaries_only=True)
    axis_facets = mesh.facets_satisfying(lambda x: x[0] < tolerance, boundaries_only=True)
    surface_basis = FacetBasis(mesh, element, facets=surface_facets, intorder=QUADRATURE_ORDER)

    @BilinearForm
    def stiffness(u, v, w):  # type: ignore[no-untyped-def]
        r = w.x[0]
        return (u.grad[0] * v.grad[0] + u.grad[1] * v.grad[1]) * r + u * v / r

    @BilinearForm
    def surface_mass(u, v, w):  # type: ignore[no-untyped-def]
        return u * v * w.x[0]

    @LinearForm
    def surface_moment(v, w):  # type: ignore[no-untyped-def]
        return v * w.x[0] ** 2

    @LinearForm
    def angular_moment(v, w):  # type: ignore[no-untyped-def]
        # (z (phi_r + phi/r) - r phi_z) r: the theta-integral of z phi_x - x phi_z over pi.
        r, z = w.x[0], w.x[1]
        return (z * (v.grad[0] + v / r) - r * v.grad[1]) * r

    stiffness_matrix = asm(stiffness, basis).tocsr()
    mass_matrix = asm(surface_mass, surface_basis).tocsr()
    moment_vector = asm(surface_moment, surface_basis)
    angular_vector = asm(angular_moment, basis)

    axis_dofs = basis.get_dofs(axis_facets).all()
    surface_dofs = np.setdiff1d(basis.get_dofs(surface_facets).all(), axis_dofs)
    interior = np.setdiff1d(np.arange(basis.N), np.concatenate((axis_dofs, surface_dofs)))
    if len(surface_dofs) < n_modes:
        raise InputError(
            "modes", n_modes, f"must be <= {len(surface_dofs)} for {radial_cells} radial cells"
        )
    k_ii = stiffness_matrix[interior][:, interior].tocsc()
    # Sparse products keep the condensation free of multithreaded BLAS calls, which cost more
    # than they save at this size on a loaded machine.
    k_is = stiffness_matrix[interior][:, surface_dofs].tocsc()
    k_ss = stiffness_matrix[surface_dofs][:, surface_dofs].toarray()
    interior_response = splu(k_ii, permc_spec="MMD_AT_PLUS_A").solve(k_is.toarray())
    condensed = k_ss - np.asarray(k_is.T @ interior_response)
    condensed = (condensed + condensed.T) / 2.0
    mass = mass_matrix[surface_dofs][:, surface_dofs].toarray()
    eigenvalues, vectors = scipy.linalg.eigh(
        condensed, mass, subset_by_index=(0, n_modes - 1), driver="gvx"
    )
    # Full shapes: psi_I = -K_II^-1 K_IS psi_S, psi = 0 on the axis.
    shapes = np.zeros((basis.N, n_modes))
    shapes[surface_dofs] = vectors
    shapes[interior] = -np.einsum("ij,jn->in", interior_response, vectors)
    wall_dof = basis.nodal_dofs[0, surface_nodes[-1]]
    norms = np.einsum("in,ij,jn->n", vectors, mass, vectors)
    moments = moment_vector @ shapes
    angular = angular_vector @ shapes
    wall = shapes[wall_dof]
    # Back to SI: lambda ~ 1/R_s, masses ~ R_s^3, lengths ~ R_s; the bob height measured from
    # the surface moves to the bottom by h (D = D' + h lambda C, Green's identity with x).
    return AxisymmetricModes(
        fill_height_m=fill_height_m,
        surface_radius_m=radius,
        eigenvalues_1_m=tuple(float(v) / radius for v in eigenvalues),
        # C_n and N_n carry the factor pi of the theta integral that the forms leave out.
        mass_per_density_m3=tuple(
            float(v) * radius**3 for v in math.pi * eigenvalues * moments**2 / norms
        ),
        bob_height_m=tuple(
            fill_height_m + radius * float(v) for v in angular / (eigenvalues * moments)
        ),
        wall_elevation_factor_m=tuple(float(v) * radius for v in moments / norms * wall),
        unknowns=int(basis.N - len(axis_dofs)),
        surface_unknowns=len(surface_dofs),
    )
