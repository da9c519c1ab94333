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


