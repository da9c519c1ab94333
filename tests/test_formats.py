"""The format registry (:mod:`medialaxis.core.formats`): every suffix it registers is routed to its
domain and read there, from a file made by the library of the format; every writer's file is read
back by an outside reader with the result's content."""

import json
import shutil
import sys
import xml.etree.ElementTree as ET

import meshio
import networkx as nx
import nibabel as nib
import nrrd
import numpy as np
import pytest
import shapely
import tifffile
import trimesh
from PIL import Image

import medialaxis as mx
from medialaxis import cli
from medialaxis._dispatch import classify
from medialaxis.cli.batch import SHAPE_SUFFIXES, expand_inputs
from medialaxis.core import formats
from medialaxis.core.io import WRITERS
from medialaxis.mesh.solid.inputs import load_mesh
from medialaxis.planar.reading.inputs import load_planar
from medialaxis.volume.files.readers import read_volume
from medialaxis.volume.files.sources import open_source

SQUARE = shapely.box(2.0, 3.0, 12.0, 9.0)  # area 60
DISK = (np.hypot(*np.mgrid[-32:32, -32:32]) < 20).astype(np.uint8) * 255  # a disk of radius 20 pixels
VOLUME = np.zeros((12, 14, 16), np.uint8)
VOLUME[3:9, 4:10, 2:14] = 200


def _image(path):
    Image.fromarray(DISK).save(path)


def _result(path):
    mx.medial_axis(SQUARE).save(path)


def _mesh(path):
    trimesh.creation.box((2.0, 1.0, 0.5)).export(path)


def _dxf(path):
    import ezdxf

    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline(list(SQUARE.exterior.coords), close=True)
    doc.saveas(path)


#: A maker of a file of each input suffix, by a library of the format (or its plain text), and the domain it is.
MAKERS = {
    **{s: (_image, "planar") for s in (".png", ".jpg", ".jpeg", ".bmp", ".gif", ".tif", ".tiff")},
    ".svg": (lambda p: p.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="20" height="20">'
                                    '<rect x="2" y="3" width="10" height="6"/></svg>'), "planar"),
    ".dxf": (_dxf, "planar"),
    ".geojson": (lambda p: p.write_text(json.dumps(shapely.geometry.mapping(SQUARE))), "planar"),
    ".json": (lambda p: p.write_text(json.dumps(shapely.geometry.mapping(SQUARE))), "planar"),
    ".wkt": (lambda p: p.write_text(SQUARE.wkt), "planar"),
    ".npy": (lambda p: np.save(p, DISK), "planar"),
    ".npz": (_result, "result"),
    **{s: (_mesh, "mesh") for s in (".obj", ".ply", ".off", ".stl", ".glb", ".gltf")},
    ".nrrd": (lambda p: nrrd.write(str(p), VOLUME, index_order="C"), "volume"),
    ".nhdr": (lambda p: nrrd.write(str(p), VOLUME, index_order="C", detached_header=True), "volume"),
    ".nii": (lambda p: nib.save(nib.Nifti1Image(VOLUME, np.eye(4)), p), "volume"),
    ".nii.gz": (lambda p: nib.save(nib.Nifti1Image(VOLUME, np.eye(4)), p), "volume"),
    ".raw": (lambda p: VOLUME.tofile(p), "volume"),
    ".dcm": (lambda p: shutil.copy(_dicom(), p), "volume"),
}


def _dicom():
    from pydicom.data import get_testdata_file

    return get_testdata_file("CT_small.dcm")


def test_every_input_suffix_has_a_maker_here():
    assert set(MAKERS) == set(formats.suffixes(*formats.ROUTED)) == set(SHAPE_SUFFIXES)


@pytest.mark.parametrize("suffix", sorted(MAKERS))
def test_each_suffix_routes_to_its_domain_which_reads_it(suffix, tmp_path):
    make, domain = MAKERS[suffix]
    path = tmp_path / f"shape{suffix.upper() if suffix == '.nii.gz' else suffix}"
    make(path)
    assert classify(str(path)) == domain
    if domain == "planar":
        region = load_planar(path).region
        expected = np.pi * 20**2 if make is _image or suffix == ".npy" else SQUARE.area
        assert region.area == pytest.approx(expected, rel=0.03)
    elif domain == "mesh":
        assert load_mesh(path).volume == pytest.approx(1.0)  # trimesh's box, 2 x 1 x 0.5
    elif domain == "result":
        assert np.array_equal(mx.load(path).points, mx.medial_axis(SQUARE).points)
    elif suffix == ".dcm":  # one CT slice (pydicom's test file): a volume one slice thick, pydicom's pixels
        import pydicom

        assert np.array_equal(read_volume(path)[0], pydicom.dcmread(path).pixel_array[None])
    else:
        layout = {"shape": VOLUME.shape, "dtype": VOLUME.dtype} if suffix == ".raw" else {}
        assert np.array_equal(read_volume(path, **layout)[0], VOLUME)
        source = open_source(path, raw_shape=VOLUME.shape, raw_dtype=VOLUME.dtype)
        assert np.array_equal(source.read(tuple(slice(0, n) for n in VOLUME.shape)), VOLUME)


@pytest.mark.parametrize(("array", "domain"), [(DISK, "planar"), (VOLUME, "volume")])
def test_tiff_and_npy_are_told_apart_by_their_content(array, domain, tmp_path):
    tifffile.imwrite(tmp_path / "a.tif", array)
    np.save(tmp_path / "a.npy", array)
    assert classify(str(tmp_path / "a.tif")) == classify(str(tmp_path / "a.npy")) == domain


def test_a_saved_result_in_json_is_a_result(tmp_path):
    _result(tmp_path / "axis.json")
    assert classify(str(tmp_path / "axis.json")) == "result"


@pytest.mark.parametrize("suffix", [".vtk", ".swc", ".graphml", ".html", ".vrt", ".xyz"])
def test_output_only_and_unknown_suffixes_are_refused_as_inputs(suffix, tmp_path):
    path = tmp_path / f"a{suffix}"
    path.write_text("x")
    with pytest.raises(mx.UnsupportedFormatError, match=f"unsupported file type '\\{suffix}'"):
        classify(str(path))


def test_a_folder_of_every_input_suffix_is_found_whole(tmp_path):
    for k, suffix in enumerate(sorted(MAKERS)):
        (tmp_path / f"s{k}{suffix}").write_text("")
    (tmp_path / "notes.txt").write_text("")
    found = expand_inputs([tmp_path])
    assert sorted(formats.suffix_of(p) for p in found) == sorted(MAKERS)


def test_suffix_of_knows_compound_suffixes():
    assert formats.suffix_of("a/b.Scan.NII.GZ") == ".nii.gz"
    assert formats.suffix_of("archive.tar.gz") == ".gz"
    assert formats.suffix_of(".nii.gz") == ".gz"  # a hidden file named '.nii' with suffix .gz
    assert formats.suffix_of("README") == ""


def test_a_suffix_is_registered_once():
    with pytest.raises(ValueError, match="taken"):
        formats.register_format(formats.Format("again", (".png",)))
    with pytest.raises(ValueError, match="malformed"):
        formats.register_format(formats.Format("upper", (".PNGX",)))


# ------------------------------------------------------------ writers
CURVE = mx.medial_axis(SQUARE)


def _surface():
    return mx.medial_axis(trimesh.creation.box((2.0, 1.0, 0.5)), method="voronoi")


def _points(ma):
    return np.c_[ma.points, np.zeros(len(ma.points))] if ma.dim == 2 else ma.points


def _read_json(path, ma):
    doc = json.loads(path.read_text())
    return np.array_equal(np.array(doc["points"], float), ma.points) and np.array_equal(doc["radii"], ma.radii)


def _read_npz(path, ma):
    with np.load(path, allow_pickle=False) as z:
        return np.array_equal(z["points"], ma.points) and np.array_equal(z["radii"], ma.radii)


def _read_graphml(path, ma):
    g = nx.read_graphml(path)
    return g.number_of_nodes() == len(ma.points) and np.allclose(
        sorted(d["radius"] for _, d in g.nodes(data=True)), np.sort(ma.radii))


def _read_geojson(path, ma):
    features = json.loads(path.read_text())["features"]
    lines = [shapely.geometry.shape(f["geometry"]) for f in features if f["properties"]["kind"] == "branch"]
    return sum(line.length for line in lines) == pytest.approx(sum(b.length for b in ma.branches()))


def _read_svg(path, ma):
    return ET.parse(path).getroot().tag.endswith("svg")


def _read_png(path, ma):
    with Image.open(path) as im:
        return im.format == "PNG" and im.width > 100


def _read_meshio(path, ma):
    m = meshio.read(path)
    return np.array_equal(m.points, _points(ma)) and np.array_equal(np.ravel(m.point_data["radius"]), ma.radii)


def _read_obj(path, ma):  # trimesh keeps the vertices its faces use
    t = trimesh.load(path, process=False, force="mesh")
    used = _points(ma)[np.unique(ma.faces)]
    return len(t.faces) == len(ma.faces) and np.allclose(np.unique(t.vertices, axis=0), np.unique(used, axis=0))


def _read_swc(path, ma):
    rows = np.loadtxt([line for line in path.read_text().splitlines() if not line.startswith("#")], ndmin=2)
    return len(rows) == len(ma.points) and np.allclose(np.sort(rows[:, 5]), np.sort(ma.radii))


def _read_html(path, ma):
    from html.parser import HTMLParser

    tags = []
    parser = HTMLParser()
    parser.handle_starttag = lambda tag, attrs: tags.append(tag)
    parser.feed(path.read_text())
    return "script" in tags


#: An outside reader of each written suffix, and the result it is tried on.
READERS = {
    ".json": (_read_json, CURVE), ".npz": (_read_npz, CURVE), ".graphml": (_read_graphml, CURVE),
    ".geojson": (_read_geojson, CURVE), ".svg": (_read_svg, CURVE), ".png": (_read_png, CURVE),
    ".ply": (_read_meshio, CURVE), ".obj": (_read_obj, None), ".vtk": (_read_meshio, None),
    ".vtu": (_read_meshio, None), ".swc": (_read_swc, CURVE), ".html": (_read_html, CURVE),
}


def test_every_writer_has_an_outside_reader_here():
    assert list(READERS) == list(WRITERS) == list(formats.writer_suffixes())


@pytest.mark.parametrize("suffix", list(READERS))
def test_each_writer_reads_back_through_an_outside_reader(suffix, tmp_path):
    read, ma = READERS[suffix]
    ma = _surface() if ma is None else ma
    path = tmp_path / f"axis{suffix}"
    ma.save(path)
    assert read(path, ma)


def test_vtk_and_vtu_without_meshio_say_what_to_install_before_writing(monkeypatch, tmp_path, capsys):
    square = tmp_path / "square.wkt"
    square.write_text(SQUARE.wkt)
    monkeypatch.setitem(sys.modules, "meshio", None)  # import meshio raises ImportError
    for suffix in (".vtk", ".vtu"):
        with pytest.raises(mx.MissingDependencyError, match=r"pip install medialaxis\[meshio\]"):
            CURVE.save(tmp_path / f"axis{suffix}")
        assert cli.main(["compute", str(square), "-o", str(tmp_path / f"a{suffix}")]) == 2
        assert "medialaxis[meshio]" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["square.wkt"]


def test_stage_files_are_written_by_registered_writers():
    from medialaxis.volume.steps import STEP_SUFFIXES

    assert set(STEP_SUFFIXES) <= set(formats.writer_suffixes())


@pytest.mark.parametrize("dtype", [np.uint8, np.float64, np.float32])
def test_a_two_level_image_is_cut_half_way_between_its_levels(dtype):
    # a GIF's palette reads as a 0/1 float image: Otsu's threshold lands in the histogram bin next to 0 there
    image = (DISK > 0).astype(dtype)
    src = load_planar(image)
    assert src.threshold == 0.5
    assert src.region.area == pytest.approx(np.count_nonzero(DISK), rel=0.01)  # the pixels' area


@pytest.mark.parametrize("fmt", formats.FORMATS, ids=lambda f: f.name)
def test_every_named_reader_and_writer_exists(fmt):
    entries = [*fmt.readers.values(), fmt.block_reader, fmt.writer]
    assert all(callable(formats.entry_point(e)) for e in entries if e is not None)
    assert (fmt.writer is None) == (fmt.holds is None)
