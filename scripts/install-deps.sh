#!/usr/bin/env bash
# Installs the Debian bookworm packages surfcomp builds, tests, fuzzes and benchmarks with, and
# the npm package of the report's viewer (3Dmol.js, pinned in report/package-lock.json) into
# report/node_modules. Idempotent: does nothing when everything is already installed. Needs
# root (or sudo) for the Debian packages.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config ca-certificates clang-format clang-tidy dpkg-dev xz-utils
  libgtest-dev libgmock-dev libbenchmark-dev
  libeigen3-dev libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev
  libboost-graph-dev libboost-iostreams-dev libboost-program-options-dev
  libtbb-dev librdkit-dev libhwy-dev libxxhash-dev gemmi gemmi-dev tao-pegtl-dev
  openmpi-bin libopenmpi-dev
  nlohmann-json3-dev
  freesasa edtsurf
  clang libfuzzer-14-dev
  python3-rdkit python3-numpy python3-dev pybind11-dev python3-pytest python3-pil
  libcairo2-dev
  chromium
)
# Node.js and npm fetch the viewer; a machine that has them from elsewhere keeps its own.
if ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The report's viewer, at the version the lock file pins; reinstalled when the lock changes.
report=$(cd "$(dirname "${BASH_SOURCE[0]}")/../report" && pwd)
stamp=$report/node_modules/.surfcomp-lock
if [ ! -f "$report/node_modules/3dmol/build/3Dmol-min.js" ] || ! cmp -s "$report/package-lock.json" "$stamp"; then
  echo "install-deps: npm ci in $report (3Dmol.js for the HTML report)"
  npm ci --prefix "$report" --no-audit --no-fund --loglevel=error
  cp "$report/package-lock.json" "$stamp"
fi
