#!/usr/bin/python3
"""Redocking's poses of several conformers ranked again by their agreement, without docking again.

Reads redock_bench.py work folders, each from a run with many poses per complex (`-- --conformers
10 --poses 40 --distinct-rmsd 0.5`), pairs every pose with its crystal pose as redock_bench does
(heavy-atom RMSD, atoms of one element paired by the assignment that minimises it), and ranks the
poses of each complex again by two consensus rules:
- `support`: the score plus LAMBDA times the poses within R A of the pose (the conformers of one
  record share their atom order, so poses of two conformers are compared atom for atom), each
  neighbour counted once or weighted by exp((its score - the best score) / T);
- `cluster`: poses taken by score, each joining the first earlier cluster head within R A; the
  cluster with the largest sum of its M best scores gives its head.
Reported: the top pose within 2 A by the score alone and by each rule, per ligand type
(thermolysin, ATP, HEM, FMN), and each rule chosen leave-one-type-out (best on the other three
types, ties to the first in the grid) and scored on the type held out.

    /usr/bin/python3 bench/conformer_ranking.py WORK [WORK ...] [--shared ../shared/datasets]
"""

import argparse
import glob
import json
import os
import sys
import tempfile

import numpy as np
from rdkit import Chem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import redock_bench  # noqa: E402


def crystal_ligands(shared, work):
    """{entry: (ligand type, crystal ligand)} of the sets redock_bench docks."""
    out = {}
    for entry, residue, crystal, _ in redock_bench.thermolysin_cases(shared, work):
        out[entry] = ("thermolysin", crystal)
    for entry, residue, crystal, _ in redock_bench.kahraman_cases(shared, work):
        out[entry] = (residue, crystal)
    return out


def complex_poses(folder, crystals):
    """{entry: (scores, heavy-atom positions, RMSDs to the crystal)} of a work folder's docks."""
    out = {}
    for result_file in sorted(glob.glob(os.path.join(folder, "*_dock.json"))):
        entry = os.path.basename(result_file)[:-len("_dock.json")]
        if entry not in crystals:
            continue
        with open(result_file) as f:
            poses = json.load(f)["poses"]
        mols = Chem.SDMolSupplier(result_file[:-len("_dock.json")] + "_poses.sdf", removeHs=False)
        reference = redock_bench.heavy_atoms(crystals[entry][1])
        scores, positions, rmsds = [], [], []
        for pose, mol in zip(poses, mols):
            elements, x = redock_bench.heavy_atoms(mol)
            scores.append(pose["score"])
            positions.append(x)
            rmsds.append(redock_bench.rmsd((elements, x), reference))
        if scores:
            out[entry] = (np.array(scores), positions, np.array(rmsds))
    return out


def pose_distances(positions):
    n = len(positions)
    d = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1, n):
            d[i, j] = d[j, i] = np.sqrt(((positions[i] - positions[j]) ** 2).sum(1).mean())
    return d


def top_pose(scores, d, rule):
    kind, parameters = rule
    if kind == "score":
        return int(np.argmax(scores))
    if kind == "support":
        near = (d < parameters["R"]).astype(float)
        np.fill_diagonal(near, 0.0)
        t = parameters["T"]
        weight = np.exp((scores - scores.max()) / t) if t else np.ones_like(scores)
        return int(np.argmax(scores + parameters["lambda"] * near @ weight))
    heads = {}
    for i in np.argsort(-scores, kind="stable"):
        head = next((h for h in heads if d[i, h] < parameters["R"]), None)
        heads.setdefault(i if head is None else head, []).append(i)
    return max(heads, key=lambda h: np.sort(scores[heads[h]])[::-1][:parameters["M"]].sum())


def successes(data, types, rule):
    """Top-1 within 2 A per ligand type."""
    out = {t: 0 for t in set(types.values())}
    for entry, (scores, _, rmsds, distances) in data.items():
        out[types[entry]] += bool(rmsds[top_pose(scores, distances, rule)] <= 2.0)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("work", nargs="+", help="redock_bench.py --work folders")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    args = parser.parse_args()
    if not os.path.isdir(args.shared):
        print(f"skipped: {args.shared} is absent")
        return 0
    with tempfile.TemporaryDirectory() as scratch:
        crystals = crystal_ligands(args.shared, scratch)
    data = {}
    for folder in args.work:
        for entry, (scores, positions, rmsds) in complex_poses(folder, crystals).items():
            data[entry] = (scores, positions, rmsds, pose_distances(positions))
    types = {entry: crystals[entry][0] for entry in data}
    order = sorted(set(types.values()))
    among = sum(bool(rmsds.min() <= 2.0) for _, _, rmsds, _ in data.values())
    print(f"{len(data)} complexes; a pose within 2 A among their poses: {among}")
    grid = [("score", {})]
    for r in (1.5, 2.0, 3.0, 4.0):
        grid += [("support", {"R": r, "lambda": w, "T": t})
                 for w in (0.01, 0.02, 0.05, 0.1, 0.2, 0.5) for t in (None, 0.1, 0.3, 1.0)]
        grid += [("cluster", {"R": r, "M": m}) for m in (1, 2, 3, 5, 10)]
    table = [successes(data, types, rule) for rule in grid]
    print(f"{'rule':50s} " + " ".join(f"{t:>11s}" for t in order) + "   all")
    for rule, per_type in zip(grid, table):
        print(f"{rule[0] + ' ' + json.dumps(rule[1]):50s} "
              + " ".join(f"{per_type[t]:11d}" for t in order) + f" {sum(per_type.values()):5d}")
    held = 0
    for t in order:
        chosen = max(range(len(grid)),
                     key=lambda k: (sum(v for u, v in table[k].items() if u != t), -k))
        held += table[chosen][t]
        print(f"held out {t}: chosen {grid[chosen][0]} {json.dumps(grid[chosen][1])}, "
              f"{table[chosen][t]} (the score alone: {table[0][t]})")
    print(f"held out, all types: {held} of {len(data)} (the score alone: {sum(table[0].values())})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
