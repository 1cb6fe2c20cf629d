#!/usr/bin/env python3
"""How the drawing reads in print: the measures of issue 16, on the sample and on
../shared/data/montblanc/Chamonix.tif, at several scales.

    /usr/bin/python3 bench/print_quality.py [--markdown FILE] [--scales 10000,25000,50000]

Per case and scale:
  - axis share: the share of face-border length running exactly along a grid axis of the
    working CRS (stair steps of a raster trace; hand-drawn borders have almost none);
  - ink per face: stroke area (length x stroke width on the ground, overlaps counted twice)
    over face area, for faces of at least 25 mm2 on paper: 95th percentile and maximum;
  - ink vs shade: Spearman rank correlation, over 100 m blocks mostly in rock, of the ink
    per rock area with 1 - hillshade;
  - fall-line angle: median angle between fill strokes and the terrain's fall line there;
  - specks / holes: faces, and holes of faces, smaller than the extraction's minimum area
    (16 mm2 on paper);
  - drawn outline: the share of the outer rock border (face borders with no face across and
    no ridge or valley on them, sampled every 0.5 mm on paper) with a fill or cross stroke
    end within 0.3 mm, and the share of fill and cross stroke ends within 0.1 mm of it.

  - edge on the terrain (issue 46): the median, over the outer-border samples, of the slope
    0.5 mm on paper inside the rock less the slope 0.5 mm outside it, across the border, on
    the DEM smoothed over 0.25 mm: a mask whose edge lies on the breaks of slope (a cliff's
    foot or top) has a sharp step there, one drawn by a smoothed threshold a gentle one.

  - structure (issue 46): length of structure lines per km2 of rock by kind (crest lines:
    the ridgeline family, or the ridge lines of the partition drawn by the ridge family;
    couloirs; cliff tops), and the share of the DEM's crests and cliff tops, found by this
    script's own detection (stricter than the style's: see crest_cells and cliff_top_cells),
    with a structure stroke (ridge, ridgeline, cliff, couloir or valley family) within 1 mm
    on paper.

--style names the style (default: the default style).
"""
import argparse
import math
import pathlib
import sys

import numpy as np
from scipy.ndimage import gaussian_filter, map_coordinates
from scipy.spatial import cKDTree

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "build" / "python"))

from rockhatch import carto  # noqa: E402
from rockhatch.tex import Point  # noqa: E402

SAMPLE = ROOT / "data" / "sample_montblanc"
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
NORDKETTE = ROOT.parent / "shared" / "data" / "nordkette" / "nordkette_5m.tif"
BORDER_STEP_MM = 0.5
END_NEAR_BORDER_MM = 0.3
END_ON_BORDER_MM = 0.1
MIN_FACE_MM2 = 25.0
SPECK_MM2 = 16.0
BLOCK_M = 100.0


def ring_area(points):
    xs = np.array([p.x for p in points])
    ys = np.array([p.y for p in points])
    return 0.5 * abs(np.dot(xs, np.roll(ys, -1)) - np.dot(ys, np.roll(xs, -1)))


def axis_share(partition):
    along = total = 0.0
    for face in partition.faces:
        for s in face.boundary:
            length = math.hypot(s.b.x - s.a.x, s.b.y - s.a.y)
            total += length
            if abs(s.b.x - s.a.x) < 1e-6 or abs(s.b.y - s.a.y) < 1e-6:
                along += length
    return along / total if total else float("nan")


def stroke_segments(hatches):
    for h in hatches:
        pts = list(h.points) + ([h.points[0]] if h.closed else [])
        for a, b in zip(pts, pts[1:]):
            yield h.family, a, b


def spearman(x, y):
    rx = np.argsort(np.argsort(x))
    ry = np.argsort(np.argsort(y))
    return float(np.corrcoef(rx, ry)[0, 1])


def outer_border_samples(partition, mm):
    """(face, x, y, segment) every BORDER_STEP_MM on paper along the outer rock border: face
    borders with no face across and no ridge or valley on them."""
    for face in partition.faces:
        for s in face.boundary:
            if s.neighbor >= 0 or s.kind != carto.LineKind.OTHER:
                continue
            length = math.hypot(s.b.x - s.a.x, s.b.y - s.a.y)
            n = max(1, int(length / (BORDER_STEP_MM * mm)))
            for k in range(n):
                t = (k + 0.5) / n
                yield face, s.a.x + (s.b.x - s.a.x) * t, s.a.y + (s.b.y - s.a.y) * t, s


def outline_measures(partition, drawing, scale):
    """(share of outer-border samples with a stroke end within 0.3 mm, share of stroke ends
    within 0.1 mm of the outer border)."""
    mm = scale / 1000.0
    samples = [(x, y) for _, x, y, _ in outer_border_samples(partition, mm)]
    ends = []
    for fh in drawing.faces:
        for h in fh.hatches:
            if h.closed or len(h.points) < 2 or h.family not in (carto.Family.FILL, carto.Family.CROSS):
                continue
            ends.append((h.points[0].x, h.points[0].y))
            ends.append((h.points[len(h.points) - 1].x, h.points[len(h.points) - 1].y))
    if not samples or not ends:
        return float("nan"), float("nan")
    samples, ends = np.array(samples), np.array(ends)
    near = cKDTree(ends).query(samples, distance_upper_bound=END_NEAR_BORDER_MM * mm)[0]
    border_share = float(np.mean(np.isfinite(near)))
    # Distance from each end to the outer border, by the border's dense samples (0.5 mm apart:
    # an end within 0.1 mm of a segment lies within 0.26 mm of a sample).
    d = cKDTree(samples).query(ends, distance_upper_bound=0.3 * mm)[0]
    close = np.isfinite(d)
    on = 0
    if close.any():
        on = int(np.sum(d[close] <= math.hypot(END_ON_BORDER_MM, BORDER_STEP_MM / 2) * mm))
    return border_share, on / len(ends)


def edge_contrast(terrain, partition, scale):
    """Median over outer-border samples of slope(0.5 mm inside) - slope(0.5 mm outside), in
    percentage points (see the module's text), and the number of samples."""
    mm = scale / 1000.0
    gt = terrain.elevation.geotransform
    cell = abs(gt[1])
    z, _ = smoothed_dem(terrain, max(0.5, 0.25 * mm / cell))
    gy, gx = np.gradient(z, cell)
    slope = 100.0 * np.hypot(gx, gy)
    diffs = []
    off = 0.5 * mm
    for face, x, y, s in outer_border_samples(partition, mm):
        dx, dy = s.b.x - s.a.x, s.b.y - s.a.y
        length = math.hypot(dx, dy)
        if length == 0:
            continue
        nx, ny = -dy / length, dx / length
        p1, p2 = (x + nx * off, y + ny * off), (x - nx * off, y - ny * off)
        if not face.region.contains(Point(*p1)):
            p1, p2 = p2, p1
        vals = []
        for px, py in (p1, p2):
            col, row = (px - gt[0]) / gt[1] - 0.5, (py - gt[3]) / gt[5] - 0.5
            vals.append(float(map_coordinates(slope, [[row], [col]], order=1, mode="nearest")[0]))
        if all(math.isfinite(v) for v in vals):
            diffs.append(vals[0] - vals[1])
    return (float(np.median(diffs)) if diffs else float("nan")), len(diffs)


STRUCTURE_NEAR_MM = 1.0
STRUCTURE_FAMILIES = ("RIDGE", "RIDGELINE", "CLIFF", "COULOIR", "VALLEY")


def smoothed_dem(terrain, sigma_cells):
    """The DEM (NaN = NoData) smoothed by a Gaussian, NoData-aware, and the valid mask."""
    z = np.array(terrain.elevation.array, dtype=float)
    valid = np.isfinite(z)
    w = gaussian_filter(valid.astype(float), sigma_cells)
    s = gaussian_filter(np.where(valid, z, 0.0), sigma_cells) / np.maximum(w, 1e-9)
    return np.where(valid, s, np.nan), valid


def sample_at(a, rows, cols):
    return map_coordinates(a, [rows, cols], order=1, mode="nearest", cval=np.nan)


def crest_cells(z, cell, mm):
    """Cells on a sharp crest: higher than the ground 1 mm on paper away on both sides along one
    of the four axes (E-W, N-S, the diagonals), the ground falling at least 35% on each side
    over that distance (the style draws a crease from a 12% fall each side)."""
    d = mm / cell
    rows, cols = np.mgrid[0:z.shape[0], 0:z.shape[1]].astype(float)
    crest = np.zeros(z.shape, bool)
    for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
        n = math.hypot(dr, dc)
        r1, c1 = rows + dr * d / n, cols + dc * d / n
        r2, c2 = rows - dr * d / n, cols - dc * d / n
        a, b = sample_at(z, r1, c1), sample_at(z, r2, c2)
        drop = 0.35 * mm
        crest |= (z - a >= drop) & (z - b >= drop)
    return crest


def cliff_top_cells(z, cell, mm):
    """Cells at a cliff's top: the ground 0.5 mm on paper down the fall line falls at 120% or
    more (the style's cliff_slope is 100%), and 0.5 mm up it at under 70%: a break of slope
    into a steep band."""
    gy, gx = np.gradient(z, cell)
    slope = np.hypot(gx, gy)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = -gx / slope, -gy / slope  # downhill, in array axes (col, row)
    d = 0.5 * mm / cell
    rows, cols = np.mgrid[0:z.shape[0], 0:z.shape[1]].astype(float)
    below = sample_at(slope, rows + uy * d, cols + ux * d)
    above = sample_at(slope, rows - uy * d, cols - ux * d)
    return (below >= 1.2) & (above < 0.7)


def structure_measures(terrain, partition, drawing, scale):
    mm = scale / 1000.0
    gt = terrain.elevation.geotransform
    cell = abs(gt[1])
    z, valid = smoothed_dem(terrain, max(1.0, 0.5 * mm / cell))
    rows, cols = np.mgrid[0:z.shape[0], 0:z.shape[1]]
    xs, ys = gt[0] + (cols + 0.5) * gt[1], gt[3] + (rows + 0.5) * gt[5]
    # Rock cells: inside a face.
    rock = np.zeros(z.shape, bool)
    for face in partition.faces:
        box = face.region.bbox()
        sel = np.nonzero((xs >= box.xmin) & (xs <= box.xmax) & (ys >= box.ymin) & (ys <= box.ymax) & valid)
        for r, c in zip(*sel):
            if not rock[r, c] and face.region.contains(Point(float(xs[r, c]), float(ys[r, c]))):
                rock[r, c] = True
    rock_km2 = rock.sum() * cell * cell / 1e6
    lengths = {"crest": 0.0, "couloir": 0.0, "cliff": 0.0}
    fam_kind = {carto.Family.RIDGELINE: "crest", carto.Family.COULOIR: "couloir", carto.Family.CLIFF: "cliff"}
    has_ridgeline = any(h.family == carto.Family.RIDGELINE for fh in drawing.faces for h in fh.hatches)
    structure = [getattr(carto.Family, n) for n in STRUCTURE_FAMILIES]
    pts = []
    for fh in drawing.faces:
        for fam, a, b in stroke_segments(fh.hatches):
            if fam not in structure:
                continue
            length = math.hypot(b.x - a.x, b.y - a.y)
            n = max(1, int(length / (0.25 * mm)))
            for k in range(n + 1):
                pts.append((a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n))
            if fam in fam_kind:
                lengths[fam_kind[fam]] += length
    if not has_ridgeline:
        # A style without the ridgeline family draws the partition's ridges as ridge strokes.
        for face in partition.faces:
            for s in face.boundary:
                if s.kind == carto.LineKind.RIDGE:
                    lengths["crest"] += math.hypot(s.b.x - s.a.x, s.b.y - s.a.y) / (2 if s.neighbor >= 0 else 1)
    out = {f"{k} km/km2": (v / 1000.0) / rock_km2 if rock_km2 else float("nan") for k, v in lengths.items()}
    tree = cKDTree(np.array(pts)) if pts else None
    for name, cells in (("crests", crest_cells(z, cell, mm)), ("cliff tops", cliff_top_cells(z, cell, mm))):
        sel = cells & rock
        if not sel.any() or tree is None:
            out[f"{name} drawn"] = float("nan")
            out[f"{name} cells"] = int(sel.sum())
            continue
        q = np.column_stack([xs[sel], ys[sel]])
        d = tree.query(q, distance_upper_bound=STRUCTURE_NEAR_MM * mm)[0]
        out[f"{name} drawn"] = float(np.mean(np.isfinite(d)))
        out[f"{name} cells"] = int(sel.sum())
    return out


def measure(dem, partition, scale, style=None, params=None, seed=0, extract=None):
    if partition == "auto" and extract:
        # The extraction with non-default options, through a partition file (the faces'
        # controls are derived from the terrain as with "auto").
        import shutil
        import tempfile
        tmp = pathlib.Path(tempfile.mkdtemp(prefix="print_quality_"))
        try:
            carto.partition_from_dem(dem, tmp / "partition.gpkg", scale=scale, **extract)
            prepared = carto.prepare(dem, tmp / "partition.gpkg", scale=scale)
        finally:
            shutil.rmtree(tmp)
    else:
        prepared = carto.prepare(dem, partition, scale=scale)
    drawing = carto.hatch(prepared, scale=scale, style=style, params=params or {}, seed=seed)
    terrain = prepared.terrain
    faces = {f.id: f for f in prepared.partition.faces}
    ground_m2_per_mm2 = (scale / 1000.0) ** 2
    width = {fam: carto.family_width_mm(fam) * scale / 1000.0 for fam in carto.Family.__members__.values()}

    # Ink per face, and ink per 100 m block.
    coverage = []
    block_ink = {}
    angles = []
    for fh in drawing.faces:
        face = faces[fh.face_id]
        area = face.region.area()
        ink = 0.0
        for fam, a, b in stroke_segments(fh.hatches):
            length = math.hypot(b.x - a.x, b.y - a.y)
            ink += length * width[fam]
            mx, my = (a.x + b.x) / 2, (a.y + b.y) / 2
            key = (math.floor(mx / BLOCK_M), math.floor(my / BLOCK_M))
            block_ink[key] = block_ink.get(key, 0.0) + length * width[fam]
        if area >= MIN_FACE_MM2 * ground_m2_per_mm2:
            coverage.append(ink / area)

    # Fall-line angles of fill strokes.
    for fh in drawing.faces:
        for fam, a, b in stroke_segments(fh.hatches):
            if fam != carto.Family.FILL:
                continue
            dx, dy = b.x - a.x, b.y - a.y
            if dx == 0 and dy == 0:
                continue
            m = Point((a.x + b.x) / 2, (a.y + b.y) / 2)
            down = terrain.aspect.sample(m)
            if math.isnan(down):
                continue
            e = abs(math.atan2(dy, dx) - down) % math.pi
            angles.append(math.degrees(min(e, math.pi - e)))

    # Rock share and shade of each block, on a 10 m lattice of sample points.
    step = 10.0
    rock = {}
    shade = {}
    for face in prepared.partition.faces:
        box = face.region.bbox()
        xs = np.arange(math.floor(box.xmin / step) * step + step / 2, box.xmax, step)
        ys = np.arange(math.floor(box.ymin / step) * step + step / 2, box.ymax, step)
        for x in xs:
            for y in ys:
                p = Point(float(x), float(y))
                if not face.region.contains(p):
                    continue
                key = (math.floor(x / BLOCK_M), math.floor(y / BLOCK_M))
                h = terrain.hillshade.sample(p)
                if math.isnan(h):
                    continue
                rock[key] = rock.get(key, 0) + 1
                shade[key] = shade.get(key, 0.0) + (1 - h)
    full = (BLOCK_M / step) ** 2
    keys = [k for k, n in rock.items() if n >= 0.5 * full]
    ink_density = [block_ink.get(k, 0.0) / (rock[k] * step * step) for k in keys]
    darkness = [shade[k] / rock[k] for k in keys]
    rho = spearman(np.array(ink_density), np.array(darkness)) if len(keys) > 3 else float("nan")

    speck = SPECK_MM2 * ground_m2_per_mm2
    specks = sum(1 for f in prepared.partition.faces if f.region.area() < speck)
    holes = sum(1 for f in prepared.partition.faces for h in f.region.holes if ring_area(h) < speck)
    cov = np.array(coverage) if coverage else np.array([float("nan")])
    border_share, ends_on = outline_measures(prepared.partition, drawing, scale)
    contrast, _ = edge_contrast(terrain, prepared.partition, scale)
    structure = structure_measures(terrain, prepared.partition, drawing, scale)
    return {
        "faces": len(prepared.partition.faces),
        "axis share": axis_share(prepared.partition),
        "ink p95": float(np.percentile(cov, 95)),
        "ink max": float(cov.max()),
        "ink vs shade": rho,
        "blocks": len(keys),
        "fall-line angle": float(np.median(angles)) if angles else float("nan"),
        "specks": specks,
        "small holes": holes,
        "border with an end": border_share,
        "ends on the border": ends_on,
        "edge step": contrast,
        **structure,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--markdown", type=pathlib.Path)
    ap.add_argument("--scales", default="10000,25000,50000")
    ap.add_argument("--style", default=None)
    ap.add_argument("--cases", default="", help="only the cases whose label contains this text")
    ap.add_argument("--seed", type=int, default=0, help="the drawing's seed (the measures' spread over seeds)")
    ap.add_argument("--param", action="append", default=[], metavar="KEY=VALUE",
                    help="a style parameter, as the command's --param (repeatable)")
    ap.add_argument("--extract", action="append", default=[], metavar="KEY=VALUE",
                    help="an option of the --partition auto extraction, as partition_from_dem's keywords "
                         "(terrain_edge=0; repeatable)")
    args = ap.parse_args()
    extract = {}
    for kv in args.extract:
        key, sep, value = kv.partition("=")
        if not sep:
            ap.error(f"--extract {kv}: expected KEY=VALUE")
        extract[key] = bool(int(value)) if key in ("terrain_edge", "extend_ridges", "label_outline") else float(value)
    params = {}
    for kv in args.param:
        key, sep, value = kv.partition("=")
        if not sep:
            ap.error(f"--param {kv}: expected KEY=VALUE")
        params[key] = float(value)
    scales = [float(s) for s in args.scales.split(",")]
    cases = [("sample, hand-drawn partition", SAMPLE / "dem.tif", SAMPLE / "partition.gpkg"),
             ("sample, --partition auto", SAMPLE / "dem.tif", "auto")]
    if SHARED_DEM.exists():
        cases.append(("Chamonix.tif, --partition auto", SHARED_DEM, "auto"))
    else:
        print(f"print_quality: {SHARED_DEM} absent, Chamonix rows skipped")
    if NORDKETTE.exists():
        cases.append(("Nordkette 5 m, --partition auto", NORDKETTE, "auto"))
    else:
        print(f"print_quality: {NORDKETTE} absent, Nordkette rows skipped")
    rows = []
    cases = [c for c in cases if args.cases in c[0]]
    for label, dem, partition in cases:
        for scale in scales:
            m = measure(dem, partition, scale, args.style, params, args.seed, extract)
            rows.append((label, scale, m))
            print(f"{label:34s} 1:{scale:<6.0f} " + ", ".join(
                f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in m.items()), flush=True)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write("<!-- written by bench/print_quality.py -->\n# How the drawing reads in print\n\n"
                    f"Measured by `/usr/bin/python3 bench/print_quality.py --markdown FILE"
                    f"{' --style ' + args.style if args.style else ''}` with the style "
                    f"{args.style or carto.default_style()} (the figures of the thesis's final design, "
                    "bidirectional, are in docs/print.md). Border along grid axes: share of face-border length running "
                    "exactly along an axis of the working CRS (raster stair steps). Ink: stroke length x stroke "
                    "width over face area, faces of 25 mm2 or more on paper. Ink vs shade: Spearman's rho over "
                    "100 m blocks at least half rock (number of blocks). Angle: median between fill strokes and "
                    "the fall line. Specks and small holes: faces and holes under 16 mm2 on paper. Goals of "
                    "issue 16: axis share under 10%, ink max under 45% at every scale, rho at least 0.8, "
                    "angle under 15 degrees, no specks or small holes. Drawn outline (issue 46): share of the "
                    "outer rock border (no face across, no ridge or valley on it; sampled every 0.5 mm on paper) "
                    "with a fill or cross stroke end within 0.3 mm (goal: at most 0.40), and share of those "
                    "strokes' ends within 0.1 mm of it (goal: at most 0.03). Slope step across it: median of the "
                    "slope 0.5 mm inside less the slope 0.5 mm outside, percentage points (an edge on the breaks "
                    "of slope steps more).\n\n")
            f.write("| case | scale | faces | border along grid axes | ink per face p95 | ink max | "
                    "ink vs 1-hillshade (rho, 100 m blocks) | median angle to fall line | specks | small holes | "
                    "outer border with an end within 0.3 mm | ends within 0.1 mm of it | slope step across it |\n")
            f.write("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
            for label, scale, m in rows:
                f.write(f"| {label} | 1:{scale:.0f} | {m['faces']} | {100 * m['axis share']:.0f}% | "
                        f"{100 * m['ink p95']:.0f}% | {100 * m['ink max']:.0f}% | {m['ink vs shade']:.2f} "
                        f"({m['blocks']}) | {m['fall-line angle']:.1f} deg | {m['specks']} | {m['small holes']} | "
                        f"{m['border with an end']:.2f} | {m['ends on the border']:.3f} | "
                        f"{m['edge step']:.1f} |\n")
        print(f"print_quality: written to {args.markdown}")


if __name__ == "__main__":
    main()
