#!/usr/bin/env python3
"""Several queries fused against the same queries one at a time, on DUD targets.

Runs on the work folder of a `dud_screen_bench.py` run (`--work WORK`), whose WORK/TARGET holds
library.sclib, query_0.sdf ... query_4.sdf and scores.csv (names and active labels). For each
target it screens all the queries in one pass, once with `--fusion max` and once with
`--fusion mean` (`surfcomp screen query_0.sdf ... library.sclib --top 0`), and reports the ROC
AUC and EF1% of each query's own table (hits.queryK.csv, the rows its own screen gives), their
mean, and of the two fused rankings.

    /usr/bin/python3 bench/fusion_bench.py --surfcomp build/release/tools/surfcomp \\
        --work /work/dudfull/work --targets hivrt,na,ace,cdk2,fxa,ache --json fusion.json
"""
import argparse
import csv
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from dud_screen_bench import evaluate, log, mean, read_hits, run_command  # noqa: E402


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", type=Path, required=True, help="path of the surfcomp program")
    parser.add_argument("--work", type=Path, required=True, help="a dud_screen_bench.py work folder")
    parser.add_argument("--targets", default="hivrt,na,ace,cdk2,fxa,ache",
                        help="comma-separated targets (folders of WORK)")
    parser.add_argument("--threads", type=int, default=2, help="surfcomp's --threads (default 2)")
    parser.add_argument("--json", type=Path, default=None, help="write every figure to this JSON file")
    parser.add_argument("--screen-args", default="",
                        help='more options for every surfcomp screen, e.g. "--chemistry on"')
    return parser.parse_args()


def labels(target_dir):
    """The library's molecule names and the set of actives, from scores.csv."""
    with open(target_dir / "scores.csv", newline="") as stream:
        rows = list(csv.DictReader(stream))
    if not rows:
        raise SystemExit(f"fusion_bench: {target_dir / 'scores.csv'} has no molecules")
    return [row["name"] for row in rows], {row["name"] for row in rows if row["active"] == "1"}


def order_scores(path):
    """{name: score following the table's order} (dud_screen_bench.read_hits)."""
    return {name: row["order_score"] for name, row in read_hits(path).items()}


def fuse_target(args, target):
    target_dir = args.work / target
    names, actives = labels(target_dir)
    queries = sorted(target_dir.glob("query_*.sdf"), key=lambda p: int(p.stem.split("_")[1]))
    if not queries:
        raise SystemExit(f"fusion_bench: {target_dir} has no query_*.sdf")
    figures = {"queries": len(queries), "molecules": len(names), "actives": len(actives)}
    for fusion in ("max", "mean"):
        table = target_dir / f"fused_{fusion}.csv"
        log(f"{target}: {len(queries)} queries in one pass, --fusion {fusion}")
        start = time.monotonic()
        run_command([args.surfcomp, "screen", *queries, target_dir / "library.sclib", "-o", table,
                     "--top", 0, "--fusion", fusion, "--threads", args.threads, *args.screen_args.split()])
        figures[f"screen_s_{fusion}"] = time.monotonic() - start
        figures[fusion] = evaluate(order_scores(table), names, actives)
        if fusion == "max":
            single = [evaluate(order_scores(target_dir / f"fused_max.query{k + 1}.csv"), names, actives)
                      for k in range(len(queries))]
            figures["single"] = single
            figures["single_mean"] = {key: mean([s[key] for s in single]) for key in ("auc", "ef1")}
    return figures


def main():
    args = parse_args()
    results = {target: fuse_target(args, target) for target in args.targets.split(",")}
    print(f"{'target':8} {'single AUC':>10} {'max AUC':>8} {'mean AUC':>9} "
          f"{'single EF1%':>11} {'max EF1%':>9} {'mean EF1%':>10}")
    for target, r in results.items():
        print(f"{target:8} {r['single_mean']['auc']:10.3f} {r['max']['auc']:8.3f} {r['mean']['auc']:9.3f} "
              f"{r['single_mean']['ef1']:11.1f} {r['max']['ef1']:9.1f} {r['mean']['ef1']:10.1f}")
    overall = {kind: {key: mean([r[kind][key] if kind != "single" else r["single_mean"][key]
                                 for r in results.values()]) for key in ("auc", "ef1")}
               for kind in ("single", "max", "mean")}
    print(f"{'mean':8} {overall['single']['auc']:10.3f} {overall['max']['auc']:8.3f} "
          f"{overall['mean']['auc']:9.3f} {overall['single']['ef1']:11.1f} {overall['max']['ef1']:9.1f} "
          f"{overall['mean']['ef1']:10.1f}")
    if args.json:
        args.json.write_text(json.dumps({"targets": results, "mean": overall}, indent=1))


if __name__ == "__main__":
    main()
