#!/usr/bin/env python3
"""Site similarity rules chosen on one site set and scored on the other.

`site_bench ENTRIES PREFIX default` writes PREFIX.default.csv with one row per site pair and
every score it prints (overlay, overlay_shape, overlay_chem, lining, interactions, site, ...),
beside the sites' sizes. This script scores rules that combine those columns, without matching
again:
- `oLiIfF`: (overlay + L/100 lining + I/100 interactions + F/100 fields) / (1 + L/100 + I/100
  + F/100), L, I and F in WEIGHTS: lining the residue composition, interactions the surface
  points' interaction composition, fields their agreement under the top-1 alignment
  (`o30i0f0` is the default site score, lining_weight 0.3);
- `pLiIfF`: the same with the partial overlay in place of the overlay: the shape Tanimoto's
  overlap over the smaller site's (overlap / min(A, B), A and B the sites' surface vertices),
  so that a small site inside a larger pocket is a match;
- `size`: the baseline, -|imaged_a - imaged_b|.

Each rule's figures on a set: the AUC over all pairs, over the size-matched pairs
(|imaged_a - imaged_b| <= 2, as site_bench counts them), the mean per-site AUC (each site the
query, the others ranked, IsoMIF's way), and leave-one-out top-1 and top-3 (ties by entry
order). The criterion a rule is chosen by is the mean of the first three (ties: the least
weight beside the overlay). For each direction
(choose on A, score on B) the script prints the rule chosen and its held-out figures beside
the documented site score's and the size baseline's.

    /usr/bin/python3 bench/site_choice.py --set kahraman-dev=kd.default.csv \\
        --set homogeneous=hom.default.csv [--json choice.json]
"""
import argparse
import csv
import json
import math
from collections import defaultdict

WEIGHTS = (0, 15, 30, 60, 100)
SIZE_MATCHED = 2.0
SITE_CHEM_WEIGHT = 0.25  # MatchOptions::site.chem_weight


def read_pairs(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def auc(values, positive):
    """Mann-Whitney AUC, ties counting one half."""
    order = sorted(range(len(values)), key=lambda i: values[i])
    ranks = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2.0 + 1.0
        i = j + 1
    p = sum(1 for x in positive if x)
    n = len(positive) - p
    if p == 0 or n == 0:
        return math.nan
    rank_sum = sum(r for r, x in zip(ranks, positive) if x)
    return (rank_sum - p * (p + 1) / 2.0) / (p * n)


def partial_overlay(row):
    """The shape overlap over the smaller site's self-overlap, from the Tanimoto T = O / (A + B
    - O): O = T (A + B) / (1 + T), with A and B the sites' surface vertices in place of their
    self-overlaps."""
    t = float(row["overlay_shape"])
    a, b = float(row["site_vertices_a"]), float(row["site_vertices_b"])
    if min(a, b) <= 0:
        return 0.0
    return min(1.0, t * (a + b) / ((1.0 + t) * min(a, b)))


def rules():
    out = {}
    for base in ("o", "p"):
        for lw in WEIGHTS:
            for iw in WEIGHTS:
                for fw in WEIGHTS:
                    out[f"{base}{lw}i{iw}f{fw}"] = (base, lw / 100.0, iw / 100.0, fw / 100.0)
    out["size"] = ("size", 0.0, 0.0, 0.0)
    return out


def rule_values(rows, rule):
    base, lw, iw, fw = rule
    values = []
    for r in rows:
        if base == "size":
            values.append(-abs(float(r["imaged_a"]) - float(r["imaged_b"])))
            continue
        first = float(r["overlay"])
        if base == "p":
            # The overlay is (shape + w chem) / (1 + w), w = site.chem_weight (0.25): the
            # partial one keeps its chem part.
            first = (partial_overlay(r) + SITE_CHEM_WEIGHT * float(r["overlay_chem"])) / (
                1.0 + SITE_CHEM_WEIGHT)
        values.append((first + lw * float(r["lining"]) + iw * float(r["interactions"]) +
                       fw * float(r["fields"])) / (1.0 + lw + iw + fw))
    return values


def figures(rows, values):
    positive = [r["same"] == "1" for r in rows]
    matched = [i for i, r in enumerate(rows)
               if abs(float(r["imaged_a"]) - float(r["imaged_b"])) <= SIZE_MATCHED]
    per_query = defaultdict(list)
    sites = []
    ligand = {}
    for i, r in enumerate(rows):
        for q, o in ((r["a"], r["b"]), (r["b"], r["a"])):
            per_query[q].append((values[i], o, positive[i]))
        for s, t in ((r["a"], r["ligand_a"]), (r["b"], r["ligand_b"])):
            if s not in ligand:
                ligand[s] = t
                sites.append(s)
    order = {s: k for k, s in enumerate(sites)}
    per_site, top1, top3 = [], 0, 0
    for q in sites:
        hits = per_query[q]
        a = auc([h[0] for h in hits], [h[2] for h in hits])
        if not math.isnan(a):
            per_site.append(a)
        ranked = sorted(hits, key=lambda h: (-h[0], order[h[1]]))
        top1 += 1 if ranked and ranked[0][2] else 0
        top3 += 1 if any(h[2] for h in ranked[:3]) else 0
    result = {
        "auc": auc(values, positive),
        "auc_size_matched": auc([values[i] for i in matched], [positive[i] for i in matched]),
        "per_site_auc": sum(per_site) / len(per_site),
        "top1": top1 / len(sites),
        "top3": top3 / len(sites),
    }
    result["criterion"] = (result["auc"] + result["auc_size_matched"] +
                           result["per_site_auc"]) / 3.0
    return result


def show(name, f):
    return (f"{name:<10} AUC {f['auc']:.3f}  size-matched {f['auc_size_matched']:.3f}  "
            f"per-site {f['per_site_auc']:.3f}  top-1 {f['top1']:.2f}  top-3 {f['top3']:.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--set", action="append", required=True, metavar="NAME=CSV",
                        help="a site set and its site_bench pairs table (two sets)")
    parser.add_argument("--json", help="write every rule's figures and the choices here")
    args = parser.parse_args()
    sets = dict(item.split("=", 1) for item in args.set)
    if len(sets) != 2:
        parser.error("give exactly two --set NAME=CSV")
    all_rules = rules()
    table = {}
    for name, path in sets.items():
        rows = read_pairs(path)
        table[name] = {r: figures(rows, rule_values(rows, rule)) for r, rule in all_rules.items()}
    choices = {}
    names = list(sets)
    for chosen_on, held_out in ((names[0], names[1]), (names[1], names[0])):
        # Ties go to the simplest rule: the least weight beside the overlay, the overlay itself
        # before its partial estimate.
        best = min((r for r in all_rules if r != "size"),
                   key=lambda r: (-table[chosen_on][r]["criterion"], sum(all_rules[r][1:]),
                                  all_rules[r][0] != "o", r))
        choices[held_out] = best
        print(f"chosen on {chosen_on}: {best} (criterion {table[chosen_on][best]['criterion']:.3f}"
              f"); held out on {held_out}:")
        for r in (best, "o30i0f0", "o0i0f0", "size"):
            print("  " + show(r, table[held_out][r]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"figures": table, "chosen_for": choices}, f, indent=1, sort_keys=True)


if __name__ == "__main__":
    main()
