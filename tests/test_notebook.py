"""Results in a notebook: ``ma.plot()`` returns its axes, ``_repr_png_`` is a picture, reprs stay short."""

import io

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import shapely  # noqa: E402
import trimesh  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import PathPatch  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402
from PIL import Image  # noqa: E402

import medialaxis as mx  # noqa: E402


@pytest.fixture(scope="module")
def image_axis():
    image = np.zeros((60, 90), bool)
    image[15:45, 10:80] = True
    return mx.medial_axis(image)


@pytest.fixture(scope="module")
def torus_axis():
    return mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow")


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _segments(ax):
    (lines,) = [c for c in ax.collections if isinstance(c, LineCollection)]
    return np.asarray(lines.get_segments())


def test_plot_returns_the_axes_it_drew_the_edges_on(image_axis):
    fig, given = plt.subplots()
    ax = image_axis.plot(ax=given)
    assert ax is given and plt.get_fignums() == [fig.number]  # no other figure
    segments = _segments(ax)
    # an image result is drawn as a picture: x = column, y = row (downwards)
    np.testing.assert_allclose(segments, image_axis.points[image_axis.edges][:, :, ::-1])
    assert ax.yaxis_inverted() and ax.get_aspect() == 1.0
    (region,) = [p for p in ax.patches if isinstance(p, PathPatch)]  # the shape under the axis
    assert shapely.Polygon(region.get_path().vertices[:-1]).area == pytest.approx(image_axis.shape.area, rel=1e-6)
    assert "2 branches" not in ax.get_title() and f"{len(image_axis.branches())} branches" in ax.get_title()


def test_plot_options_and_a_new_figure(image_axis):
    before = set(plt.get_fignums())
    ax = image_axis.plot(shape=False, nodes=False, colorbar=False, title=False, color_by_radius=False)
    assert set(plt.get_fignums()) - before == {ax.figure.number}
    assert not ax.patches and ax.get_title() == "" and len(ax.figure.axes) == 1  # no colour bar
    assert len(ax.collections) == 1 and _segments(ax).shape == (len(image_axis.edges), 2, 2)
    ax.figure.canvas.draw()


def test_plot_of_a_polygon_keeps_its_coordinates():
    polygon = shapely.box(0, 0, 100, 10)
    ma = mx.medial_axis(polygon)
    ax = ma.plot()
    np.testing.assert_allclose(_segments(ax), ma.points[ma.edges])
    assert not ax.yaxis_inverted()


def test_plot_3d_draws_the_curve_in_its_shell(torus_axis):
    ax = torus_axis.plot()
    assert hasattr(ax, "zaxis")
    ax.figure.canvas.draw()  # 3D segments are projected at draw time
    (curve,) = [c for c in ax.collections if isinstance(c, Line3DCollection)]
    assert len(curve.get_segments()) == len(torus_axis.edges)
    (shell,) = [c for c in ax.collections if isinstance(c, Poly3DCollection)]  # the torus, translucent
    assert 0 < shell.get_facecolor()[0][3] < 0.2
    # one scale on all axes, wide enough for the torus (outer radius 2.5)
    spans = [np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())]
    assert min(spans[:2]) >= 5.0


def test_plot_refuses_axes_of_the_wrong_dimension(image_axis, torus_axis):
    fig = plt.figure()
    with pytest.raises(mx.InvalidInputError, match="projection='3d'"):
        torus_axis.plot(ax=fig.add_subplot())
    with pytest.raises(mx.InvalidInputError, match="2D axes"):
        image_axis.plot(ax=fig.add_subplot(projection="3d"))


@pytest.mark.parametrize("which", ["image_axis", "torus_axis"])
def test_repr_png_is_a_picture_and_opens_no_figure(which, request):
    ma = request.getfixturevalue(which)
    before = plt.get_fignums()
    data = ma._repr_png_()
    assert plt.get_fignums() == before  # Jupyter shows it once, pyplot keeps nothing
    picture = Image.open(io.BytesIO(data))
    assert picture.format == "PNG" and 200 < picture.width < 1000 and 200 < picture.height < 1000
    pixels = np.asarray(picture.convert("RGB"), np.int16)
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 20  # drawn in colour, not blank


def test_branch_repr_is_one_short_line(image_axis):
    branch = max(image_axis.branches(), key=lambda b: b.length)
    text = repr(branch)
    assert "\n" not in text and len(text) < 100 and "array" not in text
    assert f"length={branch.length:.4g}" in text and f"points={len(branch.indices)}" in text
    assert text.startswith(f"Branch({branch.indices[0]}->{branch.indices[-1]},")
    long = mx.MedialAxis(np.c_[np.arange(5000.0), np.zeros(5000)], np.ones(5000),
                         np.c_[np.arange(4999), np.arange(1, 5000)]).branches()[0]
    assert len(repr(long)) < 100 and "length=4999" in repr(long)


def test_cycle_branch_repr(torus_axis):
    (loop,) = torus_axis.branches()
    assert repr(loop).startswith("Branch(cycle, ")
    assert repr(torus_axis) == (f"MedialAxis(method='flow', dim=3, points={len(torus_axis.points)}, "
                                f"edges={len(torus_axis.edges)}, faces=0)")


def test_an_svg_drawing_is_drawn_y_down_as_its_png(tmp_path):
    svg = tmp_path / "bar.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="40" viewBox="0 0 100 40">'
                   '<rect x="10" y="5" width="80" height="20" fill="black"/></svg>')
    ma = mx.medial_axis(svg)
    ax = ma.plot()
    assert ax.yaxis_inverted()  # SVG's y points down, as the saved .png shows it
    np.testing.assert_allclose(_segments(ax), ma.points[ma.edges])  # x, y as drawn
