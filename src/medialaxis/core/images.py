"""Opening image files with Pillow without touching its process-wide settings."""

from __future__ import annotations

import os
import threading
from typing import Any

__all__ = ["open_image"]

_PIL_LOCK = threading.Lock()


def open_image(path: str | os.PathLike[str], max_pixels: int | None) -> Any:
    """``PIL.Image.open(path)`` with Pillow's decompression-bomb limit set to ``max_pixels`` for the call.

    Pillow checks the pixel count when it opens a file (a warning above the
    limit, an error above twice it); the limit is put
    back at once (under a lock, for threads), so other users of Pillow in
    the process keep theirs. ``None`` lifts the limit for the opening only,
    for callers that check the size themselves before decoding.
    """
    from PIL import Image

    with _PIL_LOCK:
        previous = Image.MAX_IMAGE_PIXELS
        Image.MAX_IMAGE_PIXELS = None if max_pixels is None else max(1, int(max_pixels))
        try:
            return Image.open(path)
        finally:
            Image.MAX_IMAGE_PIXELS = previous
