"""Moved to :mod:`medialaxis.datasets.meshes`; kept for the docstring examples of ``flow.py``,
``flow_frames.py`` and ``deform.py`` until they import from :mod:`medialaxis.datasets` (then delete
this module)."""

from medialaxis.datasets.meshes import capsules_mesh

__all__ = ["capsules_mesh"]
