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
from medialaxis.core.arrays import unique_ints
from medialaxis.core.validate import check_coordinates
from medialaxis.errors import (
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    MedialAxisWarning,
    UnsupportedFormatError,
)

__all__ = ["MeshInput", "load_mesh", "signed_volume", "MESH_EXTENSIONS"]

MESH_EXTENSIONS = (".obj", ".ply", ".off", ".stl", ".glb", ".gltf")


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
    """

    mesh: Any
    repairs: tuple[str, ...] = ()
    volume: float = float("nan")


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
    ext = path.suffix.lower()
    if ext not in MESH_EXTENSIONS:
        raise UnsupportedFormatError(f"unsupported mesh file type {ext!r}; use one of {', '.join(MESH_EXTENSIONS)}")
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


def _solid_angle_sums(points: np.ndarray, triangles: np.ndarray, chunk: int = 2_000_000) -> np.ndarray:
    """Winding number of the closed triangle surface ``triangles`` (T, 3, 3) at each of ``points`` (P, 3).

    Sum of the signed solid angles of the triangles (Van Oosterom and
    Strackee), over 4 pi: 1 inside, 0 outside, 1/2 on the surface.
    """
    out = np.zeros(len(points))
    step = max(1, chunk // max(len(triangles), 1))
    for start in range(0, len(points), step):
        rel = triangles[None, :, :, :] - points[start : start + step, None, None, :]
        a, b, c = rel[:, :, 0], rel[:, :, 1], rel[:, :, 2]
        la, lb, lc = (np.linalg.norm(v, axis=2) for v in (a, b, c))
        det = np.einsum("ptk,ptk->pt", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ptk,ptk->pt", a, b) * lc + np.einsum("ptk,ptk->pt", a, c) * lb
               + np.einsum("ptk,ptk->pt", b, c) * la)
        out[start : start + step] = 2.0 * np.arctan2(det, den).sum(axis=1) / (4.0 * np.pi)
    return out


#: Vertices of a shell tested against the other shells (evenly spaced subset beyond this).
SHELL_PROBES = 500


def shell_labels(mesh: Any) -> np.ndarray:
    """Shell (connected set of faces) of each face: outer shells and cavities of a closed mesh."""
    from trimesh.graph import connected_component_labels

    return connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces))


def check_shells(mesh: Any) -> None:
    """Refuse a mesh whose outer shells overlap or lie inside one another.

    A closed mesh of several shells bounds a solid only if each outward
    shell lies outside every other shell's solid (inward shells are
    cavities, inside their outer shell). A vertex of an outward shell where
    the other shells' winding number is about 1 lies in another shell's
    solid: the surface is self-intersecting or has nested shells (nested
    shells do not cross, so :func:`check_self_intersection` alone misses
    them). Both mesh methods run both checks.

    Raises
    ------
    InvalidInputError
    """
    labels = shell_labels(mesh)
    n_shells = int(labels.max()) + 1
    if n_shells < 2:
        return
    tri = np.asarray(mesh.triangles)
    shells = [np.flatnonzero(labels == k) for k in range(n_shells)]
    lo = np.array([tri[f].reshape(-1, 3).min(axis=0) for f in shells])
    hi = np.array([tri[f].reshape(-1, 3).max(axis=0) for f in shells])
    for k, faces in enumerate(shells):
        if signed_volume(tri[faces]) <= 0:
            continue  # a cavity
        vertices = unique_ints(mesh.faces[faces])
        pick = np.linspace(0, len(vertices) - 1, min(SHELL_PROBES, len(vertices))).astype(int)
        probes = np.asarray(mesh.vertices)[vertices[pick]]
        # Only shells whose boxes meet this one's can hold its vertices; the
        # winding numbers of closed shells add up (a cavity's is -1 inside).
        winding = np.zeros(len(probes))
        for j in np.flatnonzero(np.all((lo <= hi[k]) & (hi >= lo[k]), axis=1)):
            if j == k:
                continue
            near = np.all((probes >= lo[j]) & (probes <= hi[j]), axis=1)
            if near.any():
                winding[near] += _solid_angle_sums(probes[near], tri[shells[j]])
        if (winding > 0.75).any():
            raise InvalidInputError(
                f"the mesh has {n_shells} shells and shell {k} lies (partly) inside another one's solid: the surface "
                "is self-intersecting or has nested shells; fix it (e.g. a mesh boolean union) first"
            )


def _sphere_pairs(tri: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Pairs ``(i, j)`` of triangles that may cross (a superset: bounding spheres about the centroids meet).

    Triangles up to twice the median size are binned on a grid
    (:func:`~medialaxis.mesh._intersect_kernels.near_pairs`, which also
    drops the pairs with a shared vertex or apart bounding boxes); the
    larger ones (slivers, long CAD faces) are matched against every
    triangle within their own reach.
    """
    from scipy.spatial import cKDTree

    from medialaxis.mesh._intersect_kernels import near_pairs

    centre = tri.mean(axis=1)
    radius = np.linalg.norm(tri - centre[:, None, :], axis=2).max(axis=1)
    small = radius <= 2.0 * float(np.median(radius))
    idx = np.flatnonzero(small)
    pairs = []
    if len(idx) > 1:
        cell = max(2.0 * float(radius[idx].max()), 2.0**-19)  # ``tri`` lies in a unit box: at most 2^19 cells a side
        pairs.append(near_pairs(tri, faces, centre, radius, idx, cell))
    big = np.flatnonzero(~small)
    if len(big):
        near = cKDTree(centre).query_ball_point(centre[big], radius[big] + float(radius.max()), return_sorted=False)
        count = np.fromiter((len(js) for js in near), np.int64, len(big))
        js = np.concatenate([np.asarray(j, np.int64) for j in near]) if count.sum() else np.empty(0, np.int64)
        bs = np.repeat(big, count)
        keep = (js != bs) & (small[js] | (js > bs))  # big-big pairs once
        keep &= np.linalg.norm(centre[js] - centre[bs], axis=1) <= radius[js] + radius[bs]
        pairs.append(np.column_stack([bs[keep], js[keep]]))
    return np.ascontiguousarray(np.vstack(pairs), dtype=np.int64) if pairs else np.empty((0, 2), np.int64)


def check_self_intersection(mesh: Any) -> None:
    """Refuse a surface that passes through itself: two faces sharing no vertex that cross.

    Faces that only touch (a boolean union's touching edge, coincident
    vertices) do not count. Both mesh methods run this check.

    Raises
    ------
    InvalidInputError
    """
    from medialaxis.mesh._intersect_kernels import first_crossing

    v = np.asarray(mesh.vertices, np.float64)
    f = np.asarray(mesh.faces, np.int64)
    centre, size = v.mean(axis=0), float(np.ptp(v, axis=0).max()) or 1.0
    tri = np.ascontiguousarray(((v - centre) / size)[f])
    # tolerance on orientation determinants (volumes), from the typical edge
    edge = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2)
    tol = 1e-9 * float(np.median(edge)) ** 3
    f = np.ascontiguousarray(f)
    pairs = _sphere_pairs(tri, f)
    k = first_crossing(tri, f, pairs, tol)
    if k >= 0:
        i, j = (int(x) for x in pairs[k])
        raise InvalidInputError(
            f"the surface passes through itself (faces {i} and {j} cross): it is self-intersecting; "
            "fix it (e.g. a mesh boolean union or a remesher) first"
        )


def _closed(mesh: Any) -> bool:
    """Every edge (by vertex index) shared by exactly two faces."""
    return bool(mesh.is_watertight)


def _drop_bad_faces(vertices: np.ndarray, faces: np.ndarray, repairs: list[str], *, flat: bool = True) -> np.ndarray:
    """Faces without a repeated vertex, each once, and (``flat``) of non-zero area; what was dropped goes to ``repairs``.

    Zero-area faces are kept with ``flat=False``: on a closed surface their
    edges are shared like any other's, and dropping them would open it
    (:mod:`medialaxis.mesh.degenerate` takes them out without opening it).
    """
    repeated = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    keep = ~repeated
    if flat:
        tri = vertices[faces]
        area2 = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        scale = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
        keep &= area2 > (1e-14 * scale) ** 2
    _, first = np.unique(np.sort(faces, axis=1), axis=0, return_index=True)
    unique = np.zeros(len(faces), bool)
    unique[first] = True
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
    """The closed ``work`` without its zero-area faces (flips, collapses; :mod:`medialaxis.mesh.degenerate`)."""
    from medialaxis.mesh.degenerate import coordinate_accuracy, remove_degenerate_faces

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


def load_mesh(mesh: Any, *, watertight: bool = True, repair: bool = False, crossing: bool = True) -> MeshInput:
    """Read and check a mesh.

    Parameters
    ----------
    mesh : trimesh.Trimesh or path
    watertight : bool
        Require a closed (watertight) surface bounding a positive volume.
    repair : bool
        Try to close small holes (``trimesh.repair.fill_holes``) before
        refusing a non-watertight mesh; the repair is reported.
    crossing : bool
        Run :func:`check_self_intersection` on a watertight mesh (``False``:
        the caller runs it, e.g. beside other work).

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
        if _closed(welded) or not watertight:
            if len(welded.vertices) < len(work.vertices):
                repairs.append(f"welded {len(work.vertices) - len(welded.vertices)} coincident vertices")
            work = welded
    unused = len(work.vertices) - len(unique_ints(work.faces))
    if unused:
        work.remove_unreferenced_vertices()
        repairs.append(f"dropped {unused} vertices used by no face")
    if watertight and not _closed(work) and repair:
        trimesh.repair.fill_holes(work)
        if _closed(work):
            repairs.append("closed holes with trimesh.repair.fill_holes")
    if watertight:
        if not _closed(work):
            shared = np.bincount(work.edges_unique_inverse, minlength=len(work.edges_unique))
            open_edges, crowded = int((shared == 1).sum()), int((shared > 2).sum())
            raise InvalidInputError(
                f"the mesh is not watertight ({open_edges} open edges, {crowded} edges shared by more than two "
                "faces); close it first or pass repair=True"
            )
        if not work.is_winding_consistent:
            trimesh.repair.fix_winding(work)
            repairs.append("made face winding consistent")
        work = _take_out_degenerate(work, repairs)
        volume = signed_volume(work.triangles)
        if volume < 0:
            work.invert()
            repairs.append("flipped inward-facing normals")
            volume = -volume
        if not volume > 0:
            raise EmptyShapeError(f"the mesh encloses no volume (volume {volume:.3g})")
        check_shells(work)
        if crossing:
            check_self_intersection(work)
        return MeshInput(work, tuple(repairs), volume)
    return MeshInput(work, tuple(repairs))
