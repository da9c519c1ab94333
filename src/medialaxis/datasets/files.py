"""The sample files bundled with the package (``src/medialaxis/data/``, described in its README).

Four Kimia-99 silhouettes (Sebastian, Klein, Kimia; MIT licence), an
L-shaped bracket with two round holes (WKT), a gasket as drawing programs
write SVG and a plate in DXF (both made for medialaxis, BSD-3-Clause).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["SAMPLES", "data_path", "kimia_mask"]

#: Each bundled file with what it holds and what is known of its medial axis.
SAMPLES: dict[str, str] = {
    "kimia_class1_01.png": "Kimia-99 silhouette, class 1 (128 x 128 binary PNG; one piece, no hole)",
    "kimia_class3_05.png": "Kimia-99 silhouette, class 3 (128 x 128 binary PNG; one piece, no hole)",
    "kimia_class5_03.png": "Kimia-99 silhouette, class 5 (128 x 128 binary PNG; one piece, no hole)",
    "kimia_class8_05.png": "Kimia-99 silhouette, class 8 (128 x 128 binary PNG; one piece, no hole)",
    "bracket_two_holes.wkt": "an L-shaped bracket with two round holes (WKT polygon): its axis has 2 cycles",
    "gasket.svg": "a gasket as drawing programs write SVG: a path of arcs, a round hole and a slot "
                  "(even-odd rule), a group transform, millimetre units",
    "plate_slot.dxf": "a plate with filleted corners, a hole (CIRCLE) and a slot on layer CUT, "
                      "a TEXT on layer NOTES (read it with layers=['CUT'])",
}


def data_path(name: str) -> Path:
    """Path of a bundled sample file.

    Parameters
    ----------
    name : str
        One of :data:`SAMPLES`.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    InvalidInputError
        A name that is not a bundled file.

    Examples
    --------
    >>> import medialaxis as mx
    >>> from medialaxis.datasets import data_path
    >>> mx.medial_axis(data_path("bracket_two_holes.wkt").read_text()).n_cycles
    2
    """
    if name not in SAMPLES:
        raise InvalidInputError(f"no bundled sample {name!r}; the samples are {', '.join(SAMPLES)}")
    return Path(str(resources.files("medialaxis") / "data" / name))


def kimia_mask(name: str = "kimia_class1_01.png") -> np.ndarray:
    """A bundled Kimia-99 silhouette as a boolean mask (``True`` inside).

    Parameters
    ----------
    name : str
        One of the ``kimia_*.png`` names of :data:`SAMPLES`.

    Returns
    -------
    (128, 128) bool ndarray

    Examples
    --------
    >>> from medialaxis.datasets import kimia_mask
    >>> mask = kimia_mask("kimia_class3_05.png")
    >>> mask.shape, mask.dtype.name
    ((128, 128), 'bool')
    """
    from PIL import Image

    if not name.startswith("kimia_"):
        raise InvalidInputError(f"{name!r} is not a Kimia silhouette; use one of "
                                f"{', '.join(n for n in SAMPLES if n.startswith('kimia_'))}")
    with Image.open(data_path(name)) as image:
        return np.asarray(image.convert("L")) > 127
