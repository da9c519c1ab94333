"""Progress bars (tqdm, shown only on a terminal) and cooperative cancellation."""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from typing import Any, TypeVar

from medialaxis.errors import Cancelled

__all__ = ["progress", "check_cancel"]

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
