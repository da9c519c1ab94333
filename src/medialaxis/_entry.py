"""The console script: ``medialaxis`` and ``python -m medialaxis``.

Nothing heavy is imported before the ``try``: Ctrl-C while NumPy, SciPy or
numba load is reported as an interruption (exit 130), not a traceback.
"""

from __future__ import annotations

import sys

__all__ = ["run"]


def run() -> int:
    """Run :func:`medialaxis.cli.main` on ``sys.argv``; return its exit code."""
    try:
        from medialaxis.cli import main

        return main()
    except KeyboardInterrupt:
        if "--debug" in sys.argv[1:]:
            raise
        print("medialaxis: interrupted", file=sys.stderr)
        return 130
