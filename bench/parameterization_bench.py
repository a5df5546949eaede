#!/usr/bin/env python3
"""Every parameterization of `surfcomp patch-map --methods all` over the critical-point patches of
real meshes: the closed CGAL data meshes of bench/mesh_registration_bench.py, each scaled so that
its area-weighted RMS radius is 12 units (the length unit `match --scale auto` gives a general
mesh), patches of the default radius (5 units) around --patches critical points per mesh (20,
evenly spread over cp-detect's order; those whose patch is no disk are left out).

Prints, per method, the median over all patches of the per-patch mean and largest angle
distortion (degrees), the mean and largest |ln area ratio|, flipped triangles and time per map,
and the share of patches with a flipped triangle.

Usage: /usr/bin/python3 bench/parameterization_bench.py --surfcomp build/release/tools/surfcomp
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import mesh_cases  # noqa: E402
from mesh_registration_bench import DEV, HELD_OUT  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", required=True, help="the surfcomp program")
    parser.add_argument("--meshes", default=str(HERE.parent / "datasets/cache/cgal/meshes"))
    parser.add_argument("--json", help="write every patch's figures here")
    parser.add_argument("--patches", type=int, default=20,
                        help="critical points per mesh, evenly spread over cp-detect's order")
    args = parser.parse_args()
    per_method, failures = {}, {}
    with tempfile.TemporaryDirectory() as work:
        work = pathlib.Path(work)
        for name in DEV + HELD_OUT:
            vertices, faces = mesh_cases.read_off(pathlib.Path(args.meshes) / f"{name}.off")
            areas = mesh_cases.face_areas(vertices, faces)
            centroids = vertices[faces].mean(1)
            centre = areas @ centroids / areas.sum()
            radius = np.sqrt(areas @ ((centroids - centre) ** 2).sum(1) / areas.sum())
            scaled = work / f"{name}.off"
            mesh_cases.write_off(scaled, (vertices - centre) * 12 / radius, faces)
            found = subprocess.run([args.surfcomp, "cp-detect", scaled, "-o", work / "cps.json"],
                                   capture_output=True, text=True)
            if found.returncode != 0:
                sys.exit(f"{name}: {found.stderr.strip()}")
            count = len(json.loads((work / "cps.json").read_text())["critical_points"])
            chosen = sorted({int(i) for i in np.linspace(0, count - 1, min(count, args.patches))})
            done = subprocess.run([args.surfcomp, "patch-map", scaled, "--methods", "all",
                                   "--threads", "1", "-o", work / name,
                                   *[a for i in chosen for a in ("--cp", str(i))]],
                                  capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit(f"{name}: {done.stderr.strip()}")
            points = json.loads((work / name / "patch_maps.json").read_text())["points"]
            count = 0
            for point in points:
                for m in point.get("methods", []):
                    per_method.setdefault(m["method"], []).append(dict(m, mesh=name))
                    if "failure" in m:
                        failures[m["method"]] = failures.get(m["method"], 0) + 1
                count += "methods" in point
            print(f"{name}: {count} patches", flush=True)
    print("\n| method | patches mapped | angle mean (deg) | angle max (deg) | area mean |ln r| "
          "| area max |ln r| | patches with a flip | ms per map |")
    print("|---|---|---|---|---|---|---|---|")
    for method, all_rows in per_method.items():
        rows = [r for r in all_rows if "failure" not in r]

        def med(key):
            return float(np.median([r[key] for r in rows]))
        flipped = np.mean([r["flipped"] > 0 for r in rows]) * 100
        print(f"| {method} | {len(rows)} | {med('angle_mean_degrees'):.2f} "
              f"| {med('angle_max_degrees'):.1f} | {med('area_mean_log'):.3f} "
              f"| {med('area_max_log'):.2f} | {flipped:.1f} % | {med('ms'):.3f} |"
          + (f" failed on {failures[method]}" if method in failures else ""))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(per_method, f)


if __name__ == "__main__":
    main()
