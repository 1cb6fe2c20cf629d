#!/usr/bin/env bash
# The main job (until the rockhatch command exists): set up, build, and draw the libtex
# gallery (thesis Appendix A) as SVG files with PNG previews in ./gallery_out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR="${RH_BUILD_DIR:-build}"
OUT="${RH_GALLERY_OUT:-gallery_out}"
"$BUILD_DIR/libtex/rh_gallery" --out "$OUT"
for svg in "$OUT"/*.svg; do
  rsvg-convert -w 800 -h 800 "$svg" -o "${svg%.svg}.png"
done
echo "main: SVG files and PNG previews in $OUT/"
