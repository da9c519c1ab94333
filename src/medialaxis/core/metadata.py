"""Result metadata as JSON holds it, so that a saved result reads back equal (:mod:`medialaxis.core.lossless`)."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import numpy as np

__all__ = ["frozen_metadata", "jsonable"]


def frozen_metadata(value: Mapping[str, Any]) -> Mapping[str, Any]:
    """Metadata made plain: a read-only mapping of what JSON holds (text keys, lists, Python numbers).

    So that a saved result reads back equal (:mod:`medialaxis.core.lossless`)
    and ``json.dumps(dict(ma.metadata))`` works. Sequences are lists, not
    tuples: ``vertices[ma.metadata["fixed_vertices"]]`` indexes rows, where
    NumPy takes a tuple for one index per axis.

    >>> frozen_metadata({"spacing": (0.5, np.float64(1.0)), "shape": np.array([2, 3]), 1: {"a": (None,)}})
    mappingproxy({'spacing': [0.5, 1.0], 'shape': [2, 3], '1': {'a': [None]}})
    """
    return MappingProxyType(jsonable(dict(value)))


def jsonable(value: Any) -> Any:
    """``value`` as JSON holds it: mappings as dicts with text keys, sequences and arrays as lists, Python numbers."""
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value
