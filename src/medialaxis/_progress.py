"""Progress bars (tqdm, shown only on a terminal), the callback protocol of every method, and cooperative
cancellation."""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import sys
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, TypeVar

from medialaxis.errors import Cancelled

__all__ = ["Progress", "progress", "check_cancel", "stage_callback", "StageClock"]


@dataclasses.dataclass(frozen=True)
class Progress:
    """What the ``callback`` of every method receives, at each stage or step; a callback returning ``False`` cancels.

    Attributes
    ----------
    method : str
        ``"voronoi"`` or ``"flow"`` (meshes), ``"midsurface"`` or ``"voxels"`` (volumes).
    stage : str
        The stage about to run (``"distance"``, a block pass ...) or ``"diffusion flow"``.
    step : int
        How many calls came before this one in this run (from 0).
    total : int or None
        How many calls the run makes, when known.
    state : object
        What the method shows of its work, or None: the flow's
        :class:`~medialaxis.mesh.skeleton.flow_mesh.FlowState` (the contracting mesh, for a
        progressive display).
    """

    method: str
    stage: str
    step: int
    total: int | None = None
    state: Any = None

T = TypeVar("T")


def _enabled(show: bool | None) -> bool:
    if show is not None:
        return show
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


def progress(iterable: Iterable[T], *, desc: str, total: int | None = None, show: bool | None = None) -> Iterator[T]:
    """Iterate with a tqdm bar on stderr when it is a terminal.

    ``KeyboardInterrupt`` inside the loop is turned into :class:`Cancelled`
    after the bar is closed, so callers clean up and the CLI exits cleanly.
    """
    if _enabled(show):
        from tqdm.auto import tqdm

        bar: Any = tqdm(iterable, desc=desc, total=total, leave=False, file=sys.stderr)
    else:
        bar = iterable
    try:
        yield from bar
    except KeyboardInterrupt as exc:
        raise Cancelled(f"{desc}: cancelled") from exc
    finally:
        if bar is not iterable:
            bar.close()


def check_cancel(callback: Any, state: Any) -> None:
    """Call a user ``callback(state)``; a return value of ``False`` cancels."""
    if callback is not None and callback(state) is False:
        raise Cancelled("cancelled by callback")


def stage_callback(callback: Callable[[Progress], Any] | None, method: str) -> Callable[[str], Any] | None:
    """A user's ``callback(Progress)`` as a ``callback(stage)`` (of tasks that name their stage only), counting calls."""
    if callback is None:
        return None
    calls = itertools.count()
    return lambda stage: callback(Progress(method, stage, next(calls)))


class StageClock:
    """The stages of a run, in order: each announced to the callback, timed, and shown on a progress bar.

    >>> clock = StageClock("voxels", ("load", "measure"))
    >>> with clock("load"):
    ...     pass
    >>> with clock("measure"):
    ...     pass
    >>> sorted(clock.timings)
    ['load', 'measure']
    """

    def __init__(self, method: str, stages: tuple[str, ...], callback: Callable[[Progress], Any] | None = None,
                 show: bool | None = None, desc: str | None = None) -> None:
        self.method, self.stages, self.callback = method, stages, callback
        self.timings: dict[str, float] = {}
        self._bar: Any = None
        if _enabled(show):
            from tqdm.auto import tqdm

            self._bar = tqdm(total=len(stages), desc=desc or method, leave=False, file=sys.stderr)

    @contextlib.contextmanager
    def __call__(self, stage: str) -> Iterator[None]:
        """Run one stage: the callback hears of it first (``False`` cancels); Ctrl-C inside becomes :class:`Cancelled`."""
        step = self.stages.index(stage)
        try:
            check_cancel(self.callback, Progress(self.method, stage, step, len(self.stages)))
            started = time.perf_counter()
            yield
            self.timings[stage] = time.perf_counter() - started
        except KeyboardInterrupt as exc:
            raise Cancelled(f"{self.method}: cancelled") from exc
        finally:
            if self._bar is not None:
                self._bar.update(1)
                if step == len(self.stages) - 1 or sys.exc_info()[0] is not None:
                    self._bar.close()
