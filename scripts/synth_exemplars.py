#!/usr/bin/python3
"""Draws the five synthesis exemplars that the tests and bench_synthesis --defaults try the
defaults of SynthesizeAlongCurve on (docs/synthesis.md, "Defaults on five exemplars"), into
libtex/examples/elements: synth_rungs, synth_bar_beads, synth_rings, synth_truss, synth_dots.

    /usr/bin/python3 scripts/synth_exemplars.py
"""
import math
import pathlib
ROOT = pathlib.Path(__file__).resolve().parents[1]
ELEMENTS = ROOT / "libtex" / "examples" / "elements"


def arc(cx, cy, r, a0, a1, n):
    """Points of a circle from angle a0 to a1 (n steps, both ends included)."""
    return [(cx + r * math.cos(a0 + (a1 - a0) * i / n), cy + r * math.sin(a0 + (a1 - a0) * i / n))
            for i in range(n + 1)]


def polygon(cx, cy, r, n=24):
    return arc(cx, cy, r, 0, 2 * math.pi, n)[:-1]


def rungs():
    """A ladder: two rails and nine evenly spaced rungs, eight holes, the rails' ends open."""
    w, rail, h, rung = 600, 8, 48, 10
    xs = [30 + i * 67.5 for i in range(9)]
    outer = [(0, 0), (w, 0), (w, rail), (xs[-1] + rung, rail), (xs[-1] + rung, h - rail), (w, h - rail), (w, h),
             (0, h), (0, h - rail), (xs[0], h - rail), (xs[0], rail), (0, rail)]
    holes = [[(a + rung, rail), (b, rail), (b, h - rail), (a + rung, h - rail)] for a, b in zip(xs, xs[1:])]
    return "a ladder: rails and nine evenly spaced rungs (eight holes)", [outer] + holes


def bar_beads():
    """Round beads resting on a thin bar, alternately above and below it: one component."""
    w, b, r, sink = 600, 2.0, 16.0, 5.0
    centres = [50 + i * 62.5 for i in range(9)]
    alpha = math.asin((r - sink) / r)  # the circle meets the bar's edge at angle -alpha (and pi + alpha)
    top, bottom = [(0, b)], [(0, -b)]
    for i, cx in enumerate(centres):
        side = top if i % 2 == 0 else bottom
        s = 1 if i % 2 == 0 else -1
        # Over the bead from its left foot to its right foot (angles pi + alpha down to -alpha).
        side.extend((x, s * y) for x, y in arc(cx, b + r - sink, r, math.pi + alpha, -alpha, 24))
    top.append((w, b))
    bottom.append((w, -b))
    return "beads on a bar, alternately above and below (no hole)", [bottom + top[::-1]]


def rings():
    """A chain of nine overlapping rings: one outline, nine holes."""
    big, d, small = 22.0, 38.0, 14.0
    centres = [big + i * d for i in range(9)]
    t = math.acos(0.5 * d / big)  # where neighbouring circles cross, seen from the left one's centre
    upper = []
    for i, cx in enumerate(centres):
        a0 = math.pi if i == 0 else math.pi - t
        a1 = 0 if i == len(centres) - 1 else t
        pts = arc(cx, 0, big, a0, a1, 20)
        upper.extend(pts if i == 0 else pts[1:])
    lower = [(x, -y) for x, y in upper[1:-1]]
    outer = upper + lower[::-1]
    return "a chain of nine overlapping rings (nine holes)", [outer] + [polygon(cx, 0, small) for cx in centres]


def truss():
    """A zig-zag between two rails (a Warren truss): triangular holes pointing up and down."""
    s, rail, h, e, f = 40.0, 6.0, 48.0, 8.0, 8.0
    w = 14 * s
    outer = [(0, 0), (w, 0), (w, h), (0, h)]
    holes = []
    for k in range(7):  # apex up, on the lower rail between nodes 2k and 2k + 2
        holes.append([(2 * k * s + e, rail), ((2 * k + 2) * s - e, rail), ((2 * k + 1) * s, h - rail - f)])
    for k in range(6):  # apex down, under the upper rail between nodes 2k + 1 and 2k + 3
        holes.append([((2 * k + 1) * s + e, h - rail), ((2 * k + 2) * s, rail + f), ((2 * k + 3) * s - e, h - rail)])
    return "a zig-zag band between two rails (a truss: thirteen triangular holes)", [outer] + holes


def dots():
    """Loose dots above a bar, beads hanging under it: six components."""
    w, bar, r, sink = 600, 6.0, 12.0, 4.0
    alpha = math.asin((r - sink) / r)
    bottom = [(0, 0)]
    for cx in (90 + i * 120.0 for i in range(5)):
        bottom.extend((x, -y) for x, y in arc(cx, r - sink, r, math.pi + alpha, -alpha, 24))
    bottom.append((w, 0))
    outer = bottom + [(w, bar), (0, bar)]
    return ("loose dots above a bar, beads under it (six components)",
            [outer] + [polygon(30 + i * 120.0, 22, 6, 16) for i in range(5)])


EXEMPLARS = {
    "synth_rungs": rungs,
    "synth_bar_beads": bar_beads,
    "synth_rings": rings,
    "synth_truss": truss,
    "synth_dots": dots,
}


def svg(title, rings_):
    xs = [x for r in rings_ for x, _ in r]
    ys = [y for r in rings_ for _, y in r]
    x0, x1, y0, y1 = min(xs) - 2, max(xs) + 2, min(ys) - 2, max(ys) + 2
    d = " ".join("M " + " L ".join(f"{x:.3f} {-y:.3f}" for x, y in r) + " Z" for r in rings_)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0:.3f} {-y1:.3f} {x1 - x0:.3f} {y1 - y0:.3f}">\n'
            f"<!-- rockhatch synthesis exemplar: {title} -->\n"
            f'<path fill-rule="evenodd" d="{d}"/>\n</svg>\n')


def main():
    for name, make in EXEMPLARS.items():
        title, rs = make()
        (ELEMENTS / f"{name}.svg").write_text(svg(title, rs))
        print("wrote", ELEMENTS / f"{name}.svg")


if __name__ == "__main__":
    main()
