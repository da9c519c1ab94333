"""The console script: ``medialaxis`` and ``python -m medialaxis``.

Importing this module installs the command line's Ctrl-C handler first of
all (it is the entry point, never imported by the library): from then on a
Ctrl-C, while NumPy, SciPy or numba load or during the work, is reported as
an interruption (exit 130, one line), even where a library turns the
``KeyboardInterrupt`` into another error (NumPy's import does). Only the
interpreter's own start-up, before this module runs, is Python's.
"""

from __future__ import annotations

import signal
import sys

#: Set by the first Ctrl-C of the run.
interrupted = False


def _on_interrupt(signum: int, frame: object) -> None:
    global interrupted
    interrupted = True
    raise KeyboardInterrupt


def _unraisable(hook: object) -> object:
    def report(unraisable: object) -> None:
        # a Ctrl-C raised inside a callback from C (numba's compiler) cannot
        # stop the work; it is not a failure to print as a traceback
        if interrupted and isinstance(getattr(unraisable, "exc_value", None), KeyboardInterrupt):
            return
        hook(unraisable)  # type: ignore[operator]

    return report


try:
    signal.signal(signal.SIGINT, _on_interrupt)
except ValueError:  # not the main thread: leave Python's handler
    pass
else:
    sys.unraisablehook = _unraisable(sys.unraisablehook)

__all__ = ["run", "interrupted"]


def run() -> int:
    """Run :func:`medialaxis.cli.main` on ``sys.argv``; return its exit code."""
    debug = "--debug" in sys.argv[1:]
    try:
        from medialaxis.cli import main

        code = main()
    except KeyboardInterrupt:
        if debug:
            raise
        code = _report_interrupt()
    except Exception:
        # an interrupt turned into another error on its way up (an import)
        if debug or not interrupted:
            raise
        code = _report_interrupt()
    # The work is done (or reported): a Ctrl-C now would only break the
    # interpreter's shutdown and end the process by the signal, silently.
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread
        pass
    return code


def _report_interrupt() -> int:
    print("medialaxis: interrupted", file=sys.stderr)
    return 130
