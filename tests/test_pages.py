"""3D pages (HTML) and pictures (PNG): light, offline, input shell, spheres, one scale on all axes.

The geometry a page carries is decoded here as a browser would (base64,
zlib, prefix sums) and compared with the result; the pages are opened in
headless Chromium where the machine has one (``scripts/browser.sh``
installs Debian's chromium; ``MEDIALAXIS_BROWSER`` names another binary).
"""

from __future__ import annotations

import base64
import json
import os
import re
import shutil
import subprocess
import zlib

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.core.export import scene3d
from medialaxis.core.export.html import medial_page, write_html

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("plotly")


def _spec(path):
    text = path.read_text()
    match = re.search(r'<script id="medialaxis-data" type="application/json">(.*?)</script>', text, re.S)
    return json.loads(match.group(1).replace("<\\/", "</"))


def _decoded(spec):
    """The page's figure with every blob inflated, as the page's own loader does."""
    kinds = {"f4": np.float32, "i4d": np.int32, "u1": np.uint8}
    arrays = []
    for blob in spec["blobs"]:
        values = np.frombuffer(zlib.decompress(base64.b64decode(blob["data"])), kinds[blob["dtype"]]).astype(np.int64 if blob["dtype"] == "i4d" else float)
        arrays.append(np.cumsum(values) if blob["dtype"] == "i4d" else values)

    def fill(node):
        if isinstance(node, list):
            return [fill(x) for x in node]
        if isinstance(node, dict):
            return arrays[node["__blob"]] if "__blob" in node else {k: fill(v) for k, v in node.items()}
        return node

    return fill(spec["figure"])


def _trace(figure, name):
    found = [t for t in figure["data"] if t.get("name") == name]
    assert found, [t.get("name") for t in figure["data"]]
    return found[0]


def _triangles(trace):
    xyz = np.stack([trace["x"], trace["y"], trace["z"]], axis=1)
    faces = np.stack([trace["i"], trace["j"], trace["k"]], axis=1).astype(int)
    return xyz, faces


def _same_triangles(xyz_a, faces_a, xyz_b, faces_b):
    def key(xyz, faces):
        tri = np.round(xyz[faces].astype(np.float32).astype(float), 5)
        tri = np.sort(tri.reshape(len(faces), 3, 3).view([("", float)] * 3).reshape(len(faces), 3), axis=1)
        return sorted(map(tuple, tri.tolist()))

    return key(xyz_a, faces_a) == key(xyz_b, faces_b)


@pytest.fixture(scope="module")
def box_axis():
    return mx.medial_axis(trimesh.creation.box(extents=(2.0, 1.0, 0.5)), method="voronoi", samples=3000)


def test_page_carries_the_exact_geometry_and_shares_one_library_per_folder(box_axis, tmp_path):
    first = write_html(box_axis, tmp_path / "a.html")
    assert [p.name for p in first] == [f.name for f in sorted(tmp_path.glob("plotly-*.min.js"))] + ["a.html"]
    second = write_html(box_axis, tmp_path / "b.html")
    assert [p.name for p in second] == ["b.html"]  # the library is written once per folder
    text = (tmp_path / "a.html").read_text()
    assert not re.search(r"<script[^>]+src=[\"']?(https?:)?//", text)  # nothing from the network
    assert len(text) < 200_000  # plotly.js is not inlined
    figure = _decoded(_spec(tmp_path / "a.html"))
    medial = _trace(figure, "medial surface")
    xyz, faces = _triangles(medial)
    assert len(faces) == len(box_axis.faces)
    assert _same_triangles(xyz, faces, box_axis.points, box_axis.faces)
    # the colour is the radius of each drawn vertex: compare through the coordinates
    radius_at = {tuple(p.astype(np.float32).tolist()): r for p, r in zip(box_axis.points, box_axis.radii)}
    got = [radius_at[tuple(p.astype(np.float32).tolist())] for p in xyz]
    np.testing.assert_allclose(medial["intensity"], got, rtol=1e-6)
    shell_xyz, shell_faces = _triangles(_trace(figure, "input surface"))
    assert _same_triangles(shell_xyz, shell_faces, np.asarray(box_axis.shape.vertices), np.asarray(box_axis.shape.faces))


def test_a_page_of_100k_faces_stays_under_2_mb(tmp_path):
    torus = trimesh.creation.torus(1.0, 0.35, major_sections=128, minor_sections=48)
    ma = mx.medial_axis(torus, method="voronoi", compact=False)  # the full complex
    assert len(ma.faces) >= 100_000
    write_html(ma, tmp_path / "torus.html")
    size = (tmp_path / "torus.html").stat().st_size
    assert size <= 2_000_000, size
    print(f"{len(ma.faces)} faces: {size / 1e6:.2f} MB")
    xyz, faces = _triangles(_trace(_decoded(_spec(tmp_path / "torus.html")), "medial surface"))
    assert len(faces) == len(ma.faces) and faces.max() < len(xyz)


def test_inline_viewer_is_one_file(box_axis, tmp_path):
    written = write_html(box_axis, tmp_path / "alone.html", viewer="inline")
    assert written == [tmp_path / "alone.html"] and os.listdir(tmp_path) == ["alone.html"]
    assert (tmp_path / "alone.html").stat().st_size > 4_000_000
    with pytest.raises(mx.InvalidInputError, match="viewer"):
        write_html(box_axis, tmp_path / "x.html", viewer="cdn")


def test_equal_scales_and_flat_skeletons_keep_a_visible_box():
    flat = np.array([[0.0, 0, 0], [4, 0, 0], [4, 2, 0]])
    ranges, ratio = scene3d.equal_ranges(flat)
    lengths = ranges[:, 1] - ranges[:, 0]
    assert (lengths > 0).all()
    np.testing.assert_allclose(lengths / lengths.max(), ratio)  # one scale on every axis
    ma = mx.MedialAxis(flat, np.ones(3), np.array([[0, 1], [1, 2]]))
    scene = medial_page(ma).layout["scene"]
    spans = np.array([np.diff(scene[f"{a}axis"]["range"])[0] for a in "xyz"])
    aspect = np.array([scene["aspectratio"][a] for a in "xyz"])
    np.testing.assert_allclose(spans / aspect, spans[0] / aspect[0])
    assert spans[2] > 0


def test_simplified_result_draws_its_spheres_and_says_so(tmp_path):
    box = trimesh.creation.box(extents=(2.0, 1.0, 0.6))
    q = mx.medial_axis(box, method="voronoi", simplify=30)
    write_html(q, tmp_path / "q.html")
    figure = _decoded(_spec(tmp_path / "q.html"))
    title = figure["layout"]["title"]["text"]
    assert title.startswith("simplified medial mesh") and f"{len(q.points)} spheres" in title
    xyz, faces = _triangles(_trace(figure, "medial spheres"))
    assert len(faces) == 80 * len(q.points)
    # every ball vertex lies on its sphere: distance to the nearest centre equals that sphere's radius
    d = np.linalg.norm(xyz[:, None, :] - q.points[None], axis=2) - q.radii[None]
    assert np.abs(d).min(axis=1).max() < 1e-5


def test_volume_results_keep_their_isosurface_as_shell():
    from medialaxis.datasets import t_phantom

    phantom = t_phantom((60, 90, 90), thickness=6, margin=10)
    spacing = (0.5, 0.25, 0.25)
    ma = mx.medial_axis(phantom.volume, method="midsurface", spacing=spacing)
    shell = trimesh.Trimesh(*ma.shape, process=False)
    assert shell.is_watertight
    voxels = (phantom.volume > ma.metadata["iso"]).sum() * np.prod(spacing)
    assert abs(abs(shell.volume) - voxels) < 0.06 * voxels  # the solid's own voxel count, independent of the shell
    page = medial_page(ma)
    assert [t["name"] for t in page.data][:2] == ["input surface", "medial surface"]
    voxels_result = mx.medial_axis(phantom.volume, method="voxels", spacing=spacing)
    assert [t["name"] for t in medial_page(voxels_result).data] == ["input surface", "medial points"]


def test_flow_page_shows_the_input_and_the_frames_have_a_slider(tmp_path):
    from medialaxis.mesh.skeleton.flow_frames import FrameWriter

    capsule = trimesh.creation.capsule(height=2.0, radius=0.5, count=[24, 24])
    sk = mx.medial_axis(capsule, method="flow")
    assert [t["name"] for t in medial_page(sk).data] == ["input surface", "medial curves"]
    writer = FrameWriter(tmp_path)
    mx.medial_axis(capsule, method="flow", callback=writer)
    writer.finish()
    figure = _decoded(_spec(tmp_path / "flow.html"))
    assert len(figure["frames"]) == len(figure["layout"]["sliders"][0]["steps"]) == len(writer.paths)
    frozen = figure["frames"][-1]["data"][0]["marker"]["color"]
    assert frozen.min() == 1  # every vertex skeletal at the end
    assert not re.search(r"<script[^>]+src=[\"']?(https?:)?//", (tmp_path / "flow.html").read_text())


def test_png_uses_one_scale_on_all_axes(box_axis):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from medialaxis.core.export.plot import plot_axis

    fig = plot_axis(box_axis)
    try:
        ax = fig.axes[0]
        spans = np.array([np.diff(ax.get_xlim3d())[0], np.diff(ax.get_ylim3d())[0], np.diff(ax.get_zlim3d())[0]])
        aspect = np.asarray(ax.get_box_aspect())
        np.testing.assert_allclose(spans / spans.max(), aspect / aspect.max(), rtol=1e-6)
    finally:
        plt.close(fig)


# ------------------------------------------------------------------ headless Chromium
def _browser():
    for name in filter(None, [os.environ.get("MEDIALAXIS_BROWSER"), "chromium", "chromium-browser", "google-chrome"]):
        path = shutil.which(name)
        if path:
            return path
    return None


def _render(page, tmp_path, screenshot=True):
    browser = _browser()
    if browser is None:
        pytest.skip("no Chromium here: bash scripts/browser.sh installs Debian's chromium")
    shot = tmp_path / (page.stem + ".png")
    flags = [browser, "--headless", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
             "--enable-unsafe-swiftshader", "--window-size=900,650", "--virtual-time-budget=30000",
             f"--user-data-dir={tmp_path / 'profile'}"]
    url = page.resolve().as_uri()
    dom = subprocess.run([*flags, "--dump-dom", url], capture_output=True, text=True, timeout=180, check=False).stdout
    if screenshot:  # a second launch of the browser
        subprocess.run([*flags, f"--screenshot={shot}", url], capture_output=True, timeout=180, check=False)
    return dom, shot


def _coloured_pixels(png):
    from PIL import Image

    rgb = np.asarray(Image.open(png).convert("RGB"), float)
    plot = rgb[60:, : int(0.85 * rgb.shape[1])]  # below the title and legend, left of the colour bar
    return int(((plot.max(axis=2) - plot.min(axis=2)) > 60).sum())


@pytest.mark.slow
def test_pages_render_in_headless_chromium(box_axis, tmp_path):
    write_html(box_axis, tmp_path / "box.html")
    dom, shot = _render(tmp_path / "box.html", tmp_path)
    assert 'data-rendered="yes"' in dom, dom[-2000:]
    assert _coloured_pixels(shot) > 5000  # the radius-coloured medial sheets are on screen
    moved = tmp_path / "elsewhere"
    moved.mkdir()
    shutil.copy(tmp_path / "box.html", moved / "box.html")  # without its library: says why, not blank
    dom, _ = _render(moved / "box.html", tmp_path, screenshot=False)  # the page's text only
    assert "was not found next to this page" in dom
