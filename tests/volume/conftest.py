import numpy as np
import pytest

from medialaxis.volume.phantoms import member_phantom, t_phantom, x_phantom


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
