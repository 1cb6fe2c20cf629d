"""The rock style's given structure lines: cliffs labelled in a partition (kind=cliff, or OSM's
natural=cliff|ridge|arete on a line layer) become cliff borders, drawn as cliff tops with their
strokes hanging into the face below; other OSM lines are not labels."""
import math
import sys

import pytest
from osgeo import ogr, osr

from bad_inputs import partition_file
from conftest import land_cover
from rockhatch import carto

SOUTH = "POLYGON((1003700 6539000,1004500 6539000,1004500 6539500,1003700 6539500,1003700 6539000))"
NORTH = "POLYGON((1003700 6539500,1004500 6539500,1004500 6540000,1003700 6540000,1003700 6539500))"
EDGE = "LINESTRING(1003700 6539500,1004500 6539500)"
EDGE_Y = 6539500.0


def osm_partition(path, tag_field):
    """Faces, and a line layer as GDAL's OSM driver writes one: `natural` as a field, or in
    other_tags."""
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(2154)
    fl = ds.CreateLayer("faces", srs, ogr.wkbPolygon)
    for wkt in (SOUTH, NORTH):
        f = ogr.Feature(fl.GetLayerDefn())
        f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        fl.CreateFeature(f)
    ll = ds.CreateLayer("lines", srs, ogr.wkbLineString)
    ll.CreateField(ogr.FieldDefn(tag_field, ogr.OFTString))
    lines = [(EDGE, "cliff"), ("LINESTRING(1003700 6539000,1003700 6540000)", "arete"),
             ("LINESTRING(1004500 6539000,1004500 6540000)", "tree_row")]
    for wkt, natural in lines:
        f = ogr.Feature(ll.GetLayerDefn())
        f.SetField(tag_field, natural if tag_field == "natural" else f'"natural"=>"{natural}","source"=>"survey"')
        f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        ll.CreateFeature(f)
    ds = None
    return path


def kinds(partition):
    out = {}
    for face in partition.faces:
        for s in face.boundary:
            out[s.kind] = out.get(s.kind, 0.0) + math.hypot(s.b.x - s.a.x, s.b.y - s.a.y)
    return out


@pytest.mark.parametrize("tag_field", ["natural", "other_tags"])
def test_osm_natural_tags_label_the_borders(tmp_path, sample_dir, tag_field):
    path = osm_partition(tmp_path / "osm.gpkg", tag_field)
    o = carto.PartitionOptions()
    o.path = str(path)
    part = carto.load_partition(o, "EPSG:2154")
    k = kinds(part)
    # The shared edge is a cliff (seen from both faces), the west side an arete (a ridge); the
    # tree row on the east side labels nothing.
    assert k.get(carto.LineKind.CLIFF, 0) == pytest.approx(2 * 800, rel=1e-6)
    assert k.get(carto.LineKind.RIDGE, 0) == pytest.approx(1000, rel=1e-6)
    assert k.get(carto.LineKind.OTHER, 0) == pytest.approx(800 + 800 + 1000, rel=1e-6)


def test_a_given_cliff_is_drawn_once_with_its_strokes_in_the_face_below(tmp_path, sample_dir):
    # The sample is a summit north of the edge: the ground falls south across it.
    part = partition_file(tmp_path, "p.gpkg", [SOUTH, NORTH], [(EDGE, "cliff")])
    prepared = carto.prepare(str(sample_dir / "dem.tif"), str(part))
    assert kinds(prepared.partition).get(carto.LineKind.CLIFF, 0) > 0
    drawing = carto.hatch(prepared, style="rock")
    south = next(f.id for f in prepared.partition.faces if f.region.bbox().ymax <= EDGE_Y + 1e-6)
    on_edge = {}
    hanging = 0
    for fh in drawing.faces:
        for h in fh.hatches:
            pts = list(h.points)
            if h.family == carto.Family.CLIFF and all(abs(p.y - EDGE_Y) < 1e-6 for p in pts):
                on_edge[fh.face_id] = on_edge.get(fh.face_id, 0.0) + sum(
                    math.hypot(b.x - a.x, b.y - a.y) for a, b in zip(pts, pts[1:]))
            if h.family == carto.Family.RIDGE and abs(pts[0].y - EDGE_Y) < 1e-6:
                assert fh.face_id == south
                assert pts[-1].y < EDGE_Y  # down, into the band
                hanging += 1
    assert list(on_edge) == [south]
    assert on_edge[south] == pytest.approx(800, rel=1e-6)
    assert hanging > 100


def test_mask_keeps_the_rock_of_a_land_cover_layer(tmp_path, sample_dir):
    dem = str(sample_dir / "dem.tif")
    everywhere = carto.prepare(dem, "auto")
    assert max(f.region.bbox().xmax for f in everywhere.partition.faces) > 1004500
    # OSM land cover: only the bare rock (west of x = 1004100) is rock.
    west = carto.prepare(dem, "auto", mask=land_cover(tmp_path / "osm.gpkg", True))
    assert west.partition.faces
    assert max(f.region.bbox().xmax for f in west.partition.faces) <= 1004100 + 1e-6
    # An untagged layer: every polygon counts.
    both = carto.prepare(dem, "auto", mask=land_cover(tmp_path / "plain.gpkg", False))
    assert max(f.region.bbox().xmax for f in both.partition.faces) > 1004500


def test_mask_needs_the_automatic_partition(rockhatch_exe, tmp_path, sample_dir):
    import subprocess
    mask = land_cover(tmp_path / "osm.gpkg", True)
    r = subprocess.run([rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", sample_dir / "partition.gpkg",
                        "--mask", mask, "-o", tmp_path / "out.svg"], capture_output=True, text=True)
    assert r.returncode == 2
    assert "--mask" in r.stderr and "--partition auto" in r.stderr
    assert not (tmp_path / "out.svg").exists()
    r = subprocess.run([rockhatch_exe, "--dem", sample_dir / "dem.tif", "--partition", "auto", "--mask", mask,
                        "--style", "rock", "-o", tmp_path / "out.gpkg"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))


def test_the_drawing_does_not_depend_on_how_the_faces_are_numbered_or_their_rings_turned(tmp_path, sample_dir):
    """A face's random draws (the rock style's frayed edge among them) are keyed by the face's
    extent, not its feature id: the sample's partition renumbered from 0 (as a shapefile
    numbers features) with every ring turned round draws the same strokes."""
    src = ogr.Open(str(sample_dir / "partition.gpkg"))
    path = tmp_path / "renumbered.gpkg"
    dst = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    for name in ("faces", "lines", "orientation"):
        layer = src.GetLayerByName(name)
        out = dst.CreateLayer(name, layer.GetSpatialRef(), layer.GetGeomType())
        defn = layer.GetLayerDefn()
        for i in range(defn.GetFieldCount()):
            out.CreateField(defn.GetFieldDefn(i))
        for k, f in enumerate(layer):
            g = f.GetGeometryRef().Clone()
            if name == "faces":
                for r in range(g.GetGeometryCount()):
                    ring = g.GetGeometryRef(r)
                    pts = ring.GetPoints()[::-1]
                    for j, p in enumerate(pts):
                        ring.SetPoint_2D(j, p[0], p[1])
            nf = ogr.Feature(out.GetLayerDefn())
            nf.SetFrom(f)
            nf.SetGeometry(g)
            nf.SetFID(k)  # from 0
            assert out.CreateFeature(nf) == 0
    dst = None
    def strokes(partition):
        drawing = carto.hatch(carto.prepare(sample_dir / "dem.tif", partition), style="rock")
        out = []
        for fh in drawing.faces:
            for h in fh.hatches:
                pts = [(p.x, p.y) for p in h.points]
                out.append((int(h.family), tuple(min(pts, pts[::-1]))))
        return sorted(out)

    given, renumbered = strokes(sample_dir / "partition.gpkg"), strokes(path)
    assert len(given) > 60000
    assert given == renumbered
