"""Thin parts as CAD tools write them (float32 STL): the default call keeps their plates.

Truth is the geometry: a plate's mid-plane and half thickness, the solid's
Betti numbers from its construction.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.mesh.sample.thin_parts import local_thickness

trimesh = pytest.importorskip("trimesh")
shapely = pytest.importorskip("shapely")


def test_the_shrinking_ball_measures_a_plate_and_a_rod():
    plate = trimesh.creation.box(extents=(4.0, 4.0, 0.2))
    points, face = trimesh.sample.sample_surface_even(plate, 4000, seed=1)
    normals = plate.face_normals[face]
    thickness = local_thickness(points, normals, np.full(len(points), 10.0))
    flat = np.abs(normals[:, 2]) > 0.9
    inner = flat & (np.abs(points[:, :2]).max(axis=1) < 1.8)  # away from the rim
    assert np.median(thickness[inner]) == pytest.approx(0.2, rel=0.05)
    assert thickness[inner].max() < 0.2 * 1.5
    # capped where the ball would be larger than asked about
    assert local_thickness(points, normals, np.full(len(points), 0.05)).max() <= 0.05


def test_a_cad_plate_keeps_its_mid_surface_by_default(tmp_path):
    trimesh.creation.box(extents=(10.0, 10.0, 0.2)).export(tmp_path / "plate.stl")  # 8 vertices, float32
    ma = mx.medial_axis(tmp_path / "plate.stl")
    assert ma.betti == (1, 0, 0)
    assert np.abs(ma.points[:, 2]).max() < 0.02  # on the mid-plane
    assert np.median(ma.radii) == pytest.approx(0.1, rel=0.02)  # half the thickness
    sheet = trimesh.Trimesh(ma.points, ma.faces, process=False).area
    assert sheet > 0.9 * 9.8**2  # the mid-plane inset by half the thickness, nearly whole
    assert ma.metadata["n_samples"] > 20_000  # grown for the thin part


def test_an_extruded_l_plate_with_a_hole_keeps_its_tunnel(tmp_path):
    outline = shapely.Polygon([(0, 0), (4, 0), (4, 1), (1, 1), (1, 4), (0, 4)]).difference(
        shapely.Point(0.5, 2.5).buffer(0.25))
    trimesh.creation.extrude_polygon(outline, 0.3).export(tmp_path / "l.stl")
    ma = mx.medial_axis(tmp_path / "l.stl")
    assert ma.betti == (1, 1, 0)  # genus 1: the hole
    assert np.abs(ma.points[:, 2] - 0.15).max() < 0.05


def test_a_thin_part_capped_below_its_count_is_warned_about_once(tmp_path, monkeypatch):
    # the thin-part check runs beside the Delaunay insertion; its warning still comes once, from the call
    import medialaxis.mesh.sample.thin_parts as sampling

    trimesh.creation.box(extents=(10.0, 10.0, 0.2)).export(tmp_path / "plate.stl")
    monkeypatch.setattr(sampling, "THIN_SAMPLES", 30_000)  # the plate wants about 55,000
    with pytest.warns(mx.MedialAxisWarning, match="mostly thin") as caught:
        ma = mx.medial_axis(tmp_path / "plate.stl", lam=0.05)
    thin = [w for w in caught if "mostly thin" in str(w.message)]
    assert len(thin) == 1 and int(re.search(r"samples=(\d+)", str(thin[0].message)).group(1)) > 30_000
    assert thin[0].filename != sampling.__file__  # the caller's line, not the thread's
    assert 30_000 <= ma.metadata["n_samples"] < 40_000  # grown to the cap, not to what it wanted


def test_a_flat_cavity_under_the_surface_and_a_slit_between_two_parts_keep_their_topology():
    """Gaps thinner than the spacing are sampled finer (the outer side's shrinking balls): a flat cavity 0.2
    thick, 0.1 under the top of a 10 x 10 x 4 box leaked into the outside, (1, 0, 0); two 4 x 4 x 1 boxes
    0.02 apart were joined, (1, 15, 0). Truth from the construction: one cavity; two parts."""
    box = trimesh.creation.box(extents=(10.0, 10.0, 4.0))
    cavity = trimesh.creation.box(extents=(4.0, 4.0, 0.2))
    cavity.apply_translation([0.0, 0.0, 2.0 - 0.1 - 0.1])
    cavity.invert()
    assert mx.medial_axis(trimesh.util.concatenate([box, cavity])).betti == (1, 0, 1)
    lower, upper = trimesh.creation.box(extents=(4.0, 4.0, 1.0)), trimesh.creation.box(extents=(4.0, 4.0, 1.0))
    upper.apply_translation([0.0, 0.0, 1.02])
    ma = mx.medial_axis(trimesh.util.concatenate([lower, upper]))
    assert ma.betti == (2, 0, 0)
    assert ma.metadata["n_samples"] < 60_000  # finer near the slit only (22,000 before)
