"""The shape-distance terms moved to ``benchmarks/research/`` (issue 17) stay tested: ``bench_compare`` reports them."""

import sys
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"
if str(BENCHMARKS) not in sys.path:
    sys.path.insert(0, str(BENCHMARKS))
