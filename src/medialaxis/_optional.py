"""Lazy loading of optional dependencies with an install hint."""

from __future__ import annotations

import importlib
from types import ModuleType

from medialaxis.errors import MissingDependencyError

__all__ = ["require"]


def require(module: str, extra: str) -> ModuleType:
    """Import ``module`` or raise :class:`MissingDependencyError` naming what to install.

    Parameters
    ----------
    module : str
        Dotted module name, e.g. ``"trimesh"``.
    extra : str
        The pip requirement or medialaxis extra that provides it.
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise MissingDependencyError(
            f"{module!r} is needed for this feature; install it with "
            f"`pip install {extra}` or `pip install medialaxis[all]`"
        ) from exc
