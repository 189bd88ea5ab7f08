"""The drive's dependence on samples outside its band: N's turn about the container's axis.

The pendulums are driven in N, the container frame turned back about its own axis by its spin
(`sloshkit.plan.path.forces.non_spinning_frame`): the sum of the body-frame rotation
increments' axial components. A sample's change moves the two increments next to it. While
the axis keeps its direction their changes cancel, but when it tilts they leave N turned by
their sum at every later sample: the spin of a body whose axis moves depends on the axis's
path, not only on where it ends (the geometric phase of a rotation; Montgomery, Am. J. Phys.
59 (1991) 394-398, doi:10.1119/1.16514). Turning N by d turns every vector in N by -d, so
d f_j / d spin_j = e_z x f_j (`sloshkit.plan.path.forces.turned_about_axis`).

`sloshkit.plan.path.program.PathProgram.jacobians` holds each force's dependence on the samples
k - 1..k + 1 and each sample's spin change (``spin``, per unit of the variable); this module
adds the rest, f_j += e_z x f_j C_j z with C_j = sum over k <= j - 2 of spin_k dz_k. So that
the condensed states stay local to their segment (`sloshkit.plan.path.condensing`), C_j is
written as sigma_i + (C_j - C_{p_i}), sigma_i = C_{p_i} z a variable per segment start p_i,
tied to the splines by one equality row. On the tilted TRD_2D programs the drive's derivative
without this term was off by 2 % at low frequency, and the residual's predicted slope by
10-40 % near the optimum, where the residual is a near-cancelled sum.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from sloshkit.plan.path.forces import turned_about_axis

FloatArray = NDArray[np.float64]

#: A sample's spin change per unit of its variable [rad/m or rad/rad] below which N is taken
#: not to turn: the finite differences' rounding (about 1e-9) while the axis keeps its
#: direction; a tilted TRD_2D plan's tilt samples turn N by up to 1e-2.
SPIN_FLOOR = 1e-6


def spin_changes(dspin: FloatArray, chosen: NDArray[np.int64]) -> tuple[FloatArray, FloatArray]:
    """N's turn at every later sample from each of a set of perturbed samples, and the turn
    that the perturbed samples two or more before each sample left there (the part of its
    force's change outside its band, k - 1..k + 1).

    A sample's change moves the spin increments on its both sides: the spin from the next
    sample on moves by their sum, ``dspin[k + 1] - dspin[k - 1]`` when the perturbed samples
    are at least three apart (`sloshkit.plan.path.program.PathProgram.jacobians`' colours).

    Parameters
    ----------
    dspin : numpy.ndarray
        The spin's change at every sample, (n,) [rad].
    chosen : numpy.ndarray
        The perturbed samples, at least three apart.

    Returns
    -------
    tuple of numpy.ndarray
        Each chosen sample's turn (zero for the last sample) and, at every sample, the sum of
        those of the chosen samples two or more before it, (n,).

    Examples
    --------
    >>> import numpy as np
    >>> turn, earlier = spin_changes(np.array([0, 0.1, 0.3, 0.3, 0.3, 0.3]), np.array([1, 4]))
    >>> turn.round(12).tolist(), earlier.round(12).tolist()
    ([0.3, 0.0], [0.0, 0.0, 0.0, 0.3, 0.3, 0.3])
    """
    n = dspin.size
    after = dspin[np.minimum(chosen + 1, n - 1)]
    before = np.where(chosen >= 1, dspin[np.maximum(chosen - 1, 0)], 0.0)
    turn = np.where(chosen + 1 <= n - 1, after - before, 0.0)
    turned = np.zeros(n)
    turned[chosen] = turn
    earlier = np.zeros(n)
    earlier[2:] = np.cumsum(turned)[:-2]
    return turn, earlier


@dataclass(frozen=True, eq=False)
class TurnGains:
    """A pseudo-block's gains for `sloshkit.plan.path.condensing.condense`.

    Parameters
    ----------
    force : numpy.ndarray
        (3, modes + 1, n, 3): the forces' gains at the offsets -1, 0, 1 (only 0 is nonzero).
    rates : numpy.ndarray
        (3, n, 4): N's rates' gains at the same offsets.
    reach : int
        The samples either side whose rows the gains see: 0, their own sample only.

    Examples
    --------
    >>> import numpy as np
    >>> TurnGains(np.zeros((3, 2, 4, 3)), np.zeros((3, 4, 4))).reach
    0
    """

    force: FloatArray
    rates: FloatArray
    reach: int = 0


@dataclass(frozen=True, eq=False)
class AxialTurn:
    """N's turn about the axis in a program (module docstring).

    Parameters
    ----------
    blocks : list of tuple
        The pseudo-block (`TurnGains`, its rows (n, columns)) to condense with the others.
    starts : numpy.ndarray
        (segments, columns): sigma_i = C_{p_i} z, the turn at each segment's start in the
        splines; its variable is column ``first + i``.
    first : int
        The column of the first segment's turn.

    Examples
    --------
    >>> import numpy as np
    >>> turn = AxialTurn([], np.ones((2, 5)), 3)
    >>> turn.starts.shape[0]
    2
    """

    blocks: list[tuple[Any, FloatArray]]
    starts: FloatArray
    first: int

    def equalities(self) -> list[tuple[NDArray[np.int64], FloatArray]]:
        """The equality rows that tie the turns to the splines, as (columns, coefficients)
        of rows = 0: sigma_i - C_{p_i} z, each on every spline column before its start. (A
        chain sigma_i - sigma_{i-1} - (C_{p_i} - C_{p_{i-1}}) z, local rows, made the KKT
        factorisation of some programs five times slower: the chain couples every segment's
        turn to the next.)

        Returns
        -------
        list of tuple
            One (columns, coefficients) per segment start.

        Examples
        --------
        >>> import numpy as np
        >>> turn = AxialTurn([], np.array([[0.5, 0, 0, 0], [0.5, 0.2, 0, 0]]), 2)
        >>> [(c.tolist(), v.tolist()) for c, v in turn.equalities()]
        [([2, 0], [1.0, -0.5]), ([3, 0, 1], [1.0, -0.5, -0.2])]
        """
        rows = []
        for i, at_start in enumerate(self.starts[:, : self.first]):
            used = np.flatnonzero(at_start)
            rows.append(
                (
                    np.concatenate(([self.first + i], used)).astype(np.int64),
                    np.concatenate(([1.0], -at_start[used])),
                )
            )
        return rows


def axial_turn(
    blocks: list[tuple[Any, FloatArray]],
    force: FloatArray,
    rates: FloatArray,
    starts: list[int],
    first: int,
) -> AxialTurn | None:
    """The drive's dependence through N's turn about the axis (module docstring), or None
    when no sample's change turns N by more than `SPIN_FLOOR` (the axis keeps its direction).

    Parameters
    ----------
    blocks : list of tuple
        Each variable block's bands (`sloshkit.plan.path.program.PathProgram.jacobians`,
        with ``spin`` (n,): d spin_{k+1..} / d x_k) and rows (n, columns): each sample's
        derivative in the variables, whose columns ``first``, ``first + 1``, ... are the
        segments' turns (zero here).
    force : numpy.ndarray
        The forces in N at the samples, (modes + 1, n, 3).
    rates : numpy.ndarray
        N's lateral rates at the samples, (n, 4).
    starts : list of int
        The samples where segments 1, 2, ... start (`sloshkit.plan.path.condensing`).
    first : int
        The column of segment 1's turn.

    Returns
    -------
    AxialTurn or None

    Examples
    --------
    A tilt sample whose change turns N by 0.1 rad per radian: every sample two or more after
    it sees that turn, through its segment's start variable (column 2) after sample 3.

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> spin = np.zeros(6); spin[1] = 0.1
    >>> dz = np.zeros((6, 4)); dz[1, 0] = 1.0
    >>> turn = axial_turn([(SimpleNamespace(spin=spin), dz)], np.ones((1, 6, 3)),
    ...                   np.zeros((6, 4)), [3], 2)
    >>> turn.blocks[0][1][:, [0, 2]].tolist()
    [[0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]]
    >>> turn.starts.tolist()
    [[0.1, 0.0, 0.0, 0.0]]
    """
    n, columns = blocks[0][1].shape
    weighted = np.zeros((n, columns))
    for band, dz in blocks:
        spin = np.where(np.abs(band.spin) > SPIN_FLOOR, band.spin, 0.0)
        weighted += spin[:, None] * dz
    if not np.any(weighted):
        return None
    # C_j = sum over k <= j - 2
    total = np.zeros((n, columns))
    total[2:] = np.cumsum(weighted, axis=0)[:-2]
    at_starts = total[starts]
    segment = np.searchsorted(np.asarray(starts), np.arange(n), side="right")
    later = segment > 0
    rows = total.copy()
    rows[later] -= at_starts[segment[later] - 1]
    rows[np.flatnonzero(later), first + segment[later] - 1] = 1.0
    turned_force = np.zeros((3, *force.shape))
    turned_rates = np.zeros((3, *rates.shape))
    turned_force[1], turned_rates[1] = turned_about_axis(force, rates)
    return AxialTurn([(TurnGains(turned_force, turned_rates), rows)], at_starts, first)


__all__ = ["SPIN_FLOOR", "AxialTurn", "TurnGains", "axial_turn", "spin_changes"]
