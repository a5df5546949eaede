#!/usr/bin/python3
"""Redocking: each crystal ligand, moved away, docked back into its own structure.

Sets (--set): thermolysin (four complexes of ../shared/datasets/thermolysin; 3TMN's ligand is
two residues, which --site-ligand cannot name as one, and is left out) and kahraman (the 36
entries of kahraman-dev: ATP, HEM and FMN, each the copy entries.txt names, its bond orders
perceived by Open Babel from the PDB residue, bonds to metals cut so that RDKit reads it).

Each ligand, in its crystal conformer, is moved by a random rigid motion (a uniform random
rotation and a translation of 10 A per axis, numpy's generator seeded by --seed) and docked
back into its structure with the structure's waters and its other copies of the ligand residue
removed:
- `surfcomp dock MOVED RECEPTOR.pdb --site-ligand RES --threads 1` (the site: the crystal
  ligand's neighbourhood, that residue taken out);
- with --vina, AutoDock Vina (`vina --cpu 1 --seed 1`, exhaustiveness 8) in the same run, on
  PDBQT files Open Babel makes (`obabel -xr` for the receptor without the ligand, `obabel -h -r`
  for the moved ligand's largest fragment: Vina docks one) and a box around the crystal
  ligand's atoms 4 A beyond them on each side.

Vina's answer does not depend on surfcomp's commit: with --vina-cache DIR each complex's Vina
result (its poses and CPU time, keyed by complex and the moved ligand's file, whose motion
depends on the seed and on the sets drawn before it) is kept in DIR and read back by later
runs, so that a run too long for one sitting (5-13 minutes per complex) can be finished in
several; --vina-only runs Vina alone, --only ENTRY,... a few complexes.

With --crystal, surfcomp also optimises the crystal ligand's own pose on its score (`dock
CRYSTAL RECEPTOR --local-only`), and each miss is told apart: a search's miss when that optimum
outscores the top pose (the search did not reach it), a score's miss when it does not.

Reported per complex and program: the heavy-atom RMSD of the top pose to the crystal pose, the
best RMSD among the poses and the CPU time (the program's and its children's, on one core); then each program's top-1 success rate (RMSD
<= 2 A) and median time, and surfcomp's median time for the ligand's steps alone (a dock into
the prepared site: its timing_ms without the receptor's surface and field). The RMSD pairs atoms of one element by the assignment that minimises it
(Open Babel reorders a ligand's atoms in PDBQT), for both programs alike.

    /usr/bin/python3 bench/redock_bench.py --program build/release/tools/surfcomp \\
        [--set thermolysin|kahraman|all] [--vina] [--shared ../shared/datasets] \\
        [--seed 20261203] [--work /tmp/redock] [--vina-cache DIR] [--vina-only]
        [--only 1TMN,1A0I] [--crystal] [-- dock options]
"""

import argparse
import hashlib
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
from rdkit import Chem, RDLogger

RDLogger.DisableLog("rdApp.*")

THERMOLYSIN = (("1THL", "0DB"), ("1TLP", "RDF"), ("1TMN", "0ZN"), ("4TMN", "0PK"))
METALS = {"Fe", "Mg", "Mn", "Zn", "Co", "Cu", "Ni", "Ca"}
WATERS = {"HOH", "WAT", "DOD", "H2O"}


def random_rotation(rng):
    """A uniform random rotation: the Q of a Gaussian matrix's QR, signs fixed (Mezzadri)."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    return q if np.linalg.det(q) > 0 else -q


def assignment(cost):
    """The permutation p minimising sum cost[i, p[i]] (Hungarian method, square cost)."""
    n = cost.shape[0]
    u, v = np.zeros(n + 1), np.zeros(n + 1)
    match, way = np.zeros(n + 1, dtype=int), np.zeros(n + 1, dtype=int)
    for i in range(1, n + 1):
        match[0], column = i, 0
        low, used = np.full(n + 1, np.inf), np.zeros(n + 1, dtype=bool)
        while True:
            used[column] = True
            row, delta, nxt = match[column], np.inf, 0
            for j in range(1, n + 1):
                if used[j]:
                    continue
                reduced = cost[row - 1, j - 1] - u[row] - v[j]
                if reduced < low[j]:
                    low[j], way[j] = reduced, column
                if low[j] < delta:
                    delta, nxt = low[j], j
            for j in range(n + 1):
                if used[j]:
                    u[match[j]] += delta
                    v[j] -= delta
                else:
                    low[j] -= delta
            column = nxt
            if match[column] == 0:
                break
        while column:
            previous = way[column]
            match[column] = match[previous]
            column = previous
    out = np.zeros(n, dtype=int)
    for j in range(1, n + 1):
        out[match[j] - 1] = j - 1
    return out


def heavy_atoms(mol):
    """(elements, positions) of a molecule's heavy atoms."""
    keep = [a.GetIdx() for a in mol.GetAtoms() if a.GetAtomicNum() > 1]
    symbols = np.array([mol.GetAtomWithIdx(i).GetSymbol() for i in keep])
    return symbols, mol.GetConformer().GetPositions()[keep]


def rmsd(pose, reference):
    """Heavy-atom RMSD, atoms of one element paired by the assignment that minimises it. A pose
    without the reference's unbonded metal ions (Vina docks the largest fragment) is compared
    over the other atoms."""
    (pose_elements, x), (elements, y) = pose, reference
    if sorted(pose_elements) != sorted(elements):
        organic = ~np.isin(elements, list(METALS))
        elements, y = elements[organic], y[organic]
        if sorted(pose_elements) != sorted(elements):
            return float("nan")
    total = 0.0
    for element in set(elements):
        a, b = x[pose_elements == element], y[elements == element]
        cost = ((a[:, None, :] - b[None, :, :]) ** 2).sum(2)
        total += cost[np.arange(len(a)), assignment(cost)].sum()
    return float(np.sqrt(total / len(elements)))


def without_metal_bonds(mol):
    editable = Chem.RWMol(mol)
    for bond in list(mol.GetBonds()):
        if {bond.GetBeginAtom().GetSymbol(), bond.GetEndAtom().GetSymbol()} & METALS:
            editable.RemoveBond(bond.GetBeginAtomIdx(), bond.GetEndAtomIdx())
    out = editable.GetMol()
    Chem.SanitizeMol(out)
    return out


def thermolysin_cases(shared, work):
    folder = os.path.join(shared, "thermolysin")
    for entry, residue in THERMOLYSIN:
        crystal = Chem.MolFromMolFile(os.path.join(folder, "ligands-original",
                                                   f"ligand{entry}.sdf"), removeHs=False)
        yield entry, residue, crystal, os.path.join(folder, f"{entry}.pdb")


def kahraman_cases(shared, work):
    folder = os.path.join(shared, "kahraman-dev")
    with open(os.path.join(folder, "entries.txt")) as f:
        entries = [line.split() for line in f if line.strip()]
    for entry, residue, number, chain, altloc in entries:
        altlocs = {" ", "A" if altloc == "-" else altloc}
        receptor, ligand = [], []
        with open(os.path.join(folder, "pdb", f"{entry}.pdb")) as f:
            for line in f:
                if not line.startswith(("ATOM", "HETATM")):
                    if line.startswith(("END", "TER")):
                        receptor.append(line)
                    continue
                name = line[17:20].strip()
                if name in WATERS or line[16] not in altlocs:
                    continue
                if name == residue:
                    if line[21] == chain and int(line[22:26]) == int(number):
                        ligand.append(line)
                        receptor.append(line)
                    continue
                receptor.append(line)
        receptor_file = os.path.join(work, f"{entry}_receptor.pdb")
        with open(receptor_file, "w") as f:
            f.writelines(receptor)
        ligand_pdb = os.path.join(work, f"{entry}_ligand.pdb")
        with open(ligand_pdb, "w") as f:
            f.writelines(ligand + ["END\n"])
        ligand_sdf = os.path.join(work, f"{entry}_ligand.sdf")
        subprocess.run(["obabel", ligand_pdb, "-O", ligand_sdf], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        crystal = Chem.MolFromMolFile(ligand_sdf, sanitize=False, removeHs=False)
        try:
            crystal = without_metal_bonds(crystal)
        except Exception as error:  # noqa: BLE001 - RDKit raises several kinds
            print(f"{entry}: left out, RDKit cannot read its ligand ({error})")
            continue
        yield entry, residue, crystal, receptor_file


# The steps of a dock's timing_ms that prepare the receptor's site; the others dock the ligand
# into the prepared site.
SITE_STEPS = {"receptor surface and description", "receptor field"}


def children_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_surfcomp(program, moved_file, receptor, residue, work, entry, extra):
    """The poses, the CPU time and the time of the ligand's steps alone (a dock into the
    prepared site, from the result's timing_ms)."""
    poses_file = os.path.join(work, f"{entry}_poses.sdf")
    result_file = os.path.join(work, f"{entry}_dock.json")
    start = children_cpu_seconds()
    subprocess.run([program, "dock", moved_file, receptor, "--site-ligand", residue,
                    "-o", poses_file, "--json", result_file, "--threads", "1"] + extra,
                   check=True, stdout=subprocess.DEVNULL)
    seconds = children_cpu_seconds() - start
    with open(result_file) as f:
        result = json.load(f)
    timing = result["timing_ms"]
    prepared = sum(ms for step, ms in timing.items() if step not in SITE_STEPS) / 1000.0
    top_score = result["poses"][0]["score"] if result["poses"] else float("nan")
    return list(Chem.SDMolSupplier(poses_file, removeHs=False)), seconds, prepared, top_score


def crystal_optimum(program, crystal, receptor, residue, work, entry, extra):
    """The crystal pose optimised on surfcomp's score (--local-only): its score, whether it
    intersects the receptor, and its RMSD to the crystal pose."""
    crystal_file = os.path.join(work, f"{entry}_crystal.sdf")
    Chem.MolToMolFile(crystal, crystal_file)
    poses_file = os.path.join(work, f"{entry}_crystal_local.sdf")
    result_file = os.path.join(work, f"{entry}_crystal_local.json")
    subprocess.run([program, "dock", crystal_file, receptor, "--site-ligand", residue,
                    "--local-only", "-o", poses_file, "--json", result_file, "--threads", "1"]
                   + own_pose_options(extra), check=True, stdout=subprocess.DEVNULL)
    with open(result_file) as f:
        optimum = json.load(f)["poses"][0]
    pose = next(iter(Chem.SDMolSupplier(poses_file, removeHs=False)))
    return optimum["score"], optimum["intersects"], rmsd(heavy_atoms(pose), heavy_atoms(crystal))


def own_pose_options(options):
    """The dock options after --, without those of conformers (the crystal's pose is its own)."""
    out, skip = [], False
    for option in options:
        if skip:
            skip = False
        elif option in ("--conformers", "--conformer-seed"):
            skip = True
        elif not option.startswith(("--conformers=", "--conformer-seed=")):
            out.append(option)
    return out


def vina_cache_file(cache, entry, moved_file):
    """Where the cache keeps Vina's poses of `entry` docked from `moved_file`."""
    with open(moved_file, "rb") as f:
        # Without the title line, which names the work folder: the key is the moved ligand.
        digest = hashlib.sha1(b"".join(f.readlines()[1:])).hexdigest()[:16]
    return os.path.join(cache, f"{entry}_{digest}_vina.sdf")


def vina_missing(bench):
    """True, having said what to install, when Vina or Open Babel is not on the PATH."""
    missing = [p for p in ("vina", "obabel") if shutil.which(p) is None]
    if missing:
        print(f"{bench}: --vina needs {' and '.join(missing)} "
              "(apt install autodock-vina openbabel)", file=sys.stderr)
    return bool(missing)


def vina_box(crystal):
    """Vina's box options: the crystal ligand's atoms and 4 A beyond them on each side."""
    _, positions = heavy_atoms(crystal)
    centre = (positions.min(0) + positions.max(0)) / 2
    size = positions.max(0) - positions.min(0) + 8.0
    return ([f"--center_{a}={c:.3f}" for a, c in zip("xyz", centre)]
            + [f"--size_{a}={s:.3f}" for a, s in zip("xyz", size)])


def vina_receptor(receptor, residue, pdb, pdbqt):
    """The receptor as Vina reads it (`obabel -xr`), without the ligand residue's HETATMs."""
    with open(receptor) as f, open(pdb, "w") as out:
        out.writelines(line for line in f if not (line.startswith("HETATM")
                                                  and line[17:20].strip() == residue))
    subprocess.run(["obabel", pdb, "-xr", "-O", pdbqt], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def run_vina(moved_file, receptor, residue, crystal, work, entry, cache):
    """Vina's poses and CPU time; from the cache when it holds this complex and moved ligand."""
    kept = vina_cache_file(cache, entry, moved_file) if cache else None
    if kept and os.path.exists(kept):
        with open(kept + ".json") as f:
            seconds = json.load(f)["cpu_seconds"]
        return [m for m in Chem.SDMolSupplier(kept, sanitize=False, removeHs=False) if m], seconds
    receptor_pdbqt = os.path.join(work, f"{entry}_receptor.pdbqt")
    ligand_pdbqt = os.path.join(work, f"{entry}_moved.pdbqt")
    out_pdbqt = os.path.join(work, f"{entry}_vina.pdbqt")
    out_sdf = os.path.join(work, f"{entry}_vina.sdf")
    quiet = {"check": True, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    start = children_cpu_seconds()
    vina_receptor(receptor, residue, os.path.join(work, f"{entry}_vina_receptor.pdb"),
                  receptor_pdbqt)
    subprocess.run(["obabel", moved_file, "-h", "-r", "-O", ligand_pdbqt], **quiet)
    subprocess.run(["vina", "--receptor", receptor_pdbqt, "--ligand", ligand_pdbqt, "--cpu", "1",
                    "--seed", "1", "--exhaustiveness", "8", "--out", out_pdbqt] + vina_box(crystal), **quiet)
    seconds = children_cpu_seconds() - start
    subprocess.run(["obabel", out_pdbqt, "-O", out_sdf], **quiet)
    if kept:
        os.makedirs(cache, exist_ok=True)
        shutil.copyfile(out_sdf, kept + ".part")
        with open(kept + ".json", "w") as f:
            json.dump({"cpu_seconds": seconds}, f)
        os.replace(kept + ".part", kept)
    poses = [m for m in Chem.SDMolSupplier(out_sdf, sanitize=False, removeHs=False) if m]
    return poses, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--program", help="the surfcomp program (not with --vina-only)")
    parser.add_argument("--set", choices=("thermolysin", "kahraman", "all"), default="thermolysin")
    parser.add_argument("--vina", action="store_true", help="run AutoDock Vina too")
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--seed", type=int, default=20261203)
    parser.add_argument("--work", default=None, help="folder for the moved ligands and poses")
    parser.add_argument("--vina-cache", default=None,
                        help="folder keeping Vina's results between runs")
    parser.add_argument("--vina-only", action="store_true", help="run Vina alone")
    parser.add_argument("--only", default=None, help="these complexes alone, e.g. 1TMN,1A0I")
    parser.add_argument("--crystal", action="store_true",
                        help="also optimise the crystal pose on surfcomp's score: is a miss "
                             "the search's or the score's?")
    parser.add_argument("options", nargs="*", help="dock options after --, e.g. -- --poses 20")
    args = parser.parse_args()
    if not os.path.isdir(args.shared):
        print(f"skipped: {args.shared} is absent")
        return 0
    if args.vina_only:
        args.vina = True
    elif not args.program:
        parser.error("--program is required (unless --vina-only)")
    if args.vina and vina_missing("redock_bench"):
        return 2
    work = args.work or tempfile.mkdtemp(prefix="redock_")
    os.makedirs(work, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    sets = ("thermolysin", "kahraman") if args.set == "all" else (args.set,)
    programs = ("surfcomp", "vina") if args.vina else ("surfcomp",)
    if args.vina_only:
        programs = ("vina",)
    only = set(args.only.split(",")) if args.only else None
    print(f"{'complex':8s} " + " ".join(f"{p + ' top-1':>14s} {'best':>6s} {'s':>6s}"
                                        for p in programs)
          + (f" {'top score':>9s} {'crystal optimum':>15s} {'A':>5s}" if args.crystal else ""))
    misses = {"search": 0, "score": 0}  # with --crystal: surfcomp's misses, by what missed
    results = {p: [] for p in programs}
    in_site = []  # surfcomp's seconds per dock into the prepared site
    for name in sets:
        cases = thermolysin_cases if name == "thermolysin" else kahraman_cases
        for entry, residue, crystal, receptor in cases(args.shared, work):
            moved = Chem.Mol(crystal)
            rotation, shift = random_rotation(rng), rng.normal(scale=10.0, size=3)
            conformer = moved.GetConformer()
            for i, p in enumerate(conformer.GetPositions()):
                conformer.SetAtomPosition(i, (rotation @ p + shift).tolist())
            if only is not None and entry not in only:
                continue
            moved_file = os.path.join(work, f"{entry}_moved.sdf")
            Chem.MolToMolFile(moved, moved_file)
            reference = heavy_atoms(crystal)
            row, crystal_columns = f"{entry:8s} ", ""
            for program in programs:
                if program == "surfcomp":
                    poses, seconds, prepared, top_score = run_surfcomp(
                        args.program, moved_file, receptor, residue, work, entry,
                        list(args.options))
                    in_site.append(prepared)
                else:
                    poses, seconds = run_vina(moved_file, receptor, residue, crystal, work, entry,
                                              args.vina_cache)
                rmsds = [rmsd(heavy_atoms(p), reference) for p in poses]
                top = rmsds[0] if rmsds else float("nan")
                results[program].append((top, seconds))
                row += f"{top:14.2f} {min(rmsds, default=float('nan')):6.2f} {seconds:6.1f} "
                if program == "surfcomp" and args.crystal:
                    score, intersects, moved_by = crystal_optimum(
                        args.program, crystal, receptor, residue, work, entry, list(args.options))
                    crystal_columns = f"{top_score:9.3f} {score:15.3f} {moved_by:5.2f}"
                    if not top <= 2.0:
                        # The search's miss: an optimum within 2 A that the ranking would put
                        # first was not reached (no pose at all counts so too).
                        reachable = moved_by <= 2.0 and not intersects
                        search = reachable and not score <= top_score
                        misses["search" if search else "score"] += 1
            print(row + crystal_columns, flush=True)
    if in_site:
        print(f"surfcomp: median {np.median(in_site):.1f} s per dock into the prepared site "
              "(the ligand's steps of timing_ms)")
    if args.crystal and "surfcomp" in programs:
        print(f"surfcomp's misses: {misses['search']} the search's (the crystal pose's optimum "
              f"outscores the top pose), {misses['score']} the score's (it does not)")
    for program in programs:
        tops = [t for t, _ in results[program]]
        times = [s for _, s in results[program]]
        print(f"{program}: top-1 within 2 A {sum(t <= 2.0 for t in tops)}/{len(tops)}, "
              f"median {np.median(times):.1f} s per complex")
    return 0


if __name__ == "__main__":
    sys.exit(main())
