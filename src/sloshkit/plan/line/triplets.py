"""Sparse matrices as (row, column, value) triplets, the form the export grid's linear programs
are written in (`sloshkit.plan.line.grid_program`, `sloshkit.plan.line.export_grid`) and handed
to HiGHS: entries at the same position summed, sorted by column, then compressed column-wise.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


class Triplets(NamedTuple):
    """A sparse matrix as (row, column, value) entries, duplicates summed.

    Parameters
    ----------
    rows, columns : ndarray of int
        Entry positions.
    values : ndarray
        Entry values.
    shape : tuple of int
        (rows, columns) of the matrix.

    Examples
    --------
    >>> import numpy as np
    >>> m = Triplets.summed(np.array([0, 0]), np.array([1, 1]), np.array([2.0, 3.0]), (1, 2))
    >>> m.values.tolist(), m.shape
    ([5.0], (1, 2))
    """

    rows: NDArray[np.int64]
    columns: NDArray[np.int64]
    values: FloatArray
    shape: tuple[int, int]

    @classmethod
    def summed(
        cls,
        rows: NDArray[np.int64],
        columns: NDArray[np.int64],
        values: FloatArray,
        shape: tuple[int, int],
    ) -> Triplets:
        """The entries sorted by column, then row, with duplicate positions summed."""
        order = np.lexsort((rows, columns))
        rows, columns, values = rows[order], columns[order], values[order]
        first = np.ones(rows.size, dtype=bool)
        first[1:] = (rows[1:] != rows[:-1]) | (columns[1:] != columns[:-1])
        starts = np.flatnonzero(first)
        return cls(rows[starts], columns[starts], np.add.reduceat(values, starts), shape)

    def compressed_columns(self) -> tuple[NDArray[np.int32], NDArray[np.int32], FloatArray]:
        """(start, index, value): the column-wise layout HiGHS takes (the entries are sorted
        by column)."""
        counts = np.bincount(self.columns, minlength=self.shape[1])
        start = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        return start, self.rows.astype(np.int32), np.asarray(self.values, dtype=float)
