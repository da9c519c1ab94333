"""The chunked volume route on a cluster of worker processes, and stopped by Ctrl-C in a child process.

Truth is the in-memory route on the same array.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.datasets import ribbed_panel_slab


def test_the_blocks_run_on_a_cluster_of_worker_processes(tmp_path, small16, small_reference, same_voxels):
    distributed = pytest.importorskip("distributed")
    np.save(tmp_path / "scan.npy", small16)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            same_voxels(small_reference, mx.medial_axis(tmp_path / "scan.npy", method="voxels", chunks=24,
                                                         scheduler=client))
            mesh = mx.medial_axis(tmp_path / "scan.npy", chunks=24, scheduler=cluster.scheduler_address)
    assert mesh.n_components == 1


def test_ctrl_c_between_blocks_stops_cleanly_and_writes_nothing(tmp_path):
    import signal
    import time

    np.save(tmp_path / "scan.npy", ribbed_panel_slab((96, 192, 192), 0, 96, levels=(1000, 3000), dtype=np.uint16))
    out = tmp_path / "mid.ply"
    proc = subprocess.Popen([sys.executable, "-m", "medialaxis", "compute", str(tmp_path / "scan.npy"), "--chunks", "16",
                             "--jobs", "2", "-o", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4.0)  # imported, reading blocks (the run takes far longer with blocks this small)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert err == "medialaxis: interrupted\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scan.npy"]
