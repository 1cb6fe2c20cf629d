"""Control fields from Python (thesis 5.3): rockhatch.tex.Field and VectorField, their
compositions, grids from numpy, face-wise constants, the locality check as a context
manager; rockhatch.carto.Field is the same class."""
import math
import threading

import numpy as np
import pytest

from rockhatch import carto, tex
from rockhatch.tex import (Angle, Apply, BBox, Centroid, Clamp, Combine, Fallback, Field, FieldWindow,  # noqa: F401
                           GridPartition, Gradient, KEEP_OUTSIDE, LocalityCheck, MapToFaces, Norm, Nothing,
                           PlanarMap, Point, Polyline, Region, Restrict, SetThreads, StripesProperties,
                           VectorField, pi)

NAN = float("nan")


def isnan(v):
    return v != v


def test_carto_field_is_the_tex_field():
    assert carto.Field is tex.Field
    a = np.array([[1.0, 2.0], [3.0, -1.0]])
    f = carto.Field.from_array(a, (1000, 5, 0, 2000, 0, -5), nodata=-1)
    assert isinstance(f, tex.Field) and f.kind == "raster"


def test_numbers_callables_and_copies():
    assert Field(2.5)(0, 0) == 2.5 and Field.constant(-1)(Point(9, 9)) == -1
    assert isnan(Field()(0, 0))
    g = Field(lambda p: p.x + 2 * p.y)
    assert g(Point(1, 2)) == 5 and g((1, 2)) == 5 and g.kind == "python"
    assert Field(g)(1, 1) == 3
    assert isnan(Field(lambda p: None)(0, 0))
    with pytest.raises(TypeError, match="a field is"):
        Field("steep")
    d = Field.function(lambda p: p.x, BBox(0, 0, 10, 10))
    assert d(5, 5) == 5 and isnan(d(11, 5)) and not d.has_value(Point(-1, 0)) and d.has_value(Point(0, 0))
    assert d.domain().xmax == 10 and Field(1).domain() is None


def test_grid_from_numpy_is_bilinear_with_nodata():
    a = np.array([[1.0, 2.0], [3.0, -9.0]])
    g = Field.grid(a, (0, 10, 0, 20, 0, -10), nodata=-9)
    assert g.kind == "grid"
    assert g(5, 15) == 1 and g(15, 15) == 2 and g(5, 5) == 3
    assert g(10, 10) == pytest.approx(2.0)  # NoData left out, weights renormalised
    assert g(7.5, 12.5) == pytest.approx(1.6)
    assert isnan(g(-1, 10)) and isnan(g(15, 5.1)) is False
    # A rotated geotransform is inverted: cell centres keep their values.
    c, s = math.cos(0.4), math.sin(0.4)
    r = Field.grid(a, (3, 2 * c, -2 * s, 1, 2 * s, 2 * c))
    for row in range(2):
        for col in range(2):
            x = 3 + (col + 0.5) * 2 * c - (row + 0.5) * 2 * s
            y = 1 + (col + 0.5) * 2 * s + (row + 0.5) * 2 * c
            assert r(x, y) == pytest.approx(a[row, col])
    with pytest.raises(ValueError, match="2-D"):
        Field.grid(np.zeros(3), (0, 1, 0, 0, 0, -1))


def test_grid_matches_the_carto_raster_sampler():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(9, 13))
    a[2:4, 3:6] = np.nan
    gt = (500.0, 2.5, 0.0, 800.0, 0.0, -2.5)
    g = Field.grid(a, gt)
    r = carto.Raster.from_array(a, gt)
    xs, ys = rng.uniform(495, 540, 500), rng.uniform(775, 805, 500)
    np.testing.assert_array_equal(g.sample(xs, ys), carto.Field(r).sample(xs, ys))
    np.testing.assert_array_equal(g.sample(xs, ys), [r.sample(Point(x, y)) for x, y in zip(xs, ys)])


def test_faces_of_a_map_and_of_regions():
    c = Polyline([Point(0, 0), Point(10, 0), Point(10, 10), Point(0, 10)], True)
    c.append(Polyline([Point(5, 0), Point(5, 10)]))
    m = PlanarMap.induce(c)
    n = len(m.faces()) + 1
    f = Field.faces(m, [float(i) for i in range(n)])
    left, right = f(2, 5), f(8, 5)
    assert left != right and f(5, 5) == min(left, right) and isnan(f(20, 20))
    regions = [Region.rectangle(0, 0, 1, 1), Region([Point(10, 10), Point(20, 10), Point(20, 20), Point(10, 20)],
                                                    [[Point(14, 14), Point(16, 14), Point(16, 16), Point(14, 16)]])]
    rf = Field.faces(regions, [1.0, 2.0])
    assert rf(0.5, 0.5) == 1 and rf(12, 12) == 2 and isnan(rf(15, 15)) and isnan(rf(5, 5))
    assert f.kind == "faces"


def test_arithmetic_compositions_and_nan():
    x, y = Field(lambda p: p.x), Field(lambda p: p.y)
    p = Point(3, 4)
    assert (x + y)(p) == 7 and (x - y)(p) == -1 and (x * y)(p) == 12 and (x / y)(p) == 0.75
    assert (1 + x)(p) == 4 and (10 - x)(p) == 7 and (2 * y)(p) == 8 and (12 / x)(p) == 4 and (-x)(p) == -3
    assert (x + (lambda q: 1))(p) == 4
    assert Apply(x, lambda v: v * v)(p) == 9
    assert Combine(x, y, math.hypot)(p) == 5
    assert Clamp(x, 0, 2)(p) == 2
    assert Restrict(x, BBox(0, 0, 5, 5))(p) == 3 and isnan(Restrict(x, BBox(0, 0, 1, 1))(p))
    assert isnan(Restrict(x, Region.rectangle(0, 0, 2, 2))(p))
    assert Fallback(Restrict(x, BBox(0, 0, 1, 1)), 42)(p) == 42
    none = Field()
    calls = []
    assert isnan((none + 1)(p)) and isnan((x * none)(p))
    assert isnan(Apply(none, lambda v: calls.append(v) or v)(p)) and not calls


def test_vector_fields():
    v = VectorField(lambda p: Point(-p.y, p.x))
    assert v(1, 0) == Point(0, 1)
    assert Angle(v)(1, 0) == pytest.approx(pi / 2) and Norm(v)(3, 4) == pytest.approx(5)
    assert VectorField(1, lambda p: p.x)(7, 0) == Point(1, 7)
    assert VectorField(Point(2, 3))(0, 0) == Point(2, 3)
    g = Gradient(lambda p: p.x * p.x + 3 * p.y, 1e-3)(Point(1, 2))
    assert g.x == pytest.approx(2) and g.y == pytest.approx(3)


def grid_of_50():
    return GridPartition(StripesProperties(0, 50), StripesProperties(pi / 2, 50), KEEP_OUTSIDE)


def reading_at(field, dx):
    def mapper(face):
        c = Centroid(face)
        field(Point(c.x + dx, c.y))
        return Polyline([c, Point(c.x + 1, c.y)])
    return MapToFaces(mapper, grid_of_50())


def test_locality_check_counts_reads_far_from_the_visited_face():
    x = Field(lambda p: p.x)
    region = Region.rectangle(0, 0, 200, 200)
    faces = len(grid_of_50().induce(region).faces())
    for threads in (1, 2):
        SetThreads(threads)
        with LocalityCheck(margin=10) as c:
            reading_at(x, 0)(region)
        assert (c.reads, c.violations, c.worst) == (faces, 0, 0)
        with LocalityCheck(10) as c:
            reading_at(x, 1000)(region)
        assert c.reads == faces and c.violations == faces and c.worst == pytest.approx(975)
    SetThreads(0)
    with LocalityCheck() as c:
        x(1e6, 0)  # no window open: not checked
        with FieldWindow(BBox(0, 0, 10, 10)):
            x(5, 5)
            x(13, 14)
    assert (c.reads, c.violations, c.worst) == (2, 1, pytest.approx(5))


def test_python_field_read_from_worker_threads_takes_the_gil():
    # A C++ field composed with a Python one, sampled with the GIL released, and read by a
    # Python mapper on two threads: no deadlock, the values of a serial run.
    SetThreads(2)
    slow = Field(lambda p: p.x * 0.5)
    f = slow + Field.grid(np.ones((4, 4)), (0, 100, 0, 400, 0, -100))
    xs = np.linspace(0, 390, 200)
    np.testing.assert_array_equal(f.sample(xs, xs), xs * 0.5 + 1)
    out = []

    def worker():
        out.append(f.sample(xs, xs).sum())

    threads = [threading.Thread(target=worker) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=60)
    assert len(out) == 3 and len(set(out)) == 1
    with LocalityCheck(0) as c:
        curves = MapToFaces(lambda face: Polyline([Centroid(face), Point(f(Centroid(face)), 0)]), grid_of_50())(
            Region.rectangle(0, 0, 200, 200))
    assert len(curves) == c.reads and c.violations == 0
    SetThreads(0)


def test_control_fields_of_carto_accept_tex_fields():
    x = Field(lambda p: p.x)
    fields = carto.ControlFields(orientation=Clamp(x, 0, 1), density=0.5, height=x * 2, roughness=Field())
    assert fields.orientation(Point(3, 0)) == 1 and fields.height(Point(3, 0)) == 6
    assert isinstance(fields.density, Field) and fields.density.kind == "constant"


def test_python_field_read_by_a_style_on_the_pipeline_workers(sample_dir, tmp_path):
    # A Python style reads a Python field once per face, and hands another one to the
    # native JitterEdges mapper as its gate: the engine reads that one on its worker
    # threads, once per hatch piece. The drawing is the same on any number of threads.
    seen, gate_reads = [], []
    spacing = Field(lambda p: seen.append(1) or 2.0)
    gate = Field(lambda p: gate_reads.append(1) or (1.0 if p.x % 50 < 40 else 0.0))

    def style(fields, params):
        def face_fn(region):
            inside = carto.interior_point(region)
            step = spacing(inside) * params["spacing"]
            theta = fields.orientation(inside)
            hatch_lines = tex.StripesProperties(theta, step)
            tex.SetEdgeLabels(hatch_lines, "fill")
            grid = tex.GridPartition(hatch_lines, tex.StripesProperties(theta + tex.pi / 2, 5 * step), tex.KEEP_OUTSIDE)
            hatches = tex.MapToEdges(tex.JitterEdges("fill", theta, step, 5 * step, 0.0, gate=gate, gate_min=0.5), grid)
            return tex.Crop(hatches, tex.CROP)(region)
        return tex.Arrangement(face_fn)

    info = carto.StyleInfo("field-probe", "", "test", [carto.StyleParam("spacing", 1.0, "mm")])
    outs = []
    for threads in (1, 2):
        out = tmp_path / f"t{threads}.svg"
        s = carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [out],
                      style=carto.python_style(info, style), threads=threads)
        assert s.hatches > 50
        outs.append(out.read_bytes())
    assert outs[0] == outs[1] and len(seen) == 40
    assert len(gate_reads) % 2 == 0 and len(gate_reads) > 100


def test_align_to_field_and_the_print_budget_helpers():
    """AlignToField turns strokes onto the field's axis at their middle; ink_area and
    area_within are what print's per-cell ink budget reads (issue 16)."""
    from rockhatch.tex import AlignToField, Arrangement, Labelled, Point, Polyline, Region

    square = Region([Point(0, 0), Point(10, 0), Point(10, 10), Point(0, 10)])
    strokes = Arrangement(lambda r: Polyline([Point(4, 5), Point(6, 5)]))
    out = AlignToField(strokes, lambda p: math.pi / 2)(square)
    a, b = out.curves[0].points
    assert abs(a.x - 5) < 1e-12 and abs(b.x - 5) < 1e-12 and abs(abs(b.y - a.y) - 2) < 1e-12
    # A 2-unit valley (0.25 mm wide) and fill stroke (0.10 mm) at 1 ground unit per mm.
    curves = Labelled(Polyline([Point(0, 0), Point(2, 0)]), "valley")
    curves.append(Polyline([Point(5, 5), Point(7, 5)]))
    assert abs(carto.ink_area(curves, 1.0) - (2 * 0.25 + 2 * 0.10)) < 1e-12
    left = Region([Point(-1, -1), Point(4, -1), Point(4, 4), Point(-1, 4)])
    assert abs(carto.ink_area(curves, 1.0, left) - 0.5) < 1e-12
    assert abs(carto.area_within(square, left) - 16) < 1e-9


def test_cut_at_levels_and_noise_from_python():
    # Strokes down a plane falling southward (f = y), cut every 10: each piece starts on a level
    # line and ends 1 above the next; a Python callable serves as the field.
    from rockhatch.tex import Constant, CutAtLevels, GetSeed, Noise, Polyline, SetSeed
    saved = GetSeed()
    strokes = Polyline([Point(0, 45), Point(0, 3)])
    out = CutAtLevels(Constant(strokes), lambda p: p.y, 10, 1)(Region.rectangle(-10, -10, 10, 50))
    tops = sorted(max(c.points[0].y, c.points[-1].y) for c in out.curves)
    bottoms = sorted(min(c.points[0].y, c.points[-1].y) for c in out.curves)
    assert tops == pytest.approx([10, 20, 30, 40, 45]) and bottoms == pytest.approx([3, 11, 21, 31, 41])
    with pytest.raises(Exception, match="CutAtLevels"):
        CutAtLevels(Constant(strokes), lambda p: p.y, 0, 1)
    SetSeed(3)
    n = Noise(5.0)
    values = [n(Point(0.37 * k, 0.71 * k)) for k in range(100)]
    assert all(-1 <= v <= 1 for v in values) and max(values) - min(values) > 0.5
    SetSeed(3)
    assert Noise(5.0)(Point(1.5, 2.5)) == n(Point(1.5, 2.5))
    SetSeed(saved)
