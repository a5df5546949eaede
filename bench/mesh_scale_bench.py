#!/usr/bin/env python3
"""The stage tools on one mesh at three scales: CGAL's bunny00.off (37,706 vertices) with its
diagonal at 0.25 (metres, as the Stanford bunny), 25 and 2500, each tool on one core
(`taskset -c 0`, --threads 1 where the tool takes it): surf-build, cp-detect, hsi-build and
patch-map --cp 0. Prints each run's wall time and peak memory, and whether cp-detect found the
same critical points (vertices) at every scale; exits 1 when it did not.

Usage: /usr/bin/python3 bench/mesh_scale_bench.py --surfcomp build/release/tools/surfcomp
"""
import argparse
import json
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import mesh_cases  # noqa: E402

DIAGONALS = {"metres": 0.25, "x100": 25.0, "x10000": 2500.0}


def timed(command):
    """Wall seconds and the child's peak memory (MB) of one run; exits on failure."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed: {done.stderr.strip()}")
    peak = max(before, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss) / 1024
    return seconds, peak


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", required=True, help="the surfcomp program")
    parser.add_argument("--mesh", default=str(HERE.parent / "datasets/cache/cgal/meshes/bunny00.off"))
    args = parser.parse_args()
    mesh = pathlib.Path(args.mesh)
    if not mesh.exists():
        print(f"mesh_scale_bench: skipped, {mesh} is not fetched (datasets/fetch.sh)")
        return 0
    vertices, faces = mesh_cases.read_off(mesh)
    diagonal = np.linalg.norm(vertices.max(0) - vertices.min(0))
    found = {}
    print(f"{mesh.name}: {len(vertices)} vertices, {len(faces)} faces")
    print(f"{'scale':8} {'tool':11} {'seconds':>8} {'peak MB':>8}")
    with tempfile.TemporaryDirectory() as work:
        work = pathlib.Path(work)
        for name, target in DIAGONALS.items():
            off = work / f"{name}.off"
            mesh_cases.write_off(off, (vertices - vertices.mean(0)) * target / diagonal, faces)
            runs = {
                "surf-build": ["surf-build", off, "-o", work / f"{name}.ply"],
                "cp-detect": ["cp-detect", off, "-o", work / f"{name}.json"],
                "hsi-build": ["hsi-build", off, "-o", work / f"{name}.hsi", "--threads", "1"],
                "patch-map": ["patch-map", off, "--cp", "0", "-o", work / name, "--threads", "1"],
            }
            for tool, arguments in runs.items():
                seconds, peak = timed(["taskset", "-c", "0", args.surfcomp, *arguments, "-q"])
                print(f"{name:8} {tool:11} {seconds:8.2f} {peak:8.0f}")
            points = json.loads((work / f"{name}.json").read_text())["critical_points"]
            found[name] = [p["vertex"] for p in points]
    same = all(v == found["metres"] for v in found.values())
    print(f"critical points: {len(found['metres'])} at every scale, "
          f"{'the same vertices' if same else 'DIFFERENT vertices'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
