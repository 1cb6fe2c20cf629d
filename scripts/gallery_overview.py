#!/usr/bin/python3
"""Tiles the gallery's drawings into one picture for the README (docs/gallery.png).

    build/libtex/rh_gallery --out DIR && scripts/gallery_overview.py DIR docs/gallery.png [RH_GALLERY]

(RH_GALLERY: the rh_gallery executable that lists the examples; default build/libtex/rh_gallery.)

Needs rsvg-convert (librsvg2-bin) and Pillow (python3-pil).
"""
import pathlib
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw

TILE, LABEL, GAP, COLS = 200, 16, 6, 9


def main():
    src, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    names = [line.split("\t")[0] for line in subprocess.run(
        [str(pathlib.Path(sys.argv[3]) if len(sys.argv) > 3 else "build/libtex/rh_gallery"), "--list"],
        capture_output=True, text=True, check=True).stdout.splitlines()]
    rows = (len(names) + COLS - 1) // COLS
    sheet = Image.new("RGB", (COLS * (TILE + GAP) + GAP, rows * (TILE + LABEL + GAP) + GAP), "white")
    draw = ImageDraw.Draw(sheet)
    with tempfile.TemporaryDirectory() as tmp:
        for k, name in enumerate(names):
            png = pathlib.Path(tmp) / f"{name}.png"
            subprocess.run(["rsvg-convert", "-w", str(TILE), "-h", str(TILE), str(src / f"{name}.svg"), "-o",
                            str(png)], check=True)
            x = GAP + (k % COLS) * (TILE + GAP)
            y = GAP + (k // COLS) * (TILE + LABEL + GAP)
            draw.text((x, y), name, fill="black")
            sheet.paste(Image.open(png).convert("RGB"), (x, y + LABEL))
            draw.rectangle([x, y + LABEL, x + TILE - 1, y + LABEL + TILE - 1], outline=(160, 160, 160))
    sheet.save(out)
    print(f"gallery_overview: {len(names)} drawings in {out}")


if __name__ == "__main__":
    main()
