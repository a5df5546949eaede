#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the test suite, in stages:
#   1. the full suite in the `ci` preset (optimised, warnings as errors);
#   2. that build installed into a temporary prefix with examples/ built against it
#      (scripts/check-install.sh);
#   3. the full suite again under AddressSanitizer + UndefinedBehaviorSanitizer (`asan` preset);
#   4. the suites labelled "threaded" in tests/CMakeLists.txt (TBB loops, OpenVDB, std::thread)
#      under ThreadSanitizer (`tsan` preset).
# Each stage prints its wall time. Fuzzing is separate: scripts/fuzz.sh (CONTRIBUTING.md).
# Tests that need ../shared/datasets skip, saying so, when it is absent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
jobs=$(nproc)

stage_start=$SECONDS
stage_done() { echo "test.sh: $1 took $((SECONDS - stage_start)) s"; stage_start=$SECONDS; }

cmake --preset ci >/dev/null
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"
stage_done "ci build and tests"
scripts/check-install.sh build/ci
stage_done "install check"

cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs"
ctest --preset asan -j "$jobs"
stage_done "ASan + UBSan build and tests"

cmake --preset tsan >/dev/null
cmake --build --preset tsan -j "$jobs" --target \
  association_graph_test curvature_test descriptors_test match_test patch_test potentials_test ses_test
ctest --preset tsan -j "$jobs" -L threaded
stage_done "TSan build and threaded tests"
