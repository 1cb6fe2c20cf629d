"""Publishing the drawing (issue 42) through the command, Python and a Dask cluster: the
georeferenced PDF renders (poppler) as the SVG does (librsvg) and opens in QGIS with its CRS;
vector tiles draw each zoom level at its own scale, the same on a Dask cluster as in one
process; bad input gets the command's clear errors."""
import os
import shutil
import sqlite3
import subprocess

import numpy as np
import pytest
from conftest import SAMPLE, python_env
from osgeo import gdal, ogr
from PIL import Image

from rockhatch import carto

gdal.UseExceptions()
ogr.UseExceptions()

DEM = str(SAMPLE / "dem.tif")
FACES = str(SAMPLE / "partition.gpkg")
CI = os.environ.get("CI") == "true"


def need(tool):
    path = shutil.which(tool)
    if not path:
        if CI:
            pytest.fail(f"{tool} is missing: scripts/setup.sh installs it")
        pytest.skip(f"{tool} is missing (scripts/setup.sh installs it)")
    return path


def rh(exe, *args, check=True):
    p = subprocess.run([str(exe), "-q", *map(str, args)], capture_output=True, text=True, timeout=600)
    if check:
        assert p.returncode == 0, p.stderr
    return p


def grey(path):
    """A rendered page as grey levels over white (0 ink .. 255 paper)."""
    im = Image.open(path).convert("RGBA")
    white = Image.new("RGBA", im.size, "white")
    white.alpha_composite(im)
    return np.asarray(white.convert("L"), dtype=float)


def test_pdf_renders_as_the_svg_and_opens_in_qgis_with_its_crs(rockhatch_exe, tmp_path):
    need("pdftoppm")
    need("rsvg-convert")
    rh(rockhatch_exe, "--dem", DEM, "--partition", FACES, "--crest-ornament", "default",
       "-o", tmp_path / "map.pdf", "-o", tmp_path / "map.svg")
    # Both at 300 dpi: the page is the SVG's frame at true scale (190 mm), pixel for pixel.
    subprocess.run(["pdftoppm", "-r", "300", "-png", "-singlefile", tmp_path / "map.pdf", tmp_path / "pdf"], check=True)
    subprocess.run(["rsvg-convert", "-d", "300", "-p", "300", tmp_path / "map.svg", "-o", tmp_path / "svg.png"],
                   check=True)
    pdf, svg = grey(tmp_path / "pdf.png"), grey(tmp_path / "svg.png")
    assert pdf.shape == svg.shape
    ink_pdf, ink_svg = (255 - pdf).mean(), (255 - svg).mean()
    assert ink_svg > 20
    # The same ink within antialiasing and line caps (GDAL's PDF writer draws butt caps).
    assert abs(ink_pdf - ink_svg) < 0.1 * ink_svg, (ink_pdf, ink_svg)
    assert np.abs(pdf - svg).mean() < 10, np.abs(pdf - svg).mean()
    # Every stroke in its place: the difference is antialiasing, not displacement (a drawing
    # shifted by 2 px differs by far more).
    assert np.abs(pdf - svg).mean() < 0.5 * np.abs(pdf[:, 2:] - svg[:, :-2]).mean()

    env = dict(python_env(), QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=str(tmp_path))
    code = ("from qgis.core import QgsApplication, QgsRasterLayer\n"
            "app = QgsApplication([], False); app.initQgis()\n"
            f"l = QgsRasterLayer({str(tmp_path / 'map.pdf')!r}, 'map')\n"
            "print(l.isValid(), l.crs().authid(), round(l.extent().width()))\n"
            "app.exitQgis()\n")
    p = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert p.stdout.split()[:3] == ["True", "EPSG:2154", "1900"], p.stdout + p.stderr


def test_pdf_on_a_page_from_python(tmp_path):
    carto.run(DEM, FACES, [tmp_path / "a3.pdf"], page="A3")
    ds = gdal.OpenEx(str(tmp_path / "a3.pdf"), gdal.OF_RASTER, open_options=["DPI=72"])
    assert abs(ds.RasterXSize - 297 / 25.4 * 72) < 1 and abs(ds.RasterYSize - 420 / 25.4 * 72) < 1
    layers = {v for k, v in (s.split("=", 1) for s in ds.GetMetadata_List("LAYERS"))
              if k.endswith("_NAME")}
    assert {"fill", "ridge", "valley", "cross"} <= layers


def tile_features(path, zoom):
    """Per tile layer, the sorted (face id, geometry WKB) of every feature at a zoom level."""
    ds = gdal.OpenEx(str(path), gdal.OF_VECTOR, open_options=[f"ZOOM_LEVEL={zoom}"])
    out = {}
    for i in range(ds.GetLayerCount()):
        layer = ds.GetLayer(i)
        out[layer.GetName()] = sorted((f.GetField("face_id"), bytes(f.GetGeometryRef().ExportToWkb())) for f in layer)
    return out


def test_vector_tiles_draw_each_zoom_at_its_scale_the_same_on_dask(rockhatch_exe, tmp_path):
    p = rh(rockhatch_exe, "--dem", DEM, "--partition", FACES, "--zoom", "14-15", "-o", tmp_path / "rock.mbtiles")
    assert "vector tiles" in p.stderr
    db = sqlite3.connect(tmp_path / "rock.mbtiles")
    meta = dict(db.execute("SELECT name, value FROM metadata"))
    assert meta["format"] == "pbf" and meta["minzoom"] == "14" and meta["maxzoom"] == "15"
    largest = db.execute("SELECT max(length(tile_data)) FROM tiles").fetchone()[0]
    assert 0 < largest <= 500000
    z14, z15 = tile_features(tmp_path / "rock.mbtiles", 14), tile_features(tmp_path / "rock.mbtiles", 15)
    assert {"fill", "ridge", "valley", "cross"} <= set(z15)
    # Zoom 15 is drawn at twice zoom 14's scale: about four times its strokes.
    ratio = len(z15["fill"]) / len(z14["fill"])
    assert 2.5 < ratio < 6, ratio
    # The same levels through a tiled run on a real Dask cluster of 2 workers.
    env = python_env()
    d = subprocess.run([str(rockhatch_exe), "tiles", "-q", "--dem", DEM, "--partition", FACES, "--zoom", "14-15",
                        "--tile-size", "1000", "--workers", "2", "-o", str(tmp_path / "dask.mbtiles")],
                       capture_output=True, text=True, env=env, timeout=900)
    assert d.returncode == 0, d.stderr
    assert "vector tiles" in d.stderr
    for zoom, whole in ((14, z14), (15, z15)):
        assert tile_features(tmp_path / "dask.mbtiles", zoom) == whole, f"zoom {zoom}"
    assert not (tmp_path / "dask.mbtiles.tiles").exists()


@pytest.mark.parametrize("args, message", [
    (["--page", "A9", "-o", "{tmp}/x.pdf"], "--page 'A9'"),
    (["--page", "A4", "-o", "{tmp}/x.svg"], "--page needs a .pdf output"),
    (["--page", "40x40", "-o", "{tmp}/x.pdf"], "use a larger page"),
    (["--zoom", "3-25", "-o", "{tmp}/x.mbtiles"], "--zoom '3-25'"),
    (["--zoom", "16-12", "-o", "{tmp}/x.mbtiles"], "--zoom '16-12'"),
    (["--zoom", "14", "-o", "{tmp}/x.gpkg"], "--zoom needs a vector-tile output"),
])
def test_bad_publishing_options_get_a_clear_error(rockhatch_exe, tmp_path, args, message):
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    p = rh(rockhatch_exe, "--dem", DEM, "--partition", FACES, *args, check=False)
    assert p.returncode == 2, p.stderr
    assert message in p.stderr and p.stderr.count("\n") == 1, p.stderr
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("name", ["dem.pdf", "dem.mbtiles"])
def test_a_pdf_or_mbtiles_output_onto_an_input_is_refused(rockhatch_exe, tmp_path, name):
    # GDAL reads a raster by its content: a GeoTIFF named .pdf or .mbtiles is a DEM.
    dem = tmp_path / name
    shutil.copy(DEM, dem)
    before = dem.read_bytes()
    p = rh(rockhatch_exe, "--dem", dem, "--partition", FACES, "-o", dem, "--overwrite", check=False)
    assert p.returncode == 9, p.stderr
    assert "refusing to write onto an input" in p.stderr
    assert dem.read_bytes() == before
