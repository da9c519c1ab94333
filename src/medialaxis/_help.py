"""Command-line plumbing shared by every ``medialaxis`` subcommand (the main CLI and the compare CLI):
the help formatter, the usage error (exit code 2) and a parser that raises it."""

from __future__ import annotations

import argparse
import sys
from typing import NoReturn

__all__ = ["HelpFormatter", "UsageError", "Parser", "print_error"]


def print_error(message: object) -> None:
    """One line on stderr: ``medialaxis: error: ...`` (whitespace folded)."""
    print(f"medialaxis: error: {' '.join(str(message).split())}", file=sys.stderr)


class UsageError(Exception):
    """A command-line usage problem (exit code 2)."""


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are :class:`UsageError` (one line, exit 2), not a usage dump."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message} (see {self.prog} --help)")


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Shows a default once: not for options without one (None, [], False) nor where the help says it."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if action.default in (None, [], False, argparse.SUPPRESS) or "default" in text:
            return text
        return super()._get_help_string(action) or text
