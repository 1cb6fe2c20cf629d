#!/usr/bin/python3
"""Draws the whole-run times of the style programs against issue 11's speed budget, from
the styles section bench/bench_carto.py wrote into docs/benchmarks-carto.md: one group of
bars per case (Chamonix.tif with --partition auto, each style and output), one bar per
column of the table (this build, then each baseline), and the budget as a dashed line.

    bench/plot_style_budget.py docs/benchmarks-carto.md -o style-budget.svg [--note TEXT]
"""
import argparse
import pathlib
import re

# Issue 11: at most 1.5 times the whole-run times measured before the style rewrite
# (bidirectional, 2 threads, 1:10000): 8.7 s to GeoPackage, 3.4 s to SVG alone.
BUDGET = {("bidirectional", "gpkg"): 1.5 * 8.7, ("bidirectional", "svg"): 1.5 * 3.4}
COLOURS = ["#1f4e79", "#9aa5b1", "#c9d1d9"]


def read_rows(markdown):
    """Column titles and the Chamonix.tif rows of the styles table: (style, output, [s or None])."""
    text = markdown.read_text()
    section = text[text.index("### Style programs"):]
    header = next(line for line in section.splitlines() if line.startswith("| case | style |"))
    titles = ["this build"] + [c.strip() for c in header.strip("|").split("|")][4:-1]
    rows = []
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) < 5 or not cells[0].startswith("Chamonix"):
            continue
        times = [float(c[:-2]) if re.fullmatch(r"[\d.]+ s", c) else None for c in cells[3:-1]]
        rows.append((cells[1], cells[2], times))
    return titles, rows


def svg(titles, rows, note=""):
    width, left, bar, gap = 760, 190, 16, 22
    top = 80 if note else 60
    height = top + len(rows) * (bar * len(titles) + gap) + 40
    longest = max(max(t for t in times if t is not None) for _, _, times in rows)
    longest = max(longest, max(BUDGET.values()))
    scale = (width - left - 110) / longest
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           '<text x="10" y="20" font-size="14" font-weight="bold">Chamonix.tif, --partition auto, 1:10000, '
           '2 threads: whole-run wall time (median)</text>']
    legend = 52 if note else 32
    if note:
        out.append(f'<text x="10" y="38" fill="#555">{note}</text>')
    for k, title in enumerate(titles):
        out.append(f'<rect x="{10 + 190 * k}" y="{legend}" width="12" height="12" fill="{COLOURS[k % len(COLOURS)]}"/>')
        out.append(f'<text x="{26 + 190 * k}" y="{legend + 11}">{title}</text>')
    y = top
    for style, output, times in rows:
        group = bar * len(titles)
        out.append(f'<text x="10" y="{y + group / 2 + 4}">{style}, {output}</text>')
        for k, t in enumerate(times):
            if t is None:
                continue
            out.append(f'<rect x="{left}" y="{y + k * bar}" width="{t * scale:.1f}" height="{bar - 3}" '
                       f'fill="{COLOURS[k % len(COLOURS)]}"/>')
            out.append(f'<text x="{left + t * scale + 4:.1f}" y="{y + k * bar + bar - 6}">{t:.2f} s</text>')
        if (style, output) in BUDGET:
            x = left + BUDGET[(style, output)] * scale
            out.append(f'<line x1="{x:.1f}" y1="{y - 4}" x2="{x:.1f}" y2="{y + group + 2}" stroke="#c0392b" '
                       'stroke-width="2" stroke-dasharray="5,3"/>')
            out.append(f'<text x="{x + 3:.1f}" y="{y - 6}" fill="#c0392b">budget {BUDGET[(style, output)]:.1f} s'
                       '</text>')
        y += group + gap
    out.append(f'<text x="10" y="{height - 12}" fill="#555">print has no budget of its own (it came after '
               'issue 11 set it); a missing bar: that version has no such style.</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("markdown", type=pathlib.Path)
    ap.add_argument("-o", "--output", type=pathlib.Path, required=True)
    ap.add_argument("--note", default="", help="a line under the title (how the runs were measured)")
    args = ap.parse_args()
    titles, rows = read_rows(args.markdown)
    if not rows:
        raise SystemExit(f"plot_style_budget: no Chamonix.tif rows in {args.markdown}")
    args.output.write_text(svg(titles, rows, args.note))
    print(f"written {args.output}")


if __name__ == "__main__":
    main()
