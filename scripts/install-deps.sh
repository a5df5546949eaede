#!/usr/bin/env bash
# Installs the Debian bookworm packages surfcomp builds, tests, fuzzes and benchmarks with.
# Idempotent: does nothing when every package is already installed. Needs root (or sudo).
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config ca-certificates clang-format clang-tidy dpkg-dev xz-utils
  libgtest-dev libgmock-dev libbenchmark-dev
  libeigen3-dev libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev
  libboost-graph-dev libboost-iostreams-dev libboost-program-options-dev
  libtbb-dev libopenvdb-dev librdkit-dev
  openmpi-bin libopenmpi-dev
  nlohmann-json3-dev
  freesasa edtsurf
  clang libfuzzer-14-dev
  python3-rdkit python3-numpy
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
