"""The package runs for a user who can write neither into it nor into a home folder.

A system-wide install or a read-only container: numba's ``cache=True`` finds
no folder to cache compiled kernels in. Run as root, the child process drops
every capability (``setpriv``), so file permissions bind it as they bind an
ordinary user.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import medialaxis as mx

PACKAGE = Path(mx.__file__).parent
SHAPE = PACKAGE / "data" / "kimia_class1_01.png"


def _unprivileged() -> list[str]:
    if os.geteuid() != 0:
        return []
    setpriv = shutil.which("setpriv")
    if setpriv is None:  # pragma: no cover - util-linux is on every Debian
        pytest.skip("running as root without setpriv: cannot drop the privilege to write anywhere")
    return [setpriv, "--bounding-set=-all", "--inh-caps=-all"]


def _read_only_copy(tmp_path: Path) -> Path:
    root = tmp_path / "site"
    shutil.copytree(PACKAGE, root / "medialaxis", ignore=shutil.ignore_patterns("__pycache__"))
    for path in [root, *root.rglob("*")]:
        path.chmod(0o555 if path.is_dir() else 0o444)
    return root


@pytest.mark.parametrize("writable_tmp", [True, False])
def test_cli_runs_from_a_read_only_install_without_a_home(tmp_path, writable_tmp):
    site = _read_only_copy(tmp_path)
    home = tmp_path / "home"
    tmp = tmp_path / "tmp"
    out = tmp_path / "out"
    for folder in (home, tmp, out):
        folder.mkdir()
    home.chmod(0o555)
    if not writable_tmp:
        tmp.chmod(0o555)
    env = {"HOME": str(home), "TMPDIR": str(tmp), "PYTHONPATH": str(site), "PATH": os.environ.get("PATH", "/usr/bin")}
    try:
        run = subprocess.run(
            [*_unprivileged(), sys.executable, "-m", "medialaxis", "compute", str(SHAPE), "-o", str(out / "a.json")],
            env=env, capture_output=True, text=True, timeout=600,
        )
    finally:
        for path in [site, *site.rglob("*"), home, tmp]:
            path.chmod(0o755 if path.is_dir() else 0o644)
    assert run.returncode == 0, run.stderr
    assert "Traceback" not in run.stderr
    assert mx.load(out / "a.json").n_components == 1
    assert not list((site / "medialaxis").rglob("__pycache__/*.nbi"))  # nothing written into the install
    cached = list(tmp.rglob("*.nbi"))
    assert bool(cached) == writable_tmp  # kernels cached privately when a temporary folder is writable
