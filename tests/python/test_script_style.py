"""A style none of the seven, written by the tests from libtex operators only
(style_scripts/framed_tiles.py), runs through `rockhatch --script` and `carto.run` with the
same bytes; the QGIS algorithm runs it too (test_qgis_plugin.py)."""
import subprocess

from osgeo import ogr

from rockhatch import carto
from conftest import python_env

import pathlib

SCRIPT = pathlib.Path(__file__).resolve().parent / "style_scripts" / "framed_tiles.py"


def test_an_operator_style_through_the_command_and_carto_run(rockhatch_exe, sample_dir, tmp_path):
    inputs = ["--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg", "--seed", "5"]
    r = subprocess.run([str(a) for a in [rockhatch_exe, *inputs, "--script", SCRIPT, "--param", "tile=5",
                                         "-o", tmp_path / "cli.gpkg", "-o", tmp_path / "cli.svg"]],
                       capture_output=True, text=True, timeout=600, env=python_env())
    assert r.returncode == 0, r.stderr
    stats = carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "py.svg"],
                      style=str(SCRIPT), params={"tile": 5}, seed=5)
    assert stats.faces == 20 and stats.hatches > 1000
    assert (tmp_path / "py.svg").read_bytes() == (tmp_path / "cli.svg").read_bytes()
    # What the program draws: tile outlines shrunk to 0.6 of 5 mm (30 m a side at 1:10000)
    # as ridge strokes, fill hatching elsewhere.
    ds = ogr.Open(str(tmp_path / "cli.gpkg"))
    sides = [f.GetGeometryRef().Length() for f in ds.GetLayerByName("hatch_ridge")]  # a tile's edges
    assert sum(1 for l in sides if abs(l - 30) < 0.01) > 200
    assert all(l <= 30 + 0.01 for l in sides)
    assert ds.GetLayerByName("hatch_fill").GetFeatureCount() > 1000
    # Its parameter table is the script's.
    r = subprocess.run([str(rockhatch_exe), *map(str, inputs), "--script", str(SCRIPT), "--param", "nope=1",
                        "-o", str(tmp_path / "x.svg")], capture_output=True, text=True, timeout=600, env=python_env())
    assert r.returncode != 0 and "framed-tiles" in r.stderr and "nope" in r.stderr
