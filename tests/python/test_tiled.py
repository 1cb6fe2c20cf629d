"""rockhatch.tex: tiled planar maps (thesis Ch. 4) under the C++ names: Tiled, TiledMap,
GhostMap, Random on a copy, and the same drawing as the planar-map engine."""
import pytest

from rockhatch.tex import (CROP, CROP_ADD_BOUNDARY, KEEP_INSIDE, Inside, Outside, Rasterize, KEEP_OUTSIDE, Contour, ExportSVG, GhostMap, GridPartition, HasLabel,
                           IncidentEdges, MapToFaces, MapToVertices, Nothing, Random, Region, Scale, SetFaceLabels,
                           Curves, GetThreads, SetThreads, StripesPartition, StripesProperties, TexError, Tiled, TiledMap, pi)

WINDOW = Region.rectangle(0, 0, 300, 200)


def labelled_grid(border):
    rows, columns = StripesProperties(0, 20), StripesProperties(pi / 2, 30)
    SetFaceLabels(columns, "a", "b")
    return GridPartition(rows, columns, border)


def segments(curves):
    """The drawing as a set of rounded, undirected segments with their edge labels."""
    out = set()
    for c in curves.curves:
        pts = list(c.points)
        for p, q in zip(pts, pts[1:] + (pts[:1] if c.closed else [])):
            a, b = sorted([(round(p.x, 6), round(p.y, 6)), (round(q.x, 6), round(q.y, 6))])
            out.add((a, b, tuple(c.labels)))
    return out


def test_tiled_grid_is_the_engine_grid():
    tiled = labelled_grid(Tiled(KEEP_OUTSIDE))
    assert isinstance(tiled, TiledMap)
    assert abs(tiled.period1.y) == pytest.approx(20)
    assert abs(tiled.period2.x) == pytest.approx(60)  # two face labels: two columns per period
    assert segments(tiled(WINDOW)) == segments(labelled_grid(KEEP_OUTSIDE)(WINDOW))


def test_mapped_faces_inside_match_the_engine():
    def shrink(f):
        return Scale(Contour(f), 0.5 if HasLabel(f, "a") else 0.8)

    tiled = MapToFaces(shrink, labelled_grid(Tiled()))
    inner = Region.rectangle(60, 40, 240, 160)
    engine = MapToFaces(shrink, labelled_grid(KEEP_OUTSIDE))(WINDOW)
    inside = [c for c in engine.curves if all(60 <= p.x <= 240 and 40 <= p.y <= 160 for p in c.points)]
    got = tiled.Convert(inner, KEEP_INSIDE)
    assert len(got.curves) == len(inside) > 0
    expected = Curves()
    expected.curves = inside
    assert segments(got) == segments(expected)


def test_border_vertices_have_degree_four():
    degrees = []

    def record(v):
        degrees.append(len(IncidentEdges(v)))
        return Nothing()

    MapToVertices(record, labelled_grid(Tiled()))
    assert degrees and set(degrees) == {4}


def test_random_in_a_regular_mapper_is_an_error():
    with pytest.raises(TexError, match="GhostMap"):
        MapToFaces(lambda f: Scale(Contour(f), Random(f, 0.5, 1.0, 0)), labelled_grid(Tiled()))


def test_ghost_mapping_is_deterministic_at_any_thread_count():
    wall = MapToFaces(lambda f: Scale(Contour(f), 0.8), labelled_grid(Tiled(CROP)))
    ghost = GhostMap(lambda e: Nothing() if Random(e, 0, 1, 0) < 0.4 else e.curves, wall)
    saved = GetThreads()
    try:
        SetThreads(1)
        one = segments(ghost(WINDOW))
        SetThreads(2)
        two = segments(ghost(WINDOW))
    finally:
        SetThreads(saved)
    assert one == two
    assert 0 < len(one) < len(segments(wall(WINDOW)))


def test_a_tiled_map_is_an_arrangement(tmp_path):
    """A tiled map evaluated on a square as any arrangement is (ExportSVG) draws what the
    planar-map engine draws there: the same curves, segment for segment."""
    out = tmp_path / "stripes.svg"
    tiled = ExportSVG(StripesPartition(StripesProperties(0.3, 10), Tiled(CROP_ADD_BOUNDARY)), 300, str(out))
    engine = ExportSVG(StripesPartition(StripesProperties(0.3, 10), CROP_ADD_BOUNDARY), 300, str(tmp_path / "e.svg"))
    assert out.read_text().count("<path") + out.read_text().count("<polyline") > 5

    def segments(curves):
        out = set()
        for cv in curves.curves:
            pts = list(cv.points) + ([cv.points[0]] if cv.closed else [])
            for p, q in zip(pts, pts[1:]):
                a, b = (round(p.x, 6) + 0.0, round(p.y, 6) + 0.0), (round(q.x, 6) + 0.0, round(q.y, 6) + 0.0)
                if a != b:
                    out.add(tuple(sorted((a, b))))
        return out

    assert len(tiled.curves) == len(engine.curves) > 30
    assert segments(tiled) == segments(engine)


def test_stripes_cannot_be_mapped():
    with pytest.raises(TexError, match="unbounded"):
        MapToFaces(lambda f: Contour(f), StripesPartition(StripesProperties(0.3, 10), Tiled()))



def test_inside_outside_and_rasterize():
    lines = StripesPartition(StripesProperties(0, 6), Tiled())
    squares = MapToFaces(lambda f: Scale(Contour(f), 0.55),
                         GridPartition(StripesProperties(0, 40), StripesProperties(pi / 2, 40), Tiled()))
    inside, outside = Inside(lines, squares, CROP), Outside(lines, squares, CROP)
    assert abs(inside.period1.y) == pytest.approx(120)
    length = lambda c: sum(abs(q.x - p.x) for cv in c.curves for p, q in zip(list(cv.points), list(cv.points)[1:]))
    whole = length(lines.Convert(WINDOW, CROP))
    inside_length, outside_length = length(inside.Convert(WINDOW, CROP)), length(outside.Convert(WINDOW, CROP))
    assert inside_length + outside_length == pytest.approx(whole)
    # Each part against the planar-map engine (neither may be empty: the sum alone holds when
    # Inside returns nothing and Outside everything), on a window of whole grid cells (the
    # engine scales each cell as the window crops it).
    cells = Region.rectangle(0, 0, 320, 200)
    plain_lines = StripesPartition(StripesProperties(0, 6), CROP)
    plain_squares = MapToFaces(lambda f: Scale(Contour(f), 0.55),
                               GridPartition(StripesProperties(0, 40), StripesProperties(pi / 2, 40), CROP))
    expected_inside = length(Inside(plain_lines, plain_squares, CROP)(cells))
    assert expected_inside == pytest.approx(18 * 8 * 22)  # 18 lines cross 8 squares 22 wide
    assert length(inside.Convert(cells, CROP)) == pytest.approx(expected_inside)
    assert length(outside.Convert(cells, CROP)) == pytest.approx(length(Outside(plain_lines, plain_squares, CROP)(cells)))
    assert 0 < inside_length < whole
    image = Rasterize(squares, WINDOW, 0.5, 1.0)
    assert image.shape == (400, 600) and image.dtype.name == "uint8"
    assert image.min() == 0 and image.max() == 255
    with pytest.raises(TexError, match="no common multiple"):
        Inside(StripesPartition(StripesProperties(0.3, 6), Tiled()), squares, CROP)


def test_a_sub_partition_is_mapped_on_the_lattice_it_repeats_on():
    grid = GridPartition(StripesProperties(0, 30), StripesProperties(pi / 2, 50), Tiled())
    # Hatching 20 apart in cells 30 high: both repeat every 60, two periods of the grid.
    hatched = MapToFaces(lambda f: StripesPartition(StripesProperties(0, 20), CROP)(f), grid)
    assert abs(hatched.period1.y) == pytest.approx(60) or abs(hatched.period2.y) == pytest.approx(60)
    # At 45 degrees the hatching never repeats with the grid: an error naming the periods.
    with pytest.raises(TexError, match=r"MapToFaces.*every 7 .*not periodic"):
        MapToFaces(lambda f: StripesPartition(StripesProperties(pi / 4, 7), CROP)(f), grid)


def test_face_labels_at_a_point_of_a_mapped_map():
    from rockhatch.tex import MapToEdges, Point, ToCurve
    grid = labelled_grid(Tiled())
    # The grid's edges as curves (with their side labels): the faces of the mapped map are
    # the cells again, found by point location in its block, labels included.
    edges = MapToEdges(lambda e: ToCurve(e), grid)
    points = [Point(3.7 + 13.1 * k, -250.3 + 29.9 * k) for k in range(40)]
    assert [edges.FaceLabelsAt(p) for p in points] == [grid.FaceLabelsAt(p) for p in points]
    assert {tuple(edges.FaceLabelsAt(p)) for p in points} == {("a",), ("b",)}


def test_face_labels_of_a_band_and_distance_far_from_the_origin():
    from rockhatch.tex import Point, Union
    bands = StripesProperties(0, 120, 300)
    SetFaceLabels(bands, "a", "b", "c")
    stripes = StripesPartition(bands, Tiled())
    # Bands 120 and 300 wide labelled a, b, c in turn: [0, 120) a, [120, 420) b, [420, 540) c,
    # [-300, 0) c; the pattern repeats every six bands (1260). The band's own label, and its
    # middle 60 from the curves, a whole number of periods away too.
    p1, p2 = stripes.period1, stripes.period2
    assert {(p1.x, p1.y), (p2.x, p2.y)} == {(0, 1260), (1260, 0)}
    for y, label in ((60, "a"), (180, "b"), (480, "c"), (-60, "c"), (600, "a")):
        assert stripes.FaceLabelsAt(Point(50, y)) == [label], y
    for k in (1, 1000, -77777):
        p = Point(50 + k * (p1.x + p2.x), 60 + k * (p1.y + p2.y))
        assert stripes.FaceLabelsAt(p) == ["a"]
        assert stripes.DistanceToCurves(p) == pytest.approx(60, abs=1e-6)
    # With squares in the bands: a face of the union carries the labels of its sides (the
    # planar map's rule). The square at (90, 105), 73.5 to 136.5 high, is cut by the line
    # y = 120: its lower part has a side on band a's line and one on the square (r1); the
    # square at (90, 315) lies inside band b: its sides are the square's alone (r2); the band
    # around the squares keeps its own label.
    rows = StripesProperties(0, 210)
    SetFaceLabels(rows, "r1", "r2")
    squares = MapToFaces(lambda f: Scale(Contour(f), 0.3), GridPartition(rows, StripesProperties(pi / 2, 180), Tiled()))
    both = Union(stripes, squares)
    assert squares.FaceLabelsAt(Point(90, 105)) == ["r1"] and squares.FaceLabelsAt(Point(90, 315)) == ["r2"]
    assert sorted(both.FaceLabelsAt(Point(90, 105))) == ["a", "r1"]
    assert both.FaceLabelsAt(Point(90, 315)) == ["r2"]
    assert both.FaceLabelsAt(Point(5, 60)) == ["a"] and both.FaceLabelsAt(Point(5, 315)) == ["b"]


def test_a_mapper_reading_absolute_positions_is_an_error():
    from rockhatch.tex import Centroid
    grid = labelled_grid(Tiled())
    with pytest.raises(TexError, match="reads absolute positions"):
        MapToFaces(lambda f: Contour(f) if Centroid(f).x > 0 else Nothing(), grid)
    MapToFaces(lambda f: Scale(Contour(f), 0.5), grid)  # reads the cell only: fine
