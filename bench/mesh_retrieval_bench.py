#!/usr/bin/env python3
"""Retrieval of partial, noisy scans among CGAL's data meshes: `surfcomp library build` of every
mesh of Debian's libcgal-demo data (datasets/fetch.sh puts them in datasets/cache/cgal/meshes),
then `surfcomp screen SCAN LIB --repair` of scans of the registration benchmark's meshes; with --peer,
Open3D FPFH + RANSAC + ICP against every mesh in the same run, ranked by its fitness.

A scan (bench/mesh_cases.py) is a crop of 30-50 % of a mesh's area, decimated to half its
triangles with Open3D, given Gaussian noise of 0.5-1 % of the diagonal and moved by a random
rigid motion. It is found when its source mesh (or a copy of it in the data: the same shape in the
same frame, found geometrically below) is the top hit (top-1) or among the first five (top-5).

Open3D is run as in bench/mesh_registration_bench.py, with the voxel set from the scan's own
diagonal (diagonal / 40), as a retrieval cannot know the source; a mesh's score is the fitness of
the ICP result (the fraction of the scan's points within 1.5 voxels of the mesh).

Usage (Debian's Python, the surfcomp program built):
  OMP_NUM_THREADS=1 /usr/bin/python3 bench/mesh_retrieval_bench.py [--seeds 2] [--peer]
      [--program build/ci/tools/surfcomp] [--threads 2] [--json out.json]
"""
import argparse
import csv
import json
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import mesh_cases  # noqa: E402
from mesh_registration_bench import DEV, HELD_OUT, fpfh_points, ransac_icp  # noqa: E402


def read_mesh(o3d, path):
    """Vertices and triangles of any mesh file Open3D reads (OFF polygons fanned)."""
    if path.suffix == ".off":
        try:
            return mesh_cases.read_off(path)
        except ValueError:  # colours or other extras: Open3D's reader
            pass
    mesh = o3d.io.read_triangle_mesh(str(path))
    return np.asarray(mesh.vertices).copy(), np.asarray(mesh.triangles).astype(np.int64)


def surface_distance(o3d, vertices, faces, points):
    """Distances from `points` to the triangles (vertices, faces)."""
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(vertices.astype(np.float32)),
                        o3d.core.Tensor(faces.astype(np.uint32)))
    return scene.compute_distance(o3d.core.Tensor(points.astype(np.float32))).numpy()


def copies_of(o3d, name, meshes):
    """The meshes that are `name`'s shape in its frame: bounding boxes within 1 % of the
    diagonal, and each one's vertices within 0.5 % of the diagonal of the other's surface on
    average (both ways)."""
    v, f = meshes[name]
    diag = mesh_cases.diagonal(v)
    found = {name}
    for other, (w, g) in meshes.items():
        if other == name or len(w) == 0 or len(g) == 0:
            continue
        if (np.abs(w.min(0) - v.min(0)).max() > 0.01 * diag
                or np.abs(w.max(0) - v.max(0)).max() > 0.01 * diag):
            continue
        if (surface_distance(o3d, v, f, w).mean() < 0.005 * diag
                and surface_distance(o3d, w, g, v).mean() < 0.005 * diag):
            found.add(other)
    return found


def open3d_scores(o3d, scan, meshes):
    """Open3D FPFH + RANSAC + ICP fitness of the scan on every mesh, and seconds."""
    voxel = mesh_cases.diagonal(scan) / 40
    start = time.perf_counter()
    source = fpfh_points(o3d, scan, voxel)
    scores = {}
    for name, (v, _) in meshes.items():
        target = fpfh_points(o3d, v, voxel) if len(v) >= 4 else None
        if target is None or len(target[0].points) < 4:
            scores[name] = 0.0
            continue
        scores[name] = ransac_icp(o3d, source, target, voxel).fitness
    return scores, time.perf_counter() - start


def rank_of(ranked, accepted):
    """1-based rank of the first accepted name in `ranked`, or None."""
    for i, name in enumerate(ranked):
        if name in accepted:
            return i + 1
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshes", default=str(HERE.parent / "datasets/cache/cgal/meshes"))
    parser.add_argument("--program", default=str(HERE.parent / "build/ci/tools/surfcomp"))
    parser.add_argument("--seeds", type=int, default=1, help="scans per mesh (seeds 1..N)")
    parser.add_argument("--threads", type=int, default=2, help="surfcomp screen --threads")
    parser.add_argument("--peer", action="store_true", help="also run Open3D on every scan")
    parser.add_argument("--only", help="comma-separated source meshes (default: all 25)")
    parser.add_argument("--library", help="reuse this library instead of building one")
    parser.add_argument("--json", help="write every scan's figures here")
    args = parser.parse_args()
    import open3d as o3d  # Debian python3-open3d

    folder = pathlib.Path(args.meshes)
    if not folder.is_dir():
        sys.exit(f"mesh_retrieval_bench: {folder} is missing; run datasets/fetch.sh")
    files = sorted(p for p in folder.iterdir() if p.suffix in (".off", ".ply", ".stl", ".obj"))
    work = pathlib.Path(tempfile.mkdtemp(prefix="surfcomp-retrieval-"))
    library = pathlib.Path(args.library) if args.library else work / "cgal.sclib"
    if not args.library:
        start = time.perf_counter()
        subprocess.run([args.program, "library", "build", str(folder), "-o", str(library),
                        "--repair", "--threads", str(args.threads)], check=True)
        print(f"library build: {len(files)} files in {time.perf_counter() - start:.1f} s",
              flush=True)
    # Keyed by file name: sphere.off, sphere.ply and sphere.stl are three meshes.
    meshes = {p.name: read_mesh(o3d, p) for p in files}
    names = DEV + HELD_OUT
    if args.only:
        names = [n for n in names if n in args.only.split(",")]
    rows = []
    for name in names:
        vertices, faces = meshes[f"{name}.off"]
        accepted = copies_of(o3d, f"{name}.off", meshes)
        for seed in range(1, args.seeds + 1):
            rng = np.random.default_rng(2000 + seed)
            case = mesh_cases.make_case(vertices, faces, seed, fraction=rng.uniform(0.3, 0.5),
                                        open3d=o3d)
            scan = work / f"{name}-{seed}.off"
            mesh_cases.write_off(scan, case.vertices, case.faces)
            hits = work / f"{name}-{seed}.csv"
            start = time.perf_counter()
            subprocess.run([args.program, "screen", str(scan), str(library), "-o", str(hits),
                            "--top", "0", "--threads", str(args.threads), "--repair", "-q"],
                           check=True)
            seconds = time.perf_counter() - start
            with open(hits) as f:
                table = list(csv.DictReader(f))
            ranked = [pathlib.Path(r["source"]).name for r in table]
            row = {"mesh": name, "seed": seed, "dev": name in DEV, "copies": sorted(accepted),
                   "area_fraction": case.area_fraction, "scan_vertices": len(case.vertices),
                   "rank": rank_of(ranked, accepted), "seconds": seconds,
                   "top": [(r["name"], round(float(r["score"]), 3)) for r in table[:5]]}
            if args.peer:
                scores, peer_seconds = open3d_scores(o3d, case.vertices, meshes)
                peer_ranked = sorted(scores, key=lambda n: (-scores[n], n))
                row["peer_rank"] = rank_of(peer_ranked, accepted)
                row["peer_seconds"] = peer_seconds
                row["peer_top"] = [(n, round(scores[n], 3)) for n in peer_ranked[:5]]
            rows.append(row)
            print(f"{name:14s} seed {seed} area {case.area_fraction:.2f}  surfcomp rank "
                  f"{row['rank']} ({seconds:.1f} s) top {row['top'][:3]}" +
                  (f"  open3d rank {row['peer_rank']} ({row['peer_seconds']:.1f} s)"
                   if args.peer else ""), flush=True)

    def figures(key, seconds_key, label):
        ranks = [r[key] for r in rows]
        top1 = sum(1 for k in ranks if k == 1)
        top5 = sum(1 for k in ranks if k is not None and k <= 5)
        print(f"| {label} | {100 * top1 / len(rows):.0f} % ({top1}) | {100 * top5 / len(rows):.0f} %"
              f" ({top5}) | {np.median([r[seconds_key] for r in rows]):.1f} |")

    print(f"\n{len(rows)} scans of {len(names)} meshes among {len(files)} meshes")
    print("| method | top-1 | top-5 | median time per scan (s) |")
    print("|---|---|---|---|")
    figures("rank", "seconds", f"surfcomp screen (--threads {args.threads})")
    if args.peer:
        figures("peer_rank", "peer_seconds", "Open3D FPFH+RANSAC+ICP (1 thread)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
