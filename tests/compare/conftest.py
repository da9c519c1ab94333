import numpy as np
import pytest


@pytest.fixture(scope="session")
def kimia_files(kimia_dir):
    files = sorted(kimia_dir.glob("class*_*.png"))
    assert len(files) == 99
    return files


@pytest.fixture(scope="session")
def kimia_labels(kimia_files):
    return np.array([int(p.stem.split("_")[0][5:]) for p in kimia_files])


@pytest.fixture(scope="session")
def kimia_signatures(kimia_files):
    from medialaxis.compare import shape_signature

    return [shape_signature(str(p)) for p in kimia_files]


@pytest.fixture(scope="session")
def kimia_matrix(kimia_signatures):
    import medialaxis as mx

    return mx.distance_matrix(kimia_signatures)
