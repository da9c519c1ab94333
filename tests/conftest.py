import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import HealthCheck, settings  # noqa: E402

settings.register_profile("ci", max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci")


@pytest.fixture(scope="session")
def kimia_dir():
    from pathlib import Path

    return Path(__file__).resolve().parent / "data" / "kimia99"


@pytest.fixture(scope="session")
def demo_run(tmp_path_factory):
    """``medialaxis demo`` run once (about 20 s): its exit code, printed lines and output folder.

    tests/test_cli.py checks the command; the tests of its tripod and compare cases
    (tests/mesh/test_flow_cli.py, tests/compare/test_cli.py) read their lines and files.
    """
    import contextlib
    import io

    from medialaxis.cli import main

    folder = tmp_path_factory.mktemp("demo") / "demo"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["demo", str(folder)])
    return code, out.getvalue().splitlines(), folder
