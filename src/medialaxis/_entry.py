"""The console script: ``medialaxis`` and ``python -m medialaxis``.

Nothing heavy is imported before the ``try``: Ctrl-C while NumPy, SciPy or
numba load is reported as an interruption (exit 130), not a traceback.
"""

from __future__ import annotations

import contextlib
import signal
import sys

__all__ = ["run"]


def run() -> int:
    """Run :func:`medialaxis.cli.main` on ``sys.argv``; return its exit code."""
    try:
        from medialaxis.cli import main

        code = main()
    except KeyboardInterrupt:
        if "--debug" in sys.argv[1:]:
            raise
        print("medialaxis: interrupted", file=sys.stderr)
        code = 130
    # The work is done (or reported): a Ctrl-C now would only break the
    # interpreter's shutdown and end the process by the signal, silently.
    with contextlib.suppress(ValueError):  # not the main thread
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code
