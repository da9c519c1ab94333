"""The mid-surface pipeline on analytic phantoms (known mid-planes)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import medialaxis as mx
from medialaxis.datasets import t_phantom
from medialaxis.volume.pipeline import volume_stages
from medialaxis.volume.sheet.polygonize import BOUNDARY, EXTENSION, JUNCTION, SURFACE
from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology


def _truth(ph):
    return np.concatenate([r.sample(0.5) for r in ph.midsurface])


def test_flat_plate_is_one_disc_on_the_mid_plane(flat_plate):
    ma = mx.medial_axis(flat_plate, method="midsurface")
    topo = mesh_topology(ma.faces)
    assert topo.components == 1 and topo.euler == 1 and topo.junction_edges == 0
    assert np.allclose(ma.points[:, 0], 9.5, atol=1e-6)
    assert np.allclose(2 * ma.radii, 6.0, atol=1e-6)
    # extended to the plate's end faces (voxels 6..37 and 5..34: faces at 5.5/37.5 and 4.5/34.5)
    assert np.isclose(ma.points[:, 1].min(), 5.5, atol=0.3) and np.isclose(ma.points[:, 1].max(), 37.5, atol=0.3)
    assert np.isclose(ma.points[:, 2].min(), 4.5, atol=0.3) and np.isclose(ma.points[:, 2].max(), 34.5, atol=0.3)


def test_t_junction_targets(small_t):
    ph = small_t
    st_ = volume_stages(ph.volume, iso=0.5)
    ma = st_.result
    d = distance_to_rects(ma.points, ph.midsurface)
    assert np.percentile(d, 99) <= 1.0 and d.max() <= 2.0
    frac, _ = coverage(_truth(ph), ma.points, ma.faces)
    assert frac >= 0.985
    flange, stem = ph.midsurface
    near = np.hypot(ma.points[:, 0] - flange.origin[0], ma.points[:, 1] - stem.origin[1]) <= ph.thickness
    assert d[near].max() <= 0.75  # no dent
    assert abs(np.median(2 * ma.radii) - 6) <= 0.6
    topo = mesh_topology(ma.faces)
    assert topo.components == 1 and topo.junction_edges > 0
    kinds = set(np.unique(ma.vertex_kind).tolist())
    assert {SURFACE, BOUNDARY, JUNCTION, EXTENSION} <= kinds


def test_extension_and_dent_removal_each_help(small_t):
    ph = small_t
    full = volume_stages(ph.volume, iso=0.5).result
    short = volume_stages(ph.volume, iso=0.5, extend=False).result
    dented = volume_stages(ph.volume, iso=0.5, remove_dents=False).result
    truth = _truth(ph)
    assert coverage(truth, full.points, full.faces)[0] > coverage(truth, short.points, short.faces)[0] + 0.02
    j = full.vertex_kind == JUNCTION
    d_full = distance_to_rects(full.points[j], ph.midsurface)
    d_dent = distance_to_rects(dented.points[dented.vertex_kind == JUNCTION], ph.midsurface)
    assert d_full.max() < d_dent.max()


def test_x_junction(x_part):
    ma = mx.medial_axis(x_part.volume, method="midsurface", iso=0.5, thickness=6.0)
    d = distance_to_rects(ma.points, x_part.midsurface)
    assert np.percentile(d, 99) <= 1.0
    assert coverage(_truth(x_part), ma.points, ma.faces)[0] >= 0.985
    topo = mesh_topology(ma.faces)
    assert topo.components == 1 and topo.junction_edges > 0 and topo.euler == 1


def test_member_box_section(member_part):
    ma = mx.medial_axis(member_part.volume, method="midsurface", iso=0.5)
    assert coverage(_truth(member_part), ma.points, ma.faces)[0] >= 0.97
    assert np.percentile(distance_to_rects(ma.points, member_part.midsurface), 99) <= 1.0
    assert mesh_topology(ma.faces).components == 1


@given(
    thickness=st.integers(4, 9),
    offset=st.integers(0, 3),
    axis=st.integers(0, 2),
    spacing=st.sampled_from([1.0, 0.5, 2.0]),
)
def test_plates_any_axis_thickness_and_spacing(thickness, offset, axis, spacing):
    shape = [18, 30, 30]
    vol = np.zeros(shape, bool)
    lo = 4 + offset
    vol[lo : lo + thickness, 4:26, 5:25] = True
    vol = np.moveaxis(vol, 0, axis)
    ma = mx.medial_axis(vol, method="midsurface", spacing=spacing)
    mid = (lo + (thickness - 1) / 2) * spacing
    assert np.allclose(ma.points[:, axis], mid, atol=0.05 * spacing)
    assert abs(np.median(2 * ma.radii) - thickness * spacing) <= 0.1 * thickness * spacing
    assert ma.metadata["thickness"] == pytest.approx(thickness * spacing, rel=0.1)


def test_translation_and_scale_equivariance(small_t):
    vol = small_t.volume
    base = mx.medial_axis(vol, method="midsurface", iso=0.5)
    shifted = mx.medial_axis(np.pad(vol, ((3, 0), (0, 0), (5, 0))), method="midsurface", iso=0.5)
    assert np.allclose(shifted.points, base.points + [3, 0, 5])
    assert np.array_equal(shifted.faces, base.faces)
    scaled = mx.medial_axis(vol, method="midsurface", iso=0.5, spacing=2.5)
    assert np.allclose(scaled.points, 2.5 * base.points)
    assert np.allclose(scaled.radii, 2.5 * base.radii)


def test_input_not_modified_and_outputs_read_only(small_t):
    vol = small_t.volume
    before = vol.copy()
    ma = mx.medial_axis(vol, method="midsurface", iso=0.5)
    assert np.array_equal(vol, before)
    for arr in (ma.points, ma.faces, ma.radii, ma.thickness, ma.vertex_kind):
        assert not arr.flags.writeable
    assert ma.metadata["method"] == "midsurface" and ma.metadata["domain"] == "volume"


def test_voxels_method(small_t):
    ma = mx.medial_axis(small_t.volume, method="voxels", iso=0.5)
    assert len(ma.faces) == 0 and len(ma.points) > 0
    assert np.allclose(ma.points, np.round(ma.points))  # voxel centres
    assert np.percentile(distance_to_rects(ma.position, small_t.midsurface), 95) <= 0.5
    assert set(np.unique(ma.voxel_kind).tolist()) <= {SURFACE, BOUNDARY, JUNCTION}
    assert abs(np.median(2 * ma.radii) - 6) <= 0.6


def test_callback_cancels(flat_plate):
    heard = []

    def until_polygonize(progress):
        heard.append(progress)
        return progress.stage != "polygonize"

    with pytest.raises(mx.Cancelled):
        mx.medial_axis(flat_plate, method="midsurface", callback=until_polygonize)
    assert [(p.method, p.stage, p.step, p.total) for p in heard] == [
        ("midsurface", stage, k, 6) for k, stage in enumerate(("binarize", "distance", "medial voxels", "polygonize"))]


def test_the_voxel_route_reports_its_stages_and_cancels(flat_plate):
    from medialaxis.volume.voxel_axis import STAGES

    heard = []
    ma = mx.medial_axis(flat_plate, method="voxels", callback=heard.append)
    assert len(ma.points) and [(p.method, p.stage, p.step) for p in heard] == [("voxels", s, k) for k, s in enumerate(STAGES)]
    with pytest.raises(mx.Cancelled):
        mx.medial_axis(flat_plate, method="voxels", callback=lambda progress: progress.stage != "classify")


def test_reproducible_for_a_seed(small_t):
    a = mx.medial_axis(small_t.volume, method="midsurface", iso=0.5, rng=3)
    b = mx.medial_axis(small_t.volume, method="midsurface", iso=0.5, rng=3)
    assert np.array_equal(a.points, b.points) and np.array_equal(a.faces, b.faces)


@pytest.mark.slow
def test_full_size_t_phantom_targets():
    """The issue's 140 x 240 x 240 T (the benchmark reports the same figures)."""
    ph = t_phantom()
    ma = mx.medial_axis(ph.volume, method="midsurface", iso=0.5)
    d = distance_to_rects(ma.points, ph.midsurface)
    assert np.percentile(d, 99) <= 1.0 and d.max() <= 2.0
    assert coverage(_truth(ph), ma.points, ma.faces)[0] >= 0.985
    flange, stem = ph.midsurface
    near = np.hypot(ma.points[:, 0] - flange.origin[0], ma.points[:, 1] - stem.origin[1]) <= ph.thickness
    x = ma.points[:, 2]
    inner = near & (x > flange.origin[2] + ph.thickness) & (x < flange.origin[2] + flange.v[2] - ph.thickness)
    assert d[inner].max() <= 0.75  # no dent along the junction
    assert d[near].max() <= 0.75  # including where the junction meets the end faces
    assert abs(np.median(2 * ma.radii) - 6) <= 0.6
    topo = mesh_topology(ma.faces)
    assert topo.components == 1 and topo.junction_edges > 0 and topo.euler == 1
