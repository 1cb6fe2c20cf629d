"""The Python module: its shape, the operators under the thesis's names, cells, mappers,
Random, threads and the GIL, and the errors it raises."""
import math
import pathlib
import threading
import time
import traceback

import pytest

import rockhatch
from rockhatch import tex
from rockhatch.tex import *  # noqa: F401,F403  (the way the thesis's scripts start)

# Tables 3.2 to 3.6 of the thesis, plus what its scripts use.
SEED_NAMES = """
StripesProperties SetEdgeLabels SetFaceLabels IrregularProperties SetWeightedVertexLabels
SetWeightedEdgeLabels SetWeightedFaceLabels StripesPartition GridPartition UniformPartition RandomPartition
CROP CROP_ADD_BOUNDARY KEEP_INSIDE KEEP_OUTSIDE
MapToVertices MapToEdges MapToFaces
IncidentFaces IncidentEdges IncidentVertices SourceVertex TargetVertex LeftFace RightFace MatchFace
Location LocationAt Centroid Contour ToCurve HasLabel IsBoundary Random
Union Merge Inside Outside
ImportSVG ExportSVG ExportSVGinDomain Nothing Append BBoxWidth BBoxHeight BBoxCenter Scale Rotate Translate MatchPoint MatchPoints
PointLabeled CurveLabeled Point pi cos sin SetSeed SetThreads
""".split()

BOX = Region.rectangle(0, 0, 1000, 1000)


def test_package_shape():
    compiled = pathlib.Path(rockhatch._rockhatch.__file__)
    assert compiled.suffix == ".so" and compiled.name.startswith("_rockhatch")
    assert pathlib.Path(rockhatch.__file__).name == "__init__.py"
    assert rockhatch.__version__
    assert issubclass(rockhatch.TexError, ValueError)
    assert issubclass(rockhatch.RockhatchError, RuntimeError)
    import rockhatch.carto as carto

    assert callable(carto.run) and callable(carto.compute_terrain)


@pytest.mark.parametrize("name", SEED_NAMES)
def test_every_operator_by_its_seed_name(name):
    assert name in globals(), f"{name} is not exported by 'from rockhatch.tex import *'"
    assert name in tex.__all__


# The math the Appendix A scripts call bare (teaser a: `curves[floor(Random(edge, 0, len(curves), 0))]`).
APPENDIX_A_MATH = "floor ceil fabs pow exp log sqrt hypot cos sin tan acos asin atan atan2".split()


def star_import():
    scope = {}
    exec("from rockhatch.tex import *", scope)
    return scope


@pytest.mark.parametrize("name", APPENDIX_A_MATH)
def test_the_star_import_brings_the_scripts_math(name):
    assert star_import()[name] is getattr(math, name)
    assert name in tex.__all__


def test_an_appendix_a_script_runs_with_the_star_import_alone():
    # Teaser a's way of choosing an element: floor() of a Random in [0, n) indexes a list.
    script = """
sizes = [10, 20, 30]
def edge_to_stroke(edge):
    s = sizes[floor(Random(edge, 0, len(sizes), 0))]
    return Scale(ToCurve(edge), s / 100 + fabs(sin(0)) + pow(2, 0) - exp(log(1)))
grid = GridPartition(StripesProperties(0, 100), StripesProperties(pi / 2, 100), KEEP_OUTSIDE)
out = MapToEdges(edge_to_stroke, grid)(Region.rectangle(0, 0, 300, 300))
"""
    scope = star_import()
    exec(script, scope)
    assert len(scope["out"]) == 24  # 4 x 3 horizontal + 3 x 4 vertical edges, each shrunk
    assert isinstance(scope["floor"](2.7), int)


def test_point_arithmetic():
    a, b = Point(1, 2), Point(3, -4)
    assert a + b == Point(4, -2)
    assert a - b == Point(-2, 6)
    assert a * 2 == 2 * a == Point(2, 4)
    assert b / 2 == Point(1.5, -2)
    assert -a == Point(-1, -2)
    assert tuple(a) == (1, 2)
    assert hash(Point(1, 2)) == hash(a)
    assert Point((5, 6)) == Point(5, 6)
    assert dot(a, b) == -5 and cross(a, b) == -10


def grid_map():
    h, v = StripesProperties(0, 100), StripesProperties(pi / 2, 100)
    SetEdgeLabels(h, "h1", "h2")
    SetEdgeLabels(v, "v1", "v2")
    SetFaceLabels(h, "row_even", "row_odd")
    return GridPartition(h, v, KEEP_INSIDE).induce(BOX)


def test_cells_are_equal_when_they_are_the_same_cell():
    m = grid_map()
    faces = m.faces()
    assert len(faces) == 100
    for f in faces[:10]:
        edges = IncidentEdges(f)
        assert len(edges) == 4
        # Each edge of a face has that face on one side: face == LeftFace(e) or RightFace(e).
        assert all(f == LeftFace(e) or f == RightFace(e) for e in edges)
        assert sum(f == RightFace(e) for e in edges) + sum(f == LeftFace(e) for e in edges) == 4
    assert faces[0] != faces[1]
    assert faces[0] == m.faces()[0] and hash(faces[0]) == hash(m.faces()[0])
    assert len({f for f in faces} | {f for f in m.faces()}) == 100
    assert faces[0] != "a face"


def test_incidence_and_labels_seen_by_python_mappers():
    seen = {}

    def vertex_mapper(v):
        seen.setdefault("degrees", []).append(len(IncidentEdges(v)))
        return Nothing()

    def edge_mapper(e):
        horizontal = HasLabel(e, "h1") or HasLabel(e, "h2")
        vertical = HasLabel(e, "v1") or HasLabel(e, "v2")
        assert horizontal != vertical
        a, b = Location(SourceVertex(e)), Location(TargetVertex(e))
        assert (a.y == b.y) == horizontal
        return ToCurve(e) if HasLabel(e, "h1") else Nothing()

    def face_mapper(f):
        assert len(IncidentVertices(f)) == 4
        c = Centroid(f)
        row = int(c.y // 100)
        assert HasLabel(f, "row_even") == (row % 2 == 0)
        return Scale(Contour(f), 0.5)

    h, v = StripesProperties(0, 100), StripesProperties(pi / 2, 100)
    SetEdgeLabels(h, "h1", "h2")
    SetEdgeLabels(v, "v1", "v2")
    SetFaceLabels(h, "row_even", "row_odd")
    grid = GridPartition(h, v, KEEP_INSIDE)
    MapToVertices(vertex_mapper, grid)(BOX)
    degrees = seen["degrees"]
    assert len(degrees) == 121 and degrees.count(4) == 81 and degrees.count(2) == 4
    edges = MapToEdges(edge_mapper, grid)(BOX)
    # h1 lines are y = 0, 200, ..., 1000: 6 lines of 10 edges.
    assert len(edges) == 60
    faces = MapToFaces(face_mapper, grid)(BOX)
    # A contour is one curve per edge of its face: four sides per square.
    assert len(faces) == 4 * 100
    assert len(PlanarMap.induce(faces).faces()) == 100
    assert abs(BBoxWidth(faces) - 950) < 1e-9


def python_jitter_texture():
    def jitter(e):
        d = Point(Random(-5, 5), Random(-5, 5))  # unkeyed: keyed by the visited cell
        return Translate(ToCurve(e), d + Point(Random(e, -1, 1, 7), 0))

    return MapToEdges(jitter, UniformPartition(IrregularProperties(300 / 1e6), KEEP_OUTSIDE))


def test_random_is_deterministic_with_python_mappers_on_any_thread_count():
    outputs = {}
    try:
        for threads in (1, 2, 1, 2):
            SetThreads(threads)
            SetSeed(7)
            outputs.setdefault(threads, []).append(ToSVG(python_jitter_texture()(BOX), 1000))
        SetSeed(8)
        other = ToSVG(python_jitter_texture()(BOX), 1000)
    finally:
        SetThreads(0)
        SetSeed(0)
    assert outputs[1][0] == outputs[1][1] == outputs[2][0] == outputs[2][1]
    assert other != outputs[1][0]


def test_python_mappers_run_one_cell_after_the_other_on_the_calling_thread():
    # A Python mapper holds the interpreter's lock: the engine calls it cell after cell on
    # the thread that evaluates the arrangement (two workers would only pass the lock back
    # and forth), with the same output as on one thread.
    idents = set()

    def mapper(f):
        idents.add(threading.get_ident())
        return Scale(Contour(f), 0.5)

    grid = GridPartition(StripesProperties(0, 50), StripesProperties(pi / 2, 50), KEEP_INSIDE)
    outs = []
    for threads in (2, 1):
        SetThreads(threads)
        try:
            outs.append(ToSVG(MapToFaces(mapper, grid)(BOX), 1000))
        finally:
            SetThreads(0)
    assert outs[0] == outs[1]
    assert idents == {threading.get_ident()}


def test_python_arrangements_run_on_the_engine_threads():
    # Python code called from the engine's worker threads (both sides of a Union are
    # evaluated in parallel) takes the interpreter's lock back safely.
    idents = set()

    def side(r):
        idents.add(threading.get_ident())
        time.sleep(0.05)  # the other side starts meanwhile, on the other worker
        return Polyline([Point(0, 0), Point(10, 10)])

    SetThreads(2)
    try:
        out = Union(Arrangement(side), Arrangement(side))(BOX)
    finally:
        SetThreads(0)
    assert len(out) == 2
    assert len(idents) == 2, "both workers should have run Python code"


def test_the_gil_is_released_during_cpp_work():
    # A heavy evaluation runs in a thread; the main thread keeps counting meanwhile.
    dense = UniformPartition(IrregularProperties(20000 / 1e6), KEEP_OUTSIDE)
    result = {}
    worker = threading.Thread(target=lambda: result.setdefault("c", dense(BOX)))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
    worker.join()
    assert len(result["c"]) > 10000
    assert ticks > 1000, f"the main thread ran only {ticks} times during the C++ evaluation"


def test_operator_errors_are_python_exceptions():
    with pytest.raises(rockhatch.TexError, match="StripesProperties.*-1") as e:
        StripesProperties(0, -1)
    assert e.value.op == "StripesProperties"
    with pytest.raises(TypeError):
        StripesProperties(0, "wide")
    with pytest.raises(TypeError, match="SetEdgeLabels: labels must be strings"):
        SetEdgeLabels(StripesProperties(0, 1), "a", 3)
    with pytest.raises(TypeError, match="label, weight pairs"):
        SetWeightedFaceLabels(IrregularProperties(1e-4), "a", 0.5, "b")
    with pytest.raises(rockhatch.TexError, match="no_such_file.svg"):
        ImportSVG("no_such_file.svg")
    with pytest.raises(rockhatch.TexError, match="'end'"):
        PointLabeled(Polyline([Point(0, 0), Point(1, 1)]), "end")
    with pytest.raises(rockhatch.TexError, match="Region"):
        Region([Point(0, 0), Point(1, 1)])


def test_a_mapper_returning_the_wrong_type_is_a_type_error():
    with pytest.raises(TypeError, match=r"MapToEdges: the mapper returned int; a mapper must return Curves"):
        MapToEdges(lambda e: 3, StripesPartition(StripesProperties(0, 100)))(BOX)
    with pytest.raises(TypeError, match=r"MapToFaces: the mapper returned NoneType"):
        MapToFaces(lambda f: None, StripesPartition(StripesProperties(0, 100)))(BOX)


def test_an_exception_in_a_mapper_propagates_with_its_traceback():
    def faulty_mapper(v):
        if Location(v).x > 500:
            raise KeyError("vertex too far east")
        return Nothing()

    for threads in (1, 2):
        SetThreads(threads)
        try:
            with pytest.raises(KeyError, match="vertex too far east") as e:
                MapToVertices(faulty_mapper, GridPartition(StripesProperties(0, 100), StripesProperties(pi / 2, 100),
                                                           KEEP_INSIDE))(BOX)
        finally:
            SetThreads(0)
        frames = [f.name for f in traceback.extract_tb(e.value.__traceback__)]
        assert "faulty_mapper" in frames


def test_nested_arrangements_inside_python_mappers():
    # A mapper evaluating a sub-scale arrangement on its face (the thesis's clusters).
    def face_to_dots(f):
        sub = UniformPartition(IrregularProperties(20 / (BBoxWidth(f) * BBoxHeight(f))), CROP_ADD_BOUNDARY)
        return MapToFaces(lambda g: Scale(Contour(g), 0.3), sub)(f)

    SetThreads(2)
    try:
        out = MapToFaces(face_to_dots, StripesPartition(StripesProperties(pi / 2, 250)))(BOX)
    finally:
        SetThreads(0)
    assert len(out) > 4 * 15


def test_svg_round_trip_and_curves_api(tmp_path):
    c = Append(Polyline([Point(0, 0), Point(10, 0)]), Polyline([Point(0, 0), Point(0, 5), Point(5, 5)], True))
    assert len(c) == 2 and BBoxWidth(c) == 10 and BBoxHeight(c) == 5 and BBoxCenter(c) == Point(5, 2.5)
    path = tmp_path / "c.svg"
    ExportSVG(c, 20, str(path))
    back = ImportSVG(str(path))
    assert len(back) == 2
    assert [len(x.points) for x in back.curves] == [2, 3]
    assert back.curves[1].closed
    m = MatchPoints(c, Point(0, 0), Point(10, 0), Point(0, 0), Point(0, 20))
    assert abs(m.curves[0].points[1].x) < 1e-12 and abs(m.curves[0].points[1].y - 20) < 1e-12


def test_each_random_partition_draws_its_own_sites():
    # Teaser b's ten identical calls must give ten different layers.
    SetSeed(0)
    p = IrregularProperties(40e-6)
    a, b = UniformPartition(p, KEEP_OUTSIDE), UniformPartition(p, KEEP_OUTSIDE)
    win = BOX
    assert ToSVG(a(win), 1000) != ToSVG(b(win), 1000)
    assert ToSVG(a(win), 1000) == ToSVG(a(win), 1000)  # the stream is fixed at creation
    # An explicit seed repeats a stream on purpose.
    assert ToSVG(RandomPartition(p, KEEP_OUTSIDE, seed=7)(win), 1000) == \
        ToSVG(RandomPartition(p, KEEP_OUTSIDE, seed=7)(win), 1000)
    # SetSeed restarts the numbering: the same script, the same sites.
    SetSeed(0)
    again = UniformPartition(p, KEEP_OUTSIDE)
    assert ToSVG(again(win), 1000) == ToSVG(a(win), 1000)


def test_partitions_built_in_python_mappers_take_their_stream_from_the_cell():
    fixed = Region.rectangle(0, 0, 300, 300)
    grid = GridPartition(StripesProperties(0, 250), StripesProperties(pi / 2, 250), KEEP_INSIDE)

    def per_face(f):
        # The same fixed square for every face: what differs is the stream.
        return UniformPartition(IrregularProperties(3e-4), KEEP_INSIDE)(fixed)

    outs = []
    for threads in (1, 2):
        SetThreads(threads)
        try:
            outs.append(ToSVG(MapToFaces(per_face, grid)(BOX), 1000))
        finally:
            SetThreads(0)
    assert outs[0] == outs[1]
    seen = set()

    def one(f):
        seen.add(ToSVG(UniformPartition(IrregularProperties(3e-4), KEEP_INSIDE)(fixed), 300))
        return Nothing()

    MapToFaces(one, grid)(BOX)
    assert len(seen) == 16


FRAME_SVG = """<svg><rect x="100" y="100" width="300" height="300"/>
<rect x="200" y="200" width="100" height="100"/></svg>"""


def test_export_svg_in_domain_fills_the_frame(tmp_path):
    SetSeed(0)
    frame = ParseSVG(FRAME_SVG, "frame.svg")
    region = FrameRegion(frame)
    assert len(region.holes) == 1
    a = GridPartition(StripesProperties(0.3, 17), StripesProperties(1.9, 23), KEEP_OUTSIDE)
    path = tmp_path / "filled.svg"
    c = ExportSVGinDomain(a, frame, str(path), margin=10)
    text = path.read_text()
    assert 'viewBox="90 90 320 320"' in text
    assert not (tmp_path / "filled.svg.tmp").exists()
    # The same curves in memory, and as an arrangement that ignores its window.
    assert ToSVG(c, 500) == ToSVG(EvaluateInDomain(a, frame), 500)
    assert ToSVG(InDomain(a, frame)(BOX), 500) == ToSVG(c, 500)
    # Nothing outside the frame (up to the outline), the frame's two rings drawn last.
    for cv in c.curves[:-2]:
        for p in cv.points:
            assert 100 - 1e-6 <= p.x <= 400 + 1e-6 and 100 - 1e-6 <= p.y <= 400 + 1e-6
            assert not (200 + 1e-6 < p.x < 300 - 1e-6 and 200 + 1e-6 < p.y < 300 - 1e-6)
    assert [cv.closed for cv in c.curves[-2:]] == [True, True]
    # The grid fills the whole frame: its lines' length is the frame's area (300^2 - 100^2)
    # over each family's spacing (8,194 against 8,184 drawn).
    def length(cv):
        pts = list(cv.points) + (list(cv.points)[:1] if cv.closed else [])
        return sum(math.hypot(q.x - p.x, q.y - p.y) for p, q in zip(pts, pts[1:]))

    assert len(c.curves) > 300
    assert sum(length(cv) for cv in c.curves[:-2]) == pytest.approx(80000 / 17 + 80000 / 23, rel=0.01)
    assert [length(cv) for cv in c.curves[-2:]] == pytest.approx([1200, 400])
    assert ToSVG(Merge(a, a)(BOX), 1000) == ToSVG(Union(a, a)(BOX), 1000)


def test_export_svg_in_domain_needs_a_closed_curve(tmp_path):
    a = StripesPartition(StripesProperties(0.0, 20))
    open_frame = Polyline([Point(0, 0), Point(100, 0), Point(100, 100)])
    with pytest.raises(TexError, match="ExportSVGinDomain.*no closed curve"):
        ExportSVGinDomain(a, open_frame, str(tmp_path / "x.svg"))
    assert not (tmp_path / "x.svg").exists()


def test_faces_know_whether_they_are_bounded():
    m = PlanarMap.induce(Polyline([Point(0, 0), Point(10, 0), Point(10, 10)], True))
    inner = m.faces()
    assert len(inner) == 1 and inner[0].is_bounded_face()
    assert not m.unbounded_face().is_bounded_face()
    e = m.edges()[0]
    assert {LeftFace(e).is_bounded_face(), RightFace(e).is_bounded_face()} == {True, False}


def test_face_locator_finds_the_face_holding_a_point():
    """FaceLocator(map).face_at(p): on a 10 x 10 grid of unit squares with a square hole cut
    in one of them, every random point is in the face whose outline holds it (checked against
    a plain scan of the faces), a point in the hole is in the hole's face, and a point
    outside is in the unbounded face."""
    import random
    grid = Arrangement(GridPartition(StripesProperties(0, 1), StripesProperties(math.pi / 2, 1), CROP_ADD_BOUNDARY))
    curves = grid(Region.rectangle(0, 0, 10, 10))
    curves.append(Polyline([Point(3.3, 3.3), Point(3.6, 3.3), Point(3.6, 3.6), Point(3.3, 3.6)], True))
    m = PlanarMap.induce(curves)
    locator = FaceLocator(m)
    rng = random.Random(1)
    regions = [(f, ToRegion(f)) for f in m.faces()]
    for _ in range(300):
        p = Point(rng.uniform(0.01, 9.99), rng.uniform(0.01, 9.99))
        found = locator.face_at(p)
        assert found.is_bounded_face()
        holding = [f for f, r in regions if r.contains(p)]
        assert holding == [found]
    hole = locator.face_at(Point(3.45, 3.45))
    assert ToRegion(hole).area() == pytest.approx(0.09)
    assert not locator.face_at(Point(-5, 5)).is_bounded_face()
    assert locator.face_at(Point(-5, 5)) == m.unbounded_face()
