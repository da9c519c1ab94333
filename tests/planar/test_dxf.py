"""The DXF reader: CAD-drawn parts against their exact areas and axes, blocks, hatches, layers, and every failure.

Drawings are written with ezdxf into ``tmp_path`` the way CAD tools write
them (a slot as two LINEs and two ARCs in any order and direction, bulges for
fillets); the real files of ``tests/data/dxf/`` come from the ezdxf
repository (see ``tests/data/README.md``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from shapely.geometry import Point, box

from medialaxis.errors import (
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    MedialAxisError,
    MissingDependencyError,
    UnsupportedFeatureError,
)
from medialaxis.planar.drawings.dxf import read_dxf
from medialaxis.planar.pipeline import voronoi_medial_axis

ezdxf = pytest.importorskip("ezdxf")

DATA = Path(__file__).resolve().parents[1] / "data" / "dxf"
#: Bulge of a quarter circle: tan(90 degrees / 4).
QUARTER = math.tan(math.pi / 8)


def new_drawing():
    doc = ezdxf.new("R2010")
    return doc, doc.modelspace()


def save(doc, tmp_path: Path, name: str = "drawing.dxf") -> Path:
    path = tmp_path / name
    doc.saveas(path)
    return path


def slot_entities(msp, centre_a, centre_b, radius, *, layer="0"):
    """A stadium between two arc centres on a horizontal line: two LINEs and two ARCs, shuffled and reversed."""
    (xa, y), (xb, _) = centre_a, centre_b
    attribs = {"layer": layer}
    msp.add_line((xb, y + radius), (xa, y + radius), dxfattribs=attribs)  # top, right to left
    msp.add_arc((xa, y), radius, 90, 270, dxfattribs=attribs)  # left end, counter-clockwise
    msp.add_line((xa, y - radius), (xb, y - radius), dxfattribs=attribs)  # bottom, left to right
    msp.add_arc((xb, y), radius, -90, 90, dxfattribs=attribs)  # right end


def plate_outline(msp, width, height, fillet, *, layer="0"):
    """A width x height plate with four filleted corners: one closed LWPOLYLINE with bulges."""
    w, h, r = width, height, fillet
    points = [
        (r, 0, 0),
        (w - r, 0, QUARTER),
        (w, r, 0),
        (w, h - r, QUARTER),
        (w - r, h, 0),
        (r, h, QUARTER),
        (0, h - r, 0),
        (0, r, QUARTER),
    ]
    msp.add_lwpolyline(points, format="xyb", close=True, dxfattribs={"layer": layer})


def holes(region) -> int:
    return sum(len(p.interiors) for p in shapely.get_parts(region))


# 1. A plate with filleted corners, a round hole and a slot -------------------------------------------


def test_plate_with_fillets_hole_and_slot(tmp_path):
    width, height, fillet = 160.0, 60.0, 10.0
    hole_centre, hole_radius = (25.0, 30.0), 8.0
    slot_a, slot_b, slot_radius = (50.0, 30.0), (70.0, 30.0), 6.0
    doc, msp = new_drawing()
    slot_entities(msp, slot_a, slot_b, slot_radius)
    msp.add_circle(hole_centre, hole_radius)
    plate_outline(msp, width, height, fillet)
    region, info = read_dxf(save(doc, tmp_path))

    exact = (
        width * height
        - (4 - math.pi) * fillet**2
        - math.pi * hole_radius**2
        - (2 * slot_radius * (slot_b[0] - slot_a[0]) + math.pi * slot_radius**2)
    )
    perimeter = (
        2 * (width + height) - (8 - 2 * math.pi) * fillet
        + 2 * math.pi * hole_radius
        + 2 * (slot_b[0] - slot_a[0]) + 2 * math.pi * slot_radius
    )
    chord = 1e-4 * width
    assert info["tolerance"] == pytest.approx(chord)
    assert abs(region.area - exact) <= chord * perimeter
    assert region.is_valid and region.geom_type == "Polygon"
    assert holes(region) == 2
    assert info["loops"] == 3 and info["skipped"] == {} and info["layers"] == ["0"]
    # The largest inscribed circle touches the top and bottom right of the slot:
    # radius height / 2 (its centre anywhere with x in [106, 130]).
    circle = shapely.maximum_inscribed_circle(region, tolerance=1e-3)
    assert circle.length == pytest.approx(height / 2, abs=2e-3)
    centre = np.asarray(circle.coords[0])
    assert 106 - 1e-2 <= centre[0] <= 130 + 1e-2 and centre[1] == pytest.approx(30, abs=2e-2)


# 2. An ellipse: area and the axis between the centres of curvature ------------------------------


def test_ellipse_area_and_axis_ends_at_centres_of_curvature(tmp_path):
    a, b = 4.0, 2.0
    doc, msp = new_drawing()
    msp.add_ellipse((0, 0), major_axis=(a, 0), ratio=b / a)
    region, info = read_dxf(save(doc, tmp_path))
    chord = 1e-4 * 2 * a
    assert info["tolerance"] == pytest.approx(chord)
    perimeter = math.pi * (3 * (a + b) - math.sqrt((3 * a + b) * (a + 3 * b)))  # Ramanujan
    assert abs(region.area - math.pi * a * b) <= chord * perimeter

    ma = voronoi_medial_axis(region)
    xs, ys = np.abs(ma.points[:, 0]), np.abs(ma.points[:, 1])
    end = a - b**2 / a  # the centre of curvature of the ellipse's ends
    # The bounds asked for; reached: max |x| = 2.99413, 7.3e-4 * (2 a) short of a - b^2 / a.
    assert end - 1e-2 * (2 * a) <= xs.max() <= end + 1e-3 * (2 * a)
    assert ys.max() <= 1e-4 * (2 * a)  # on the major axis
    assert len(ma.endpoints) == 2


# 3. A slot alone: the axis is the segment between the arc centres ---------------------------------


def test_slot_axis_is_the_segment_between_arc_centres(tmp_path):
    doc, msp = new_drawing()
    slot_entities(msp, (-10.0, 5.0), (10.0, 5.0), 4.0)
    region, info = read_dxf(save(doc, tmp_path))
    size = 28.0
    assert info["loops"] == 1
    ma = voronoi_medial_axis(region)
    assert len(ma.endpoints) == 2 and len(ma.junctions) == 0
    ends = ma.points[ma.endpoints]
    ends = ends[np.argsort(ends[:, 0])]
    assert np.abs(ends - [[-10.0, 5.0], [10.0, 5.0]]).max() <= 1e-3 * size
    assert np.abs(ma.points[:, 1] - 5.0).max() <= 1e-3 * size
    assert np.abs(ma.radii - 4.0).max() <= 1e-3 * size


# 4. A filleted corner: the axis runs along the bisector to the fillet's centre ------------------


def test_fillet_axis_meets_the_corner_bisector_at_the_fillet_centre(tmp_path):
    side, fillet = 10.0, 3.0
    doc, msp = new_drawing()
    # A square whose corner (10, 10) is filleted: three LINEs, two half-sides and an ARC.
    msp.add_line((0, 0), (side, 0))
    msp.add_line((side, side - fillet), (side, 0))
    msp.add_arc((side - fillet, side - fillet), fillet, 0, 90)
    msp.add_line((side - fillet, side), (0, side))
    msp.add_line((0, side), (0, 0))
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(side**2 - (4 - math.pi) / 4 * fillet**2, abs=1e-3 * 4 * side)
    ma = voronoi_medial_axis(region)
    on_bisector = np.abs(ma.points[:, 0] - ma.points[:, 1]) <= 1e-3 * side
    assert on_bisector.sum() >= 2
    # The branch into the filleted corner ends at the fillet's centre, with the fillet's radius.
    tip = ma.points[on_bisector].sum(1).argmax()
    tip_point, tip_radius = ma.points[on_bisector][tip], ma.radii[on_bisector][tip]
    assert np.abs(tip_point - (side - fillet)).max() <= 1e-3 * side
    assert tip_radius == pytest.approx(fillet, abs=1e-3 * side)


# 5. Layers, units, blocks, hatches, open drawings, skipped entities, bad files -------------------


def test_layers_pick_only_the_named_layer(tmp_path):
    doc, msp = new_drawing()
    doc.layers.add("CUT")
    doc.layers.add("ENGRAVE")
    msp.add_lwpolyline([(0, 0), (4, 0), (4, 3), (0, 3)], close=True, dxfattribs={"layer": "CUT"})
    msp.add_circle((10, 10), 5, dxfattribs={"layer": "ENGRAVE"})
    path = save(doc, tmp_path)
    region, info = read_dxf(path, layers=["CUT"])
    assert region.area == pytest.approx(12.0) and info["layers"] == ["CUT"]
    region, _ = read_dxf(path, layers=["cut"])  # CAD layer names are case-insensitive
    assert region.area == pytest.approx(12.0)
    region, info = read_dxf(path)
    assert info["layers"] == ["CUT", "ENGRAVE"] and region.area > 12.0


def test_unknown_layer_lists_the_drawing_layers(tmp_path):
    doc, msp = new_drawing()
    doc.layers.add("CUT")
    msp.add_circle((0, 0), 1, dxfattribs={"layer": "CUT"})
    with pytest.raises(InvalidInputError, match="no layer 'MILL'") as err:
        read_dxf(save(doc, tmp_path), layers=["MILL"])
    assert "'CUT'" in str(err.value) and "'0'" in str(err.value)


def test_layers_off_or_frozen_are_skipped_unless_named(tmp_path):
    doc, msp = new_drawing()
    doc.layers.add("HIDDEN").off()
    doc.layers.add("COLD").freeze()
    msp.add_circle((0, 0), 1)
    msp.add_circle((10, 0), 2, dxfattribs={"layer": "HIDDEN"})
    msp.add_circle((20, 0), 3, dxfattribs={"layer": "COLD"})
    path = save(doc, tmp_path)
    region, info = read_dxf(path)
    assert region.area == pytest.approx(math.pi, rel=1e-3) and info["hidden"] == 2
    region, _ = read_dxf(path, layers=["HIDDEN", "COLD"])
    assert region.area == pytest.approx(13 * math.pi, rel=1e-3)


@pytest.mark.parametrize(("code", "units"), [(4, "mm"), (1, "in"), (6, "m"), (0, None)])
def test_units_from_insunits(tmp_path, code, units):
    doc, msp = new_drawing()
    doc.header["$INSUNITS"] = code
    msp.add_circle((0, 0), 1)
    _, info = read_dxf(save(doc, tmp_path))
    assert info["units"] == units and info["format"] == "dxf"


def d_block(doc, name="D"):
    """A 'D': the rectangle [0, 3] x [0, 2] whose left side bulges out as a half circle of radius 1."""
    block = doc.blocks.new(name)
    block.add_lwpolyline([(0, 0, 0), (3, 0, 0), (3, 2, 0), (0, 2, 1.0)], format="xyb", close=True)
    return block


def test_insert_scaled_rotated_and_mirrored(tmp_path):
    doc, msp = new_drawing()
    d_block(doc)
    # (x, y) -> 2 * (-y, x) + (10, 0): the rectangle to [6, 10] x [0, 6], the half disc below y = 0.
    msp.add_blockref("D", (10, 0), dxfattribs={"xscale": 2, "yscale": 2, "rotation": 90})
    # (x, y) -> (20 - x, y): the rectangle to [17, 20] x [0, 2], the half disc right of x = 20.
    msp.add_blockref("D", (20, 0), dxfattribs={"xscale": -1})
    region, info = read_dxf(save(doc, tmp_path))
    rotated = box(6, 0, 10, 6).union(Point(8, 0).buffer(2, 256).intersection(box(0, -3, 20, 0)))
    mirrored = box(17, 0, 20, 2).union(Point(20, 1).buffer(1, 256).intersection(box(20, -1, 22, 3)))
    expected = rotated.union(mirrored)
    chord = info["tolerance"]
    assert region.area == pytest.approx(expected.area, abs=chord * expected.length)
    assert region.symmetric_difference(expected).area <= 2 * chord * expected.length
    assert region.geom_type == "MultiPolygon" and len(region.geoms) == 2


def test_insert_block_entities_on_layer_0_take_the_insert_layer(tmp_path):
    doc, msp = new_drawing()
    doc.layers.add("CUT")
    d_block(doc)
    msp.add_blockref("D", (0, 0), dxfattribs={"layer": "CUT"})
    msp.add_circle((50, 0), 1)
    region, info = read_dxf(save(doc, tmp_path), layers=["CUT"])
    assert region.area == pytest.approx(6 + math.pi / 2, rel=1e-3) and info["layers"] == ["CUT"]


def test_insert_non_uniform_scale_grid_and_nesting(tmp_path):
    doc, msp = new_drawing()
    disc = doc.blocks.new("DISC")
    disc.add_circle((0, 0), 1)
    pair = doc.blocks.new("PAIR")  # a block of two scaled DISCs: nested inserts
    pair.add_blockref("DISC", (0, 0), dxfattribs={"xscale": 2, "yscale": 1})  # an ellipse 2 x 1
    pair.add_blockref("DISC", (10, 0))
    msp.add_blockref("PAIR", (0, 0))
    grid = msp.add_blockref("DISC", (0, 20))
    grid.grid(size=(2, 3), spacing=(5, 5))  # MINSERT: 2 rows, 3 columns
    region, info = read_dxf(save(doc, tmp_path))
    assert len(region.geoms) == 8 and info["loops"] == 8
    perimeter = 9.6884 + 7 * 2 * math.pi  # the ellipse's and seven circles'
    assert abs(region.area - 9 * math.pi) <= info["tolerance"] * perimeter


def test_old_style_polyline_with_bulges(tmp_path):
    doc = ezdxf.new("R12")
    doc.modelspace().add_polyline2d([(0, 0, 0), (3, 0, 0), (3, 2, 0), (0, 2, 1.0)], format="xyb", close=True)
    region, _ = read_dxf(save(doc, tmp_path))
    assert abs(region.area - (6 + math.pi / 2)) <= 4e-4 * (8 + math.pi)  # chord tolerance times perimeter


@pytest.mark.parametrize(("style", "area"), [(0, 100 - 16), (1, 100 - 16), (2, 100)])
def test_hatch_style_decides_the_islands(tmp_path, style, area):
    doc, msp = new_drawing()
    hatch = msp.add_hatch(dxfattribs={"hatch_style": style})
    hatch.paths.add_polyline_path([(0, 0), (10, 0), (10, 10), (0, 10)], is_closed=True, flags=1)  # external
    hatch.paths.add_polyline_path([(3, 3), (7, 3), (7, 7), (3, 7)], is_closed=True, flags=16)  # outermost
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(area)


def test_hatch_with_a_hole(tmp_path):
    doc, msp = new_drawing()
    hatch = msp.add_hatch()
    hatch.paths.add_polyline_path([(0, 0), (10, 0), (10, 10), (0, 10)], is_closed=True, flags=1)
    hole = hatch.paths.add_edge_path(flags=16)
    hole.add_arc((5, 5), 2, 0, 360)
    region, info = read_dxf(save(doc, tmp_path))
    assert holes(region) == 1 and info["loops"] == 2
    assert abs(region.area - (100 - 4 * math.pi)) <= info["tolerance"] * (40 + 4 * math.pi)


def test_hatch_over_its_own_outline_counts_once(tmp_path):
    doc, msp = new_drawing()
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], close=True)
    hatch = msp.add_hatch()
    hatch.paths.add_polyline_path([(0, 0), (10, 0), (10, 10), (0, 10)], is_closed=True, flags=1)
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(100.0)


def test_open_chain_names_the_gap(tmp_path):
    doc, msp = new_drawing()
    msp.add_line((0, 0), (10, 0))
    msp.add_line((10, 0), (10, 10))
    msp.add_line((10, 10), (0, 10))
    msp.add_line((0, 10), (0, 0.5))  # stops 0.5 short of the start
    with pytest.raises(InvalidInputError, match="not closed") as err:
        read_dxf(save(doc, tmp_path))
    message = str(err.value)
    assert "gap of 0.5 between" in message
    assert "(0, 0.5)" in message and "(0, 0)" in message
    # A tolerance above the gap closes it (and coarsens the curves).
    region, info = read_dxf(tmp_path / "drawing.dxf", tolerance=0.6)
    assert region.area == pytest.approx(100.0) and info["join_tolerance"] == 0.6


def test_a_line_ending_on_another_is_named(tmp_path):
    doc, msp = new_drawing()
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], close=True)
    msp.add_line((5, 0), (5, 10))  # a bend line across the plate: it meets the outline mid-edge
    with pytest.raises(InvalidInputError, match="both ends of one curve are loose") as err:
        read_dxf(save(doc, tmp_path))
    assert "(5, 0)" in str(err.value) and "(5, 10)" in str(err.value)
    assert "curves must meet end to end" not in str(err.value)  # the outline is a loop, not a curve to meet
    doc, msp = new_drawing()
    for start, end in (((0, 0), (10, 0)), ((10, 0), (10, 10)), ((10, 10), (0, 10)), ((0, 10), (0, 0))):
        msp.add_line(start, end)
    msp.add_line((5, 0), (5, 10))
    with pytest.raises(InvalidInputError, match="ends on LINE .* curves must meet end to end"):
        read_dxf(save(doc, tmp_path))


def test_text_and_dimensions_are_skipped_and_counted(tmp_path):
    doc, msp = new_drawing()
    msp.add_circle((0, 0), 1)
    for k in range(3):
        msp.add_text(f"label {k}").set_placement((k, 2))
    msp.add_point((5, 5))
    msp.add_mtext("note").set_location((0, -3))
    _, info = read_dxf(save(doc, tmp_path))
    assert info["skipped"] == {"MTEXT": 1, "POINT": 1, "TEXT": 3}


def test_text_only_is_empty(tmp_path):
    doc, msp = new_drawing()
    msp.add_text("nothing to cut")
    with pytest.raises(EmptyShapeError, match="skipped 1 TEXT"):
        read_dxf(save(doc, tmp_path))


def test_not_a_dxf_and_truncated_dxf(tmp_path):
    (tmp_path / "notes.dxf").write_text("these are not the drawings you are looking for\n")
    with pytest.raises(InputFileError, match="cannot read"):
        read_dxf(tmp_path / "notes.dxf")
    doc, msp = new_drawing()
    msp.add_circle((0, 0), 1)
    data = save(doc, tmp_path).read_bytes()
    for cut in (len(data) // 4, len(data) // 2, len(data) - 5):
        (tmp_path / "cut.dxf").write_bytes(data[:cut])
        with pytest.raises(InputFileError):
            read_dxf(tmp_path / "cut.dxf")
    with pytest.raises(InputFileError):
        read_dxf(tmp_path / "missing.dxf")


def test_missing_ezdxf(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)  # import ezdxf now raises ImportError
    with pytest.raises(MissingDependencyError, match="ezdxf"):
        read_dxf(tmp_path / "any.dxf")


# More: OCS, tilted planes, solids, duplicates, adjacent outlines ----------------------------------


def test_extrusion_is_mapped_to_wcs(tmp_path):
    doc, msp = new_drawing()
    # OCS with extrusion (0, 0, -1): OCS x runs along WCS -x, so the centre (5, 5) is at WCS (-5, 5).
    msp.add_circle((5, 5), 1, dxfattribs={"extrusion": (0, 0, -1)})
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.centroid.x == pytest.approx(-5) and region.centroid.y == pytest.approx(5)


def test_elevation_is_projected_but_a_tilted_entity_is_refused(tmp_path):
    doc, msp = new_drawing()
    msp.add_circle((0, 0, 7), 1)  # parallel to xy, at z = 7
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(math.pi, rel=1e-3)
    msp.add_circle((0, 0), 1, dxfattribs={"extrusion": (1, 0, 0)})  # in the yz plane
    with pytest.raises(UnsupportedFeatureError, match="CIRCLE .* not parallel to the xy plane"):
        read_dxf(save(doc, tmp_path))


def test_acis_solid_is_refused_by_name_and_avoided_by_layers(tmp_path):
    doc = ezdxf.new("R2000")  # ACIS as SAT text
    msp = doc.modelspace()
    doc.layers.add("3D")
    msp.add_circle((0, 0), 1)
    solid = msp.add_3dsolid(dxfattribs={"layer": "3D"})
    # An empty ACIS body: ezdxf writes no 3DSOLID without ACIS data.
    solid.sat = ["400 0 1 0", "@3 odd @12 ACIS 4.0 NT @24 Thu Jan 01 00:00:00 2020", "1 1e-06 1e-10", "End-of-ACIS-data"]
    path = save(doc, tmp_path)
    with pytest.raises(UnsupportedFeatureError, match="3DSOLID .*layer '3D'"):
        read_dxf(path)
    region, _ = read_dxf(path, layers=["0"])
    assert region.area == pytest.approx(math.pi, rel=1e-3)


def test_a_hole_drawn_twice_stays_a_hole(tmp_path):
    doc, msp = new_drawing()
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], close=True)
    msp.add_circle((5, 5), 2)
    msp.add_circle((5, 5), 2)  # the same hole on top of itself (even-odd would erase it)
    msp.add_line((0, 0), (10, 0))  # a LINE over the polyline's edge
    region, info = read_dxf(save(doc, tmp_path))
    assert holes(region) == 1 and info["duplicates"] == 2


def test_squares_sharing_an_edge_fill_their_union(tmp_path):
    doc, msp = new_drawing()
    # Two unit squares side by side, each drawn as four LINEs: their common edge is drawn twice.
    for x0 in (0, 1):
        corners = [(x0, 0), (x0 + 1, 0), (x0 + 1, 1), (x0, 1)]
        for k in range(4):
            msp.add_line(corners[k], corners[(k + 1) % 4])
    # A closed polyline and a copy of it as four LINEs, one of them drawn twice.
    msp.add_lwpolyline([(5, 0), (6, 0), (6, 1), (5, 1)], close=True)
    for k, (start, end) in enumerate(zip([(5, 0), (6, 0), (6, 1), (5, 1)], [(6, 0), (6, 1), (5, 1), (5, 0)])):
        msp.add_line(*((start, end) if k % 2 else (end, start)))  # every other one reversed
    msp.add_line((5, 0), (6, 0))
    region, info = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(3.0) and len(region.geoms) == 2 and info["duplicates"] == 2


def test_lines_meeting_at_a_vertex_shared_by_two_squares(tmp_path):
    doc, msp = new_drawing()
    # Two squares touching at the corner (1, 1), drawn as eight LINEs: four curve ends meet there.
    for x0, y0 in ((0, 0), (1, 1)):
        corners = [(x0, y0), (x0 + 1, y0), (x0 + 1, y0 + 1), (x0, y0 + 1)]
        for k in range(4):
            msp.add_line(corners[k], corners[(k + 1) % 4])
    region, _ = read_dxf(save(doc, tmp_path))
    assert region.area == pytest.approx(2.0) and region.geom_type == "MultiPolygon"


def test_bad_tolerance_and_empty_layers(tmp_path):
    doc, msp = new_drawing()
    msp.add_circle((0, 0), 1)
    path = save(doc, tmp_path)
    with pytest.raises(InvalidInputError, match="tolerance"):
        read_dxf(path, tolerance=0)
    with pytest.raises(InvalidInputError):
        read_dxf(path, layers=[])


def test_spline_and_elliptic_arc_chain(tmp_path):
    doc, msp = new_drawing()
    # Lower half: an elliptic arc from (4, 0) to (-4, 0) through (0, -2); upper half: a spline closing it.
    msp.add_ellipse((0, 0), major_axis=(4, 0), ratio=0.5, start_param=math.pi, end_param=2 * math.pi)
    msp.add_spline([(4, 0), (2, 1), (0, 1.5), (-2, 1), (-4, 0)])
    region, info = read_dxf(save(doc, tmp_path))
    assert info["loops"] == 1 and region.is_valid and 4 * math.pi < region.area < 4 * math.pi + 8 * 1.5


# 6. Real CAD files from the ezdxf repository ---------------------------------------------------------

REAL_FILES = {
    # file: the area of the region, or the error it must raise
    "hatch_issues.dxf": 150.78,  # exactly 48 pi = 150.796: the chords (tolerance 1.8e-3) cut 0.017
    "circle_radius_le_0.dxf": 3.14076,
    "R12_with_trash_beyond_EOF.dxf": 7.06672,
    "no_layouts.dxf": 178.328,
    "bin_dxf_r12.dxf": InvalidInputError,
}


@pytest.mark.parametrize("name", sorted(REAL_FILES))
def test_real_ezdxf_files(name):
    expected = REAL_FILES[name]
    try:
        region, info = read_dxf(DATA / name)
    except MedialAxisError as exc:
        assert isinstance(expected, type) and isinstance(exc, expected), f"{name}: {exc!r}"
        return
    assert not isinstance(expected, type), f"{name} should raise {expected}"
    assert region.is_valid and region.area == pytest.approx(expected, rel=1e-4)
    assert info["format"] == "dxf"
