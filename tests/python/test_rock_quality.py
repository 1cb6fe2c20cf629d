"""The default style against the goals of issue 46 on the Nordkette DEM (5 m cells, cliffs and
couloirs above Innsbruck, NoData around it; ../shared/data/nordkette), with --partition auto,
measured as bench/print_quality.py measures them for docs/print-quality.md and docs/rock.md:
no drawn outline, the DEM's crests and cliff tops drawn, the tone following the shade, the
strokes on the fall line, the ink under its ceiling, and the rock's edge on the breaks of slope.
Skipped, with the reason, when ../shared is absent."""
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))

import print_quality as pq  # noqa: E402

SCALES = (10000, 25000)


@pytest.fixture(scope="module")
def measures():
    if not pq.NORDKETTE.exists():
        pytest.skip(f"{pq.NORDKETTE} is absent (../shared is not beside the project)")
    return {scale: pq.measure(pq.NORDKETTE, "auto", scale) for scale in SCALES}


@pytest.mark.parametrize("scale", SCALES)
def test_no_stroke_end_draws_the_rock_border(measures, scale):
    m = measures[scale]
    # Goals: at most 0.40 of the outer border with a stroke end within 0.3 mm (0.75 with
    # strokes cut by the border), at most 3 % of the ends within 0.1 mm of it.
    assert m["border with an end"] <= 0.40, m
    assert m["ends on the border"] <= 0.03, m


@pytest.mark.parametrize("scale", SCALES)
def test_the_dem_crests_and_cliff_tops_are_drawn(measures, scale):
    m = measures[scale]
    assert m["crests drawn"] >= 0.60, m
    assert m["cliff tops drawn"] >= 0.50, m
    # Every kind of structure line is there: crests, couloirs, cliff tops.
    for kind in ("crest", "couloir", "cliff"):
        assert m[f"{kind} km/km2"] > 0.5, (kind, m)


@pytest.mark.parametrize("scale", SCALES)
def test_the_tone_follows_the_shade_under_the_ceiling_along_the_fall_line(measures, scale):
    m = measures[scale]
    assert m["ink vs shade"] >= 0.8, m
    assert m["ink max"] <= 0.45, m
    assert m["fall-line angle"] <= 15, m
    assert m["axis share"] < 0.10, m  # no raster steps in the borders
    assert m["specks"] == 0 and m["small holes"] == 0, m


def test_the_rock_edge_steps_more_than_the_smooth_edge(measures):
    # The slope across the outer border (0.5 mm inside less 0.5 mm outside): the edge on the
    # breaks of slope (12.4 points) against the 25 m means' smooth edge (7.6).
    smooth = pq.measure(pq.NORDKETTE, "auto", 10000, extract={"terrain_edge": False})
    assert measures[10000]["edge step"] >= smooth["edge step"] + 3, (measures[10000]["edge step"], smooth["edge step"])
