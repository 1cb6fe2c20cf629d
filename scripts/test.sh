#!/usr/bin/env bash
# Set up, build, then run every test: ctest (C++) and pytest (Python), then both again
# under ASan + UBSan (scripts/sanitize.sh), whose build runs beside the normal tests. Fails
# if any fails, and if pytest collects nothing (exit code 5).
set -uo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
scripts/setup.sh || exit 1
t_built=$(date +%s)
BUILD_DIR="${RH_BUILD_DIR:-build}"
export RH_BUILD_DIR="$(cd "$BUILD_DIR" && pwd)"

# The sanitizer build starts now, beside the normal tests, under Linux's idle scheduling
# class (chrt --idle: it runs only on a core nothing else wants, and yields the moment a test
# wakes up): it takes the CPU time the tests leave idle (a test waiting on a child process, a
# Dask cluster starting, the last test of a phase running alone) without slowing them (ctest
# took 60.6 and 63.5 s beside it, 62.2 and 60.7 s alone; at nice 19 instead, 60.7 and 63.4 s
# against 57.4 and 59.1); once they are done it has the machine to itself. Its output goes to
# a log, shown if it fails.
san_build_pid=""
if [ "${RH_TEST_SANITIZERS:-1}" != 0 ]; then
  san_log="$(mktemp)"
  idle="nice -n 19"
  chrt --idle 0 true 2>/dev/null && idle="chrt --idle 0"
  $idle scripts/sanitize.sh --build-only > "$san_log" 2>&1 &
  san_build_pid=$!
fi

ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)"
ctest_rc=$?
t_ctest=$(date +%s)

# Debian's interpreter: the first python3 on PATH may not see Debian's modules. One pytest
# worker per core (pytest-xdist): most tests wait on a child process.
/usr/bin/python3 -m pytest -q -n "$(nproc)" tests/python
pytest_rc=$?
t_pytest=$(date +%s)
if [ "$pytest_rc" -eq 5 ]; then
  echo "test: pytest collected no test: the test setup is broken" >&2
fi

# The same tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan), unless
# RH_TEST_SANITIZERS=0 (a quick local run).
sanitize_rc=0
t_san_built=$t_pytest
if [ -n "$san_build_pid" ]; then
  wait "$san_build_pid"
  san_build_rc=$?
  t_san_built=$(date +%s)
  tail -n 1 "$san_log"
  if [ "$san_build_rc" -ne 0 ]; then
    cat "$san_log" >&2
    echo "test: the sanitizer build failed" >&2
    sanitize_rc=$san_build_rc
  else
    # Configures and builds again (nothing left to do) and runs the tests.
    scripts/sanitize.sh
    sanitize_rc=$?
  fi
  rm -f "$san_log"
fi

t_end=$(date +%s)
# Each phase's wall time, for the budget of the whole command (README, "Running the tests").
echo "test: setup+build $((t_built - t0)) s, ctest $((t_ctest - t_built)) s, pytest $((t_pytest - t_ctest)) s," \
     "sanitizer build after them $((t_san_built - t_pytest)) s, sanitizers $((t_end - t_san_built)) s," \
     "total $((t_end - t0)) s"
echo "test: ctest exit $ctest_rc, pytest exit $pytest_rc, sanitizers exit $sanitize_rc"
[ "$ctest_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ] && [ "$sanitize_rc" -eq 0 ]
