"""Reading and validating surface meshes (trimesh objects or OBJ/PLY/OFF/STL/GLB files).

The input is never modified: a copy is cleaned. The checks are explicit so
a method never computes a silent wrong axis on a broken mesh.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError, UnsupportedFormatError

__all__ = ["MeshInput", "load_mesh", "MESH_EXTENSIONS"]

MESH_EXTENSIONS = (".obj", ".ply", ".off", ".stl", ".glb", ".gltf")


@dataclasses.dataclass(frozen=True)
class MeshInput:
    """A validated triangle mesh.

    Attributes
    ----------
    mesh : trimesh.Trimesh
        A cleaned copy (duplicate vertices merged, degenerate and duplicate
        faces dropped, normals made consistent and outward).
    repairs : tuple of str
        What was changed to make the mesh usable, if anything.
    """

    mesh: Any
    repairs: tuple[str, ...] = ()


def _read(path: Path) -> Any:
    trimesh = require("trimesh", "medialaxis[mesh]")
    if not path.is_file():
        raise InputFileError(f"no such file: {str(path)!r}")
    ext = path.suffix.lower()
    if ext not in MESH_EXTENSIONS:
        raise UnsupportedFormatError(f"unsupported mesh file type {ext!r}; use one of {', '.join(MESH_EXTENSIONS)}")
    try:
        loaded = trimesh.load(str(path), force="mesh", process=False)
    except Exception as exc:  # noqa: BLE001 - trimesh raises many types on bad files
        raise InputFileError(f"cannot read mesh {str(path)!r}: {type(exc).__name__}: {exc}") from exc
    if not isinstance(loaded, trimesh.Trimesh):
        raise InputFileError(f"{str(path)!r} holds no triangle mesh")
    return loaded


def load_mesh(mesh: Any, *, watertight: bool = True, repair: bool = False) -> MeshInput:
    """Read and check a mesh.

    Parameters
    ----------
    mesh : trimesh.Trimesh or path
    watertight : bool
        Require a closed (watertight) surface bounding a positive volume.
    repair : bool
        Try to close small holes (``trimesh.repair.fill_holes``) before
        refusing a non-watertight mesh; the repair is reported.

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
    if not np.all(np.isfinite(vertices)):
        raise InvalidInputError("mesh vertices contain NaN or infinite coordinates")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise InvalidInputError("mesh faces index vertices that do not exist")
    repairs: list[str] = []
    work = trimesh.Trimesh(vertices, faces, process=True, validate=True)
    if len(work.faces) < len(faces):
        repairs.append(f"dropped {len(faces) - len(work.faces)} degenerate or duplicate faces")
    if len(work.faces) == 0:
        raise EmptyShapeError("every face of the mesh is degenerate")
    if watertight and not work.is_watertight and repair:
        trimesh.repair.fill_holes(work)
        if work.is_watertight:
            repairs.append("closed holes with trimesh.repair.fill_holes")
    if watertight:
        if not work.is_watertight:
            broken = int((np.bincount(work.edges_unique_inverse, minlength=len(work.edges_unique)) != 2).sum())
            raise InvalidInputError(
                f"the mesh is not watertight ({broken} edges are not shared by exactly two faces); "
                "close it first or pass repair=True"
            )
        if not work.is_winding_consistent:
            trimesh.repair.fix_winding(work)
            repairs.append("made face winding consistent")
        if work.volume < 0:
            work.invert()
            repairs.append("flipped inward-facing normals")
        if not work.volume > 0:
            raise EmptyShapeError(f"the mesh encloses no volume (volume {work.volume:.3g})")
    return MeshInput(work, tuple(repairs))
