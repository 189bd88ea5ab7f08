"""The pendulum states of a path program as functions of its variables, condensed per segment
(`sloshkit.plan.path.transcription`).

Linearised along the current track (`sloshkit.plan.path.pendulums.step_jacobians`), the
states' deviations obey dx_{k+1} = A_k dx_k + B_k df_k + E_k df_{k+1}, the drive's deviation
df_k a function of the samples k - 1..k + 1 (`sloshkit.plan.path.program.PathProgram.
jacobians`). Within a segment of periods [p0, p1) that starts from its own state variable
(multiple shooting in condensed blocks: Bock & Plitt, IFAC Proc. 17 (1984) 1603-1608;
Kirches et al., Optim. Methods Softw. 27 (2012) 2, condensing),

    dx_k = Phi_k x_seg + Psi_k z,

and Psi_k can depend only on the variables whose B-splines reach the samples p0 - 1..p1 + 1.
`condense` computes each segment's Psi on those columns alone, its window: the work grows with
the samples times the window (about twenty coefficients per spline over the default segment),
not times every variable of the move, which on a 4-8 s tilted move is 400-700 columns.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class CondensedStates:
    """Phi and Psi of every sample (module docstring), Psi stored per segment on its window.

    Parameters
    ----------
    phi : numpy.ndarray
        (modes, n, 6, 6): d x_k / d x_seg of each sample's segment.
    segment : numpy.ndarray
        (n,): each sample's segment (a segment's start sample still belongs to the one
        before it; segment 0 starts at rest, without a state variable).
    windows : list of tuple
        Per segment: its first sample p0, its columns (the window) and Psi on them,
        (modes, p1 - p0 + 1, 6, window) for the samples p0..p1.
    columns : int
        nz, the variables.

    Examples
    --------
    >>> import numpy as np
    >>> windows = [(0, np.array([1]), np.ones((1, 3, 6, 1)))]
    >>> states = CondensedStates(np.zeros((1, 3, 6, 6)), np.zeros(3, dtype=int), windows, 2)
    >>> states.psi_at(2)[0, 0]
    array([0., 1.])
    """

    phi: FloatArray
    segment: NDArray[np.int64]
    windows: list[tuple[int, NDArray[np.int64], FloatArray]]
    columns: int

    def psi_at(self, sample: int) -> FloatArray:
        """Psi of one sample on every column, (modes, 6, nz)."""
        first, window, psi = self.windows[int(self.segment[sample])]
        dense = np.zeros((psi.shape[0], 6, self.columns))
        dense[:, :, window] = psi[:, sample - first]
        return dense

    def wall(self, slopes: FloatArray) -> FloatArray:
        """sum_n slopes_n Psi_n[:3] at every sample on every column, (n, 2, nz), from the
        modes' slope Jacobians ``slopes`` (modes, n, 2, 3)."""
        n = self.segment.size
        wall = np.zeros((n, 2, self.columns))
        for first, window, psi in self.windows:
            last = first + psi.shape[1]
            # mode by mode, as the wall height sums them (`sloshkit.plan.path.program`)
            local = np.zeros((last - first, 2, window.size))
            for slope, mode_psi in zip(slopes[:, first:last], psi, strict=True):
                local += np.einsum("kac,kcz->kaz", slope, mode_psi[:, :3])
            # the segment's first sample belongs to the one before (or is the rest at 0)
            wall[first + 1 : last, :, window] += local[1:]
        return wall


def condense(
    steps: tuple[FloatArray, FloatArray, FloatArray],
    blocks: list[tuple[Any, FloatArray]],
    kappa: FloatArray,
    width: int,
    starts: list[int],
) -> CondensedStates:
    """The states' Phi and windowed Psi (module docstring) of one band model's pendulums.

    Parameters
    ----------
    steps : tuple of numpy.ndarray
        A_k (modes, n - 1, 6, 6), B_k and E_k (modes, n - 1, 6, width)
        (`sloshkit.plan.path.pendulums.step_jacobians`).
    blocks : list of tuple
        Per variable block, its force and rate bands (``force`` (3, modes + 1, n, 3),
        ``rates`` (3, n, 4): derivatives at k in the sample k - 1, k, k + 1;
        `sloshkit.plan.path.program.PathProgram.jacobians`) and each sample's derivative in
        the variables (n, nz).
    kappa : numpy.ndarray
        omega_n^2 L_n / g of each mode: the drive is the force at the hinge plus
        (kappa_n - 1) times gravity's row (`sloshkit.sim.spatial_drive`).
    width : int
        The drive's components the pendulums see: 3 (the specific force) or 7 (with the
        frame's lateral turning rate and its derivative).
    starts : list of int
        The samples where segments 1, 2, ... start.

    Returns
    -------
    CondensedStates
        Phi, each sample's segment and Psi per segment.

    Examples
    --------
    One mode driven through one variable at the middle sample: Psi is the step's input there
    and A times it after, and the columns outside the window are never touched.

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> a = np.broadcast_to(2.0 * np.eye(6), (1, 4, 6, 6))
    >>> b = np.zeros((1, 4, 6, 3)); b[0, :, 0, 0] = 1.0
    >>> force = np.zeros((3, 2, 5, 3)); force[1, 0, :, 0] = 1.0
    >>> band = SimpleNamespace(force=force, rates=np.zeros((3, 5, 4)))
    >>> dz = np.zeros((5, 3)); dz[2, 1] = 1.0
    >>> states = condense((a, b, 0 * b), [(band, dz)], np.ones(1), 3, [])
    >>> [float(states.psi_at(k)[0, 0, 1]) for k in range(5)]
    [0.0, 0.0, 0.0, 1.0, 2.0]
    >>> states.windows[0][1]
    array([1])
    """
    a_k, b_k, e_k = steps
    modes, periods = a_k.shape[0], a_k.shape[1]
    n = periods + 1
    nz = blocks[0][1].shape[1]
    # each block's nonzero rows, and how many samples either side its gains reach (a band's
    # k - 1..k + 1; `sloshkit.plan.path.axial_turn`'s pseudo-block its own sample only)
    active = [(dz != 0.0, getattr(band, "reach", 1)) for band, dz in blocks]
    identity = np.broadcast_to(np.eye(6), (modes, 6, 6))
    phi = np.zeros((modes, n, 6, 6))
    phi[:, 0] = identity
    segment = np.zeros(n, dtype=np.int64)
    windows = []
    bounds = [0, *starts, periods]
    for index, (first, end) in enumerate(pairwise(bounds)):
        # the periods first..end - 1 see the drive at first..end, which sees the samples
        # first - 1..end + 1
        seen = np.zeros(nz, dtype=bool)
        for nonzero, reach in active:
            seen |= nonzero[max(first - reach, 0) : min(end + 1 + reach, n)].any(axis=0)
        window = np.flatnonzero(seen)
        samples = np.arange(first, end + 1)
        # the step inputs B_k df_k + E_k df_{k+1}, df_k = sum over the offsets o of the
        # drive's gain at k in the sample k + o times that sample's row of dz: the gains
        # contracted with B and E first, then one batched product over every block, offset
        # and step matrix, so that no (modes, samples, 7, window) drive is formed
        gains_through, rows = [], []
        for band, dz in blocks:
            local = dz[:, window]
            moved = np.zeros((3, samples.size, window.size))
            gains = np.empty((3, modes, samples.size, 7))
            for o, offset in enumerate((-1, 0, 1)):
                source = samples + offset
                inside = (source >= 0) & (source < n)
                moved[o][inside] = local[source[inside]]
                force = band.force[offset + 1]
                gains[o, :, :, :3] = (
                    force[:modes][:, samples]
                    + (kappa - 1.0)[:, None, None] * force[-1][None, samples]
                )
                gains[o, :, :, 3:] = band.rates[offset + 1][None, samples]
            # B_k and E_k times the gains (modes, samples, width, offsets), batched
            columns = gains[..., :width].transpose(1, 2, 3, 0)
            gains_through.append(np.matmul(b_k[:, first:end], columns[:, :-1]))
            gains_through.append(np.matmul(e_k[:, first:end], columns[:, 1:]))
            rows += [moved[:, :-1].transpose(1, 0, 2), moved[:, 1:].transpose(1, 0, 2)]
        inputs = np.matmul(np.concatenate(gains_through, axis=3), np.concatenate(rows, axis=1))
        psi = np.zeros((modes, samples.size, 6, window.size))
        current_phi = np.array(identity)
        current_psi = np.zeros((modes, 6, window.size))
        for j, k in enumerate(range(first, end)):
            current_phi = np.matmul(a_k[:, k], current_phi)
            current_psi = np.matmul(a_k[:, k], current_psi) + inputs[:, j]
            phi[:, k + 1] = current_phi
            psi[:, j + 1] = current_psi
            segment[k + 1] = index
        windows.append((first, window, psi))
    return CondensedStates(phi, segment, windows, nz)


__all__ = ["CondensedStates", "condense"]
