"""The block-reader interface of the chunked route (:class:`Source`) and the checks every source makes."""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["Source", "Region", "check_volume"]


Region = tuple[slice, slice, slice]


class Source:
    """A 3D volume read by boxes.

    Attributes
    ----------
    shape : tuple of 3 int
    dtype : numpy dtype
    spacing : tuple of 3 float or None
        Voxel size per array axis when the file records it.
    name : str
        For messages.
    """

    shape: tuple[int, int, int]
    dtype: np.dtype
    spacing: tuple[float, float, float] | None = None
    name: str = "volume"

    def read(self, region: Region) -> np.ndarray:
        """The voxels of ``region`` (slices with explicit bounds inside ``shape``) as a new array."""
        raise NotImplementedError

    @property
    def nbytes(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64)) * self.dtype.itemsize


def check_volume(shape: Any, dtype: Any, name: str) -> tuple[tuple[int, int, int], np.dtype]:
    shape = tuple(int(s) for s in shape)
    if len(shape) != 3:
        raise InvalidInputError(f"{name}: a volume must be a 3D array, got shape {shape}")
    if min(shape) < 3:
        raise InvalidInputError(f"{name}: a volume needs at least 3 voxels per axis, got shape {shape}")
    dt = np.dtype(dtype)
    if not (dt.kind == "b" or (np.issubdtype(dt, np.number) and not np.issubdtype(dt, np.complexfloating))):
        raise InvalidInputError(f"{name}: a volume must be bool or numeric, got dtype {dt}")
    return shape, dt  # type: ignore[return-value]
