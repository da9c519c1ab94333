"""Curve skeletons of closed meshes by a diffusion flow (Du and Qin, SM '04), with user control.

The surface ``S`` evolves by a diffusion equation in the spirit of Du and
Qin [1]_, eq. (4), ``dS/dt = D laplacian(S) + (grassfire term)``, discretised with the
cotangent Laplacian ``L`` and lumped mass ``M`` of the *input* surface and
solved implicitly (backward Euler, unconditionally stable)::

    (M + tau (L + w M)) p_next = M p + tau w M c

``c`` is the centre of each vertex's inner medial ball (shrinking-ball poles,
computed once): the pull towards it plays the role of the paper's normal
term ``N`` (the grassfire direction) and keeps tips from retracting, while the
Laplacian smooths, so the surface collapses onto a smoothed medial axis.
Because the operator is built once, one sparse LU factorization serves every
step and all three coordinates (only user-fixed vertices and vertices
outside the region are eliminated, before factorizing).

A vertex whose one-ring area has shrunk below ``collapse`` times its initial
area, or that moved less than ``settle_tolerance`` in a step, has met the
rest of the collapsing surface: it is frozen there as a skeletal point (the
paper's collision test, in a form that costs O(n) per step); frozen vertices
are put back after each solve, so they never move during the flow; one last
implicit mean-curvature step on the contracted surface (cotangent operator of
the contracted geometry) then gathers each collapsed ring onto its centre.
Degenerate edges are
not collapsed one by one: the final grouping of
:mod:`medialaxis.mesh.skeleton.contract_graph` merges vertices that have come
together, which is the equivalent of collapsing them, and turns the
contracted mesh into the curve skeleton graph.

User control, as in Du and Qin, section 4.2: ``fixed_points`` freezes chosen
vertices from the start (the skeleton reaches them), ``region`` restricts the
flow to a box, ``curvature_threshold`` turns convex tips of high Gaussian
curvature (eq. 7) into skeletal points, ``callback`` watches every step.

References
----------
.. [1] H. Du, H. Qin, "Medial axis extraction and shape manipulation of solid objects using
       parabolic PDEs", Proc. 9th ACM Symposium on Solid Modeling and Applications (SM '04),
       2004 (DOI unconfirmed: docs/references.md), sections 3-4.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from medialaxis._progress import Progress, check_cancel, progress
from medialaxis.core import graph as _graph
from medialaxis.core.arrays import unique_ints
from medialaxis.core.options import make_options, takes_options
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import ComputationError, EmptyShapeError, InvalidInputError
from medialaxis.mesh.options import FlowOptions
from medialaxis.mesh.skeleton import _flow_operators as ops
from medialaxis.mesh.skeleton.contract_graph import skeleton_graph
from medialaxis.mesh.skeleton.flow_mesh import (
    FlowState,
    curvature_tips,
    nonmanifold_vertices,
    prepare_flow_mesh,
    readonly,
    smoothed_gaussian_curvature,
)
from medialaxis.mesh.skeleton.flow_refine import centre_nodes
from medialaxis.mesh.skeleton.refine import refine_coarse

__all__ = ["FlowState", "flow_skeleton", "prepare_flow_mesh", "nonmanifold_vertices", "smoothed_gaussian_curvature"]


def _check_box(region: Any) -> np.ndarray:
    box = np.asarray(region, dtype=np.float64)
    if box.shape != (2, 3) or not np.all(np.isfinite(box)) or np.any(box[0] > box[1]):
        raise InvalidInputError(f"region must be a finite (2, 3) box [[xmin, ymin, zmin], [xmax, ymax, zmax]], got {region!r}")
    return box


@takes_options(FlowOptions)
def flow_skeleton(
    mesh: Any, options: FlowOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> MedialAxis:
    """Curve skeleton of a closed mesh by the diffusion flow of Du and Qin (SM '04).

    Parameters
    ----------
    mesh : trimesh.Trimesh or path
        A closed, manifold triangle mesh (several closed components are
        allowed: each gets its own skeleton component; the shells that bound
        cavities are left out, with a warning: a curve has no room for a void).
    callback : callable, optional
        ``callback(Progress)`` after every step, its ``state`` the
        :class:`~medialaxis.mesh.skeleton.flow_mesh.FlowState` (the contracting mesh);
        returning ``False`` cancels (:class:`~medialaxis.errors.Cancelled`).
    {options}
    Returns
    -------
    MedialAxis
        ``points`` (s, 3), ``radii`` (mean distance from each node to the
        surface points that collapsed onto it), ``edges``, no faces;
        ``extras["correspondence"]`` (n_input,) is the node of each input
        vertex (``-1`` on a filled cavity's surface); metadata holds ``steps``, ``converged``, ``dt``, ``repairs``,
        ``refined_vertices`` (midpoints added to a coarse surface, see
        :func:`~medialaxis.mesh.skeleton.refine.refine_coarse`).

    Raises
    ------
    InvalidInputError
        Open, non-manifold, self-intersecting (crossing faces, overlapping
        shells) or non-finite meshes; bad option values.
    EmptyShapeError
        Empty meshes or meshes without volume; a region holding no vertex.
    ComputationError
        The flow diverged (non-finite or exploding positions).
    Cancelled
        The callback returned ``False``.

    References
    ----------
    .. [1] H. Du, H. Qin, "Medial axis extraction and shape manipulation of solid objects using
           parabolic PDEs", Proc. 9th ACM Symposium on Solid Modeling and Applications (SM '04),
           2004 (DOI unconfirmed: docs/references.md), sections 3-4.

    Examples
    --------
    >>> import medialaxis as mx
    >>> from medialaxis.datasets import capsules_mesh
    >>> capsule = capsules_mesh([[[0, 0, 0], [3, 0, 0]]], 0.5, pitch=0.1)
    >>> sk = mx.medial_axis(capsule, method="flow")
    >>> len(sk.endpoints), len(sk.junctions)
    (2, 0)
    """
    t_start = time.perf_counter()
    opts = make_options(FlowOptions, options, kwargs, "flow_skeleton")
    dt, fixed_points, region, curvature_threshold, max_steps = (
        opts.dt, opts.fixed_points, opts.region, opts.curvature_threshold, opts.max_steps)
    attraction, collapse, final_collapse, node_spacing = opts.attraction, opts.collapse, opts.final_collapse, opts.node_spacing
    dt_rel = 1.0 if dt is None else check_number(dt, "dt", positive=True)
    threshold = None if curvature_threshold is None else float(curvature_threshold)
    if threshold is not None and not np.isfinite(threshold):
        raise InvalidInputError(f"curvature_threshold must be finite, got {curvature_threshold!r}")
    if max_steps is None:
        max_steps = 60
    if int(max_steps) != max_steps or max_steps < 1:
        raise InvalidInputError(f"max_steps must be a positive integer, got {max_steps!r}")
    max_steps = int(max_steps)
    attraction = check_number(attraction, "attraction", positive=True)
    collapse = check_number(collapse, "collapse", positive=True)
    final_collapse = float(final_collapse)
    if not (np.isfinite(final_collapse) and final_collapse >= 0):
        raise InvalidInputError(f"final_collapse must be a non-negative number, got {final_collapse!r}")
    if collapse >= 1:
        raise InvalidInputError(f"collapse must be in (0, 1), got {collapse!r}")
    spacing = None if node_spacing is None else check_number(node_spacing, "node_spacing", positive=True)
    if callback is not None and not callable(callback):
        raise InvalidInputError(f"callback must be callable, got {type(callback).__name__}")

    clean, vertex_map, repairs = prepare_flow_mesh(mesh, repair=opts.repair)
    p0, faces = refine_coarse(np.array(clean.vertices, dtype=np.float64), np.array(clean.faces, dtype=np.int64))
    refined = len(p0) - len(clean.vertices)
    n = len(p0)
    edges = ops.unique_edges(faces)
    n_input = len(vertex_map)

    fixed = np.zeros(0, dtype=np.int64)
    if fixed_points is not None:
        fp = np.asarray(fixed_points)
        if fp.size and (fp.ndim != 1 or not np.issubdtype(fp.dtype, np.integer)):
            raise InvalidInputError(f"fixed_points must be a 1D sequence of vertex indices, got {fixed_points!r}")
        fp = fp.astype(np.int64).ravel()
        if fp.size and (fp.min() < 0 or fp.max() >= n_input):
            bad = fp[(fp < 0) | (fp >= n_input)][0]
            raise InvalidInputError(f"fixed_points index {int(bad)} out of range for a mesh of {n_input} vertices")
        fixed = unique_ints(vertex_map[fp])
        fixed = fixed[fixed >= 0]  # vertices of a filled cavity
    use = np.ones(n, dtype=bool)
    if region is not None:
        box = _check_box(region)
        use = np.all((p0 >= box[0]) & (p0 <= box[1]), axis=1)
        if not use.any():
            raise EmptyShapeError(f"no mesh vertex lies inside the region {box.tolist()}")

    normals = ops.vertex_normals(p0, faces)
    diag = float(np.linalg.norm(p0.max(axis=0) - p0.min(axis=0)))
    edge_length = float(np.linalg.norm(p0[edges[:, 0]] - p0[edges[:, 1]], axis=1).mean())
    poles, pole_radius = ops.robust_poles(p0, normals, max_radius=0.5 * diag, edge_length=edge_length, faces=faces)
    s = float(np.median(pole_radius[use]))
    if not s > 0:
        raise ComputationError("could not estimate the thickness of the mesh (all inner-ball radii are zero)")
    in_box = use.copy()
    if region is not None:
        # flow a margin beyond the box so the surface held still outside does
        # not bend the axis inside it; the skeleton is clipped to the box
        margin = 3.0 * s
        use = np.all((p0 >= box[0] - margin) & (p0 <= box[1] + margin), axis=1)
    if threshold is not None:
        tips = curvature_tips(p0, faces, edges, threshold, 0.5 * s)
        fixed = np.union1d(fixed, tips[in_box[tips]])
    tau = dt_rel * s * s
    mass0 = ops.vertex_areas(p0, faces)
    lap0 = ops.cotangent_laplacian(p0, faces)
    w = attraction / (s * s)
    mass_floor = 1e-12 * float(mass0.mean())
    frozen = ~use
    frozen[fixed] = True
    p = p0.copy()
    steps, converged = 0, False
    centre = p0.mean(axis=0)
    # The operator is built once on the input surface (cotangent stiffness and
    # lumped mass), so one sparse LU factorization serves every step and axis.
    dirichlet = frozen.copy()  # user-fixed vertices and those outside the region
    free = np.flatnonzero(~dirichlet)
    mass = np.maximum(mass0, mass_floor)
    a = (lap0 * tau + sparse.diags(mass * (1.0 + tau * w))).tocsr()
    a_ff = a[free][:, free].tocsc()
    coupling = a[free][:, np.flatnonzero(dirichlet)] @ p0[dirichlet] if dirichlet.any() else 0.0
    try:
        solve = splinalg.factorized(a_ff)
    except RuntimeError as exc:  # "Factor is exactly singular": degenerate faces or a mesh of slivers
        raise ComputationError(f"the diffusion operator of this mesh is singular ({exc}); is the mesh degenerate?") from exc
    attract = (tau * w * mass)[:, None] * poles
    settle = opts.settle_tolerance * s
    for step in progress(range(1, max_steps + 1), desc="diffusion flow", total=max_steps):
        rhs = (mass[:, None] * p + attract)[free] - coupling
        x = np.column_stack([solve(rhs[:, d]) for d in range(3)])
        p_new = p.copy()
        p_new[free] = x
        if not np.all(np.isfinite(p_new)) or np.abs(p_new - centre).max() > 10.0 * diag:
            raise ComputationError(
                f"the diffusion flow diverged at step {step} (dt={dt_rel} x {s * s:.3g}); try a smaller dt"
            )
        p_new[frozen] = p[frozen]  # skeletal points never move again
        moved = np.linalg.norm(p_new - p, axis=1)
        p = p_new
        steps = step
        # a vertex is skeletal once its one-ring has collapsed or it has stopped
        collapsed = ~frozen & ((ops.vertex_areas(p, faces) < collapse * mass0) | (moved < settle))
        frozen = frozen | collapsed
        state = FlowState(step, readonly(p), readonly(frozen), readonly(faces), step * dt_rel)
        check_cancel(callback, Progress("flow", "diffusion flow", step - 1, max_steps, state))
        if frozen.all():
            converged = True
            break
    final_skipped = None  # why the last step was left out, if it was
    if final_collapse > 0:
        # one mean-curvature step on the contracted surface: its operator has
        # huge weights across the collapsed rings and small ones along the
        # branches, so it pulls each ring onto its centre without retracting tips
        lap_c = ops.cotangent_laplacian(p, faces)
        mass_c = np.maximum(ops.vertex_areas(p, faces), mass_floor)
        a_c = (sparse.diags(mass_c) + (final_collapse * s * s) * lap_c).tocsr()
        a_cf = a_c[free][:, free].tocsc()
        rhs_c = mass_c[free, None] * p[free]
        if dirichlet.any():
            rhs_c = rhs_c - a_c[free][:, np.flatnonzero(dirichlet)] @ p[dirichlet]
        try:
            solve_c = splinalg.factorized(a_cf)
        except RuntimeError:  # singular on a degenerate contracted surface: skip this refinement
            solve_c, final_skipped = None, "its operator is singular"
        if solve_c is not None:
            p_c = p.copy()
            p_c[free] = np.column_stack([solve_c(rhs_c[:, d]) for d in range(3)])
            if np.all(np.isfinite(p_c)):
                p = p_c
            else:
                final_skipped = "it gave non-finite points"
    t_flow = time.perf_counter() - t_start
    cell = spacing if spacing is not None else 0.5 * s
    graph = skeleton_graph(p, p0, faces, cell=cell, use=use, fixed=fixed)
    node_edges, node_of_vertex = graph.edges, graph.correspondence
    pinned = np.zeros(len(graph.points), dtype=bool)
    pinned[node_of_vertex[fixed]] = True
    nodes, radii = centre_nodes(graph.points, node_edges, node_of_vertex, p0, faces, pinned)
    if region is not None:
        slack = 1e-9 * diag
        keep = np.all((nodes >= box[0] - slack) & (nodes <= box[1] + slack), axis=1)
        kept_edges = node_edges[keep[node_edges].all(axis=1)] if len(node_edges) else node_edges
        old_index, node_edges = _graph.compact(len(nodes), kept_edges, keep_nodes=keep)
        new_of_old = np.full(len(nodes) + 1, -1, dtype=np.int64)
        new_of_old[old_index] = np.arange(len(old_index))
        nodes, radii = nodes[old_index], radii[old_index]
        node_of_vertex = np.where(in_box & (node_of_vertex >= 0), new_of_old[node_of_vertex], -1)
    correspondence = np.where(vertex_map >= 0, node_of_vertex[vertex_map], -1)
    metadata = {
        "method": "flow",
        "domain": "mesh",
        "dt": dt_rel,
        "time_unit": s * s,
        "steps": steps,
        "converged": converged,
        "unfrozen_vertices": int((~frozen).sum()),
        "node_spacing": cell,
        "attraction": attraction,
        "collapse": collapse,
        "final_collapse": final_collapse,
        "final_collapse_skipped": final_skipped,
        "curvature_threshold": threshold,
        "fixed_vertices": [int(v) for v in fixed],
        "region": None if region is None else np.asarray(region, dtype=float).tolist(),
        "repairs": list(repairs),
        "refined_vertices": refined,
        "n_vertices": n_input,
        "timings": {"flow": t_flow, "total": time.perf_counter() - t_start},
    }
    return MedialAxis(
        nodes, radii, node_edges, extras={"correspondence": correspondence}, metadata=metadata, shape=clean
    )
