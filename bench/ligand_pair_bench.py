#!/usr/bin/env python3
"""Time of a ligand pair from molecule files through the library API (the Python module):
surfcomp.match(a.sdf, b.sdf) on thermolysin crystal ligands, and of one ligand's surface and
description, on the threads asked for (issue 13's targets: 40 ms a pair, 15 ms a description).

Run with the system Python, the module on its path (scripts/demo.sh puts it there), on one core:
    taskset -c 0 /usr/bin/python3 bench/ligand_pair_bench.py [--threads 1] [--repeat 5]
"""
import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import surfcomp

PAIRS = (("1THL", "4TMN"), ("1TLP", "1TMN"))
DEFAULT = Path(__file__).resolve().parents[2] / "shared" / "datasets" / "thermolysin" / "ligands-common-frame"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ligands", type=Path, default=DEFAULT, help="folder of NAME_ligand.sdf files")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    if not args.ligands.is_dir():
        print(f"ligand_pair_bench: {args.ligands} not found; skipped", file=sys.stderr)
        return 0
    path = lambda name: args.ligands / f"{name}_ligand.sdf"
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


if __name__ == "__main__":
    sys.exit(main())
