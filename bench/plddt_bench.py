#!/usr/bin/python3
"""What --min-plddt does to pocket detection on AlphaFold-style structures.

No AlphaFold model can be fetched here, so each crystal structure of kahraman-dev and the
thermolysin complexes is made into one (its ligand removed, as `surfcomp pockets` does):
  - every residue gets a pLDDT-like B-factor, high where it is buried (95 with 16 or more other
    C-alpha atoms within 10 A, falling linearly to 50 with none) and low at the chain ends (40
    over the first and last five residues), as AlphaFold's confidence falls on exposed loops and
    termini;
  - a disordered tail is appended: 40 glycine residues (N, CA, C, O) in a random walk of 3.8 A
    steps that keeps 4 to 9 A from the protein's atoms, starting just outside the last C-alpha, with pLDDT 30, like the low-confidence
    "spaghetti" AlphaFold draws for disordered segments. Such a tail lies on the surface and
    makes grooves that a detector takes for pockets.
Each model is searched with --min-plddt 0 (every residue) and with each cut given. Reported per
cut: DCA top-1 and top-3 of the crystal ligand's site (pocket centre within 4 A of a ligand heavy
atom), how many structures' rank-1 pocket touches the tail (a tail atom within 4 A of its
centre), and the median time. The walk is seeded by the structure's name: the models are the
same on every run.

    /usr/bin/python3 bench/plddt_bench.py --surfcomp build/release/tools/surfcomp \\
        [--shared ../shared/datasets] [--cuts 50 70] [--json plddt.json]
"""

import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pocket_detection_bench import cases, distance  # noqa: E402

TAIL_RESIDUES = 40
TAIL_PLDDT = 30.0


def protein_atoms(pdb):
    """The ATOM records of model 1 as (line, residue key, position)."""
    atoms = []
    with open(pdb) as f:
        for line in f:
            if line.startswith("ENDMDL"):
                break
            if line.startswith("ATOM"):
                atoms.append((line, (line[21], line[22:27]),
                              (float(line[30:38]), float(line[38:46]), float(line[46:54]))))
    return atoms


def plddt_by_residue(atoms):
    """Buried residues high, exposed ones lower, chain ends low."""
    ca = {key: xyz for line, key, xyz in atoms if line[12:16].strip() == "CA"}
    keys = list(dict.fromkeys(key for _, key, _ in atoms))
    by_chain = {}
    for key in keys:
        by_chain.setdefault(key[0], []).append(key)
    values = {}
    for key in keys:
        if key not in ca:
            values[key] = 50.0
            continue
        near = sum(1 for other, xyz in ca.items() if other != key and distance(ca[key], xyz) < 10)
        values[key] = 50.0 + 45.0 * min(near, 16) / 16.0
    for chain in by_chain.values():
        for key in chain[:5] + chain[-5:]:
            values[key] = 40.0
    return values


def tail(atoms, name):
    """A disordered glycine tail from the last C-alpha: positions of N, CA, C, O per residue."""
    rng = random.Random(name)
    positions = [xyz for _, _, xyz in atoms]
    cas = [xyz for line, _, xyz in atoms if line[12:16].strip() == "CA"]
    # The walk starts outside the protein, straight out from its centre through the last CA.
    centre = [sum(p[k] for p in positions) / len(positions) for k in range(3)]
    out = [cas[-1][k] - centre[k] for k in range(3)]
    norm = math.sqrt(sum(x * x for x in out)) or 1.0
    current = cas[-1]
    for t in range(1, 40):
        current = [cas[-1][k] + t * out[k] / norm for k in range(3)]
        if min(distance(current, p) for p in positions) >= 4.5:
            break
    residues = []
    for _ in range(TAIL_RESIDUES):
        for _attempt in range(200):
            u = [rng.gauss(0, 1) for _ in range(3)]
            norm = math.sqrt(sum(x * x for x in u))
            step = [current[k] + 3.8 * u[k] / norm for k in range(3)]
            gap = min(distance(step, p) for p in positions)
            if 4.0 <= gap <= 9.0 and all(distance(step, r[1]) >= 3.5 for r in residues):
                break
        else:
            break
        direction = [(step[k] - current[k]) / 3.8 for k in range(3)]
        n = [step[k] - 1.2 * direction[k] for k in range(3)]
        c = [step[k] + 1.3 * direction[k] for k in range(3)]
        o = [c[0] + 1.2, c[1], c[2]]
        residues.append((n, step, c, o))
        current = step
    return residues


def write_model(pdb, out, name):
    atoms = protein_atoms(pdb)
    values = plddt_by_residue(atoms)
    lines = [line[:60] + f"{values[key]:6.2f}" + line[66:] for line, key, _ in atoms]
    chain, number = "Z", 1
    serial = len(lines) + 1
    tail_atoms = []
    for residue in tail(atoms, name):
        for atom_name, xyz, element in zip((" N  ", " CA ", " C  ", " O  "), residue, "NCCO"):
            lines.append(f"ATOM  {serial % 100000:5d} {atom_name} GLY {chain}{number:4d}    "
                         f"{xyz[0]:8.3f}{xyz[1]:8.3f}{xyz[2]:8.3f}  1.00{TAIL_PLDDT:6.2f}"
                         f"          {element:>2s}\n")
            tail_atoms.append(xyz)
            serial += 1
        number += 1
    with open(out, "w") as f:
        f.writelines(line if line.endswith("\n") else line + "\n" for line in lines)
        f.write("END\n")
    return tail_atoms


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", required=True)
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--cuts", type=float, nargs="+", default=[50.0, 70.0])
    parser.add_argument("--json")
    args = parser.parse_args()
    if not os.path.isdir(args.shared):
        print(f"plddt_bench: {args.shared} is absent; nothing to measure")
        return 0
    chosen = [c for c in cases(args.shared) if c[0] != "homogeneous"]
    cuts = [0.0] + args.cuts
    rows = {cut: [] for cut in cuts}
    with tempfile.TemporaryDirectory() as work:
        for group, code, pdb, ligand in chosen:
            model = os.path.join(work, code + ".pdb")
            tail_atoms = write_model(pdb, model, code)
            for cut in cuts:
                out = os.path.join(work, f"{code}.{cut:g}.json")
                start = time.perf_counter()
                run = subprocess.run([args.surfcomp, "pockets", model, "-o", out,
                                      "--min-plddt", f"{cut:g}"], capture_output=True, text=True)
                seconds = time.perf_counter() - start
                if run.returncode != 0:
                    print(f"{code} cut {cut:g}: {run.stderr.strip()}", file=sys.stderr)
                    rows[cut].append({"structure": code, "error": run.stderr.strip()})
                    continue
                pockets = json.load(open(out))["pockets"]
                dca = [min(distance(a, p["center"]) for a in ligand) for p in pockets]
                rank = next((k + 1 for k, d in enumerate(dca) if d <= 4.0), None)
                on_tail = bool(pockets) and any(
                    distance(t, pockets[0]["center"]) <= 4.0 for t in tail_atoms)
                rows[cut].append({"structure": code, "set": group, "pockets": len(pockets),
                                  "dca_rank": rank, "rank1_on_tail": on_tail,
                                  "tail_atoms": len(tail_atoms), "seconds": seconds})
            print(f"{code}: " + ", ".join(
                f"cut {c:g} rank {rows[c][-1].get('dca_rank')}"
                f"{' (rank 1 on the tail)' if rows[c][-1].get('rank1_on_tail') else ''}"
                for c in cuts), flush=True)
    for cut in cuts:
        ok = [r for r in rows[cut] if "error" not in r]
        n = len(ok)
        if not n:
            continue
        top1 = sum(1 for r in ok if r["dca_rank"] and r["dca_rank"] <= 1)
        top3 = sum(1 for r in ok if r["dca_rank"] and r["dca_rank"] <= 3)
        tail_first = sum(1 for r in ok if r["rank1_on_tail"])
        median = sorted(r["seconds"] for r in ok)[n // 2]
        print(f"--min-plddt {cut:g}: n={n}, DCA top-1 {top1}/{n} ({top1 / n:.0%}), top-3 "
              f"{top3}/{n} ({top3 / n:.0%}); rank-1 pocket on the tail {tail_first}/{n}; median "
              f"{median:.2f} s")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({f"{c:g}": rows[c] for c in cuts}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
