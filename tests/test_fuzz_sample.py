"""Fast samples of the fuzz harness (benchmarks/fuzz.py).

Two samples of 100 mutated files over every input format, two fixed seeds,
each on two workers: no run may crash or hang, every format must have been
run, and every unmutated seed file must give ``ok`` (so the sample is not
vacuous). Failures print the crash list with the kept inputs and reproduction
commands. The inputs that found bugs are named regressions
(``tests/test_fuzz_regressions.py``); the large random budget is
``benchmarks/fuzz.py`` (``--count 10000`` per seed, the README's figures).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _load_harness():
    name = "medialaxis_bench_fuzz"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / "fuzz.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses look their module up by name
    spec.loader.exec_module(module)
    return module


fuzz = _load_harness()


def _report(summary) -> str:
    lines = []
    for what in ("crashes", "hangs"):
        for e in summary[what]:
            lines.append(
                f"{e['status']}: {e['type']} in {','.join(e['formats'])} ({','.join(e['kinds'])}): "
                f"{str(e['message'])[:200]}\n    at {e['last_frame']} [{e.get('medialaxis_frame') or ''}]\n"
                f"    repro: {e['repro']}"
            )
    return "\n".join(lines)


def _check(summary, formats) -> None:
    bad_seeds = {f: k for f, k in summary["seeds"].items() if any(s != "ok" for s in k.values())}
    assert not bad_seeds, f"unmutated seed files do not all run ok: {bad_seeds}\n{_report(summary)}"
    assert set(summary["formats"]) == set(formats)
    for fmt, row in summary["formats"].items():
        assert row["files"] >= 1 and row["runs"] >= 1, f"format {fmt} was not run: {row}"
        assert row["ok"] + row["clean"] + row["crash"] + row["hang"] == row["runs"]
    assert summary["n_crashes"] == 0 and summary["n_hangs"] == 0, (
        f"{summary['n_crashes']} crashing and {summary['n_hangs']} hanging runs:\n{_report(summary)}"
    )


@pytest.fixture(scope="module")
def keep_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz-crashes")


@pytest.mark.parametrize("seed", [20240611, 7])
def test_fuzz_sample(keep_dir, seed):
    """100 mutated files (5 a format) on two workers, the pool's path (about 12 s; ``benchmarks/fuzz.py`` runs thousands)."""
    formats = list(fuzz.FORMATS)
    summary = fuzz.run_fuzz(100, seed=seed, jobs=2, timeout=20.0, keep=keep_dir)
    assert sum(row["files"] for row in summary["formats"].values()) == 100
    # the mutations reach past the parsers: some mutated files still compute, some are refused
    total_ok = sum(row["ok"] for row in summary["formats"].values())
    total_clean = sum(row["clean"] for row in summary["formats"].values())
    assert total_ok > 0 and total_clean > 0
    _check(summary, formats)


def test_mutations_are_seeded():
    """The same seed gives the same mutated bytes; another seed different ones."""
    import numpy as np

    data = bytes(range(256)) * 4
    a = [fuzz.mutate(data, "nii", np.random.default_rng(s)) for s in range(10)]
    b = [fuzz.mutate(data, "nii", np.random.default_rng(s)) for s in range(10)]
    c = [fuzz.mutate(data, "nii", np.random.default_rng(s)) for s in range(10, 20)]
    assert a == b and a != c
    text = b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n"
    outs = {fuzz.mutate(text, "off", np.random.default_rng(s))[0] for s in range(30)}
    assert len(outs) > 20 and text not in outs


def test_harness_detects_crash_hang_and_death(tmp_path):
    """The worker reports an exception as a crash, and a hang or a fatal signal is caught and survived."""
    worker = fuzz.Worker(tmp_path / "w", memory_limit_kib=None)
    try:
        crash = worker.run({"kind": "selftest", "what": "crash"}, 10.0)
        assert crash["status"] == "crash" and crash["type"] == "IndexError"
        hang = worker.run({"kind": "selftest", "what": "hang"}, 1.5)
        assert hang["status"] == "hang" and "worker_main" in hang["last_frame"]
        died = worker.run({"kind": "selftest", "what": "segv"}, 10.0)
        assert died["status"] == "crash" and died["type"].startswith("WorkerDied")
        again = worker.run({"kind": "selftest", "what": "crash"}, 10.0)  # restarted
        assert again["status"] == "crash" and worker.starts == 3
    finally:
        worker.stop()
