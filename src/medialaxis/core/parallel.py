"""Tasks on local threads or a Dask cluster, with a progress bar and clean cancellation.

``scheduler`` is ``None``/``"threads"`` (local threads), ``"synchronous"``
(one thread, in order), a ``dask.distributed.Client`` or a scheduler address
such as ``"tcp://host:8786"``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from typing import Any

import numpy as np

from medialaxis._progress import check_cancel, progress
from medialaxis.errors import Cancelled, InvalidInputError

__all__ = ["check_scheduler", "check_jobs", "dask_client", "run_tasks"]


def check_scheduler(scheduler: Any) -> None:
    """Refuse anything but the schedulers listed in the module docstring."""
    if scheduler in (None, "threads", "synchronous"):
        return
    if isinstance(scheduler, str) and "://" in scheduler:
        return
    if not isinstance(scheduler, str) and hasattr(scheduler, "submit") and hasattr(scheduler, "scatter"):
        return
    raise InvalidInputError(
        f"scheduler must be None, 'threads', 'synchronous', a dask Client or an address like "
        f"'tcp://host:8786', got {scheduler!r}"
    )


def check_jobs(n_jobs: Any) -> None:
    """``n_jobs`` is None or a positive integer."""
    if n_jobs is None:
        return
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or n_jobs < 1:
        raise InvalidInputError(f"n_jobs must be a positive integer or None, got {n_jobs!r}")


def dask_client(scheduler: Any) -> tuple[Any, bool]:
    """The Dask client for ``scheduler`` and whether this call opened it (and must close it)."""
    from medialaxis._optional import require

    distributed = require("distributed", "medialaxis[dask]")
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    return distributed.Client(scheduler), True


def run_tasks(
    fn: Callable[..., Any],
    items: Sequence[Any],
    *args: Any,
    scheduler: Any = None,
    n_jobs: int | None = None,
    desc: str = "tasks",
    show_progress: bool | None = None,
    callback: Callable[[str], Any] | None = None,
) -> list[Any]:
    """``[fn(item, *args) for item in items]`` in parallel, results in the order of ``items``.

    At most ``n_jobs`` tasks (default: all CPUs) run at once locally, and at
    most twice as many are queued. Ctrl-C or a ``callback`` returning
    ``False`` (called after each task) drops the tasks not yet started, waits
    for the running ones and raises
    :class:`~medialaxis.errors.Cancelled`; a task's error cancels the others
    and is raised as it is.
    """
    check_scheduler(scheduler)
    check_jobs(n_jobs)
    results: list[Any] = [None] * len(items)
    if scheduler not in (None, "threads", "synchronous"):
        return _run_dask(fn, items, args, scheduler, desc, show_progress, callback)
    workers = 1 if scheduler == "synchronous" else (os.cpu_count() or 1) if n_jobs is None else int(n_jobs)
    if workers == 1:
        for k in progress(range(len(items)), desc=desc, total=len(items), show=show_progress):
            results[k] = fn(items[k], *args)
            check_cancel(callback, desc)
        return results
    pool = ThreadPoolExecutor(workers)
    todo = iter(enumerate(items))
    index: dict[Any, int] = {}  # the tasks submitted and not yet collected
    try:
        _top_up(pool, todo, index, 2 * workers, fn, args)
        for _ in progress(range(len(items)), desc=desc, total=len(items), show=show_progress):
            fut = _next(index)
            results[index.pop(fut)] = fut.result()
            check_cancel(callback, desc)
            _top_up(pool, todo, index, 2 * workers, fn, args)
    except BaseException as exc:
        for fut in index:
            fut.cancel()
        if isinstance(exc, KeyboardInterrupt):
            raise Cancelled(f"{desc}: cancelled") from exc
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return results


def _top_up(pool: ThreadPoolExecutor, todo: Any, index: dict[Any, int], window: int, fn: Callable[..., Any],
            args: tuple[Any, ...]) -> None:
    """Submit tasks until ``window`` are in flight: a large batch never queues every task at once, so
    Ctrl-C drops the rest at once and waiting stays cheap."""
    while len(index) < window:
        k, item = next(todo, (None, None))
        if k is None:
            return
        index[pool.submit(fn, item, *args)] = k


def _next(index: dict[Any, int]) -> Any:
    """Wait for one more task (a short timeout keeps the main thread responsive to Ctrl-C)."""
    while True:
        done, _ = wait(index, timeout=0.2, return_when=FIRST_COMPLETED)
        if done:
            return min(done, key=index.__getitem__)


def _run_dask(fn: Callable[..., Any], items: Sequence[Any], args: tuple[Any, ...], scheduler: Any, desc: str,
              show_progress: bool | None, callback: Callable[[str], Any] | None) -> list[Any]:
    from medialaxis._optional import require

    distributed = require("distributed", "medialaxis[dask]")
    client, owned = dask_client(scheduler)
    futures: list[Any] = []
    try:
        # each argument as one object under its own key (a dict or tuple would be split, and
        # equal values of an earlier call could share a key being released)
        shared = [client.scatter([a], broadcast=True, hash=False)[0] if _shared(a) else a for a in args]
        futures = [client.submit(fn, item, *shared, pure=False) for item in items]
        index = {f.key: k for k, f in enumerate(futures)}
        results: list[Any] = [None] * len(items)
        done = distributed.as_completed(futures, with_results=False)
        for fut in progress(done, desc=desc, total=len(futures), show=show_progress):
            results[index[fut.key]] = fut.result()
            check_cancel(callback, desc)
        return results
    except BaseException:
        client.cancel(futures)
        raise
    finally:
        if owned:
            client.close()


def _shared(value: Any) -> bool:
    """Arguments sent to every worker once (scattered) rather than with each task: all but plain scalars."""
    return not (value is None or isinstance(value, (bool, int, float, str, np.number)))
