#!/usr/bin/env python3
"""Screening rankings computed again from one run's hits: the `--chemistry` rules, blends of
the shape and overlay scores, and the fusion of several queries, without screening again.

Every stage of `surfcomp screen` poses by the overlay score (shape, ESP, LP and heteroatoms)
and picks the molecules of the full match (stage 3) by it, whatever --chemistry says; the rule
only chooses the value that orders the rows (docs/screening.md). So one run with
`--chemistry on --top 0`, whose hits_<q>.csv give every molecule's shape, chem and atoms
terms beside its score, holds every rule's ranking:
- `on`: the overlay score (the run's own order; checked against its figures);
- `shape`: the shape term alone (`--chemistry off`);
- `auto`: the mean of shape and score for a query without an ionic group, `on` for one with
  (asked of the program, whose summary line says which), as `--chemistry auto` ranks;
- `neutral-shape`: `shape` for a query without an ionic group, `on` for one with (the
  default before issue 47);
- `nAiB`: (1 - W) shape + W score, W = A / 100 for a query without an ionic group and B / 100
  for one with (`auto` is n50i100, `neutral-shape` n0i100, `on` n100i100, `shape` n0i0), A and
  B in WEIGHTS;
- `cAaB`: the score with other weights for every query, (shape + A chem + B atoms) / (1 + A +
  B), A in CHEM_WEIGHTS and B in ATOM_WEIGHTS (the screen's own: 6 and 14);
as `rank_hits` orders them: the stage-3 rows first, each part by the rule's value (`flat-RULE`:
every row by the value, the full match's beside stage 2's, for RULE in FLAT). Fused
(`fusedmax-RULE`, `fusedmean-RULE`): each molecule's values for the target's queries, their
maximum or mean, as `fuse_scores` ranks them (one ranking per target, no stage first; when the
queries are mixed, all take the ionic weight, as `agree_on_chemistry` does).

Each variant is written as a dud_screen_bench-like JSON (config.set, targets.T.mean) to
--out/VARIANT.SET.json, for bench/loto.py. With --choose, the script also makes the held-out
choice among the `nAiB` rules that docs/decisions.md describes: for each target, the rule best
on the other targets by the mean of its one-query AUC and its fused (max) AUC, among the rules
that keep every other DUD target's one-query AUC at or above the lower of `neutral-shape`'s and
`on`'s; it prints each target's choice and the held-out means beside `auto`, `neutral-shape`
and `on`, and writes them to --out/choice.json.

    /usr/bin/python3 bench/ranking_variants.py --surfcomp SURFCOMP --work dud=WORK_DUD \\
        --work muv=WORK_MUV --out variants/ --choose
    /usr/bin/python3 bench/loto.py --variant auto=variants/auto.dud.json,variants/auto.muv.json \\
        --variant on=variants/on.dud.json,variants/on.muv.json
"""
import argparse
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from dud_screen_bench import evaluate, log, mean  # noqa: E402

WEIGHTS = (0, 25, 50, 75, 100)
NAMED = {"auto": (50, 100), "neutral-shape": (0, 100), "on": (100, 100), "shape": (0, 0)}
# Each rule: (weight of the score for a query without an ionic group, for one with), in %.
RULES = dict(NAMED, **{f"n{a}i{b}": (a, b) for a in WEIGHTS for b in WEIGHTS
                       if (a, b) not in NAMED.values()})
FLAT = ("auto", "neutral-shape", "on", "shape")
CHEM_WEIGHTS = (0, 1, 3, 6, 12)
ATOM_WEIGHTS = (0, 3, 7, 14, 28)
RULES.update({f"c{a}a{b}": ("weights", a, b) for a in CHEM_WEIGHTS for b in ATOM_WEIGHTS})
FUSIONS = ("max", "mean")
# What the program's summary line says of a query --chemistry auto does not rank by the score.
NEUTRAL_SUMMARY = "(no ionic group;"


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", type=Path, required=True,
                        help="the program, asked which queries carry no ionic group (the ones "
                             "--chemistry auto does not rank by the score alone)")
    parser.add_argument("--work", action="append", required=True,
                        help="SET=FOLDER: a dud_screen_bench.py --work folder of a "
                             "`--screen-args \"--chemistry on\"` run (SET: dud or muv)")
    parser.add_argument("--out", type=Path, required=True, help="folder for VARIANT.SET.json")
    parser.add_argument("--choose", action="store_true",
                        help="make the held-out choice among the nAiB rules (see above)")
    return parser.parse_args(argv)


def read_rows(path):
    """hits_<q>.csv as {name: (stage 3?, (shape, chem, atoms, score))}."""
    rows = {}
    with open(path, newline="") as stream:
        for row in csv.DictReader(stream):
            rows[row["name"]] = (row["stage"] == "3",
                                 tuple(float(row[k]) for k in ("shape", "chem", "atoms", "score")))
    return rows


def rule_value(rule, by_shape, terms):
    """The value `rule` orders a row by; `by_shape`: the query has no ionic group."""
    shape, chem, atoms, score = terms
    spec = RULES[rule]
    if spec[0] == "weights":
        a, b = spec[1], spec[2]
        return (shape + a * chem + b * atoms) / (1.0 + a + b)
    w = spec[0 if by_shape else 1] / 100.0
    return (1.0 - w) * shape + w * score


def single_scores(rows, rule, by_shape, flat=False):
    """{name: sort key}: the stage-3 rows above every other (unless `flat`), each part by the
    rule's value."""
    values = {n: rule_value(rule, by_shape, terms) for n, (_, terms) in rows.items()}
    if flat:
        return values
    finite = [v for v in values.values() if math.isfinite(v)]
    lift = (max(finite) - min(finite) + 1.0) if finite else 0.0
    return {n: values[n] + (lift if rows[n][0] else 0.0) for n in rows}


def fused_scores(all_rows, rule, flags, fusion):
    """{name: fused value} over the queries (a molecule missing from a query's rows is left out)."""
    by_shape = all(flags)
    names = set.intersection(*(set(r) for r in all_rows))
    fused = {}
    for name in names:
        values = [rule_value(rule, by_shape, rows[name][1]) for rows in all_rows]
        fused[name] = max(values) if fusion == "max" else sum(values) / len(values)
    return fused


def query_flags(surfcomp, target_dir, count):
    """Whether each query carries no ionic group, as the program's summary line of an `auto`
    screen says (cached in neutral_queries.json beside the program's path, size and time)."""
    cache = target_dir / "neutral_queries.json"
    stat = Path(surfcomp).stat()
    program = {"program": str(Path(surfcomp).resolve()), "size": stat.st_size,
               "mtime": stat.st_mtime}
    if cache.is_file():
        saved = json.loads(cache.read_text())
        if saved.get("by") == program:
            return saved["flags"]
    flags = []
    for q in range(count):
        out = target_dir / f"auto_probe_{q}.csv"
        result = subprocess.run(
            [str(surfcomp), "screen", str(target_dir / f"query_{q}.sdf"),
             str(target_dir / "library.sclib"), "-o", str(out), "--top", "1", "--candidates", "0",
             "--chemistry", "auto"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if result.returncode != 0:
            raise SystemExit(f"ranking_variants: {target_dir}: {result.stderr.strip()}")
        out.unlink(missing_ok=True)
        flags.append(NEUTRAL_SUMMARY in result.stdout + result.stderr)
    cache.write_text(json.dumps({"by": program, "flags": flags}))
    return flags


def target_figures(surfcomp, target_dir):
    """{variant: {"auc", "ef1"}} of one target, and its baselines' means."""
    saved = json.loads((target_dir / "result.json").read_text())
    result = saved["result"]
    screen_args = saved["settings"].get("screen_args", "")
    if "--chemistry on" not in screen_args:
        raise SystemExit(f"ranking_variants: {target_dir} was screened with {screen_args!r}, "
                         "not --chemistry on")
    with open(target_dir / "scores.csv", newline="") as stream:
        labels = list(csv.DictReader(stream))
    names = [row["name"] for row in labels]
    actives = {row["name"] for row in labels if row["active"] == "1"}
    count = len(result["queries"])
    all_rows = [read_rows(target_dir / f"hits_{q}.csv") for q in range(count)]
    flags = query_flags(surfcomp, target_dir, count)
    figures = {}
    for rule in RULES:
        per_query = [evaluate(single_scores(rows, rule, flag), names, actives)
                     for rows, flag in zip(all_rows, flags)]
        figures[rule] = {k: mean(p[k] for p in per_query) for k in ("auc", "ef1")}
        if rule in FLAT:
            per_query = [evaluate(single_scores(rows, rule, flag, flat=True), names, actives)
                         for rows, flag in zip(all_rows, flags)]
            figures[f"flat-{rule}"] = {k: mean(p[k] for p in per_query) for k in ("auc", "ef1")}
        for fusion in FUSIONS:
            figures[f"fused{fusion}-{rule}"] = evaluate(
                fused_scores(all_rows, rule, flags, fusion), names, actives)
    stored = result["mean"]["surfcomp"]
    if any(abs(figures["on"][k] - stored[k]) > 1e-9 for k in ("auc", "ef1")):
        raise SystemExit(f"ranking_variants: {target_dir}: the `on` ranking recomputed gives "
                         f"{figures['on']}, the run {stored}")
    baselines = {m: result["mean"][m] for m in ("usrcat", "o3a_shape") if m in result["mean"]}
    return figures, baselines, flags


def main(argv=None):
    args = parse_args(argv)
    variants = {}
    flags_by_target = {}
    for spec in args.work:
        dataset, _, folder = spec.partition("=")
        folder = Path(folder)
        for target_dir in sorted(p for p in folder.iterdir() if (p / "result.json").is_file()):
            figures, baselines, flags = target_figures(args.surfcomp, target_dir)
            flags_by_target[f"{dataset}:{target_dir.name}"] = flags
            log(f"{dataset}:{target_dir.name}: {sum(flags)} of {len(flags)} queries without an "
                "ionic group; " + ", ".join(f"{v} {f['auc']:.3f}" for v, f in figures.items()
                                      if not v.startswith("fused")))
            for variant, figure in figures.items():
                report = variants.setdefault(variant, {}).setdefault(
                    dataset, {"config": {"set": dataset}, "targets": {}})
                report["targets"][target_dir.name] = {"mean": {"surfcomp": figure, **baselines}}
    args.out.mkdir(parents=True, exist_ok=True)
    for variant, by_set in variants.items():
        for dataset, report in by_set.items():
            (args.out / f"{variant}.{dataset}.json").write_text(json.dumps(report, indent=1) + "\n")
    (args.out / "neutral_queries.json").write_text(json.dumps(flags_by_target, indent=1) + "\n")
    if args.choose:
        choose(variants, args.out)
    return 0


def choose(variants, out):
    """The held-out choice among the nAiB rules (module docstring); prints and writes it."""
    def figures(variant):
        return {f"{d}:{t}": r["mean"] for d, report in variants[variant].items()
                for t, r in report["targets"].items()}

    rules = [r for r in RULES if not r.startswith("c")]
    single = {r: figures(r) for r in rules}
    fused = {r: figures(f"fusedmax-{r}") for r in rules}
    targets = sorted(single["auto"])

    def auc(table, rule, target):
        return table[rule][target]["surfcomp"]["auc"]

    def guarded(rule, others):
        return all(auc(single, rule, u) >= min(auc(single, "neutral-shape", u),
                                               auc(single, "on", u)) - 1e-12
                   for u in others if u.startswith("dud:"))

    chosen = {}
    for target in targets:
        others = [u for u in targets if u != target]
        allowed = [r for r in rules if guarded(r, others)]
        chosen[target] = max(allowed, key=lambda r: (
            mean((auc(single, r, u) + auc(fused, r, u)) / 2 for u in others), -rules.index(r)))
    lines = [f"{t}: {chosen[t]}" for t in targets]
    summary = {}
    for dataset in sorted({t.split(":")[0] for t in targets}):
        chosen_here = [t for t in targets if t.startswith(dataset + ":")]
        row = {}
        for label, pick in (("held_out", lambda t: chosen[t]), ("auto", lambda t: "auto"),
                            ("neutral-shape", lambda t: "neutral-shape"), ("on", lambda t: "on")):
            row[label] = {kind: {k: mean(table[pick(t)][t]["surfcomp"][k] for t in chosen_here)
                                 for k in ("auc", "ef1")}
                          for kind, table in (("single", single), ("fused_max", fused))}
        for baseline in ("o3a_shape", "usrcat"):
            values = [single["auto"][t][baseline] for t in chosen_here
                      if baseline in single["auto"][t]]
            if values:
                row[baseline] = {k: mean(v[k] for v in values) for k in ("auc", "ef1")}
        summary[dataset] = row
        for label, value in row.items():
            text = "; ".join(f"{kind} {v['auc']:.3f} / {v['ef1']:.2f}" for kind, v in value.items()) \
                if "single" in value else f"{value['auc']:.3f} / {value['ef1']:.2f}"
            lines.append(f"mean {dataset} ({len(chosen_here)}) {label}: {text}")
    print("\n".join(lines))
    (out / "choice.json").write_text(json.dumps({"chosen": chosen, "means": summary}, indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main())
