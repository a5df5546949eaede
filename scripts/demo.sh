#!/usr/bin/env bash
# Sets everything up on a fresh Debian bookworm machine and runs the main job on data from
# Debian's rdkit-data package (Aurora-A kinase crystal ligands, pre-aligned in one frame):
#  1. the solvent-excluded surface of ligand AKI (PDB 3m11) with ESP, LP and curvature per
#     vertex -> out/3m11_AKI.ply;
#  2. the surface match of ligand 1C9 from PDB 4i24 onto the same ligand from PDB 4i23: the
#     ranked alignments -> out/1C9_match.json, and 4i24's ligand moved by the top alignment ->
#     out/4i24_1C9_aligned.pdb (the crystal overlay says it should land on its own position), and
#     the match as an HTML page to open in a browser -> out/1C9_report.html;
#  3. a screen: the benzodiazepine-receptor ligands of rdkit-data (bzr.sdf, 163 molecules) made a
#     library -> out/bzr.sclib, and its first molecule (adinazolam) screened against it ->
#     out/bzr_hits.csv and the top hits moved onto it -> out/bzr_hits.sdf (it finds itself first);
#  4. the Python module: `import surfcomp` for the system's Python 3 (a surfcomp.pth file in its
#     site-packages names build/release/python), and the example script
#     examples/python_align_two_ligands.py on the 1C9 pair -> out/python/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
datasets/fetch.sh
cmake --preset release >/dev/null
cmake --build --preset release --target surfcomp _surfcomp _command_line
site_packages=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
if [ "$(cat "$site_packages/surfcomp.pth" 2>/dev/null)" != "$PWD/build/release/python" ]; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo mkdir -p "$site_packages"
  echo "$PWD/build/release/python" | $sudo tee "$site_packages/surfcomp.pth" >/dev/null
  echo "demo: import surfcomp now works in /usr/bin/python3 ($site_packages/surfcomp.pth)"
fi
mkdir -p out
data=datasets/cache/rdkit-data
build/release/tools/surfcomp surf-build "$data/3m11_AKI.pdb" -o out/3m11_AKI.ply
build/release/tools/surfcomp match "$data/4i23_1C9.pdb" "$data/4i24_1C9.pdb" --top 5 \
  -o out/1C9_match.json --aligned-out out/4i24_1C9_aligned.pdb --report out/1C9_report.html
build/release/tools/surfcomp library build "$data/bzr.sdf" -o out/bzr.sclib
build/release/tools/surfcomp screen "$data/bzr.sdf" --record 1 out/bzr.sclib --top 20 \
  -o out/bzr_hits.csv --aligned-out out/bzr_hits.sdf
head -n 4 out/bzr_hits.csv | cut -d, -f1-9
/usr/bin/python3 examples/python_align_two_ligands.py "$data/4i23_1C9.pdb" "$data/4i24_1C9.pdb" \
  out/python
echo "wrote out/3m11_AKI.ply, out/1C9_match.json, out/4i24_1C9_aligned.pdb," \
  "out/1C9_report.html, out/bzr.sclib, out/bzr_hits.csv, out/bzr_hits.sdf, out/python/"
