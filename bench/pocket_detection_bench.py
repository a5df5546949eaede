#!/usr/bin/python3
"""Pocket detection without a ligand (`surfcomp pockets`) on structures whose ligand is known.

For each structure the ligand is removed by the detector itself (it reads ATOM records only),
and the ligand's heavy atoms, read here from the file, say where the site is. A pocket finds the
site when its centre lies within 4 A of the ligand's centre (DCC), when its centre lies within
4 A of any ligand heavy atom (DCA, the criterion of most published detector figures), or when at least half the ligand's heavy atoms lie inside its alpha
spheres. Reported: top-1 and top-3 success by each criterion, the ligand fraction covered by the
best of the top 3, and the time per structure.

Sets: the 36 structures of ../shared/datasets/kahraman-dev (entries.txt names each ligand), the
five thermolysin complexes, and the 100 of ../shared/datasets/homogeneous (ten other ligand
types). Beside each rank-1 pocket's volume, the ligand's own (the union of its heavy atoms' van
der Waals balls, 1.7 A, on a 0.4 A grid) and their ratio.

Ranking terms, measured from the same pockets (issue 48): each pocket's value
buriedness * spheres^A * (1 + H hydrophobic), where buriedness is the mean over its alpha
spheres, spheres their count and hydrophobic the fraction of its lining residues that are
aliphatic or aromatic; A = 1, H = 0 is the program's own score. The rule (A, H) with the best
mean of DCA top-1 and top-3 is chosen on kahraman-dev with thermolysin and scored on
homogeneous, and the other way round.

    /usr/bin/python3 bench/pocket_detection_bench.py --surfcomp build/release/tools/surfcomp \\
        [--shared ../shared/datasets] [--json detection.json] [pocket options...]

Options after the known ones go to `surfcomp pockets` unchanged.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

THERMOLYSIN = {"1THL": ["0DB"], "1TLP": ["RDF"], "1TMN": ["0ZN"], "3TMN": ["TRP", "VAL"],
               "4TMN": ["0PK"]}


def ligand_atoms(pdb, names, number=None, chain=None):
    """Heavy-atom positions of the HETATM residues named `names` (one residue when number and
    chain are given), first alternate location only, model 1."""
    atoms, seen = [], set()
    with open(pdb) as f:
        for line in f:
            if line.startswith("ENDMDL"):
                break
            if not line.startswith("HETATM") or line[17:20].strip() not in names:
                continue
            if number is not None and int(line[22:26]) != number:
                continue
            if chain is not None and line[21] != chain:
                continue
            element = line[76:78].strip() or line[12:14].strip()
            if element in ("H", "D"):
                continue
            key = (line[21], line[22:27], line[12:16])
            if key in seen:
                continue
            seen.add(key)
            atoms.append((float(line[30:38]), float(line[38:46]), float(line[46:54])))
    return atoms


def distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def covered(atoms, pocket):
    inside = sum(1 for a in atoms
                 if any(distance(a, s[:3]) <= s[3] for s in pocket["spheres"]))
    return inside / len(atoms)


HYDROPHOBIC = {"ALA", "VAL", "LEU", "ILE", "MET", "PHE", "TRP", "TYR", "PRO", "CYS"}
SIZE_POWERS = (0.0, 0.25, 0.5, 0.75, 1.0)
HYDROPHOBIC_WEIGHTS = (0.0, 0.5, 1.0, 2.0)


def ligand_volume(atoms, radius=1.7, step=0.4):
    """A^3 of the union of balls of `radius` around `atoms`, counted on a grid of `step`."""
    import numpy as np
    xyz = np.array(atoms)
    low, high = xyz.min(axis=0) - radius, xyz.max(axis=0) + radius
    axes = [np.arange(low[k], high[k] + step, step) for k in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    inside = np.zeros(len(grid), dtype=bool)
    for a in xyz:
        inside |= ((grid - a) ** 2).sum(axis=1) <= radius * radius
    return float(inside.sum()) * step ** 3


def rule_value(pocket, power, weight):
    residues = pocket["lining_residues"]
    hydrophobic = sum(1 for r in residues if r[:3] in HYDROPHOBIC) / max(1, len(residues))
    return pocket["buriedness"] * len(pocket["spheres"]) ** power * (1.0 + weight * hydrophobic)


def rule_ranks(pockets, dca, power, weight):
    """The DCA rank of the site when the pockets are ranked by the rule (ties: program order)."""
    order = sorted(range(len(pockets)), key=lambda k: (-rule_value(pockets[k], power, weight), k))
    return next((r + 1 for r, k in enumerate(order) if dca[k] <= 4.0), None)


def entry_cases(shared, name):
    """The structures of the site set `name` (entries.txt: PDB ligand residue-number chain),
    each with its listed ligand copy; none when the set is absent."""
    out = []
    entries = os.path.join(shared, name, "entries.txt")
    if not os.path.exists(entries):
        return out
    with open(entries) as f:
        for line in f:
            fields = line.split()
            if len(fields) < 4 or line.startswith("#"):
                continue
            pdb = os.path.join(shared, name, "pdb", fields[0] + ".pdb")
            out.append((name, fields[0], pdb,
                        ligand_atoms(pdb, [fields[1]], int(fields[2]), fields[3])))
    return out


def cases(shared):
    out = entry_cases(shared, "kahraman-dev")
    for code, names in THERMOLYSIN.items():
        pdb = os.path.join(shared, "thermolysin", code + ".pdb")
        out.append(("thermolysin", code, pdb, ligand_atoms(pdb, names)))
    return out + entry_cases(shared, "homogeneous")


def rule_figures(rows, rule):
    ranks = [r["rule_dca_ranks"][rule] for r in rows]
    top1 = sum(1 for k in ranks if k is not None and k <= 1) / len(rows)
    top3 = sum(1 for k in ranks if k is not None and k <= 3) / len(rows)
    return top1, top3


def choose_ranking(rows):
    """The ranking rule chosen on one side (kahraman-dev with thermolysin, or homogeneous) by the
    mean of DCA top-1 and top-3, scored on the other."""
    ok = [r for r in rows if "error" not in r]
    sides = {"kahraman-dev+thermolysin": [r for r in ok if r["set"] != "homogeneous"],
             "homogeneous": [r for r in ok if r["set"] == "homogeneous"]}
    if not all(sides.values()):
        return
    rules = list(ok[0]["rule_dca_ranks"])
    for chosen_on, held_out in (tuple(sides), tuple(reversed(list(sides)))):
        # Ties go to the program's own rule, then to the smaller size power.
        best = max(rules, key=lambda q: (sum(rule_figures(sides[chosen_on], q)),
                                         q == "1.0:0.0", -float(q.split(":")[0])))
        top1, top3 = rule_figures(sides[held_out], best)
        own1, own3 = rule_figures(sides[held_out], "1.0:0.0")
        power, weight = best.split(":")
        print(f"ranking chosen on {chosen_on}: size power {power}, hydrophobic weight {weight}; "
              f"held out on {held_out}: DCA top-1 {top1:.0%} top-3 {top3:.0%} (the program's "
              f"score: {own1:.0%} / {own3:.0%})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", required=True)
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--json")
    args, extra = parser.parse_known_args()
    if not os.path.isdir(args.shared):
        print(f"pocket_detection_bench: {args.shared} is absent; nothing to measure")
        return 0
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for group, code, pdb, ligand in cases(args.shared):
            out = os.path.join(work, code + ".json")
            start = time.perf_counter()
            run = subprocess.run([args.surfcomp, "pockets", pdb, "-o", out] + extra,
                                 capture_output=True, text=True)
            seconds = time.perf_counter() - start
            if run.returncode != 0:
                print(f"{code}: {run.stderr.strip()}", file=sys.stderr)
                rows.append({"set": group, "structure": code, "error": run.stderr.strip()})
                continue
            pockets = json.load(open(out))["pockets"]
            center = [sum(c) / len(ligand) for c in zip(*ligand)]
            dcc = [distance(center, p["center"]) for p in pockets]
            cover = [covered(ligand, p) for p in pockets]
            first_dcc = next((k + 1 for k, d in enumerate(dcc) if d <= 4.0), None)
            first_cover = next((k + 1 for k, c in enumerate(cover) if c >= 0.5), None)
            dca = [min(distance(a, p["center"]) for a in ligand) for p in pockets]
            first_dca = next((k + 1 for k, d in enumerate(dca) if d <= 4.0), None)
            rows.append({"set": group, "structure": code, "pockets": len(pockets),
                         "seconds": seconds, "dcc_rank": first_dcc, "dca_rank": first_dca,
                         "cover_rank": first_cover,
                         "best_dcc_top3": min(dcc[:3]) if dcc else None,
                         "best_cover_top3": max(cover[:3]) if cover else 0.0,
                         "top1_volume": pockets[0]["volume"] if pockets else None,
                         "ligand_volume": ligand_volume(ligand),
                         "rule_dca_ranks": {f"{a}:{h}": rule_ranks(pockets, dca, a, h)
                                            for a in SIZE_POWERS
                                            for h in HYDROPHOBIC_WEIGHTS}})
            r = rows[-1]
            print(f"{group:13s} {code}: {len(pockets):3d} pockets, DCC rank {first_dcc}, "
                  f"DCA rank {first_dca}, "
                  f"cover rank {first_cover}, best top-3 cover {r['best_cover_top3']:.2f}, "
                  f"{seconds:.2f} s", flush=True)
    for group in ("kahraman-dev", "thermolysin", "homogeneous", None):
        chosen = [r for r in rows if "error" not in r and (group is None or r["set"] == group)]
        if not chosen:
            continue
        n = len(chosen)

        def share(key, top):
            return sum(1 for r in chosen if r[key] is not None and r[key] <= top) / n

        print(f"{group or 'all':13s} n={n}: DCC<=4A top-1 {share('dcc_rank', 1):.0%} "
              f"top-3 {share('dcc_rank', 3):.0%}; DCA<=4A top-1 {share('dca_rank', 1):.0%} "
              f"top-3 {share('dca_rank', 3):.0%}; half the ligand inside top-1 "
              f"{share('cover_rank', 1):.0%} top-3 {share('cover_rank', 3):.0%}; "
              f"median {sorted(r['seconds'] for r in chosen)[n // 2]:.2f} s per structure")
        ratios = sorted(r["top1_volume"] / r["ligand_volume"] for r in chosen
                        if r["top1_volume"])
        if ratios:
            volumes = sorted(r["top1_volume"] for r in chosen if r["top1_volume"])
            print(f"{'':13s} rank-1 volume: median {volumes[len(volumes) // 2]:.0f} A^3, "
                  f"{ratios[len(ratios) // 2]:.1f} x the ligand's; within 2x for "
                  f"{sum(1 for x in ratios if 0.5 <= x <= 2.0)}/{n}")
    choose_ranking(rows)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
