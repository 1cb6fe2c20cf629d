"""rockhatch.tex.SynthesizeAlongCurve / SynthesizeInRectangle (seed 002) from Python: the
topology of the output counted again here (contour nesting, after checking that no two
segments meet), use inside a Python mapper along every edge of a partition, determinism and
errors."""
import math
import pathlib

import pytest

from rockhatch.tex import (KEEP_OUTSIDE, GridPartition, ImportSVG, MapToEdges, Point, Polyline, Region, SetThreads,
                           StripesProperties, SynthesizeAlongCurve, SynthesizeInRectangle, TexError, ToCurve, ToSVG,
                           pi)

ELEMENTS = pathlib.Path(__file__).resolve().parents[2] / "libtex" / "examples" / "elements"


def exemplar(name):
    return ImportSVG(str(ELEMENTS / f"{name}.svg"))


def area(ring):
    return 0.5 * sum(a.x * b.y - b.x * a.y for a, b in zip(ring, ring[1:] + ring[:1]))


def inside(ring, p):
    hit = False
    for a, b in zip(ring, ring[-1:] + ring[:-1]):
        if (a.y > p.y) != (b.y > p.y) and p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x:
            hit = not hit
    return hit


def segments_meet(c):
    """True when two segments of the contours touch or cross (neighbours along a contour aside)."""
    segs = []
    for r, cv in enumerate(c.curves):
        p = list(cv.points)
        for i in range(len(p)):
            a, b = p[i], p[(i + 1) % len(p)]
            segs.append((min(a.x, b.x), max(a.x, b.x), a, b, r, i, len(p)))
    segs.sort(key=lambda s: s[0])

    def orient(p, q, r):
        v = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)
        return (v > 0) - (v < 0)

    for i, s in enumerate(segs):
        for t in segs[i + 1:]:
            if t[0] > s[1]:
                break
            if s[4] == t[4] and ((s[5] + 1) % s[6] == t[5] or (t[5] + 1) % s[6] == s[5]):
                continue
            o1, o2 = orient(s[2], s[3], t[2]), orient(s[2], s[3], t[3])
            o3, o4 = orient(t[2], t[3], s[2]), orient(t[2], t[3], s[3])
            if o1 != o2 and o3 != o4:
                return True
    return False


def topology(c):
    """(components, holes, oriented): even nesting depth bounds a component, odd a hole."""
    rings = [list(cv.points) for cv in c.curves]
    comps = holes = 0
    oriented = True
    for i, r in enumerate(rings):
        depth = sum(1 for j, o in enumerate(rings) if j != i and inside(o, r[0]))
        if depth % 2 == 0:
            comps += 1
        else:
            holes += 1
        oriented &= (area(r) > 0) == (depth % 2 == 0)
    return comps, holes, oriented


def wave(length, amp, n=150):
    return Polyline([Point(length * i / n, amp * math.sin(3 * pi * i / n)) for i in range(n + 1)])


@pytest.mark.parametrize("holes", [None, 0, 2])
def test_one_component_along_an_open_curve(holes):
    c = SynthesizeAlongCurve(exemplar("synth_vine"), wave(1500, 60), 40, components=1, holes=holes,
                             event_grouping=0.03, seed=3)
    assert all(cv.closed for cv in c.curves)
    assert not segments_meet(c)
    comps, h, oriented = topology(c)
    assert comps == 1 and oriented
    if holes is not None:
        assert h == holes


def test_closed_pattern_round_a_circle():
    circle = Polyline([Point(300 * math.cos(2 * pi * i / 200), 300 * math.sin(2 * pi * i / 200)) for i in range(200)],
                      True)
    c = SynthesizeAlongCurve(exemplar("synth_ladder"), circle, 40, components=1, closed_pattern=True,
                             event_grouping=0.03, seed=1)
    assert not segments_meet(c)
    assert topology(c)[0] == 1


def test_inside_a_python_mapper_along_every_edge():
    grid = GridPartition(StripesProperties(0, 200), StripesProperties(pi / 2, 200), KEEP_OUTSIDE)
    vine = exemplar("synth_vine")
    made = []

    def ornament(edge):
        c = SynthesizeAlongCurve(vine, ToCurve(edge), 30, components=1, holes=0, event_grouping=0.03,
                                 max_length_deviation=0.5)
        made.append(c)
        return c

    out = MapToEdges(ornament, grid)(Region.rectangle(0, 0, 400, 400))
    assert len(made) > 4 and len(out) == sum(len(c) for c in made)
    # Each edge's ornament is one component without holes (ornaments of edges meeting at a
    # vertex may overlap there: each is a pattern of its own).
    for c in made:
        assert not segments_meet(c)
        assert topology(c)[:2] == (1, 0)


def test_rectangle_is_one_component():
    c = SynthesizeInRectangle(exemplar("synth_ladder"), 500, 400, 60, components=1, event_grouping=0.03, seed=2)
    assert not segments_meet(c)
    assert topology(c)[0] == 1
    box = c.bbox()
    assert 0 <= box.ymin and box.ymax <= 400


def test_same_seed_same_bytes_at_one_and_two_threads():
    outs = []
    for threads in (1, 2):
        SetThreads(threads)
        c = SynthesizeAlongCurve(exemplar("synth_vine"), wave(1200, 40), 40, event_grouping=0.03, seed=11)
        outs.append(ToSVG(c, 2000))
    SetThreads(0)
    assert outs[0] == outs[1]


def test_impossible_request_is_a_clear_error():
    with pytest.raises(TexError, match="no sequence of the exemplar's .* gives 1 component"):
        SynthesizeAlongCurve(exemplar("synth_two_blobs"), wave(2000, 10), 40, components=1)


@pytest.mark.parametrize("kwargs, match", [
    (dict(band_height=0), "band_height"),
    (dict(band_height=10, components=0), "components"),
    (dict(band_height=10, holes=-2), "holes"),
    (dict(band_height=10, slicing="zigzag"), "slicing must be"),
    (dict(band_height=10, closed_pattern=True), "closed_pattern"),
    (dict(band_height=10, event_grouping=0), r"event_grouping must be in \(0, 1\] or unset"),
])
def test_bad_options_name_themselves(kwargs, match):
    with pytest.raises(TexError, match=match):
        SynthesizeAlongCurve(exemplar("synth_vine"), wave(300, 10), **kwargs)
# Five exemplars of scripts/synth_exemplars.py whose events lie closer together than the seed's
# 0.2 of their width: that grouping leaves each one piece, which cannot make one component.
FIVE = ["synth_rungs", "synth_bar_beads", "synth_rings", "synth_truss", "synth_dots"]


@pytest.mark.parametrize("name", FIVE)
def test_the_defaults_succeed_on_ordinary_exemplars(name):
    ex = exemplar(name)
    c = SynthesizeAlongCurve(ex, wave(1500, 60), 40)
    assert not segments_meet(c)
    comps, holes, oriented = topology(c)
    assert comps == 1 and oriented
    # None is the default: the grouping is chosen from the exemplar.
    assert ToSVG(SynthesizeAlongCurve(ex, wave(1500, 60), 40, event_grouping=None), 2000) == ToSVG(c, 2000)
    # The seed's grouping, asked for, still refuses, and the error gives a grouping that works.
    with pytest.raises(TexError, match=r"exemplar's 1 pieces gives 1 component.*; event_grouping=0\.\d+ meets it "
                                       r"\(leave event_grouping unset"):
        SynthesizeAlongCurve(ex, wave(1500, 60), 40, event_grouping=0.2)


def test_the_grouping_named_by_the_error_works():
    with pytest.raises(TexError) as e:
        SynthesizeAlongCurve(exemplar("synth_rings"), wave(1500, 60), 40, event_grouping=0.2, holes=44)
    g = float(str(e.value).split("event_grouping=")[1].split()[0])
    c = SynthesizeAlongCurve(exemplar("synth_rings"), wave(1500, 60), 40, event_grouping=g, holes=44)
    assert topology(c)[:2] == (1, 44)


def test_the_seeds_grouping_is_kept_where_it_works():
    # The project's ladder makes one component at 0.2: the same bytes with the option unset.
    a = SynthesizeAlongCurve(exemplar("synth_ladder"), wave(1500, 60), 40, seed=4)
    b = SynthesizeAlongCurve(exemplar("synth_ladder"), wave(1500, 60), 40, seed=4, event_grouping=0.2)
    assert ToSVG(a, 2000) == ToSVG(b, 2000)


def test_a_band_without_events_is_told_to_slice_uniformly():
    top = [Point(20 * i, 10 * (i % 2) + 5) for i in range(31)]
    zigzag = Polyline([Point(p.x, p.y - 8) for p in top] + top[::-1], True)
    with pytest.raises(TexError, match=r"; slicing=uniform \(slicing_lines=8\) meets it \(the exemplar has no topological "
                                       r"event but its ends, so no event_grouping can cut it\)"):
        SynthesizeAlongCurve(zigzag, wave(2000, 10), 40)
    c = SynthesizeAlongCurve(zigzag, wave(2000, 10), 40, slicing="uniform")
    assert topology(c)[0] == 1


def test_unknown_option_is_a_type_error():
    with pytest.raises(TypeError, match="unexpected keyword argument .colour."):
        SynthesizeAlongCurve(exemplar("synth_vine"), wave(300, 10), 10, colour="red")
