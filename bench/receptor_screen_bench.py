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

    /usr/bin/python3 bench/receptor_screen_bench.py --program build/release/tools/surfcomp \\
        [--ligand ATP|HEM|FMN|all] [--conformers 3] [--shared ../shared/datasets] \\
        [--work /tmp/receptor_screen] [-- screen options, e.g. --candidates 10]
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from rdkit import Chem, RDLogger

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dud_screen_bench import roc_auc  # noqa: E402
from redock_bench import kahraman_cases  # noqa: E402

RDLogger.DisableLog("rdApp.*")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--program", required=True, help="the surfcomp program")
    parser.add_argument("--ligand", default="ATP", help="the sites screened: ATP, HEM, FMN or all")
    parser.add_argument("--conformers", type=int, default=3)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--work", default=None, help="folder for the library and the tables")
    parser.add_argument("options", nargs="*", help="screen options after --")
    args = parser.parse_args()
    if not os.path.isdir(os.path.join(args.shared, "kahraman-dev")):
        print(f"skipped: {args.shared}/kahraman-dev is absent")
        return 0
    work = args.work or tempfile.mkdtemp(prefix="receptor_screen_")
    os.makedirs(work, exist_ok=True)
    cases = list(kahraman_cases(args.shared, work))
    ligands = os.path.join(work, "ligands.sdf")
    writer = Chem.SDWriter(ligands)
    for entry, residue, crystal, _ in cases:
        crystal.SetProp("_Name", f"{entry}_{residue}")
        writer.write(crystal)
    writer.close()
    library = os.path.join(work, "ligands.sclib")
    subprocess.run([args.program, "library", "build", ligands, "--conformers",
                    str(args.conformers), "-o", library], check=True, stdout=subprocess.DEVNULL)
    aucs, times = [], []
    print(f"{'site':8s} {'AUC':>6s} {'own rank':>8s} {'s':>7s}")
    for entry, residue, _, receptor in cases:
        if args.ligand != "all" and residue != args.ligand:
            continue
        hits = os.path.join(work, f"{entry}_hits.csv")
        start = time.perf_counter()
        subprocess.run([args.program, "screen", "--receptor", receptor, library,
                        "--site-ligand", residue, "-o", hits, "--threads", str(args.threads)]
                       + list(args.options), check=True, stdout=subprocess.DEVNULL)
        seconds = time.perf_counter() - start
        with open(hits) as f:
            names = [row["name"] for row in csv.DictReader(f)]
        labels = [name.endswith("_" + residue) for name in names]
        auc = roc_auc(-np.arange(len(names)), labels)
        own = names.index(f"{entry}_{residue}") + 1 if f"{entry}_{residue}" in names else 0
        aucs.append(auc)
        times.append(seconds)
        print(f"{entry:8s} {auc:6.3f} {own:8d} {seconds:7.1f}", flush=True)
    print(f"{len(aucs)} sites ({args.ligand}) against {len(cases)} ligands: mean AUC "
          f"{np.mean(aucs):.3f}, median {np.median(times):.1f} s per site")
    return 0


if __name__ == "__main__":
    sys.exit(main())
