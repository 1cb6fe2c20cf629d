"""rockhatch.tex: the engine's stock mappers (JitterEdges) handed to MapToEdges as native
values, and the operators the style programs use (Crop, Outline, Labelled, labelled
regions, SeedScope, StreamScope)."""
import math

import pytest

from rockhatch.tex import (CROP, KEEP_OUTSIDE, Curve, Curves, Crop, EdgeMapper, GetSeed, GetThreads, GridPartition,
                           HasLabel, JitterEdges, Labelled, Location, MapToEdges, MatchPoints, Nothing, Outline, Point,
                           PlanarMap, Random, Region, SeedScope, SetEdgeLabels, SetSeed, SetThreads, SourceVertex,
                           StreamScope, StripesProperties, TargetVertex, TexError, ToCurve, UniformPartition,
                           IrregularProperties, pi)

BOX = Region.rectangle(0, 0, 100, 80)
THETA = 0.4


def grid():
    along, across = StripesProperties(THETA, 8), StripesProperties(THETA + pi / 2, 20)
    SetEdgeLabels(along, "fill")
    return GridPartition(along, across, KEEP_OUTSIDE)


def python_jitter(label, theta, across, along, r):
    """JitterEdges written out in Python, as the thesis's App. E writes it."""
    d = Point(math.cos(theta), math.sin(theta))
    n = Point(-d.y, d.x)

    def moved(v):
        return (Location(v) + n * Random(v, -across * r / 2, across * r / 2, 0)
                + d * Random(v, -along * r / 2, along * r / 2, 1))

    def mapper(e):
        if not HasLabel(e, label):
            return Nothing()
        s, t = SourceVertex(e), TargetVertex(e)
        return MatchPoints(ToCurve(e), Location(s), Location(t), moved(s), moved(t))

    return mapper


def points(curves):
    return [list(c.points) for c in curves.curves]


def test_the_native_mapper_draws_what_the_python_one_draws():
    native = JitterEdges("fill", THETA, 8, 20, 0.7)
    assert isinstance(native, EdgeMapper) and "fill" in repr(native)
    a = MapToEdges(native, grid())(BOX)
    b = MapToEdges(python_jitter("fill", THETA, 8, 20, 0.7), grid())(BOX)
    assert len(a) > 50 and points(a) == points(b)
    assert all("fill" in c.labels for c in a.curves)


def test_the_native_mapper_is_the_same_on_any_thread_count_and_follows_the_seed():
    saved_threads, saved_seed = GetThreads(), GetSeed()
    try:
        SetSeed(3)
        runs = []
        for threads in (1, 2):
            SetThreads(threads)
            runs.append(points(MapToEdges(JitterEdges("fill", THETA, 8, 20, 0.7), grid())(BOX)))
        assert runs[0] == runs[1]
        with SeedScope(4):
            assert GetSeed() == 4
            other = points(MapToEdges(JitterEdges("fill", THETA, 8, 20, 0.7), grid())(BOX))
        assert GetSeed() == 3 and other != runs[0]
    finally:
        SetThreads(saved_threads)
        SetSeed(saved_seed)


def test_a_native_mapper_called_on_one_edge():
    m = PlanarMap.induce(grid()(BOX))
    edges = m.edges()
    fill = [e for e in edges if HasLabel(e, "fill")]
    assert fill and len(fill) < len(edges)
    mapper = JitterEdges("fill", THETA, 8, 20, 0.0, gap=0.5)
    for e in fill[:10]:
        c = mapper(e).curves[0]
        whole = ToCurve(e).curves[0]
        length = math.dist(tuple(c.points[0]), tuple(c.points[-1]))
        assert length == pytest.approx(0.5 * math.dist(tuple(whole.points[0]), tuple(whole.points[-1])))
    assert all(len(mapper(e)) == 0 for e in edges if not HasLabel(e, "fill"))


def test_the_gate_is_any_field():
    kept = MapToEdges(JitterEdges("fill", THETA, 8, 20, 0.7, gate=lambda p: p.x, gate_min=50), grid())(BOX)
    everything = MapToEdges(JitterEdges("fill", THETA, 8, 20, 0.7), grid())(BOX)
    assert 0 < len(kept) < len(everything)
    assert len(MapToEdges(JitterEdges("fill", THETA, 8, 20, 0.7, gate=None, gate_min=1), grid())(BOX)) == 0
    with pytest.raises(TypeError, match="a field is"):
        JitterEdges("fill", THETA, 8, 20, 0.7, gate="steep", gate_min=1)


def test_crop_outline_labelled_and_labelled_regions():
    edges = Curves()
    edges.curves = [Curve([Point(0, 0), Point(100, 0), Point(100, 80)], labels=["ridge"]),
                    Curve([Point(100, 80), Point(0, 80), Point(0, 0)], labels=["valley"])]
    region = BOX.with_edges(edges)
    assert region.has_edges() and not BOX.has_edges()
    assert sorted(c.labels[0] for c in Outline()(region).curves) == ["ridge", "valley"]
    assert len(Outline()(BOX)) == 1  # the ring
    small = Region.rectangle(10, 10, 30, 30)
    cut = Crop(grid(), CROP)(small)
    assert len(cut) > 0 and all(10 - 1e-9 <= q.x <= 30 + 1e-9 and 10 - 1e-9 <= q.y <= 30 + 1e-9
                                for c in cut.curves for q in c.points)
    marked = Labelled(cut, "ridge")
    assert all("ridge" in c.labels for c in marked.curves)


def test_stream_scope_restarts_the_numbering_of_streams():
    def sites():
        p = IrregularProperties(0.01)
        with StreamScope(99):
            return points(PlanarMap.induce(UniformPartition(p, KEEP_OUTSIDE)(BOX)).edge_curves())

    assert sites() == sites()


def test_thin_lines_keeps_an_even_share_that_grows_with_the_field():
    """ThinLines as a native mapper: the kept lines are a subset at a smaller share, their
    count follows the share, a field growing to the right keeps more lines there, and an
    owner region takes only the edges centred in it."""
    from rockhatch.tex import Field, Pow, ThinLines, ThinRank, LocationAt

    def lines(keep, owner=None):
        got = MapToEdges(ThinLines(JitterEdges("fill", THETA, 8, 20, 0.0), THETA, 8, keep, owner), grid())(BOX)
        n = Point(-math.sin(THETA), math.cos(THETA))
        out = set()
        for c in got.curves:
            a, b = c.points[0], c.points[-1]
            out.add(round(((a.x + b.x) / 2 * n.x + (a.y + b.y) / 2 * n.y) / 8))
        return out, got

    every, _ = lines(1.0)
    half, _ = lines(0.5)
    third, _ = lines(0.3)
    assert third < half < every and len(every) > 12
    assert all(ThinRank(k) < 0.5 for k in half) and all(ThinRank(k) >= 0.5 for k in every - half)
    assert lines(0.0)[1].empty()
    # keep = x / 100: more curves on the right half than on the left
    _, ramp = lines(Field(lambda p: p.x / 100.0))
    right = sum(1 for c in ramp.curves if c.points[0].x > 50)
    assert right > 1.5 * (len(ramp.curves) - right)
    # an owner: the curves whose middle lies in it, whole (not cut at its border)
    left = Region.rectangle(-100, -100, 50, 200)
    _, owned = lines(1.0, left)
    _, everything = lines(1.0)
    assert 0 < len(owned.curves) < len(everything.curves)
    assert all((c.points[0].x + c.points[-1].x) / 2 <= 50 for c in owned.curves)
    assert any(max(c.points[0].x, c.points[-1].x) > 50 for c in owned.curves)
    assert Pow(Field(3.0), 2.0)(Point(0, 0)) == 9.0
    # The engine's refusal, not a TypeError of a wrong call (whose text names "spacing" too).
    with pytest.raises(TexError, match="ThinLines: the spacing must be positive"):
        ThinLines(JitterEdges("fill", THETA, 8, 20, 0.0), THETA, 0.0, 1.0)


def test_smoothed_and_map_along_draw_strokes_hanging_from_a_smooth_line():
    """Smoothed keeps a curve's ends and rounds its corner; MapAlong hands a Python mapper the
    points every spacing along it (from half a spacing), with unit tangents, indices and the
    length left, and gathers what it returns."""
    from rockhatch.tex import MapAlong, Polyline, Smoothed

    corner = Curves()
    corner.curves = [Curve([Point(0, 0), Point(40, 0), Point(40, 40)], labels=["ridge"])]
    line = Smoothed(corner, 4.0).curves[0]
    assert (line.points[0].x, line.points[0].y) == (0, 0) and (line.points[-1].x, line.points[-1].y) == (40, 40)
    assert "ridge" in line.labels
    assert 0.1 < min(math.hypot(p.x - 40, p.y) for p in line.points) < 1.0
    seen = []

    def hang(foot, tangent, k, to_end):
        seen.append((foot, tangent, k, to_end))
        return Polyline([foot, foot + Point(-tangent.y, tangent.x)])

    straight = Curves()
    straight.curves = [Curve([Point(0, 0), Point(10, 0)])]
    strokes = MapAlong(straight, 2.0, hang)
    assert len(strokes.curves) == 5 and [k for _, _, k, _ in seen] == [0, 1, 2, 3, 4]
    assert [f.x for f, _, _, _ in seen] == [1.0, 3.0, 5.0, 7.0, 9.0]
    assert all((t.x, t.y) == (1.0, 0.0) for _, t, _, _ in seen)
    assert [round(r, 9) for _, _, _, r in seen] == [9.0, 7.0, 5.0, 3.0, 1.0]
    with pytest.raises(TexError, match="MapAlong: the spacing must be positive"):
        MapAlong(straight, 0.0, hang)
