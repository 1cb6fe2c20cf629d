"""Thesis-style Python scripts against their C++ twins: the Appendix A gallery, one script
per example (partitions, mappers, merges, utilities), written with `from rockhatch.tex
import *`, must give the very bytes rh_gallery writes."""
import subprocess
import sys

import pytest

from conftest import GALLERY_PY, python_env

FAMILIES = {
    "partitions": ["stripes", "grid", "uniform", "random"],
    "mappers": ["puzzle", "rosettes", "cracks", "bimodal", "crosses", "curves", "clusters", "overview"],
    "teasers": ["teaser_a", "teaser_b", "teaser_c", "teaser_d", "teaser_e", "teaser_f", "teaser_g", "teaser_h"],
    # The "Combining" section: its three textures alone (a to c), then their merges.
    "merges": ["combine_a", "combine_b", "combine_c", "combine_d", "combine_e", "combine_f", "combine_g",
               "combine_h"],
    # "Regular result" a to d, "Non regular result" a to d, "Script edition" a to d.
    "regular": ["regular_a", "regular_b", "regular_c", "regular_d"],
    "nonregular": ["nonregular_a_left", "nonregular_a_right", "nonregular_b", "nonregular_c", "nonregular_d"],
    "script_edition": ["script_edit_a", "script_edit_b", "script_edit_c", "script_edit_d"],
    "tilings": ["triangles", "bee_hive", "wallpaper_p6", "wallpaper_p4m", "wallpaper_p31m", "escher_p6", "escher_p4m",
                "escher_p31m"],
    # Textures filling an outline (ExportSVGinDomain).
    "domain": ["parquetry", "table", "bottle", "teapot"],
    # Traces, chips and solder joints (two merges with CROP_ADD_BOUNDARY, face labels).
    "micro": ["microprocessor"],
    # Tiled planar maps (thesis Fig. 4.5): a regular wall and three ghost mappers.
    "tiled": ["tiled_a", "tiled_b", "tiled_c", "tiled_d"],
    # A control field turning every element (thesis 5.3).
    "fields": ["oriented_darts"],
    # Seed 004's figures 1a-1g: dart throwing, relaxation, stream lines (rockhatch.discrete).
    "discrete": ["discrete_1a", "discrete_1b", "discrete_1c", "discrete_1d", "discrete_1e", "discrete_1f",
                 "discrete_1g"],
    # Topology-constrained synthesis along curves and in a rectangle (seed 002).
    "synthesis": ["synth_circle", "synth_curve", "synth_rectangle"],
}


@pytest.fixture(scope="module")
def cpp_gallery(gallery_exe, tmp_path_factory):
    out = tmp_path_factory.mktemp("cpp")
    r = subprocess.run([str(gallery_exe), "--out", str(out), "--threads", "1"], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    return out


@pytest.fixture(scope="module")
def py_gallery(tmp_path_factory):
    out = tmp_path_factory.mktemp("py")
    r = subprocess.run(["/usr/bin/python3", str(GALLERY_PY), "--out", str(out), "--threads", "2"],
                       capture_output=True, text=True, timeout=300, env=python_env())
    assert r.returncode == 0, r.stderr
    return out


def test_the_python_gallery_lists_every_cpp_example(gallery_exe):
    r = subprocess.run([str(gallery_exe), "--list"], capture_output=True, text=True, timeout=60)
    cpp = [line.split("\t")[0] for line in r.stdout.splitlines()]
    sys.path.insert(0, str(GALLERY_PY.parent))
    try:
        import gallery
    finally:
        sys.path.pop(0)
    assert list(gallery.EXAMPLES) == cpp
    assert sorted(sum(FAMILIES.values(), [])) == sorted(cpp)


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_python_scripts_write_the_bytes_of_their_cpp_twins(cpp_gallery, py_gallery, family):
    for name in FAMILIES[family]:
        cpp = (cpp_gallery / f"{name}.svg").read_bytes()
        py = (py_gallery / f"{name}.svg").read_bytes()
        assert len(cpp) > 1000, f"{name}: the C++ drawing is nearly empty"
        assert py == cpp, f"{name}: the Python script and the C++ example differ"


def test_seed_changes_the_python_output(tmp_path):
    for seed in (0, 5):
        r = subprocess.run(["/usr/bin/python3", str(GALLERY_PY), "--out", str(tmp_path / str(seed)), "--only",
                            "cracks", "--seed", str(seed)], capture_output=True, text=True, timeout=120,
                           env=python_env())
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "0" / "cracks.svg").read_bytes() != (tmp_path / "5" / "cracks.svg").read_bytes()
