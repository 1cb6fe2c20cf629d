"""The terrain styles scree and slope-hachures through the command and the Python module: their
layers, the same bytes at one and two threads, NoData and the parameter errors. Their geometry
(no overlap, fall line, density) is tested in tests/carto/test_terrain_styles.cpp."""
import math
import subprocess

import pytest
from osgeo import gdal, ogr

from rockhatch import carto
from conftest import SHARED_DEM, partition_with_scree, real_dem

gdal.UseExceptions()


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=600)


def polygons(gpkg, layer):
    ds = ogr.Open(str(gpkg))
    lyr = ds.GetLayerByName(layer)
    assert lyr is not None, f"{gpkg} has no layer {layer}"
    assert lyr.GetGeomType() == ogr.wkbPolygon
    return [f.GetGeometryRef().Clone() for f in lyr]


def test_the_style_table_lists_them():
    terrain = [s.name for s in carto.styles() if s.terrain]
    assert terrain == ["scree", "slope-hachures"]
    assert carto.default_style() == "rock"
    units = {p.name: p.unit for p in carto.find_style("slope-hachures").params}
    assert units["interval"] == "m" and units["spacing_min"] == "mm"


@pytest.mark.parametrize("style,layer", [("scree", "hatch_stone"), ("slope-hachures", "hatch_hachure")])
def test_command_writes_the_filled_layer(rockhatch_exe, sample_dir, tmp_path, style, layer):
    out = tmp_path / "t.gpkg"
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg",
            "--style", style, "-q", "-o", out, "-o", tmp_path / "t.svg")
    assert r.returncode == 0, r.stderr
    shapes = polygons(out, layer)
    assert len(shapes) > 1000
    assert all(g.IsValid() and g.GetArea() > 0 for g in shapes[:500])
    # The rock is hatched too, with the default style.
    assert ogr.Open(str(out)).GetLayerByName("hatch_fill").GetFeatureCount() > 1000
    svg = (tmp_path / "t.svg").read_text()
    assert f'<g id="{layer[6:]}" fill="black" stroke="none">' in svg


@pytest.mark.parametrize("style", ["scree", "slope-hachures"])
def test_same_bytes_at_one_and_two_threads(sample_dir, tmp_path, style):
    for threads in (1, 2):
        carto.run(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg"),
                  [str(tmp_path / f"{style}{threads}.svg")], style=style, threads=threads, seed=5)
    assert (tmp_path / f"{style}1.svg").stat().st_size > 100000, style
    assert (tmp_path / f"{style}1.svg").read_bytes() == (tmp_path / f"{style}2.svg").read_bytes(), style


def test_two_windows_draw_the_whole_runs_stones(rockhatch_exe, sample_dir, tmp_path):
    # --window with a terrain style: the window draws the elements whose tile of the style's
    # grid it owns, as the whole run draws them; two windows that meet draw them all once.
    dem, faces = sample_dir / "dem.tif", sample_dir / "partition.gpkg"
    base = [rockhatch_exe, "--dem", dem, "--partition", faces, "--style", "scree", "-q"]

    def stones(out):
        return sorted(bytes(g.ExportToWkb()) for g in polygons(out, "hatch_stone"))

    assert run(*base, "-o", tmp_path / "w.gpkg").returncode == 0
    whole = stones(tmp_path / "w.gpkg")
    x = 1004100  # the sample spans x 1,002,900 to 1,005,300
    windows = {"west": f"0,0,{x},1e8", "east": f"{x},0,2e6,1e8"}
    for name, box in windows.items():
        r = run(*base, "--window", box, "-o", tmp_path / f"{name}.gpkg")
        assert r.returncode == 0, r.stderr
    west = stones(tmp_path / "west.gpkg")
    assert len(west) > 500
    east = stones(tmp_path / "east.gpkg")
    assert len(east) > 500
    assert sorted(west + east) == whole


@pytest.mark.parametrize("args,message", [
    (["--style", "slope-hachures", "--param", "spacing_min=3"],
     "--param spacing_min: must not exceed spacing_max for style 'slope-hachures'"),
    (["--style", "scree", "--param", "stone_min=-1"], "--param stone_min: -1 is not a valid value (mm)"),
    (["--style", "scree", "--param", "interval=5"], "style 'scree' has no parameter 'interval'"),
])
def test_bad_parameters_give_one_line(rockhatch_exe, sample_dir, tmp_path, args, message):
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg",
            *args, "-q", "-o", tmp_path / "x.gpkg")
    assert r.returncode in (2, 7), r.stderr
    assert message in r.stderr and r.stderr.count("\n") == 1, r.stderr


def test_partition_none_is_for_terrain_styles_only(rockhatch_exe, sample_dir, tmp_path):
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", "none", "-q", "-o", tmp_path / "x.gpkg")
    assert r.returncode == 2 and "--partition none: style 'rock' hatches rock faces" in r.stderr
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", "none", "--style", "slope-hachures",
            "-o", tmp_path / "h.gpkg")
    assert r.returncode == 0, r.stderr
    assert "0 faces" in r.stderr
    assert ogr.Open(str(tmp_path / "h.gpkg")).GetLayerByName("hatch_fill").GetFeatureCount() == 0
    assert len(polygons(tmp_path / "h.gpkg", "hatch_hachure")) > 1000


def test_scree_layer_replaces_the_band(rockhatch_exe, sample_dir, tmp_path):
    # The sample's partition plus a polygon layer "scree" south-west of the summit.
    part = tmp_path / "partition.gpkg"
    box = partition_with_scree(sample_dir, part)
    out = tmp_path / "s.gpkg"
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", part, "--faces-layer", "faces",
            "--scree-layer", "scree", "--style", "scree", "-o", out)
    assert r.returncode == 0, r.stderr
    assert "1 scree area(s) from layer 'scree'" in r.stderr
    stones = polygons(out, "hatch_stone")
    assert len(stones) > 100
    grown = box.Buffer(1.0)
    assert all(grown.Contains(g) for g in stones)
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", part, "--scree-layer", "nope",
            "--style", "scree", "-q", "-o", tmp_path / "x.gpkg")
    assert r.returncode == 6 and "no layer named 'nope'" in r.stderr


def test_no_hachure_in_nodata(rockhatch_exe, sample_dir, tmp_path):
    # The sample's NoData corner (south-east) stays white: no stroke vertex in a NoData cell.
    out = tmp_path / "h.gpkg"
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", "none", "--style", "slope-hachures",
            "-q", "-o", out)
    assert r.returncode == 0, r.stderr
    ds = gdal.Open(str(sample_dir / "dem.tif"))
    band, gt = ds.GetRasterBand(1), ds.GetGeoTransform()
    a, nodata = band.ReadAsArray(), band.GetNoDataValue()
    assert (a == nodata).sum() > 1000, "the sample should hold NoData"
    # Cells within 3 cells of NoData: hachures reach there, so the check below is exercised.
    near = a == nodata
    for _ in range(3):
        grown = near.copy()
        grown[1:, :] |= near[:-1, :]
        grown[:-1, :] |= near[1:, :]
        grown[:, 1:] |= near[:, :-1]
        grown[:, :-1] |= near[:, 1:]
        near = grown
    hachures, close = 0, 0
    for g in polygons(out, "hatch_hachure"):
        hachures += 1
        for x, y in g.GetGeometryRef(0).GetPoints():
            c, r_ = math.floor((x - gt[0]) / gt[1]), math.floor((y - gt[3]) / gt[5])
            assert 0 <= r_ < a.shape[0] and 0 <= c < a.shape[1], (x, y)
            assert a[r_, c] != nodata, (x, y)
            close += bool(near[r_, c])
    assert hachures > 1000 and close > 10, (hachures, close)


@real_dem
@pytest.mark.parametrize("style,layer", [("scree", "hatch_stone"), ("slope-hachures", "hatch_hachure")])
def test_on_chamonix(rockhatch_exe, tmp_path, style, layer):
    # A 160 x 160 cell crop of the real DEM (read in place, cropped into tmp_path), its rock
    # extracted from it, at 1:25000.
    crop = tmp_path / "crop.tif"
    gdal.Translate(str(crop), str(SHARED_DEM), srcWin=[300, 250, 160, 160])
    out = tmp_path / "c.gpkg"
    r = run(rockhatch_exe, "--dem", crop, "--partition", "auto", "--style", style, "--scale", "25000",
            "-q", "-o", out)
    assert r.returncode == 0, r.stderr
    assert len(polygons(out, layer)) > 100
