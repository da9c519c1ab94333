"""Options of the volume methods: :func:`~medialaxis.volume.voxel_axis.medial_voxel_axis` (:class:`VoxelOptions`)
and :func:`~medialaxis.volume.pipeline.midsurface_medial_axis` (:class:`MidsurfaceOptions`, the same and more)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from medialaxis.core.options import LAM_FLAG, SEED_FLAG, SPACING_FLAG, THRESHOLD_FLAG, Flag, Options, option

__all__ = ["VoxelOptions", "MidsurfaceOptions"]


@dataclass(frozen=True)
class VoxelOptions(Options):
    """Options of the medial voxels (``method="voxels"``), shared by the mid-surface.

    >>> VoxelOptions(thickness=(2.0, 6.0)).changed()
    {'thickness': (2.0, 6.0)}
    """

    iso: float | None = option(None, """
        Foreground is ``grey > iso``. Default 0.5 for bool input, else ISO-50:
        half-way between the background and material peaks of the grey-value
        histogram, or Otsu's class means where it has not two
        (:func:`~medialaxis.volume.inputs.iso50`).""")
    threshold: float | None = option(None, """
        The dispatcher's name for ``iso`` (give one of them).""", flag=THRESHOLD_FLAG)
    thickness: Any = option(None, """
        Plate thickness (the paper's epsilon), physical units. Omitted: every
        plate at least 2 voxels (of the finest spacing) thick is kept, each
        judged by its own thickness, measured where adjacent voxels see the
        plate's two faces (a rib thinner than its wall keeps its
        mid-surface). A ``(min, max)`` range: the same, for plates of
        thickness in the range (``max`` may be ``inf``). A number: one
        nominal thickness for the whole part, as in the paper. Plates left
        out by a number or a range are reported in ``metadata["dropped"]``
        and by a :class:`~medialaxis.MedialAxisWarning`.""",
        flag=Flag("plate thickness; one value (nominal), or MIN MAX (plates in that range); default: every plate, "
                  "each with its own thickness", type=float, nargs="+", metavar="T", counts=(1, 2)),
        kind="float or (min, max), optional")
    lam: float | None = option(None, """
        Lambda of the grid lambda-medial axis: adjacent voxels whose nearest
        boundary points are more than ``lam`` apart are medial. Default
        ``0.75`` times the thickness (of each plate, or the nominal one),
        which keeps plates and drops the branches into convex edges.""", flag=LAM_FLAG)
    spacing: Any = option(None, """
        Voxel size per array axis (default: the file's, else 1).""", flag=SPACING_FLAG,
        kind="float or 3 floats, optional")
    raw_shape: Any = option(None, """
        Array shape ``(Z, Y, X)`` of a ``.raw`` file.""",
        flag=Flag("array shape of a .raw file", type=int, nargs=3, metavar=("Z", "Y", "X")),
        kind="(3,) ints, optional")
    raw_dtype: Any = option(None, """
        Data type of a ``.raw`` file (e.g. ``"uint16"``).""",
        flag=Flag("data type of a .raw file (e.g. uint16)", type=str), kind="dtype, optional")
    chunks: Any = option(None, """
        Block size of the chunked route (:mod:`~medialaxis.volume.blockwise.chunked`),
        for volumes larger than memory: the volume is read and processed a
        block at a time, each with a halo (see below); the medial voxels of
        each block wait in a folder (``spill``). Default: blocks of 256 for a Dask or Zarr array,
        with a cluster ``scheduler``, or above 2^27 voxels (512^3); ``0``
        keeps the whole volume in memory. The medial voxels are identical to
        the in-memory route's, and so is the mesh: each block meshes a window
        of the sheet around it and keeps what it owns, vertices named by
        their voxel, so the pieces join without seams.

        The halo is chosen from the part: without a thickness, a first pass
        measures the deepest voxel ``D`` (half the thickest plate); the halo
        is ``D`` plus two voxels (the medial test of a core voxel uses its
        neighbours' nearest boundary points, which must be inside the read
        box), or ``3 D`` plus four voxels when plates of several nominal
        thicknesses are labelled; with a number ``thickness``, half of it
        plus three voxels. Every block checks that each voxel its answer
        depends on is nearer to a boundary point it read than to the sides
        of its box, and reads itself again with a doubled halo where not.
        The mesh stages read a window of the neighbouring blocks' medial
        voxels, wider where the picks near the core are not provably the
        whole sheet's (``metadata["mesh_halo"]``).
        Accepted sources: arrays, ``dask.array.Array``, Zarr arrays and
        stores, OME-Zarr images (level 0, or the level a path names),
        ``.npy`` and raw files (memory-mapped), NRRD (raw memory-mapped;
        gzip/bzip2 decompressed once to a temporary file), NIfTI, TIFF
        stacks and folders (page by page).""",
        flag=Flag("process in blocks of N (or Z Y X) voxels, reading one block at a time; 0 keeps the volume in "
                  "memory (default: blocks of 256 above 512^3 voxels)", type=int, nargs="+", metavar="N",
                  counts=(1, 3)), kind="int or 3 ints, optional")
    scheduler: Any = option(None, """
        Where the blocks run: local threads (default), one thread, or a Dask
        cluster (a ``Client`` or an address such as ``"tcp://host:8786"``;
        its workers must see the input file). Implies the chunked route.""",
        flag=Flag("run the blocks on a Dask cluster (tcp://host:8786); its workers must see the input", type=str,
                  metavar="ADDRESS"), kind='None, "threads", "synchronous", dask Client or str')
    n_jobs: int | None = option(None, """
        Local worker threads of the chunked route (default: all CPUs).""",
        flag=Flag("local worker threads for the blocks (default: all CPUs)", name="--jobs", metavar="N"))
    show_progress: bool | None = option(None, """
        Progress bar on stderr (default: when stderr is a terminal).""")


@dataclass(frozen=True)
class MidsurfaceOptions(VoxelOptions):
    """Options of the mid-surface (``method="midsurface"``): those of the medial voxels and the mesh's.

    >>> MidsurfaceOptions(extend=False).changed()
    {'extend': False}
    """

    extend: bool = option(True, """
        Extend the free edges to the isosurface.""",
        flag=Flag("do not extend the free edges to the isosurface", name="--no-extend", const=False))
    remove_dents: bool = option(True, """
        Move junction vertices by eq. (1).""",
        flag=Flag("do not move junction vertices by eq. (1)", name="--keep-dents", const=False))
    density: float = option(1.0, """
        Vertex spacing in units of the local half thickness.""",
        flag=Flag("vertex spacing in units of the local half thickness"))
    rng: Any = option(0, """
        Order of the sub-sampling within a class (reproducible per seed).""", flag=SEED_FLAG,
        kind="seed or numpy Generator")
    out: Any = option(None, """
        A ``.ply`` file or a ``.zarr`` group (arrays ``vertices``, ``faces``,
        ``radii``, ``vertex_kind``) for the mesh. The chunked route streams it
        there block by block (the mesh is never whole in one process) and
        returns a result without the mesh: ``metadata["written"]``,
        ``["vertices"]`` and ``["faces"]``; in memory the result is written
        and returned. A ``.ome.zarr`` path gets an OME-Zarr image of the wall thickness on the
        mid-surface's voxels, the mesh in its group ``mesh`` (:mod:`~medialaxis.volume.files.ome_zarr`).""",
        kind="str or path, optional")
    spill: Any = option(None, """
        Folder for the blocks' medial voxels and mesh pieces of the chunked
        route (default: the temporary folder; on a cluster of several
        machines, a folder every worker sees).""",
        flag=Flag("folder for the blocks' intermediate files (default: the temporary folder)", type=str,
                  metavar="DIR"), kind="str or path, optional")
