"""Method options as frozen dataclasses: one source for the keywords, the docstrings, the flags and docs/options.md."""

from __future__ import annotations

import dataclasses
import inspect
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import Polygon, box

import medialaxis as mx
from medialaxis import _dispatch
from medialaxis.cli import build_parser
from medialaxis.cli.compute import compute_options, options_markdown
from medialaxis.errors import InvalidInputError
from medialaxis.planar.options import PlanarOptions
from medialaxis.planar.pipeline import voronoi_medial_axis as planar_axis
from medialaxis.volume.options import MidsurfaceOptions, VoxelOptions

DOCS = Path(__file__).resolve().parents[1] / "docs" / "options.md"
KEYS = sorted(_dispatch.OPTIONS)


def test_docs_options_md_is_generated_from_the_dataclasses():
    assert DOCS.read_text() == options_markdown(), "regenerate: python -m medialaxis.cli.compute > docs/options.md"


@pytest.mark.parametrize("key", KEYS, ids=" ".join)
def test_each_method_takes_exactly_its_dataclass_options(key):
    domain, method = key
    _, fn = _dispatch.resolve(domain, method)
    cls = _dispatch.option_types()[key]
    assert fn.options_type is cls
    params = inspect.signature(fn).parameters
    fields = [f.name for f in dataclasses.fields(cls)]
    options = [n for n, p in params.items() if p.kind is inspect.Parameter.KEYWORD_ONLY and n != "callback"]
    assert options == fields
    assert all(params[f.name].default is f.default or params[f.name].default == f.default
               for f in dataclasses.fields(cls))
    for name in fields:  # each option is documented in the method's docstring, as numpydoc
        assert f"\n    {name} : " in fn.__doc__
    assert "{options}" not in fn.__doc__


def test_options_are_frozen_and_checked():
    opts = PlanarOptions(tolerance=0.01)
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.tolerance = 0.1  # type: ignore[misc]
    with pytest.raises(InvalidInputError, match="boundary must be one of 'contour', 'canny'"):
        PlanarOptions(boundary="sobel")
    assert MidsurfaceOptions(extend=False).changed() == {"extend": False}
    assert issubclass(MidsurfaceOptions, VoxelOptions)  # the voxel options are the mid-surface's too


def test_a_dataclass_keywords_and_a_mapping_give_the_same_axis():
    shape = Polygon([(0, 0), (6, 0), (6, 1), (1, 1), (1, 4), (0, 4)])  # an L
    by_keywords = planar_axis(shape, tolerance=0.01, detour=0.1)
    by_options = planar_axis(shape, PlanarOptions(tolerance=0.01, detour=0.1))
    by_mapping = mx.medial_axis(shape, options={"tolerance": 0.01, "detour": 0.1})
    for ma in (by_options, by_mapping):
        assert np.array_equal(ma.points, by_keywords.points) and np.array_equal(ma.edges, by_keywords.edges)
    # keywords override the dataclass's fields
    overridden = planar_axis(shape, PlanarOptions(tolerance=0.5, detour=0.1), tolerance=0.01)
    assert overridden.metadata["tolerance"] == by_keywords.metadata["tolerance"] == 0.01


def test_another_methods_options_give_what_they_set():
    plate = np.zeros((16, 24, 24), bool)
    plate[6:10, 4:20, 4:20] = True
    voxel_options = VoxelOptions(lam=2.0)
    assert mx.medial_axis(plate, method="midsurface", options=voxel_options).metadata["lam"] == 2.0
    with pytest.raises(InvalidInputError, match="unknown option\\(s\\) 'extend'"):
        mx.medial_axis(plate, method="voxels", options=MidsurfaceOptions(extend=False))


def test_an_unknown_option_names_the_accepted_ones():
    with pytest.raises(InvalidInputError, match=r"unknown option\(s\) 'tolerence'.* tolerance"):
        planar_axis(box(0, 0, 4, 2), tolerence=0.1)
    with pytest.raises(InvalidInputError, match="must be a PlanarOptions or a mapping"):
        planar_axis(box(0, 0, 4, 2), 0.1)


def test_flags_become_the_option_values_the_methods_take():
    args = build_parser().parse_args([
        "compute", "in.nrrd", "--thickness", "2", "6", "--chunks", "64", "--jobs", "3", "--spacing", "0.5", "0.5",
        "1", "--lam", "1.5", "--threshold", "100", "--no-extend", "--seed", "7", "--raw-shape", "4", "5", "6"])
    options, spacing = compute_options(args)
    assert spacing == (0.5, 0.5, 1.0)
    assert options == {"thickness": (2.0, 6.0), "chunks": 64, "n_jobs": 3, "lam": 1.5, "threshold": 100.0,
                       "extend": False, "rng": 7, "raw_shape": (4, 5, 6)}
    MidsurfaceOptions(**options)  # every value is one the mid-surface accepts
    args = build_parser().parse_args(["compute", "in.stl", "--full", "--repair", "--simplify", "50",
                                      "--topology", "lambda", "--fixed-points", "3", "9"])
    options, spacing = compute_options(args)
    assert spacing is None
    assert options == {"compact": False, "repair": True, "simplify": 50, "topology": "lambda", "fixed_points": (3, 9)}
    args = build_parser().parse_args(["compute", "in.svg", "--fills-only", "--layers", "A", "B"])
    assert compute_options(args)[0] == {"strokes": False, "layers": ("A", "B")}


@pytest.mark.parametrize("argv, message", [
    (["--thickness", "1", "2", "3"], "--thickness takes 1 or 2 values, got 3"),
    (["--chunks", "8", "8"], "--chunks takes 1 or 3 values, got 2"),
    (["--jobs", "0"], "--jobs must be at least 1"),
])
def test_bad_flag_values_are_usage_errors(argv, message):
    from medialaxis._help import UsageError

    args = build_parser().parse_args(["compute", "in.nrrd", *argv])
    with pytest.raises(UsageError, match=message):
        compute_options(args)


def test_every_flag_is_in_compute_help(capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args(["compute", "--help"])
    text = capsys.readouterr().out
    for key, cls in _dispatch.option_types().items():
        for field in dataclasses.fields(cls):
            flag = field.metadata["flag"]
            if flag is not None:
                assert (flag.name or "--" + field.name.replace("_", "-")) in text, (key, field.name)
