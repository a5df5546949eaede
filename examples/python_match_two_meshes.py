#!/usr/bin/env python3
"""Matches a partial, noisy, moved copy of a mesh onto the mesh with NumPy arrays in and a 4x4
transform out: the surfcomp module takes a mesh as (V, F), matches it by shape alone in a length
unit taken from the meshes, and returns the alignments in the meshes' own coordinates.

Usage: /usr/bin/python3 examples/python_match_two_meshes.py [MESH.off]
(default: datasets/cache/cgal/meshes/elephant.off, which datasets/fetch.sh fetches)
"""
import pathlib
import sys

import numpy as np

import surfcomp

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
import mesh_cases  # noqa: E402  (reads OFF files and makes the partial copy)

mesh = sys.argv[1] if len(sys.argv) > 1 else ROOT / "datasets/cache/cgal/meshes/elephant.off"
V, F = mesh_cases.read_off(mesh)
# 40 % of the surface, each triangle split in four, noise of 0.5 % of the diagonal, moved.
case = mesh_cases.make_case(V, F, seed=2, fraction=0.4, noise=0.005)

result = surfcomp.match((V, F), (case.vertices, case.faces), repair=True)
top = result[0]
print(f"{len(result)} alignments; shape only: {result.shape_only}; length unit {result.unit:.4g}")
print("top transform (moves the copy onto the mesh):")
print(np.array2string(top.transform, precision=4, suppress_small=True))
error = mesh_cases.motion_error(case, top.transform)
print(f"error against the true motion: {100 * error:.2f} % of the diagonal")
sys.exit(0 if error < 0.02 else 1)
