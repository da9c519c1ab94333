"""Reading and validating surface meshes (trimesh objects or OBJ/PLY/OFF/STL/GLB files).

The input is never modified: a copy is cleaned. The checks are explicit so
a method never computes a silent wrong axis on a broken mesh.
"""

from __future__ import annotations

import dataclasses
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core import formats
from medialaxis.core.arrays import unique_ints
from medialaxis.core.validate import check_coordinates
from medialaxis.errors import (
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    MedialAxisWarning,
    UnsupportedFormatError,
)
from medialaxis.mesh.solid.contour import contoured
from medialaxis.mesh.solid.crossings import inside_out_shells
from medialaxis.mesh.solid.orientation import fix_winding

__all__ = ["MeshInput", "load_mesh", "resolve_solid", "signed_volume"]


@dataclasses.dataclass(frozen=True)
class MeshInput:
    """A validated triangle mesh.

    Attributes
    ----------
    mesh : trimesh.Trimesh
        A copy, as given where it is a closed, consistently oriented
        2-manifold (coincident but distinct vertices are kept); otherwise
        coincident vertices welded (triangle soups such as STL), degenerate
        and duplicate faces and unused vertices dropped, winding made
        consistent and the whole surface turned outward.
    repairs : tuple of str
        What was changed to make the mesh usable, if anything.
    volume : float
        Volume enclosed (:func:`signed_volume`, positive once turned
        outward); ``nan`` when the mesh need not be watertight.
    found : dict of str to int
        Where the mesh crosses itself or its shells nest (counts of
        :func:`resolve_solid`); empty when it bounds its solid plainly.
    """

    mesh: Any
    repairs: tuple[str, ...] = ()
    volume: float = float("nan")
    found: dict[str, int] = dataclasses.field(default_factory=dict)


def signed_volume(triangles: np.ndarray) -> float:
    """Signed volume bounded by ``(f, 3, 3)`` triangles (positive for outward normals), about their centre.

    The divergence theorem, one determinant per face: 0.04 s for the 200k
    faces of a uv ellipsoid, where trimesh's full mass properties take 0.35 s.
    """
    tri = np.asarray(triangles, np.float64)
    if not len(tri):
        return 0.0
    tri = tri - tri.reshape(-1, 3).mean(axis=0)  # about the centre: no cancellation far from the origin
    return float(np.einsum("ij,ij->", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))) / 6.0


def _read(path: Path) -> Any:
    trimesh = require("trimesh", "medialaxis[mesh]")
    if not path.is_file():
        raise InputFileError(f"no such file: {str(path)!r}")
    ext, known = formats.suffix_of(path), formats.suffixes("mesh")  # the formats trimesh reads for us
    if ext not in known:
        raise UnsupportedFormatError(f"unsupported mesh file type {ext!r}; use one of {', '.join(known)}")
    if ext == ".stl":
        _check_stl(path)
    try:
        loaded = trimesh.load(str(path), force="mesh", process=False)
    except IndexError as exc:
        raise InputFileError(f"cannot read mesh {str(path)!r}: a face refers to a vertex that does not exist ({exc})") from exc
    except ImportError as exc:  # trimesh guesses the encoding of text that is not UTF-8 with charset_normalizer
        if "charset_normalizer" not in str(exc):
            raise
        raise InputFileError(f"cannot read mesh {str(path)!r}: its text is not UTF-8 (a corrupt {ext} file?)") from exc
    except Exception as exc:  # noqa: BLE001 - trimesh raises many types on bad files
        raise InputFileError(f"cannot read mesh {str(path)!r}: {type(exc).__name__}: {exc}") from exc
    if not isinstance(loaded, trimesh.Trimesh):
        raise InputFileError(f"{str(path)!r} holds no triangle mesh")
    return loaded


def _check_stl(path: Path) -> None:
    """Refuse an STL that is neither a whole binary STL nor ASCII text, naming what is wrong.

    A binary STL is an 80-byte header, a triangle count ``n`` and ``50 n``
    bytes; anything else must be an ASCII STL (``solid ...``).
    """
    size = path.stat().st_size
    with open(path, "rb") as fh:
        head = fh.read(84)
        if len(head) == 84:
            count = int(np.frombuffer(head[80:84], "<u4")[0])
            if size == 84 + 50 * count:
                return  # binary, and whole
        fh.seek(0)
        sample = fh.read(1 << 16)
    text = sample.lstrip().lower().startswith(b"solid")
    try:
        sample.decode("ascii")
    except UnicodeDecodeError:
        text = False
    if text:
        return
    if len(head) < 84:
        raise InputFileError(f"{str(path)!r} is not an STL file: {size} bytes, no ASCII 'solid' header")
    raise InputFileError(
        f"{str(path)!r} is a truncated or corrupt binary STL: its header announces {count} triangles "
        f"({84 + 50 * count} bytes) but the file has {size} bytes"
    )


def resolve_solid(work: Any, repairs: list[str], found: dict[str, int], pairs: np.ndarray | None = None,
                  *, force: bool = False) -> Any:
    """``work``, or where its faces cross or its shells overlap or nest, the surface of its solid.

    The solid is where the generalized winding number is at least 1/2
    (:mod:`medialaxis.mesh.solid.arrangement`); what was found goes to ``found``
    and ``repairs``, and a :class:`~medialaxis.errors.MedialAxisWarning` says it.
    ``pairs``: the crossing face pairs when the caller has them. ``force``:
    cut along where faces meet (within the coordinates' accuracy) even
    where no face crosses another strictly (a crossing through a vertex);
    ``work`` itself if that changes nothing.
    """
    from medialaxis.mesh.solid.arrangement import solid_surface
    from medialaxis.mesh.solid.crossings import crossing_pairs, nested_shell
    from medialaxis.mesh.solid.degenerate import coordinate_accuracy
    from medialaxis.mesh.solid.pinches import carve_pinches

    pairs = crossing_pairs(work) if pairs is None else pairs
    nested = nested_shell(work) if not len(pairs) else None
    if not len(pairs) and nested is None and not force:
        return work
    vertices = np.asarray(work.vertices)
    try:
        surface = solid_surface(vertices, np.asarray(work.faces), coordinate_accuracy(vertices))
    except InvalidInputError as error:  # no face kept, or none at the coordinates' accuracy
        return contoured(work, f"the surface passes through itself ({len(pairs)} pairs of crossing faces) and {error}",
                         repairs, found)
    if force and not (surface.cut_faces or surface.dropped_faces or surface.flipped_faces):
        return work
    solid = type(work)(surface.vertices, surface.faces, process=False)
    if not _closed(solid) or not solid.is_winding_consistent:
        crowded, open_edges = _edge_defects(solid)
        return contoured(work, f"the surface passes through itself ({len(pairs)} pairs of crossing faces) and the surface "
                         f"of the solid its winding number defines is not a closed manifold ({open_edges} open edges, "
                         f"{crowded} edges of more than two faces: sheets within the accuracy of the coordinates)", repairs, found)
    what = (f"the surface passes through itself ({len(pairs)} pairs of faces cross)" if len(pairs)
            else f"shell {nested} lies inside another shell's solid (nested or overlapping shells)" if nested is not None
            else "the surface passes through itself (where faces meet at a vertex or an edge)")
    solid, pinches = carve_pinches(solid)  # the interior's topology where the solid touches itself at a point
    done = (f"{surface.cut_faces} faces cut where others cross them, {surface.dropped_faces} left out inside or outside "
            f"the solid" + (f", {surface.flipped_faces} turned over" if surface.flipped_faces else "")
            + (f", {pinches} points where it touches itself opened by a small ball" if pinches else ""))
    found.update(crossing_face_pairs=int(len(pairs)), nested_shells=int(nested is not None),
                 cut_faces=surface.cut_faces, dropped_faces=surface.dropped_faces)
    found.update({"pinches_opened": pinches} if pinches else {})
    repairs.append(f"solid by winding number: {done}")
    warnings.warn(f"{what}: the medial axis is that of the solid where its winding number is at least 1/2 "
                  f"({done})", MedialAxisWarning, stacklevel=4)
    return solid


def _edge_defects(mesh: Any) -> tuple[int, int]:
    """Edges shared by more than two faces, and open edges (one face)."""
    shared = np.bincount(mesh.edges_unique_inverse, minlength=len(mesh.edges_unique))
    return int((shared > 2).sum()), int((shared == 1).sum())


def _area(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Area of the triangles ``faces`` of ``vertices``."""
    t = vertices[faces]
    return float(np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum() / 2)


def _closed(mesh: Any) -> bool:
    """Every edge (by vertex index) shared by exactly two faces."""
    return bool(mesh.is_watertight)


def _drop_bad_faces(vertices: np.ndarray, faces: np.ndarray, repairs: list[str], *, flat: bool = True) -> np.ndarray:
    """Faces without a repeated vertex, each once, and (``flat``) of non-zero area; what was dropped goes to ``repairs``.

    Zero-area faces are kept with ``flat=False``: on a closed surface their
    edges are shared like any other's, and dropping them would open it
    (:mod:`medialaxis.mesh.solid.degenerate` takes them out without opening it).
    """
    repeated = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    keep = ~repeated
    if flat:
        tri = vertices[faces]
        area2 = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        scale = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
        keep &= area2 > (1e-14 * scale) ** 2
    unique = np.isin(np.arange(len(faces)), np.unique(np.sort(faces, axis=1), axis=0, return_index=True)[1])
    degenerate = int((~keep).sum())
    duplicate = int((keep & ~unique).sum())
    if degenerate:
        repairs.append(f"dropped {degenerate} degenerate faces" + ("" if flat else " (a vertex repeated)"))
    if duplicate:
        repairs.append(f"dropped {duplicate} duplicate faces")
    faces = faces[keep & unique]
    if len(faces) == 0:
        raise EmptyShapeError("every face of the mesh is degenerate")
    return faces


def _take_out_degenerate(work: Any, repairs: list[str]) -> Any:
    """The closed ``work`` without its zero-area faces (flips, collapses; :mod:`medialaxis.mesh.solid.degenerate`)."""
    from medialaxis.mesh.solid.degenerate import coordinate_accuracy, remove_degenerate_faces

    vertices = np.asarray(work.vertices)
    faces, flipped, collapsed, kept = remove_degenerate_faces(vertices, np.asarray(work.faces), coordinate_accuracy(vertices))
    if not flipped + collapsed + kept:
        return work
    done = [f"{flipped} flipped away" if flipped else "", f"{collapsed} collapsed" if collapsed else "",
            f"{kept} kept (no flip or collapse keeps the surface closed)" if kept else ""]
    repairs.append(f"zero-area faces: {', '.join(x for x in done if x)}")
    warnings.warn(f"the mesh has {flipped + collapsed + kept} zero-area faces (at the accuracy of its coordinates): "
                  f"{', '.join(x for x in done if x)}; the surface stays closed", MedialAxisWarning, stacklevel=4)
    work = type(work)(vertices, faces, process=False)
    work.remove_unreferenced_vertices()
    return work


#: Caps larger than this share of a mesh's area do not repair it: its solid is contoured (:mod:`.contour`).
SOUP_CAPS = 0.5
#: Holes up to this fraction of the mesh's size across are capped at once; larger ones where the
#: open surface's winding number decides the solid (:func:`medialaxis.mesh.solid.holes.undecided_share`).
SMALL_HOLE = 0.1
#: A mesh whose winding number is undecided over more than this share of what caps enclose bounds no solid
#: (open sheets and shells without a bottom: 0.89-1 on the real models, 0.43 for a hemisphere; scans with
#: holes, as the Stanford bunny's: at most 0.17).
UNDECIDED_SOLID = 0.25


def _paired(faces: np.ndarray) -> bool:
    """Whether each edge has as many faces along it one way as the other (a closed surface, touching solids included)."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    _, inverse = np.unique(np.sort(directed, axis=1), axis=0, return_inverse=True)
    balance = np.zeros(inverse.max() + 1, np.int64)
    np.add.at(balance, inverse.ravel(), np.where(directed[:, 0] < directed[:, 1], 1, -1))
    return not balance.any()


def _touching_solids(work: Any, crowded: int, repairs: list[str], found: dict[str, int]) -> Any:
    """The closed ``work`` whose solids touch along edges of four or more faces, as a 2-manifold (its solid's surface)."""
    from medialaxis.mesh.solid.arrangement import solid_surface
    from medialaxis.mesh.solid.degenerate import coordinate_accuracy

    vertices = np.asarray(work.vertices)
    surface = solid_surface(vertices, np.asarray(work.faces), coordinate_accuracy(vertices))
    solid = type(work)(surface.vertices, surface.faces, process=False)
    if not _closed(solid):
        return contoured(work, f"the mesh has {crowded} edges of more than two faces around which the surface of its "
                         "solid (by winding number) is not a closed manifold", repairs, found)
    found["shared_edges"] = crowded
    done = f"{crowded} edges of more than two faces (solids touching along them) kept apart, one side per solid"
    repairs.append(done)
    warnings.warn(f"the mesh is not a 2-manifold: {done}", MedialAxisWarning, stacklevel=5)
    return solid


def _close_holes(work: Any, repair: bool, repairs: list[str], found: dict[str, int]) -> Any:
    """The open ``work`` with its holes capped (:mod:`medialaxis.mesh.solid.holes`): small ones always, any with ``repair``."""
    from medialaxis.mesh.solid.holes import boundary_loops, cap_holes, undecided_share

    crowded, open_edges = _edge_defects(work)
    if crowded:
        if open_edges or not _paired(np.asarray(work.faces)):
            return contoured(work, f"the mesh is not watertight ({open_edges} open edges, {crowded} edges of more than "
                             "two faces that do not pair up in opposite directions)", repairs, found)
        return _touching_solids(work, crowded, repairs, found)
    fix_winding(work)  # on open surfaces too; nothing to do where the winding agrees
    loops = boundary_loops(np.asarray(work.faces))
    if not loops:
        return contoured(work, f"the mesh is not watertight ({open_edges} open edges; three holes or more touch at a "
                         "vertex)", repairs, found)
    vertices = np.asarray(work.vertices)
    size = float(np.linalg.norm(np.ptp(vertices, axis=0)))
    across = max(float(np.linalg.norm(np.ptp(vertices[loop], axis=0))) for loop in loops)
    capped_vertices, capped_faces = cap_holes(vertices, np.asarray(work.faces), loops)
    decided = ""
    if across > SMALL_HOLE * size and not repair:
        share = undecided_share(vertices, np.asarray(work.faces), capped_vertices, capped_faces)
        if share > UNDECIDED_SOLID:
            raise InvalidInputError(
                f"the mesh is not watertight and bounds no solid: its {len(loops)} holes ({open_edges} open edges, the "
                f"largest {across:.3g} across, {100 * across / size:.0f}% of its size) leave its winding number "
                f"undecided over {100 * share:.0f}% of what caps would enclose; close them first or pass repair=True "
                "to cap them anyway"
            )
        decided = f" (its winding number is undecided over {100 * share:.1f}% of the solid)"
    elif not repair and _area(capped_vertices, capped_faces[len(work.faces):]) > SOUP_CAPS * work.area:
        return contoured(work, f"the mesh is not watertight ({open_edges} open edges in {len(loops)} holes whose caps "
                         f"would be more than {SOUP_CAPS:.0%} of its area: a triangle soup)", repairs, found)
    found["holes"] = len(loops)
    vertices, faces = capped_vertices, capped_faces
    done = (f"closed {len(loops)} holes ({open_edges} open edges), the largest {across:.3g} across, with flat caps"
            + decided)
    repairs.append(done)
    warnings.warn(f"the mesh is not watertight: {done}; the solid is the one its winding number defines",
                  MedialAxisWarning, stacklevel=4)
    return type(work)(vertices, faces, process=False)


def load_mesh(mesh: Any, *, watertight: bool = True, repair: bool = False, crossing: bool = True) -> MeshInput:
    """Read and check a mesh.

    Parameters
    ----------
    mesh : trimesh.Trimesh or path
    watertight : bool
        Require a closed (watertight) surface bounding a positive volume.
    repair : bool
        Cap the holes of a non-watertight mesh even where its winding number
        leaves the solid undecided. Without it, holes up to ``SMALL_HOLE`` of
        the mesh's size, and larger ones where the open surface's winding
        number decides the solid (undecided over at most
        ``UNDECIDED_SOLID`` of it), are capped with a warning; the repair is
        reported either way.
    crossing : bool
        Look for crossing faces on a watertight mesh and take the surface of
        its solid by winding number where there are (:func:`resolve_solid`;
        ``False``: the caller does, e.g. beside other work). Nested shells
        are looked for either way.

    Raises
    ------
    InputFileError
        Unreadable or corrupt file.
    EmptyShapeError
        No faces, or zero volume.
    InvalidInputError
        Non-finite coordinates, or a mesh that is not watertight when required.
    """
    trimesh = require("trimesh", "medialaxis[mesh]")
    if isinstance(mesh, (str, os.PathLike)):
        source = _read(Path(mesh))
    elif isinstance(mesh, trimesh.Trimesh):
        source = mesh
    elif hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        source = trimesh.Trimesh(np.asarray(mesh.vertices), np.asarray(mesh.faces), process=False)
    else:
        raise InvalidInputError(f"expected a trimesh.Trimesh or a mesh file, got {type(mesh).__name__}")
    vertices = np.array(source.vertices, dtype=np.float64, copy=True)
    faces = np.array(source.faces, dtype=np.int64, copy=True)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise InvalidInputError(f"mesh vertices must have shape (n, 3), got {vertices.shape}")
    if len(faces) == 0 or len(vertices) < 4:
        raise EmptyShapeError(f"the mesh is empty ({len(vertices)} vertices, {len(faces)} faces)")
    check_coordinates(vertices, "mesh vertices")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise InvalidInputError("mesh faces index vertices that do not exist")
    repairs: list[str] = []
    faces = _drop_bad_faces(vertices, faces, repairs, flat=not watertight)
    work = trimesh.Trimesh(vertices, faces, process=False)
    if not _closed(work):
        # Triangle soups (STL) and some exporters do not share the vertices
        # of adjacent faces: weld coincident vertices. A mesh that is closed
        # as given keeps its vertices, coincident ones included (a boolean
        # union keeps the two sides of a touching edge apart on purpose).
        welded = work.copy()
        welded.merge_vertices(merge_tex=True, merge_norm=True)
        welded = trimesh.Trimesh(welded.vertices, _drop_bad_faces(welded.vertices, welded.faces, [], flat=not watertight),
                                 process=False)  # faces whose corners were welded together
        if _closed(welded) or not watertight or _edge_defects(welded) < _edge_defects(work):  # seams welded, holes left
            if len(welded.vertices) < len(work.vertices):
                repairs.append(f"welded {len(work.vertices) - len(welded.vertices)} coincident vertices")
            work = welded
    unused = len(work.vertices) - len(unique_ints(work.faces))
    if unused:
        work.remove_unreferenced_vertices()
        repairs.append(f"dropped {unused} vertices used by no face")
    found: dict[str, int] = {}
    if watertight:
        if not _closed(work):
            work = _close_holes(work, repair, repairs, found)
        if not work.is_winding_consistent:
            fix_winding(work)
            repairs.append("made face winding consistent")
        work = _take_out_degenerate(work, repairs)
        volume = signed_volume(work.triangles)
        if volume < 0:
            work.invert()
            repairs.append("flipped inward-facing normals")
            volume = -volume
        turned = inside_out_shells(work.vertices, work.faces)
        if len(turned):  # a part turned over by its exporter, enclosed by nothing: a solid, not a cavity
            faces = np.array(work.faces)
            faces[turned] = faces[turned][:, ::-1]
            work = trimesh.Trimesh(work.vertices, faces, process=False)
            repairs.append(f"turned {len(turned)} faces of shells facing inward with nothing around them outward")
            warnings.warn(f"{len(turned)} faces of shells facing inward with nothing around them were turned outward: "
                          "they bound parts, not cavities", MedialAxisWarning, stacklevel=3)
            volume = signed_volume(work.triangles)
        if not volume > 0:
            raise EmptyShapeError(f"the mesh encloses no volume (volume {volume:.3g})")
        solid = resolve_solid(work, repairs, found, None if crossing else np.empty((0, 2), np.int64))
        if solid is not work:
            work, volume = solid, signed_volume(solid.triangles)
        return MeshInput(work, tuple(repairs), volume, found)
    return MeshInput(work, tuple(repairs))
