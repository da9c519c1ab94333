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


def _launch(tmp_path: Path, writable_tmp: bool) -> tuple[subprocess.Popen, dict[str, Path]]:
    """Start the CLI on a read-only copy, with a home it cannot write and a temporary folder it can or cannot."""
    base = tmp_path / ("writable-tmp" if writable_tmp else "read-only-tmp")
    base.mkdir()
    folders = {name: base / name for name in ("home", "tmp", "out")}
    for folder in folders.values():
        folder.mkdir()
    folders["site"] = _read_only_copy(base)
    folders["home"].chmod(0o555)
    if not writable_tmp:
        folders["tmp"].chmod(0o555)
    # NUMBA_OPT=0: LLVM does not optimise the kernels it compiles (a fifth less CPU). Where numba may cache
    # them (the fallback of medialaxis._jit, at import) and which kernels compile are the same.
    env = {"HOME": str(folders["home"]), "TMPDIR": str(folders["tmp"]), "PYTHONPATH": str(folders["site"]),
           "PATH": os.environ.get("PATH", "/usr/bin"), "NUMBA_OPT": "0"}
    command = [*_unprivileged(), sys.executable, "-m", "medialaxis", "compute", str(SHAPE), "-o",
               str(folders["out"] / "a.json")]
    child = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return child, folders


def test_cli_runs_from_a_read_only_install_without_a_home(tmp_path):
    # Both cases compile every kernel of the image route from scratch (about 30 s each): they run side by side.
    runs = {writable: _launch(tmp_path, writable) for writable in (True, False)}
    try:
        done = {writable: child.communicate(timeout=600) for writable, (child, _) in runs.items()}
    finally:
        for child, folders in runs.values():
            if child.poll() is None:
                child.kill()
                child.wait()
            for path in [folders["site"], *folders["site"].rglob("*"), folders["home"], folders["tmp"]]:
                path.chmod(0o755 if path.is_dir() else 0o644)
    for writable_tmp, (child, folders) in runs.items():
        stderr = done[writable_tmp][1]
        assert child.returncode == 0, (writable_tmp, stderr)
        assert "Traceback" not in stderr
        assert mx.load(folders["out"] / "a.json").n_components == 1
        assert not list((folders["site"] / "medialaxis").rglob("__pycache__/*.nbi"))  # nothing written into the install
        cached = list(folders["tmp"].rglob("*.nbi"))
        assert bool(cached) == writable_tmp  # kernels cached privately when a temporary folder is writable
