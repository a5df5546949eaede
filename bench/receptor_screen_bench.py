#!/usr/bin/python3
"""Structure-based screening: kahraman-dev's binding sites screened against the set's ligands.

The 36 kahraman-dev ligands (ATP, HEM and FMN; each the copy entries.txt names, read as
redock_bench.py reads it: bond orders from Open Babel, bonds to metals cut) make one library of
RDKit conformers (`surfcomp library build --conformers N`, from their bonds: no crystal
coordinates). Each site of the chosen ligand type (--ligand, default ATP, as the issue asks) is
screened against it with `surfcomp screen --receptor STRUCTURE LIB --site-ligand RES` (the
structure without waters or the ligand's other copies); the ligands of its type are the actives
(its own among them, as conformers), the others the decoys. Reported per site: the ROC AUC of
the ranking and the rank of the site's own ligand; then the mean AUC and the median time.

With --vina, AutoDock Vina screens the same sites in the same run: each ligand, as one ETKDG
conformer of its bonds (RDKit, seed 42; Vina turns its torsions), made PDBQT by Open Babel (`obabel
-h -r`: the largest fragment, hydrogens added) and docked into the structure without the ligand
residue (`obabel -xr`) in a box 4 A beyond the site ligand's atoms (`vina --cpu 1 --seed 1
--exhaustiveness E`, E by --vina-exhaustiveness, default Vina's 8); the ligands are ranked by
their best affinity. Each dock's affinity and CPU time are kept in --vina-cache DIR (keyed by
site, ligand and exhaustiveness) and read back by later runs: a site costs Vina 36 docks (1-5
minutes each at 8), so the table can be filled over several sittings; --vina-only runs Vina
alone, --only ENTRY,... some sites (of any ligand type).

    /usr/bin/python3 bench/receptor_screen_bench.py --program build/release/tools/surfcomp \\
        [--ligand ATP|HEM|FMN|all] [--conformers 3] [--shared ../shared/datasets] \\
        [--work /tmp/receptor_screen] [--vina] [--vina-cache DIR] [--vina-exhaustiveness 8] \\
        [--vina-only] [--only 1A0I,1A49] [-- screen options, e.g. --candidates 10]
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from rdkit import Chem, RDLogger
from rdkit.Chem import AllChem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dud_screen_bench import roc_auc  # noqa: E402
from redock_bench import (children_cpu_seconds, kahraman_cases, vina_box,  # noqa: E402
                          vina_missing, vina_receptor)

RDLogger.DisableLog("rdApp.*")


def vina_ligands(cases, work):
    """Each ligand's PDBQT file for Vina: one ETKDG conformer of its bonds, the largest fragment
    with hydrogens (Open Babel)."""
    out = {}
    for entry, residue, crystal, _ in cases:
        name = f"{entry}_{residue}"
        mol = Chem.AddHs(Chem.Mol(crystal), addCoords=True)
        parameters = AllChem.ETKDGv3()
        parameters.randomSeed = 42
        if AllChem.EmbedMolecule(mol, parameters) != 0:
            print(f"note: ETKDG could not embed {name}; its crystal coordinates go to Vina")
            mol = Chem.AddHs(Chem.Mol(crystal), addCoords=True)
        sdf = os.path.join(work, f"{name}_vina_ligand.sdf")
        Chem.MolToMolFile(mol, sdf)
        pdbqt = os.path.join(work, f"{name}_vina_ligand.pdbqt")
        subprocess.run(["obabel", sdf, "-h", "-r", "-O", pdbqt], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        out[name] = pdbqt
    return out


def vina_screen(site, residue, crystal, receptor, ligands, work, cache, exhaustiveness):
    """Vina's best affinity (kcal/mol) per ligand name docked into the site, and its CPU
    seconds; each dock from the cache when it holds it."""
    quiet = {"check": True, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    receptor_pdbqt = os.path.join(work, f"{site}_vina_receptor.pdbqt")
    box = vina_box(crystal)
    affinities, seconds = {}, 0.0
    for name, ligand in ligands.items():
        kept = os.path.join(cache, f"{site}_{name}_e{exhaustiveness}.json") if cache else None
        if kept and os.path.exists(kept):
            with open(kept) as f:
                record = json.load(f)
        else:
            if not os.path.exists(receptor_pdbqt):
                vina_receptor(receptor, residue, os.path.join(work, f"{site}_vina_receptor.pdb"),
                              receptor_pdbqt)
            out_pdbqt = os.path.join(work, f"{site}_{name}_vina.pdbqt")
            start = children_cpu_seconds()
            subprocess.run(["vina", "--receptor", receptor_pdbqt, "--ligand", ligand, "--cpu", "1",
                            "--seed", "1", "--exhaustiveness", str(exhaustiveness),
                            "--out", out_pdbqt] + box, **quiet)
            record = {"cpu_seconds": children_cpu_seconds() - start, "affinity": None}
            with open(out_pdbqt) as f:
                for line in f:
                    if line.startswith("REMARK VINA RESULT:"):
                        record["affinity"] = float(line.split()[3])
                        break
            if kept:
                os.makedirs(cache, exist_ok=True)
                with open(kept + ".part", "w") as f:
                    json.dump(record, f)
                os.replace(kept + ".part", kept)
        # A ligand Vina placed nowhere ranks last.
        affinities[name] = record["affinity"] if record["affinity"] is not None else float("inf")
        seconds += record["cpu_seconds"]
    return affinities, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--program", help="the surfcomp program (not with --vina-only)")
    parser.add_argument("--ligand", default="ATP", help="the sites screened: ATP, HEM, FMN or all")
    parser.add_argument("--conformers", type=int, default=3)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--work", default=None, help="folder for the library and the tables")
    parser.add_argument("--vina", action="store_true", help="screen with AutoDock Vina too")
    parser.add_argument("--vina-only", action="store_true", help="Vina alone")
    parser.add_argument("--vina-cache", default=None, help="folder keeping Vina's docks")
    parser.add_argument("--vina-exhaustiveness", type=int, default=8)
    parser.add_argument("--only", default=None, help="these sites alone, e.g. 1A0I,1A49")
    parser.add_argument("options", nargs="*", help="screen options after --")
    args = parser.parse_args()
    if not os.path.isdir(os.path.join(args.shared, "kahraman-dev")):
        print(f"skipped: {args.shared}/kahraman-dev is absent")
        return 0
    args.vina = args.vina or args.vina_only
    if args.vina and vina_missing("receptor_screen_bench"):
        return 2
    work = args.work or tempfile.mkdtemp(prefix="receptor_screen_")
    os.makedirs(work, exist_ok=True)
    cases = list(kahraman_cases(args.shared, work))
    ligands = os.path.join(work, "ligands.sdf")
    writer = Chem.SDWriter(ligands)
    for entry, residue, crystal, _ in cases:
        crystal.SetProp("_Name", f"{entry}_{residue}")
        writer.write(crystal)
    writer.close()
    if not args.vina_only:
        if not args.program:
            parser.error("--program is required (unless --vina-only)")
        library = os.path.join(work, "ligands.sclib")
        subprocess.run([args.program, "library", "build", ligands, "--conformers",
                        str(args.conformers), "-o", library], check=True,
                       stdout=subprocess.DEVNULL)
    vina_ligand_files = vina_ligands(cases, work) if args.vina else {}
    only = set(args.only.split(",")) if args.only else None
    if only is not None:
        args.ligand = "all"  # the sites named, whatever their ligand
    results = {"surfcomp": ([], []), "vina": ([], [])}  # AUCs, seconds
    programs = (() if args.vina_only else ("surfcomp",)) + (("vina",) if args.vina else ())
    print(f"{'site':8s} " + " ".join(f"{p + ' AUC':>13s} {'own rank':>8s} {'s':>7s}"
                                     for p in programs))
    for entry, residue, crystal, receptor in cases:
        if args.ligand != "all" and residue != args.ligand:
            continue
        if only is not None and entry not in only:
            continue
        row = f"{entry:8s} "
        for program in programs:
            if program == "surfcomp":
                hits = os.path.join(work, f"{entry}_hits.csv")
                start = time.perf_counter()
                subprocess.run([args.program, "screen", "--receptor", receptor, library,
                                "--site-ligand", residue, "-o", hits, "--threads",
                                str(args.threads)] + list(args.options), check=True,
                               stdout=subprocess.DEVNULL)
                seconds = time.perf_counter() - start
                with open(hits) as f:
                    names = [record["name"] for record in csv.DictReader(f)]
            else:
                affinities, seconds = vina_screen(entry, residue, crystal, receptor,
                                                  vina_ligand_files, work, args.vina_cache,
                                                  args.vina_exhaustiveness)
                names = sorted(affinities, key=lambda name: (affinities[name], name))
            labels = [name.endswith("_" + residue) for name in names]
            if program == "surfcomp":
                auc = roc_auc(-np.arange(len(names)), labels)  # the order of hits.csv
            else:  # Vina's affinities (0.1 kcal/mol) tie: their mid-ranks count
                auc = roc_auc(np.array([-min(affinities[n], 1e9) for n in names]), labels)
            own = names.index(f"{entry}_{residue}") + 1 if f"{entry}_{residue}" in names else 0
            results[program][0].append(auc)
            results[program][1].append(seconds)
            row += f"{auc:13.3f} {own:8d} {seconds:7.1f} "
        print(row, flush=True)
    for program in programs:
        aucs, times = results[program]
        unit = "s per site" if program == "surfcomp" else "CPU s per site"
        print(f"{program}: {len(aucs)} sites ({args.ligand}) against {len(cases)} ligands: "
              f"mean AUC {np.mean(aucs):.3f}, median {np.median(times):.1f} {unit}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
