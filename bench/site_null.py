#!/usr/bin/python3
"""The null model of the site score, fitted on one site set and checked on the other.

A site score means little alone: two large pockets score higher than two small ones, related or
not. `surfcomp match` therefore reports a z-score, (score - mean(n)) / spread(n), where mean and
spread are those of the site score over unrelated pairs (sites of different ligand types) whose
smaller site has n surface points, both linear in log10 n (matching::site_score_null). This
script fits the two lines on the unrelated pairs of one `site_bench` table and reports, on the
other set's table:
  - the unrelated pairs' z: mean, standard deviation, and the share above 2 and 3 (a standard
    normal gives 2.3 % and 0.13 %), in all and by size third;
  - the AUC of z and of the raw score for same-type pairs against the others.

    /usr/bin/python3 bench/site_null.py FIT.default.csv CHECK.default.csv [--score site]

The tables are site_bench's (PREFIX.default.csv); --score names the column fitted.
"""

import argparse
import csv
import math
import sys


def rows(path, score):
    out = []
    with open(path) as f:
        for r in csv.DictReader(f):
            n = min(int(r["site_vertices_a"]), int(r["site_vertices_b"]))
            if n <= 0 or r[score] in ("", "nan"):
                continue
            out.append((math.log10(n), float(r[score]), r["same"] in ("1", "true")))
    return out


def line(xs, ys):
    """Least-squares intercept and slope of ys on xs."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    return my - slope * mx, slope


def fit(table):
    """Mean and spread lines of the unrelated pairs: the spread from the absolute residuals
    (times sqrt(pi / 2), the normal's ratio of standard deviation to mean absolute deviation)."""
    unrelated = [(x, y) for x, y, same in table if not same]
    xs, ys = [x for x, _ in unrelated], [y for _, y in unrelated]
    mean = line(xs, ys)
    spread = line(xs, [abs(y - mean[0] - mean[1] * x) * math.sqrt(math.pi / 2)
                       for x, y in unrelated])
    return mean, spread


def z_of(model, x, y):
    """As matching::site_z_score: n clamped to the fitted range."""
    (m0, m1), (s0, s1), low, high = model
    x = min(max(x, math.log10(low)), math.log10(high))
    return (y - m0 - m1 * x) / (s0 + s1 * x)


def auc(positives, negatives):
    ranked = sorted([(v, 1) for v in positives] + [(v, 0) for v in negatives])
    rank_sum, k = 0.0, 0
    while k < len(ranked):
        j = k
        while j < len(ranked) and ranked[j][0] == ranked[k][0]:
            j += 1
        rank_sum += sum(label for _, label in ranked[k:j]) * (k + j + 1) / 2.0
        k = j
    p, n = len(positives), len(negatives)
    return (rank_sum - p * (p + 1) / 2.0) / (p * n) if p and n else float("nan")


def describe(name, zs):
    n = len(zs)
    mean = sum(zs) / n
    sd = math.sqrt(sum((z - mean) ** 2 for z in zs) / n)
    over2 = sum(1 for z in zs if z > 2) / n
    over3 = sum(1 for z in zs if z > 3) / n
    print(f"  {name}: n={n}, z mean {mean:+.2f}, sd {sd:.2f}, above 2 {over2:.1%}, above 3 "
          f"{over3:.2%}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fit")
    parser.add_argument("check")
    parser.add_argument("--score", default="site")
    args = parser.parse_args()
    fitted, checked = rows(args.fit, args.score), rows(args.check, args.score)
    model = fit(fitted)
    (m0, m1), (s0, s1) = model
    low = min(10 ** x for x, _, same in fitted if not same)
    high = max(10 ** x for x, _, same in fitted if not same)
    print(f"fitted on {args.fit} ({sum(1 for r in fitted if not r[2])} unrelated pairs): mean "
          f"{m0:.4f} + {m1:.4f} log10 n, spread {s0:.4f} + {s1:.4f} log10 n, n in "
          f"[{low:.0f}, {high:.0f}]")
    print(f"  as matching::SiteScoreNull: {{{m0:.4f}, {m1:.4f}, {s0:.4f}, {s1:.4f}, {low:.0f}.0, "
          f"{high:.0f}.0}}")
    model = ((m0, m1), (s0, s1), low, high)
    for name, table in (("fit set", fitted), ("held-out set", checked)):
        print(f"{name} ({args.fit if table is fitted else args.check}):")
        unrelated = sorted((x, z_of(model, x, y)) for x, y, same in table if not same)
        describe("unrelated pairs", [z for _, z in unrelated])
        third = len(unrelated) // 3
        for k, label in enumerate(("smallest third", "middle third", "largest third")):
            part = unrelated[k * third:(k + 1) * third if k < 2 else len(unrelated)]
            describe(f"{label} (n >= {10 ** part[0][0]:.0f})", [z for _, z in part])
        same = [z_of(model, x, y) for x, y, s in table if s]
        other = [z_of(model, x, y) for x, y, s in table if not s]
        describe("same-type pairs", same)
        print(f"  AUC same type against the rest: z {auc(same, other):.3f}, score "
              f"{auc([y for _, y, s in table if s], [y for _, y, s in table if not s]):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
