"""The rh_gallery program as a user runs it: outputs, determinism, errors."""
import math
import subprocess
import xml.etree.ElementTree as ET

import pytest

SVG = "{http://www.w3.org/2000/svg}"


def run(exe, *args):
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=120)


def test_list_names_every_example(gallery_exe):
    r = run(gallery_exe, "--list")
    assert r.returncode == 0
    names = [line.split("\t")[0] for line in r.stdout.splitlines()]
    assert names == ["stripes", "grid", "uniform", "random", "puzzle", "rosettes", "cracks",
                     "bimodal", "crosses", "curves", "clusters", "overview",
                     "teaser_a", "teaser_b", "teaser_c", "teaser_d", "teaser_e", "teaser_f", "teaser_g",
                     "teaser_h", "combine_a", "combine_b", "combine_c", "combine_d", "combine_e",
                     "combine_f", "combine_g", "combine_h",
                     "regular_a", "regular_b", "regular_c", "regular_d", "nonregular_a_left",
                     "nonregular_a_right", "nonregular_b", "nonregular_c", "nonregular_d",
                     "script_edit_a", "script_edit_b", "script_edit_c", "script_edit_d",
                     "triangles", "bee_hive", "wallpaper_p6", "wallpaper_p4m", "wallpaper_p31m",
                     "escher_p6", "escher_p4m", "escher_p31m", "parquetry", "table", "bottle", "teapot",
                     "microprocessor", "tiled_a", "tiled_b", "tiled_c", "tiled_d", "oriented_darts",
                     "discrete_1a", "discrete_1b", "discrete_1c", "discrete_1d", "discrete_1e", "discrete_1f",
                     "discrete_1g", "synth_circle", "synth_curve", "synth_rectangle"]


@pytest.mark.parametrize("name,minimum", [("puzzle", 400), ("rosettes", 300), ("cracks", 1000),
                                          ("clusters", 400), ("overview", 1000),
                                          ("combine_e", 50), ("combine_g", 250)])
def test_outputs_are_svg_drawings(gallery_exe, tmp_path, name, minimum):
    r = run(gallery_exe, "--out", tmp_path, "--only", name)
    assert r.returncode == 0, r.stderr
    root = ET.parse(tmp_path / f"{name}.svg").getroot()
    assert root.tag == SVG + "svg"
    assert root.get("viewBox") == "0 0 2000 2000"
    shapes = root.findall(f".//{SVG}polyline") + root.findall(f".//{SVG}polygon")
    assert len(shapes) >= minimum
    # Every coordinate parses as a finite number (a shape has two points or more).
    for s in shapes:
        pairs = s.get("points").split()
        assert len(pairs) >= 2
        for pair in pairs:
            x, y = pair.split(",")
            assert math.isfinite(float(x)) and math.isfinite(float(y))


def test_same_bytes_whatever_the_thread_count(gallery_exe, tmp_path):
    one, two = tmp_path / "one", tmp_path / "two"
    assert run(gallery_exe, "--out", one, "--threads", 1, "--only", "clusters,overview,cracks").returncode == 0
    assert run(gallery_exe, "--out", two, "--threads", 2, "--only", "clusters,overview,cracks").returncode == 0
    for name in ("clusters", "overview", "cracks"):
        assert (one / f"{name}.svg").read_bytes() == (two / f"{name}.svg").read_bytes(), name


def test_seed_changes_the_drawing(gallery_exe, tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    assert run(gallery_exe, "--out", a, "--seed", 1, "--only", "puzzle").returncode == 0
    assert run(gallery_exe, "--out", b, "--seed", 2, "--only", "puzzle").returncode == 0
    assert (a / "puzzle.svg").read_bytes() != (b / "puzzle.svg").read_bytes()


def test_unknown_example_is_named(gallery_exe, tmp_path):
    r = run(gallery_exe, "--out", tmp_path, "--only", "puzzle,nonesuch")
    assert r.returncode == 1
    assert "no example named 'nonesuch'" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("args,message", [
    (["--threads", "two"], "--threads: 'two' is not a non-negative integer"),
    (["--seed", "-4"], "--seed: '-4' is not a non-negative integer"),
    (["--bogus"], "unknown option '--bogus'"),
    (["--out"], "--out needs a value"),
])
def test_bad_options(gallery_exe, args, message):
    r = run(gallery_exe, *args)
    assert r.returncode == 2
    assert message in r.stderr


def test_missing_elements_folder_fails_cleanly(gallery_exe, tmp_path):
    r = run(gallery_exe, "--out", tmp_path / "out", "--only", "puzzle", "--elements", tmp_path / "none")
    assert r.returncode == 1
    assert "ImportSVG" in r.stderr and "zig2.svg" in r.stderr and "cannot open" in r.stderr
    assert not (tmp_path / "out" / "puzzle.svg").exists()
    assert not list((tmp_path / "out").glob("*.tmp"))
