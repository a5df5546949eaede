#!/usr/bin/env python3
"""Cost of one screening-library entry, in one run on the CPUs given (taskset): surfcomp's own
time per entry from a conformer with coordinates (`surfcomp library build` of the records' own
coordinates; reading, screening sample, packing), beside RDKit's ETKDG + MMFF time per conformer
and USRCAT's descriptor time per conformer on the same molecules (issue 27's target: at most
3 ms of surfcomp time per conformer).

Run with the system Python (Debian's RDKit) on one core:
    taskset -c 0 /usr/bin/python3 bench/library_entry_bench.py --surfcomp build/release/tools/surfcomp
"""
import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# The 76 thermolysin inhibitors (../shared/datasets) and RDKit's 163 BZR ligands (datasets/fetch.sh).
DEFAULT_SETS = (ROOT.parent / "shared" / "datasets" / "sutherland" / "therm_3dqsar.sdf",
                ROOT / "datasets" / "cache" / "rdkit-data" / "bzr.sdf")


def surfcomp_ms(program, sdf, work):
    """surfcomp's core time per entry (its own summary) and the whole process's wall per entry."""
    library = Path(work) / (sdf.stem + ".sclib")
    start = time.perf_counter()
    run = subprocess.run([program, "library", "build", str(sdf), "-o", str(library), "--threads", "1"],
                         check=True, capture_output=True, text=True)
    wall = time.perf_counter() - start
    found = re.search(r"core time per entry: ([0-9.]+) ms", run.stdout + run.stderr)
    entries = re.search(r"-> ([0-9]+) entries", run.stdout + run.stderr)
    if not found or not entries:
        sys.exit(f"library_entry_bench: no summary from surfcomp library build:\n{run.stdout}{run.stderr}")
    return float(found.group(1)), 1e3 * wall / int(entries.group(1)), int(entries.group(1))


def rdkit_ms(sdf, conformers):
    """ETKDG + MMFF per conformer, and USRCAT per conformer, on the molecules of sdf."""
    from rdkit import Chem, RDLogger
    from rdkit.Chem import AllChem, rdDistGeom, rdMolDescriptors

    RDLogger.DisableLog("rdApp.*")
    molecules = [m for m in Chem.SDMolSupplier(str(sdf)) if m is not None]
    embed_s, embedded, usrcat_s, described = 0.0, 0, 0.0, 0
    for molecule in molecules:
        with_h = Chem.AddHs(molecule)
        params = rdDistGeom.ETKDGv3()
        params.randomSeed = 42
        start = time.perf_counter()
        ids = list(rdDistGeom.EmbedMultipleConfs(with_h, conformers, params))
        if ids:
            AllChem.MMFFOptimizeMoleculeConfs(with_h)
        embed_s += time.perf_counter() - start
        embedded += len(ids)
        heavy = Chem.RemoveHs(with_h)
        start = time.perf_counter()
        for conformer in heavy.GetConformers():
            rdMolDescriptors.GetUSRCAT(heavy, confId=conformer.GetId())
            described += 1
        usrcat_s += time.perf_counter() - start
    return 1e3 * embed_s / max(embedded, 1), 1e3 * usrcat_s / max(described, 1), len(molecules)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", type=Path, required=True, help="path of the surfcomp program")
    parser.add_argument("--sets", nargs="*", type=Path,
                        default=list(DEFAULT_SETS), help="SDF files with coordinates")
    parser.add_argument("--conformers", type=int, default=3, help="ETKDG conformers per molecule (default 3)")
    parser.add_argument("--repeat", type=int, default=3, help="surfcomp builds per set; the median is kept")
    args = parser.parse_args()
    sets = [s for s in args.sets if s.is_file()]
    for missing in set(args.sets) - set(sets):
        print(f"library_entry_bench: {missing} not found; skipped", file=sys.stderr)
    if not sets:
        return 0
    print("set                  molecules | surfcomp per entry: core, whole process | "
          "ETKDG+MMFF per conformer | USRCAT per conformer   (ms, one run)")
    with tempfile.TemporaryDirectory() as work:
        for sdf in sets:
            runs = [surfcomp_ms(str(args.surfcomp.resolve()), sdf, work) for _ in range(args.repeat)]
            core = statistics.median(r[0] for r in runs)
            whole = statistics.median(r[1] for r in runs)
            embed, usrcat, molecules = rdkit_ms(sdf, args.conformers)
            print(f"{sdf.stem:20s} {molecules:9d} | {core:8.2f} {whole:8.2f}                   | "
                  f"{embed:10.2f}               | {usrcat:8.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
