#!/usr/bin/env python3
"""Time of a ligand pair from molecule files on thermolysin crystal ligands: through the library
API (the Python module, surfcomp.match(a.sdf, b.sdf)) with one ligand's surface and description,
or with --cli through the program (`surfcomp match A.sdf B.sdf -o result.json`, the whole process)
beside Open3DAlign (RDKit's GetO3A with MMFF typing, from the same files, in this process) and
`surfcomp --version`, in the same run (issue 27's targets: 30 ms a pair through the CLI, 10 ms
for --version, 15 ms a description).

Run with the system Python on one core, the module on its path (scripts/demo.sh puts it there)
unless --cli is given:
    taskset -c 0 /usr/bin/python3 bench/ligand_pair_bench.py [--threads 1] [--repeat 5]
    taskset -c 0 /usr/bin/python3 bench/ligand_pair_bench.py --cli build/release/tools/surfcomp
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PAIRS = (("1THL", "4TMN"), ("1TLP", "1TMN"))
DEFAULT = Path(__file__).resolve().parents[2] / "shared" / "datasets" / "thermolysin" / "ligands-common-frame"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ligands", type=Path, default=DEFAULT, help="folder of NAME_ligand.sdf files")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--cli", type=Path, help="time this surfcomp program, whole process, beside Open3DAlign")
    args = parser.parse_args()
    if not args.ligands.is_dir():
        print(f"ligand_pair_bench: {args.ligands} not found; skipped", file=sys.stderr)
        return 0
    path = lambda name: args.ligands / f"{name}_ligand.sdf"
    if args.cli:
        return time_cli(args, path)
    import surfcomp
    times = []
    for a, b in PAIRS:
        surfcomp.match(path(a), path(b), threads=args.threads)  # warm
        for _ in range(args.repeat):
            start = time.perf_counter()
            surfcomp.match(path(a), path(b), threads=args.threads)
            times.append(1e3 * (time.perf_counter() - start))
    print(f"ligand pair from SDF files, {args.threads} thread(s): median {statistics.median(times):.1f} ms, "
          f"min {min(times):.1f} ms over {len(times)} runs of {len(PAIRS)} pairs")
    surface_times, describe_times = [], []
    for _ in range(args.repeat):
        start = time.perf_counter()
        surface = surfcomp.build_surface(path("1THL"))
        middle = time.perf_counter()
        surfcomp.describe(surface, threads=args.threads)
        surface_times.append(1e3 * (middle - start))
        describe_times.append(1e3 * (time.perf_counter() - middle))
    print(f"1THL ligand: surface {statistics.median(surface_times):.1f} ms, "
          f"description {statistics.median(describe_times):.1f} ms (medians)")
    return 0


def process_ms(command):
    """Wall time of one run of command, in ms; the run must succeed."""
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return 1e3 * (time.perf_counter() - start)


def o3a_ms(reference, probe):
    """Open3DAlign of probe onto reference from their files: read, hydrogens, MMFF typing, align."""
    from rdkit import Chem
    from rdkit.Chem import AllChem, rdMolAlign

    start = time.perf_counter()
    mols = [Chem.AddHs(Chem.MolFromMolFile(str(f)), addCoords=True) for f in (reference, probe)]
    props = [AllChem.MMFFGetMoleculeProperties(m) for m in mols]
    rdMolAlign.GetO3A(mols[1], mols[0], props[1], props[0]).Align()
    return 1e3 * (time.perf_counter() - start)


def time_cli(args, path):
    cli = str(args.cli.resolve())
    version = [process_ms([cli, "--version"]) for _ in range(10 * args.repeat)]
    pair, o3a = [], []
    with tempfile.TemporaryDirectory() as work:
        result = str(Path(work) / "result.json")
        for a, b in PAIRS:
            command = [cli, "match", str(path(a)), str(path(b)), "-o", result, "-q"]
            process_ms(command)  # warm the page cache
            o3a_ms(path(a), path(b))
            for _ in range(args.repeat):
                pair.append(process_ms(command))
                o3a.append(o3a_ms(path(a), path(b)))
    print(f"surfcomp --version, whole process: median {statistics.median(version):.1f} ms, min {min(version):.1f} ms")
    print(f"ligand pair from SDF files through the CLI, whole process on the CPUs given (taskset): "
          f"median {statistics.median(pair):.1f} ms, min {min(pair):.1f} ms over {len(pair)} runs of {len(PAIRS)} pairs")
    print(f"Open3DAlign (MMFF) of the same pairs from the same files, in process: "
          f"median {statistics.median(o3a):.1f} ms, min {min(o3a):.1f} ms")
    print(f"ratio surfcomp CLI / Open3DAlign (medians): {statistics.median(pair) / statistics.median(o3a):.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
