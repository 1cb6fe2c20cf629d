"""Building blocks shared by the style scripts: the Python side of carto/src/styles/blocks.cpp.

Not a style: the scripts of this folder import it (its name starts with an underscore).
Each block is a small program of libtex operators in the thesis's App. E idiom. The
hatch lines are never looped over here: partitions make them, the native JitterEdges
mapper moves them, Crop cuts them to the face; the Python mappers visit coarse cells and
the vertices of a few stripes, and loop only over the edges of one cell. Every block
calls the operators, and draws the random values (Random(cell, lo, hi, n)), the C++
block of the same name does, so a script draws what the built-in style draws, bit for bit.
"""
from math import cos, isnan, sin

from rockhatch.carto import Family, area_within, family_width_mm, ink_area, interior_point
from rockhatch.tex import (CROP, CROP_ADD_BOUNDARY, KEEP_OUTSIDE, AlignToField, Arrangement, Centroid, Crop, Fallback,
                           Field, GridPartition, HasLabel, IncidentEdges, JitterEdges, Labelled, LeftFace, Location,
                           LocationAt, MapAlong, MapToEdges, MapToFaces, MapToVertices, Nothing, Outline, Point,
                           Polyline, Random, Region, RightFace, Scale, SetEdgeLabels, Smoothed, StripesPartition,
                           StripesProperties, ThinRank, ToCurve, ToRegion, distance, dot, pi)

# ---- Parameters (defaults follow App. E at 1:10000) ----

def fill_params(length, jitter):
    """The parameters of the fill hatching, shared by every iteration."""
    return [
        ("spacing_min", 0.35, "mm", "hatch spacing in the darkest faces"),
        ("spacing_max", 1.5, "mm", "hatch spacing in the lightest faces"),
        ("length", length, "mm", "length of a hatch between two jittered break points"),
        ("jitter", jitter, "ratio", "jitter of the break points, as a fraction of spacing and length"),
        ("contrast", 1.0, "ratio", "how much height pushes dark faces darker and light faces lighter"),
        ("slope_min", 0.0, "%", "no fill hatch where the slope is below this (percent; 0: everywhere)"),
    ]


TRIANGLES = [
    ("ridge_spacing", 3.0, "mm", "spacing of the triangle grid along the ridges"),
    ("ridge_length", 1.5, "mm", "side of the triangles falling from the ridges"),
]
COARSE = [
    ("cell_spacing", 3.0, "mm", "width of the coarse jittered cells that carry local density"),
    ("cell_jitter", 1.0, "ratio", "jitter of the coarse cells"),
]
# print's tone cells: COARSE's parameters, 2 mm wide.
TONE_CELLS = [
    ("cell_spacing", 2.0, "mm", "width of the coarse jittered cells that carry local tone"),
    COARSE[1],  # cell_jitter
]
PEAKS = [
    ("peak_spacing", 2.0, "mm", "distance between two ridge shapes"),
    ("peak_length", 2.0, "mm", "length of a ridge shape down the slope"),
    ("peak_width", 0.8, "mm", "width of a ridge shape at its base"),
    ("peak_fill", 0.2, "mm", "spacing of the fine hatching inside ridge shapes"),
]
BALANCED = [
    ("gap", 0.95, "ratio", "each hatch is shortened to this fraction, leaving gaps between strokes"),
]
HIGH = [
    ("peak_height_gain", 1.0, "ratio", "ridge shapes grow by this fraction on the highest ground"),
]
TONE = [
    ("length", 1.5, "mm", "length of a hatch between two jittered break points"),
    ("jitter", 0.5, "ratio", "jitter of the break points, as a fraction of spacing and length"),
    ("slope_min", 0.0, "%", "no fill hatch where the slope is below this (percent; 0: everywhere)"),
    ("tone_min", 0.05, "ratio", "ink coverage of fill and cross strokes on fully lit ground"),
    ("tone_max", 0.36, "ratio", "ink coverage of fill and cross strokes in full shade"),
    ("tone_gamma", 1.0, "ratio", "exponent of the tone curve (above 1: mid-tones lighter)"),
    ("ink_max", 0.40, "ratio", "ceiling of the ink coverage of every cell, crests and valleys included"),
    ("min_gap", 0.15, "mm", "least white paper between two neighbouring fill strokes"),
    ("follow_fall_line", 1.0, "ratio", "1: strokes follow the local fall line; 0: one direction per face"),
]
CREST = [
    ("crest_spacing", 0.4, "mm", "distance between two shadow-side strokes along a crest line"),
    ("crest_length", 0.8, "mm", "longest shadow-side stroke on low ground"),
    ("crest_height_gain", 0.5, "ratio", "shadow-side strokes grow by this fraction on the highest ground"),
    ("crest_smoothing", 0.8, "mm", "crest lines are drawn smooth at this length (shorter bends and steps go)"),
]
CROSS = [
    ("roughness_min", 0.01, "ratio", "roughness (0..1) below which no cross hatching is drawn"),
    ("roughness_max", 0.08, "ratio", "roughness at which cross hatching is densest"),
    ("cross_spacing_min", 0.6, "mm", "cross hatch spacing at the highest roughness"),
    ("cross_spacing_max", 2.5, "mm", "cross hatch spacing at the lowest roughness"),
    ("cross_angle", 90.0, "deg", "angle between fill and cross hatches"),
]


# ---- Small helpers ----

def clamp01(v):
    return min(max(v, 0.0), 1.0)


def unit(angle):
    return Point(cos(angle), sin(angle))


def stripes(angle, width, label=""):
    """StripesProperties(angle, width), its lines labelled `label` when given."""
    s = StripesProperties(angle, width)
    if label:
        SetEdgeLabels(s, label)
    return s


# ---- What a style reads about its face ----

class FaceReading:
    """The orientation and density at a point inside the face, the highest relief on its
    outer ring (defaults where the fields have no value)."""
    __slots__ = ("theta", "density", "height")

    def __init__(self, theta=0.0, density=0.5, height=0.5):
        self.theta, self.density, self.height = theta, density, height


def read_face(f, region):
    out = FaceReading()
    inside = interior_point(region)
    t, d = f.orientation(inside), f.density(inside)
    if not isnan(t):
        out.theta = t
    if not isnan(d):
        out.density = d
    # The highest relief on the face's outer ring (App. E `highest_height`).
    height, h = f.height, -1e300
    for q in region.outer:
        v = height(q)
        if not isnan(v):
            h = max(h, v)
    if h > -1e300:
        out.height = clamp01(h)
    return out


def spacing_for(p, density, height, linear):
    """Hatch spacing from density and height (App. E `stripes_cycle`); `linear` from (e) on,
    where height acts linearly instead of squared."""
    h = height if linear else height * height
    d = clamp01(0.5 + (density - 0.5) * (1 + p["contrast"] * h))
    return p["spacing_min"] + (p["spacing_max"] - p["spacing_min"]) * (1 - d)


# ---- Arrangements ----

def noisy_lines(label, theta, spacing, length, r, gap=1.0, slope=None, slope_min=0.0):
    """One axis of a jittered grid: lines labelled `label` every `spacing` at theta, broken
    every `length`, jittered by r (App. E "noisy hatching"); no hatch where the slope is
    below slope_min (when > 0)."""
    return MapToEdges(JitterEdges(label, theta, spacing, length, r, gap, slope, slope_min),
                      GridPartition(stripes(theta, spacing, label), stripes(theta + pi / 2, length), KEEP_OUTSIDE))


def cell_hatching(f, p, face, linear, gap):
    """Coarse jittered cells, each hatched with the spacing of the relief at its centre
    (App. E "multiscale density variations")."""
    cs, length, theta = p["cell_spacing"], p["length"], face.theta
    grid = MapToEdges(JitterEdges("grid", theta, cs, cs, 0.5 * p["cell_jitter"]),
                      GridPartition(stripes(theta, cs, "grid"), stripes(theta + pi / 2, cs, "grid"), KEEP_OUTSIDE))
    height, slope, jitter, slope_min = f.height, f.slope, p["jitter"], p["slope_min"]

    def hatch_cell(cell):
        h = height(Centroid(cell))
        if isnan(h):
            h = face.height
        s = spacing_for(p, face.density, h, linear)
        # The noisy lines of the cell's spacing, cut to the cell: lines of equal spacing
        # run on across cells.
        return Crop(noisy_lines("fill", theta, s, length, jitter, gap, slope, slope_min), CROP)(cell)

    return MapToFaces(hatch_cell, grid)


def darker_across(f, face, e, cell):
    """Whether the face is the darker side of the ridge edge e of a cell inside it: the
    density just across e (NaN: no face there) against the face's own."""
    a, b, mid = LocationAt(e, 0.49), LocationAt(e, 0.51), LocationAt(e, 0.5)
    l = distance(a, b)
    if l == 0:
        return False
    ab = b - a
    out = Point(ab.y / l, -ab.x / l)  # right of the edge
    if RightFace(e) == cell:
        out = -out
    eps = min(0.5, 2.5 * l)  # 2.5 l: 5 % of the edge's length
    other = f.density(mid + out * eps)
    return face.density >= 0.5 if isnan(other) else face.density > other


def ridge_triangles(f, p, face):
    """(b) Triangles falling from the ridges into the darker face: cells of a grid at theta
    and theta + 45 degrees cut by the face, kept when they touch a ridge on its darker side."""
    def keep_ridge(cell):
        for e in IncidentEdges(cell):
            if HasLabel(e, "ridge") and darker_across(f, face, e, cell):
                return Labelled(Scale(Polyline(ToRegion(cell).outer, True), 0.98), "ridge")  # one closed stroke
        return Nothing()

    return MapToFaces(keep_ridge, GridPartition(stripes(face.theta, p["ridge_spacing"]),
                                                stripes(face.theta + pi / 4, p["ridge_length"]), CROP_ADD_BOUNDARY))


def ridge_foot(f, face, v):
    """Whether the vertex v lies on a ridge on the darker side of it, and the edge that
    leaves it into the face (None when there is none): where ridge shapes and crest
    strokes hang from."""
    dark, into = False, None
    for e in IncidentEdges(v):
        if HasLabel(e, "ridge"):
            if not dark:
                left = LeftFace(e)
                dark = darker_across(f, face, e, left if left.is_bounded_face() else RightFace(e))
        elif not HasLabel(e, "valley") and not HasLabel(e, "other"):
            into = e
    return dark, into


def ridge_peaks(f, p, face, gain):
    """(d) Ridge shapes: triangles hanging from the dark ridges where stripes at theta meet
    them, filled with sub-scale hatching; `gain` grows them on high ground (f)."""
    height, theta = f.height, face.theta
    d = unit(theta)
    n = Point(-d.y, d.x)
    fill = stripes(theta, p["peak_fill"])

    def shape(v):
        dark, into = ridge_foot(f, face, v)
        if not dark or into is None:
            return Nothing()
        apex = Location(v)
        # Down the slope: along the stripe that leaves the ridge into the face.
        down = d if dot(LocationAt(into, 0.5) - apex, d) >= 0 else -d
        h = height(apex)
        if isnan(h):
            h = face.height
        length = p["peak_length"] * (1 + gain * h) * Random(v, 0.7, 1.0, 4)
        half = p["peak_width"] / 2 * (1 + 0.5 * gain * h)
        tri = Region([apex, apex + down * length + n * half, apex + down * length - n * half], [], "ridge shape")
        return Labelled(StripesPartition(fill)(tri), "ridge")

    return MapToVertices(shape, StripesPartition(stripes(theta, p["peak_spacing"])))


# Stroke k hanging from a crest line has (SHORTEST_CREST_STROKE + (1 - SHORTEST_CREST_STROKE) x
# ThinRank(k)) of the longest length: the ink fades down the slope instead of ending in a comb.
SHORTEST_CREST_STROKE = 0.35
# Near a ridge's end the strokes shrink, to this fraction at the end, growing to full length
# (1 - this) x crest_length from it.
CREST_END_TAPER = 0.3
# A stroke leaves the crest line within 60 degrees of its normal (this cosine); where the fall line
# runs nearly along the crest (a spur falling away) the line is drawn alone.
CREST_STROKE_MIN_COS = 0.5


def crest_lines(p):
    """The crest line: each ridge on the face's border smooth at crest_smoothing (the same line
    from both faces), cut to the face: each face draws its part of it."""
    step = p["crest_smoothing"]

    def line(e):
        return Smoothed(ToCurve(e), step) if HasLabel(e, "ridge") else Nothing()

    return Crop(MapToEdges(line, Outline()), CROP)


def crest_strokes(f, p, face, region):
    """Shadow-side strokes: along each ridge of the face on its darker side, every crest_spacing
    along the crest line, one stroke into the face down the local fall line (read crest_length / 2
    inside the face), of golden-ratio lengths, shorter near the ridge's ends; the lit side gets none."""
    height, fall_line, density, theta = f.height, f.fall_line, f.density, face.theta
    follow = p["follow_fall_line"] > 0
    longest, spacing, gain, step = p["crest_length"], p["crest_spacing"], p["crest_height_gain"], p["crest_smoothing"]

    def strokes(e):
        if not HasLabel(e, "ridge"):
            return Nothing()
        # Which side of the ridge the face lies on, and whether it is the darker one.
        a, b, mid = LocationAt(e, 0.49), LocationAt(e, 0.51), LocationAt(e, 0.5)
        l = distance(a, b)
        if l == 0:
            return Nothing()
        ab = b - a
        left = Point(-ab.y / l, ab.x / l)
        eps = min(0.5, 2.5 * l)  # 2.5 l: 5 % of the edge's length
        side = 1.0 if region.contains(mid + left * eps) else -1.0
        other = density(mid - left * (side * eps))
        if not (face.density >= 0.5 if isnan(other) else face.density > other):
            return Nothing()

        def hang(foot, t, k, to_end):
            n = Point(-t.y, t.x) * side  # into the face
            # The fall line on the crest itself averages two opposite slopes: read it a little
            # down the face instead.
            angle = theta
            if follow:
                local = fall_line(foot + n * (0.5 * longest))
                if not isnan(local):
                    angle = local
            d = unit(angle)
            if dot(d, n) < 0:
                d = -d
            if dot(d, n) < CREST_STROKE_MIN_COS:
                return Nothing()
            h = height(foot)
            if isnan(h):
                h = face.height
            from_end = min((k + 0.5) * spacing, to_end)
            taper = min(1.0, CREST_END_TAPER + from_end / longest)
            length = (longest * (1 + gain * clamp01(h)) *
                      (SHORTEST_CREST_STROKE + (1 - SHORTEST_CREST_STROKE) * ThinRank(k)) * taper)
            return Labelled(Polyline([foot, foot + d * length]), "ridge")

        # The feet on the crest line as crest_lines draws it.
        return MapAlong(Smoothed(ToCurve(e), step), spacing, hang)

    return MapToEdges(strokes, Outline())


def tone_coverage(p, shade):
    """The tone curve: ink coverage of fill and cross strokes for a shade in 0..1."""
    return p["tone_min"] + (p["tone_max"] - p["tone_min"]) * clamp01(shade) ** p["tone_gamma"]


def toned_hatching(f, p, face, region, spent):
    """Coarse jittered cells, each hatched so that its ink follows the tone of the shade at its
    centre under ink_max, the ink `spent` (crests, valleys) has in the cell over the cell's
    area inside the face `region` included, with at least min_gap between fill strokes;
    strokes along the fall line when follow_fall_line > 0."""
    cs, theta0 = p["cell_spacing"], face.theta
    grid = MapToEdges(JitterEdges("grid", theta0, cs, cs, 0.5 * p["cell_jitter"]),
                      GridPartition(stripes(theta0, cs, "grid"), stripes(theta0 + pi / 2, cs, "grid"), KEEP_OUTSIDE))
    mm, gap, length, jitter = p["ground_per_mm"], p["gap"], p["length"], p["jitter"]
    shade_f, fall_line, roughness, slope = f.shade, f.fall_line, f.roughness, f.slope
    follow = p["follow_fall_line"] > 0
    r0 = p["roughness_min"]
    r1 = max(p["roughness_max"], r0 + 1e-9)
    s_min, s_max = p["cross_spacing_min"], p["cross_spacing_max"]
    wc = family_width_mm(Family.CROSS) * mm
    wf = family_width_mm(Family.FILL) * mm

    def hatch_cell(cell):
        box = ToRegion(cell)
        c = Centroid(cell)
        shade = shade_f(c)
        if isnan(shade):
            shade = face.density
        # The tone under the ceiling, less what the crests and valleys already put in this
        # cell (they run along the face's border, where cells reach out of the face: its part
        # counts): the cell's ink, lines included, follows the shade.
        area = area_within(region, box)
        used = ink_area(spent, mm, box) / area if area > 0 else 0.0
        target = min(tone_coverage(p, shade), p["ink_max"]) - used
        if not target > 0:
            return Nothing()
        theta = theta0
        if follow:
            local = fall_line(c)
            if not isnan(local):
                theta = local
        out = Nothing()
        cross_cover = 0
        rough = roughness(c)
        # Rough cells: cross strokes take up to half the cell's tone, denser when rougher;
        # none where that half is too little ink to space them within cross_spacing_max
        # (lone crosses on lit ground read as noise, not texture).
        s_cross = max(s_max - (s_max - s_min) * clamp01((rough - r0) / (r1 - r0)), wc * gap / (0.5 * target))
        if rough > r0 and s_cross <= s_max:
            s = s_cross
            cross_cover = wc * gap / s
            angle = theta + p["cross_angle"]
            out = MapToEdges(JitterEdges("cross", angle, s, length, 0.5, gap),
                             StripesPartition(stripes(angle, s, "cross"), CROP))(cell)
        # Fill strokes of width w every s cover w x gap / s of the cell; min_gap keeps white
        # paper between neighbours whatever the tone asks.
        s = max(wf * gap / (target - cross_cover), wf + p["min_gap"])
        lines = Crop(noisy_lines("fill", theta, s, length, jitter, gap, slope, p["slope_min"]), CROP)
        # Each stroke laid on the fall line at its middle (where the partition gave no
        # orientation), else on the cell's direction: the jitter of the break points moves
        # strokes, it does not tilt them (tilted, sparse strokes read as zigzags).
        out.append(AlignToField(lines, Fallback(fall_line, theta) if follow else Field(theta))(cell))
        return out

    return MapToFaces(hatch_cell, grid)


def _owned_valley(e):
    return ToCurve(e) if HasLabel(e, "valley") and HasLabel(e, "owned") else Nothing()


def valleys():
    """(f) The valleys the face owns (a valley between two faces is drawn once)."""
    return MapToEdges(_owned_valley, Outline())


def cross_hatching(f, p, face):
    """(g) Cross hatches in the coarse cells rough enough, denser when rougher."""
    cs, theta = p["cell_spacing"], face.theta
    angle = theta + p["cross_angle"]
    roughness, length, gap = f.roughness, p["length"], p["gap"]
    r0 = p["roughness_min"]
    r1 = max(p["roughness_max"], r0 + 1e-9)
    s_min, s_max = p["cross_spacing_min"], p["cross_spacing_max"]

    def hatch_cell(cell):
        rough = roughness(Centroid(cell))
        if not rough > r0:
            return Nothing()
        t = clamp01((rough - r0) / (r1 - r0))
        s = s_max - (s_max - s_min) * t
        return MapToEdges(JitterEdges("cross", angle, s, length, 0.5, gap),
                          StripesPartition(stripes(angle, s, "cross"), CROP))(cell)

    return MapToFaces(hatch_cell, GridPartition(stripes(theta, cs), stripes(theta + pi / 2, cs), KEEP_OUTSIDE))


# ---- Programs ----

def per_face(fields, params, body, with_valleys=False):
    """The arrangement a style draws in each face: body(fields, params, face) with the face
    read once, cut to the face; with `with_valleys`, the face's valleys (on its border)
    added uncut."""
    def draw(region):
        face = read_face(fields, region)
        out = Crop(body(fields, params, face), CROP)(region)
        if with_valleys:
            out.append(valleys()(region))
        return out

    return Arrangement(draw)
