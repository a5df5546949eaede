#!/usr/bin/env bash
# Checks surfcomp as an installed package, the way a C++ user meets it: installs an existing
# build into a temporary prefix, builds examples/ against it (find_package(surfcomp CONFIG)) and
# runs align_two_ligands on ligand 1C9 of PDB 4i24 (PROBE) onto the one of PDB 4i23 (REF), then
# match_two_meshes on a mesh and a partial copy of it.
# The two crystal ligands overlay with a known pose: their 22 shared atoms (same names) superpose
# to 0.16 A RMSD after a 13-degree rotation, and lie 1.07 A apart as the files give them. The top
# transform must move PROBE's shared atoms onto REF's to within 0.5 A RMSD.
# Usage: scripts/check-install.sh [BUILD_DIR]   (default build/ci, built already). A build with
# SURFCOMP_SANITIZE is a different ABI (Eigen, for one, allocates otherwise under ASan): the
# example is then compiled and linked with the same sanitizers, leak checks off as in the tests.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build_dir=${1:-build/ci}
ref=datasets/cache/rdkit-data/4i23_1C9.pdb
probe=datasets/cache/rdkit-data/4i24_1C9.pdb
max_rmsd=0.5

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Runs a step quietly; on failure shows its output.
quietly() {
  if ! "$@" >"$work/step.log" 2>&1; then
    cat "$work/step.log" >&2
    echo "check-install: failed: $*" >&2
    exit 1
  fi
}
sanitize=""
if grep -q '^SURFCOMP_SANITIZE:BOOL=ON$' "$build_dir/CMakeCache.txt"; then
  sanitize="-fsanitize=address,undefined"
  export ASAN_OPTIONS=detect_leaks=0
fi
quietly cmake --install "$build_dir" --prefix "$work/prefix"
quietly "$work/prefix/bin/surfcomp" --version
quietly cmake -S examples -B "$work/examples" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_FLAGS="$sanitize" \
  -DCMAKE_EXE_LINKER_FLAGS="$sanitize"
quietly cmake --build "$work/examples"
# The installed modules, not the build tree's: the example must run from the install alone.
module=$(find "$work/prefix" -name libsurfcomp_rdkit.so | head -n 1)
[[ -n "$module" ]] || { echo "check-install: the install has no libsurfcomp_rdkit.so" >&2; exit 1; }
SURFCOMP_MODULE_DIR="$(dirname "$module")" \
  "$work/examples/align_two_ligands" "$ref" "$probe" | tee "$work/align.txt"

# The transform's first three rows follow the line "top transform"; atoms are matched by name
# (PDB columns 13-16).
awk -v out="$work/align.txt" -v ref="$ref" -v max_rmsd="$max_rmsd" '
  function trim(s) { gsub(/ /, "", s); return s }
  FILENAME == out && row > 0 && row <= 3 { for (c = 1; c <= 4; ++c) t[row, c] = $c; ++row }
  FILENAME == out && /^top transform/ { row = 1 }
  FILENAME != out && /^(ATOM  |HETATM)/ {
    name = trim(substr($0, 13, 4))
    x = substr($0, 31, 8) + 0; y = substr($0, 39, 8) + 0; z = substr($0, 47, 8) + 0
    if (FILENAME == ref) { rx[name] = x; ry[name] = y; rz[name] = z; next }
    if (!(name in rx)) next
    dx = t[1, 1] * x + t[1, 2] * y + t[1, 3] * z + t[1, 4] - rx[name]
    dy = t[2, 1] * x + t[2, 2] * y + t[2, 3] * z + t[2, 4] - ry[name]
    dz = t[3, 1] * x + t[3, 2] * y + t[3, 3] * z + t[3, 4] - rz[name]
    sum += dx * dx + dy * dy + dz * dz; ++n
  }
  END {
    if (row != 4) { print "check-install: no transform in the example'"'"'s output" > "/dev/stderr"; exit 1 }
    if (n < 3) { print "check-install: fewer than 3 shared atoms" > "/dev/stderr"; exit 1 }
    cosine = (t[1, 1] + t[2, 2] + t[3, 3] - 1) / 2
    if (cosine > 1) cosine = 1
    if (cosine < -1) cosine = -1
    angle = atan2(sqrt(1 - cosine * cosine), cosine) * 45 / atan2(1, 1)
    rmsd = sqrt(sum / n)
    printf "check-install: top transform rotates %.1f deg; %d shared atoms moved onto REF: " \
           "RMSD %.3f A (at most %.1f A)\n", angle, n, rmsd, max_rmsd
    if (rmsd > max_rmsd) {
      print "check-install: FAILED: the top alignment is not the crystal overlay" > "/dev/stderr"
      exit 1
    }
  }' "$work/align.txt" "$ref" "$probe"

# match_two_meshes on CGAL's elephant and a partial copy of it (bench/mesh_cases.py: 40 % of the
# area, subdivided, noise of 0.5 % of the diagonal, moved): the top transform must take the copy
# back to within 2 % of the diagonal of where it came from.
elephant=datasets/cache/cgal/meshes/elephant.off
/usr/bin/python3 - "$elephant" "$work/partial.off" <<'PY'
import sys
sys.path.insert(0, "bench")
import mesh_cases
V, F = mesh_cases.read_off(sys.argv[1])
case = mesh_cases.make_case(V, F, seed=2, fraction=0.4, noise=0.005)
mesh_cases.write_off(sys.argv[2], case.vertices, case.faces)
PY
"$work/examples/match_two_meshes" "$elephant" "$work/partial.off" | tee "$work/meshes.txt"
/usr/bin/python3 - "$elephant" "$work/meshes.txt" <<'PY'
import sys
import numpy as np
sys.path.insert(0, "bench")
import mesh_cases
V, F = mesh_cases.read_off(sys.argv[1])
case = mesh_cases.make_case(V, F, seed=2, fraction=0.4, noise=0.005)
lines = open(sys.argv[2]).read().splitlines()
at = lines.index("top transform (moves PROBE into REF's frame):")
transform = np.array([[float(x) for x in line.split()] for line in lines[at + 1:at + 5]])
error = mesh_cases.motion_error(case, transform)
print(f"check-install: match_two_meshes puts the partial copy {100 * error:.2f} % of the "
      f"diagonal from its true place (at most 2 %)")
sys.exit(0 if error < 0.02 else "check-install: FAILED: the partial copy is not recovered")
PY
