"""Fuzz harness: mutated input files through the API and the command line.

Run::

    .venv/bin/python benchmarks/fuzz.py [--count 10000] [--seed 0] [--timeout 20]
        [--formats png,off,...] [--jobs 2] [--keep DIR]

What it does:

1. Builds one tiny valid seed file per input format in a temporary folder
   (64 x 64 images, meshes of at most 128 faces, 24^3 volumes holding a thin
   plate, and saved results ``.json``/``.npz`` of a small planar axis); the
   formats are listed in ``FORMATS``.
2. Derives ``--count`` mutated files from them, spread evenly over the
   formats, with ``np.random.default_rng(seed)``: bit flips, overwrites with
   interesting bytes / integers / floats, truncation, chunk deletion,
   duplication and insertion (offsets biased towards the header), PNG chunk
   CRCs recomputed half of the time and ``.npz`` members mutated and zipped
   again half of the time (so the decoders get past their checksums); for
   text formats (and the text headers of NRRD, binary PLY and ``.npy``)
   token-level mutations: numbers replaced by huge / NaN / negative values,
   huge or off-by-one indices, deleted, duplicated, swapped or cut lines,
   JSON values replaced by values of another type. The same seed gives the
   same files whatever ``--jobs``.
3. Runs each file, in worker subprocesses, through
   ``mx.medial_axis(path)`` (meshes with ``samples=1000`` so a valid run is
   fast; ``.raw`` with ``raw_shape``/``raw_dtype``), an extra method
   (``method="flow"`` for meshes, ``method="voxels"`` for volumes),
   ``mx.shape_distance(path, path)`` for planar files, and
   ``medialaxis.cli.main(["compute", path, "-o", out.json])``; each run has
   its own wall-clock limit (``--timeout``).
4. Classifies every run:

   * ``ok``: returned a result (CLI: exit 0, at most one stderr line);
   * ``clean``: raised a :class:`medialaxis.MedialAxisError` (CLI: exit 1 or 2
     with exactly one stderr line and no traceback);
   * ``crash``: any other exception, the worker dying (signal), the worker
     passing the memory limit (``--memory-limit``, MiB of RSS), a CLI exit
     code other than 0/1/2, an exception escaping ``main``, or a CLI
     stderr of several lines or with a traceback (e.g. printed warnings);
   * ``hang``: the time limit was hit; the worker is killed (its Python
     stack, dumped by :mod:`faulthandler` just before, says where it was)
     and restarted.

   Peak memory is the worker's peak RSS during the run (``VmHWM`` of
   ``/proc/self/status``, reset before each run through
   ``/proc/self/clear_refs``; ``getrusage`` where that is missing), together
   with the RSS the parent polls (psutil when installed).
   A worker serves many runs; process-global settings a run changes (PIL's
   decompression-bomb limit, NumPy error state, warning filters, logging,
   cwd, environment, ``sys.path``...) are reported and put back after each
   run, so every run starts from the same state.
5. Prints a table per format (files, runs, ok, clean errors, crashes, hangs,
   max seconds of a run, peak MiB), checks that every unmutated seed runs
   ``ok``, and lists the distinct crashes and hangs, deduplicated by
   (exception type, last traceback frame), with the deepest medialaxis frame,
   whether it happens again in a fresh worker (``--no-confirm`` skips that)
   and a reproduction command. Also listed, not counted as crashes: clean
   errors whose message names an internal exception (``InputFileError:
   ... IndexError: ...``, ``No module named ...``) and the global settings
   runs changed. Every crashing or hanging input is copied to ``--keep DIR``
   (with a ``.txt`` record next to it, and ``summary.json``).

Exit status 1 if any crash or hang (seeds included), else 0.
:func:`run_fuzz` returns the summary as a dict (used by
``tests/test_fuzz_sample.py``). Workers run with one numba/BLAS thread.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import traceback
import zipfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
HERE = Path(__file__).resolve()

# ---------------------------------------------------------------- formats
#: name -> (extension, domain, kind of mutations). Kinds: "text" (token-level
#: and byte mutations), "header" (text header + binary body), "binary".
FORMATS: dict[str, tuple[str, str, str]] = {
    "png": (".png", "planar", "binary"),
    "tiff": (".tif", "planar", "binary"),
    "tiff3d": (".tiff", "volume", "binary"),
    "jpeg": (".jpg", "planar", "binary"),
    "svg": (".svg", "planar", "text"),
    "geojson": (".geojson", "planar", "text"),
    "wkt": (".wkt", "planar", "text"),
    "off": (".off", "mesh", "text"),
    "ply_ascii": (".ply", "mesh", "text"),
    "ply_binary": (".ply", "mesh", "header"),
    "stl_ascii": (".stl", "mesh", "text"),
    "stl_binary": (".stl", "mesh", "binary"),
    "obj": (".obj", "mesh", "text"),
    "nrrd": (".nrrd", "volume", "header"),
    "nii": (".nii", "volume", "binary"),
    "raw": (".raw", "volume", "binary"),
    "npy2d": (".npy", "planar", "header"),
    "npy3d": (".npy", "volume", "header"),
    "json": (".json", "result", "text"),
    "npz": (".npz", "result", "binary"),
}

RAW_SHAPE = (24, 24, 24)
RAW_DTYPE = "uint8"
MESH_SAMPLES = 1000  # smallest value the mesh Voronoi method accepts; keeps a valid run ~0.2 s

STATUSES = ("ok", "clean", "crash", "hang")

#: A clean error whose message names one of these wraps an internal failure (a bug reported as a bad file);
#: listed apart as "leaks", not counted as crashes.
_LEAK_RE = re.compile(r"\b(ModuleNotFoundError|No module named|ImportError|IndexError|KeyError|AttributeError|"
                      r"TypeError|"
                      r"ZeroDivisionError|AssertionError|RecursionError|UnboundLocalError|NameError|"
                      r"NotImplementedError|OverflowError|MemoryError|LinAlgError|QhullError)\b")


def _tally(entry: dict, fmt: str, kind: str) -> None:
    """Count one more run in ``entry`` and note its format and kind of run (each once)."""
    entry["count"] += 1
    if fmt not in entry["formats"]:
        entry["formats"].append(fmt)
    if kind not in entry["kinds"]:
        entry["kinds"].append(kind)


def _normalize(message: str) -> str:
    """A message with paths, numbers and quoted values blanked, for grouping."""
    m = re.sub(r"'[^']*'|\"[^\"]*\"", "'…'", str(message))
    m = re.sub(r"(?<![A-Za-z_])[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?", "N", m)
    return m[:160]


def _mask2d() -> np.ndarray:
    """64 x 64 uint8: a rectangle with a notch and a round bump (foreground 255)."""
    yy, xx = np.mgrid[:64, :64]
    m = np.zeros((64, 64), np.uint8)
    m[18:46, 10:50] = 255
    m[((yy - 32) ** 2 + (xx - 50) ** 2) < 100] = 255
    m[28:36, 10:22] = 0
    return m


def _plate() -> np.ndarray:
    """24^3 uint8 volume holding a 4-voxel thick plate (value 200)."""
    v = np.zeros(RAW_SHAPE, np.uint8)
    v[10:14, 4:20, 4:20] = 200
    return v


_SVG = """<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64" viewBox="0 0 64 64">
  <path d="M 8 8 L 56 8 L 56 30 Q 40 44 32 56 C 24 50 12 44 8 30 Z"/>
  <rect x="20" y="14" width="10" height="8"/>
</svg>
"""

_GEOJSON = {
    "type": "FeatureCollection",
    "features": [
        {
            "type": "Feature",
            "properties": {"name": "plate"},
            "geometry": {
                "type": "Polygon",
                "coordinates": [
                    [[0, 0], [60, 0], [60, 30], [30, 45], [0, 30], [0, 0]],
                    [[10, 8], [20, 8], [20, 16], [10, 16], [10, 8]],
                ],
            },
        }
    ],
}

_WKT = "POLYGON ((0 0, 50 0, 50 12, 20 12, 20 40, 0 40, 0 0), (5 5, 10 5, 10 10, 5 10, 5 5))\n"


def build_seeds(folder: str | os.PathLike[str], formats: list[str] | None = None) -> dict[str, Path]:
    """Write one small valid file per format into ``folder``; return ``{format: path}``."""
    import nibabel as nib
    import nrrd
    import tifffile
    import trimesh
    from PIL import Image

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    formats = list(FORMATS) if formats is None else formats
    mask, plate = _mask2d(), _plate()
    meshes = {
        "ico": trimesh.creation.icosphere(subdivisions=1),  # 80 faces
        "box": trimesh.creation.box(extents=(2.0, 1.0, 0.6)),  # 12 faces
        "capsule": trimesh.creation.capsule(height=1.0, radius=0.4, count=[8, 8]),  # 128 faces
    }
    paths: dict[str, Path] = {}
    for fmt in formats:
        ext = FORMATS[fmt][0]
        p = folder / f"seed_{fmt}{ext}"
        if fmt == "png":
            Image.fromarray(mask, "L").save(p)
        elif fmt == "tiff":
            tifffile.imwrite(p, mask)
        elif fmt == "tiff3d":
            tifffile.imwrite(p, plate)
        elif fmt == "jpeg":
            Image.fromarray(mask, "L").save(p, quality=90)
        elif fmt == "svg":
            p.write_text(_SVG)
        elif fmt == "geojson":
            p.write_text(json.dumps(_GEOJSON, indent=1) + "\n")
        elif fmt == "wkt":
            p.write_text(_WKT)
        elif fmt == "off":
            meshes["ico"].export(p, file_type="off")
        elif fmt == "ply_ascii":
            meshes["capsule"].export(p, file_type="ply", encoding="ascii")
        elif fmt == "ply_binary":
            meshes["ico"].export(p, file_type="ply", encoding="binary")
        elif fmt == "stl_ascii":
            meshes["box"].export(p, file_type="stl_ascii")
        elif fmt == "stl_binary":
            meshes["capsule"].export(p, file_type="stl")
        elif fmt == "obj":
            meshes["box"].export(p, file_type="obj")
        elif fmt == "nrrd":
            nrrd.write(str(p), plate, header={"encoding": "raw", "spacings": [1.0, 1.0, 1.0]})
        elif fmt == "nii":
            nib.save(nib.Nifti1Image(plate, np.eye(4)), str(p))
        elif fmt == "raw":
            plate.tofile(p)
        elif fmt == "npy2d":
            np.save(p, mask > 0)
        elif fmt == "npy3d":
            np.save(p, plate)
        elif fmt in ("json", "npz"):
            import medialaxis as mx

            mx.medial_axis(mask > 0).save(p)
        else:  # pragma: no cover
            raise ValueError(f"unknown format {fmt!r}")
        paths[fmt] = p
    return paths


# -------------------------------------------------------------- mutations
INTERESTING_BYTES = (0x00, 0x01, 0x7F, 0x80, 0xFF, 0x20, 0x0A, 0x2D, 0x30, 0x39)
INTERESTING_INTS = (0, 1, -1, 2, 3, 0x7F, 0x80, 0xFF, 0x7FFF, 0x8000, 0xFFFF, 0x7FFFFFFF, 0x80000000,
                    0xFFFFFFFF, 0x7FFFFFFFFFFFFFFF, 2**63, 2**64 - 1, 65536, 1 << 20, 1 << 30, 10**9)
INTERESTING_FLOATS = (float("nan"), float("inf"), float("-inf"), 1e38, -1e38, 1e308, -0.0, 1e-45, 1e-320, 3.4e38)
TEXT_NUMBERS = ("nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308", "1e999", "1e-320", "0", "-0",
                "-1", "-2", "1", "2", "3", "0.0", "-999999", "2147483647", "2147483648", "-2147483649",
                "4294967296", "9223372036854775808", "99999999999999999999999", "1.5", "-0.5", "", "x", "0x10",
                "1e5", "65536", "1_000", "٣", "--1", "1.2.3", "+", "e", "999999999")
JUNK_LINES = ("", " ", "\t", "#", "nan nan nan", "f 1 2 3", "v 1e308 -1e308 nan", "3 0 1 99999999",
              "element vertex 99999999", "end_header", "facet normal 0 0 0", "endsolid", "}", "{", "]", "[",
              "<path d=\"M 0 0 L\"/>", "POLYGON EMPTY", "\x00\x00", "\xff\xfe", "sizes: 99999 99999 99999",
              "type: double", "encoding: gzip", "dimension: 7", "data file: /etc/passwd", "<!ENTITY a \"aaaa\">")
_NUM_RE = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_INT_RE = re.compile(rb"(?<![\d.eE+-])\d+(?![\d.eE])")
_WORD_RE = re.compile(rb"[A-Za-z_]{2,}")


def _header_len(fmt: str, data: bytes) -> int:
    """Length of the text header of a "header" format (the rest is binary)."""
    if fmt == "nrrd":
        i = data.find(b"\n\n")
        return len(data) if i < 0 else i + 2
    if fmt == "ply_binary":
        i = data.find(b"end_header")
        return len(data) if i < 0 else i + len(b"end_header\n")
    if fmt.startswith("npy"):
        i = data.find(b"\n", 10)
        return min(len(data), 128) if i < 0 else i + 1
    return len(data)


def _pos(rng: np.random.Generator, n: int, head: int = 256) -> int:
    """A byte offset in [0, n), biased towards the first ``head`` bytes (headers)."""
    if n <= 0:
        return 0
    if rng.random() < 0.5:
        return int(rng.integers(0, min(n, head)))
    return int(rng.integers(0, n))


def _chunk_len(rng: np.random.Generator, n: int) -> int:
    return max(1, min(n, int(np.exp(rng.uniform(0, np.log(max(2, min(n, 4096))))))))


def _pack_interesting(rng: np.random.Generator) -> bytes:
    order = "<" if rng.random() < 0.7 else ">"
    if rng.random() < 0.6:
        v = int(rng.choice(INTERESTING_INTS))
        size = int(rng.choice([1, 2, 4, 8]))
        return (v % (1 << (8 * size))).to_bytes(size, "little" if order == "<" else "big")
    v = float(rng.choice(INTERESTING_FLOATS))
    with np.errstate(over="ignore"):  # 1e308 as float32 is inf: fine
        return np.array([v], dtype=order + ("f4" if rng.random() < 0.5 else "f8")).tobytes()


def mutate_bytes(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """One byte-level mutation."""
    b = bytearray(data)
    n = len(b)
    op = str(rng.choice(["bitflip", "byte", "value", "truncate", "delete", "duplicate", "insert", "overwrite"]))
    if n == 0:
        op = "insert"
    if op == "bitflip":
        for _ in range(int(rng.integers(1, 9))):
            i = _pos(rng, n)
            b[i] ^= 1 << int(rng.integers(0, 8))
    elif op == "byte":
        for _ in range(int(rng.integers(1, 5))):
            b[_pos(rng, n)] = int(rng.choice(INTERESTING_BYTES)) if rng.random() < 0.7 else int(rng.integers(0, 256))
    elif op == "value":
        v = _pack_interesting(rng)
        i = _pos(rng, n)
        b[i : i + len(v)] = v
    elif op == "truncate":
        b = b[: _pos(rng, n, head=1024)]
    elif op == "delete":
        i = _pos(rng, n)
        del b[i : i + _chunk_len(rng, n - i)]
    elif op == "duplicate":
        i = _pos(rng, n)
        chunk = b[i : i + _chunk_len(rng, n - i)]
        b[i:i] = chunk * int(rng.choice([1, 1, 2, 16]))
    elif op == "insert":
        k = _chunk_len(rng, 512)
        r = rng.random()
        if r < 0.4:
            chunk = rng.integers(0, 256, k, dtype=np.uint8).tobytes()
        elif r < 0.7:
            chunk = bytes([int(rng.choice(INTERESTING_BYTES))]) * k
        else:
            chunk = _pack_interesting(rng) * int(rng.integers(1, 8))
        i = _pos(rng, n + 1)
        b[i:i] = chunk
    else:  # overwrite a chunk with another part of the file
        i, j = _pos(rng, n), int(rng.integers(0, n))
        k = _chunk_len(rng, n - max(i, j))
        b[i : i + k] = data[j : j + k]
    return bytes(b), op


def _json_mutate(text: bytes, rng: np.random.Generator) -> bytes | None:
    """Replace one node of a JSON document by a value of another kind."""
    try:
        doc = json.loads(text)
    except (ValueError, UnicodeDecodeError):
        return None
    slots: list[tuple[Any, Any]] = []

    def walk(node: Any) -> None:
        if len(slots) > 5000:
            return
        if isinstance(node, dict):
            for k, v in node.items():
                slots.append((node, k))
                walk(v)
        elif isinstance(node, list):
            for i, v in enumerate(node):
                slots.append((node, i))
                walk(v)

    walk(doc)
    if not slots:
        return None
    parent, key = slots[int(rng.integers(len(slots)))]
    old = parent[key]
    choices: list[Any] = [None, [], {}, "x", "", -1, 0, 1e308, float("nan"), float("inf"), 2**63, True,
                          [[0, 0]], [old, old], [float("nan")] * 3, {"type": "Polygon", "coordinates": [[]]}]
    if isinstance(old, list) and old:
        choices += [old[:1], old[: len(old) // 2], old[::-1], old + old, old[0]]
    if isinstance(old, (int, float)) and not isinstance(old, bool):
        choices += [-old, old * 1e12, int(old) + 1, str(old)]
    action = rng.random()
    if (action < 0.15 and isinstance(parent, dict)) or (action < 0.25 and isinstance(parent, list)):
        del parent[key]
    else:
        parent[key] = choices[int(rng.integers(len(choices)))]
    return json.dumps(doc).encode()


def mutate_text(text: bytes, rng: np.random.Generator, fmt: str) -> tuple[bytes, str]:
    """One token- or line-level mutation of a text (kept as bytes, latin-1 safe)."""
    ops = ["number", "number", "index", "scale", "nudge", "nudge", "copy_number", "delete_line", "duplicate_line",
           "swap_lines", "cut_line", "insert_line", "word", "delete_token"]
    if fmt in ("json", "geojson"):
        ops += ["json", "json", "json"]
    op = str(rng.choice(ops))
    if op == "json":
        out = _json_mutate(text, rng)
        if out is not None:
            return out, op
        op = "number"
    if op in ("number", "index", "scale", "nudge", "copy_number"):
        matches = list((_INT_RE if op == "index" else _NUM_RE).finditer(text))
        if matches:
            out = bytearray(text)
            picks = rng.choice(len(matches), size=min(len(matches), int(rng.integers(1, 4))), replace=False)
            for m in sorted((matches[int(k)] for k in picks), key=lambda m: -m.start()):
                if op == "number":
                    new = str(rng.choice(TEXT_NUMBERS)).encode("utf-8")
                elif op == "index":
                    try:
                        v = int(m.group())
                    except ValueError:
                        v = 0
                    cand = [v + 1, v - 1, -1, -v - 1, 2**31, 2**31 - 1, 2**32, 2**63, 2**64, 10**30, v * 1000, 0]
                    new = str(cand[int(rng.integers(len(cand)))]).encode()
                elif op == "copy_number":  # another number of the file: coincident points, repeated indices
                    new = matches[int(rng.integers(len(matches)))].group()
                else:
                    try:
                        v = float(m.group())
                    except ValueError:
                        v = 1.0
                    if op == "nudge":  # small geometric change: the file stays well-formed
                        v = v * float(rng.uniform(0.5, 1.5)) + float(rng.normal(0, 1e-3))
                        new = f"{v:.6f}".encode()
                    else:
                        new = repr(v * float(rng.choice([-1.0, 1e10, -1e10, 1e300, 1e-300, 0.0]))).encode()
                out[m.start() : m.end()] = new
            return bytes(out), op
        op = "delete_line"
    lines = text.split(b"\n")
    if op == "delete_line" and len(lines) > 1:
        i = int(rng.integers(len(lines)))
        del lines[i : i + int(rng.choice([1, 1, 1, 2, 5]))]
    elif op == "duplicate_line":
        i = int(rng.integers(len(lines)))
        lines[i:i] = [lines[i]] * int(rng.choice([1, 1, 3, 50]))
    elif op == "swap_lines" and len(lines) > 1:
        i, j = rng.choice(len(lines), 2, replace=False)
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "cut_line":
        i = int(rng.integers(len(lines)))
        lines[i] = lines[i][: int(rng.integers(0, len(lines[i]) + 1))]
        if rng.random() < 0.5:
            lines = lines[: i + 1]
    elif op == "insert_line":
        lines.insert(int(rng.integers(len(lines) + 1)), str(rng.choice(JUNK_LINES)).encode("latin-1"))
    elif op == "word":
        words = list(_WORD_RE.finditer(text))
        if words:
            m = words[int(rng.integers(len(words)))]
            other = words[int(rng.integers(len(words)))].group()
            new = [other, m.group().upper(), m.group()[:-1], b"", b"nan", m.group() * 2][int(rng.integers(6))]
            return text[: m.start()] + new + text[m.end() :], op
    elif op == "delete_token":
        toks = list(re.finditer(rb"\S+", text))
        if toks:
            m = toks[int(rng.integers(len(toks)))]
            return text[: m.start()] + text[m.end() :], op
    return b"\n".join(lines), op


def _fix_png_crcs(data: bytes) -> bytes:
    """Recompute the CRC of every complete PNG chunk (so decoders look past them)."""
    b = bytearray(data)
    i = 8
    while i + 12 <= len(b):
        length = int.from_bytes(b[i : i + 4], "big")
        end = i + 8 + length
        if end + 4 > len(b):
            break
        b[end : end + 4] = zlib.crc32(bytes(b[i + 4 : end])).to_bytes(4, "big")
        i = end + 4
    return bytes(b)


def _mutate_npz_member(data: bytes, rng: np.random.Generator) -> tuple[bytes, str] | None:
    """Mutate one member of an ``.npz`` (an ``.npy`` inside a zip) and zip it again."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            members = [(info.filename, zf.read(info.filename)) for info in zf.infolist()]
    except Exception:  # noqa: BLE001 - an earlier mutation broke the zip
        return None
    if not members:
        return None
    k = int(rng.integers(len(members)))
    name, body = members[k]
    if rng.random() < 0.5:
        h = _header_len("npy", body)
        head, op = mutate_text(body[:h], rng, "npy")
        body = head + body[h:]
    else:
        body, op = mutate_bytes(body, rng)
    members[k] = (name, body)
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_STORED) as zf:
        for nm, bd in members:
            zf.writestr(nm, bd)
    return out.getvalue(), f"member:{name}:{op}"


def mutate(data: bytes, fmt: str, rng: np.random.Generator) -> tuple[bytes, list[str]]:
    """1 to 3 stacked mutations suited to ``fmt``; returns the data and the operations applied."""
    kind = FORMATS[fmt][2]
    original = data
    ops: list[str] = []
    for _ in range(int(rng.choice([1, 1, 1, 1, 2, 2, 3]))):
        r = rng.random()
        if fmt == "npz" and r < 0.5:
            res = _mutate_npz_member(data, rng)
            if res is not None:
                data, op = res
                ops.append(op)
                continue
        if kind == "text" and r < 0.75:
            data, op = mutate_text(data, rng, fmt)
        elif kind == "header" and r < 0.6:
            h = _header_len(fmt, data)
            head, op = mutate_text(data[:h], rng, fmt)
            data = head + data[h:]
            op = "header:" + op
        else:
            data, op = mutate_bytes(data, rng)
        ops.append(op)
    if fmt == "png" and rng.random() < 0.5:
        data = _fix_png_crcs(data)
        ops.append("fix_crc")
    while data == original:  # a no-op (a number replaced by itself, identical lines swapped): flip a bit
        data, op = mutate_bytes(data, rng)
        ops.append(op)
    return data, ops


# ------------------------------------------------------------------ runs
def run_kinds(fmt: str, planar_results: bool = True) -> list[str]:
    """The runs of one file of format ``fmt``."""
    domain = FORMATS[fmt][1]
    kinds = ["api"]
    if domain == "mesh":
        kinds.append("flow")
    elif domain == "volume":
        kinds.append("voxels")
    if domain == "planar" or (domain == "result" and planar_results):
        kinds.append("distance")
    kinds.append("cli")
    return kinds


def _api_options(fmt: str, kind: str, mesh_samples: int | None) -> dict[str, Any]:
    opts: dict[str, Any] = {}
    domain = FORMATS[fmt][1]
    if kind == "flow":
        opts["method"] = "flow"
    elif kind == "voxels":
        opts["method"] = "voxels"
    elif kind == "api" and domain == "mesh" and mesh_samples is not None:
        opts["samples"] = mesh_samples
    if fmt == "raw" and kind in ("api", "voxels"):
        opts.update(raw_shape=list(RAW_SHAPE), raw_dtype=RAW_DTYPE)
    return opts


def _cli_args(fmt: str, mesh_samples: int | None) -> list[str]:
    args: list[str] = []
    if FORMATS[fmt][1] == "mesh" and mesh_samples is not None:
        args += ["--option", f"samples={mesh_samples}"]
    if fmt == "raw":
        args += ["--option", f"raw_shape={json.dumps(list(RAW_SHAPE))}", "--option", f"raw_dtype={RAW_DTYPE}"]
    return args


def make_job(path: Path, fmt: str, kind: str, mesh_samples: int | None) -> dict[str, Any]:
    if kind == "cli":
        return {"kind": "cli", "path": str(path), "args": _cli_args(fmt, mesh_samples)}
    if kind == "distance":
        return {"kind": "distance", "path": str(path)}
    return {"kind": "api", "path": str(path), "options": _api_options(fmt, kind, mesh_samples)}


def repro_command(job: dict[str, Any], path: str) -> str:
    """A shell command reproducing one run on ``path``."""
    py = "python"
    if job["kind"] == "cli":
        args = " ".join(_shell_quote(a) for a in job["args"])
        return f"{py} -m medialaxis compute {_shell_quote(path)} -o /tmp/fuzz-out.json{' ' + args if args else ''}"
    lit = json.dumps  # double-quoted literals: the command is single-quoted for the shell
    if job["kind"] == "distance":
        code = f"import medialaxis as mx; print(mx.shape_distance({lit(path)}, {lit(path)}))"
    else:
        opts = "".join(f", {k}={lit(v)}" for k, v in job["options"].items())
        code = f"import medialaxis as mx; print(mx.medial_axis({lit(path)}{opts}))"
    return f"{py} -c {_shell_quote(code)}"


def _shell_quote(s: str) -> str:
    import shlex

    return shlex.quote(s)


# ---------------------------------------------------------------- worker
def _vm_hwm_kib() -> int:
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    import resource

    return int(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)


def _reset_hwm() -> None:
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
    except OSError:
        pass


def _frame_str(fr: traceback.FrameSummary) -> str:
    return f"{_short(fr.filename)}:{fr.lineno} in {fr.name}"


def _short(filename: str) -> str:
    for prefix in (str(ROOT) + os.sep, str(Path(sys.prefix)) + os.sep):
        if filename.startswith(prefix):
            return filename[len(prefix) :]
    m = re.search(r"site-packages/(.*)$", filename)
    return m.group(1) if m else filename


def _exc_info(exc: BaseException) -> dict[str, Any]:
    frames = traceback.extract_tb(exc.__traceback__)
    ours = [f for f in frames if f"{os.sep}medialaxis{os.sep}" in f.filename]
    return {
        "type": f"{type(exc).__module__}.{type(exc).__qualname__}".replace("builtins.", ""),
        "message": str(exc)[:600],
        "last_frame": _frame_str(frames[-1]) if frames else "?",
        "medialaxis_frame": _frame_str(ours[-1]) if ours else "",
        "traceback": "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))[-4000:],
    }


def _run_cli(main: Any, job: dict[str, Any], tmp: Path) -> dict[str, Any]:
    import warnings

    out_json = tmp / "out.json"
    argv = ["compute", job["path"], "-o", str(out_json), *job["args"]]
    fd_out, fd_err = tempfile.TemporaryFile(dir=tmp), tempfile.TemporaryFile(dir=tmp)  # noqa: SIM115 - closed below
    py_out, py_err = io.StringIO(), io.StringIO()
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    os.dup2(fd_out.fileno(), 1)
    os.dup2(fd_err.fileno(), 2)
    old = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = py_out, py_err
    code: Any = None
    escaped: BaseException | None = None
    where: list[str] = []  # deepest medialaxis frame of each printed warning
    show = warnings.showwarning

    def showwarning(message: Any, category: Any, filename: str, lineno: int, file: Any = None,
                    line: Any = None) -> None:
        ours = [f for f in traceback.extract_stack()[:-1] if f"{os.sep}medialaxis{os.sep}" in f.filename]
        where.append(_frame_str(ours[-1]) if ours else "")
        show(message, category, filename, lineno, file, line)

    try:
        with warnings.catch_warnings():  # fresh warning registries: a warning shows as in a new process
            warnings.showwarning = showwarning
            code = main(argv)
    except BaseException as exc:  # noqa: BLE001 - an exception escaping main is what we look for
        escaped = exc
    finally:
        sys.stdout, sys.stderr = old
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])
    fd_err.seek(0)
    stderr = py_err.getvalue() + fd_err.read().decode("utf-8", "replace")
    fd_out.close()
    fd_err.close()
    for p in tmp.iterdir():
        if p.is_file():
            p.unlink()
        elif p.is_dir():
            shutil.rmtree(p, ignore_errors=True)
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    res: dict[str, Any] = {"exit": code, "stderr": stderr[-2000:]}
    if escaped is not None:
        res.update(status="crash", **_exc_info(escaped))
        res["type"] = "escaped " + res["type"]
        return res
    if not isinstance(code, int) or isinstance(code, bool) or code not in (0, 1, 2):
        res.update(status="crash", type=f"CLI exit {code!r}", message=stderr.strip()[:600], last_frame="cli",
                   medialaxis_frame="")
        return res
    if "Traceback" in stderr or len(lines) > 1 or (code != 0 and len(lines) != 1):
        m = re.search(r"^(\S.*?):(\d+): (\w+): (.*)$", stderr, re.MULTILINE)  # a printed warning
        if "Traceback" in stderr:
            tb = re.findall(r'File "([^"]+)", line (\d+), in (\S+)', stderr)
            last = f"{_short(tb[-1][0])}:{tb[-1][1]} in {tb[-1][2]}" if tb else "?"
            kind = "CLI stderr traceback"
        elif m:
            last, kind = f"{_short(m.group(1))}:{m.group(2)}", f"CLI stderr {m.group(3)}"
        else:
            last, kind = "cli stderr", f"CLI stderr of {len(lines)} lines (exit {code})"
        res.update(status="crash", type=kind, message=stderr.strip()[:600], last_frame=last,
                   medialaxis_frame=where[0] if where else "")
        return res
    res["status"] = "ok" if code == 0 else "clean"
    if code != 0:
        res["message"] = lines[0][:600]
    return res


def _global_state() -> dict[str, Any]:
    """Process-global settings a run should leave as it found them (a change makes runs order-dependent)."""
    import logging
    import warnings

    pil = sys.modules.get("PIL.Image")
    return {
        "PIL.Image.MAX_IMAGE_PIXELS": getattr(pil, "MAX_IMAGE_PIXELS", None),
        "numpy.geterr()": dict(np.geterr()),
        "warnings.filters": list(warnings.filters),
        "logging root level/handlers": (logging.root.level, len(logging.root.handlers)),
        "sys.getrecursionlimit()": sys.getrecursionlimit(),
        "os.getcwd()": os.getcwd(),
        "SIGINT handler": repr(signal.getsignal(signal.SIGINT)),
        "os.environ": dict(os.environ),
        "sys.path": list(sys.path),
    }


def _restore_state(base: dict[str, Any]) -> list[str]:
    """Names (with before -> after) of the settings a run changed; the simple ones are put back."""
    import warnings

    now = _global_state()
    changed = []
    for key, before in base.items():
        after = now[key]
        if after == before:
            continue
        if key == "os.environ":
            diff = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
            changed.append(f"os.environ[{', '.join(diff)}]")
            for k in diff:
                if k in before:
                    os.environ[k] = before[k]
                else:
                    os.environ.pop(k, None)
        elif key == "warnings.filters":
            changed.append(f"warnings.filters ({len(before)} -> {len(after)} entries)")
            warnings.filters[:] = before
            warnings._filters_mutated()  # type: ignore[attr-defined]
        else:
            changed.append(f"{key}: {before!r} -> {after!r}"[:200])
            if key == "PIL.Image.MAX_IMAGE_PIXELS":
                sys.modules["PIL.Image"].MAX_IMAGE_PIXELS = before
            elif key == "numpy.geterr()":
                np.seterr(**before)
            elif key == "sys.getrecursionlimit()":
                sys.setrecursionlimit(before)
            elif key == "os.getcwd()":
                os.chdir(before)
            elif key == "sys.path":
                sys.path[:] = before
    return changed


def worker_main(workdir: str) -> None:
    """Serve jobs (one JSON line each on stdin), answer one JSON line each on the original stdout."""
    import faulthandler

    tmp = Path(workdir)
    tmp.mkdir(parents=True, exist_ok=True)
    result_fd = os.dup(1)
    log = open(tmp / "worker.log", "ab")  # noqa: SIM115 - stray output of C code and libraries goes here
    os.dup2(log.fileno(), 1)
    os.dup2(log.fileno(), 2)
    out = os.fdopen(result_fd, "w", buffering=1)
    crash_file = open(tmp / "fatal.txt", "w")  # noqa: SIM115
    faulthandler.enable(file=crash_file)
    hang_file = open(tmp / "hang.txt", "w")  # noqa: SIM115
    usr1_file = open(tmp / "usr1.txt", "w")  # noqa: SIM115 - the parent asks for a stack dump with SIGUSR1
    faulthandler.register(signal.SIGUSR1, file=usr1_file, all_threads=True)
    runs = tmp / "run"
    runs.mkdir(exist_ok=True)

    os.environ.setdefault("MPLBACKEND", "Agg")
    # imported now, so that import time is not in the first runs' times and PIL's settings are in the baseline
    import PIL.Image  # noqa: F401

    import medialaxis as mx
    import medialaxis.compare
    import medialaxis.mesh.flow
    import medialaxis.mesh.voronoi
    import medialaxis.planar.pipeline
    import medialaxis.volume.pipeline
    from medialaxis.cli import main as cli_main

    baseline = _global_state()
    out.write(json.dumps({"ready": True, "pid": os.getpid()}) + "\n")
    for line in sys.stdin:
        job = json.loads(line)
        if job is None:
            break
        timeout = float(job.get("timeout", 20.0))
        hang_file.seek(0)
        hang_file.truncate()
        faulthandler.dump_traceback_later(max(0.2, timeout - min(1.0, 0.2 * timeout)), repeat=False, file=hang_file)
        _reset_hwm()
        t0 = time.perf_counter()
        try:
            if job["kind"] == "cli":
                res = _run_cli(cli_main, job, runs)
            elif job["kind"] == "selftest":  # the harness's own checks: hang, fatal signal, memory, crash
                what = job["what"]
                if what == "hang":
                    time.sleep(3600)
                elif what == "segv":
                    os.kill(os.getpid(), signal.SIGSEGV)
                elif what == "memory":
                    hog = [np.ones(2**27) for _ in range(64)]  # 64 GiB, touched gradually
                    del hog
                try:
                    raise IndexError("selftest")
                except IndexError as exc:
                    res = {"status": "crash", **_exc_info(exc)}
            else:
                try:
                    if job["kind"] == "distance":
                        value = mx.shape_distance(job["path"], job["path"])
                        res = {"status": "ok", "value": float(value)}
                    else:
                        ma = mx.medial_axis(job["path"], **job["options"])
                        res = {"status": "ok", "points": len(ma.points)}
                except mx.MedialAxisError as exc:
                    res = {"status": "clean", "type": type(exc).__name__, "message": str(exc)[:600]}
                except BaseException as exc:  # noqa: BLE001 - every other exception is a crash
                    res = {"status": "crash", **_exc_info(exc)}
        except BaseException as exc:  # noqa: BLE001 - the harness itself failed; report, keep serving
            res = {"status": "crash", **_exc_info(exc)}
            res["type"] = "harness " + res["type"]
        faulthandler.cancel_dump_traceback_later()
        res["seconds"] = time.perf_counter() - t0
        res["peak_kib"] = _vm_hwm_kib()
        try:  # each run starts from the same process state, as in a fresh process
            res["state_changed"] = _restore_state(baseline)
        except Exception as exc:  # noqa: BLE001
            res["state_changed"] = [f"(state check failed: {exc!r})"]
        out.write(json.dumps(res, default=str) + "\n")


# ---------------------------------------------------------------- parent
def _rss_kib(pid: int) -> int:
    try:
        import psutil

        return int(psutil.Process(pid).memory_info().rss // 1024)
    except ImportError:
        pass
    except Exception:  # noqa: BLE001 - process gone
        return 0
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0


def _parse_dump(text: str) -> str:
    """Innermost frame of the main thread in a faulthandler dump."""
    blocks = re.split(r"\n(?=(?:Current thread|Thread) 0x)", text)
    main_blocks = [b for b in blocks if "worker_main" in b] or blocks
    for block in main_blocks:
        m = re.search(r'File "([^"]+)", line (\d+) in (\S+)', block)
        if m:
            return f"{_short(m.group(1))}:{m.group(2)} in {m.group(3)}"
    return "?"


def _dump_ours(text: str) -> str:
    blocks = re.split(r"\n(?=(?:Current thread|Thread) 0x)", text)
    main_blocks = [b for b in blocks if "worker_main" in b] or blocks
    for block in main_blocks:
        for m in re.finditer(r'File "([^"]+)", line (\d+) in (\S+)', block):
            if f"{os.sep}medialaxis{os.sep}" in m.group(1):
                return f"{_short(m.group(1))}:{m.group(2)} in {m.group(3)}"
    return ""


class Worker:
    """One worker subprocess, restarted after a hang, a fatal signal or a memory blow-up."""

    def __init__(self, workdir: Path, memory_limit_kib: int | None):
        self.workdir = workdir
        self.memory_limit_kib = memory_limit_kib
        self.proc: subprocess.Popen[bytes] | None = None
        self.buf = b""
        self.starts = 0

    def start(self) -> None:
        env = dict(os.environ)
        env.update(MPLBACKEND="Agg", NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
                   MKL_NUM_THREADS="1", PYTHONFAULTHANDLER="1")
        env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
        self.workdir.mkdir(parents=True, exist_ok=True)
        self.proc = subprocess.Popen(
            [sys.executable, str(HERE), "--worker", str(self.workdir)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env,
            start_new_session=True,
        )
        self.buf = b""
        self.starts += 1
        ready = self._read_line(120.0)
        if ready is None or not ready.get("ready"):
            self.kill()
            raise RuntimeError(f"fuzz worker failed to start; see {self.workdir / 'worker.log'}")

    def _read_line(self, timeout: float, track: list[int] | None = None) -> dict[str, Any] | None:
        assert self.proc is not None and self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        deadline = time.monotonic() + timeout
        while b"\n" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            r, _, _ = select.select([fd], [], [], min(left, 0.1))
            if track is not None:
                rss = _rss_kib(self.proc.pid)
                track[0] = max(track[0], rss)
                if self.memory_limit_kib and rss > self.memory_limit_kib:
                    return {"status": "memory", "rss_kib": rss}
            if r:
                chunk = os.read(fd, 65536)
                if not chunk:
                    return {"status": "died"}
                self.buf += chunk
        line, _, self.buf = self.buf.partition(b"\n")
        return json.loads(line)

    def kill(self) -> None:
        if self.proc is not None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except OSError:
                pass
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                pass
            self.proc = None

    def stop(self) -> None:
        if self.proc is not None:
            with contextlib.suppress(Exception):  # it may be dead already
                assert self.proc.stdin is not None
                self.proc.stdin.write(b"null\n")
                self.proc.stdin.flush()
                self.proc.wait(5)
            self.kill()

    def run(self, job: dict[str, Any], timeout: float) -> dict[str, Any]:
        if self.proc is None:
            self.start()
        assert self.proc is not None and self.proc.stdin is not None
        job = dict(job, timeout=timeout)
        for name in ("hang.txt", "fatal.txt", "usr1.txt"):
            with open(self.workdir / name, "w"):
                pass
        t0 = time.perf_counter()
        track = [0]
        try:
            self.proc.stdin.write((json.dumps(job) + "\n").encode())
            self.proc.stdin.flush()
            res = self._read_line(timeout, track)
        except (BrokenPipeError, OSError):
            res = {"status": "died"}
        elapsed = time.perf_counter() - t0
        if res is not None and res.get("status") not in ("died", "memory"):
            res["peak_kib"] = max(int(res.get("peak_kib", 0)), track[0])
            return res
        # hang, memory blow-up or death: kill, diagnose from the faulthandler files, restart later
        if res is None or res["status"] == "memory":
            try:  # where is it? (faulthandler's SIGUSR1 handler dumps even while C code holds the GIL)
                os.kill(self.proc.pid, signal.SIGUSR1)
                time.sleep(0.5)
            except OSError:
                pass
        try:
            code = self.proc.wait(2) if res is not None and res["status"] == "died" else self.proc.poll()
        except subprocess.TimeoutExpired:
            code = None
        self.kill()
        usr1 = (self.workdir / "usr1.txt").read_text(errors="replace")
        hang = usr1 if "File " in usr1 else (self.workdir / "hang.txt").read_text(errors="replace")
        fatal = (self.workdir / "fatal.txt").read_text(errors="replace")
        if res is None:
            return {"status": "hang", "type": "Timeout", "message": f"no answer within {timeout:g} s",
                    "last_frame": _parse_dump(hang) if hang else "?", "medialaxis_frame": _dump_ours(hang),
                    "traceback": hang[-4000:], "seconds": elapsed, "peak_kib": track[0]}
        if res["status"] == "memory":
            return {"status": "crash", "type": "MemoryLimit",
                    "message": f"worker RSS {res['rss_kib'] // 1024} MiB passed the limit "
                               f"{(self.memory_limit_kib or 0) // 1024} MiB",
                    "last_frame": _parse_dump(hang) if hang else "?", "medialaxis_frame": _dump_ours(hang),
                    "traceback": hang[-4000:], "seconds": elapsed, "peak_kib": track[0]}
        sig = f"signal {-code}" if code is not None and code < 0 else f"exit {code}"
        first = fatal.strip().splitlines()[0] if fatal.strip() else ""
        return {"status": "crash", "type": f"WorkerDied({sig})", "message": first,
                "last_frame": _parse_dump(fatal) if fatal else "?", "medialaxis_frame": _dump_ours(fatal),
                "traceback": fatal[-4000:], "seconds": elapsed, "peak_kib": track[0]}


@dataclass
class Case:
    """One file to run: a seed (``index`` -1) or a mutated file."""

    fmt: str
    index: int
    path: Path
    ops: list[str] = field(default_factory=list)


def _spread(count: int, formats: list[str]) -> dict[str, int]:
    base, extra = divmod(count, len(formats))
    return {f: base + (1 if i < extra else 0) for i, f in enumerate(formats)}


def _pool_run(tasks: list[tuple[Case, str, dict[str, Any]]], jobs: int, timeout: float, base: Path,
              memory_limit_kib: int | None, progress: Any) -> list[dict[str, Any]]:
    """Run every task on ``jobs`` workers; results in task order."""
    results: list[dict[str, Any] | None] = [None] * len(tasks)
    lock = threading.Lock()
    nxt = [0]
    errors: list[BaseException] = []

    def serve(k: int) -> None:
        worker = Worker(base / f"worker{k}", memory_limit_kib)
        try:
            while True:
                with lock:
                    i = nxt[0]
                    nxt[0] += 1
                if i >= len(tasks):
                    return
                res = worker.run(tasks[i][2], timeout)
                results[i] = res
                if progress is not None:
                    with lock:
                        progress(i, tasks[i], res)
        except BaseException as exc:  # noqa: BLE001
            errors.append(exc)
        finally:
            worker.stop()

    threads = [threading.Thread(target=serve, args=(k,), daemon=True) for k in range(max(1, jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise errors[0]
    return [r if r is not None else {"status": "crash", "type": "harness", "message": "not run"} for r in results]


def _keep_example(e: dict[str, Any], prefix: str, keep_dir: Path | None) -> None:
    case, job = e.pop("_case"), e.pop("_job")
    if keep_dir is not None:
        name = f"{prefix}_{case.fmt}_{'seed' if case.index < 0 else f'{case.index:06d}'}{FORMATS[case.fmt][0]}"
        shutil.copyfile(case.path, keep_dir / name)
        e["example"] = str(keep_dir / name)
        if "message" in e:
            e["message"] = e["message"].replace(str(case.path), e["example"])
        e["repro"] = repro_command(job, e["example"])


def run_fuzz(
    count: int,
    seed: int,
    formats: list[str] | str | None = None,
    timeout: float = 20.0,
    jobs: int = 1,
    keep: str | os.PathLike[str] | None = None,
    *,
    mesh_samples: int | None = MESH_SAMPLES,
    memory_limit_mib: float | None = 4096,
    verbose: bool = False,
    workdir: str | os.PathLike[str] | None = None,
    confirm: bool = True,
) -> dict[str, Any]:
    """Build seeds, mutate ``count`` files, run them all; return the summary.

    Returns
    -------
    dict
        ``formats``: per format ``files``, ``runs``, ``ok``, ``clean``,
        ``crash``, ``hang``, ``max_seconds``, ``peak_mib``; ``seeds``: per
        format the status of each run kind on the unmutated seed;
        ``crashes`` / ``hangs``: the distinct ones (``key`` (type, last
        frame), ``formats``, ``kinds``, ``count``, ``type``, ``message``,
        ``last_frame``, ``medialaxis_frame``, ``example`` (kept input or
        temporary path), ``repro``, ``traceback``); ``n_crashes``,
        ``n_hangs`` (runs); ``seconds``, ``count``, ``seed``.
    """
    if isinstance(formats, str):
        formats = [f.strip() for f in formats.split(",") if f.strip()]
    formats = list(FORMATS) if not formats else list(formats)
    unknown = [f for f in formats if f not in FORMATS]
    if unknown:
        raise ValueError(f"unknown format(s) {unknown}; known: {', '.join(FORMATS)}")
    t_start = time.perf_counter()
    own_tmp = workdir is None
    base = Path(tempfile.mkdtemp(prefix="medialaxis-fuzz-")) if own_tmp else Path(workdir)
    base.mkdir(parents=True, exist_ok=True)
    keep_dir = Path(keep) if keep is not None else None
    if keep_dir is not None:
        keep_dir.mkdir(parents=True, exist_ok=True)
    try:
        seeds = build_seeds(base / "seeds", formats)
        rng = np.random.default_rng(seed)
        cases: list[Case] = [Case(f, -1, seeds[f]) for f in formats]
        files_dir = base / "files"
        files_dir.mkdir()
        counter = 0
        per = _spread(count, formats)
        seed_bytes = {f: seeds[f].read_bytes() for f in formats}
        # interleave formats so that a partial or slow run still covers all of them
        for round_ in range(max(per.values(), default=0)):
            for f in formats:
                if round_ < per[f]:
                    data, ops = mutate(seed_bytes[f], f, rng)
                    p = files_dir / f"{f}_{counter:06d}{FORMATS[f][0]}"
                    p.write_bytes(data)
                    cases.append(Case(f, counter, p, ops))
                    counter += 1
        tasks = [(c, kind, make_job(c.path, c.fmt, kind, mesh_samples)) for c in cases for kind in run_kinds(c.fmt)]

        done = [0]
        t0 = time.perf_counter()

        def progress(i: int, task: tuple[Case, str, dict[str, Any]], res: dict[str, Any]) -> None:
            done[0] += 1
            c, kind, _ = task
            if res["status"] in ("crash", "hang") and verbose:
                print(f"  [{res['status']}] {c.fmt} {c.path.name} {kind}: {res.get('type')}: "
                      f"{str(res.get('message', ''))[:160]}", file=sys.stderr, flush=True)
            if verbose and (done[0] % 200 == 0 or done[0] == len(tasks)):
                print(f"  {done[0]}/{len(tasks)} runs, {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)

        results = _pool_run(tasks, jobs, timeout, base / "workers",
                            int(memory_limit_mib * 1024) if memory_limit_mib else None, progress)

        table: dict[str, dict[str, Any]] = {
            f: {"files": per[f], "runs": 0, **{s: 0 for s in STATUSES}, "max_seconds": 0.0, "peak_mib": 0.0}
            for f in formats
        }
        seed_status: dict[str, dict[str, str]] = {f: {} for f in formats}
        distinct: dict[tuple[str, str, str], dict[str, Any]] = {}
        leaks: dict[tuple[str, str], dict[str, Any]] = {}
        state_leaks: dict[str, dict[str, Any]] = {}
        clean_messages: dict[str, dict[str, int]] = {f: {} for f in formats}
        n_bad = {"crash": 0, "hang": 0}
        for (case, kind, job), res in zip(tasks, results, strict=True):
            st = res["status"]
            if case.index < 0:
                seed_status[case.fmt][kind] = st
            else:
                row = table[case.fmt]
                row["runs"] += 1
                row[st] += 1
                row["max_seconds"] = max(row["max_seconds"], float(res.get("seconds", 0.0)))
                row["peak_mib"] = max(row["peak_mib"], int(res.get("peak_kib", 0)) / 1024)
            for change in res.get("state_changed") or []:
                sk = change.split(":")[0].split(" (")[0].split("[")[0]
                if sk not in state_leaks:
                    state_leaks[sk] = {"change": change, "count": 0, "formats": [], "kinds": [],
                                       "example": str(case.path), "repro": repro_command(job, str(case.path)),
                                       "_case": case, "_job": job}
                _tally(state_leaks[sk], case.fmt, kind)
            if st == "clean":
                msg = str(res.get("message", ""))
                norm = _normalize(msg)
                counts = clean_messages[case.fmt]
                counts[norm] = counts.get(norm, 0) + 1
                hit = _LEAK_RE.search(msg)
                if hit and kind != "cli":  # the CLI prints the same message as the API run
                    lk = (hit.group(1), norm)
                    if lk not in leaks:
                        leaks[lk] = {"wrapped": hit.group(1), "type": res.get("type"), "message": msg,
                                     "formats": [], "kinds": [], "count": 0, "example": str(case.path),
                                     "repro": repro_command(job, str(case.path)), "_case": case, "_job": job}
                    _tally(leaks[lk], case.fmt, kind)
            if st not in ("crash", "hang"):
                continue
            n_bad[st] += 1
            kept = str(case.path)
            if keep_dir is not None:
                name = f"{case.fmt}_{'seed' if case.index < 0 else f'{case.index:06d}'}{FORMATS[case.fmt][0]}"
                dest = keep_dir / name
                shutil.copyfile(case.path, dest)
                kept = str(dest)
                with open(keep_dir / (name + ".txt"), "a") as fh:
                    fh.write(f"format: {case.fmt}\nrun: {kind}\nmutations: {case.ops}\nstatus: {st}\n"
                             f"type: {res.get('type')}\nmessage: {res.get('message')}\n"
                             f"last frame: {res.get('last_frame')}\nmedialaxis frame: {res.get('medialaxis_frame')}\n"
                             f"repro: {repro_command(job, kept)}\n"
                             f"{res.get('traceback') or res.get('stderr') or ''}\n\n")
            for name in ("message", "traceback", "stderr"):  # name the kept copy, not the temporary file
                if isinstance(res.get(name), str):
                    res[name] = res[name].replace(str(case.path), kept)
            key = (st, str(res.get("type")), str(res.get("last_frame")))
            entry = distinct.get(key)
            if entry is None:
                entry = distinct[key] = {
                    "status": st, "key": [str(res.get("type")), str(res.get("last_frame"))], "type": res.get("type"),
                    "message": res.get("message"), "last_frame": res.get("last_frame"),
                    "medialaxis_frame": res.get("medialaxis_frame"), "formats": [], "kinds": [], "count": 0,
                    "example": kept, "example_ops": case.ops, "seed": case.index < 0,
                    "repro": repro_command(job, kept), "traceback": res.get("traceback") or res.get("stderr"),
                    "_job": job,
                }
            _tally(entry, case.fmt, kind)
        for prefix, group in (("leak", leaks.values()), ("state", state_leaks.values())):
            for e in group:  # keep one example input of each
                _keep_example(e, prefix, keep_dir)
        top = {f: dict(sorted(c.items(), key=lambda kv: -kv[1])[:10]) for f, c in clean_messages.items()}
        if confirm and distinct:
            # each distinct crash/hang once more, in a fresh worker: does it happen without earlier runs?
            if verbose:
                print(f"  confirming {len(distinct)} distinct crashes/hangs in fresh workers", file=sys.stderr)
            limit = int(memory_limit_mib * 1024) if memory_limit_mib else None
            for k, entry in enumerate(distinct.values()):
                worker = Worker(base / "workers" / f"confirm{k}", limit)
                try:
                    again = worker.run(entry["_job"], timeout)
                finally:
                    worker.stop()
                entry["standalone"] = {"status": again["status"], "type": again.get("type"),
                                       "last_frame": again.get("last_frame"),
                                       "message": str(again.get("message", ""))[:300]}
                entry["reproduces"] = again["status"] == entry["status"] and again.get("type") == entry["type"]
        for entry in distinct.values():
            entry.pop("_job", None)
        summary = {
            "count": count, "seed": seed, "timeout": timeout, "jobs": jobs, "formats": table, "seeds": seed_status,
            "leaks": list(leaks.values()), "clean_messages": top, "state_leaks": list(state_leaks.values()),
            "crashes": [e for e in distinct.values() if e["status"] == "crash"],
            "hangs": [e for e in distinct.values() if e["status"] == "hang"],
            "n_crashes": n_bad["crash"], "n_hangs": n_bad["hang"], "n_runs": len(tasks),
            "seconds": time.perf_counter() - t_start,
        }
        if keep_dir is not None:
            (keep_dir / "summary.json").write_text(json.dumps(summary, indent=1, default=str))
        return summary
    finally:
        if own_tmp:
            shutil.rmtree(base, ignore_errors=True)


def print_summary(summary: dict[str, Any], out: Any = None, show_clean: bool = False) -> None:
    out = sys.stdout if out is None else out
    cols = ("files", "runs", "ok", "clean", "crash", "hang")
    print(f"{'format':<11}" + "".join(f"{c:>7}" for c in cols) + f"{'max s':>8}{'peak MiB':>10}", file=out)
    tot = {c: 0 for c in cols}
    for fmt, row in summary["formats"].items():
        for c in cols:
            tot[c] += row[c]
        print(f"{fmt:<11}" + "".join(f"{row[c]:>7}" for c in cols)
              + f"{row['max_seconds']:>8.2f}{row['peak_mib']:>10.0f}", file=out)
    mx_s = max((r["max_seconds"] for r in summary["formats"].values()), default=0.0)
    mx_m = max((r["peak_mib"] for r in summary["formats"].values()), default=0.0)
    print(f"{'total':<11}" + "".join(f"{tot[c]:>7}" for c in cols) + f"{mx_s:>8.2f}{mx_m:>10.0f}", file=out)
    bad_seeds = {f: k for f, k in summary["seeds"].items() if any(s != "ok" for s in k.values())}
    print(f"\nunmutated seeds: {'all ok' if not bad_seeds else 'NOT ok: ' + json.dumps(bad_seeds)}", file=out)
    for what in ("crashes", "hangs"):
        items = summary[what]
        print(f"\n{len(items)} distinct {what} ({summary['n_' + what]} runs)", file=out)
        for k, e in enumerate(items, 1):
            print(f"\n[{k}] {e['type']}  x{e['count']}  formats={','.join(e['formats'])}  runs={','.join(e['kinds'])}"
                  f"{'  (unmutated seed)' if e['seed'] else ''}", file=out)
            print(f"    message: {str(e['message'])[:300]}", file=out)
            print(f"    last frame: {e['last_frame']}", file=out)
            if e.get("medialaxis_frame") and e["medialaxis_frame"] != e["last_frame"]:
                print(f"    medialaxis frame: {e['medialaxis_frame']}", file=out)
            if "standalone" in e:
                sa = e["standalone"]
                print(f"    fresh process: {'reproduces' if e['reproduces'] else 'DOES NOT reproduce'} "
                      f"({sa['status']}: {sa['type']} at {sa['last_frame']})", file=out)
            print(f"    input: {e['example']}", file=out)
            print(f"    repro: {e['repro']}", file=out)
    state = summary.get("state_leaks", [])
    print(f"\n{len(state)} process-global settings changed by runs (put back after each run)", file=out)
    for k, e in enumerate(state, 1):
        print(f"\n[S{k}] {e['change']}  x{e['count']}  formats={','.join(e['formats'])}  runs={','.join(e['kinds'])}",
              file=out)
        print(f"    first seen: {e['repro']}", file=out)
    leaks = summary.get("leaks", [])
    print(f"\n{len(leaks)} distinct clean errors that leak an internal exception (not counted as crashes)", file=out)
    for k, e in enumerate(leaks, 1):
        print(f"\n[L{k}] {e['type']} wrapping {e['wrapped']}  x{e['count']}  formats={','.join(e['formats'])}  "
              f"runs={','.join(e['kinds'])}", file=out)
        print(f"    message: {str(e['message'])[:300]}", file=out)
        print(f"    input: {e['example']}", file=out)
        print(f"    repro: {e['repro']}", file=out)
    if show_clean:
        print("\nmost frequent clean errors per format:", file=out)
        for fmt, counts in summary.get("clean_messages", {}).items():
            print(f"  {fmt}:", file=out)
            for msg, n in counts.items():
                print(f"    {n:>5}  {msg}", file=out)
    print(f"\n{summary['n_runs']} runs in {summary['seconds']:.1f} s", file=out)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--worker"]:
        worker_main(argv[1])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--count", type=int, default=10000, help="mutated files in all, spread evenly over the formats")
    ap.add_argument("--seed", type=int, default=0, help="seed of np.random.default_rng")
    ap.add_argument("--timeout", type=float, default=20.0, help="wall-clock limit of one run, seconds")
    ap.add_argument("--formats", default=None, help=f"comma-separated subset of: {','.join(FORMATS)}")
    ap.add_argument("--jobs", type=int, default=2, help="worker processes")
    ap.add_argument("--keep", default=None, help="copy crashing/hanging inputs (and a .txt record each) here")
    ap.add_argument("--memory-limit", type=float, default=4096, help="worker RSS limit in MiB (0: none)")
    ap.add_argument("--mesh-samples", type=int, default=MESH_SAMPLES,
                    help="samples= of the default mesh method (0: the library default)")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    ap.add_argument("--no-confirm", action="store_true",
                    help="do not re-run each distinct crash/hang in a fresh worker")
    ap.add_argument("--show-clean", action="store_true", help="also list the most frequent clean errors per format")
    a = ap.parse_args(argv)
    if a.formats:
        unknown = [f for f in a.formats.split(",") if f.strip() and f.strip() not in FORMATS]
        if unknown:
            ap.error(f"unknown format(s) {', '.join(unknown)}; known: {','.join(FORMATS)}")
    summary = run_fuzz(a.count, a.seed, a.formats, timeout=a.timeout, jobs=a.jobs, keep=a.keep,
                       mesh_samples=a.mesh_samples or None, memory_limit_mib=a.memory_limit or None,
                       verbose=not a.quiet, confirm=not a.no_confirm)
    print_summary(summary, show_clean=a.show_clean)
    return 1 if summary["n_crashes"] or summary["n_hangs"] else 0


if __name__ == "__main__":
    sys.exit(main())
