#!/usr/bin/env bash
# The main job: set up, build, and run rockhatch on the bundled synthetic sample, writing a
# GeoPackage, an SVG and a PNG preview to ./out. Also extracts a partition from the DEM
# alone and hatches it (./out/auto_*), and draws the libtex gallery (thesis Appendix A)
# into ./out/gallery.
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
# The same DEM without its hand-made partition: extract one, then hatch it.
"$BUILD_DIR/carto/rockhatch" partition -q --dem data/sample_montblanc/dem.tif --overwrite \
  -o "$OUT/auto_partition.gpkg" --png "$OUT/auto_partition.png"
"$BUILD_DIR/carto/rockhatch" -q --dem data/sample_montblanc/dem.tif --partition "$OUT/auto_partition.gpkg" \
  --overwrite -o "$OUT/auto_hatching.svg" -o "$OUT/auto_hatching.png"
"$BUILD_DIR/libtex/rh_gallery" --out "$OUT/gallery" > /dev/null
for svg in "$OUT"/gallery/*.svg; do
  rsvg-convert -w 800 -h 800 "$svg" -o "${svg%.svg}.png"
done
echo "main: $OUT/hatching.gpkg, $OUT/hatching.svg, $OUT/hatching.png; from the DEM alone:" \
  "$OUT/auto_partition.gpkg, $OUT/auto_hatching.svg; gallery in $OUT/gallery/"
