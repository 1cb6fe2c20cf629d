#!/usr/bin/python3
"""Ridge triangles (thesis Fig. 5.4b): noisy hatching plus triangles falling from the
ridges into the darker face.

Design iteration (b), on top of (a) (noisy.py). A grid at the hatch direction and at 45
degrees from it is laid over the face; its cells cut by the face are drawn as closed
shapes when they touch a ridge on which the face is the darker side (the face across is
lighter: the thesis's must_provide_coulis).

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min    0.35 mm     hatch spacing in the darkest faces
    spacing_max    1.5  mm     hatch spacing in the lightest faces
    length         3.0  mm     length of a hatch between two jittered break points
    jitter         1.0  ratio  jitter of the break points (fraction of spacing and length)
    contrast       1.0  ratio  how much height pushes dark faces darker, light faces lighter
    ridge_spacing  3.0  mm     spacing of the triangle grid along the ridges
    ridge_length   1.5  mm     side of the triangles falling from the ridges

    /usr/bin/python3 styles/ridge_triangles.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import math
import sys

from noisy import fill_face, fill_params
from rockhatch.carto import Family, Hatch, Hatches, LineKind, clip_polygon_convex, face_controls, scale_ring
from rockhatch.tex import Point, cos, cross, distance, dot, pi, signed_area, sin

NAME = "ridge-triangles"
FIGURE = "5.4b"
TITLE = "noisy hatching plus triangles falling from ridges into the darker face"

TRIANGLES = [
    ("ridge_spacing", 3.0, "mm", "spacing of the triangle grid along the ridges"),
    ("ridge_length", 1.5, "mm", "side of the triangles falling from the ridges"),
]
PARAMS = fill_params(3.0, 1.0) + TRIANGLES


def dark_ridges(boundary, c):
    """Indices of the ridge segments on which this face is the darker side."""
    out = []
    for i, seg in enumerate(boundary):
        if seg.kind != LineKind.RIDGE:
            continue
        other = c.neighbour_density(i)
        if (c.density >= 0.5) if math.isnan(other) else (c.density > other):
            out.append(i)
    return out


def touches(poly, segments):
    """True when an edge of the polygon lies on one of the segments (its middle within
    1e-6 x (1 + length) of the segment)."""
    pts = [(q.x, q.y) for q in poly]
    xs, ys = [x for x, _ in pts], [y for _, y in pts]
    n = len(pts)
    for seg in segments:
        ax, ay, bx, by = seg.a.x, seg.a.y, seg.b.x, seg.b.y
        ex, ey = bx - ax, by - ay
        l2 = ex * ex + ey * ey
        if l2 == 0:
            continue
        tol = 1e-6 * (1 + math.sqrt(l2))
        # Quick rejection: the polygon's box must reach the segment's box.
        if (min(xs) > max(ax, bx) + 2 * tol or max(xs) < min(ax, bx) - 2 * tol or min(ys) > max(ay, by) + 2 * tol
                or max(ys) < min(ay, by) - 2 * tol):
            continue
        for k in range(n):
            (px, py), (qx, qy) = pts[k], pts[(k + 1) % n]
            mx, my = (px + qx) / 2, (py + qy) / 2
            t = ((mx - ax) * ex + (my - ay) * ey) / l2
            if t < 0 or t > 1:
                continue
            if abs(ex * (my - ay) - ey * (mx - ax)) / math.sqrt(l2) < tol and distance(poly[k], poly[(k + 1) % n]) >= 1e-9:
                return True
    return False


def ridge_triangles(out, p, face, c):
    boundary = face.boundary
    ridges = [boundary[i] for i in dark_ridges(boundary, c)]
    if not ridges:
        return
    a1, a2 = c.orientation, c.orientation + pi / 4
    s1, s2 = p["ridge_spacing"], p["ridge_length"]
    n1, n2 = Point(-sin(a1), cos(a1)), Point(-sin(a2), cos(a2))
    det = cross(n1, n2)

    def vertex(i, j):
        a, b = float(i) * s1, float(j) * s2
        return Point((a * n2.y - b * n1.y) / det, (n1.x * b - n2.x * a) / det)

    # The grid cells along the dark ridges (and their neighbours).
    cells = set()
    for seg in ridges:
        steps = max(1, int(math.ceil(distance(seg.a, seg.b) / (0.25 * min(s1, s2)))))
        for k in range(steps + 1):
            q = seg.a + (seg.b - seg.a) * (k / steps)
            i, j = math.floor(dot(q, n1) / s1), math.floor(dot(q, n2) / s2)
            cells.update((i + di, j + dj) for di in (-1, 0, 1) for dj in (-1, 0, 1))
    outer = face.region.outer
    for i, j in sorted(cells):
        cell = [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)]
        if signed_area(cell) < 0:
            cell.reverse()
        piece = clip_polygon_convex(outer, cell)
        if len(piece) < 3 or abs(signed_area(piece)) < 1e-9 or not touches(piece, ridges):
            continue
        # Drawn slightly shrunk so that neighbours stay apart; the cell is shrunk before the
        # cut, so the shape stays inside the face.
        shape = clip_polygon_convex(outer, scale_ring(cell, 0.98))
        if len(shape) >= 3 and abs(signed_area(shape)) >= 1e-9:
            out.append(Hatch(shape, True, Family.RIDGE))


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_face(out, params, face, c, seed)
        ridge_triangles(out, params, face, c)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
