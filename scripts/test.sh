#!/usr/bin/env bash
# Set up, build, then run every test: ctest (C++) and pytest (Python), then both again
# under ASan + UBSan (scripts/sanitize.sh). Fails if any fails, and if pytest collects
# nothing (exit code 5).
set -uo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
scripts/setup.sh || exit 1
t_built=$(date +%s)
BUILD_DIR="${RH_BUILD_DIR:-build}"
export RH_BUILD_DIR="$(cd "$BUILD_DIR" && pwd)"

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
if [ "${RH_TEST_SANITIZERS:-1}" != 0 ]; then
  scripts/sanitize.sh
  sanitize_rc=$?
fi

t_end=$(date +%s)
# Each phase's wall time, for the budget of the whole command (README, "Running the tests").
echo "test: setup+build $((t_built - t0)) s, ctest $((t_ctest - t_built)) s, pytest $((t_pytest - t_ctest)) s," \
     "sanitizers $((t_end - t_pytest)) s, total $((t_end - t0)) s"
echo "test: ctest exit $ctest_rc, pytest exit $pytest_rc, sanitizers exit $sanitize_rc"
[ "$ctest_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ] && [ "$sanitize_rc" -eq 0 ]
