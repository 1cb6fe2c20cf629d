#!/usr/bin/env bash
# The main job: set up, build, and run rockhatch on the bundled synthetic sample, writing a
# GeoPackage, an SVG and a PNG preview to ./out. Also draws the libtex gallery (thesis
# Appendix A) into ./out/gallery.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
BUILD_DIR="${RH_BUILD_DIR:-build}"
OUT="${RH_OUT:-out}"
mkdir -p "$OUT/gallery"
"$BUILD_DIR/carto/rockhatch" \
  --dem data/sample_montblanc/dem.tif --partition data/sample_montblanc/partition.gpkg \
  --scale 10000 --overwrite \
  -o "$OUT/hatching.gpkg" -o "$OUT/hatching.svg" -o "$OUT/hatching.png"
"$BUILD_DIR/libtex/rh_gallery" --out "$OUT/gallery" > /dev/null
for svg in "$OUT"/gallery/*.svg; do
  rsvg-convert -w 800 -h 800 "$svg" -o "${svg%.svg}.png"
done
echo "main: $OUT/hatching.gpkg, $OUT/hatching.svg, $OUT/hatching.png; gallery in $OUT/gallery/"
