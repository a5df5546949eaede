#!/usr/bin/env python3
"""Leave-one-target-out choice of a screening default among variants, as docs/decisions.md's
rule for defaults asks: for each target, the variant with the best mean figure over the *other*
targets (DUD's and MUV's together) is the one chosen without it, and its figure on the target
is the held-out figure. The held-out means, beside each variant kept fixed and the baselines,
say whether a choice holds beyond the targets it was made on.

Each variant is one or more bench/dud_screen_bench.py JSON files (--json) of the same settings
but the variant's (`--screen-args`, say), e.g. one for --set dud and one for --set muv; their
surfcomp figures per target (the mean over the queries) are pooled. Targets missing from a
variant are left out of every variant. The first variant listed wins ties (the current default).

Usage:
  /usr/bin/python3 bench/loto.py --variant auto=dud_auto.json,muv_auto.json \\
      --variant on=dud_on.json,muv_on.json [--metric auc|ef1] [--json loto.json]
"""
import argparse
import json
import sys
from pathlib import Path

BASELINES = ("usrcat", "o3a_shape")


def read_variant(paths):
    """{set:target: {method: {"auc", "ef1"}}} from dud_screen_bench JSON files."""
    figures = {}
    for path in paths:
        report = json.loads(Path(path).read_text())
        dataset = report.get("config", {}).get("set", "dud")
        for target, result in report["targets"].items():
            figures[f"{dataset}:{target}"] = result["mean"]
    return figures


def mean(values):
    values = list(values)
    return sum(values) / len(values) if values else float("nan")


def choose(variants, targets, metric, left_out):
    """The variant with the best mean `metric` over `targets` but `left_out` (first on ties)."""
    others = [t for t in targets if t != left_out]
    best, best_value = None, None
    for name, figures in variants.items():
        value = mean(figures[t]["surfcomp"][metric] for t in others)
        if best_value is None or value > best_value:
            best, best_value = name, value
    return best


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--variant", action="append", required=True,
                        help="NAME=FILE.json[,FILE.json...]; at least two")
    parser.add_argument("--metric", choices=("auc", "ef1"), default="auc",
                        help="the figure a variant is chosen by (default auc)")
    parser.add_argument("--json", type=Path, help="write the held-out table here")
    args = parser.parse_args(argv)
    variants = {}
    for spec in args.variant:
        name, _, files = spec.partition("=")
        if not name or not files:
            parser.error(f"--variant {spec}: expected NAME=FILE.json[,FILE.json...]")
        variants[name] = read_variant(files.split(","))
    if len(variants) < 2:
        parser.error("give at least two variants")
    targets = sorted(set.intersection(*(set(f) for f in variants.values())))
    targets = [t for t in targets if all("surfcomp" in v[t] for v in variants.values())]
    if len(targets) < 2:
        sys.exit("loto: fewer than two targets with surfcomp figures in every variant")
    first = next(iter(variants.values()))
    rows = []
    for target in targets:
        chosen = choose(variants, targets, args.metric, target)
        row = {"target": target, "chosen": chosen,
               "held_out": variants[chosen][target]["surfcomp"],
               "variants": {n: v[target]["surfcomp"] for n, v in variants.items()},
               "baselines": {b: first[target][b] for b in BASELINES if b in first[target]}}
        rows.append(row)
    names = list(variants)
    header = ("| target | " + " | ".join(f"{n} AUC / EF1%" for n in names) +
              " | chosen without it | held-out AUC / EF1% | " +
              " | ".join(f"{b} AUC / EF1%" for b in BASELINES) + " |")
    print(header)
    print("|" + "---|" * (header.count("|") - 1))

    def pair(f):
        return f"{f['auc']:.3f} / {f['ef1']:.1f}" if f else "-"

    for row in rows:
        print(f"| {row['target']} | " + " | ".join(pair(row["variants"][n]) for n in names) +
              f" | {row['chosen']} | {pair(row['held_out'])} | " +
              " | ".join(pair(row["baselines"].get(b)) for b in BASELINES) + " |")
    for dataset in sorted({t.split(":")[0] for t in targets}) + ["all"]:
        selected = [r for r in rows if dataset == "all" or r["target"].startswith(dataset + ":")]

        def means(get):
            values = [get(r) for r in selected]
            values = [v for v in values if v]
            return {k: mean(v[k] for v in values) for k in ("auc", "ef1")} if values else None

        cells = [pair(means(lambda r, n=n: r["variants"][n])) for n in names]
        baselines = [pair(means(lambda r, b=b: r["baselines"].get(b))) for b in BASELINES]
        print(f"| mean {dataset} ({len(selected)}) | " + " | ".join(cells) + " | | " +
              pair(means(lambda r: r["held_out"])) + " | " + " | ".join(baselines) + " |")
    if args.json:
        args.json.write_text(json.dumps({"metric": args.metric, "rows": rows}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
