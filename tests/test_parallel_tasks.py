"""core.parallel.run_tasks on local threads: order, errors, a bounded queue and clean cancellation."""

from __future__ import annotations

import _thread
import signal
import threading
import time

import pytest

from medialaxis.core.parallel import run_tasks
from medialaxis.errors import Cancelled


def _square(x: int, offset: int = 0) -> int:
    time.sleep(0.001 * (x % 3))  # tasks finish out of order
    return x * x + offset


def test_results_in_the_order_of_the_items() -> None:
    assert run_tasks(_square, list(range(200)), 1, n_jobs=3) == [x * x + 1 for x in range(200)]
    assert run_tasks(_square, [], n_jobs=2) == []


def test_a_task_error_is_raised_as_it_is_and_the_rest_not_started() -> None:
    started = []

    def task(x: int) -> int:
        started.append(x)
        if x == 5:
            raise ValueError("task 5")
        time.sleep(0.005)
        return x

    with pytest.raises(ValueError, match="task 5"):
        run_tasks(task, list(range(10_000)), n_jobs=2)
    assert len(started) < 50


def test_a_callback_cancels_with_at_most_the_queued_tasks_started() -> None:
    started, calls = [], []

    def task(x: int) -> int:
        started.append(x)
        time.sleep(0.002)
        return x

    def callback(desc: str) -> bool:
        calls.append(desc)
        return len(calls) < 3

    threads = threading.active_count()
    with pytest.raises(Cancelled):
        run_tasks(task, list(range(100_000)), n_jobs=2, callback=callback)
    # three collected, at most 2 x n_jobs queued beside them: the 100,000 were never all submitted
    assert len(started) <= 3 + 2 * 2
    assert threading.active_count() == threads


def test_ctrl_c_raises_cancelled_quickly_and_leaves_no_thread() -> None:
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        threads = threading.active_count()
        timer = threading.Timer(0.3, _thread.interrupt_main)
        timer.start()
        start = time.perf_counter()
        with pytest.raises(Cancelled):
            run_tasks(time.sleep, [0.01] * 100_000, n_jobs=2)  # 500 s of work on two threads
        timer.cancel()
        assert time.perf_counter() - start < 3.0
        assert threading.active_count() == threads
    finally:
        signal.signal(signal.SIGINT, previous)


def test_waiting_does_not_grow_with_the_batch() -> None:
    # Waiting on every submitted future once per finished task was quadratic: 20,000 trivial
    # tasks took 583 s on two threads (15 s for 5,000); with a bounded queue they take a fraction of a second.
    start = time.perf_counter()
    assert run_tasks(abs, list(range(-20_000, 0)), n_jobs=2)[:2] == [20_000, 19_999]
    assert time.perf_counter() - start < 20.0
