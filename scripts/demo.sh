#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the main job on data from
# Debian's rdkit-data package (Aurora-A kinase crystal ligands, pre-aligned in one frame):
#  1. the solvent-excluded surface of ligand AKI (PDB 3m11) with ESP, LP and curvature per
#     vertex -> out/3m11_AKI.ply;
#  2. the surface match of ligand 1C9 from PDB 4i24 onto the same ligand from PDB 4i23: the
#     ranked alignments -> out/1C9_match.json, and 4i24's ligand moved by the top alignment ->
#     out/4i24_1C9_aligned.pdb (the crystal overlay says it should land on its own position).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
cmake --preset release >/dev/null
cmake --build --preset release --target surfcomp
mkdir -p out
data=datasets/cache/rdkit-data
build/release/tools/surfcomp surf-build "$data/3m11_AKI.pdb" -o out/3m11_AKI.ply
build/release/tools/surfcomp match "$data/4i23_1C9.pdb" "$data/4i24_1C9.pdb" --top 5 \
  -o out/1C9_match.json --aligned-out out/4i24_1C9_aligned.pdb
echo "wrote out/3m11_AKI.ply, out/1C9_match.json, out/4i24_1C9_aligned.pdb"
