"""styles/: one Python script per design iteration of Fig. 5.4. Each lists its parameters
in its header, has the parameters of the built-in style of the same name, runs on its own
and through `rockhatch --script`, and draws exactly what the built-in C++ style draws."""
import importlib
import re
import subprocess
import sys

import pytest

from rockhatch import carto
from conftest import STYLES, features_by_face, python_env

# The rock styles; the terrain styles (scree, slope-hachures) draw outside the faces and are
# not per-face scripts (tests/python/test_terrain_styles.py).
SCRIPTS = {s.name: s.name.replace("-", "_") + ".py" for s in carto.styles() if not s.terrain}


def load(name):
    sys.path.insert(0, str(STYLES))
    try:
        return importlib.import_module(SCRIPTS[name][:-3])
    finally:
        sys.path.remove(str(STYLES))


def test_one_script_per_iteration():
    # One script per built-in style; what they share lives in modules named _*.py, which
    # are not styles (they define no style()).
    assert len(SCRIPTS) == 10
    assert sorted(p.name for p in STYLES.glob("*.py") if not p.name.startswith("_")) == sorted(SCRIPTS.values())
    for shared in STYLES.glob("_*.py"):
        assert not re.search(r"^def style\(", shared.read_text(), re.M), shared.name


@pytest.mark.parametrize("name", sorted(SCRIPTS))
def test_header_and_parameters_match_the_builtin(name):
    module = load(name)
    builtin = carto.find_style(name)
    assert module.NAME == name and module.FIGURE == builtin.figure
    assert getattr(module, "CREST_ORNAMENT", False) == builtin.crest_ornament
    assert [(p[0], p[1], p[2]) for p in module.PARAMS] == [(p.name, p.value, p.unit) for p in builtin.params]
    # The header's parameter lines are made from PARAMS, as --list-styles prints them.
    header = module.__doc__
    for pname, value, unit, _ in module.PARAMS:
        line = re.search(rf"^\s+{pname} = (\S+) (\S+)\s", header, re.M)
        assert line, f"{name}: the header does not list {pname}"
        assert float(line.group(1)) == value and line.group(2) == unit, f"{name}: header of {pname}"


def test_the_blocks_are_the_builtins_own():
    # The scripts compose native blocks: no block is written in Python, and the parameter
    # tables are the C++ ones.
    from rockhatch.carto import blocks
    assert not list(STYLES.glob("_*.py"))
    assert type(blocks.toned_hatching).__name__ == "builtin_function_or_method"
    print_params = carto.find_style("print").params
    tables = blocks.TONE + blocks.TONE_CELLS + blocks.BALANCED + blocks.CREST + blocks.CROSS
    assert [(p.name, p.value, p.unit, p.help) for p in print_params] == tables
    face = blocks.FaceReading()
    assert (face.theta, face.density, face.height) == (0.0, 0.5, 0.5)
    # The print style's check of its tone parameters is the built-in's: a usage error.
    with pytest.raises(carto.RockhatchError, match="tone_min=0.5 is above tone_max=0.1") as e:
        blocks.check_tone({"tone_min": 0.5, "tone_max": 0.1, "ink_max": 0.4, "gap": 0.95})
    assert e.value.code == 2


def run(args, **kw):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=600, env=python_env(), **kw)


@pytest.mark.parametrize("name", sorted(SCRIPTS))
def test_the_script_draws_what_the_builtin_draws(rockhatch_exe, sample_dir, tmp_path, name):
    inputs = ["--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg", "--seed", "11", "-q"]
    c = run([rockhatch_exe, *inputs, "--style", name, "-o", tmp_path / "c.gpkg", "-o", tmp_path / "c.svg"])
    assert c.returncode == 0, c.stderr
    p = run(["/usr/bin/python3", STYLES / SCRIPTS[name], *inputs, "-o", tmp_path / "p.gpkg", "-o", tmp_path / "p.svg"])
    assert p.returncode == 0, p.stderr
    assert re.search(r"20 faces, [1-9]\d* hatches", p.stderr)
    assert (tmp_path / "p.svg").read_bytes() == (tmp_path / "c.svg").read_bytes()
    # The same features, byte for byte; the files differ only in what records how they were
    # made (the script's digest and the command: rockhatch update's fingerprints).
    assert features_by_face(tmp_path / "p.gpkg") == features_by_face(tmp_path / "c.gpkg")
    from osgeo import ogr
    assert ogr.Open(str(tmp_path / "p.gpkg")).GetMetadataItem("RH_FRAME") == \
        ogr.Open(str(tmp_path / "c.gpkg")).GetMetadataItem("RH_FRAME")
    # A style of the table that asks for crest ornaments (aretes) gets the crest layer.
    assert ("crest" in layer_names(tmp_path / "c.gpkg")) == carto.find_style(name).crest_ornament


def layer_names(gpkg):
    from osgeo import ogr
    ds = ogr.Open(str(gpkg))
    return {ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount())}


def test_rockhatch_script_runs_a_style_script(rockhatch_exe, sample_dir, tmp_path):
    inputs = ["--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg", "-q"]
    c = run([rockhatch_exe, *inputs, "--style", "high-ridges", "--param", "gap=0.8", "-o", tmp_path / "c.svg"])
    s = run([rockhatch_exe, *inputs, "--script", STYLES / "high_ridges.py", "--param", "gap=0.8", "--threads", "1",
             "-o", tmp_path / "s.svg"])
    assert c.returncode == 0 and s.returncode == 0, s.stderr
    assert (tmp_path / "s.svg").read_bytes() == (tmp_path / "c.svg").read_bytes()


def test_script_errors(rockhatch_exe, sample_dir, tmp_path):
    inputs = ["--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg", "-o", tmp_path / "x.svg"]
    r = run([rockhatch_exe, *inputs, "--script", tmp_path / "missing.py"])
    assert r.returncode == 3 and "missing.py': no such file" in r.stderr
    (tmp_path / "empty.py").write_text("NAME = 'empty'\n")
    r = run([rockhatch_exe, *inputs, "--script", tmp_path / "empty.py"])
    assert r.returncode == 7 and "defines no style(fields, params)" in r.stderr
    (tmp_path / "broken.py").write_text(
        "from rockhatch.tex import Arrangement\n\n"
        "def style(fields, params):\n    def face_fn(region):\n        return 1 / 0\n    return Arrangement(face_fn)\n")
    r = run([rockhatch_exe, *inputs, "--script", tmp_path / "broken.py"])
    assert r.returncode == 1 and "ZeroDivisionError" in r.stderr and "face_fn" in r.stderr
    r = run([rockhatch_exe, *inputs, "--script", STYLES / "noisy.py", "--style", "noisy"])
    assert r.returncode == 2 and "exclude each other" in r.stderr
    r = run([rockhatch_exe, *inputs, "--script", STYLES / "noisy.py", "--param", "cell_jitter=1"])
    assert r.returncode == 7 and "no parameter 'cell_jitter'" in r.stderr
    assert not (tmp_path / "x.svg").exists()


def test_python_entry_point_shares_the_option_table(rockhatch_exe):
    py = run(["/usr/bin/python3", "-m", "rockhatch", "--help"])
    cpp = run([rockhatch_exe, "--help"])
    assert py.returncode == 0 and py.stdout == cpp.stdout and "--script PATH" in py.stdout
    bad = run(["/usr/bin/python3", "-m", "rockhatch", "--colour", "red"])
    assert bad.returncode == 2 and bad.stderr.strip() == "rockhatch: unknown option '--colour' (see --help)"
