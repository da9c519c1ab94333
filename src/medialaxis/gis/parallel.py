"""The features of a layer on threads, worker processes or Dask, or one after the other here.

Threads are the pool for ``n_jobs`` > 1: measured on tiled OpenStreetMap
lakes (``benchmarks/bench_gis_scale.py``, 2 cores shared with other work),
2 threads took 0.73 to 0.93 of the time of 2 worker processes in four runs
at load average 7 to 14 (600, 2,000 and twice 3,000 lakes) and 0.97 of it
at load 4.3 (5,000 lakes, 52.5 s against 54.1 s), with half the peak memory
(470 MB against 864 MB for 5,000 lakes): nothing is pickled or started, and
the compiled kernels and shapely release the GIL. Worker processes
(``scheduler="processes"``) are there for work that holds it.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections.abc import Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor, wait
from typing import Any

from medialaxis._progress import progress
from medialaxis.core.parallel import check_jobs, check_scheduler, run_tasks
from medialaxis.errors import Cancelled, InvalidInputError
from medialaxis.gis.features import run_chunk

__all__ = ["LOCAL_SCHEDULERS", "check_parallel", "map_features"]

#: Schedulers on this machine; anything else is a Dask client or address.
LOCAL_SCHEDULERS = ("processes", "threads", "synchronous")

#: Largest number of features sent to a worker at once: enough to make the
#: cost of sending them small, few enough for a progress bar and a quick stop.
CHUNK = 64


def check_parallel(n_jobs: Any, scheduler: Any) -> None:
    """``n_jobs`` is None or a positive integer; ``scheduler`` one of the local ones, a Client or an address."""
    check_jobs(n_jobs)
    if scheduler == "processes":
        return
    try:
        check_scheduler(scheduler)
    except InvalidInputError:
        raise InvalidInputError(
            f"scheduler must be None, 'processes', 'threads', 'synchronous', a dask Client or an address like "
            f"'tcp://host:8786', got {scheduler!r}"
        ) from None


def _chunks(items: Sequence[Any], workers: int) -> list[Sequence[Any]]:
    """Chunks of at most :data:`CHUNK` items, at least four per worker when there are enough items."""
    size = max(1, min(CHUNK, len(items) // max(4 * workers, 1)))
    return [items[k:k + size] for k in range(0, len(items), size)]


def map_features(kind: str, items: Sequence[tuple[Any, Any]], options: dict[str, Any], *, step: float | None = None,
                 n_jobs: int | None = None, scheduler: Any = None, show_progress: bool | None = None) -> list[Any]:
    """:func:`~medialaxis.gis.features.run_chunk` over ``(index, geometry)`` items, results in their order.

    ``scheduler`` None runs here when ``n_jobs`` is None or 1, else on
    ``n_jobs`` threads; ``"threads"`` on ``n_jobs`` threads (default all
    CPUs), one feature per task; ``"processes"`` on worker processes and a
    Dask client or address on its cluster, chunk by chunk. Ctrl-C cancels
    the tasks not started (threads: waits for the running features; worker
    processes are ended) and raises :class:`~medialaxis.errors.Cancelled`.
    """
    check_parallel(n_jobs, scheduler)
    workers = (os.cpu_count() or 1) if n_jobs is None and scheduler is not None else int(n_jobs or 1)
    if scheduler == "synchronous" or (scheduler is None and workers == 1) or not items:
        results = []
        # here, chunks of CHUNK features: each chunk's shapely work is vectorised (features.chunk_axes)
        for chunk in progress([items[k:k + CHUNK] for k in range(0, len(items), CHUNK)], desc="features",
                              show=show_progress):
            results.extend(run_chunk(kind, chunk, options, step))
        return results
    if scheduler in (None, "threads"):
        # nothing is sent to a thread: one feature per task, counted one by one
        pool: Executor = ThreadPoolExecutor(workers)
        return _on_pool(pool, kind, [[item] for item in items], options, step, workers, show_progress)
    chunks = _chunks(items, workers)
    if scheduler == "processes":
        # forkserver, not fork: the parent may hold threads (numba, a progress bar) that a fork would copy mid-step
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["medialaxis.gis._warm"])
        pool = ProcessPoolExecutor(min(workers, len(chunks)), mp_context=context, initializer=_quiet_worker)
        return _on_pool(pool, kind, chunks, options, step, workers, show_progress)
    try:
        done = run_tasks(_chunk_task, chunks, kind, options, step, scheduler=scheduler, desc="feature chunks",
                         show_progress=show_progress)
    except OSError as exc:  # distributed: no scheduler there
        raise InvalidInputError(f"cannot reach the Dask scheduler {scheduler!r}: {exc}") from exc
    return [row for rows in done for row in rows]


def _chunk_task(chunk: Sequence[Any], kind: str, options: dict[str, Any], step: float | None) -> list[Any]:
    return run_chunk(kind, chunk, options, step)


def _quiet_worker() -> None:
    """Workers leave Ctrl-C to the parent, which stops handing out chunks and ends the workers."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _on_pool(pool: Executor, kind: str, chunks: list[Sequence[Any]], options: dict[str, Any], step: float | None,
             workers: int, show_progress: bool | None) -> list[Any]:
    """The chunks on a thread or process pool, a few per worker handed out at a time; rows in order."""
    results: list[Any] = [None] * len(chunks)
    pending: dict[Future, int] = {}
    ended: list[Any] = []
    try:
        total = sum(len(chunk) for chunk in chunks)
        for _ in progress(_rows_done(pool, kind, chunks, options, step, 4 * workers, pending, results),
                          desc="features", total=total, show=show_progress):
            pass
    except BaseException as exc:
        # the chunks handed out to processes compute nothing that outlives them: stop them now rather
        # than wait (ProcessPoolExecutor.terminate_workers from Python 3.14); threads end their feature.
        # The futures not started are cancelled by the shutdown (cancelled here, a pool that then finds
        # its workers gone would fail them again, and its manager thread die of it)
        ended = list((getattr(pool, "_processes", None) or {}).values())
        for process in ended:
            process.terminate()
        if isinstance(exc, KeyboardInterrupt):
            raise Cancelled("features: cancelled") from exc
        raise
    finally:
        if ended:
            _end_pool(pool, ended)
        else:
            pool.shutdown(wait=True, cancel_futures=True)
    return [row for rows in results for row in rows]


def _end_pool(pool: Executor, ended: list[Any]) -> None:
    """``pool.shutdown(wait=True)`` once its worker processes ``ended`` were terminated, without hanging.

    A worker ended while it wrote its result leaves part of a message in the result pipe, and the
    pool's manager thread waits in its read for the rest, so ``shutdown`` never returns (a CI run
    hung so in the Ctrl-C test, 2026-11-28). Once every worker is gone our own writing end of that
    pipe is its last: closed, the read ends at end of file, which the pool takes as a worker lost
    (it fails the futures left and ends by itself). Nothing is written to that pipe from this side.
    """
    manager = getattr(pool, "_executor_manager_thread", None)
    queue = getattr(pool, "_result_queue", None)
    pool.shutdown(wait=False, cancel_futures=True)  # wakes the manager; the pool lets go of both
    for process in ended:
        process.join(5.0)
    if manager is None:
        return
    manager.join(2.0)
    if manager.is_alive() and queue is not None and not any(process.is_alive() for process in ended):
        queue._writer.close()
        manager.join(10.0)
    if queue is not None and not manager.is_alive():
        queue.close()


def _rows_done(pool: Executor, kind: str, chunks: list[Sequence[Any]], options: dict[str, Any],
               step: float | None, in_flight: int, pending: dict[Future, int], results: list[Any]) -> Iterator[None]:
    """Hand out chunks (at most ``in_flight`` at once), store each one's rows as it completes, and yield
    once per feature (for the progress bar)."""
    queue = iter(range(len(chunks)))
    for k in queue:
        pending[pool.submit(run_chunk, kind, chunks[k], options, step)] = k
        if len(pending) >= in_flight:
            break
    while pending:
        # a short timeout keeps the main thread responsive to Ctrl-C
        done, _ = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
        for fut in done:
            results[pending.pop(fut)] = rows = fut.result()
            k = next(queue, None)
            if k is not None:
                pending[pool.submit(run_chunk, kind, chunks[k], options, step)] = k
            yield from (None for _ in rows)
