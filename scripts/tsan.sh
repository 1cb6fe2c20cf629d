#!/usr/bin/env bash
# ThreadSanitizer (GCC's) on the parallel paths, in build-tsan: libtex's parallel_for
# (every libtex test evaluates on all cores by default), mappers in worker threads, the
# pipeline with one and two threads, the rockhatch command with --threads 2 on the sample,
# and Python mappers and arrangements called from the engine's threads through the
# bindings. Not part of scripts/test.sh (slow: see the README for the time it takes).
#
#   scripts/tsan.sh
#   RH_TSAN_BUILD_DIR=dir scripts/tsan.sh
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
BUILD_DIR="${RH_TSAN_BUILD_DIR:-build-tsan}"
JOBS="${RH_JOBS:-$(nproc)}"
[ "$JOBS" -gt 2 ] && JOBS=2
start=$(date +%s)

mkdir -p "$BUILD_DIR"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DRH_SANITIZE=thread \
      -DRH_BUILD_BENCH=OFF -DRH_BUILD_EXAMPLES=OFF >"$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
cmake --build "$BUILD_DIR" --parallel "$JOBS" --target test_mapping test_mappers test_partitions \
      test_fields test_planar_map test_pipeline rockhatch rockhatch_python || exit 1
built=$(date +%s)

# Two threads at least, whatever the machine: the races need two.
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$ROOT/scripts/sanitizers/tsan.supp"
rc=0
for t in test_mapping test_mappers test_partitions test_fields test_planar_map; do
  "$BUILD_DIR/tests/$t" --gtest_brief=1 || rc=1
done
"$BUILD_DIR/tests/test_pipeline" --gtest_brief=1 --gtest_filter='Pipeline.SameHatchesWithOneOrTwoThreads' || rc=1

OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
S="$ROOT/data/sample_montblanc"
"$BUILD_DIR/carto/rockhatch" -q --dem "$S/dem.tif" --partition "$S/partition.gpkg" --threads 2 \
    -o "$OUT/h.gpkg" -o "$OUT/h.svg" || rc=1

# Python mappers through the bindings (the interpreter is not instrumented: the TSan
# runtime is loaded first).
RH_BUILD_DIR="$ROOT/$BUILD_DIR" LD_PRELOAD="$(g++ -print-file-name=libtsan.so)" \
  /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python/test_module.py tests/python/test_stock_mappers.py \
  -k "thread or mapper or gil or nested or partitions_built" || rc=1
end=$(date +%s)
echo "tsan: build $((built - start)) s, tests $((end - built)) s, exit $rc"
exit $rc
