#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang (-fsanitize=fuzzer,address,undefined)
# in build-fuzz and runs each for a fixed time from the seed corpus of fuzz/corpus.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]    default 60 s each, every target
#
# Not part of scripts/test.sh: installs the packages of scripts/setup.sh when missing
# (clang and libclang-rt-14-dev: libFuzzer and clang's sanitizer runtimes, Debian bookworm). New inputs go
# to build-fuzz/corpus/<target> (the repository's seeds are not touched); a crash leaves
# its input in build-fuzz/artifacts/<target>/ and fails the script. Prints executions,
# time and coverage per target.
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
SECS="${1:-60}"
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(fuzz_svg fuzz_pgm fuzz_partition_raw fuzz_partition_struct fuzz_cli fuzz_param)
BUILD_DIR="${RH_FUZZ_BUILD_DIR:-build-fuzz}"
JOBS="${RH_JOBS:-$(nproc)}"
[ "$JOBS" -gt 2 ] && JOBS=2

scripts/setup.sh --packages || exit 1

# Only what the targets need: libtex and carto, instrumented for coverage and the
# sanitizers; no tests, Python module, gallery or benchmarks.
mkdir -p "$BUILD_DIR"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ \
      -DRH_SANITIZE=address,undefined -DRH_FUZZ=ON -DRH_BUILD_TESTS=OFF -DRH_BUILD_PYTHON=OFF \
      -DRH_BUILD_EXAMPLES=OFF -DRH_BUILD_BENCH=OFF >"$BUILD_DIR/configure.log" 2>&1 \
  || { cat "$BUILD_DIR/configure.log"; exit 1; }
cmake --build "$BUILD_DIR" --parallel "$JOBS" --target "${TARGETS[@]}" || exit 1

# A 4 MB quarantine and 2 frames per allocation stack (sanitize.sh: 16 MB and 5; ASan's
# defaults 256 MB and 30): over a grown corpus the partition targets spent a third of their
# time in ASan's allocator, stack records and quarantine (docs/testing.md). Run a crash's
# input again under sanitize.sh's settings for the allocation stacks in full.
export ASAN_OPTIONS="detect_leaks=1:quarantine_size_mb=4:malloc_context_size=2:suppressions=$ROOT/scripts/sanitizers/asan.supp"
export LSAN_OPTIONS="suppressions=$ROOT/scripts/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$ROOT/scripts/sanitizers/ubsan.supp"
summary=()
rc=0
for t in "${TARGETS[@]}"; do
  seeds="$ROOT/fuzz/corpus/${t#fuzz_}"
  work="$BUILD_DIR/corpus/$t"
  art="$BUILD_DIR/artifacts/$t"
  mkdir -p "$work" "$art"
  extra=()
  case "$t" in
    fuzz_cli|fuzz_param) extra+=(-dict="$ROOT/fuzz/cli.dict") ;;
    fuzz_partition_raw) extra+=(-max_len=65536) ;;
  esac
  log="$BUILD_DIR/$t.log"
  echo "fuzz: $t for $SECS s"
  "$BUILD_DIR/fuzz/$t" "$work" "$seeds" -max_total_time="$SECS" -timeout=20 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="$art/" "${extra[@]}" >"$log" 2>&1
  trc=$?
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -n 1)
  took=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*')
  line="$t: exit $trc, ${execs:-?} executions in ${took:-$SECS} s, ${cov:-no coverage line}, corpus $(ls "$work" | wc -l) inputs"
  if [ "$trc" -ne 0 ]; then
    rc=1
    line="$line: FAILED (see $log, input in $art)"
    grep -m1 -E 'ERROR: |runtime error|deadly signal' "$log" >&2
  fi
  summary+=("$line")
done
printf 'fuzz: %s\n' "${summary[@]}"
exit $rc
