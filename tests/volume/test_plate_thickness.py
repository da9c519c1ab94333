"""Parts whose plates differ in thickness (issue 11): every plate is kept, each
with its own thickness, and what a thickness setting leaves out is reported.

Truth is the phantom's own geometry (the rectangles it was drawn from and the
thickness it was drawn with), never the pipeline's estimate.
"""

import json
import warnings

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.cli import main
from medialaxis.datasets import Rect, t_phantom
from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology

SHAPE = (100, 160, 160)


@pytest.fixture(scope="module")
def rib_t():
    """A T whose flange is 8 voxels thick and whose stem (the rib) is 4."""
    return t_phantom(SHAPE, thickness=8, stem_thickness=4, margin=16)


def _plates(ma, rects, thickness, tolerance=1.5):
    """Per plate: coverage of its true mid-plane within ``tolerance`` and the
    median thickness of the vertices on it (away from the other plate)."""
    out = []
    for k, rect in enumerate(rects):
        others = [r for j, r in enumerate(rects) if j != k]
        frac, _ = coverage(rect.sample(0.5), ma.points, ma.faces, tolerance=tolerance)
        on = (distance_to_rects(ma.points, [rect]) < tolerance) & (distance_to_rects(ma.points, others) > 6)
        out.append((frac, float(np.median(2 * ma.radii[on])) if on.any() else float("nan"), thickness[k]))
    return out


def _check_every_plate(ma, rects, thickness):
    for frac, measured, true in _plates(ma, rects, thickness):
        assert frac >= 0.97, (frac, true)
        assert abs(measured - true) <= 0.15 * true, (measured, true)
    assert mesh_topology(ma.faces).components == 1


def test_a_uniform_part_is_judged_by_its_one_thickness(small_t):
    """One plate thickness: the result is the nominal-thickness result."""
    auto = mx.medial_axis(small_t.volume, method="midsurface", iso=0.5)
    nominal = mx.medial_axis(small_t.volume, method="midsurface", iso=0.5, thickness=auto.metadata["thickness"])
    assert np.array_equal(auto.faces, nominal.faces) and np.allclose(auto.points, nominal.points)
    assert abs(auto.metadata["thickness"] - small_t.thickness) <= 0.1 * small_t.thickness


def test_a_rib_thinner_than_its_wall_is_kept_with_its_own_thickness(rib_t):
    with warnings.catch_warnings():
        warnings.simplefilter("error", mx.MedialAxisWarning)
        ma = mx.medial_axis(rib_t.volume, method="midsurface", iso=0.5)
    _check_every_plate(ma, rib_t.midsurface, rib_t.plate_thickness)
    assert ma.metadata["dropped"] is None
    assert ma.metadata["thickness_range"] == [2.0, None]


def _coarse_slices(volume):
    """Slices twice as far apart as pixels: each slice averages two fine ones
    (a CT slice integrates over its width)."""
    z = volume.shape[0] // 2 * 2
    return 0.5 * (volume[0:z:2] + volume[1:z:2])


def _physical(rect, order):
    """A fine-grid rectangle in the coarse volume's physical frame: axes
    permuted by ``order``, then the slice centre half a fine voxel down."""
    shift = np.array([-0.5, 0.0, 0.0])
    return Rect(rect.origin[order] + shift, rect.u[order], rect.v[order])


@pytest.mark.parametrize("order", [(0, 1, 2), (2, 1, 0), (1, 0, 2)],
                         ids=["flange-across-slices", "flange-along-slices", "rib-across-slices"])
def test_anisotropic_voxels_keep_both_plates(rib_t, order):
    order = list(order)
    coarse = _coarse_slices(np.ascontiguousarray(rib_t.volume.transpose(order)))
    ma = mx.medial_axis(coarse, method="midsurface", iso=0.5, spacing=(2.0, 1.0, 1.0))
    rects = [_physical(r, order) for r in rib_t.midsurface]
    _check_every_plate(ma, rects, rib_t.plate_thickness)


def test_a_fixed_thickness_says_what_it_leaves_out(rib_t):
    with pytest.warns(mx.MedialAxisWarning, match=r"plates about 4(\.\d+)? thick .* thickness=8"):
        ma = mx.medial_axis(rib_t.volume, method="midsurface", iso=0.5, thickness=8)
    dropped = ma.metadata["dropped"]
    assert abs(dropped["thickness"] - 4) <= 0.6 and dropped["fraction"] > 0.1
    (flange, _, _), (stem, _, _) = _plates(ma, rib_t.midsurface, rib_t.plate_thickness)
    assert flange >= 0.97 and stem < 0.2


def test_a_thickness_range_keeps_the_plates_inside_it(rib_t):
    both = mx.medial_axis(rib_t.volume, method="midsurface", iso=0.5, thickness=(2, 20))
    _check_every_plate(both, rib_t.midsurface, rib_t.plate_thickness)
    assert both.metadata["thickness_range"] == [2.0, 20.0]
    with pytest.warns(mx.MedialAxisWarning, match="thickness range 6 to 20"):
        thick = mx.medial_axis(rib_t.volume, method="midsurface", iso=0.5, thickness=(6, 20))
    (flange, _, _), (stem, _, _) = _plates(thick, rib_t.midsurface, rib_t.plate_thickness)
    assert flange >= 0.97 and stem < 0.2
    assert abs(thick.metadata["dropped"]["thickness"] - 4) <= 0.6
    with pytest.warns(mx.MedialAxisWarning, match="thickness range 2 to 5"):
        thin = mx.medial_axis(rib_t.volume, method="midsurface", iso=0.5, thickness=(2, 5))
    (flange, _, _), (stem, _, _) = _plates(thin, rib_t.midsurface, rib_t.plate_thickness)
    assert flange < 0.2 and stem >= 0.93  # the stem ends short of the flange it no longer meets


def test_medial_voxels_take_the_same_thickness_options(rib_t):
    ma = mx.medial_axis(rib_t.volume, method="voxels", iso=0.5)
    stem = rib_t.midsurface[1]
    on_stem = distance_to_rects(ma.points, [stem]) < 1.5
    assert on_stem.sum() > 1000 and ma.metadata["dropped"] is None
    with pytest.warns(mx.MedialAxisWarning):
        fixed = mx.medial_axis(rib_t.volume, method="voxels", iso=0.5, thickness=8)
    assert (distance_to_rects(fixed.points, [stem]) < 1.5).sum() < 0.2 * on_stem.sum()


@pytest.mark.parametrize("bad", [(5, 2), (0, 5), (-1, 5), ("a", 3), (1, 2, 3), (float("nan"), 5), (2, float("nan"))])
def test_bad_thickness_ranges_are_named(small_t, bad):
    with pytest.raises(mx.InvalidInputError, match="thickness"):
        mx.medial_axis(small_t.volume, method="midsurface", iso=0.5, thickness=bad)


def test_a_range_with_no_plate_in_it_is_an_empty_shape(small_t):
    with pytest.raises(mx.EmptyShapeError, match=r"between 20 and 30 thick; the plates found are"):
        mx.medial_axis(small_t.volume, method="midsurface", iso=0.5, thickness=(20, 30))


def test_cli_prints_one_warning_line(rib_t, tmp_path, capsys):
    src = tmp_path / "rib_t.npy"
    np.save(src, rib_t.volume)
    out = tmp_path / "mid.json"
    code = main(["compute", str(src), "--method", "midsurface", "--threshold", "0.5",
                 "--option", "thickness=8", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 0
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("medialaxis: warning: plates about 4"), err
    assert json.loads(out.read_text())["metadata"]["dropped"]["fraction"] > 0.1
