#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the test suite, in stages:
#   1. everything but the benchmarks built with AddressSanitizer + UndefinedBehaviorSanitizer
#      (`asan` preset: optimised, warnings as errors) and the whole suite run on it; the
#      benchmarks are built by the `release` preset that runs them;
#   2. the suites labelled `threaded` under ThreadSanitizer, against a oneTBB built with it
#      (scripts/tsan.sh);
#   3. clang-format and clang-tidy over the sources (scripts/lint.sh);
#   4. the asan build installed into a temporary prefix with examples/ built against it
#      (scripts/check-install.sh).
# Each stage prints its wall time. The `ci` preset is the same build without the sanitizers.
# Fuzzing (scripts/fuzz.sh) runs separately: CONTRIBUTING.md says how.
# Tests that need ../shared/datasets skip, saying so, when it is absent, or fail under
# SURFCOMP_REQUIRE_DATA=1 (.ci/run sets it).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
jobs=$(nproc)

stage_start=$SECONDS
stage_done() { echo "test.sh: $1 took $((SECONDS - stage_start)) s"; stage_start=$SECONDS; }

cmake --preset asan -DSURFCOMP_BUILD_BENCH=OFF >/dev/null
cmake --build --preset asan -j "$jobs"
ctest --preset asan -j "$jobs"
stage_done "ASan + UBSan build and suite"
scripts/tsan.sh
stage_done "ThreadSanitizer build and threaded suites"
scripts/lint.sh build/asan
stage_done "lint"
scripts/check-install.sh build/asan
stage_done "install check"
