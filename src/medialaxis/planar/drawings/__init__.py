"""Drawings read as they are painted: SVG (svgelements) and DXF (ezdxf), over regions of rings and strokes."""

from __future__ import annotations

__all__: list[str] = []
