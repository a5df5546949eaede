"""Aligning two ligands by their surfaces from Python, step by step (run it as a script, or paste
the cells into a notebook). After scripts/demo.sh (which puts the module on the system Python's
path):

    /usr/bin/python3 examples/python_align_two_ligands.py \
        datasets/cache/rdkit-data/4i23_1C9.pdb datasets/cache/rdkit-data/4i24_1C9.pdb out/

The two crystal ligands are in one frame, so the probe should land on the reference.
"""
import pathlib
import sys

import numpy as np
from rdkit import Chem

import surfcomp

reference_file, probe_file, out = (pathlib.Path(a) for a in sys.argv[1:4])
out.mkdir(parents=True, exist_ok=True)

# %% The molecules, as RDKit reads them (PDB ligands: heavy atoms, no bond orders).
reference = Chem.MolFromPDBFile(str(reference_file))
probe = Chem.MolFromPDBFile(str(probe_file))
print(f"reference {reference.GetNumAtoms()} atoms, probe {probe.GetNumAtoms()} atoms")

# %% Surfaces: NumPy arrays of vertices, faces and per-vertex properties.
surface = surfcomp.build_surface(reference_file)
esp = surface.properties["esp"]
print(f"reference surface: {surface.n_vertices} vertices, area {surface.measures().area:.1f} A^2,"
      f" ESP from {esp.min():.1f} to {esp.max():.1f} kcal/(mol e)")

# %% Descriptors: critical points and harmonic shape images (k, rings, sectors).
described = surfcomp.describe(surface)
types = described.critical_points.type
print(f"{(types == 'peak').sum()} peaks, {(types == 'valley').sum()} valleys,"
      f" images {described.images.shape}")

# %% The match: alignments best first; a description or a molecule may go in on either side.
result = surfcomp.match(described, probe, report=out / "report.html")
print(f"{len(result)} alignments in {result.prepare_ms + result.match_ms:.0f} ms")
print("rank  source          score  shape   chem  atoms  pairs")
for a in result[:5]:
    o = a.overlay
    print(f"{a.rank:4d}  {a.source:14s} {o.score:6.3f} {o.shape:6.3f} {o.chem:6.3f}"
          f" {o.atoms:6.3f} {len(a.cp_pairs):6d}")

# %% The probe moved by the best alignment, and how far it is from its crystal pose, over the
# atoms both crystal structures resolve (matched by PDB atom name; 4i23 lacks six of 1C9's).
moved = result[0].apply(probe)


def positions_by_name(mol):
    xyz = mol.GetConformer().GetPositions()
    return {a.GetPDBResidueInfo().GetName().strip(): xyz[a.GetIdx()] for a in mol.GetAtoms()}


at_reference, at_moved = positions_by_name(reference), positions_by_name(moved)
common = sorted(set(at_reference) & set(at_moved))
deviation = np.array([at_moved[n] - at_reference[n] for n in common])
print(f"heavy-atom RMSD to the crystal pose: {np.sqrt((deviation ** 2).sum(axis=1).mean()):.2f} A"
      f" over {len(common)} atoms")
Chem.MolToMolFile(moved, str(out / "4i24_1C9_on_4i23.sdf"))
print(f"wrote {out / '4i24_1C9_on_4i23.sdf'} and {out / 'report.html'}")
