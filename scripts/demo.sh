#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the main job: the solvent-
# excluded surface of the Aurora-A crystal ligand AKI (PDB 3m11, from Debian's rdkit-data),
# with ESP, LP and curvature per vertex, written to out/3m11_AKI.ply.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
cmake --preset release >/dev/null
cmake --build --preset release --target surfcomp
mkdir -p out
build/release/tools/surfcomp surf-build datasets/cache/rdkit-data/3m11_AKI.pdb -o out/3m11_AKI.ply
echo "wrote out/3m11_AKI.ply"
