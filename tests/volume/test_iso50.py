"""Wall thickness without bias (issue 35.4): ISO-50 from the histogram's peaks.

The phantom is the benchmark's (``benchmarks/bench_iso50.py``): a 6-voxel disc
plate with partial-volume edges, blur 0.8 and a little noise, background 1000
and material 3000, whose profile crosses 2000 exactly 6.0 voxels apart. Otsu's
class means put the old default at 1830-1890 on it (thickness read 6.2-6.4).
"""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.volume.inputs import iso50, iso50_counts, iso50_histogram, load_volume, value_counts

ROOT = Path(__file__).resolve().parents[2]


def _bench():
    spec = importlib.util.spec_from_file_location("bench_iso50", ROOT / "benchmarks" / "bench_iso50.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


bench = _bench()


@pytest.fixture(scope="module", params=list(bench.ORIENTATIONS))
def plate(request):
    return request.param, *bench.plate(bench.ORIENTATIONS[request.param])


def test_thickness_and_mid_plane_at_every_orientation(plate):
    name, volume, normal, centre = plate
    ma = mx.medial_axis(volume, method="midsurface")
    found = bench.measure(ma, normal, centre)
    assert ma.metadata["threshold_method"] == "peaks"
    assert abs(found["iso"] - 2000.0) <= 0.02 * 2000.0, (name, found)
    assert abs(found["thickness"] - 6.0) <= 0.02 * 6.0, (name, found)
    assert found["p99_inner"] <= 0.3, (name, found)
    # the rim too: the free edges and their extension sit on the chords' mid-points across the plate
    assert found["p99_all"] <= 0.3, (name, found)


@pytest.mark.filterwarnings("ignore::medialaxis.MedialAxisWarning")  # the rim's voxels, under the plates' lam
def test_the_rim_by_blocks_is_the_whole_rim():
    """The chords are sampled by blocks as the whole volume samples them: the same mesh, bit for bit
    (a wider plate, so that the blocks' windows do not all reach the whole sheet)."""
    volume, normal, centre = bench.plate(bench.ORIENTATIONS["tilted 45 deg"], size=80, radius=36, sub=2, rng=3)
    whole = mx.medial_axis(volume, method="midsurface", chunks=0)
    blocks = mx.medial_axis(volume, method="midsurface", chunks=20, n_jobs=1)
    assert blocks.metadata["blocks"]["blocks"] == 64 and blocks.metadata["mesh_halo"] < 60
    assert np.array_equal(blocks.points, whole.points) and np.array_equal(blocks.faces, whole.faces)
    assert bench.measure(blocks, normal, centre, radius=36)["p99_all"] <= 0.3


def test_a_chord_mid_point_is_on_the_mid_plane_whatever_the_normal():
    """A flat plate (exact: its grey value is a ramp of the distance to its mid-plane): the mid-point
    of a chord along a normal 20 degrees off is on the mid-plane; a chord longer than the plate is refused."""
    from medialaxis.volume.sheet.extension import centre_on_chords

    n = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    index = np.indices((40, 40, 40), dtype=np.float64).transpose(1, 2, 3, 0)
    grey = np.clip(3.0 - np.abs((index - 19.5) @ n), -1.0, 1.0)  # crosses 0 at +-3: 6 voxels thick
    tilt = np.radians(20.0)
    normal = np.cos(tilt) * n + np.sin(tilt) * np.array([0.0, 0.0, 1.0])
    centres = np.array([[19.5, 19.5, 19.5], [21.0, 20.0, 18.0], [18.0, 19.0, 22.0]]) + 0.8 * n
    spacing = np.ones(3)
    offsets = centre_on_chords(grey, 0.0, spacing, centres, np.tile(normal, (3, 1)), np.full(3, 6.0), np.full(3, 6.0))
    moved = centres + offsets[:, None] * normal
    assert np.abs((moved - 19.5) @ n).max() <= 0.02
    thin = centre_on_chords(grey, 0.0, spacing, centres, np.tile(normal, (3, 1)), np.full(3, 6.0), np.full(3, 3.0))
    assert np.array_equal(thin, np.zeros(3))  # a 6-voxel chord where the plate is 3 thick


def test_the_previous_rule_read_the_plate_thick(plate):
    """What the issue reports: Otsu's class means read the plate 4-7 % thick."""
    name, volume, normal, centre = plate
    found = bench.measure(mx.medial_axis(volume, method="midsurface", iso=bench.previous_iso(volume)), normal, centre)
    assert found["iso"] < 1900 and found["thickness"] > 6.15, (name, found)


@pytest.mark.filterwarnings("ignore::medialaxis.MedialAxisWarning")  # the rim's voxels, under the plates' lam
def test_float_counted_and_chunked_routes_agree():
    volume, _, _ = bench.plate(bench.ORIENTATIONS["tilted 20 deg"], dtype=np.float32)
    whole = iso50(volume)
    assert whole.method == "peaks" and abs(whole.value - 2000.0) < 40.0
    assert 950 < whole.background < 1050 and 2900 < whole.material < 3050
    counted = iso50_counts(*value_counts(np.rint(volume).astype(np.uint16)))
    assert counted.method == "peaks" and abs(counted.value - whole.value) < 5.0
    in_memory = mx.medial_axis(volume, method="voxels", chunks=0)
    by_blocks = mx.medial_axis(volume, method="voxels", chunks=24, n_jobs=1)
    assert by_blocks.metadata["iso"] == in_memory.metadata["iso"] == whole.value
    assert by_blocks.metadata["threshold_method"] == in_memory.metadata["threshold_method"] == "peaks"


def test_otsu_is_the_fallback_where_there_are_not_two_peaks():
    # a cone of grey values (the distance to the centre): one hump, no two peaks
    grey = np.sqrt(((np.indices((24, 24, 24)) - 11.5) ** 2).sum(0)).astype(np.float32)
    found = iso50(grey)
    assert found.method == "otsu"
    low, high = grey[grey <= _otsu(grey)], grey[grey > _otsu(grey)]
    assert found.value == pytest.approx(0.5 * (low.mean() + high.mean()), rel=1e-6)
    assert load_volume(grey).threshold_method == "otsu"
    # a flat histogram has no peaks; a class left empty gives Otsu's threshold itself
    flat = iso50_histogram(np.ones(256), 0.0, 1.0, lambda t: None)
    assert flat.method == "otsu" and flat.background == flat.value == flat.material


def _otsu(grey):
    from skimage.filters import threshold_otsu

    hist, edges = np.histogram(grey, 256, (grey.min(), grey.max()))
    return threshold_otsu(hist=(hist, 0.5 * (edges[:-1] + edges[1:])))


def test_threshold_method_in_metadata(flat_plate):
    assert mx.medial_axis(flat_plate, method="midsurface").metadata["threshold_method"] == "mask"
    grey = flat_plate * np.float32(1000.0) + np.float32(100.0)
    assert mx.medial_axis(grey, method="midsurface", threshold=600).metadata["threshold_method"] == "given"
    ma = mx.medial_axis(grey, method="voxels")
    assert ma.metadata["threshold_method"] == "peaks" and ma.metadata["iso"] == pytest.approx(600.0)
