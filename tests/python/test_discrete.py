"""rockhatch.discrete: seed 004's operators from Python, Python callables where the seed
passes functions, the properties of the programs' outputs (checked on every pair of
elements with Distance, without the set's index), determinism and bad input."""
import math
import subprocess

import pytest

from conftest import GALLERY_PY, python_env
from rockhatch import discrete as d
from rockhatch.discrete import (And, BBox, BuiltinCircle, BuiltinHatch, Centroid, Compose, Const, Contour, CountUpTo,
                                Distance, Image, MinimalDistance, Not, Overlap, Point, Polyline, RandomPinning,
                                RandomR, Region, RegionSet, RegularPinning, RegularPinning1D, Rotation, Scale,
                                TangentFlowField, TexError, ToCurves, ToSVG, Translation, VoronoiCells,
                                greedy_distribution, relaxation, stream_line, trace_stream)
from rockhatch.tex import SetThreads, StreamScope



def pairs(regions, reach=0.0):
    """Smallest distance between two of the regions, over every pair near enough."""
    regions = list(regions)
    best = math.inf
    for i, a in enumerate(regions):
        ba = a.bbox().expanded(reach)
        for b in regions[i + 1:]:
            if ba.intersects(b.bbox()):
                best = min(best, Distance(a, b))
    return best


def test_star_import_gives_the_seed_names():
    ns = {}
    exec("from rockhatch.discrete import *", ns)
    for name in ["RandomPinning", "RegularPinning", "RegularPinning1D", "Centroid", "TangentFlowField", "Contour",
                 "Interpolation", "VoronoiCells", "ApplyThickness", "Translation", "Rotation", "Scale", "CountUpTo",
                 "Overlap", "RandomR", "Distance", "MinimalDistance", "Image", "BuiltinHatch", "BuiltinRectangle",
                 "BuiltinCircle", "UserRegion", "ToCurves", "greedy_distribution", "relaxation", "stream_line", "Not",
                 "And", "Compose", "Const", "pi"]:
        assert name in ns, name


def test_operators_are_values():
    c = CountUpTo(2)
    assert [c(), c(), c()] == [True, True, False]
    box = RegionSet([Region.rectangle(0, 0, 10, 10)])
    inside, outside = Overlap(box), Not(Overlap(box))
    assert inside(Point(5, 5)) and not outside(Point(5, 5))
    left = And(Overlap(box), lambda p: p.x < 5)
    assert left(Point(2, 2)) and not left(Point(7, 2))
    grown = Compose(Scale(2.0), Const(Region.rectangle(0, 0, 1, 1)))
    assert grown().area() == pytest.approx(4)
    moved = Translation(Region.rectangle(0, 0, 2, 2), Point(10, 20))
    assert Centroid(moved).x == pytest.approx(10) and Centroid(moved).y == pytest.approx(20)
    v = Rotation(math.pi / 2)(Point(1, 0))
    assert v.x == pytest.approx(0, abs=1e-15) and v.y == pytest.approx(1)


def test_transformations_take_a_shape_or_a_generator_alike():
    def ring(r):
        return [(p.x, p.y) for p in r.outer]

    shape = Region.rectangle(0, 0, 4, 1)
    angles = iter([0.3, 1.2])
    turned = Rotation(shape, lambda: next(angles))  # a Python callable as the angle
    assert ring(turned()) == ring(Rotation(shape, 0.3))
    assert ring(turned()) == ring(Rotation(shape, 1.2))
    factors = iter([2.0])
    assert Scale(shape, lambda: next(factors))().area() == pytest.approx(4 * shape.area())
    points = iter([Point(10, 20)])
    placed = Translation(shape, lambda: next(points))
    assert Centroid(placed()).x == pytest.approx(10)
    # A callable as the element, with a plain or a generated parameter.
    shapes = iter([shape, Scale(shape, 3.0)])
    both = Rotation(lambda: next(shapes), 0.5)
    assert ring(both()) == ring(Rotation(shape, 0.5))
    assert both().area() == pytest.approx(9 * shape.area())
    # The seed's spelling: the same draws as Compose(Rotation(RandomR(...)), Const(shape)).
    with StreamScope(0):
        a = Rotation(shape, RandomR(0, math.pi))
    with StreamScope(0):
        b = Compose(Rotation(RandomR(0, math.pi)), Const(shape))
    assert [ring(a()) for _ in range(3)] == [ring(b()) for _ in range(3)]
    assert ring(a()) != ring(shape)


def test_python_callables_drive_a_greedy_distribution():
    with StreamScope(0):
        hatches = RegionSet()
        thrown = greedy_distribution(hatches, CountUpTo(1500), RandomPinning(Image(400, 400)),
                                     lambda p: Translation(Rotation(BuiltinHatch(), p.x / 50), p),
                                     lambda r: not Overlap(hatches, r))
    assert thrown == 1500
    assert 200 < len(hatches) < 1500
    assert pairs(hatches) > 0


def test_minimal_distance_keeps_the_gap():
    with StreamScope(0):
        dots = RegionSet()
        greedy_distribution(dots, CountUpTo(1500), RandomPinning(Image(300, 300)), Translation(BuiltinCircle(3, 10)),
                            Not(MinimalDistance(dots, 5)))
    assert len(dots) > 100
    assert pairs(dots, 5) >= 5 - 1e-9


def test_density_from_a_python_function():
    p = RandomPinning(Image(100, 100), lambda q: 1.0 if q.y > 50 else 0.0)
    assert all(p().y > 50 for _ in range(500))


def test_a_pgm_image_as_a_density():
    field, frame = d.ParsePGM(b"P2\n2 2\n255\n255 0\n255 0\n")
    assert frame.bbox().xmax == 2 and frame.bbox().ymax == 2
    pins = RandomPinning(frame, field)
    assert all(pins().x < 1.5 for _ in range(300))  # the right column is black: never pinned there


def test_regular_pinnings():
    assert len(RegularPinning(Image(100, 100), 4, 5)) == 20
    assert len(RegularPinning1D(Contour(Region.rectangle(0, 0, 10, 10)), 1.0)) == 40
    assert len(RegularPinning1D(Polyline([Point(0, 0), Point(10, 0)]), 0.5)) == 6


def test_voronoi_cells_tile_the_domain_and_relaxation_spreads():
    with StreamScope(0):
        circles, relaxed = RegionSet(), RegionSet()
        greedy_distribution(circles, CountUpTo(40), RandomPinning(Image(400, 300)), Translation(BuiltinCircle(12, 16)),
                            Not(Overlap(circles)))
        domain = BBox(0, 0, 400, 300)
        cells = VoronoiCells(circles.regions, domain)
        assert len(cells) == len(circles)
        assert sum(c.area() for c in cells) == pytest.approx(400 * 300, rel=1e-9)
        for cell, circle in zip(cells, circles):
            assert all(cell.contains(q) for q in circle.outer if domain.contains(q))
        relaxation(circles, relaxed, CountUpTo(6), VoronoiCells(domain), Centroid)
    assert len(relaxed) == len(circles)
    assert pairs(relaxed, 1e9) > pairs(circles, 1e9)


def test_stream_lines_follow_a_python_field_and_do_not_cross():
    # A Python field: circles around the origin; a stream line stays on its circle.
    def swirl(p):
        r = math.hypot(p.x, p.y)
        return Point(-p.y / r, p.x / r)

    line = trace_stream(Point(50, 0), swirl, lambda p: True, 100)
    assert len(line) > 90
    assert all(abs(math.hypot(q.x, q.y) - 50) < 1.0 for q in line.points)
    # Closed orbits (a radial pull back to r = 50) and far longer than a turn: the line
    # stops where it would run over its own start.
    def orbit(p):
        r = math.hypot(p.x, p.y)
        return Point(-p.y / r + p.x / r * (50 - r), p.x / r + p.y / r * (50 - r))

    loop = trace_stream(Point(50, 0), orbit, lambda p: True, 1000)
    assert 2 * math.pi * 50 - 5 < len(loop) - 1 < 2 * math.pi * 50 + 5
    with StreamScope(0):
        circles = RegionSet([Translation(BuiltinCircle(25), Point(100, 100)),
                             Translation(BuiltinCircle(25), Point(220, 160))])
        lines = RegionSet()
        shaping = stream_line(TangentFlowField(circles, 2.0), Not(MinimalDistance(lines, 3)), 120, lambda t: 2.0, 8)
        greedy_distribution(lines, CountUpTo(300), RandomPinning(Image(320, 260)), shaping,
                            And(Not(Overlap(circles)), Not(MinimalDistance(lines, 1))))
    assert len(lines) > 10
    assert pairs(lines, 1) >= 1 - 1e-9
    assert all(not Overlap(circles, r) for r in lines)


def test_same_bytes_with_one_or_two_threads():
    def draw():
        with StreamScope(0):
            circles = RegionSet()
            greedy_distribution(circles, CountUpTo(60), RandomPinning(Image(500, 500)),
                                Translation(BuiltinCircle(15)), Not(Overlap(circles)))
            return ToSVG(ToCurves(VoronoiCells(circles.regions, BBox(0, 0, 500, 500))), 500)

    SetThreads(1)
    one = draw()
    SetThreads(2)
    two = draw()
    SetThreads(0)
    assert one == two


@pytest.mark.parametrize("call, match", [
    (lambda: RandomPinning(Image(10, 10), 0.0)(), "RandomPinning: no point found"),
    (lambda: RegularPinning(Image(10, 10), 0, 1), "RegularPinning: .*nx, ny"),
    (lambda: RegularPinning1D(Polyline([Point(0, 0), Point(1, 0)]), 0), "RegularPinning1D: density"),
    (lambda: VoronoiCells([Region.rectangle(0, 0, 1, 1)], BBox(0, 0, 5, 5)), "VoronoiCells: needs at least two"),
    (lambda: Scale(Region.rectangle(0, 0, 1, 1), -1.0), "Scale: the factor must be a positive"),
    (lambda: CountUpTo(-3), "CountUpTo"),
    (lambda: RandomR(1, 0), "RandomR"),
    (lambda: TangentFlowField(RegionSet(), 1.0), "TangentFlowField: needs at least one region"),
    (lambda: d.ReadPGM("/nonexistent.pgm"), "ReadPGM: /nonexistent.pgm: cannot open"),
    (lambda: d.ApplyThickness(Polyline([Point(0, 0), Point(1, 0)]), lambda t: -1.0), "ApplyThickness"),
])
def test_bad_input_is_a_tex_error(call, match):
    with pytest.raises(TexError, match=match):
        call()


def test_a_python_check_that_raises_stops_the_program():
    def bad(_region):
        raise RuntimeError("user check failed")

    with pytest.raises(RuntimeError, match="user check failed"):
        greedy_distribution(RegionSet(), CountUpTo(5), RandomPinning(Image(10, 10)), Translation(BuiltinHatch(2, 1)),
                            bad)


def test_the_figures_script_runs(tmp_path):
    r = subprocess.run(["/usr/bin/python3", str(GALLERY_PY), "--out", str(tmp_path), "--only",
                        "discrete_1a,discrete_1b,discrete_1e"],
                       capture_output=True, text=True, timeout=300, env=python_env())
    assert r.returncode == 0, r.stderr
    for n in ["1a", "1b", "1e"]:
        assert (tmp_path / f"discrete_{n}.svg").stat().st_size > 2000
