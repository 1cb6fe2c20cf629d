"""The rockhatch command as a cartographer runs it: outputs, errors, real terrain."""
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest
from osgeo import gdal, ogr, osr

from bad_inputs import partition_file

gdal.UseExceptions()
ogr.UseExceptions()

# The default style's layers on the sample (rock: no couloir there).
FAMILIES = ["hatch_fill", "hatch_ridge", "hatch_valley", "hatch_cross", "hatch_ridgeline", "hatch_cliff"]


def run(exe, *args, timeout=300):
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=timeout)


def sample_args(sample_dir):
    return ["--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg"]


@pytest.fixture(scope="module")
def sample_run(rockhatch_exe, sample_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("sample")
    r = run(rockhatch_exe, *sample_args(sample_dir), "-o", out / "h.gpkg", "-o", out / "h.svg", "-o", out / "h.png")
    assert r.returncode == 0, r.stderr
    return out, r


def test_geopackage_layers_crs_and_attributes(sample_run):
    out, _ = sample_run
    ds = ogr.Open(str(out / "h.gpkg"))
    names = [ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount())]
    # The hatch layers, then the faces' fingerprints (rockhatch update).
    assert names == FAMILIES + ["rockhatch_faces"]
    assert ds.GetLayerByName("rockhatch_faces").GetFeatureCount() == 20
    for name in FAMILIES:
        layer = ds.GetLayerByName(name)
        assert layer.GetGeomType() == ogr.wkbLineString
        assert layer.GetSpatialRef().GetAuthorityCode(None) == "2154"
        defn = layer.GetLayerDefn()
        assert [defn.GetFieldDefn(i).GetName() for i in range(defn.GetFieldCount())] == \
            ["face_id", "family", "style", "width_mm"]
        assert layer.GetFeatureCount() > 0, name
        # Every feature: its family, the default style, one of the sample's 20 faces, one width.
        rows = ds.ExecuteSQL(f"SELECT family, style, min(face_id), max(face_id), min(width_mm), max(width_mm), "
                             f"count(*) FROM {name} GROUP BY family, style")
        groups = [[f.GetField(i) for i in range(7)] for f in rows]
        ds.ReleaseResultSet(rows)
        assert len(groups) == 1, groups
        family, style, lo, hi, w_lo, w_hi, n = groups[0]
        assert (family, style, n) == (name.split("_")[1], "rock", layer.GetFeatureCount())
        assert 1 <= lo <= hi <= 20 and 0 < w_lo == w_hi


def test_svg_groups_scale_and_georeference(sample_run):
    out, _ = sample_run
    root = ET.parse(out / "h.svg").getroot()
    ns = {"s": "http://www.w3.org/2000/svg", "rh": "https://rockhatch.invalid/ns"}
    groups = [g.get("id") for g in root.findall("s:g", ns)]
    assert groups == ["fill", "ridge", "valley", "cross", "ridgeline", "cliff"]
    geo = root.find("s:metadata/rh:georeference", ns)
    assert geo.get("crs") == "EPSG:2154"
    assert float(geo.get("scale")) == 10000
    # True scale: the drawing's width in mm is its ground width / 10.
    width_m = float(geo.get("xmax")) - float(geo.get("xmin"))
    assert float(root.get("width").removesuffix("mm")) == pytest.approx(width_m / 10, rel=1e-4)


def test_png_preview(sample_run):
    out, _ = sample_run
    ds = gdal.Open(str(out / "h.png"))
    assert ds.RasterXSize == 1600
    band = ds.GetRasterBand(1).ReadAsArray()
    assert band.min() < 60 and band.max() > 200  # ink and paper


def test_figures_and_notes_on_stderr(sample_run):
    _, r = sample_run
    assert "rockhatch: 20 faces," in r.stderr
    assert "working CRS EPSG:2154" in r.stderr
    assert "orientation of 20 face(s) from layer 'orientation'" in r.stderr


def test_same_bytes_with_one_or_two_threads(rockhatch_exe, sample_dir, tmp_path):
    for t in (1, 2):
        r = run(rockhatch_exe, *sample_args(sample_dir), "-q", "--threads", t, "--style", "fine-ridges",
                "-o", tmp_path / f"t{t}.gpkg", "-o", tmp_path / f"t{t}.svg")
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "t1.gpkg").read_bytes() == (tmp_path / "t2.gpkg").read_bytes()
    assert (tmp_path / "t1.svg").read_bytes() == (tmp_path / "t2.svg").read_bytes()


def test_a_geopackage_alone_is_written_while_drawn_with_the_same_bytes(rockhatch_exe, sample_dir, tmp_path):
    """A GeoPackage alone is written face by face while the faces are drawn (the faces never
    all in memory): the same bytes at one and two threads, the same as the GeoPackage written
    from the whole drawing beside an SVG, and a valid GeoPackage with every family the style
    drew (rock: the structure families after the rock ones)."""
    import sys
    validator = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py"
    for t in (1, 2):
        r = run(rockhatch_exe, *sample_args(sample_dir), "-q", "--threads", t, "-o", tmp_path / f"alone{t}.gpkg")
        assert r.returncode == 0, r.stderr
    r = run(rockhatch_exe, *sample_args(sample_dir), "-q", "--threads", 2, "-o", tmp_path / "both.gpkg",
            "-o", tmp_path / "both.svg")
    assert r.returncode == 0, r.stderr
    alone = (tmp_path / "alone1.gpkg").read_bytes()
    assert alone == (tmp_path / "alone2.gpkg").read_bytes()
    # The command line is kept in the file: the two runs differ by their outputs only there.
    import sqlite3
    def content(path):
        con = sqlite3.connect(str(path))
        try:
            return [line for line in con.iterdump() if "RH_RUN_COMMAND" not in line]
        finally:
            con.close()
    assert content(tmp_path / "alone1.gpkg") == content(tmp_path / "both.gpkg")
    ds = ogr.Open(str(tmp_path / "alone1.gpkg"))
    assert [ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount())] == FAMILIES + ["rockhatch_faces"]
    assert sum(ds.GetLayerByName(f).GetFeatureCount() for f in FAMILIES) > 10000
    v = subprocess.run([sys.executable, validator, str(tmp_path / "alone1.gpkg")], capture_output=True, text=True)
    assert v.returncode == 0 and not v.stdout.strip() and not v.stderr.strip(), v.stdout + v.stderr


def test_seed_changes_the_hatches(rockhatch_exe, sample_dir, tmp_path):
    for s in (1, 2):
        assert run(rockhatch_exe, *sample_args(sample_dir), "-q", "--seed", s, "--style", "noisy",
                   "-o", tmp_path / f"s{s}.svg").returncode == 0
    assert (tmp_path / "s1.svg").read_bytes() != (tmp_path / "s2.svg").read_bytes()


@pytest.mark.parametrize("style", ["print", "noisy", "ridge-triangles", "density-cells",
                                   "fine-ridges", "balanced", "high-ridges", "bidirectional"])
def test_every_style_runs(rockhatch_exe, sample_dir, tmp_path, style):
    r = run(rockhatch_exe, *sample_args(sample_dir), "-q", "--style", style, "-o", tmp_path / "o.gpkg")
    assert r.returncode == 0, r.stderr
    ds = ogr.Open(str(tmp_path / "o.gpkg"))
    assert ds.GetLayerByName("hatch_fill").GetFeatureCount() > 1000
    ridge = ds.GetLayerByName("hatch_ridge").GetFeatureCount()
    assert (ridge > 0) == (style != "noisy")
    assert (ds.GetLayerByName("hatch_cross").GetFeatureCount() > 0) == (style in ("bidirectional", "print"))


def test_list_styles_and_help(rockhatch_exe):
    r = run(rockhatch_exe, "--list-styles")
    assert r.returncode == 0
    for name in ["noisy", "ridge-triangles", "density-cells", "fine-ridges", "balanced", "high-ridges",
                 "bidirectional", "print"]:
        assert name in r.stdout
    assert "spacing_min = 0.35 mm" in r.stdout
    h = run(rockhatch_exe, "--help")
    assert h.returncode == 0 and "--scale N" in h.stdout and "exit codes" in h.stdout


def test_parameters_change_the_drawing(rockhatch_exe, sample_dir, tmp_path):
    counts = []
    for spacing in ("0.35", "0.7"):
        out = tmp_path / f"p{spacing}.gpkg"
        r = run(rockhatch_exe, *sample_args(sample_dir), "-q", "--style", "noisy", "--param", f"spacing_min={spacing}",
                "--param", f"spacing_max={spacing}", "-o", out)
        assert r.returncode == 0, r.stderr
        ds = ogr.Open(str(out))  # keep the dataset alive while its layer is used
        counts.append(ds.GetLayerByName("hatch_fill").GetFeatureCount())
    assert counts[0] > 1.6 * counts[1]


# ---- errors: one line naming the input, a distinct exit code, no output left behind

def write_partition(path, polygons, lines, srs_epsg=2154, label_field="kind", densities=None):
    faces = [(wkt, {"density": d}) for wkt, d in zip(polygons, densities)] if densities else polygons
    partition_file(path.parent, path.name, faces, lines, epsg=srs_epsg, label_field=label_field,
                   face_fields={"density": ogr.OFTReal} if densities else None)


SQUARE = "POLYGON((1004000 6540000,1004200 6540000,1004200 6540200,1004000 6540200,1004000 6540000))"
BOWTIE = "POLYGON((1004000 6540000,1004200 6540200,1004200 6540000,1004000 6540200,1004000 6540000))"
RIDGE = ("LINESTRING(1004000 6540000,1004200 6540000)", "ridge")


def expect_error(r, code, *fragments):
    assert r.returncode == code, (r.returncode, r.stderr)
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1, r.stderr
    for frag in fragments:
        assert frag in lines[0], lines[0]


def test_missing_label_attribute(rockhatch_exe, sample_dir, tmp_path):
    write_partition(tmp_path / "p.gpkg", [SQUARE], [RIDGE], label_field="nature")
    r = run(rockhatch_exe, "-q", "--dem", sample_dir / "dem.tif", "--partition", tmp_path / "p.gpkg",
            "-o", tmp_path / "o.gpkg")
    expect_error(r, 6, "p.gpkg", "'kind'")
    ok = run(rockhatch_exe, "-q", "--dem", sample_dir / "dem.tif", "--partition", tmp_path / "p.gpkg",
             "--label-field", "nature", "-o", tmp_path / "o.gpkg")
    assert ok.returncode == 0, ok.stderr


def test_self_intersecting_polygon_repaired_or_refused(rockhatch_exe, sample_dir, tmp_path):
    write_partition(tmp_path / "p.gpkg", [BOWTIE], [RIDGE])
    refused = run(rockhatch_exe, "-q", "--no-repair", "--dem", sample_dir / "dem.tif", "--partition",
                  tmp_path / "p.gpkg", "-o", tmp_path / "o.gpkg")
    expect_error(refused, 8, "face 1", "not a valid polygon")
    assert not list(tmp_path.glob("o.gpkg*"))
    repaired = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", tmp_path / "p.gpkg",
                   "-o", tmp_path / "o.gpkg")
    assert repaired.returncode == 0, repaired.stderr
    assert "repaired 1 invalid face polygon(s)" in repaired.stderr
    assert "2 faces" in repaired.stderr  # the bow tie became two triangles


def test_existing_output_is_kept(rockhatch_exe, sample_dir, tmp_path):
    target = tmp_path / "o.svg"
    target.write_text("precious")
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "-o", target)
    expect_error(r, 9, "o.svg", "--overwrite")
    assert target.read_text() == "precious"
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "-o", target, "--overwrite")
    assert r.returncode == 0
    assert target.read_text().startswith("<?xml")


def test_a_file_with_a_temporary_looking_name_is_never_touched(rockhatch_exe, sample_dir, tmp_path):
    # Outputs are written under a fresh temporary name, then renamed: a user's file that looks
    # like one (the name older versions used and removed first) survives, and nothing is left.
    decoys = {tmp_path / "o.svg.part.svg": "mine", tmp_path / "o.gpkg.part.gpkg": "mine too"}
    for path, text in decoys.items():
        path.write_text(text)
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "-o", tmp_path / "o.svg",
            "-o", tmp_path / "o.gpkg")
    assert r.returncode == 0, r.stderr
    for path, text in decoys.items():
        assert path.read_text() == text
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["o.svg", "o.gpkg", *(p.name for p in decoys)])


# ---- the real DEM (geographic CRS, NoData)

@pytest.fixture(scope="module")
def real_partition(tmp_path_factory, real_dem_file):
    from realdem import grid_partition
    path = tmp_path_factory.mktemp("real") / "grid.gpkg"
    n = grid_partition(real_dem_file, path, 90)
    assert n > 50
    return path, n


def test_a_geographic_dem_with_nodata_is_reprojected_to_utm(rockhatch_exe, sample_dir, tmp_path):
    """The same path as the real DEM below, without ../shared: the sample warped to
    longitude / latitude, with a NoData border, is drawn in UTM 32N."""
    geo = tmp_path / "geo.tif"
    gdal.Warp(str(geo), str(sample_dir / "dem.tif"), dstSRS="EPSG:4326", dstNodata=-9999, resampleAlg="bilinear")
    ds = gdal.Open(str(geo))
    arr = ds.GetRasterBand(1).ReadAsArray()
    assert (arr == -9999).any()  # the warped square's corners
    ds = None
    r = run(rockhatch_exe, "--dem", geo, "--partition", sample_dir / "partition.gpkg", "-o", tmp_path / "g.gpkg")
    assert r.returncode == 0, r.stderr
    assert "reprojected to EPSG:32632" in r.stderr and "working CRS EPSG:32632" in r.stderr, r.stderr
    out = ogr.Open(str(tmp_path / "g.gpkg"))
    layer = out.GetLayerByName("hatch_fill")
    assert layer.GetSpatialRef().GetAuthorityCode(None) == "32632"
    assert layer.GetFeatureCount() > 10000
    xmin, xmax, ymin, ymax = layer.GetExtent()  # Mont Blanc in UTM 32N
    assert 320000 < xmin < xmax < 360000 and 5060000 < ymin < ymax < 5110000


def test_real_dem_geographic_with_nodata(rockhatch_exe, real_dem_file, real_partition, tmp_path):
    path, n = real_partition
    r = run(rockhatch_exe, "--dem", real_dem_file, "--partition", path, "--no-spatial-index",
            "-o", tmp_path / "real.gpkg", "-o", tmp_path / "real.png")
    assert r.returncode == 0, r.stderr
    assert "reprojected to EPSG:32632" in r.stderr
    assert f"{n} faces" in r.stderr
    assert "derived from the terrain" in r.stderr
    ds = ogr.Open(str(tmp_path / "real.gpkg"))
    layer = ds.GetLayerByName("hatch_fill")
    assert layer.GetSpatialRef().GetAuthorityCode(None) == "32632"
    assert layer.GetFeatureCount() > 10000
    # Hatches stay within the DEM's footprint: its box in degrees carried to UTM 32N (about
    # 331-346 km E, 5075-5092 km N), give or take one cell (30 m).
    dem = gdal.Open(str(real_dem_file))
    gt, w, h = dem.GetGeoTransform(), dem.RasterXSize, dem.RasterYSize
    src, dst = dem.GetSpatialRef().Clone(), layer.GetSpatialRef().Clone()
    for srs in (src, dst):
        srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)  # x = longitude / easting
    to_utm = osr.CoordinateTransformation(src, dst)
    fx0, fy0, fx1, fy1 = to_utm.TransformBounds(gt[0], gt[3] + h * gt[5], gt[0] + w * gt[1], gt[3], 21)
    xmin, xmax, ymin, ymax = layer.GetExtent()
    assert 330000 < fx0 - 30 < xmin < xmax < fx1 + 30 < 347000
    assert 5074000 < fy0 - 30 < ymin < ymax < fy1 + 30 < 5093000


def test_geopackage_spatial_index_is_valid_and_maintained(sample_run, tmp_path):
    import sqlite3
    src, _ = sample_run
    path = tmp_path / "copy.gpkg"
    shutil.copy(src / "h.gpkg", path)
    con = sqlite3.connect(path)
    for name in FAMILIES:
        assert con.execute(f"SELECT rtreecheck('rtree_{name}_geom')").fetchone()[0] == "ok"
        assert con.execute(f"SELECT count(*) FROM rtree_{name}_geom").fetchone()[0] == \
            con.execute(f"SELECT count(*) FROM {name}").fetchone()[0]
    con.close()
    ds = ogr.Open(str(path), update=1)
    assert ds.ExecuteSQL("SELECT HasSpatialIndex('hatch_fill', 'geom')").GetNextFeature().GetField(0) == 1
    layer = ds.GetLayerByName("hatch_fill")
    xmin, xmax, ymin, ymax = layer.GetExtent()
    cx, cy = (xmin + xmax) / 2, (ymin + ymax) / 2
    box = (cx - 150, cy - 150, cx + 150, cy + 150)
    layer.SetSpatialFilterRect(*box)
    found = {f.GetFID(): f.GetGeometryRef().GetEnvelope() for f in layer}
    layer.SetSpatialFilter(None)
    inside = set()
    for f in layer:
        e = f.GetGeometryRef().GetEnvelope()  # (minx, maxx, miny, maxy)
        if e[0] > box[0] + 1 and e[1] < box[2] - 1 and e[2] > box[1] + 1 and e[3] < box[3] - 1:
            inside.add(f.GetFID())
    # Nothing the index should find is missing, and nothing far away comes back.
    assert inside and inside <= set(found)
    for e in found.values():
        assert e[1] >= box[0] - 1 and e[0] <= box[2] + 1 and e[3] >= box[1] - 1 and e[2] <= box[3] + 1
    # An edit after the fact goes through the index's triggers.
    f = ogr.Feature(layer.GetLayerDefn())
    f.SetGeometry(ogr.CreateGeometryFromWkt("LINESTRING(1000000 6500000,1000010 6500010)"))
    layer.CreateFeature(f)
    layer.SetSpatialFilterRect(999990, 6499990, 1000020, 6500020)
    assert layer.GetFeatureCount() == 1


def test_sample_generator_is_deterministic_and_repeats_the_massif(rockhatch_exe, sample_dir, tmp_path):
    gen = rockhatch_exe.parent / "rh_make_sample"
    r = subprocess.run([gen, "-o", tmp_path / "one"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for name in ("dem.tif", "partition.gpkg", "truth.gpkg"):
        assert (tmp_path / "one" / name).read_bytes() == (sample_dir / name).read_bytes(), name
    r = subprocess.run([gen, "-o", tmp_path / "four", "--size", "4800"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    ds = gdal.Open(str(tmp_path / "four" / "dem.tif"))
    gt = ds.GetGeoTransform()
    a = ds.GetRasterBand(1).ReadAsArray()
    # The four summits (one per 2400 m copy, east and south of the first) are at 3412 m.
    for dx, dy in ((0, 0), (2400, 0), (0, -2400), (2400, -2400)):
        col = int((1004100 + dx - gt[0]) / gt[1])
        row = int((6539900 + dy - gt[3]) / gt[5])
        assert a[row, col] == pytest.approx(3400, abs=30)
    assert ogr.Open(str(tmp_path / "four" / "partition.gpkg")).GetLayerByName("faces").GetFeatureCount() == 80


def test_shapefiles_work_too(rockhatch_exe, sample_dir, tmp_path):
    # A folder of shapefiles is a multi-layer OGR dataset: faces.shp, lines.shp, orientation.shp.
    shp = tmp_path / "shp"
    gdal.VectorTranslate(str(shp), str(sample_dir / "partition.gpkg"), format="ESRI Shapefile")
    assert (shp / "faces.shp").exists() and (shp / "lines.shp").exists()
    r = run(rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", shp, "--style", "noisy",
            "-o", tmp_path / "o.svg")
    assert r.returncode == 0, r.stderr
    assert "20 faces" in r.stderr


def test_borders_digitised_twice_draw_one_valley(rockhatch_exe, sample_dir, tmp_path):
    # Two squares whose common side each digitised with its own vertices, 0.05-0.1 m apart
    # (issue 11): the borders are snapped, the valley along them is drawn once.
    x, y = 1004000, 6540000
    a = f"POLYGON(({x} {y},{x + 100} {y},{x + 100.1} {y + 30},{x + 100} {y + 100},{x} {y + 100},{x} {y}))"
    b = (f"POLYGON(({x + 100.08} {y - 0.06},{x + 200} {y},{x + 200} {y + 100},{x + 99.95} {y + 100.07},"
         f"{x + 99.9} {y + 70},{x + 100.08} {y - 0.06}))")
    write_partition(tmp_path / "p.gpkg", [a, b], [(f"LINESTRING({x + 100} {y},{x + 100} {y + 100})", "valley")])
    r = run(rockhatch_exe, "-q", "--dem", sample_dir / "dem.tif", "--partition", tmp_path / "p.gpkg",
            "--style", "high-ridges", "-o", tmp_path / "o.gpkg")
    assert r.returncode == 0, r.stderr
    ds = ogr.Open(str(tmp_path / "o.gpkg"))
    length = sum(f.GetGeometryRef().Length() for f in ds.GetLayerByName("hatch_valley"))
    assert length == pytest.approx(100, abs=0.5)  # once, not twice


def test_no_stroke_segment_leaves_a_concave_face_with_a_hole(rockhatch_exe, sample_dir, tmp_path):
    # A comb (three teeth: a concave outline) with a rectangular hole, a ridge along its foot
    # and a valley along one tooth (issue 11: ridge shapes were clipped to the outer ring
    # only, with zero-width bridges on concave outlines). Every segment of every stroke stays
    # in the face, its holes excluded.
    x, y = 1004000, 6540000
    outer = [(0, 0), (300, 0), (300, 200), (240, 200), (240, 60), (180, 60), (180, 200), (120, 200), (120, 60),
             (60, 60), (60, 200), (0, 200), (0, 0)]
    hole = [(200, 10), (200, 40), (280, 40), (280, 10), (200, 10)]
    ring = lambda pts: "(" + ",".join(f"{x + a} {y + b}" for a, b in pts) + ")"
    comb = f"POLYGON({ring(outer)},{ring(hole)})"
    write_partition(tmp_path / "comb.gpkg", [comb],
                    [(f"LINESTRING({x} {y},{x + 300} {y})", "ridge"),
                     (f"LINESTRING({x + 60} {y + 200},{x + 60} {y + 60},{x + 120} {y + 60})", "valley"),
                     (f"LINESTRING({x + 200} {y + 10},{x + 200} {y + 40},{x + 280} {y + 40})", "ridge")],
                    densities=[0.9])  # dark: the ridge shapes fall into it
    face = ogr.CreateGeometryFromWkt(comb)
    inside = face.Buffer(0.01)
    hole_core = ogr.CreateGeometryFromWkt(f"POLYGON({ring(hole)})").Buffer(-0.01)
    for style in ("ridge-triangles", "fine-ridges", "bidirectional"):
        out = tmp_path / f"{style}.gpkg"
        r = run(rockhatch_exe, "-q", "--dem", sample_dir / "dem.tif", "--partition", tmp_path / "comb.gpkg",
                "--style", style, "--param", "peak_length=6" if style != "ridge-triangles" else "ridge_length=4",
                "-o", out)
        assert r.returncode == 0, r.stderr
        ds = ogr.Open(str(out))
        segments = 0
        for layer in ("hatch_fill", "hatch_ridge", "hatch_valley", "hatch_cross"):
            for f in ds.GetLayerByName(layer):
                g = f.GetGeometryRef()
                for k in range(g.GetPointCount() - 1):
                    seg = ogr.Geometry(ogr.wkbLineString)
                    seg.AddPoint_2D(*g.GetPoint_2D(k))
                    seg.AddPoint_2D(*g.GetPoint_2D(k + 1))
                    assert inside.Contains(seg), f"{style}: {layer} segment {seg.ExportToWkt()} leaves the face"
                    assert not hole_core.Intersects(seg), f"{style}: {layer} segment in the hole"
                    segments += 1
        ridge = sum(1 for _ in ds.GetLayerByName("hatch_ridge"))
        assert segments > 100 and ridge > 0, (style, segments, ridge)


def test_slope_min_leaves_flat_ground_unhatched(rockhatch_exe, sample_dir, tmp_path):
    # --slope is a real input of the styles: with slope_min, no fill hatch lies where the
    # slope raster given reads below it; a flat slope raster leaves no fill at all.
    def fill_midpoints(path):
        ds = ogr.Open(str(path))
        pts = []
        for f in ds.GetLayerByName("hatch_fill"):
            g = f.GetGeometryRef()
            n = g.GetPointCount()
            a, b = g.GetPoint_2D(0), g.GetPoint_2D(n - 1)
            pts.append(((a[0] + b[0]) / 2, (a[1] + b[1]) / 2))
        return pts

    base = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "-o", tmp_path / "all.gpkg")
    assert base.returncode == 0, base.stderr
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "--param", "slope_min=80",
            "-o", tmp_path / "steep.gpkg")
    assert r.returncode == 0, r.stderr
    every, steep = fill_midpoints(tmp_path / "all.gpkg"), fill_midpoints(tmp_path / "steep.gpkg")
    assert 0 < len(steep) < 0.9 * len(every)
    # A slope raster given with --slope: half of it flat (0 %), half steep (100 %).
    dem = gdal.Open(str(sample_dir / "dem.tif"))
    gt, w, h = dem.GetGeoTransform(), dem.RasterXSize, dem.RasterYSize
    mid_x = gt[0] + gt[1] * w / 2
    drv = gdal.GetDriverByName("GTiff")
    slope = drv.Create(str(tmp_path / "slope.tif"), w, h, 1, gdal.GDT_Float32)
    slope.SetGeoTransform(gt)
    slope.SetProjection(dem.GetProjection())
    import numpy as np
    values = np.zeros((h, w), dtype=np.float32)
    values[:, w // 2:] = 100
    slope.GetRasterBand(1).WriteArray(values)
    slope = None
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "--slope", tmp_path / "slope.tif",
            "--param", "slope_min=50", "-o", tmp_path / "half.gpkg")
    assert r.returncode == 0, r.stderr
    half = fill_midpoints(tmp_path / "half.gpkg")
    # The gate reads the slope at the middle of each stroke before its jitter, which moves it
    # by up to half a hatch length (3 mm: 30 m at 1:10000) along.
    assert half and all(px >= mid_x - 30 for px, _ in half)
    assert sum(1 for px, _ in every if px >= mid_x) * 0.8 < len(half)
    # All flat: no fill at all.
    flat = gdal.Translate(str(tmp_path / "flat.tif"), str(tmp_path / "slope.tif"), scaleParams=[[0, 100, 0, 0]])
    flat = None
    r = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "noisy", "--slope", tmp_path / "flat.tif",
            "--param", "slope_min=50", "-o", tmp_path / "flat.gpkg")
    assert r.returncode == 0, r.stderr
    assert fill_midpoints(tmp_path / "flat.gpkg") == []


def test_relief_radius_option(rockhatch_exe, sample_dir, tmp_path):
    # --relief-radius sets the neighbourhood of the height field; a bad value is a usage error.
    near = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "high-ridges", "--relief-radius", "200",
               "-o", tmp_path / "near.svg")
    wide = run(rockhatch_exe, "-q", *sample_args(sample_dir), "--style", "high-ridges", "-o", tmp_path / "wide.svg")
    assert near.returncode == 0 and wide.returncode == 0, near.stderr + wide.stderr
    assert (tmp_path / "near.svg").read_bytes() != (tmp_path / "wide.svg").read_bytes()
    for bad in ("0", "-5", "nan", "far"):
        r = run(rockhatch_exe, *sample_args(sample_dir), "--relief-radius", bad, "-o", tmp_path / "x.svg")
        assert r.returncode == 2 and "--relief-radius" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert not (tmp_path / "x.svg").exists()
    assert "--relief-radius" in run(rockhatch_exe, "--help").stdout


def test_the_command_sets_its_allocator_and_a_user_may_override_it(rockhatch_exe, sample_dir, tmp_path):
    """Linked with jemalloc, the command asks it for huge pages and one arena per CPU
    (docs/engine.md); MALLOC_CONF in the environment still wins, and the drawing's bytes
    do not depend on the allocator."""
    libs = subprocess.run(["ldd", str(rockhatch_exe)], capture_output=True, text=True).stdout
    if "libjemalloc" not in libs:
        pytest.skip("the command is not linked with jemalloc here (no libjemalloc-dev at build time)")
    env = dict(os.environ, MALLOC_CONF="stats_print:true")
    stats = subprocess.run([str(rockhatch_exe), "--help"], capture_output=True, text=True, env=env).stderr
    assert 'opt.thp: "always"' in stats and 'opt.percpu_arena: "percpu"' in stats, stats[:2000]
    env = dict(os.environ, MALLOC_CONF="stats_print:true,thp:never,percpu_arena:disabled")
    stats = subprocess.run([str(rockhatch_exe), "--help"], capture_output=True, text=True, env=env).stderr
    assert 'opt.thp: "never"' in stats and 'opt.percpu_arena: "disabled"' in stats, stats[:2000]
    outs = []
    for conf in ("", "thp:never,percpu_arena:disabled"):
        out = tmp_path / f"h{len(outs)}.svg"
        env = dict(os.environ, MALLOC_CONF=conf)
        r = subprocess.run([str(rockhatch_exe), *map(str, sample_args(sample_dir)), "-q", "-o", str(out)],
                           capture_output=True, text=True, env=env, timeout=300)
        assert r.returncode == 0, r.stderr
        outs.append(out.read_bytes())
    assert outs[0] == outs[1]
