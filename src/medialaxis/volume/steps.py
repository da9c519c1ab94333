"""Writing the stages of the volume pipeline (``medialaxis compute --steps``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from medialaxis.errors import InvalidInputError
from medialaxis.volume.pipeline import VolumeStages, volume_stages

__all__ = ["save_steps", "stages_for_method", "STEP_SUFFIXES"]

#: Formats a stage can be written in.
STEP_SUFFIXES = (".ply", ".vtk", ".obj", ".json", ".npz")


def stages_for_method(volume: Any, method: str | None = None, **options: Any) -> VolumeStages:
    """Run :func:`~medialaxis.volume.pipeline.volume_stages` for the CLI.

    Parameters
    ----------
    volume : array_like or path
    method : {"midsurface", None}
        Stages exist for the mid-surface method only.
    **options
        Options of :func:`~medialaxis.volume.pipeline.midsurface_medial_axis`;
        ``None`` values are dropped.

    Raises
    ------
    InvalidInputError
        For another method or an unknown option.
    """
    if method not in (None, "midsurface"):
        raise InvalidInputError(f"stages are written for method 'midsurface', not {method!r}")
    given = {k: v for k, v in options.items() if v is not None}
    import inspect

    accepted = inspect.signature(volume_stages).parameters
    chunked = [k for k in ("chunks", "scheduler", "n_jobs") if k in given]
    if chunked:
        raise InvalidInputError("stages are kept whole in memory: --steps does not take --chunks, --scheduler or --jobs")
    unknown = [k for k in given if k not in accepted]
    if unknown:
        raise InvalidInputError(f"unknown option(s) {', '.join(map(repr, unknown))} for the volume mid-surface")
    return volume_stages(volume, **given)


def save_steps(stages: VolumeStages, path: str | Path) -> list[Path]:
    """Write every stage next to ``path`` as ``STEM_<k>_<stage><suffix>``.

    Parameters
    ----------
    stages : VolumeStages
    path : str or path
        Its suffix picks the format (``.ply``, ``.vtk``, ``.obj``, ``.json``,
        ``.npz``); its stem prefixes the stage files.

    Returns
    -------
    list of Path
        The files written, in stage order.

    Raises
    ------
    UnsupportedFormatError
        For another suffix.
    """
    from medialaxis.errors import UnsupportedFormatError

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in STEP_SUFFIXES:
        raise UnsupportedFormatError(f"stages are written as {', '.join(STEP_SUFFIXES)}, got {str(path)!r}")
    written = []
    for k, (name, axis) in enumerate(stages.steps.items(), start=1):
        out = path.with_name(f"{path.stem}_{k}_{name}{suffix}")
        axis.save(out)
        written.append(out)
    return written
