"""A branch of an axis: the chain between two nodes that are junctions or endpoints."""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["Branch"]


@dataclasses.dataclass(frozen=True, eq=False)
class Branch:
    """A chain of the axis between two nodes that are junctions or endpoints.

    Attributes
    ----------
    indices : (p,) int64 ndarray
        Point indices along the chain, in order. For a closed loop without
        junctions the first index is repeated at the end.
    points : (p, d) float64 ndarray
        The chain's coordinates.
    radii : (p,) float64 ndarray
        The radius function along the chain.
    """

    indices: np.ndarray
    points: np.ndarray
    radii: np.ndarray

    @property
    def length(self) -> float:
        """Polyline length of the chain."""
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())

    @property
    def is_cycle(self) -> bool:
        """True when the chain closes on itself."""
        return len(self.indices) > 1 and self.indices[0] == self.indices[-1]

    def __repr__(self) -> str:
        ends = "cycle" if self.is_cycle else f"{int(self.indices[0])}->{int(self.indices[-1])}"
        radius = f"{self.radii.min():.4g}..{self.radii.max():.4g}" if len(self.radii) else "-"
        return f"Branch({ends}, points={len(self.indices)}, length={self.length:.4g}, radius={radius})"
