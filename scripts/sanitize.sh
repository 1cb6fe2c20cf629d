#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (GCC's), in a second
# build folder: the C++ tests (ctest; the gallery's on request), then the Python tests of the
# bindings with the instrumented module loaded into Debian's interpreter (every Python test
# on request). scripts/test.sh runs it after the normal tests.
#
#   scripts/sanitize.sh                   configure + build build-asan, run the tests
#   RH_ASAN_BUILD_DIR=dir scripts/sanitize.sh
#   RH_SANITIZE_PYTEST=0 scripts/sanitize.sh   C++ tests only (=all: every Python test)
#   RH_SANITIZE_GALLERY=1 scripts/sanitize.sh  the gallery's C++ tests too
#
# A finding fails the test that meets it: UBSan does not recover (-fno-sanitize-recover),
# ASan aborts at the first error, LeakSanitizer fails a C++ test that leaks. Findings in
# third-party code only are suppressed in scripts/sanitizers/*.supp (one comment each).
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
BUILD_DIR="${RH_ASAN_BUILD_DIR:-build-asan}"
JOBS="${RH_JOBS:-$(nproc)}"
[ "$JOBS" -gt 2 ] && JOBS=2
start=$(date +%s)

# Debug (assertions on), optimised at -O2 with line tables (RH_SAN_OPT in CMakeLists.txt);
# no benchmarks, and no gallery unless its tests are asked for: building it and running its
# 112 tests under ASan adds about 6 minutes on two cores, over CI's budget, and they run
# libtex code that libtex's own tests cover (run on request, they were clean).
EXAMPLES=OFF
{ [ "${RH_SANITIZE_GALLERY:-0}" != 0 ] || [ "${RH_SANITIZE_PYTEST:-1}" = all ]; } && EXAMPLES=ON
mkdir -p "$BUILD_DIR"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DRH_SANITIZE=address,undefined \
      -DRH_BUILD_BENCH=OFF -DRH_BUILD_EXAMPLES=$EXAMPLES >"$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
cmake --build "$BUILD_DIR" --parallel "$JOBS" || exit 1
built=$(date +%s)

SUPP="$ROOT/scripts/sanitizers"
# ASan's quarantine keeps freed memory poisoned (256 MB by default) to catch a use after free.
# The pipeline frees many small maps, and with the default the sample run under ASan took
# 3.1 s and 721 MB; with 16 MB, 2.2 s and 220 MB (a use after free is still caught while the
# block has not been reused: the 16 MB most recently freed). RH_ASAN_QUARANTINE_MB=0 keeps
# ASan's default.
QUARANTINE="${RH_ASAN_QUARANTINE_MB:-16}"
Q_OPT=""
[ "$QUARANTINE" != 0 ] && Q_OPT=":quarantine_size_mb=$QUARANTINE"
export ASAN_OPTIONS="detect_leaks=1$Q_OPT:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:suppressions=$SUPP/asan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$SUPP/ubsan.supp"
export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0"

# RH_SANITIZED=1: the slowest tests check their property on less work (tests/common/sanitized.hpp,
# tests/python/conftest.py); the normal pass runs their full versions.
export RH_SANITIZED=1
# The gallery's tests carry the label gallery.
EXCLUDE=(-LE gallery)
[ "${RH_SANITIZE_GALLERY:-0}" != 0 ] && EXCLUDE=()
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS" "${EXCLUDE[@]}"
ctest_rc=$?
ctested=$(date +%s)

# The Python tests under ASan, JOBS at a time (pytest-xdist): every file that runs the
# instrumented module in the interpreter's own process (the bindings, Python mappers called
# from the engine's threads, fields, carto, tiled maps and their images, the discrete and
# synthesis operators, reliability), and the command files that are cheap under ASan: bad
# inputs (every refusal path of the command and of `rockhatch partition`), crests, the
# partition command, the Python gallery scripts (against the golden bytes; the one test that
# lists rh_gallery's examples is left out, as the gallery program is not built here unless
# asked). Six files are left to the normal pass by default: test_gallery_cli (rh_gallery),
# test_qgis_plugin, test_rockhatch_cli, test_styles, test_terrain_styles and test_tiles (QGIS,
# Dask clusters, many whole-sample commands: about 1,200 CPU-seconds under ASan, which do not
# fit CI's budget with the rest). RH_SANITIZE_PYTEST=all runs every file.
PYTESTS=(tests/python/test_module.py tests/python/test_stock_mappers.py tests/python/test_fields.py
         tests/python/test_python_carto.py tests/python/test_tiled.py tests/python/test_tiled_image.py
         tests/python/test_discrete.py tests/python/test_synthesis.py tests/python/test_reliability.py
         tests/python/test_python_partition.py tests/python/test_script_style.py
         tests/python/test_bad_inputs.py tests/python/test_crest.py tests/python/test_partition_cli.py
         tests/python/test_python_gallery.py
         --deselect tests/python/test_python_gallery.py::test_the_python_gallery_lists_every_cpp_example)
[ "${RH_SANITIZE_PYTEST:-1}" = all ] && PYTESTS=(tests/python)
pytest_rc=0
if [ "${RH_SANITIZE_PYTEST:-1}" != 0 ]; then
  # Debian's interpreter is not instrumented: the ASan runtime must be loaded first
  # (LD_PRELOAD), and leaks are not checked (CPython keeps its objects at exit by design).
  # Child processes (the rockhatch commands, python3 -m rockhatch, Dask's workers, QGIS's
  # qgis_process) inherit the settings (test_bad_inputs.py then limits memory through ASan,
  # not with an address-space limit).
  LIBASAN="$(g++ -print-file-name=libasan.so)"
  LIBUBSAN="$(g++ -print-file-name=libubsan.so)"
  RH_BUILD_DIR="$ROOT/$BUILD_DIR" \
  LD_PRELOAD="$LIBASAN $LIBUBSAN" \
  ASAN_OPTIONS="detect_leaks=0$Q_OPT:suppressions=$SUPP/asan.supp" \
  QT_QPA_PLATFORM=offscreen \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider -n "$JOBS" "${PYTESTS[@]}"
  pytest_rc=$?
fi
end=$(date +%s)
echo "sanitize: build $((built - start)) s, ctest $((ctested - built)) s, pytest $((end - ctested)) s;" \
     "ctest exit $ctest_rc, pytest exit $pytest_rc"
[ "$ctest_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ]
