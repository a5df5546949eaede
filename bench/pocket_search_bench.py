#!/usr/bin/python3
"""Pocket search with detected pockets: each Kahraman dev site against every pocket of the set.

The 36 structures of ../shared/datasets/kahraman-dev go into one pocket library (`surfcomp
library build --pockets`, every pocket `surfcomp pockets` finds, no ligand used). Each site, as
its ligand defines it (spheres of 4 A around the ligand's heavy atoms, on the structure without
its HETATM records), is then screened against that library (`surfcomp screen --site-sphere`,
every row). A pocket holds a ligand type when its centre lies within 4 A of a heavy atom of the
structure's listed ligand (DCA) or at least half that ligand's heavy atoms lie inside its alpha
spheres (coverage; both as pocket_detection_bench.py). Reported, with the query's own structure
left out of its ranking:
  - top-1 and top-3: how often the first (first three) pocket holds the query's ligand type;
  - AUC over pockets: per query, the ROC AUC of the screen's ranking for the pockets holding the
    query's ligand type against every other pocket, then the mean over the queries, and the same
    against the other ligand-holding pockets only (the ligand-defined comparison's setting);
  - times: the library build and each screen.

    /usr/bin/python3 bench/pocket_search_bench.py --surfcomp build/release/tools/surfcomp \\
        [--shared ../shared/datasets] [--library pockets.sclib] [--work DIR] [--reuse] \\
        [--json out.json] [--detect 'POCKET OPTIONS'] [screen options...]

--library reuses a library built before (its pockets must be those of --detect's detection);
--reuse keeps the screens' tables already in --work (a rerun of the figures); options after the
known ones go to `surfcomp screen` unchanged.
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pocket_detection_bench import covered, distance, ligand_atoms  # noqa: E402


def entries(shared):
    out = []
    with open(os.path.join(shared, "kahraman-dev", "entries.txt")) as f:
        for line in f:
            fields = line.split()
            if len(fields) < 4 or line.startswith("#"):
                continue
            pdb = os.path.join(shared, "kahraman-dev", "pdb", fields[0] + ".pdb")
            out.append({"code": fields[0], "ligand": fields[1], "pdb": pdb,
                        "atoms": ligand_atoms(pdb, [fields[1]], int(fields[2]), fields[3])})
    return out


def protein_only(pdb, out):
    """The structure without HETATM records (model 1): the query's surface, its ligand gone."""
    with open(pdb) as f, open(out, "w") as o:
        for line in f:
            if line.startswith("ENDMDL"):
                break
            if not line.startswith("HETATM"):
                o.write(line)


def auc(ranks_positive, ranks_negative):
    """ROC AUC of a ranking (rank 1 best) for the positives against the negatives."""
    if not ranks_positive or not ranks_negative:
        return None
    wins = sum(1.0 if p < n else 0.5 if p == n else 0.0
               for p in ranks_positive for n in ranks_negative)
    return wins / (len(ranks_positive) * len(ranks_negative))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", required=True)
    parser.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                         "shared", "datasets"))
    parser.add_argument("--library")
    parser.add_argument("--work")
    parser.add_argument("--reuse", action="store_true")
    parser.add_argument("--json")
    parser.add_argument("--detect", default="",
                        help="pocket detection options for the library and the pockets' ligand "
                             "check, as one string (e.g. '--pocket-max-volume 600')")
    args, extra = parser.parse_known_args()
    detect = args.detect.split()
    if not os.path.isdir(os.path.join(args.shared, "kahraman-dev")):
        print(f"pocket_search_bench: {args.shared}/kahraman-dev is absent; nothing to measure")
        return 0
    work = args.work or tempfile.mkdtemp(prefix="pocket_search_")
    os.makedirs(work, exist_ok=True)
    sites = entries(args.shared)
    library = args.library or os.path.join(work, "pockets.sclib")
    if not args.library:
        start = time.perf_counter()
        subprocess.run([args.surfcomp, "library", "build", "--pockets",
                        os.path.join(args.shared, "kahraman-dev", "pdb"), "-o", library] + detect,
                       check=True)
        print(f"library built in {time.perf_counter() - start:.0f} s", flush=True)

    # Which pockets hold their structure's listed ligand (the library's names: CODE:pocketN).
    holds = {}
    for site in sites:
        out = os.path.join(work, site["code"] + ".pockets.json")
        if not (args.reuse and os.path.exists(out)):
            subprocess.run([args.surfcomp, "pockets", site["pdb"], "-o", out] + detect,
                           check=True, capture_output=True)
        for pocket in json.load(open(out))["pockets"]:
            dca = min(distance(a, pocket["center"]) for a in site["atoms"])
            inside = dca <= 4.0 or covered(site["atoms"], pocket) >= 0.5
            holds[f"{site['code']}:pocket{pocket['rank']}"] = site["ligand"] if inside else None

    rows = []
    for site in sites:
        query = os.path.join(work, site["code"] + ".protein.pdb")
        protein_only(site["pdb"], query)
        spheres = []
        for a in site["atoms"]:
            spheres += ["--site-sphere", f"{a[0]:.3f},{a[1]:.3f},{a[2]:.3f},4"]
        hits = os.path.join(work, site["code"] + ".hits.csv")
        seconds = None  # a table kept from an earlier run (--reuse) was not timed here
        if not (args.reuse and os.path.exists(hits)):
            start = time.perf_counter()
            subprocess.run([args.surfcomp, "screen", query, library, "-o", hits, "--top", "0"] +
                           spheres + extra, check=True, capture_output=True)
            seconds = time.perf_counter() - start
        ranked = [r["name"] for r in csv.DictReader(open(hits))
                  if not r["name"].startswith(site["code"] + ":")]
        positive = [k + 1 for k, name in enumerate(ranked) if holds.get(name) == site["ligand"]]
        others = [k + 1 for k, name in enumerate(ranked) if holds.get(name) != site["ligand"]]
        ligand_others = [k + 1 for k, name in enumerate(ranked)
                         if holds.get(name) not in (None, site["ligand"])]
        rows.append({"code": site["code"], "ligand": site["ligand"], "seconds": seconds,
                     "first": positive[0] if positive else None, "positives": len(positive),
                     "auc": auc(positive, others), "auc_ligand_sites": auc(positive, ligand_others),
                     "top": [(name, holds.get(name)) for name in ranked[:3]]})
        r = rows[-1]
        print(f"{site['code']} {site['ligand']}: first same-type pocket at rank {r['first']} of "
              f"{len(ranked)}, AUC {r['auc']:.3f} (ligand sites {r['auc_ligand_sites']:.3f}), "
              f"top 3 {r['top']}" + (f", {seconds:.0f} s" if seconds is not None else ""),
              flush=True)

    n = len(rows)
    top1 = sum(1 for r in rows if r["first"] == 1)
    top3 = sum(1 for r in rows if r["first"] is not None and r["first"] <= 3)
    mean_auc = sum(r["auc"] for r in rows if r["auc"] is not None) / n
    mean_ligand = sum(r["auc_ligand_sites"] for r in rows if r["auc_ligand_sites"] is not None) / n
    seconds = sorted(r["seconds"] for r in rows if r["seconds"] is not None)
    times = (f"; screen median {seconds[len(seconds) // 2]:.0f} s, max {seconds[-1]:.0f} s"
             if seconds else "")
    print(f"{n} queries, {len(holds)} pockets ({sum(1 for v in holds.values() if v)} hold their "
          f"structure's ligand): top-1 same ligand type {top1}/{n}, top-3 {top3}/{n}; mean AUC "
          f"{mean_auc:.3f} against every other pocket, {mean_ligand:.3f} against the other "
          f"ligand-holding pockets{times}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
