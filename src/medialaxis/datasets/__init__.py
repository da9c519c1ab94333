"""Sample shapes with known answers: bundled files, planar shapes, meshes and CT-like volumes.

Each dataset says what its medial axis is where that is known exactly, so a
result can be checked against it:

- **Bundled files** (:mod:`medialaxis.datasets.files`): :func:`data_path`
  of each of :data:`SAMPLES` (four Kimia-99 silhouettes, a bracket with two
  holes as WKT, a gasket as SVG, a plate as DXF) and :func:`kimia_mask`.
- **Planar shapes** (:mod:`medialaxis.datasets.shapes`): a rectangle, an
  ellipse, an annulus and a capsule with their exact axes
  (:func:`rectangle_axis`, :func:`ellipse_axis`); :func:`holed_shapes`, plates
  with the numbers of holes in :data:`HOLES`; :func:`render` and
  :func:`rasterize` to images, :func:`raster_counts` to count a mask's pieces
  and holes with scikit-image.
- **Meshes** (:mod:`medialaxis.datasets.meshes`, needs ``medialaxis[mesh]``):
  unions of capsules (:func:`capsules_mesh`, :func:`tripod_mesh`) whose curve
  skeleton is their segments and whose radius is known; :func:`torus_mesh`;
  :func:`segment_distance` from points to the true axis.
- **Volumes** (:mod:`medialaxis.datasets.phantoms`): blurred, noisy plates
  (a T, an X, a box member, a ribbed panel) with their exact mid-surfaces
  (:class:`Rect`) and thicknesses.

Nothing here imports the domains (planar, mesh, volume): the datasets sit
below them, with the core.

>>> import medialaxis as mx
>>> from medialaxis import datasets
>>> ma = mx.medial_axis(datasets.data_path("bracket_two_holes.wkt").read_text())
>>> ma.n_cycles  # one cycle around each of the bracket's two holes
2
>>> phantom = datasets.t_phantom((40, 60, 60), margin=6)
>>> phantom.plate_thickness
(6.0, 6.0)
"""

from __future__ import annotations

from medialaxis.datasets.files import SAMPLES, data_path, kimia_mask
from medialaxis.datasets.meshes import capsules_mesh, segment_distance, torus_mesh, tripod_mesh, tripod_segments
from medialaxis.datasets.phantoms import (
    Phantom,
    Rect,
    member_phantom,
    ribbed_panel,
    ribbed_panel_slab,
    ribbed_panel_truth,
    t_phantom,
    x_phantom,
)
from medialaxis.datasets.shapes import (
    HOLES,
    annulus,
    capsule,
    ellipse,
    ellipse_axis,
    holed_shapes,
    in_image,
    raster_counts,
    rasterize,
    rectangle_axis,
    render,
    rotation,
)

__all__ = [
    "SAMPLES", "data_path", "kimia_mask",
    "capsules_mesh", "segment_distance", "torus_mesh", "tripod_mesh", "tripod_segments",
    "Phantom", "Rect", "member_phantom", "ribbed_panel", "ribbed_panel_slab", "ribbed_panel_truth", "t_phantom",
    "x_phantom",
    "HOLES", "annulus", "capsule", "ellipse", "ellipse_axis", "holed_shapes", "in_image", "raster_counts",
    "rasterize", "rectangle_axis", "render", "rotation",
]
