"""Crest ornaments from Python: the pipeline's crest_ornament / crest_height_mm options, the
Python command line (same option table, same bytes as the C++ program), draw_crests on a
partition, and errors with the command's exit codes."""
import re
import subprocess
import sys

import pytest
from osgeo import gdal, ogr

from conftest import python_env
from rockhatch import RockhatchError, carto


def run_sample(sample_dir, outputs, **kwargs):
    return carto.run(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg"), [str(p) for p in outputs],
                     style="noisy", **kwargs)


def test_crests_from_python_one_polygon_per_ridge(sample_dir, tmp_path):
    stats = run_sample(sample_dir, [tmp_path / "c.gpkg"], crest_ornament="default", crest_height_mm=2.5)
    part = carto.prepare(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg")).partition
    ridges = [i for i, line in enumerate(part.lines) if line.kind == carto.LineKind.RIDGE]
    assert stats.crests == len(ridges) >= 5
    ds = ogr.Open(str(tmp_path / "c.gpkg"))  # kept: the layer dies with its dataset
    layer = ds.GetLayerByName("crest")
    ids = []
    for f in layer:
        g = f.GetGeometryRef()
        assert g.GetGeometryType() == ogr.wkbPolygon and g.IsValid() and g.GetArea() > 0
        ids.append(f.GetField("ridge_id"))
    # One polygon per ridge, no more; its id is the ridge's key, from its points.
    drawn = carto.draw_crests(part, "default", 2.5 * 10000 / 1000, seed=0).ornaments
    assert sorted(ids) == sorted(o.id for o in drawn) and len(set(ids)) == len(ridges)
    assert any(n.startswith("crest ornaments on") for n in stats.notes)


def _crest_layer(path):
    """{ridge_id: polygon} of a written crest layer (OGR geometries, cloned)."""
    ds = ogr.Open(str(path))
    out = {}
    for f in ds.GetLayerByName("crest"):
        assert f.GetField("ridge_id") not in out, "two crest polygons with one ridge id"
        out[f.GetField("ridge_id")] = f.GetGeometryRef().Clone()
    return out


def _line(points):
    g = ogr.Geometry(ogr.wkbLineString)
    for p in points:
        g.AddPoint_2D(p.x, p.y)
    return g


def test_each_crest_polygon_lies_along_its_own_ridge(sample_dir, tmp_path):
    """Checked against the partition's ridge lines, not against draw_crests: each polygon of
    the crest layer lies in a band of its height along one ridge line and covers it end to
    end but for the branches cut back at nodes; no two polygons share a ridge; and the
    ridge_id follows the ridge, the same in a run with another seed and band height."""
    part = carto.prepare(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg")).partition
    ridges = [_line(line.points) for line in part.lines if line.kind == carto.LineKind.RIDGE]
    assert len(ridges) >= 5
    owner = {}
    # (run, band height in mm at 1:10,000: 25 m and 15 m on the ground, seed)
    for run, mm, seed in (("a", 2.5, 0), ("b", 1.5, 9)):
        run_sample(sample_dir, [tmp_path / f"{run}.gpkg"], crest_ornament="default", crest_height_mm=mm, seed=seed)
        band = mm * 10000 / 1000
        crests = _crest_layer(tmp_path / f"{run}.gpkg")
        assert len(crests) == len(ridges)
        mine = {}
        for rid, poly in crests.items():
            # The ridge this polygon covers most of (a ridge ends at nodes where others start).
            covered = [r.Intersection(poly.Buffer(0.05 * band)).Length() / r.Length() for r in ridges]
            best = max(range(len(ridges)), key=covered.__getitem__)
            assert covered[best] > 0.6, f"{run}: crest {rid} covers no ridge ({max(covered):.2f})"
            assert sorted(covered)[-2] < 0.2, f"{run}: crest {rid} covers two ridges"
            # Within a band of its height of the ridge (a little more for the teeth's tips).
            assert poly.Within(ridges[best].Buffer(1.5 * band)), f"{run}: crest {rid} strays from its ridge"
            mine[best] = rid
        assert sorted(mine) == list(range(len(ridges))), f"{run}: a ridge has no crest, or one has two"
        owner[run] = mine
    assert owner["a"] == owner["b"], "a ridge's id changed with the seed or the band height"


def test_draw_crests_is_keyed_by_the_ridge(sample_dir, tmp_path):
    part = carto.prepare(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg")).partition
    a = _rings(carto.draw_crests(part, "default", 20.0, seed=5))
    b = _rings(carto.draw_crests(part, band_height=20.0, seed=5))
    c = _rings(carto.draw_crests(part, "default", 20.0, seed=6))
    assert a == b and a != c
    assert all(len([r for r in o if _area(r) > 0]) == 1 for o in a)  # one outer ring each
    assert "<svg" in carto.default_crest_svg()
    # Keyed by the ridge, not by the order it comes in: the same partition with its line
    # layer written in reverse order draws the same ornaments (as a set).
    reversed_lines = tmp_path / "reversed.gpkg"
    gdal.VectorTranslate(str(reversed_lines), str(sample_dir / "partition.gpkg"), layers=["faces", "orientation"])
    src, dst = ogr.Open(str(sample_dir / "partition.gpkg")), ogr.Open(str(reversed_lines), 1)
    lines = src.GetLayerByName("lines")
    out = dst.CreateLayer("lines", lines.GetSpatialRef(), lines.GetGeomType())
    for i in range(lines.GetLayerDefn().GetFieldCount()):
        out.CreateField(lines.GetLayerDefn().GetFieldDefn(i))
    features = list(lines)
    for f in reversed(features):
        g = ogr.Feature(out.GetLayerDefn())
        g.SetFrom(f)
        assert out.CreateFeature(g) == 0
    assert len(features) > 5
    src = dst = None
    turned = carto.prepare(str(sample_dir / "dem.tif"), str(reversed_lines)).partition
    d = _rings(carto.draw_crests(turned, "default", 20.0, seed=5))
    assert len(a) >= 5 and sorted(map(str, d)) == sorted(map(str, a))


def _rings(result):
    return [[[(p.x, p.y) for p in ring] for ring in o.rings] for o in result.ornaments]


def _area(ring):
    return 0.5 * sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(ring, ring[1:] + ring[:1]))


def test_python_command_writes_the_same_bytes_as_the_program(rockhatch_exe, sample_dir, tmp_path):
    args = ["-q", "--dem", str(sample_dir / "dem.tif"), "--partition", str(sample_dir / "partition.gpkg"),
            "--style", "noisy", "--crest-ornament", "default", "--crest-height", "1.5", "--seed", "4"]
    subprocess.run([str(rockhatch_exe), *args, "-o", str(tmp_path / "cpp.svg")], check=True)
    subprocess.run([sys.executable, "-m", "rockhatch", *args, "-o", str(tmp_path / "py.svg")], check=True,
                   env=python_env())
    svg = (tmp_path / "cpp.svg").read_bytes()
    assert b'<g id="crest"' in svg
    assert svg == (tmp_path / "py.svg").read_bytes()


@pytest.mark.parametrize("exemplar, height, code, message", [
    ("/nonexistent/crest.svg", None, 3, r"--crest-ornament '/nonexistent/crest.svg': no such file"),
    ("default", 0.0, 2, r"--crest-height"),
    ("default", 80.0, 2, r"--crest-height"),
    (None, 2.0, 2, r"--crest-height needs --crest-ornament"),
])
def test_bad_crest_options(sample_dir, tmp_path, exemplar, height, code, message):
    with pytest.raises(RockhatchError, match=message) as e:
        run_sample(sample_dir, [tmp_path / "x.svg"], crest_ornament=exemplar, crest_height_mm=height)
    assert e.value.code == code
    assert not (tmp_path / "x.svg").exists()


def test_an_exemplar_that_cannot_make_one_band_is_refused(rockhatch_exe, sample_dir, tmp_path):
    apart = tmp_path / "apart.svg"
    apart.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0 L 10 10 L 0 10 Z '
                     'M 0 20 L 10 20 L 10 30 L 0 30 Z"/></svg>')
    r = subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                        str(sample_dir / "partition.gpkg"), "--crest-ornament", str(apart), "-o",
                        str(tmp_path / "o.svg")], capture_output=True, text=True)
    assert r.returncode == 6
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "cannot make one connected crest band" in lines[0]


def test_every_ridge_of_the_real_dem_is_one_valid_polygon(real_dem_file):
    """The automatic partition of Chamonix.tif (599 ridge lines): each ornament drawn is one
    polygon GEOS finds valid (its outer ring and the holes inside it); the ridges skipped
    because no pattern fits them are few, and short branches cut back where ridges meet are
    counted apart, all in the note; ornaments of different ridges seldom meet (118 of 596
    pairs did before the ends were cut back at nodes, 5 of 518 since)."""
    part = carto.prepare(str(real_dem_file), "auto").partition
    ridges = sum(1 for line in part.lines if line.kind == carto.LineKind.RIDGE)
    r = carto.draw_crests(part, "default", 20.0)
    assert f"on {len(r.ornaments)} of {ridges} ridge line(s)" in r.notes[0]
    refused = re.search(r"(\d+) skipped: no pattern fits", r.notes[0])
    assert refused is None or int(refused.group(1)) <= 0.02 * ridges, r.notes[0]
    assert len(r.ornaments) >= 0.8 * ridges, r.notes[0]
    polygons = []
    for o in r.ornaments:
        outer = [ring for ring in o.rings if _area([(p.x, p.y) for p in ring]) > 0]
        assert len(outer) == 1, f"ridge {o.ridge}"
        poly = ogr.Geometry(ogr.wkbPolygon)
        for ring in sorted(o.rings, key=lambda ring: -_area([(p.x, p.y) for p in ring])):
            lr = ogr.Geometry(ogr.wkbLinearRing)
            for p in list(ring) + [ring[0]]:
                lr.AddPoint_2D(p.x, p.y)
            poly.AddGeometry(lr)
        assert poly.IsValid(), f"ridge {o.ridge}"
        polygons.append((o.ridge, poly, poly.GetEnvelope()))
    meeting = 0
    for i, (_, a, ea) in enumerate(polygons):
        for _, b, eb in polygons[i + 1:]:
            if ea[1] < eb[0] or eb[1] < ea[0] or ea[3] < eb[2] or eb[3] < ea[2]:
                continue
            meeting += a.Intersects(b)
    assert meeting <= 0.02 * len(polygons), f"{meeting} pairs of ornaments meet"
