#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the test suite, in stages:
#   1. the full suite in the `ci` preset (optimised, warnings as errors);
#   2. clang-format and clang-tidy over the sources (scripts/lint.sh);
#   3. that build installed into a temporary prefix with examples/ built against it
#      (scripts/check-install.sh);
#   4. the file-reader tests (robustness, limits) under AddressSanitizer +
#      UndefinedBehaviorSanitizer (`asan` preset).
# Each stage prints its wall time. The whole suite under ASan + UBSan and the threaded suites under
# ThreadSanitizer (`tsan` preset), and fuzzing (scripts/fuzz.sh), run separately: CONTRIBUTING.md.
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
scripts/lint.sh build/ci
stage_done "lint"
scripts/check-install.sh build/ci
stage_done "install check"

cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs" --target \
  mesh_reader_robustness_test molecule_reader_robustness_test reader_limits_test
ctest --preset asan -j "$jobs" -R 'ReaderRobustness|ReadInputFile|ReadCoordinates|ReadHsi|ReadRecords'
stage_done "ASan + UBSan reader tests"
