#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the test suite: the full suite
# in the `ci` preset; clang-format and clang-tidy over the sources (scripts/lint.sh); that build
# installed into a temporary prefix with examples/ built against it (scripts/check-install.sh);
# then the file-reader robustness tests under ASan + UBSan
# (`asan` preset).
# Tests that need ../shared/datasets skip, saying so, when it is absent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
jobs=$(nproc)

cmake --preset ci >/dev/null
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"
scripts/lint.sh build/ci
scripts/check-install.sh build/ci

cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs" --target mesh_reader_robustness_test molecule_reader_robustness_test
ctest --preset asan -j "$jobs" -R 'ReaderRobustness'
