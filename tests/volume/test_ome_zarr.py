"""OME-Zarr (NGFF 0.4) in and out (issue 35.5).

The input is written here with zarr and the NGFF metadata by hand, as the
specification lays them out (https://ngff.openmicroscopy.org/0.4/): a channel
axis of size 1, a 2-level pyramid, an anisotropic scale; and by ome-zarr's own
writer, as users make such files. The reference reader (``ome-zarr``, in the
test extra) reads the output; the fields the specification requires are
checked too.
"""


import numpy as np
import pytest

import medialaxis as mx
from medialaxis.datasets import t_phantom
from medialaxis.errors import InvalidInputError
from medialaxis.volume.files.ome_zarr import image_levels
from medialaxis.volume.files.sources import open_source

zarr = pytest.importorskip("zarr")

SPACING = (1.5, 1.0, 1.0)


def _write_ome(path, volume, *, axes="czyx", spacing=SPACING, unit="millimeter", version="0.4"):
    """A 2-level OME-Zarr image of ``volume`` (level 1 every second voxel), extra axes of size 1 in front."""
    lead = len(axes) - 3
    group = zarr.open_group(str(path), mode="w", zarr_format=2)
    kinds = {"t": "time", "c": "channel"}
    group.attrs["multiscales"] = [{
        "version": version,
        "axes": [{"name": a, "type": kinds.get(a, "space"), **({"unit": unit} if a in "zyx" else {})} for a in axes],
        "datasets": [{"path": str(k), "coordinateTransformations": [
            {"type": "scale", "scale": [1.0] * lead + [s * 2**k for s in spacing]}]} for k in range(2)],
    }]
    for k in range(2):
        level = volume[:: 2**k, :: 2**k, :: 2**k].reshape((1,) * lead + volume[:: 2**k, :: 2**k, :: 2**k].shape)
        array = group.create_array(str(k), shape=level.shape, dtype=level.dtype, chunks=(1,) * lead + (16, 16, 16),
                                   chunk_key_encoding={"name": "v2", "separator": "/"})
        array[:] = level


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ome")
    volume = t_phantom((40, 64, 56), margin=6).volume
    np.save(folder / "t.npy", volume)
    _write_ome(folder / "t.ome.zarr", volume)
    return folder, volume


def test_an_ome_zarr_image_gives_the_mesh_of_its_array_with_its_spacing(scan):
    folder, _ = scan
    ome = mx.medial_axis(str(folder / "t.ome.zarr"), method="midsurface", chunks=24)
    npy = mx.medial_axis(str(folder / "t.npy"), method="midsurface", chunks=24, spacing=SPACING)
    assert ome.metadata["spacing"] == list(SPACING) and ome.metadata["image_shape"] == [40, 64, 56]
    assert np.array_equal(ome.points, npy.points) and np.array_equal(ome.faces, npy.faces)
    assert np.array_equal(ome.radii, npy.radii)


def test_a_level_is_chosen_by_its_path_and_keeps_its_own_scale(scan):
    folder, volume = scan
    source = open_source(folder / "t.ome.zarr" / "1")
    assert source.level == 1 and source.shape == (20, 32, 28) and source.spacing == (3.0, 2.0, 2.0)
    assert source.unit == "millimeter"
    box = (slice(2, 9), slice(0, 32), slice(5, 6))
    assert np.array_equal(source.read(box), volume[::2, ::2, ::2][box])  # the channel axis dropped
    assert open_source(folder / "t.ome.zarr").level == 0


def test_an_axis_of_several_channels_is_refused(tmp_path):
    group = zarr.open_group(str(tmp_path / "two.ome.zarr"), mode="w", zarr_format=2)
    group.attrs["multiscales"] = [{"version": "0.4", "axes": [{"name": "c", "type": "channel"}] + [
        {"name": a, "type": "space"} for a in "zyx"], "datasets": [{"path": "0", "coordinateTransformations": [
            {"type": "scale", "scale": [1.0, 1.0, 1.0, 1.0]}]}]}]
    group.create_array("0", shape=(2, 8, 8, 8), dtype="u2")
    with pytest.raises(InvalidInputError, match="'c' has 2 entries"):
        open_source(tmp_path / "two.ome.zarr")


def _check_ngff_04(group, shape, spacing):
    """The fields NGFF 0.4 requires of a multiscale image (section "multiscales")."""
    (multiscale,) = group.attrs["multiscales"]
    assert multiscale["version"] == "0.4"
    assert [(a["name"], a["type"]) for a in multiscale["axes"]] == [("z", "space"), ("y", "space"), ("x", "space")]
    levels = image_levels(shape)
    assert len(multiscale["datasets"]) == len(levels) >= 2
    for k, (dataset, level) in enumerate(zip(multiscale["datasets"], levels)):
        transforms = dataset["coordinateTransformations"]
        assert transforms[0] == {"type": "scale", "scale": [s * 2**k for s in spacing]}  # scale first, one per axis
        assert all(len(t.get("scale", t.get("translation"))) == 3 for t in transforms)
        array = group[dataset["path"]]
        assert array.shape == level and array.metadata.zarr_format == 2
        assert array.metadata.dimension_separator == "/"


def test_out_ome_zarr_is_the_thickness_on_the_mid_surface_and_the_mesh(scan, tmp_path):
    folder, volume = scan
    out = tmp_path / "thickness.ome.zarr"
    streamed = mx.medial_axis(str(folder / "t.ome.zarr"), method="midsurface", chunks=24, out=out)
    whole = mx.medial_axis(volume, method="midsurface", chunks=0, spacing=SPACING, out=tmp_path / "memory.ome.zarr")
    group = zarr.open_group(str(out), mode="r")
    _check_ngff_04(group, volume.shape, SPACING)
    assert group.attrs["multiscales"][0]["axes"][0]["unit"] == "millimeter"  # the input's unit
    level0, level1 = np.asarray(group["0"]), np.asarray(group["1"])
    medial = mx.medial_axis(volume, method="voxels", spacing=SPACING)  # the medial voxels and their radii
    index = np.rint(medial.points / np.array(SPACING)).astype(int)
    assert np.count_nonzero(level0) == len(index)
    assert np.allclose(level0[tuple(index.T)], 2.0 * medial.radii)
    # each coarser voxel keeps the largest thickness of its 2x2x2
    padded = np.zeros((40, 64, 56), np.float32)
    padded[tuple(index.T)] = level0[tuple(index.T)]
    assert np.array_equal(level1, padded.reshape(20, 2, 32, 2, 28, 2).max(axis=(1, 3, 5)))
    # the in-memory route writes the same image; the mesh is in the group "mesh"
    assert np.array_equal(np.asarray(zarr.open_group(str(tmp_path / "memory.ome.zarr"), mode="r")["0"]), level0)
    mesh = group["mesh"]
    assert streamed.metadata["vertices"] == len(whole.points) == mesh["vertices"].shape[0]
    assert np.array_equal(np.sort(np.asarray(mesh["vertices"]), axis=0), np.sort(whole.points, axis=0))


def test_the_reference_reader_reads_the_output(scan, tmp_path):
    """ome-zarr (the OME-NGFF reference reader, in the test extra) reads the levels we write."""
    from ome_zarr.io import parse_url
    from ome_zarr.reader import Reader

    folder, volume = scan
    out = tmp_path / "thickness.ome.zarr"
    mx.medial_axis(str(folder / "t.ome.zarr"), method="midsurface", chunks=24, out=out)
    (image, *_) = list(Reader(parse_url(str(out)))())
    assert [tuple(level.shape) for level in image.data] == image_levels(volume.shape)


def test_the_cli_reads_an_ome_zarr_level(scan, tmp_path):
    """``medialaxis compute scan.ome.zarr/1``: the store is one volume (not a folder of shape files)."""
    import json

    from medialaxis.cli import main

    folder, _ = scan
    assert main(["compute", str(folder / "t.ome.zarr" / "1"), "--method", "midsurface", "-o", str(tmp_path / "a.json")]) == 0
    assert json.loads((tmp_path / "a.json").read_text())["metadata"]["spacing"] == [3.0, 2.0, 2.0]


def test_an_image_written_by_ome_zarr_gives_the_mesh_of_its_array(scan, tmp_path):
    """A file made the way users make them: ome-zarr's own writer (NGFF 0.4, a pyramid, physical scale)."""
    from ome_zarr.format import FormatV04
    from ome_zarr.writer import write_image

    folder, volume = scan
    group = zarr.open_group(str(tmp_path / "w.ome.zarr"), mode="w", zarr_format=2)
    write_image(volume, group, scale_factors=[2], axes="zyx", fmt=FormatV04(),
                scale=dict(zip("zyx", SPACING)))
    ome = mx.medial_axis(str(tmp_path / "w.ome.zarr"), method="midsurface", chunks=24)
    npy = mx.medial_axis(str(folder / "t.npy"), method="midsurface", chunks=24, spacing=SPACING)
    assert ome.metadata["spacing"] == list(SPACING)
    assert np.array_equal(ome.points, npy.points) and np.array_equal(ome.faces, npy.faces)
