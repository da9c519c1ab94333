"""Voronoi lambda-medial surfaces of closed triangle meshes (Algorithm 5 of "Curved Voronoi diagrams").

1. Sample the surface (:mod:`medialaxis.mesh.sample.sampling`): an epsilon-sample
   built from the mesh (vertices, edge points, face grids), with a spacing
   adapted to the local feature size estimated on a coarse first pass.
2. Build the Delaunay tetrahedralisation of the sample, whose dual is the
   Voronoi diagram (:mod:`medialaxis.mesh.medial.voronoi_diagram`).
3. Keep the Voronoi facets dual to Delaunay edges at least ``lam`` long
   (contact set at least ``lam`` wide) whose vertices all lie inside the
   solid; triangulate them as fans over shared vertices. Where the inner
   tetrahedra were mended through air thicker than a sliver and the complex
   lacks the solid's Euler characteristic (the sample does not resolve the
   solid there), sample those places more finely and start once more
   (``REFINE_FACTOR``).

Inside/outside and the radii refer to the input mesh, not to the samples:
each candidate Voronoi vertex gets its closest point on the mesh (searched
among the faces around its four sample points, then by local descent over
face rings) and is signed with the angle-weighted pseudo-normal there. The
radius stored is that distance; the local search can stop at a face slightly
farther than the closest one on faceted surfaces (never nearer: measured
within 0.2 % on a 16-sided torus tube).
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from medialaxis._jit import Beside
from medialaxis._progress import Progress, check_cancel
from medialaxis.core.arrays import SparseRows
from medialaxis.core.memory import release_freed_memory
from medialaxis.core.options import make_options, takes_options
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import (
    ComputationError,
    InvalidInputError,
    MedialAxisError,
    MedialAxisWarning,
)
from medialaxis.mesh.medial._voronoi_kernels import tet_centroids
from medialaxis.mesh.medial.inner_set import inner_tets
from medialaxis.mesh.medial.stray_cycles import complement_voids, without_stray_cycles
from medialaxis.mesh.medial.voronoi_complex import euler_characteristic, medial_complex
from medialaxis.mesh.options import MeshVoronoiOptions
from medialaxis.mesh.sample.sample_delaunay import surface_structures, tetrahedralised_sample
from medialaxis.mesh.sample.sampling import (
    adaptive_spacing,
    degenerate,
    lfs_estimate,
    local_caps,
    pseudo_normals,
    sample_count,
    sample_surface,
)
from medialaxis.mesh.sample.signed_distance import SignedDistance
from medialaxis.mesh.solid.crossings import shell_labels, solid_betti
from medialaxis.mesh.solid.inputs import MeshInput, load_mesh, resolve_solid, signed_volume

__all__ = ["voronoi_medial_axis", "SignedDistance", "euler_characteristic", "LAM_FACTOR"]

#: Default lambda: ``LAM_FACTOR * sqrt(epsilon * diagonal)``. Lambda must
#: grow like the square root of epsilon for the lambda-medial axis of the
#: sample to converge (Chazal and Lieutier; "Curved Voronoi diagrams", 2.7); 0.65 keeps the
#: capsule's axis within 3 % and 95 % of a box's volume covered.
LAM_FACTOR = 0.65
#: Largest relative gap between the inner Delaunay tetrahedra's volume and the mesh's.
VOLUME_TOLERANCE = 2e-3
#: A circumcentre inside is a medial point when its distance to the mesh is
#: at least its circumradius minus this many epsilons (the surface cannot
#: reach further into a ball empty of samples; 2 allows for epsilon being
#: measured on random points, from below).
EMPTY_BALL_SLACK = 2.0
#: Where :func:`~medialaxis.mesh.medial.inner_set.unpinch` fills a thick pocket and the complex then
#: lacks the solid's Euler characteristic, the faces within ``REFINE_REACH`` longest edges of each such
#: pocket get ``REFINE_FACTOR`` times the finest spacing at its corners, and the route starts once more
#: from the sample. (Refining wherever a thick pocket is filled, 9 of 54 models, sampled ogre's thin
#: cavity walls three times finer and its compact complex grew from 2,930 points to 84,000.)
REFINE_REACH = 1.0
REFINE_FACTOR = 1.0 / 3.0


def _solid_of(src: MeshInput, pairs: np.ndarray, force: bool = False) -> MeshInput:
    """The input whose surface crosses itself at ``pairs`` as the surface of its solid (winding number)."""
    repairs, found = list(src.repairs), dict(src.found)
    solid = resolve_solid(src.mesh, repairs, found, pairs, force=force)
    return src if solid is src.mesh else MeshInput(solid, tuple(repairs), signed_volume(solid.triangles), found)


@takes_options(MeshVoronoiOptions)
def voronoi_medial_axis(
    mesh: Any, options: MeshVoronoiOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> MedialAxis:
    """Lambda-medial surface of a closed mesh from the Voronoi diagram of a surface sample.

    Parameters
    ----------
    mesh : trimesh.Trimesh or path
        A closed (watertight) triangle mesh, or an OBJ / PLY / OFF / STL / GLB
        file. Degenerate and duplicate faces are dropped, and the winding
        made consistent and outward; small holes are capped; a surface that
        passes through itself or whose shells overlap or nest is replaced by
        the surface of the solid where its generalized winding number is at
        least 1/2 (:mod:`medialaxis.mesh.solid.arrangement`), with a warning. These
        repairs are listed in ``metadata["repairs"]``, what was found in
        ``metadata["defects"]``.
    callback : callable, optional
        ``callback(Progress)`` before each stage (``"sampling"`` with the tetrahedralisation, ``"inside"``,
        ``"facets"``, ``"compact"``, ``"simplify"``); returning ``False`` cancels.

    {options}
    Returns
    -------
    MedialAxis
        ``points`` (n, 3): Voronoi vertices inside the solid; ``radii`` (n,):
        their distance to the mesh; ``faces`` (k, 3): the kept Voronoi
        facets, triangulated over shared vertices; ``edges``: facet sides on
        the boundary of the medial surface or where three or more facets
        meet. Extras: ``contact_diameter`` (n,) the longest Delaunay edge of
        each vertex's tetrahedron (its four contacts are on the ball),
        ``closest`` (n, 3) its closest surface point, ``contacts`` (n, 4, 3)
        the four samples on its ball, ``inside`` (n,) whether it lies inside
        (always, except possibly for facets kept only for topology),
        ``face_contact_diameter``
        (k,) the Delaunay edge length of each triangle's facet,
        ``face_certified`` (k,) whether that facet is one of Algorithm 5 (at least
        ``lam`` wide, all vertices inside and no nearer the mesh than their circumradius
        minus ``EMPTY_BALL_SLACK`` epsilons) rather than kept for topology, ``face_thin`` (k,)
        whether it spans a part thinner than ``lam`` (kept whatever lambda). Metadata:
        ``lam``, ``epsilon`` (measured ``max d(x, P)``), ``epsilon_lfs``
        (the same relative to the estimated local feature size),
        ``lam_bound`` (the lambda of Algorithm 5 step 3 as we read the
        paper's formula, ``10 * (9 D^3 epsilon)^(1/4)`` with ``D`` the
        bounding-box diagonal standing for the diameter: a worst-case bound,
        usually larger than the shape, hence the practical default ``lam``),
        ``euler_characteristic``, ``n_filling_faces``, ``n_cut_cycles`` (cycles the
        solid lacks, cut where they ran through points that are not medial:
        :mod:`~medialaxis.mesh.medial.stray_cycles`), ``timings`` (seconds
        per step; ``epsilon`` is the wait for the work done beside the Delaunay
        insertion: the thin-part check, the crossing check, epsilon, the closest-point structure;
        ``refine``, if present, the second sample, finer where the first did not resolve the solid
        (``REFINE_FACTOR``: its sampling, Delaunay insertion and inside test; ``delaunay`` and
        ``epsilon`` are then the second's),
        ``delaunay_share`` and ``defects`` (crossings, holes). The compact complex keeps a subset
        of these points (extras follow them) and adds ``compact`` (the
        collapse rule that ran), ``compact_tolerance``, ``full_points`` and
        ``full_faces``.

    Raises
    ------
    InvalidInputError
        A mesh with large holes (without ``repair``) or edges of more than
        two faces, bad option values, or crossings whose cut does not close
        up. (Inner Delaunay tetrahedra whose volume differs from the signed
        volume by more than ``VOLUME_TOLERANCE`` give a warning.)
    EmptyShapeError
        Empty or zero-volume mesh.
    InputFileError, UnsupportedFormatError
        Unreadable file.
    ComputationError
        The Delaunay step failed or nothing of the medial surface survived.

    References
    ----------
    .. [1] J.-D. Boissonnat, C. Wormser, M. Yvinec, "Curved Voronoi diagrams", in J.-D.
           Boissonnat, M. Teillaud (eds.), Effective Computational Geometry for Curves and
           Surfaces, Springer, 67-116, 2006, section 2.7, Algorithm 5 (sample, Voronoi
           diagram, remove the faces whose contact set is narrower than lambda).
           https://hal.archives-ouvertes.fr/hal-00488446
    .. [2] F. Chazal, A. Lieutier, "The lambda-medial axis", Graphical Models, 2005.
           doi:10.1016/j.gmod.2005.01.002
    .. [3] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a
           2D image; authors, venue and year unconfirmed: docs/references.md): the
           Voronoi/Delaunay view of the medial axis of a point sample.

    Examples
    --------
    >>> import trimesh
    >>> ma = voronoi_medial_axis(trimesh.creation.capsule(height=2.0, radius=0.5), samples=4000)
    >>> bool(abs(ma.radii.max() - 0.5) < 0.02)
    True
    """
    t_start = time.perf_counter()
    opts = make_options(MeshVoronoiOptions, options, kwargs, "voronoi_medial_axis")
    lam, samples, simplify, simplify_error, simplify_mode = (
        opts.lam, opts.samples, opts.simplify, opts.simplify_error, opts.simplify_mode)
    topology, repair, compact = opts.topology, opts.repair, opts.compact
    timings: dict[str, float] = {}
    src = load_mesh(mesh, watertight=True, repair=repair, crossing=False)  # checked beside the Delaunay
    work = src.mesh
    rng = np.random.default_rng(opts.rng)
    count = sample_count(samples, len(work.vertices))
    lam_given = None if lam is None else check_number(lam, "lam", positive=True)
    if not isinstance(compact, (bool, np.bool_)):
        raise InvalidInputError(f"compact must be True or False, got {compact!r}")
    if simplify_error is not None:
        if simplify is not None:
            raise InvalidInputError("give simplify (spheres) or simplify_error (error bound), not both")
        if not isinstance(simplify_error, (float, np.floating)) or not 0.0 < simplify_error < 1.0:
            raise InvalidInputError(f"simplify_error must be a float in (0, 1) of the diagonal, got {simplify_error!r}")
        simplify = simplify_error
    if simplify is not None or simplify_mode != "medial":
        from medialaxis.mesh.simplify.qmat import check_simplify

        if simplify is None:
            raise InvalidInputError("simplify_mode needs simplify or simplify_error")
        check_simplify(simplify, simplify_mode)
    stages = ["sampling", "inside", "facets"] + ["compact"] * bool(compact) + ["simplify"] * (simplify is not None)
    def stage(name: str) -> None:
        release_freed_memory()  # the last stage's arrays: ogre's 2.7M tetrahedra left 0.26 GB in the heap
        check_cancel(callback, Progress("voronoi", name, stages.index(name), len(stages)))

    stage("sampling")
    while True:  # once more on the surface of the solid if the mesh passes through itself
        diag = float(np.linalg.norm(np.ptp(np.asarray(work.vertices), axis=0)))
        t0 = time.perf_counter()
        normals = pseudo_normals(work)
        surface = Beside(surface_structures, work, normals)  # the crossing faces, the signed distance: beside the sampling
        try:
            tree = lfs_estimate(work, max(count // 8, 2000), normals)
            spacing = adaptive_spacing(work, tree, count)
            smp = sample_surface(work, spacing, normals)
            timings["sampling"] = time.perf_counter() - t0
            # with the default count, the check for thin parts runs beside the Delaunay insertion of the
            # sample it keeps on most meshes
            dt, more, pairs, eps, eps_lfs, sd = tetrahedralised_sample(
                work, smp, rng, tree, normals, (count, spacing) if samples is None else None, timings, surface)
            if more is not None and more[2]:
                warnings.warn(more[2], MedialAxisWarning, stacklevel=2)
            jitter = not isinstance(dt, MedialAxisError) and degenerate(len(dt.simplices), len(smp.points))
            if more is not None and (more[0] != count or not np.array_equal(more[1], spacing)) or jitter:
                count, spacing = (count, spacing) if more is None else more[:2]  # more, for the plates of a thin part
                if not len(pairs):  # (else the count holds for the solid, next round)
                    dt = None  # the first one freed before the next is made
                    smp = sample_surface(work, spacing, normals, jitter=jitter)  # cospherical fans broken
                    dt, _, pairs, eps, eps_lfs, sd = tetrahedralised_sample(
                        work, smp, rng, tree, normals, None, timings, surface)
        except MedialAxisError:
            try:
                pairs = surface.result()[0]  # a surface through itself: its solid rather than what it broke
            except MedialAxisError:  # (the same error, or one after it) what the sampling met is raised, as it came
                pairs = np.empty((0, 2), np.int64)
            if not len(pairs):
                raise
            src = _solid_of(src, pairs)
            work = src.mesh
            continue
        if isinstance(dt, MedialAxisError):
            if not len(pairs):
                raise dt
            dt = None
        if not len(pairs):
            stage("inside")
            t0 = time.perf_counter()
            inner = inner_tets(dt, smp, sd, 1e-6 * float(spacing.min()))
            union_volume = float(dt.volume[inner].sum())
            timings["inside"] = time.perf_counter() - t0
            if abs(union_volume - src.volume) <= VOLUME_TOLERANCE * src.volume or src.found:
                break
            # faces crossing at the accuracy of the coordinates (through a vertex): the winding number decides
            solid = _solid_of(src, pairs, force=True)
            if solid is src:
                break
            src = solid
        else:
            src = _solid_of(src, pairs)
        work = src.mesh
    assert dt is not None and sd is not None
    lam_used = LAM_FACTOR * float(np.sqrt(eps * diag)) if lam_given is None else lam_given
    point_spacing = np.asarray(spacing)[smp.face]  # that of its face (a sample on an edge takes one of them)
    if abs(union_volume - src.volume) > VOLUME_TOLERANCE * src.volume:
        # crossings and nested shells were resolved above: what is left is a sample too coarse somewhere
        warnings.warn(
            f"the inner Delaunay tetrahedra of the sample hold {union_volume:.6g} where the mesh encloses "
            f"{src.volume:.6g} ({100 * abs(union_volume / src.volume - 1):.2g}% apart): the sample may miss thin or "
            "sharp parts; raise samples", MedialAxisWarning, stacklevel=2)

    stage("facets")
    t0, n_tets = time.perf_counter(), len(dt.simplices)
    signed = np.full(n_tets, np.inf)  # of the circumcentres queried (negative inside)
    closest = SparseRows(n_tets, 3)  # of the few circumcentres queried
    finer: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []

    def refine(tets: np.ndarray) -> None:
        """Where a thick pocket is filled the sample may be too coarse for the solid: the caps around it (once)."""
        if not finer:
            corners = dt.simplices[tets]
            finer.append((tet_centroids(dt.points, corners), REFINE_REACH * dt.longest[tets],
                          REFINE_FACTOR * point_spacing[corners].min(axis=1)))

    def medial(tets: np.ndarray) -> np.ndarray:
        """Circumcentres inside, bounded, and at least as far from the mesh as their samples, up to epsilon."""
        bounded = dt.radii[tets] < diag
        ask = tets[bounded]
        signed[ask], closest[ask] = sd.query(dt.centres[ask], smp.face[dt.simplices[ask]])
        # A Voronoi ball is empty of samples, so the surface reaches into it by at most epsilon: a
        # circumcentre far nearer the surface than its four samples is not a medial point but the
        # arbitrary centre of a flat tetrahedron (four co-circular samples near a faceted surface)
        out = np.zeros(len(tets), bool)
        out[bounded] = (signed[ask] < 0) & (dt.radii[ask] + signed[ask] <= EMPTY_BALL_SLACK * eps)
        return out

    solid_numbers_beside = Beside(solid_betti, src.mesh)  # needs the mesh only: beside the serial collapses
    while True:
        # thin parts narrower than lam keep their sheets
        cx = medial_complex(dt, inner, medial, lam_used, topology, spacing=point_spacing, thick_pockets=refine)
        if len(cx.faces) == 0:
            raise ComputationError(
                f"no Voronoi facet with a contact set of at least lam={lam_used:.4g} lies inside the mesh; "
                "lower lam or raise samples"
            )
        used = cx.tets
        todo = used[~np.isfinite(signed[used])]
        signed[todo], closest[todo] = sd.query(dt.centres[todo], smp.face[dt.simplices[todo]])
        solid_numbers = solid_numbers_beside.result()
        faces, edges, n_curve, n_cut = cx.faces, cx.edges, cx.n_curve_edges, 0
        chi = euler_characteristic(len(used), faces, edges)
        if topology == "preserve":  # cycles the solid lacks, run out through flat tetrahedra on the surface
            medial_point = (signed[used] < 0) & (dt.radii[used] + signed[used] <= EMPTY_BALL_SLACK * eps)
            one_sided = dt.longest[used] < -signed[used]  # its four contacts within 60 degrees, seen from its centre
            used, faces, edges, n_curve, n_cut = without_stray_cycles(
                used, faces, edges, n_curve, ~medial_point | one_sided | (dt.radii[used] >= diag), solid_numbers,
                partial(complement_voids, dt.simplices, dt.neighbors, cx.facet_ij), chi)
            chi += n_cut
        if not finer or "refine" in timings or chi == solid_numbers[0] - solid_numbers[1] + solid_numbers[2]:
            break
        # The solid's topology is lost where thick air was filled: once more on a sample finer there (lam stays)
        t1, spacing = time.perf_counter(), local_caps(work, spacing, *finer[0])
        dt = signed = closest = cx = None  # type: ignore[assignment]  # freed before the next ones are made
        smp = sample_surface(work, spacing, normals, jitter=jitter)
        dt, _, _, eps, eps_lfs, sd = tetrahedralised_sample(work, smp, rng, tree, normals, None, timings, surface)
        if isinstance(dt, MedialAxisError):
            raise dt
        inner = inner_tets(dt, smp, sd, 1e-6 * float(spacing.min()))
        union_volume, point_spacing = float(dt.volume[inner].sum()), np.asarray(spacing)[smp.face]
        signed, closest = np.full(len(dt.simplices), np.inf), SparseRows(len(dt.simplices), 3)
        timings["refine"] = time.perf_counter() - t1
    stray = used[(signed[used] >= 0) | (dt.radii[used] >= diag)]  # kept for topology, its circumcentre out or far
    if len(stray):  # the centroid of its (inner) tetrahedron stands for it: far circumcentres broke compaction
        dt.centres[stray] = tet_centroids(dt.points, dt.simplices[stray])
        signed[stray], closest[stray] = sd.query(dt.centres[stray], smp.face[dt.simplices[stray]])
    points = dt.centres[used]
    radii = np.abs(signed[used])
    inside = signed[used] < 0
    timings["facets"] = time.perf_counter() - t0
    timings["total"] = time.perf_counter() - t_start

    metadata = {
        "domain": "mesh",
        "method": "voronoi",
        "lam": lam_used,
        "lam_default": lam_given is None,
        "epsilon": eps,
        "epsilon_lfs": eps_lfs,
        "lam_bound": float(10.0 * (9.0 * diag**3 * eps) ** 0.25),
        "n_samples": int(len(smp.points)), "sample_jittered": bool(jitter),  # sampling.degenerate
        "n_tetrahedra": int(len(dt.simplices)),
        "mesh_vertices": int(len(src.mesh.vertices)),
        "mesh_faces": int(len(src.mesh.faces)),
        "mesh_volume": src.volume,
        "mesh_euler_characteristic": int(src.mesh.euler_number),
        "euler_characteristic": chi,
        "solid_betti": list(solid_numbers),
        "repairs": list(src.repairs),
        "defects": dict(src.found),
        "topology": topology,
        "n_filling_faces": int((~cx.face_certified).sum()),
        "n_outside_points": int((~inside).sum()),
        "inner_volume": union_volume,
        "n_curve_edges": int(n_curve),
        "n_cut_cycles": n_cut,
        "timings": timings,
        "delaunay_share": timings["delaunay"] / timings["total"],
    }
    extras = {
        "contact_diameter": dt.longest[used],
        "closest": closest[used],
        "face_contact_diameter": cx.face_length,
        "face_certified": cx.face_certified,
        "face_thin": cx.face_thin,
        "inside": inside,
        "contacts": dt.points[dt.simplices[used]],
    }
    contact_faces = smp.face[dt.simplices[used]] if compact else smp.face[:0]  # each sphere's samples' faces
    dt = signed = closest = cx = inner = None  # type: ignore[assignment]  # the tetrahedra's, freed before the copies
    result = MedialAxis(points, radii, edges, faces, extras=extras, metadata=metadata, shape=src.mesh)
    del points, radii, edges, faces, extras, inside  # the result holds its own copies
    if compact:
        from medialaxis.mesh.medial.compact import COMPACT_TOLERANCE, compact_medial_axis

        stage("compact")
        t0 = time.perf_counter()
        result = compact_medial_axis(
            result, COMPACT_TOLERANCE * eps, exact=sd.exact, shells=int(shell_labels(work).max()) + 1,
            signed=lambda x, near: sd.query(x, contact_faces[near].reshape(len(x), -1))[0],
        )
        timings.update(compact=time.perf_counter() - t0, total=time.perf_counter() - t_start)
        result = dataclasses.replace(result, metadata=dict(result.metadata, timings=timings))  # metadata is a copy
    solid_chi = metadata["solid_betti"][0] - metadata["solid_betti"][1] + metadata["solid_betti"][2]
    if topology == "preserve" and result.metadata["euler_characteristic"] != solid_chi:
        warnings.warn(
            f"the medial complex has Euler characteristic {result.metadata['euler_characteristic']} where the solid has "
            f"{solid_chi} (Betti numbers {tuple(metadata['solid_betti'])}): a handle or a part smaller than the "
            "sampling is lost or added; raise samples", MedialAxisWarning, stacklevel=2)
    if simplify is None:
        return result
    from medialaxis.mesh.simplify.qmat import simplify_medial_mesh

    stage("simplify")
    return simplify_medial_mesh(result, simplify, surface=src.mesh, signed=sd, mode=simplify_mode)
