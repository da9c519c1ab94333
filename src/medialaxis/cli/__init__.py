"""The ``medialaxis`` command line: one module per command.

``compute`` (:mod:`medialaxis.cli.compute`, its many inputs in
:mod:`medialaxis.cli.batch`), ``centerlines`` (:mod:`medialaxis.cli.centerlines`),
``demo`` (:mod:`medialaxis.cli.demo`), ``warmup`` (:mod:`medialaxis.cli.warmup`),
``compare`` and ``search`` (:mod:`medialaxis.cli.compare`).

Exit codes: 0 success, 1 failure (bad or unreadable input, computation
failed, an output that cannot be written), 2 usage error (bad arguments),
130 interrupted (Ctrl-C). Errors print one line on stderr, never a
traceback (``--debug`` shows it); the libraries' warnings and log records
are silenced. Outputs are checked before any work, written atomically and
never over the input, and appear together at the end or not at all.
"""

from __future__ import annotations

import argparse
import logging
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import Any

from medialaxis._help import Parser as _Parser
from medialaxis._help import UsageError
from medialaxis._help import print_error as _fail
from medialaxis._version import __version__
from medialaxis.errors import Cancelled, MedialAxisError, MedialAxisWarning, UnsupportedFormatError

__all__ = ["main", "build_parser"]


#: Exit code of an interrupted run (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130


def _subcommands() -> list[Callable[[Any], None]]:
    """Subcommand builders, one module each; each adds a parser whose ``run`` default handles it.

    Imported when the parser is built, so that ``python -m medialaxis.cli.compute`` runs its module once.
    """
    from medialaxis.cli import centerlines, compare, compute, demo, warmup

    return [compute.add_compute, centerlines.add_centerlines, demo.add_demo, warmup.add_warmup,
            compare.add_compare, compare.add_search]


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="medialaxis",
        description="Medial axis transforms of images, polygons, meshes and volumes.",
    )
    parser.add_argument("--version", action="version", version=f"medialaxis {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for add in _subcommands():
        add(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``medialaxis`` console script; returns the exit code.

    0 success; 1 failure (bad or unreadable input, the computation failed,
    an output could not be written); 2 usage error; 130 interrupted
    (Ctrl-C). An error is one line on stderr, never a traceback unless
    ``--debug`` is given.
    """
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    if debug:
        return _main(argv, debug)
    # The libraries' warnings and log records about a bad file are not ours to
    # print: the error line says what went wrong (--debug shows them). Our
    # own warnings (something left out of a result) are one line each.
    # They are held until the run ends: after a result they are printed as one line, after an
    # error not at all (the error is the one line).
    previous = logging.root.manager.disable
    logging.disable(logging.CRITICAL)
    held: list[str] = []
    code = 1
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            warnings.simplefilter("default", MedialAxisWarning)
            warnings.showwarning = lambda message, *args, **kwargs: held.append(str(message))
            code = _main(argv, debug)
            return code
    finally:
        logging.disable(previous)
        if code == 0 and held:
            _warning_line("; ".join(dict.fromkeys(held)))


def _was_interrupted() -> bool:
    """Whether the console script's Ctrl-C handler has fired (not imported here:
    the library's callers keep Python's handler)."""
    return bool(getattr(sys.modules.get("medialaxis._entry"), "interrupted", False))


def _warning_line(message: Warning | str, *args: Any, **kwargs: Any) -> None:
    print(f"medialaxis: warning: {message}", file=sys.stderr)


def _main(argv: Sequence[str] | None, debug: bool) -> int:
    try:
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help and --version
            return int(exc.code or 0)
        if not getattr(args, "run", None):
            commands = ", ".join(sorted(parser._subparsers._group_actions[0].choices))  # type: ignore[union-attr,arg-type]
            raise UsageError(f"a command is required: {commands} (see medialaxis --help)")
        return int(args.run(args))
    except (UsageError, UnsupportedFormatError) as exc:
        if debug:
            raise
        _fail(str(exc))
        return 2
    except (Cancelled, KeyboardInterrupt):
        if debug:
            raise
        print("medialaxis: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except MedialAxisError as exc:
        if debug:
            raise
        if _was_interrupted():  # a Ctrl-C turned into this error (an import it broke)
            print("medialaxis: interrupted", file=sys.stderr)
            return EXIT_INTERRUPTED
        _fail(str(exc))
        return 1
    except MemoryError:
        if debug:
            raise
        _fail("out of memory")
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
