"""Demo case for ``medialaxis demo``: compare the bundled Kimia shapes."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["DEMO_CASES"]

SAMPLES = ("kimia_class1_01.png", "kimia_class3_05.png", "kimia_class5_03.png", "kimia_class8_05.png")


def _compare_case(outdir: Path) -> str:
    import numpy as np
    from PIL import Image

    import medialaxis as mx
    from medialaxis.compare.cli import save_match_picture
    from medialaxis.compare.distance import match_tour, shape_signature
    from medialaxis.compare.signature import DEFAULT_PRUNE
    from medialaxis.demo import data_path

    t0 = time.perf_counter()
    masks = [np.asarray(Image.open(data_path(name)).convert("L")) > 127 for name in SAMPLES]
    turned = np.rot90(masks[0])  # the first shape, turned by 90 degrees
    axes = [mx.medial_axis(m) for m in [*masks, turned]]
    D = mx.distance_matrix([shape_signature(a) for a in axes], n_jobs=1)
    distance, points_a, points_b = match_tour(axes[0], axes[-1])
    save_match_picture(axes[0], axes[-1], points_a, points_b, outdir / "compare_match.png", prune=DEFAULT_PRUNE,
                       titles=(SAMPLES[0], SAMPLES[0] + " turned"), distance=distance)
    elapsed = time.perf_counter() - t0
    nearest = int(np.argsort(D[-1])[1])
    return (
        f"compare: turned {SAMPLES[0]} is at {D[-1, 0]:.3g} from itself, nearest other "
        f"{min(D[-1, 1:-1]):.3g}; nearest shape {SAMPLES[nearest] if nearest < len(SAMPLES) else '?'}; "
        f"compare_match.png, {elapsed * 1000:.0f} ms"
    )


#: (title, runner) pairs picked up by :func:`medialaxis.demo.run_demo`.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [("compare", _compare_case)]
