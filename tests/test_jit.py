"""The numba helpers: work beside a serial kernel on a second thread, or at once."""

import threading

import numpy as np
import pytest

import medialaxis._jit as jit
from medialaxis.errors import InvalidInputError


def _fails(message: str) -> None:
    raise InvalidInputError(message)


@pytest.mark.parametrize("concurrent", [True, False])
def test_beside_returns_the_value_or_raises_the_error_of_its_function(monkeypatch, concurrent):
    monkeypatch.setattr(jit, "concurrent_kernels", lambda: concurrent)
    caller = threading.get_ident()
    ran_on = []

    def work(a, b):
        ran_on.append(threading.get_ident())
        return np.add(a, b)

    side = jit.Beside(work, np.arange(3), 1)
    assert side.result().tolist() == [1, 2, 3]
    assert (ran_on[0] != caller) == concurrent  # a second thread only where the layer allows it
    with pytest.raises(InvalidInputError, match="bad value 7"):
        jit.Beside(_fails, "bad value 7").result()


def test_concurrent_kernels_follows_the_threading_layer():
    import numba

    assert jit.concurrent_kernels() == (numba.threading_layer() in ("omp", "tbb"))




class _Terminal:
    """A stream that says it is a terminal, keeping what is written."""

    def __init__(self, tty: bool = True) -> None:
        self.tty, self.text = tty, ""

    def isatty(self) -> bool:
        return self.tty

    def write(self, text: str) -> None:
        self.text += text

    def flush(self) -> None:
        pass


_MODULE = '''
from medialaxis._jit import njit

@njit(cache=True)
def twice(x):
    return 2 * x
'''

_CHECK = '''
import sys
sys.path.insert(0, sys.argv[1])
import cold_module
from medialaxis._jit import is_compiled
before = is_compiled(cold_module.twice)
assert cold_module.twice(3) == 6
print(before, is_compiled(cold_module.twice))
'''


def test_is_compiled_reads_numba_s_disk_cache_in_a_new_process(tmp_path):
    import subprocess
    import sys

    (tmp_path / "cold_module.py").write_text(_MODULE)
    env = {k: v for k, v in __import__("os").environ.items() if k != "NUMBA_CACHE_DIR"}

    def run() -> str:
        done = subprocess.run([sys.executable, "-c", _CHECK, str(tmp_path)], capture_output=True, text=True, env=env,
                              timeout=120)
        assert done.returncode == 0, done.stderr
        return done.stdout.split()

    assert run() == ["False", "True"]  # nothing cached yet: compiled by the call
    assert any(tmp_path.glob("__pycache__/cold_module.twice-*.nbi"))  # numba's own index, written beside the module
    assert run() == ["True", "True"]  # a new process finds it on disk before any call


def test_announce_compiling_says_one_line_on_a_terminal_only_while_the_kernel_is_not_compiled(monkeypatch):
    import numba

    kernel = numba.njit(lambda x: x + 1)  # never compiled, not cached
    quiet = _Terminal(tty=False)
    assert not jit.announce_compiling(kernel, "mesh voronoi", quiet) and quiet.text == ""
    monkeypatch.setattr(jit, "QUIET", True)  # medialaxis warmup compiles on purpose
    tty = _Terminal()
    assert not jit.announce_compiling(kernel, "mesh voronoi", tty) and tty.text == ""
    monkeypatch.setattr(jit, "QUIET", False)
    assert jit.announce_compiling(kernel, "mesh voronoi", tty)
    assert tty.text.count("\n") == 1 and "mesh voronoi" in tty.text and "medialaxis warmup" in tty.text
    assert kernel(1) == 2
    again = _Terminal()
    assert not jit.announce_compiling(kernel, "mesh voronoi", again) and again.text == ""


def _small_shapes():
    import trimesh

    from medialaxis.datasets import data_path, t_phantom

    capsule = trimesh.creation.capsule(height=1.0, radius=0.4, count=[12, 12])
    phantom = t_phantom((24, 40, 40), thickness=5, margin=6).volume
    return {("planar", "voronoi"): (data_path("bracket_two_holes.wkt").read_text(), {}),
            ("mesh", "voronoi"): (capsule, {"samples": 1500}),
            ("mesh", "flow"): (capsule, {}),
            ("volume", "midsurface"): (phantom, {}),
            ("volume", "voxels"): (phantom, {})}


def test_every_method_runs_the_kernel_that_tells_whether_it_will_compile():
    """The kernel named for a method in FIRST_KERNELS is one its call compiles (or loads): else no notice is right."""
    import medialaxis as mx
    from medialaxis import _dispatch

    shapes = _small_shapes()
    assert set(shapes) == set(_dispatch.FIRST_KERNELS) == {(d, m) for d, ms in _dispatch.METHODS.items() for m in ms}
    for (domain, method), (shape, options) in shapes.items():
        mx.medial_axis(shape, method=method, **options)
        kernel = _dispatch._load(_dispatch.FIRST_KERNELS[domain, method])
        assert kernel.signatures, (domain, method)  # typed in this process: the call ran it
