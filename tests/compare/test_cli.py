"""The compare and search subcommands."""

import numpy as np

from medialaxis.cli import main


def test_compare_prints_distance_and_draws(kimia_dir, tmp_path, capsys):
    out = tmp_path / "match.png"
    a, b = kimia_dir / "class1_01.png", kimia_dir / "class1_02.png"
    assert main(["compare", str(a), str(b), "-o", str(out)]) == 0
    printed = capsys.readouterr().out.strip()
    assert float(printed) > 0
    assert out.stat().st_size > 1000
    assert main(["compare", str(a), str(a)]) == 0
    assert float(capsys.readouterr().out.strip()) == 0.0


def test_compare_reads_saved_axis(kimia_dir, tmp_path, capsys):
    import medialaxis as mx

    a = kimia_dir / "class3_05.png"
    saved = tmp_path / "axis.npz"
    mx.medial_axis(str(a)).save(saved)
    assert main(["compare", str(a), str(saved)]) == 0
    assert float(capsys.readouterr().out.strip()) == 0.0


def test_search_ranks_folder(kimia_dir, tmp_path, capsys):
    import shutil

    for name in ("class2_01", "class2_02", "class5_01", "class9_01"):
        shutil.copy(kimia_dir / f"{name}.png", tmp_path / f"{name}.png")
    (tmp_path / "notes.txt").write_text("not a shape")
    assert main(["search", str(kimia_dir / "class2_03.png"), str(tmp_path), "--top", "3", "--jobs", "1"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert len(lines) == 3
    ranks, dists, paths = zip(*(line.split("\t") for line in lines))
    assert ranks == ("1", "2", "3")
    assert np.all(np.diff([float(d) for d in dists]) >= 0)
    assert paths[0].endswith(("class2_01.png", "class2_02.png"))


def test_search_skips_bad_files(kimia_dir, tmp_path, capsys):
    import shutil

    shutil.copy(kimia_dir / "class4_01.png", tmp_path / "good.png")
    (tmp_path / "bad.png").write_bytes(b"not a png")
    assert main(["search", str(kimia_dir / "class4_02.png"), str(tmp_path)]) == 0
    captured = capsys.readouterr()
    assert "good.png" in captured.out and "skipped" in captured.err


def test_usage_and_input_errors(kimia_dir, tmp_path, capsys):
    a = str(kimia_dir / "class1_01.png")
    assert main(["compare", a]) == 2
    assert main(["compare", a, a, "-o", str(tmp_path / "x.txt")]) == 2
    assert main(["compare", a, str(tmp_path / "missing.png")]) == 1
    assert main(["search", a, str(kimia_dir), "--top", "0"]) == 2
    assert main(["search", a, str(tmp_path / "nowhere")]) == 1
    assert main(["search", a, str(tmp_path)]) == 1  # empty folder
    err = capsys.readouterr().err
    assert "error" in err and "Traceback" not in err
    assert main(["compare", "--help"]) == 0
    assert main(["search", "--help"]) == 0


def test_demo_case_writes_match_picture(demo_run):
    # the line and picture of this case in the run of ``medialaxis demo`` (tests/conftest.py), not computed again
    from medialaxis.cli.demo import DEMO_CASES, compare_case

    assert ("compare", compare_case) in DEMO_CASES
    _, lines, folder = demo_run
    assert len([line for line in lines if line.startswith("compare:")]) == 1
    assert (folder / "compare_match.png").stat().st_size > 1000


def test_search_draws_the_top_matches_as_a_grid(kimia_dir, tmp_path, capsys):
    import shutil

    from PIL import Image

    folder = tmp_path / "shapes"
    folder.mkdir()
    for name in ("class2_01", "class2_02", "class5_01", "class9_01", "class7_02"):
        shutil.copy(kimia_dir / f"{name}.png", folder / f"{name}.png")
    out = tmp_path / "grid.png"
    query = kimia_dir / "class2_03.png"
    assert main(["search", str(query), str(folder), "--top", "4", "--columns", "3", "--jobs", "1", "-o", str(out)]) == 0
    assert len(capsys.readouterr().out.strip().splitlines()) == 4
    with Image.open(out) as im:  # two rows of three panels: the query and four matches
        assert im.width > im.height > 300
        grey = np.asarray(im.convert("L"))
    assert (grey < 128).mean() > 0.005  # shapes and text drawn, not a blank page
    # Refused before any work: a picture path that is an input, a bad format, a bad column count.
    assert main(["search", str(query), str(folder), "-o", str(folder / "class2_01.png")]) == 2
    assert main(["search", str(query), str(folder), "-o", str(tmp_path / "grid.txt")]) == 2
    assert main(["search", str(query), str(folder), "--columns", "0"]) == 2
    assert sorted(p.name for p in folder.iterdir()) == sorted(f"{n}.png" for n in (
        "class2_01", "class2_02", "class5_01", "class9_01", "class7_02"))
