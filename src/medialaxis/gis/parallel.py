"""The features of a layer in chunks: in this process, in worker processes, on threads or on Dask.

Measured on tiled OpenStreetMap lakes (``benchmarks/bench_gis_scale.py``, 2
cores): worker processes run 2 workers at 1.9 times the speed of one, threads
at 1.1 times (the per-feature work holds the GIL most of the time), so
processes are the default pool for ``n_jobs`` > 1.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections.abc import Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
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
    ``n_jobs`` worker processes; ``"threads"`` on ``n_jobs`` threads (default
    all CPUs); a Dask client or address on its cluster, chunk by chunk.
    Ctrl-C cancels the chunks not started, waits for the running ones and
    raises :class:`~medialaxis.errors.Cancelled`.
    """
    check_parallel(n_jobs, scheduler)
    workers = (os.cpu_count() or 1) if n_jobs is None and scheduler is not None else int(n_jobs or 1)
    if scheduler == "synchronous" or (scheduler is None and workers == 1) or not items:
        results = []
        for chunk in progress(_chunks(items, 1), desc="features", show=show_progress):
            results.extend(run_chunk(kind, chunk, options, step))
        return results
    chunks = _chunks(items, workers)
    if scheduler in (None, "processes"):
        return _on_processes(kind, chunks, options, step, workers, len(items), show_progress)
    done = run_tasks(_chunk_task, chunks, kind, options, step, scheduler=scheduler,
                     n_jobs=workers if scheduler == "threads" else None, desc="feature chunks",
                     show_progress=show_progress)
    return [row for rows in done for row in rows]


def _chunk_task(chunk: Sequence[Any], kind: str, options: dict[str, Any], step: float | None) -> list[Any]:
    return run_chunk(kind, chunk, options, step)


def _quiet_worker() -> None:
    """Workers leave Ctrl-C to the parent, which stops handing out chunks and waits for theirs."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _on_processes(kind: str, chunks: list[Sequence[Any]], options: dict[str, Any], step: float | None,
                  workers: int, total: int, show_progress: bool | None) -> list[Any]:
    # forkserver, not fork: the parent may hold threads (numba, a progress bar) that a fork would copy mid-step
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(["medialaxis.gis._warm"])
    pool = ProcessPoolExecutor(min(workers, len(chunks)), mp_context=context, initializer=_quiet_worker)
    futures = {pool.submit(run_chunk, kind, chunk, options, step): k for k, chunk in enumerate(chunks)}
    results: list[Any] = [None] * len(chunks)
    try:
        for _ in progress(_features_done(futures, results), desc="features", total=total, show=show_progress):
            pass
    except BaseException as exc:
        for fut in futures:
            fut.cancel()
        if isinstance(exc, KeyboardInterrupt):
            raise Cancelled("features: cancelled") from exc
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return [row for rows in results for row in rows]


def _features_done(futures: dict[Future, int], results: list[Any]) -> Iterator[None]:
    """Store each chunk's rows as it completes and yield once per feature (for the progress bar)."""
    pending = set(futures)
    while pending:
        # a short timeout keeps the main thread responsive to Ctrl-C
        done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
        for fut in done:
            rows = fut.result()
            results[futures[fut]] = rows
            yield from (None for _ in rows)
