#!/usr/bin/env bash
# The test command: set up and build (scripts/setup.sh), then every test, ctest (C++) and
# pytest (Python). Fails if either fails, and if pytest collects nothing (exit code 5: the
# test set-up is broken). Prints each phase's wall time.
#
#   scripts/test.sh
#   RH_BUILD_DIR=dir scripts/test.sh
#
# The same tests under ASan + UBSan are a separate pass, scripts/sanitize.sh (its own build,
# build-asan); .ci/run runs it after this one.
set -uo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
scripts/setup.sh || { echo "test: set-up or build failed" >&2; exit 1; }
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
  echo "test: pytest collected no test: the test set-up is broken" >&2
fi

# Each phase's wall time, for the budget of the command (README, "Running the tests").
echo "test: setup+build $((t_built - t0)) s, ctest $((t_ctest - t_built)) s, pytest $((t_pytest - t_ctest)) s," \
     "total $((t_pytest - t0)) s"
echo "test: ctest exit $ctest_rc, pytest exit $pytest_rc"
[ "$ctest_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ]
