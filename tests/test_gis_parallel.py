"""Features in parallel: worker processes, threads, Dask (a cluster, a dask GeoDataFrame), progress, Ctrl-C.

The truth is the layer computed feature by feature in this process: where
a feature runs must not change its line or its widths.
"""

import _thread
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import medialaxis as mx

gpd = pytest.importorskip("geopandas")
psutil = pytest.importorskip("psutil")

LAKES = Path(__file__).parent / "data" / "osm_lakes.geojson"


@pytest.fixture(scope="module")
def lakes():
    layer = gpd.read_file(LAKES).to_crs("EPSG:3857").iloc[:12]  # 12 OpenStreetMap lakes
    return layer.set_index(layer.index * 10 + 5)  # an index that is not 0, 1, ...


@pytest.fixture(scope="module")
def serial(lakes):
    return mx.centerlines(lakes)


def same(out, serial):
    assert list(out.index) == list(serial.index) and out.crs == serial.crs
    assert list(out.columns) == list(serial.columns)
    assert (out["islands"] == serial["islands"]).all()
    for name in mx.gis.WIDTH_COLUMNS:
        np.testing.assert_array_equal(out[name].to_numpy(), serial[name].to_numpy())
    assert all(a.equals_exact(b, 0.0) for a, b in zip(out.geometry, serial.geometry))


@pytest.mark.parametrize("scheduler", [None, "processes", "threads", "synchronous"])
def test_the_same_layer_on_threads_processes_and_in_order(lakes, serial, scheduler):
    same(mx.centerlines(lakes, n_jobs=2, scheduler=scheduler), serial)


def test_a_dask_cluster_and_a_dask_geodataframe(lakes, serial):
    dask_geopandas = pytest.importorskip("dask_geopandas")
    distributed = pytest.importorskip("distributed")
    lazy = mx.centerlines(dask_geopandas.from_geopandas(lakes, npartitions=3))
    assert isinstance(lazy, dask_geopandas.GeoDataFrame) and lazy.npartitions == 3
    same(lazy.compute(scheduler="synchronous"), serial)
    with distributed.Client(processes=False, n_workers=2, threads_per_worker=1, dashboard_address=":0") as client:
        same(lazy.compute(), serial)  # on the active cluster
        same(mx.centerlines(lakes, scheduler=client), serial)  # a layer sent to it in chunks
    with pytest.raises(mx.InvalidInputError, match="scheduler active when it is computed"):
        mx.centerlines(dask_geopandas.from_geopandas(lakes, npartitions=2), n_jobs=2)


def test_bad_options_name_the_value(lakes):
    with pytest.raises(mx.InvalidInputError, match="n_jobs must be a positive integer"):
        mx.centerlines(lakes, n_jobs=0)
    with pytest.raises(mx.InvalidInputError, match="'forks'"):
        mx.centerlines(lakes, scheduler="forks")
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}), \
            pytest.raises(mx.InvalidInputError, match="cannot reach the Dask scheduler 'tcp://127.0.0.1:1'"):
        mx.centerlines(lakes, scheduler="tcp://127.0.0.1:1")


@pytest.mark.parametrize("scheduler", [None, "processes"])
def test_a_progress_bar_counts_the_features(lakes, capsys, scheduler):
    mx.centerlines(lakes.iloc[:6], n_jobs=2, scheduler=scheduler, show_progress=True)
    err = capsys.readouterr().err
    assert "features" in err and "/6 [" in err, err
    mx.centerlines(lakes.iloc[:6], show_progress=False)
    assert capsys.readouterr().err == ""


def _descendants():
    return {p.pid for p in psutil.Process().children(recursive=True)}


@pytest.fixture
def python_sigint(monkeypatch):
    """Python's own Ctrl-C handler for the test; the command line's flag (``medialaxis._entry``,
    when another test imported it) put back after, so later in-process runs are not taken as interrupted."""
    import signal
    import sys

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    entry = sys.modules.get("medialaxis._entry")
    if entry is not None:
        monkeypatch.setattr(entry, "interrupted", False)
    yield
    signal.signal(signal.SIGINT, previous)


@pytest.mark.parametrize("scheduler", ["threads", "processes"])
def test_ctrl_c_stops_the_workers_and_raises_cancelled(lakes, scheduler, python_sigint):
    mx.centerlines(lakes.iloc[:4], n_jobs=2, scheduler=scheduler)  # the worker server is up
    before, threads = _descendants(), threading.active_count()
    many = gpd.GeoDataFrame(geometry=list(lakes.geometry) * 250, crs=lakes.crs)  # 40 s of work on one core
    timer = threading.Timer(1.0, _thread.interrupt_main)
    timer.start()
    start = time.perf_counter()
    with pytest.raises(mx.Cancelled):
        mx.centerlines(many, n_jobs=2, scheduler=scheduler)
    timer.cancel()
    assert time.perf_counter() - start < 10.0
    assert _descendants() <= before  # no worker process left running
    assert threading.active_count() == threads  # nor a thread


HALF_MESSAGE = """
import multiprocessing, os, struct, sys, threading, time
from concurrent.futures import ProcessPoolExecutor

def half_message(flag):
    # in a worker: a 1000-byte result begun, 10 bytes of it written, then the stall of a worker ended mid-write
    frame = sys._getframe()
    while "result_queue" not in frame.f_locals:
        frame = frame.f_back
    os.write(frame.f_locals["result_queue"]._writer.fileno(), struct.pack("!i", 1000) + b"x" * 10)
    open(flag, "w").close()
    time.sleep(600)

if __name__ == "__main__":
    from medialaxis.gis.parallel import _end_pool
    pool = ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("forkserver"))
    future = pool.submit(half_message, sys.argv[1])
    while not os.path.exists(sys.argv[1]):
        time.sleep(0.05)
    time.sleep(0.5)  # the pool's manager thread now waits in its read for the other 990 bytes
    processes = list(pool._processes.values())
    for process in processes:
        process.terminate()
    if sys.argv[2] == "fixed":
        closing = threading.Thread(target=_end_pool, args=(pool, processes), daemon=True)
    else:
        closing = threading.Thread(target=pool.shutdown, kwargs={"wait": True, "cancel_futures": True}, daemon=True)
    closing.start()
    closing.join(10)
    print("hangs" if closing.is_alive() else type(future.exception(0)).__name__, flush=True)
    os._exit(0)
"""


@pytest.mark.parametrize("fixed", [True, False])
def test_a_worker_ended_mid_result_does_not_hang_the_pool(tmp_path, fixed):
    """The CI hang of 2026-11-28: Ctrl-C ended a worker while it wrote its result, and ``shutdown`` waited forever.

    With ``shutdown`` as it is (the control case) CPython's pool does hang on this input.
    """
    import subprocess
    import sys

    script = tmp_path / "half.py"
    script.write_text(HALF_MESSAGE)
    run = subprocess.run([sys.executable, str(script), str(tmp_path / "flag"), "fixed" if fixed else "as is"],
                         capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert run.stdout.strip() == ("BrokenProcessPool" if fixed else "hangs"), run.stderr[-2000:]


def test_cli_jobs_and_scheduler(lakes, serial, tmp_path):
    from medialaxis.cli import main

    source = tmp_path / "lakes.gpkg"
    lakes.to_file(source)
    assert main(["centerlines", str(source), "-o", str(tmp_path / "lines.gpkg"), "--jobs", "2"]) == 0
    back = gpd.read_file(tmp_path / "lines.gpkg")
    np.testing.assert_allclose(back["width_mean"], serial["width_mean"])
    assert main(["centerlines", str(source), "-o", str(tmp_path / "t.gpkg"), "--scheduler", "threads"]) == 0
    assert main(["centerlines", str(source), "-o", str(tmp_path / "x.gpkg"), "--scheduler", "forks"]) == 2
    assert main(["centerlines", str(source), "-o", str(tmp_path / "x.gpkg"), "--jobs", "0"]) == 2
