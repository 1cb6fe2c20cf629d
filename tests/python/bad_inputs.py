"""Every input and option of the rockhatch command and its partition and update subcommands, with the
bad values tried on each, the exit code and the words the one-line message must contain.

One table serves three purposes: test_bad_inputs.py runs every row, README.md lists every
row (scripts/bad_input_table.py writes that list from the real messages), and a test checks
that the README and this table agree.

Each row builds its inputs in a scratch folder `w` (the sample DEM and partition are copied
there, bad files are made there) and names the outputs in `w / "out"`: after a refused run
that folder must be empty and every input unchanged.
"""
from __future__ import annotations

import atexit
import dataclasses
import pathlib
import os
import shutil
import subprocess
import tempfile
from typing import Callable, List, Sequence

import numpy as np
from osgeo import gdal, ogr, osr

gdal.UseExceptions()
ogr.UseExceptions()

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "data" / "sample_montblanc"


@dataclasses.dataclass(frozen=True)
class Case:
    cmd: str          # "rockhatch", "rockhatch partition" or "rockhatch update"
    what: str         # the input or option, as the README names it
    bad: str          # the bad case, in words
    args: Callable[[pathlib.Path], Sequence]  # argv after the command, given the scratch folder
    code: int         # expected exit code
    words: Sequence[str]  # fragments of the one-line message

    @property
    def id(self) -> str:
        return f"{self.cmd.split()[-1]}:{self.what}:{self.bad}".replace(" ", "_")


# ---- inputs made on demand in the scratch folder

def dem(w):
    p = w / "dem.tif"
    if not p.exists():
        shutil.copy(SAMPLE / "dem.tif", p)
    return p


def part(w):
    p = w / "partition.gpkg"
    if not p.exists():
        shutil.copy(SAMPLE / "partition.gpkg", p)
    return p


def out(w, name="o.gpkg"):
    (w / "out").mkdir(exist_ok=True)
    return w / "out" / name


def copy_as(src, dst):
    shutil.copy(src, dst)
    return dst


def text_file(w, name, text):
    p = w / name
    p.write_text(text)
    return p


def hard_link(src, link):
    link.hardlink_to(src)
    return link


def truncated(w, src, name):
    p = w / name
    data = src.read_bytes()
    p.write_bytes(data[: len(data) // 3])
    return p


def raster_like_dem(w, name, fill=None, crs=True, dtype=gdal.GDT_Float32, size=None):
    """A copy of the sample DEM with its values replaced by `fill` (a function of the array)."""
    src = gdal.Open(str(SAMPLE / "dem.tif"))
    arr = src.GetRasterBand(1).ReadAsArray().astype(np.float64)
    if fill is not None:
        arr = fill(arr)
    ny, nx = arr.shape if size is None else size
    p = w / name
    ds = gdal.GetDriverByName("GTiff").Create(str(p), nx, ny, 1, dtype)
    gt = list(src.GetGeoTransform())
    if size is not None:
        gt[1] *= src.RasterXSize / nx
        gt[5] *= src.RasterYSize / ny
        arr = np.resize(arr, (ny, nx))
    ds.SetGeoTransform(gt)
    if crs:
        ds.SetProjection(src.GetProjection())
    ds.GetRasterBand(1).WriteArray(arr)
    ds = None
    return p


def huge_raster(w, name):
    """A 20000 x 20000 DEM over the sample's area: a sparse file of a few kB whose pixels
    would fill 1.6 GB per grid."""
    src = gdal.Open(str(SAMPLE / "dem.tif"))
    p = w / name
    n = 20000
    ds = gdal.GetDriverByName("GTiff").Create(str(p), n, n, 1, gdal.GDT_Float32,
                                              ["SPARSE_OK=TRUE", "TILED=YES", "BIGTIFF=YES"])
    gt = list(src.GetGeoTransform())
    gt[1] *= src.RasterXSize / n
    gt[5] *= src.RasterYSize / n
    ds.SetGeoTransform(gt)
    ds.SetProjection(src.GetProjection())
    ds = None
    return p


def shifted_raster(w, name, dx):
    """The sample DEM moved `dx` metres east (no overlap with the partition when large)."""
    p = w / name
    src = gdal.Open(str(SAMPLE / "dem.tif"))
    gdal.Translate(str(p), src)
    ds = gdal.Open(str(p), gdal.GA_Update)
    gt = list(ds.GetGeoTransform())
    gt[0] += dx
    ds.SetGeoTransform(gt)
    ds = None
    return p


def partition_file(w, name, faces=None, lines=None, epsg=2154, label_field="kind", face_fields=None,
                   faces_geom=ogr.wkbPolygon):
    """A GeoPackage partition: `faces` WKT polygons (with optional attribute dicts), `lines`
    (WKT, kind) pairs. Coordinates are in the sample's CRS (Lambert-93)."""
    p = w / name
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(p))
    srs = None
    if epsg:
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(epsg)
    if faces is not None:
        fl = ds.CreateLayer("faces", srs, faces_geom)
        for fname, ftype in (face_fields or {}).items():
            fl.CreateField(ogr.FieldDefn(fname, ftype))
        for item in faces:
            wkt, attrs = item if isinstance(item, tuple) else (item, {})
            f = ogr.Feature(fl.GetLayerDefn())
            for k, v in attrs.items():
                f.SetField(k, v)
            f.SetGeometry(wkt if isinstance(wkt, ogr.Geometry) else ogr.CreateGeometryFromWkt(wkt))
            fl.CreateFeature(f)
    if lines is not None:
        ll = ds.CreateLayer("lines", srs, ogr.wkbLineString)
        ll.CreateField(ogr.FieldDefn(label_field, ogr.OFTString))
        for wkt, kind in lines:
            f = ogr.Feature(ll.GetLayerDefn())
            f.SetField(label_field, kind)
            f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
            ll.CreateFeature(f)
    ds = None
    return p


SQUARE = "POLYGON((1004000 6540000,1004200 6540000,1004200 6540200,1004000 6540200,1004000 6540000))"
FAR = "POLYGON((1104000 6440000,1104200 6440000,1104200 6440200,1104000 6440200,1104000 6440000))"
BOWTIE = "POLYGON((1004000 6540000,1004200 6540200,1004200 6540000,1004000 6540200,1004000 6540000))"


def _nan_triangle():
    ring = ogr.Geometry(ogr.wkbLinearRing)  # WKT cannot spell NaN: build it point by point
    for x, y in ((1004000, 6540000), (float("nan"), 6540000), (1004200, 6540200), (1004000, 6540000)):
        ring.AddPoint_2D(x, y)
    poly = ogr.Geometry(ogr.wkbPolygon)
    poly.AddGeometry(ring)
    return poly


NAN_TRIANGLE = _nan_triangle()
RIDGE = ("LINESTRING(1004000 6540000,1004200 6540000)", "ridge")


def main(w, *extra, o=None):
    """The main command on the sample, with `extra` options."""
    return ["-q", "--dem", dem(w), "--partition", part(w), *extra, "-o", o or out(w)]


def with_partition(w, p, *extra):
    return ["-q", "--dem", dem(w), "--partition", p, *extra, "-o", out(w)]


def with_dem(w, d, *extra):
    return ["-q", "--dem", d, "--partition", part(w), *extra, "-o", out(w)]


def sub(w, *extra, o=None):
    """The partition subcommand on the sample DEM."""
    return ["-q", "--dem", dem(w), *extra, "-o", o or out(w)]


def number_cases(cmd: str, option: str, build, usage_words=(), extra_bad=()) -> List[Case]:
    """The bad numbers every numeric option is tried with: not a number, NaN, infinity."""
    rows = [
        Case(cmd, option, "not a number", lambda w: build(w, option, "abc"), 2, (option, "'abc'")),
        Case(cmd, option, "NaN", lambda w: build(w, option, "nan"), 2, (option, "nan")),
        Case(cmd, option, "infinite", lambda w: build(w, option, "inf"), 2, (option, "inf")),
    ]
    for bad, value, words in extra_bad:
        rows.append(Case(cmd, option, bad, lambda w, v=value: build(w, option, v), 2, (option, *words)))
    return rows


def main_opt(w, option, value):
    return main(w, option, value)


def sub_opt(w, option, value):
    return sub(w, option, value)


def param(w, option, value):
    return main(w, "--style", "bidirectional", "--param", f"spacing_min={value}")


# Two squares apart: no sequence of their pieces is one connected crest band.
APART_SVG = ('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0 L 10 10 L 0 10 Z '
             'M 0 20 L 10 20 L 10 30 L 0 30 Z"/></svg>')

_HATCHED = {}


def hatched(w, fingerprints=True):
    """A hatch GeoPackage of the sample written by the built command, in w (the file
    rockhatch update is given as -o: an input it must leave as it was when refused); without
    fingerprints: as a tiled run or an older version writes it."""
    key = fingerprints
    if key not in _HATCHED:
        build = pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))
        folder = pathlib.Path(tempfile.mkdtemp(prefix="rh_bad_update_"))
        atexit.register(shutil.rmtree, folder, True)
        path = folder / "h.gpkg"
        subprocess.run([str(build / "carto" / "rockhatch"), "-q", "--dem", SAMPLE / "dem.tif", "--partition",
                        SAMPLE / "partition.gpkg", "-o", path], check=True, capture_output=True)
        if not fingerprints:
            ds = ogr.Open(str(path), 1)
            ds.DeleteLayer("rockhatch_faces")
            ds = None
        _HATCHED[key] = path
    p = w / ("h.gpkg" if fingerprints else "old.gpkg")
    shutil.copy(_HATCHED[key], p)
    return p


def upd(w, *extra, o=None):
    """rockhatch update on the sample (the copied partition: the same faces as the file's run)."""
    return ["-q", "--dem", dem(w), "--partition", part(w), *extra, "-o", o or hatched(w)]


RH = "rockhatch"
PART = "rockhatch partition"
UPD = "rockhatch update"

CASES: List[Case] = [
    # ---- the main command: inputs
    Case(RH, "--dem", "missing file", lambda w: with_dem(w, w / "none.tif"), 3, ("--dem", "none.tif", "no such file")),
    Case(RH, "--dem", "not a raster", lambda w: with_dem(w, text_file(w, "junk.tif", "not a raster")), 3,
         ("junk.tif", "not a raster")),
    Case(RH, "--dem", "truncated GeoTIFF", lambda w: with_dem(w, truncated(w, SAMPLE / "dem.tif", "cut.tif")), 3,
         ("cut.tif",)),
    Case(RH, "--dem", "a vector file", lambda w: with_dem(w, part(w)), 3, ("partition.gpkg", "raster")),
    Case(RH, "--dem", "a folder", lambda w: with_dem(w, w), 3, ("--dem",)),
    Case(RH, "--dem", "no CRS", lambda w: with_dem(w, raster_like_dem(w, "nocrs.tif", crs=False)), 4,
         ("nocrs.tif", "no CRS")),
    Case(RH, "--dem", "no overlap with the partition", lambda w: with_dem(w, shifted_raster(w, "far.tif", 1e6)), 5,
         ("does not overlap", "far.tif")),
    Case(RH, "--dem", "all NaN", lambda w: with_dem(w, raster_like_dem(w, "nan.tif", lambda a: a * np.nan)), 6,
         ("nan.tif", "every cell is NoData")),
    Case(RH, "--dem", "infinite values", lambda w: with_dem(w, raster_like_dem(w, "inf.tif", lambda a: a + np.inf)), 6,
         ("inf.tif", "every cell is NoData")),
    Case(RH, "--dem", "so large it would exhaust memory", lambda w: with_dem(w, huge_raster(w, "huge.tif")), 3,
         ("huge.tif", "20000 x 20000 cells")),
    Case(RH, "--dem", "not given", lambda w: ["-q", "--partition", part(w), "-o", out(w)], 2, ("--dem",)),
    Case(RH, "--partition", "missing file", lambda w: with_partition(w, w / "none.gpkg"), 3,
         ("--partition", "none.gpkg")),
    Case(RH, "--partition", "not a vector file", lambda w: with_partition(w, text_file(w, "junk.gpkg", "junk")), 3,
         ("junk.gpkg",)),
    Case(RH, "--partition", "truncated GeoPackage",
         lambda w: with_partition(w, truncated(w, SAMPLE / "partition.gpkg", "cut.gpkg")), 3, ("cut.gpkg",)),
    Case(RH, "--partition", "a raster", lambda w: with_partition(w, dem(w)), 3, ("dem.tif", "not a vector")),
    Case(RH, "--partition", "no CRS",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [SQUARE], [RIDGE], epsg=None)), 4,
         ("p.gpkg", "has no CRS")),
    Case(RH, "--partition", "no overlap with the DEM",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [FAR], [RIDGE])), 5, ("does not overlap", "dem.tif")),
    Case(RH, "--partition", "empty face layer",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [], [RIDGE])), 6, ("p.gpkg",)),
    Case(RH, "--partition", "no polygon layer",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", None, [RIDGE])), 6, ("p.gpkg", "polygon")),
    Case(RH, "--partition", "label attribute missing",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [SQUARE], [RIDGE], label_field="nature")), 6,
         ("p.gpkg", "'kind'")),
    Case(RH, "--partition", "unknown label value",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [SQUARE],
                                                    [("LINESTRING(1004000 6540000,1004200 6540000)", "crevasse")])), 6,
         ("'crevasse'", "ridge, valley, cliff or other")),
    Case(RH, "--partition", "self-intersecting face with --no-repair",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [BOWTIE], [RIDGE]), "--no-repair"), 8,
         ("face 1", "not a valid polygon")),
    Case(RH, "--partition", "NaN coordinates",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [NAN_TRIANGLE], [RIDGE])), 8, ("p.gpkg",)),
    Case(RH, "--partition", "density outside 0..1",
         lambda w: with_partition(w, partition_file(w, "p.gpkg", [(SQUARE, {"density": 7.0})], [RIDGE],
                                                    face_fields={"density": ogr.OFTReal})), 6, ("density", "7")),
    Case(RH, "--slope", "missing file", lambda w: main(w, "--slope", w / "none.tif"), 3, ("--slope", "none.tif")),
    Case(RH, "--slope", "not a raster", lambda w: main(w, "--slope", text_file(w, "s.tif", "x")), 3, ("s.tif",)),
    Case(RH, "--slope", "no CRS", lambda w: main(w, "--slope", raster_like_dem(w, "s.tif", crs=False)), 4,
         ("s.tif", "no CRS")),
    Case(RH, "--slope", "no overlap", lambda w: main(w, "--slope", shifted_raster(w, "s.tif", 1e6)), 5,
         ("s.tif", "does not overlap")),
    Case(RH, "--roughness", "missing file", lambda w: main(w, "--roughness", w / "none.tif"), 3,
         ("--roughness", "none.tif")),
    Case(RH, "--roughness", "no CRS", lambda w: main(w, "--roughness", raster_like_dem(w, "r.tif", crs=False)), 4,
         ("r.tif", "no CRS")),
    Case(RH, "--script", "missing file", lambda w: main(w, "--script", w / "none.py"), 3, ("--script", "none.py")),
    Case(RH, "--script", "syntax error", lambda w: main(w, "--script", text_file(w, "bad.py", "x = 1\ndef (:\n")), 7,
         ("bad.py", "line 2")),
    Case(RH, "--script", "fails when loaded",
         lambda w: main(w, "--script", text_file(w, "boom.py", "import no_such_module_here\n")), 7,
         ("boom.py", "line 1", "no_such_module_here")),
    Case(RH, "--script", "no style in it", lambda w: main(w, "--script", text_file(w, "empty.py", "x = 1\n")), 7,
         ("empty.py",)),
    Case(RH, "--style", "unknown name", lambda w: main(w, "--style", "watercolour"), 7,
         ("--style", "'watercolour'", "bidirectional", "print")),
    Case(RH, "--param", "unknown name", lambda w: main(w, "--style", "noisy", "--param", "peak_length=3"), 7,
         ("'noisy'", "'peak_length'")),
    Case(RH, "--param", "no value", lambda w: main(w, "--param", "spacing_min"), 2, ("expected NAME=VALUE",)),
    Case(RH, "--param", "rows laid over twice as dense as the tone", lambda w: main(w, "--param", "band_ragged=3"), 2,
         ("band_ragged=3", "above 1")),
    Case(RH, "--param", "cliff tops longer than a sheet", lambda w: main(w, "--param", "cliff_min_length=1000"), 2,
         ("cliff_min_length=1000", "above 50 mm", "cliff_slope")),
    *number_cases(RH, "--param", param, extra_bad=[
        ("zero", "0", ("spacing_min",)),
        ("negative", "-1", ("spacing_min",)),
        ("so small it would exhaust memory", "1e-9", ("spacing_min", "raise --scale or spacing_min")),
    ]),
    *number_cases(RH, "--scale", main_opt, extra_bad=[
        ("zero", "0", ()), ("negative", "-5000", ()),
        ("so small the hatches would exhaust memory", "10", ("--scale 10", "raise --scale")),
    ]),
    *number_cases(RH, "--relief-radius", main_opt, extra_bad=[("negative", "-1", ())]),
    *number_cases(RH, "--seed", main_opt, extra_bad=[("negative", "-1", ())]),
    *number_cases(RH, "--threads", main_opt, extra_bad=[("negative", "-1", ()),
                                                         ("absurdly many", "100000", ("more than 1024",))]),
    *number_cases(RH, "--snap", main_opt, extra_bad=[("negative", "-1", ())]),
    *number_cases(RH, "--png-size", lambda w, opt, v: main(w, opt, v, o=out(w, "o.png")), extra_bad=[
        ("zero", "0", ()), ("negative", "-10", ()), ("so large it would exhaust memory", "10000000", ()),
    ]),
    Case(RH, "--crest-ornament", "missing file", lambda w: main(w, "--crest-ornament", w / "none.svg"), 3,
         ("--crest-ornament", "none.svg", "no such file")),
    Case(RH, "--crest-ornament", "not SVG", lambda w: main(w, "--crest-ornament", text_file(w, "junk.svg", "<<<")), 3,
         ("--crest-ornament", "junk.svg", "not an SVG")),
    Case(RH, "--crest-ornament", "shapes that cannot join into one band",
         lambda w: main(w, "--crest-ornament", text_file(w, "apart.svg", APART_SVG)), 6,
         ("apart.svg", "one connected crest band")),
    Case(RH, "--crest-ornament", "the output, with --overwrite",
         lambda w: main(w, "--overwrite", "--crest-ornament", text_file(w, "mine.svg", APART_SVG), o=w / "mine.svg"), 9,
         ("mine.svg", "--crest-ornament", "onto an input")),
    *number_cases(RH, "--crest-height", lambda w, opt, v: main(w, "--crest-ornament", "default", opt, v), extra_bad=[
        ("zero", "0", ()), ("negative", "-1", ()), ("over 50 mm", "80", ()),
    ]),
    Case(RH, "--crest-height", "without --crest-ornament", lambda w: main(w, "--crest-height", "2"), 2,
         ("--crest-height needs --crest-ornament",)),
    Case(RH, "--mask", "with a partition file", lambda w: main(w, "--mask", partition_file(w, "m.gpkg", [SQUARE])), 2,
         ("--mask", "--partition auto")),
    Case(RH, "--mask", "missing file", lambda w: with_partition(w, "auto", "--mask", w / "none.gpkg"), 3,
         ("--mask", "none.gpkg")),
    Case(RH, "--window", "not four numbers", lambda w: main(w, "--window", "1,2,3"), 2, ("--window",)),
    Case(RH, "--window", "empty box", lambda w: main(w, "--window", "10,10,0,0"), 2, ("--window",)),
    Case(RH, "--window", "NaN", lambda w: main(w, "--window", "nan,0,1,1"), 2, ("--window",)),
    Case(RH, "--faces-layer", "no such layer", lambda w: main(w, "--faces-layer", "nope"), 6, ("'nope'",)),
    Case(RH, "--lines-layer", "no such layer", lambda w: main(w, "--lines-layer", "nope"), 6, ("'nope'",)),
    Case(RH, "--label-field", "no such attribute", lambda w: main(w, "--label-field", "nope"), 6, ("'nope'",)),
    Case(RH, "--id-field", "no such attribute", lambda w: main(w, "--id-field", "nope"), 6, ("'nope'",)),
    Case(RH, "--orientation-field", "no such attribute", lambda w: main(w, "--orientation-field", "nope"), 6,
         ("'nope'", "--orientation-field")),
    Case(RH, "--orientation-layer", "no such layer", lambda w: main(w, "--orientation-layer", "nope"), 6,
         ("'nope'",)),
    Case(RH, "--density-field", "no such attribute", lambda w: main(w, "--density-field", "nope"), 6,
         ("'nope'", "--density-field")),
    Case(RH, "--density-layer", "no such layer", lambda w: main(w, "--density-layer", "nope"), 6, ("'nope'",)),
    Case(RH, "--scree-layer", "no such layer", lambda w: main(w, "--scree-layer", "nope", "--style", "scree"), 6,
         ("'nope'",)),
    Case(RH, "--scree-layer", "not a polygon layer", lambda w: main(w, "--scree-layer", "lines", "--style", "scree"),
         6, ("'lines'", "polygon")),
    Case(RH, "-o", "not given", lambda w: ["-q", "--dem", dem(w), "--partition", part(w)], 2, ("-o",)),
    Case(RH, "-o", "unknown extension", lambda w: main(w, o=out(w, "o.docx")), 2, ("o.docx",)),
    Case(RH, "-o", "folder missing", lambda w: main(w, o=w / "out" / "nope" / "o.gpkg"), 9,
         ("the folder does not exist",)),
    Case(RH, "-o", "exists (no --overwrite)", lambda w: main(w, o=text_file(w, "keep.svg", "precious")), 9,
         ("keep.svg", "--overwrite")),
    Case(RH, "-o", "the partition, with --overwrite", lambda w: main(w, "--overwrite", o=part(w)), 9,
         ("partition.gpkg", "--partition", "onto an input")),
    Case(RH, "-o", "a hard link to the DEM", lambda w: main(w, "--overwrite", o=hard_link(dem(w), w / "h.tif")), 9,
         ("h.tif", "--dem", "onto an input")),
    Case(RH, "-o", "a .pdf that is the DEM, with --overwrite",
         lambda w: ["-q", "--dem", copy_as(dem(w), w / "d.pdf"), "--partition", part(w), "--overwrite", "-o", w / "d.pdf"],
         9, ("d.pdf", "--dem", "onto an input")),
    Case(RH, "-o", "a .mbtiles that is the DEM, with --overwrite",
         lambda w: ["-q", "--dem", copy_as(dem(w), w / "d.mbtiles"), "--partition", part(w), "--overwrite", "-o",
                    w / "d.mbtiles"], 9, ("d.mbtiles", "--dem", "onto an input")),
    Case(RH, "--page", "unknown size", lambda w: main(w, "--page", "A9", o=out(w, "o.pdf")), 2, ("--page 'A9'",)),
    Case(RH, "--page", "smaller than the drawing", lambda w: main(w, "--page", "40x40", o=out(w, "o.pdf")), 2,
         ("--page 40x40", "use a larger page")),
    Case(RH, "--page", "without a .pdf output", lambda w: main(w, "--page", "A4"), 2, ("--page needs a .pdf",)),
    Case(RH, "--zoom", "out of 0-22", lambda w: main(w, "--zoom", "3-25", o=out(w, "o.mbtiles")), 2,
         ("--zoom '3-25'", "0..22")),
    Case(RH, "--zoom", "reversed", lambda w: main(w, "--zoom", "16-12", o=out(w, "o.mbtiles")), 2,
         ("--zoom '16-12'",)),
    Case(RH, "--zoom", "not a number", lambda w: main(w, "--zoom", "z15", o=out(w, "o.mbtiles")), 2,
         ("--zoom 'z15'",)),
    Case(RH, "--zoom", "without a vector-tile output", lambda w: main(w, "--zoom", "14"), 2,
         ("--zoom needs a vector-tile output",)),
    Case(RH, "(any)", "unknown option", lambda w: main(w, "--bogus"), 2, ("unknown option '--bogus'",)),
    Case(RH, "(any)", "option without its value", lambda w: ["-q", "--dem", dem(w), "--partition"], 2,
         ("--partition",)),

    # ---- the partition subcommand
    Case(PART, "--dem", "missing file", lambda w: ["-q", "--dem", w / "none.tif", "-o", out(w)], 3, ("none.tif",)),
    Case(PART, "--dem", "not a raster", lambda w: ["-q", "--dem", text_file(w, "j.tif", "x"), "-o", out(w)], 3,
         ("j.tif",)),
    Case(PART, "--dem", "no CRS", lambda w: ["-q", "--dem", raster_like_dem(w, "nocrs.tif", crs=False), "-o", out(w)],
         4, ("nocrs.tif",)),
    Case(PART, "--dem", "flat: no rock",
         lambda w: ["-q", "--dem", raster_like_dem(w, "flat.tif", lambda a: a * 0 + 1000), "-o", out(w)], 6,
         ("flat.tif", "no rock")),
    Case(PART, "--dem", "all NaN",
         lambda w: ["-q", "--dem", raster_like_dem(w, "nan.tif", lambda a: a * np.nan), "-o", out(w)], 6,
         ("nan.tif",)),
    Case(PART, "--dem", "so large it would exhaust memory", lambda w: ["-q", "--dem", huge_raster(w, "huge.tif"),
                                                                        "-o", out(w)], 3,
         ("huge.tif", "20000 x 20000 cells")),
    Case(PART, "--mask", "missing file", lambda w: sub(w, "--mask", w / "none.gpkg"), 3, ("--mask", "none.gpkg")),
    Case(PART, "--mask", "no polygon", lambda w: sub(w, "--mask", partition_file(w, "m.gpkg", None, [RIDGE])), 6,
         ("m.gpkg",)),
    *[c for opt in ("--min-slope", "--min-roughness", "--min-area", "--scale", "--thalweg-area", "--ridge-area",
                    "--max-fill", "--smooth", "--converge", "--simplify")
      for c in number_cases(PART, opt, sub_opt, extra_bad=[("negative", "-1", ())])],
    *number_cases(PART, "--png-size", lambda w, opt, v: sub(w, "--png", out(w, "p.png"), opt, v),
                  extra_bad=[("zero", "0", ()), ("so large it would exhaust memory", "10000000", ())]),
    Case(PART, "--png", "folder missing", lambda w: sub(w, "--png", w / "nope" / "p.png"), 9, ("p.png",)),
    Case(PART, "-o", "not a GeoPackage", lambda w: sub(w, o=out(w, "x.shp")), 2, ("x.shp",)),
    Case(PART, "-o", "exists (no --overwrite)", lambda w: sub(w, o=text_file(w, "keep.gpkg", "keep")), 9,
         ("keep.gpkg", "--overwrite")),
    Case(PART, "-o", "not given", lambda w: ["-q", "--dem", dem(w)], 2, ("-o",)),
    Case(PART, "--png", "the DEM, with --overwrite", lambda w: sub(w, "--overwrite", "--png", dem(w)), 9,
         ("dem.tif", "--dem", "onto an input")),
    Case(PART, "(any)", "unknown option", lambda w: sub(w, "--bogus"), 2, ("--bogus",)),
    # ---- rockhatch update
    Case(UPD, "-o", "missing file", lambda w: upd(w, o=w / "none.gpkg"), 3, ("none.gpkg", "no such file")),
    Case(UPD, "-o", "no fingerprints (a tiled run's)", lambda w: upd(w, o=hatched(w, fingerprints=False)), 6,
         ("old.gpkg", "keeps no fingerprints")),
    Case(UPD, "-o", "not a GeoPackage (only an SVG)", lambda w: upd(w, o=out(w, "h.svg")), 2, ("GeoPackage",)),
    Case(UPD, "-o", "vector tiles", lambda w: upd(w, "-o", out(w, "t.mbtiles")), 2, ("t.mbtiles", "vector tiles")),
    Case(UPD, "--style", "another than the file's", lambda w: upd(w, "--style", "noisy"), 2,
         ("h.gpkg", "style rock", "--reset")),
    Case(UPD, "--style", "a terrain style", lambda w: upd(w, "--style", "scree"), 2, ("scree", "terrain")),
    Case(UPD, "--crest-ornament", "given", lambda w: upd(w, "--crest-ornament", "default"), 2,
         ("--crest-ornament", "per ridge")),
    Case(UPD, "--face", "not a face of the partition", lambda w: upd(w, "--face", "999"), 2, ("--face 999",)),
    Case(UPD, "--face", "not an integer", lambda w: upd(w, "--face", "x"), 2, ("--face", "'x'")),
    Case(UPD, "--dem", "the file to update", lambda w: ["-q", "--dem", hatched(w), "--partition", part(w), "-o",
                                                        hatched(w)], 9, ("h.gpkg", "onto an input")),
]
