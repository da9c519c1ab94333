"""The compaction works on its points in Z order; the order it works in does not change its result."""

from __future__ import annotations

import numpy as np
import pytest

import medialaxis.mesh.medial.compact as compact
from medialaxis.mesh.voronoi import voronoi_medial_axis

trimesh = pytest.importorskip("trimesh")


@pytest.fixture(scope="module")
def capsule_inputs():
    """The full complex of a capsule and the compaction's arguments, as :func:`voronoi_medial_axis` makes them."""
    seen = {}
    real = compact.compact_medial_axis

    def spy(ma, tolerance, **kwargs):
        seen.update(ma=ma, tolerance=tolerance, signed=kwargs["signed"])
        return real(ma, tolerance, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(compact, "compact_medial_axis", spy)
        voronoi_medial_axis(trimesh.creation.capsule(height=2.0, radius=0.5), samples=2000)
    return seen


@pytest.mark.parametrize("rule", list(compact.RULES))
def test_the_working_order_does_not_change_the_compact_complex(capsule_inputs, rule, monkeypatch):
    ma, tolerance, signed = capsule_inputs["ma"], capsule_inputs["tolerance"], capsule_inputs["signed"]

    def run():
        c = compact.compact_complex(ma.points, ma.radii, ma.faces, ma.edges, ma.extras["contacts"], tolerance, rule=rule,
                                    signed=signed)
        return c.keep, c.faces, c.face_origin, c.edges, c.rounds

    z_order = run()
    assert len(z_order[0]) < len(ma.points) // 4 and z_order[4] > 3  # it compacts, over several rounds
    for order in (lambda p: np.arange(len(p)), lambda p: np.arange(len(p))[::-1].copy()):
        monkeypatch.setattr(compact, "_working_order", order)
        other = run()
        assert all(np.array_equal(a, b) for a, b in zip(z_order[:4], other[:4])) and z_order[4] == other[4]
