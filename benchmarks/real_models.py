"""Real triangle meshes for benchmarks, pinned to a commit and checked by SHA-256.

``MODELS``: eleven scanned or modelled watertight, consistently oriented
2-manifolds of genus 0 to 8 (the bunny's faces point inward, the seahorse has
27 pairs of faces crossing). ``AS_GIVEN`` (issue 31, ``bench_mesh_routes.py``):
46 more meshes as people have them, 1k-62k vertices: scans, ABC CAD exports
whose patches do not share their seam vertices, Thingi10K solids up to genus
24, and meshes with crossing faces, holes, non-manifold edges, several shells,
inconsistent winding, a triangle soup. ``ALL_MODELS`` is both. The genus is
the sum over shells from the Euler characteristic, holes counted as capped
(half-integers: a pinched vertex).

A model missing from the cache is downloaded from raw.githubusercontent.com,
or (``--from-mirror DIR``) read from local git clones; a model already in the
cache is used as it is. ``licence`` names the host repository's licence and
the model's origin; none of the models is redistributed here.

Usage::

    python benchmarks/real_models.py --list [--cache DIR]
    python benchmarks/real_models.py [--all] [--from-mirror /work/.mirror]

The cache defaults to ``$MEDIALAXIS_MODELS`` or ``~/.cache/medialaxis-models``.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import subprocess
import sys
import urllib.request
from pathlib import Path

_AVAXMAN = ("avaxman/CEA-EDF-INRIA-summer-school---Directional-Fields", "ce54a4c2e1b863e3d46b1a0c5a8b6af9403db322")
_CFWEN = ("cfwen/geometry-processing-package", "d45cc47b177be7be3c5806cdd03b5566c099a6b0")
_LIBIGL = ("libigl/libigl-tutorial-data", "c1f9ede366d02e3531ecbaec5e3769312f31cccd")
_COMMON = ("alecjacobson/common-3d-test-models", "8a4f8642acaf43f9cd7b67858a1502e1055ef202")
_DIRECTIONAL = ("avaxman/Directional", "d756bc53c15e79790fe020a64350f8dc6cf30e92")
_DIRECTIONAL_NEW = ("avaxman/Directional", "25738730958f0bfa68289ae628a5cd3c4b719d61")
_GT = ("Frank-ZY-Dou/Geometry_Tools", "5befc9ee1af6850a8893fd500c341308527264ce")
_MATFP = ("ningnawang/MATFP", "1f1ec5b2a5c0011d078a80cf1e1d3655ce5eb2a5")
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
_AS_GIVEN_ROWS = [
    # meshes as people have them (issue 31): scans, CAD exports with unwelded seams, crossing faces,
    # small holes, non-manifold edges, several shells, a triangle soup; the genus is from the Euler
    # characteristic with the holes capped (half-integers: pinched vertices)
    ("gt-crab", _GT, "data/01crab.off", 0, 5002,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-dog", _GT, "data/01dog.off", 0, 3911,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-fertility", _GT, "data/01fertility.off", 4, 17827,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-hand", _GT, "data/01hand.off", 0, 37136,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-human", _GT, "data/01human-2/01human-2.off", 0, 5002,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-vase", _GT, "data/01vase.off", 5, 14859,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-hand-shells", _GT, "data/01Hand.obj", 3, 5002,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("gt-sphere-soup", _GT, "sphere_I_perturbed_triangular_soup.obj", 0, 15360,
     f"{_NO_LICENCE}; Geometry_Tools sample data (Coverage Axis / MAT test shapes), origin unstated"),
    ("abc-00000068", _MATFP, "models/00000068_767e4372b5f94a88a7a17d90_trimesh_009.obj", 4, 7871,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00000077", _MATFP, "models/00000077_767e4372b5f94a88a7a17d90_trimesh_018.obj", 0, 19842,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00000125", _MATFP, "models/00000125_e18c7feacfb54f3880659b43_trimesh_000.obj", 3, 6164,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00000329", _MATFP, "models/00000329_12a935cd9b684f879c0505fe_trimesh_000.obj", 3, 5502,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00000801", _MATFP, "models/00000801_ad6107d9fc994ccca38cc4e4_trimesh_003.obj", 9, 18125,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00000802", _MATFP, "models/00000802_ad6107d9fc994ccca38cc4e4_trimesh_004.obj", 4, 11757,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("abc-00001029", _MATFP, "models/00001029_cde47df6e28543d1b434f206_trimesh_001.obj", 0, 14778,
     "host repo MIT; ABC dataset CAD model (Onshape public documents, ABC terms of use)"),
    ("matfp-bear", _MATFP, "models/bear.off", 0, 10141,
     "host repo MIT; origin unstated"),
    ("alligator", _COMMON, "data/alligator.obj", 0, 3208,
     f"{_NO_LICENCE}; Alec Jacobson (thesis model)"),
    ("beast", _COMMON, "data/beast.obj", 1, 33963,
     f"{_NO_LICENCE}; Autodesk (Weber et al. 2007)"),
    ("beetle", _COMMON, "data/beetle-alt.obj", 1, 19887,
     f"{_NO_LICENCE}; Ivan Sutherland's 1972 VW Beetle mesh (common alt)"),
    ("cheburashka", _COMMON, "data/cheburashka.obj", 0, 6669,
     f"{_NO_LICENCE}; Ilya Baran(?)"),
    ("cow", _COMMON, "data/cow.obj", 0.5, 2903,
     f"{_NO_LICENCE}; Viewpoint Animation Engineering / Sun Microsystems"),
    ("homer", _COMMON, "data/homer.obj", 0, 6002,
     f"{_NO_LICENCE}; origin unclear (via Pierre Alliez)"),
    ("nefertiti", _COMMON, "data/nefertiti.obj", 0, 49971,
     f"{_NO_LICENCE}; Nefertiti bust scan, Berlin Egyptian Museum (Thingiverse 3974391)"),
    ("ogre", _COMMON, "data/ogre.obj", 1, 62194,
     f"{_NO_LICENCE}; Kiaran Ritchie"),
    ("spot", _COMMON, "data/spot.obj", 0, 3225,
     f"{_NO_LICENCE}; Keenan Crane's model repository (CC0)"),
    ("stanford-bunny", _COMMON, "data/stanford-bunny.obj", 0, 34834,
     f"{_NO_LICENCE}; Stanford 3D Scanning Repository, research use"),
    ("teapot", _COMMON, "data/teapot.obj", 0.5, 3644,
     f"{_NO_LICENCE}; Martin Newell's Utah teapot"),
    ("thingi-1146164", _DIRECTIONAL_NEW, "tutorial/data/1146164.off", 4, 2056,
     f"{_NO_LICENCE} (sources MPL-2.0); Thingi10K file 1146164, licence of its Thingiverse author"),
    ("thingi-129110", _DIRECTIONAL_NEW, "tutorial/data/129110__sf.obj", 24, 4989,
     f"{_NO_LICENCE} (sources MPL-2.0); Thingi10K file 129110, licence of its Thingiverse author"),
    ("thingi-60745", _DIRECTIONAL_NEW, "tutorial/data/60745__sf.obj", 0, 11973,
     f"{_NO_LICENCE} (sources MPL-2.0); Thingi10K file 60745, licence of its Thingiverse author"),
    ("thingi-697224", _DIRECTIONAL_NEW, "tutorial/data/697224__sf.obj", 1, 3464,
     f"{_NO_LICENCE} (sources MPL-2.0); Thingi10K file 697224, licence of its Thingiverse author"),
    ("chassis-upright", _DIRECTIONAL, "tutorial/data/Chassis_-_upright_f_l-1_front_upright-1_B9-1.off", 2, 1396,
     f"{_NO_LICENCE} (sources MPL-2.0); CAD part, origin unstated"),
    ("deckel", _DIRECTIONAL_NEW, "tutorial/data/deckel_input.off", 4, 5000,
     f"{_NO_LICENCE} (sources MPL-2.0); CAD part, origin unstated"),
    ("universal-joint", _DIRECTIONAL_NEW, "tutorial/data/modular_universal_joint.off", 2, 5299,
     f"{_NO_LICENCE} (sources MPL-2.0); CAD part, origin unstated"),
    ("orc", _DIRECTIONAL, "tutorial/data/orc_84k_tri.obj", 0, 43111,
     f"{_NO_LICENCE} (sources MPL-2.0); origin unstated"),
    ("lion", _DIRECTIONAL, "tutorial/data/lion.off", 0, 8356,
     f"{_NO_LICENCE} (sources MPL-2.0); origin unstated"),
    ("chipped-torus", _DIRECTIONAL, "tutorial/data/chipped-torus.obj", 1, 2208,
     f"{_NO_LICENCE} (sources MPL-2.0); origin unstated"),
    ("cup", _AVAXMAN, "data/cup_input_simple_10000.off", 2, 10000,
     f"{_NO_LICENCE}; origin unstated"),
    ("dancer", _AVAXMAN, "data/dancer_25k.off", 1, 24998,
     f"{_NO_LICENCE}; origin unstated (AIM@SHAPE Dancer?)"),
    ("dragon", _AVAXMAN, "data/dragon.off", 0, 12494,
     f"{_NO_LICENCE}; Stanford dragon, decimated, research use"),
    ("joint", _AVAXMAN, "data/joint.off", 2, 20902,
     f"{_NO_LICENCE}; origin unstated"),
    ("camel", _AVAXMAN, "data/camel.off", 1, 34546,
     f"{_NO_LICENCE}; Sumner and Popovic's camel (deformation transfer data)"),
    ("knot", _CFWEN, "data/knot.obj", 1, 1573,
     "host repo MIT; origin unstated"),
    ("three-holes", _LIBIGL, "3holes.off", 3, 3596,
     f"{_NO_LICENCE}; origin unstated"),
    ("camel-pinched", _LIBIGL, "camel_b.obj", 0.5, 2032,
     f"{_NO_LICENCE}; origin unstated"),
    ("truck", _LIBIGL, "truck.obj", 42, 2956,
     f"{_NO_LICENCE}; CAD assembly, origin unstated"),
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
    "gt-crab": "697239b80ee9a5a7f91c717412973ba69b40d276c41fa0f5e8133c007660e77b",
    "gt-dog": "a3e0c0b03a42ecce7e2a8083def04718d11f7d59e2f22d76de52078141a96f91",
    "gt-fertility": "24d27a650b158703562c126d98e0b355e0c8b4ec3ae923291c364f97d9e0275c",
    "gt-hand": "8b9e0b8fdbdf0db33c0a72f3616ec1b5d0b3606383f5821aaea1c96ba48f0f9a",
    "gt-human": "615956df4a0b020e79288d0da6217626c6bce3906c0cc8edee5a132ef3380a42",
    "gt-vase": "d400aa7c47f88fd0a2e50e7f61f3b1fd67283e2ce93fafdfb3b9fbfb816b7b84",
    "gt-hand-shells": "3d84a3616eba8e6656f963a43dcc73ae3cedee5591310bbfb1b12c8f988554f7",
    "gt-sphere-soup": "e4474a730421cf5cce0bf95097107c12fdc6dcbd6defbff2acc0c6dd18ebc45f",
    "abc-00000068": "acdb2b914e03a3697d4acf5fe52a85568f3aec24907b7525bbe420e9c5432b99",
    "abc-00000077": "2bf4aa51f85cacf2adbf76e21cafcd65da0c3039dfd7fd4d5857ef80b10dca38",
    "abc-00000125": "36cf5aa9bd7675af6eea440a5e6747aede2bfb2122bec269f703043a2efaa626",
    "abc-00000329": "e8195cebee3b3233068c7f40d09439e6c829a4f835336692ff0afe8ad5e15bce",
    "abc-00000801": "54d91489de2953a98d18e406d0eed59401e5c2c94457702e4a372df552069318",
    "abc-00000802": "748a29e0d3fc41461ccb9295c05dbc38c06e5ed48e16df682828adeb0ee4907c",
    "abc-00001029": "69eaa6cebfef5c499466d660012093c5974539d5d3bb5be54569e20e72b11bb1",
    "matfp-bear": "b7342aa4cfbb0bd18833818ecd955ecca9709b6a44389843d4ddbf7b7753d03b",
    "alligator": "108a1f4319e4a069b2bfbee3b5f278551501d75c473bb705c62e2bef872ad544",
    "beast": "74c5fecd883b761bc1b2bb6c82fe94d3b3b450297ab561e83c0e63c7ed46abe8",
    "beetle": "4528700590e20363b27e8ab77a4af6199a59b94ab6b849c9ba5a4a36f7c5b8cd",
    "cheburashka": "b2ac59bc1112f1b3e086ac0285d9be7fdefef278a32151a79e650414b2244f3f",
    "cow": "69afce548640bc2beb0c44894d1a24d5766cc9cd3fd74f3ec55b4e229104b23f",
    "homer": "b20b1391fd62964f65703d748514d86d747d1202d38e55e0f1addac7a5a10e8b",
    "nefertiti": "19e39748b145092878cc4faafd050505eb5991c5d3e497be2b4575673fa87968",
    "ogre": "b72e270246ec3bd91bd8e082c4acf462352680f09067813322903b4e1a3f6967",
    "spot": "0738b5e8608fed74e5e8c7aa8dd0af97b4b74f9f6cbf7aac84cd7e40b2e44a75",
    "stanford-bunny": "1eb35d1e21ce99e5ce911353b6be278990713448dd9e8f5c9387f9de39b32205",
    "teapot": "1b5396fedd74b577e32cef41146582c2f2e1a050d5b4915193c0ac1ad4187ed4",
    "thingi-1146164": "3bc64801864e742110f816bcd71e924f1146abee3340d024def8968484ffadcf",
    "thingi-129110": "a5a20f3c3acf38dc2074aaa6fd28158d779072e6ef902210f46fef138223c6a7",
    "thingi-60745": "3cb65f0cc9c38589bf5e763193556485b3d3b63307440146470046770d32cfd4",
    "thingi-697224": "c4eb2beae37ee3c15421d7519d92130e8826163cdcb6242566ee92200d000c7e",
    "chassis-upright": "477d37d7d2366e0fa044a775ebb4ff7ecccf3c158be204816375ac84706f39a8",
    "deckel": "7d275a76fdca6ebc4bbe2c698163f85b95820ddb26e924f1588cfe61f019d8e9",
    "universal-joint": "6d5785584d448bcfc30a22984e0ef5b8aeacb7571c75174f83fa26f9fd9a6ff8",
    "orc": "0a180246c1776fa50b63983de161df65832bbb82c5f4a69e38e5549673d45bf9",
    "lion": "eff3b6021044aeae2d64c147cc0ad4ee16042e16c2c5d336efa86031cc815df4",
    "chipped-torus": "8d0a5aa57070a66e5b250a208d92e6d77db29fb06c39c2e679d81d0e423ce30e",
    "cup": "2fc48cadc5e1101ca4524e754bc1ee2fde6631984cf4d3dac1c0e901477e5a0a",
    "dancer": "1828e94dc404467d721947ef79cd7413c03abe405ca238db739f5bcd0ebb75c5",
    "dragon": "20839e63efc7b8a155e91ab70209949980ea5b8145cd90d0258068211089887b",
    "joint": "e13de1de91ea14f72c94c6c33b8b71fa4f72ab9d36878f20ff7315a8d4311976",
    "camel": "76b292b762771a93c9128ddca8effb136b22fc13d6bd85b99d67e5f3a946cce3",
    "knot": "445d78adec5662c9d657c8203b423e8a454ae5d3193314be50bee41ea57b3664",
    "three-holes": "e8b1038cc70d11f393d8894ac08a5106293c50e95a5a60f0d5a8c8a7e884d106",
    "camel-pinched": "91f7a9a22a273e3dc4c9eab85674ac2a04355f21699a18032f2d5f1f7a7f62c4",
    "truck": "c3aeca508490cbb8a0d58131619685b6cee82eb51c0af4ded984dac5ee9f3c11",
}


def _table(rows: list) -> list[dict]:
    return [
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
        for name, (repo, commit), path, genus, vertices, licence in rows
    ]


MODELS = _table(_ROWS)
AS_GIVEN = _table(_AS_GIVEN_ROWS)
ALL_MODELS = MODELS + AS_GIVEN


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


def _select(names: list[str] | None) -> list[dict]:
    """``MODELS`` by default (the benchmarks written for them), else the named ones of ``ALL_MODELS``."""
    if names is None:
        return MODELS
    unknown = set(names) - {m["name"] for m in ALL_MODELS}
    if unknown:
        raise ValueError(f"unknown models: {', '.join(sorted(unknown))}")
    return [m for m in ALL_MODELS if m["name"] in names]


def fetch_models(cache_dir: str | os.PathLike, names: list[str] | None = None) -> dict[str, Path]:
    """Make sure each model is in the cache, downloading the missing ones.

    Parameters
    ----------
    cache_dir : str or os.PathLike
        Directory holding ``<name><suffix>`` files; created if absent.
    names : list of str, optional
        These models of ``ALL_MODELS`` (default: ``MODELS``).

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
    for model in _select(names):
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


def _git_dir(mirror: Path, repo: str) -> Path | None:
    """The git directory of ``owner/name`` under ``mirror`` (``owner+name/repo[/.git]`` or ``owner/name[/.git]``)."""
    for base in (mirror / repo.replace("/", "+") / "repo", mirror / repo.replace("/", "+"), mirror / repo):
        for candidate in (base / ".git", base):
            if (candidate / "HEAD").is_file():
                return candidate
    return None


def fill_from_mirror(cache_dir: str | os.PathLike, mirror_dir: str | os.PathLike,
                     names: list[str] | None = None) -> dict[str, Path]:
    """Fill the cache from local git clones or snapshots instead of downloading.

    Parameters
    ----------
    cache_dir : str or os.PathLike
        The model cache; created if absent.
    mirror_dir : str or os.PathLike
        Directory of clones, one per repository, named ``owner+name/repo``
        (a git directory, bare or with a ``.git``), ``owner+name`` or
        ``owner/name``; each model is read with ``git show commit:path``.
    names : list of str, optional
        These models of ``ALL_MODELS`` (default: ``MODELS``).

    Returns
    -------
    dict of str to Path
        As :func:`fetch_models`: the models in the cache after the call, each
        checked by SHA-256 when it was copied in.
    """
    cache, mirror = Path(cache_dir), Path(mirror_dir)
    cache.mkdir(parents=True, exist_ok=True)
    paths = {}
    for model in _select(names):
        target = _cached(cache, model)
        if not target.exists():
            git = _git_dir(mirror, model["repo"])
            if git is None:
                print(f"{model['name']}: no clone of {model['repo']} under {mirror}", file=sys.stderr)
                continue
            done = subprocess.run(["git", "--git-dir", str(git), "show", f"{model['commit']}:{model['path']}"],
                                  capture_output=True, check=False)
            if done.returncode:
                print(f"{model['name']}: {done.stderr.decode(errors='replace').strip()}", file=sys.stderr)
                continue
            if hashlib.sha256(done.stdout).hexdigest() != model["sha256"]:
                print(f"{model['name']}: {model['path']} at {model['commit'][:10]} does not match its SHA-256",
                      file=sys.stderr)
                continue
            part = target.with_name(target.name + ".part")
            part.write_bytes(done.stdout)
            part.replace(target)
        paths[model["name"]] = target
    return paths


def describe(path: str | os.PathLike, *, crossings: bool = True) -> dict:
    """Measure a mesh file's size and topology, as trimesh reads it.

    Parameters
    ----------
    path : str or os.PathLike
        Mesh file readable by trimesh.
    crossings : bool
        Also count the pairs of faces that cross (with medialaxis's own
        test, :func:`medialaxis.mesh.solid.crossings.crossing_pairs`; ``None``
        where that is not available).

    Returns
    -------
    dict
        ``vertices``, ``faces``, ``welded`` (vertices merged because the
        file does not share them between faces, as a triangle soup),
        ``components`` (edge-connected shells), ``euler`` (V - E + F),
        ``holes`` (loops of edges with one face), ``open_edges``,
        ``crowded_edges`` (edges of more than two faces), ``genus`` (total
        over shells of the closed surface, holes capped:
        ``components - (euler + holes) / 2``), ``watertight``, ``oriented``
        and ``crossing_pairs``.
    """
    import numpy as np
    import trimesh
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    mesh = trimesh.load(path, force="mesh", process=False)
    vertices = len(mesh.vertices)
    welded = 0
    if not mesh.is_watertight:
        soup = mesh.copy()
        soup.merge_vertices(merge_tex=True, merge_norm=True)
        if soup.is_watertight or len(soup.vertices) < vertices:
            welded = vertices - len(soup.vertices)
            mesh = soup
    labels = trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces))
    components = int(labels.max()) + 1
    used = len(np.unique(mesh.faces))  # vertices of no face are no part of the surface
    euler = used - len(mesh.edges_unique) + len(mesh.faces)
    shared = np.bincount(mesh.edges_unique_inverse, minlength=len(mesh.edges_unique))
    open_edges = mesh.edges_unique[shared == 1]
    holes = 0
    if len(open_edges):
        n = len(mesh.vertices)
        graph = coo_matrix((np.ones(len(open_edges)), (open_edges[:, 0], open_edges[:, 1])), shape=(n, n))
        _, lab = connected_components(graph, directed=False)
        holes = len(np.unique(lab[np.unique(open_edges)]))
    pairs = None
    if crossings:
        try:
            from medialaxis.mesh.solid.crossings import crossing_pairs
        except ImportError:
            pass
        else:
            pairs = int(len(crossing_pairs(mesh)))
    return {
        "vertices": vertices,
        "faces": len(mesh.faces),
        "welded": welded,
        "components": components,
        "euler": int(euler),
        "holes": holes,
        "open_edges": int((shared == 1).sum()),
        "crowded_edges": int((shared > 2).sum()),
        "genus": components - (euler + holes) / 2,
        "watertight": bool(mesh.is_watertight),
        "oriented": bool(mesh.is_winding_consistent),
        "crossing_pairs": pairs,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cache", type=Path, default=default_cache(), help="model cache directory")
    parser.add_argument("--list", action="store_true", help="print the cached models without downloading")
    parser.add_argument("--all", action="store_true", help="ALL_MODELS, not only MODELS")
    parser.add_argument("--from-mirror", type=Path, help="fill the cache from local git clones (owner+name/repo)")
    args = parser.parse_args()

    models = ALL_MODELS if args.all else MODELS
    names = [m["name"] for m in models]
    if args.list:
        paths = {m["name"]: _cached(args.cache, m) for m in models if _cached(args.cache, m).exists()}
    elif args.from_mirror:
        paths = fill_from_mirror(args.cache, args.from_mirror, names)
    else:
        paths = fetch_models(args.cache, names)
    print(f"{'name':<16} {'vertices':>8} {'shells':>6} {'genus':>5} {'holes':>5} {'crossing':>8} watertight oriented"
          "  licence")
    for model in models:
        if model["name"] in paths:
            d = describe(paths[model["name"]])
            row = (f"{model['name']:<16} {d['vertices']:>8} {d['components']:>6} {d['genus']:>5g} {d['holes']:>5} "
                   f"{d['crossing_pairs']!s:>8} {d['watertight']!s:>10} {d['oriented']!s:>8}")
            print(f"{row}  {model['licence']}")


if __name__ == "__main__":
    main()
