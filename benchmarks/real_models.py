"""Real closed triangle meshes of genus 0 to 8 for benchmarks.

Eleven scanned or modelled watertight, consistently oriented 2-manifolds from
public GitHub repositories, pinned to a commit and checked by SHA-256. A model
missing from the cache is downloaded from raw.githubusercontent.com; a model
already in the cache is used as it is. ``licence`` names the host repository's
licence and the model's origin; none of the models is redistributed here.
All are free of non-manifold edges and vertices, but the bunny's faces point
inward and the seahorse has 16 faces crossing others.

Usage::

    python benchmarks/real_models.py --list [--cache DIR]

The cache defaults to ``$MEDIALAXIS_MODELS`` or ``~/.cache/medialaxis-models``.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
import urllib.request
from pathlib import Path

_AVAXMAN = ("avaxman/CEA-EDF-INRIA-summer-school---Directional-Fields", "ce54a4c2e1b863e3d46b1a0c5a8b6af9403db322")
_CFWEN = ("cfwen/geometry-processing-package", "d45cc47b177be7be3c5806cdd03b5566c099a6b0")
_LIBIGL = ("libigl/libigl-tutorial-data", "c1f9ede366d02e3531ecbaec5e3769312f31cccd")
_COMMON = ("alecjacobson/common-3d-test-models", "8a4f8642acaf43f9cd7b67858a1502e1055ef202")
_DIRECTIONAL = ("avaxman/Directional", "d756bc53c15e79790fe020a64350f8dc6cf30e92")
_NO_LICENCE = "host repo has no licence file"


# name, source, path inside the repository, genus, vertices, licence
_ROWS = [
    ("bunny", _AVAXMAN, "data/Bunny.off", 0, 11247, f"{_NO_LICENCE}; Stanford 3D Scanning Repository, research use"),
    ("max-planck", _CFWEN, "data/maxplanck.nf25k.off", 0, 12556, "host repo MIT; Max Planck bust, MPI Informatik"),
    ("fandisk", _LIBIGL, "fandisk.off", 0, 7229, f"{_NO_LICENCE}; AIM@SHAPE (Hoppe's CAD part)"),
    ("rocker-arm", _COMMON, "data/rocker-arm.obj", 1, 10044, f"{_NO_LICENCE}; INRIA via AIM@SHAPE"),
    ("kitten", _CFWEN, "data/kitten.nf20k.off", 1, 10000, "host repo MIT; AIM@SHAPE Kitten"),
    ("eight", _AVAXMAN, "data/eight.off", 2, 5544, f"{_NO_LICENCE}; AIM@SHAPE Eight"),
    ("genus3", _AVAXMAN, "data/genus3.off", 3, 6652, f"{_NO_LICENCE}; origin unstated"),
    ("fertility", _AVAXMAN, "data/fertility_input.off", 4, 6551, f"{_NO_LICENCE}; AIM@SHAPE Fertility"),
    ("botijo", _AVAXMAN, "data/botijo.off", 5, 41158, f"{_NO_LICENCE}; AIM@SHAPE Botijo"),
    ("rolling-stage", _DIRECTIONAL, "tutorial/data/rolling_stage.obj", 7, 49988,
     f"{_NO_LICENCE} (sources MPL-2.0); origin unstated, name of AIM@SHAPE Rolling Stage"),
    ("seahorse", _AVAXMAN, "data/seahorse2_100K.off", 8, 49986, f"{_NO_LICENCE}; origin unstated"),
]
_SHA256 = {
    "bunny": "4bdea784a4a76ed1b5044cee064aec5abc4bbfe5b7dbec1f89f60189633e55cf",
    "max-planck": "6f53e9e563ef7c83220b7ad31b9e76156f70d336f88712ff5233f5300443d45e",
    "fandisk": "05bd799a78e7feece372b5b19787b7bc56c5f5e46888f998db23eaf30be2e443",
    "rocker-arm": "590257e6d01e689354821d807854306c3bfbb02d9cca73404d5a4924f105c287",
    "kitten": "ac15824022ed568d7c9286cc80651e916e593480102a016a987d7a3180c6aa12",
    "eight": "f5f474d3cbcac1ed2c58c121ab6d8bb05df5bea8201ff831d297c1278a18fa6f",
    "genus3": "ee287997e279ff3bd42c2f20f728b7068fadedf355c46a54c12053c7e91e4c52",
    "fertility": "b6e09afac94229dbfd9266569050f2dbc9e97e6b75a69b00cafa28a4151a4157",
    "botijo": "fc0237c71efd4b8f1dfa82fa1cc30d6dc935c52c225e91bfac5f2e5aace32441",
    "rolling-stage": "bb8211710b3e54881b47278d0a13982dea23967cd2fe98b2884a0883d43ae84b",
    "seahorse": "f18aa67af05fdaa4698531e5564564ca2c5adffa2e791f04ab591ec70277c4c4",
}
MODELS = [
    {
        "name": name,
        "repo": repo,
        "commit": commit,
        "path": path,
        "licence": licence,
        "genus": genus,
        "vertices": vertices,
        "sha256": _SHA256[name],
    }
    for name, (repo, commit), path, genus, vertices, licence in _ROWS
]


def default_cache() -> Path:
    """Return the model cache directory.

    Returns
    -------
    Path
        ``$MEDIALAXIS_MODELS`` if set, else ``~/.cache/medialaxis-models``.
    """
    return Path(os.environ.get("MEDIALAXIS_MODELS") or Path.home() / ".cache" / "medialaxis-models")


def _cached(cache: Path, model: dict) -> Path:
    return cache / (model["name"] + Path(model["path"]).suffix)


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def fetch_models(cache_dir: str | os.PathLike) -> dict[str, Path]:
    """Make sure each model is in the cache, downloading the missing ones.

    Parameters
    ----------
    cache_dir : str or os.PathLike
        Directory holding ``<name><suffix>`` files; created if absent.

    Returns
    -------
    dict of str to Path
        Model name to its cached file, for the models present after the call.
        A model that cannot be downloaded, or whose download fails its SHA-256
        check, is reported on stderr and left out.
    """
    cache = Path(cache_dir)
    cache.mkdir(parents=True, exist_ok=True)
    paths = {}
    for model in MODELS:
        target = _cached(cache, model)
        if not target.exists():
            url = f"https://raw.githubusercontent.com/{model['repo']}/{model['commit']}/{model['path']}"
            part = target.with_name(target.name + ".part")
            try:
                with urllib.request.urlopen(url, timeout=60) as response:
                    part.write_bytes(response.read())
            except OSError as error:
                print(f"{model['name']}: cannot download {url}: {error}", file=sys.stderr)
                continue
            if _sha256(part) != model["sha256"]:
                part.unlink()
                print(f"{model['name']}: {url} does not match its SHA-256", file=sys.stderr)
                continue
            part.replace(target)
        paths[model["name"]] = target
    return paths


def describe(path: str | os.PathLike) -> dict:
    """Measure a mesh file's size and topology.

    Parameters
    ----------
    path : str or os.PathLike
        Mesh file readable by trimesh.

    Returns
    -------
    dict
        ``vertices``, ``faces``, ``components`` (edge-connected shells),
        ``euler`` (V - E + F), ``genus`` (total over shells,
        ``components - euler / 2``), ``watertight`` and ``oriented``.
    """
    import trimesh

    mesh = trimesh.load(path, force="mesh", process=False)
    labels = trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces))
    components = int(labels.max()) + 1
    euler = len(mesh.vertices) - len(mesh.edges_unique) + len(mesh.faces)
    return {
        "vertices": len(mesh.vertices),
        "faces": len(mesh.faces),
        "components": components,
        "euler": euler,
        "genus": components - euler / 2,
        "watertight": mesh.is_watertight,
        "oriented": mesh.is_winding_consistent,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cache", type=Path, default=default_cache(), help="model cache directory")
    parser.add_argument("--list", action="store_true", help="print the cached models without downloading")
    args = parser.parse_args()

    if args.list:
        paths = {m["name"]: _cached(args.cache, m) for m in MODELS if _cached(args.cache, m).exists()}
    else:
        paths = fetch_models(args.cache)
    print(f"{'name':<13} {'vertices':>8} {'genus':>5} {'watertight':>10}  licence")
    for model in MODELS:
        if model["name"] in paths:
            d = describe(paths[model["name"]])
            row = f"{model['name']:<13} {d['vertices']:>8} {d['genus']:>5g} {d['watertight']!s:>10}"
            print(f"{row}  {model['licence']}")


if __name__ == "__main__":
    main()
