#!/usr/bin/python3
"""Pocket detection without a ligand (`surfcomp pockets`) on structures whose ligand is known.

For each structure the ligand is removed by the detector itself (it reads ATOM records only),
and the ligand's heavy atoms, read here from the file, say where the site is. A pocket finds the
site when its centre lies within 4 A of the ligand's centre (DCC), when its centre lies within
4 A of any ligand heavy atom (DCA, the criterion of most published detector figures), or when at least half the ligand's heavy atoms lie inside its alpha
spheres. Reported: top-1 and top-3 success by each criterion, the ligand fraction covered by the
best of the top 3, and the time per structure.

Sets: the 36 structures of ../shared/datasets/kahraman-dev (entries.txt names each ligand) and
the five thermolysin complexes.

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


def cases(shared):
    out = []
    entries = os.path.join(shared, "kahraman-dev", "entries.txt")
    with open(entries) as f:
        for line in f:
            fields = line.split()
            if len(fields) < 4 or line.startswith("#"):
                continue
            pdb = os.path.join(shared, "kahraman-dev", "pdb", fields[0] + ".pdb")
            out.append(("kahraman-dev", fields[0], pdb,
                        ligand_atoms(pdb, [fields[1]], int(fields[2]), fields[3])))
    for code, names in THERMOLYSIN.items():
        pdb = os.path.join(shared, "thermolysin", code + ".pdb")
        out.append(("thermolysin", code, pdb, ligand_atoms(pdb, names)))
    return out


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
                         "top1_volume": pockets[0]["volume"] if pockets else None})
            r = rows[-1]
            print(f"{group:13s} {code}: {len(pockets):3d} pockets, DCC rank {first_dcc}, "
                  f"DCA rank {first_dca}, "
                  f"cover rank {first_cover}, best top-3 cover {r['best_cover_top3']:.2f}, "
                  f"{seconds:.2f} s", flush=True)
    for group in ("kahraman-dev", "thermolysin", None):
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
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
