"""The DXF reader on every DXF file of the ezdxf repository: a result or a clear error, never a crash.

Run:  .venv/bin/python benchmarks/bench_dxf_examples.py [GIT_DIR] [--no-axis] [--match TEXT]

GIT_DIR is a clone (bare or not) of https://github.com/mozman/ezdxf; default
the environment variable MEDIALAXIS_EZDXF_GIT, else
/work/.mirror/mozman+ezdxf/repo. Every ``*.dxf`` file of its HEAD
(examples_dxf/, integration_tests/data/, exploration/, docs/, ...) is
extracted once into a cache folder (``$XDG_CACHE_HOME/medialaxis/ezdxf-dxf/<commit>``)
and read with :func:`medialaxis.planar.drawings.dxf.read_dxf` (every layer shown);
when the read succeeds, :func:`medialaxis.planar.pipeline.voronoi_medial_axis`
runs on the region.

What it measures: the outcome of each file and the seconds spent reading and
computing the axis. A file ends in one of three ways:

- ``ok``: a region (area, loops read, skipped entity types) and its axis;
- a clear error: one of medialaxis's exceptions (``MedialAxisError``), with
  its one-line message (an open drawing, text only, an ACIS body, ...);
- a crash: any other exception, a bug of the reader. The totals line counts
  them; the number must be 0.

There is no peer tool reading DXF regions to compare with; the figure is the
count of crashes (0) and the time per file.
"""

from __future__ import annotations

import argparse
import logging
import os
import subprocess
import sys
import time
import traceback
from pathlib import Path

from medialaxis.errors import MedialAxisError
from medialaxis.planar.drawings.dxf import read_dxf
from medialaxis.planar.pipeline import voronoi_medial_axis

DEFAULT_GIT = "/work/.mirror/mozman+ezdxf/repo"


def extract(git_dir: Path) -> tuple[str, Path, list[Path]]:
    """Every .dxf of HEAD written once under the cache; (commit, folder, files)."""
    commit = subprocess.run(
        ["git", "--git-dir", str(git_dir), "rev-parse", "HEAD"], check=True, capture_output=True, text=True
    ).stdout.strip()
    cache = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "medialaxis" / "ezdxf-dxf" / commit
    listing = subprocess.run(
        ["git", "--git-dir", str(git_dir), "ls-tree", "-r", "--name-only", "-z", "HEAD"],
        check=True,
        capture_output=True,
    ).stdout.decode()
    names = sorted(n for n in listing.split("\0") if n.lower().endswith(".dxf"))
    files = []
    for name in names:
        target = cache / name
        if not target.exists():
            data = subprocess.run(
                ["git", "--git-dir", str(git_dir), "show", f"HEAD:{name}"], check=True, capture_output=True
            ).stdout
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        files.append(target)
    return commit, cache, files


def one_line(exc: BaseException, cache: Path, width: int = 150) -> str:
    text = " ".join(str(exc).replace(f"{cache}{os.sep}", "").split())
    return text if len(text) <= width else text[: width - 3] + "..."


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("git_dir", nargs="?", default=os.environ.get("MEDIALAXIS_EZDXF_GIT", DEFAULT_GIT))
    parser.add_argument("--no-axis", action="store_true", help="read the files only, skip the medial axis")
    parser.add_argument("--match", default="", help="only files whose path contains this text")
    parser.add_argument("--traceback", action="store_true", help="print the traceback of each crash")
    args = parser.parse_args(argv)

    logging.getLogger("ezdxf").setLevel(logging.ERROR)  # ezdxf's notes on damaged files, not our outcome
    commit, cache, files = extract(Path(args.git_dir))
    files = [f for f in files if args.match in str(f.relative_to(cache))]
    print(f"ezdxf {commit[:12]}: {len(files)} DXF files in {cache}\n")
    print(f"{'file':58} {'read s':>7} {'axis s':>7}  outcome")
    totals = {"ok": 0, "clear error": 0, "crash": 0}
    started = time.perf_counter()
    for file in files:
        name = str(file.relative_to(cache))
        t0 = time.perf_counter()
        axis_seconds = ""
        try:
            region, info = read_dxf(file)
            read_seconds = time.perf_counter() - t0
            outcome = f"ok: area {region.area:.6g}, {info['loops']} loops"
            if info["skipped"]:
                outcome += ", skipped " + " ".join(f"{k}:{v}" for k, v in info["skipped"].items())
            if not args.no_axis:
                t1 = time.perf_counter()
                try:
                    ma = voronoi_medial_axis(region)
                    outcome += f"; axis {len(ma.points)} points"
                except MedialAxisError as exc:
                    outcome += f"; axis: {type(exc).__name__}: {one_line(exc, cache)}"
                axis_seconds = f"{time.perf_counter() - t1:7.2f}"
            totals["ok"] += 1
        except MedialAxisError as exc:
            read_seconds = time.perf_counter() - t0
            outcome = f"{type(exc).__name__}: {one_line(exc, cache)}"
            totals["clear error"] += 1
        except Exception as exc:  # noqa: BLE001 - counted as the reader's bug
            read_seconds = time.perf_counter() - t0
            outcome = f"CRASH {type(exc).__name__}: {one_line(exc, cache)}"
            totals["crash"] += 1
            if args.traceback:
                traceback.print_exc()
        print(f"{name:58} {read_seconds:7.2f} {axis_seconds:>7}  {outcome}", flush=True)
    print(
        f"\ntotals: {len(files)} files, ok {totals['ok']}, clear error {totals['clear error']}, "
        f"crash {totals['crash']} (must be 0); {time.perf_counter() - started:.1f} s"
    )
    return 1 if totals["crash"] else 0


if __name__ == "__main__":
    sys.exit(main())
