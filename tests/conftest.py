import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import HealthCheck, settings  # noqa: E402

settings.register_profile("ci", max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci")


@pytest.fixture
def kimia_dir():
    from pathlib import Path

    here = Path(__file__).resolve().parents[1]
    for cand in (here / ".." / "shared" / "data" / "kimia99", here / "tests" / "data" / "kimia99"):
        if cand.is_dir():
            return cand.resolve()
    pytest.skip("Kimia-99 data not found")
