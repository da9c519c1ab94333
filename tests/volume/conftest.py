import numpy as np
import pytest

import medialaxis as mx
from medialaxis.datasets import member_phantom, t_phantom, x_phantom


@pytest.fixture(scope="session")
def small_t():
    return t_phantom((48, 80, 70), margin=8)


@pytest.fixture(scope="session")
def x_part():
    return x_phantom()


@pytest.fixture(scope="session")
def member_part():
    return member_phantom()


@pytest.fixture(scope="session")
def flat_plate():
    vol = np.zeros((20, 44, 40), bool)
    vol[7:13, 6:38, 5:35] = True
    return vol


@pytest.fixture(scope="session")
def small16():
    """A T part as a 16-bit scan (grey 1000 / 3000) for the chunked route's readers and schedulers."""
    return (t_phantom((40, 64, 56), margin=6).volume * 2000 + 1000).astype(np.uint16)


@pytest.fixture(scope="session")
def small_reference(small16):
    """The in-memory route's medial voxels of ``small16``."""
    return mx.medial_axis(small16, method="voxels", chunks=0)


@pytest.fixture(scope="session")
def same_voxels():
    """Check that two medial-voxel results are the same, bit for bit."""

    def check(a, b):
        assert a.points.shape == b.points.shape
        assert np.array_equal(a.points, b.points)
        for key in ("radii", "position", "normal", "voxel_kind"):
            assert np.array_equal(np.asarray(getattr(a, key)), np.asarray(getattr(b, key))), key

    return check
