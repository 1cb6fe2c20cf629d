#!/usr/bin/env bash
# Installs the Debian bookworm packages rockhatch needs (when missing) and builds it.
#
#   scripts/setup.sh            install + configure + build into ./build
#   RH_BUILD_DIR=dir scripts/setup.sh
#   scripts/setup.sh --packages install only (scripts/sanitize.sh and scripts/fuzz.sh), with
#                               web/'s npm packages
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev   # libtex: exact planar maps
  libtinyxml2-dev                                   # libtex: SVG import
  libgdal-dev gdal-bin libproj-dev proj-bin         # carto: rasters, vectors, CRSs
  libgeographiclib-dev                              # carto: UTM zone of geographic DEMs
  libsqlite3-dev                                    # carto: bulk-loaded GeoPackage R-tree
  zlib1g-dev                                        # carto: the PDF layers' compressed pages
  libjemalloc-dev                                   # the rockhatch command's allocator (many small maps)
  libgtest-dev                                      # C++ tests
  python3 python3-dev pybind11-dev                  # the Python module, for /usr/bin/python3
  python3-pytest python3-pytest-xdist               # Python tests (Debian's interpreter), a worker per core
  python3-gdal python3-numpy
  python3-scipy                                     # bench/print_quality.py, the drawing-quality tests (KD-trees)
  python3-pil openimageio-tools                     # tests read written images back (PNG, TIFF; EXR)
  python3-distributed python3-dask python3-psutil  # rockhatch tiles: tiled runs on Dask distributed
  librsvg2-bin time                                 # PNG previews of SVG outputs; GNU time (benchmarks)
  poppler-utils                                     # tests render PDF outputs (pdftoppm)
  dpkg-dev file binutils                            # the Debian package (cpack: dpkg-shlibdeps, file, objdump)
  libopenimageio-dev                                # libtex_image: tiled maps rasterised to image files
  qgis python3-qgis qgis-providers                  # the QGIS plugin and its tests (headless QGIS, qgis_process)
  clang libclang-rt-14-dev                          # the sanitizer build of the tests; libFuzzer (scripts/fuzz.sh)
  chromium                                          # the web page's browser test (headless, tests/python/test_web.py)
)
# Node.js and npm for web/ (MapLibre GL JS, playwright-core): Debian's, unless a node with its
# npm is already there (a NodeSource nodejs carries its own npm and conflicts with Debian's).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The web page's packages (web/package-lock.json), again whenever the lock file changed.
if [ ! -f web/node_modules/.package-lock.json ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  echo "setup: npm ci in web/"
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
[ "${1:-}" = --packages ] && exit 0

BUILD_DIR="${RH_BUILD_DIR:-build}"
# libtex and carto compile in batches (RH_UNITY_BUILD, CMakeLists.txt): a fresh build is
# quicker, an edit of one file recompiles its batch (-DRH_UNITY_BUILD=OFF for editing).
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRH_UNITY_BUILD=ON
cmake --build "$BUILD_DIR" --parallel "$(nproc)"

# Make `import rockhatch` work for Debian's interpreter: a .pth file in its site folder
# names this build's package folder (like an editable install; rerun to point elsewhere).
PY_DIR="$(cd "$BUILD_DIR" && pwd)/python"
if [ -d "$PY_DIR/rockhatch" ]; then
  SITE="$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')"
  if mkdir -p "$SITE" 2>/dev/null && echo "$PY_DIR" > "$SITE/rockhatch.pth" 2>/dev/null; then
    echo "setup: rockhatch Python module installed for /usr/bin/python3 ($SITE/rockhatch.pth -> $PY_DIR)"
  else
    echo "setup: cannot write $SITE/rockhatch.pth; use PYTHONPATH=$PY_DIR" >&2
  fi
fi
