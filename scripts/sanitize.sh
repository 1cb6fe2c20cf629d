#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (clang's), in a second
# build folder: every C++ test (ctest, the gallery's included), then the Python tests with the
# instrumented module loaded into Debian's interpreter (every test, none skipped). A separate
# pass: .ci/run runs it after scripts/test.sh.
#
#   scripts/sanitize.sh                   configure + build build-asan, run the tests
#   RH_ASAN_BUILD_DIR=dir scripts/sanitize.sh
#   RH_SANITIZE_PYTEST=0 scripts/sanitize.sh   C++ tests only
#   scripts/sanitize.sh --build-only      configure + build, no test
#
# A finding fails the test that meets it: UBSan does not recover (-fno-sanitize-recover),
# ASan aborts at the first error, LeakSanitizer fails a C++ test that leaks. Findings in
# third-party code only are suppressed in scripts/sanitizers/*.supp (one comment each).
#
# Every test runs on the same data as in the normal pass. RH_SANITIZED=1 (set below) is read
# only where a test cannot do the same thing under ASan at all (tests/python/conftest.py:
# SANITIZED): test_bad_inputs limits memory through ASan's allocator, not an address-space
# limit (ASan's shadow memory exceeds any), and test_qgis_plugin's cancel test allows 30 s, not
# 3, for the face in flight to finish.
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
BUILD_DIR="${RH_ASAN_BUILD_DIR:-build-asan}"
JOBS="${RH_JOBS:-$(nproc)}"
[ "$JOBS" -gt 2 ] && JOBS=2
start=$(date +%s)

# Debug (assertions on), optimised at -O1 with line tables (RH_SAN_OPT in CMakeLists.txt);
# no benchmarks. Compiled by clang (Debian's clang 14; scripts/setup.sh installs it), not GCC:
# the same instrumentation and runtime (compiler-rt), but the build took 584 job-seconds
# against 899 with GCC (planar_map.cpp 60 s against 82, the Python module's glue 156 against
# 236), and the C++ tests ran in 261 s against 291 s, every test passing under both.
scripts/setup.sh --packages || exit 1
mkdir -p "$BUILD_DIR"
BUILD_ABS="$(cd "$BUILD_DIR" && pwd)"  # RH_ASAN_BUILD_DIR may be relative or absolute
# A folder configured with another compiler (GCC, before) is configured afresh.
if [ -f "$BUILD_DIR/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' "$BUILD_DIR/CMakeCache.txt"; then
  rm -rf "$BUILD_DIR/CMakeCache.txt" "$BUILD_DIR/CMakeFiles"
fi
CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DRH_SANITIZE=address,undefined \
      -DRH_BUILD_BENCH=OFF -DRH_BUILD_EXAMPLES=ON -DRH_UNITY_BUILD=ON >"$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
cmake --build "$BUILD_DIR" --parallel "$JOBS" || exit 1
built=$(date +%s)
if [ "${1:-}" = --build-only ]; then
  echo "sanitize: build $((built - start)) s"
  exit 0
fi

SUPP="$ROOT/scripts/sanitizers"
# ASan's quarantine keeps freed memory poisoned (256 MB by default) to catch a use after free.
# The pipeline frees many small maps, and with the default the sample run under ASan took
# 3.1 s and 721 MB; with 16 MB, 2.2 s and 220 MB (a use after free is still caught while the
# block has not been reused: the 16 MB most recently freed). RH_ASAN_QUARANTINE_MB=0 keeps
# ASan's default.
QUARANTINE="${RH_ASAN_QUARANTINE_MB:-16}"
Q_OPT=""
[ "$QUARANTINE" != 0 ] && Q_OPT=":quarantine_size_mb=$QUARANTINE"
# The stack ASan records at every malloc and free, for its reports (30 frames by default):
# 5 frames, the allocating call and four callers. The pipeline allocates many small vectors;
# TerrainStyles.RunOnTheSample took 22.0 CPU-s with 30 frames, 19.4 with 5 (2.0 s less wall
# of 14.3). RH_ASAN_CONTEXT=30 restores the default to read a report's full stacks.
Q_OPT="$Q_OPT:malloc_context_size=${RH_ASAN_CONTEXT:-5}"
export ASAN_OPTIONS="detect_leaks=1$Q_OPT:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:suppressions=$SUPP/asan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$SUPP/ubsan.supp"
export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0"

export RH_SANITIZED=1
# Here ctest runs each test program whole, the slow ones in gtest shards (rh_register_tests in
# tests/CMakeLists.txt): a test process under ASan takes 0.2 to 0.6 s to start.
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS"
ctest_rc=$?
ctested=$(date +%s)

# The Python tests under ASan, JOBS at a time (pytest-xdist): every test, the Dask tiled runs,
# the QGIS algorithms and the real-DEM tests included, on the same data as the normal pass.
pytest_rc=0
if [ "${RH_SANITIZE_PYTEST:-1}" != 0 ]; then
  # Debian's interpreter is not instrumented: the ASan runtime must be loaded first
  # (LD_PRELOAD), and leaks are not checked (CPython keeps its objects at exit by design).
  # Child processes (the rockhatch commands, python3 -m rockhatch, Dask's workers, QGIS's
  # qgis_process) inherit the settings (test_bad_inputs.py then limits memory through ASan,
  # not with an address-space limit).
  # clang's shared ASan runtime, which also holds UBSan's: the one the programs of the build
  # link (-shared-libsan), as CMakeLists.txt found it.
  LIBASAN="$(sed -n 's/^RH_ASAN_RUNTIME:INTERNAL=//p' "$BUILD_DIR/CMakeCache.txt")"
  RH_BUILD_DIR="$BUILD_ABS" \
  LD_PRELOAD="$LIBASAN" \
  ASAN_OPTIONS="detect_leaks=0$Q_OPT:suppressions=$SUPP/asan.supp" \
  QT_QPA_PLATFORM=offscreen \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider -n "$JOBS" tests/python
  pytest_rc=$?
fi
end=$(date +%s)
echo "sanitize: build $((built - start)) s, ctest $((ctested - built)) s, pytest $((end - ctested)) s;" \
     "ctest exit $ctest_rc, pytest exit $pytest_rc"
[ "$ctest_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ]
