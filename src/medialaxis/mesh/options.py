"""Options of the mesh methods: :func:`~medialaxis.mesh.voronoi.voronoi_medial_axis` and
:func:`~medialaxis.mesh.flow.flow_skeleton`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from medialaxis.core.options import LAM_FLAG, REPAIR_FLAG, SEED_FLAG, Flag, Options, option

__all__ = ["MeshVoronoiOptions", "FlowOptions"]

_REPAIR_DOC = """
        Cap the holes of an open mesh even where its winding number leaves
        the solid undecided (without it, holes are capped where the rest of
        the surface decides inside and outside, and the mesh is refused
        otherwise: :func:`medialaxis.mesh.solid.inputs.load_mesh`)."""


@dataclass(frozen=True)
class MeshVoronoiOptions(Options):
    """Options of the mesh Voronoi method (:func:`~medialaxis.mesh.voronoi.voronoi_medial_axis`).

    >>> MeshVoronoiOptions(simplify=200).changed()
    {'simplify': 200}
    """

    lam: float | None = option(None, """
        Lambda of the lambda-medial axis: the smallest contact-set diameter
        kept, in the mesh's units. A Voronoi facet is kept when its Delaunay
        edge is at least ``lam`` long. Default ``0.65 * sqrt(epsilon * D)``,
        with ``epsilon`` the measured sampling density
        (``metadata["epsilon"]``) and ``D`` the bounding-box diagonal: facets
        of sampling noise have contact sets up to about ``sqrt(epsilon * r)``
        at depth ``r``, so a lambda linear in epsilon keeps noise sheets.""", flag=LAM_FLAG)
    samples: int | None = option(None, """
        Target number of surface samples. Default ``max(20000,
        n_vertices)``, more for a mostly thin part (up to 250,000, so that
        a plate's two sides are three spacings apart:
        :func:`~medialaxis.mesh.sample.thin_parts.thin_part_count`); the mesh
        vertices are always included.""", flag=Flag("target number of surface samples", metavar="N"))
    simplify: int | float | None = option(None, """
        Reduce the medial mesh by quadric error minimisation on spheres
        (:func:`medialaxis.mesh.simplify.qmat.simplify_medial_mesh`): an ``int`` is the
        most spheres kept (a quarter of them, or all those the
        compact complex lacks, placed last where the surface is farthest
        from the others: tips of limbs), a ``float`` in (0, 1) an error
        bound as a fraction of the bounding-box diagonal. It starts from
        the compact complex (``compact=False``: the full one), which is
        ``ma.raw`` (the full complex is then ``ma.raw.raw``).""",
        flag=Flag("simplify the medial mesh to N spheres (Q-MAT)", type=int, metavar="N"), kind="int or float, optional")
    simplify_error: float | None = option(None, """
        The same as a ``float`` ``simplify``, by name: the fewest spheres whose
        two-sided error (``metadata["hausdorff"]``, exact envelope of the
        interpolated spheres against the input surface) is at most this
        fraction of the bounding-box diagonal. Not with ``simplify``.""",
        flag=Flag("simplify to the fewest spheres whose two-sided error is at most E times the bounding-box "
                  "diagonal", metavar="E"))
    simplify_mode: Literal["medial", "packing"] = option("medial", """
        ``"medial"`` (default): every sphere kept is a sphere of the medial
        complex whose contacts span a wide angle (it touches two sides);
        ``"packing"``: spheres anywhere inside, for the smallest two-sided
        error (a sphere packing rather than a medial mesh).""",
        flag=Flag("spheres of the medial axis (medial, default) or anywhere inside (packing)"))
    topology: Literal["preserve", "lambda"] = option("preserve", """
        ``"preserve"`` (default): keep every facet of at least ``lam`` plus
        the narrower facets and curve pieces needed for the complex to have
        the solid's homotopy type (connected, same number of tunnels),
        found by collapsing the dual complex of the inner Delaunay
        tetrahedra (:mod:`medialaxis.mesh.medial.voronoi_complex`). ``"lambda"``:
        Algorithm 5 literally, only the facets of at least ``lam``.""",
        flag=Flag("preserve: the solid's homotopy type (default); lambda: only the facets of at least lam"))
    repair: bool = option(False, _REPAIR_DOC, flag=REPAIR_FLAG)
    rng: Any = option(0, """
        Seed of the random check points used to measure epsilon.""", flag=SEED_FLAG,
        kind="int or numpy.random.Generator")
    compact: bool = option(True, """
        ``True`` (default): the compact complex
        (:func:`medialaxis.mesh.medial.compact.compact_medial_axis`): edges are
        contracted while the spheres left stay within the sampling error
        (``COMPACT_TOLERANCE * epsilon``) of the contacts and features they
        replace, keeping the homotopy type, so sheets thinner than the
        sampling error become curves (a capsule's axis is a polyline, a
        box's its few planar sheets) and flat sheets take few triangles;
        ``ma.raw`` is the full complex. ``False``: the full complex, every
        Voronoi facet kept. ``simplify`` starts from the complex chosen here.""",
        flag=Flag("the full complex, every Voronoi facet kept (no compaction)", name="--full", const=False))


@dataclass(frozen=True)
class FlowOptions(Options):
    """Options of the mesh flow method (:func:`~medialaxis.mesh.flow.flow_skeleton`).

    >>> FlowOptions(dt=0.5).changed()
    {'dt': 0.5}
    """

    dt: float | None = option(None, """
        Implicit time step in units of ``s**2``, ``s`` the median inner-ball
        radius of the mesh (so results do not depend on scale). Default 1.0.
        Smaller steps follow the flow more closely and take more steps.""", flag=Flag("implicit time step (s**2)"))
    fixed_points: Any = option(None, """
        Input vertex indices that become skeletal points where they are: they
        never move, each is a skeleton node and the skeleton reaches it.""",
        flag=Flag("input vertex indices that stay where they are as skeleton nodes", nargs="+", type=int,
                  metavar="VERTEX"), kind="sequence of int, optional")
    region: Any = option(None, """
        Axis-aligned box ``[[xmin, ymin, zmin], [xmax, ymax, zmax]]``: only
        the part of the mesh in the box, plus a margin of three thicknesses
        ``s``, flows (the rest stays on the surface, held still); the skeleton
        is clipped to the box and ``correspondence`` is ``-1`` for vertices
        outside it.""", kind="(2, 3) array_like, optional")
    curvature_threshold: float | None = option(None, """
        Gaussian curvature (angle defect per area, eq. (7), in 1/length**2,
        averaged over a disc of radius ``s / 2`` because the per-vertex value
        of a sampled surface is noisy). In every connected patch of the input surface where the curvature is at
        least this, the vertex deepest inside the patch (its apex) becomes a
        skeletal point at its place, so the skeleton reaches into sharp convex tips (a capsule's
        caps have ``1/r**2``). Lower thresholds make more tips reach the
        surface; ``None`` (default) keeps none, and the skeleton ends inside
        the tips, at the centres of their inner balls. Patches of total
        curvature below ``MIN_TIP_CURVATURE`` (pi/16) are noise and ignored.""",
        flag=Flag("Gaussian curvature above which a convex tip's apex becomes a skeleton end (1/length**2)"))
    max_steps: int | None = option(None, """
        Upper bound on the steps (default 60). Vertices still moving then are
        frozen where they are and ``metadata["converged"]`` is ``False``.""", flag=Flag("most flow steps"))
    attraction: float = option(4.0, """
        Weight ``w`` (in 1/s**2) of the pull towards the inner-ball centres.""",
        flag=Flag("weight of the pull towards the inner-ball centres (1/s**2)"))
    collapse: float = option(0.01, """
        A vertex freezes when its one-ring area falls below this fraction of
        its initial area.""", flag=Flag("one-ring area fraction at which a vertex freezes"))
    settle_tolerance: float = option(1e-3, """
        A vertex that moves less than this (times ``s``) in a step has
        stopped: it freezes as a skeletal point.""", flag=Flag("step length (times s) below which a vertex freezes"))
    final_collapse: float = option(0.01, """
        Duration (in units of ``s**2``) of one last implicit mean-curvature
        step on the contracted surface, which gathers each collapsed ring onto
        its centre before the graph is built (0 skips it).""",
        flag=Flag("duration of the last mean-curvature step (s**2; 0 skips it)"))
    node_spacing: float | None = option(None, """
        Spacing of the skeleton nodes (length); default ``s / 2``.""", flag=Flag("spacing of the skeleton nodes"))
    repair: bool = option(False, _REPAIR_DOC, flag=REPAIR_FLAG)
