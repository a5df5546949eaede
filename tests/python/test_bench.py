"""The screening benchmarks' own arithmetic and their run on MUV (bench/dud_screen_bench.py,
bench/ranking_variants.py, bench/loto.py), with the system Python (RDKit, numpy)."""
import json
import math
import shutil
import sys

import pytest

from conftest import SOURCE_DIR, _shared_dir, absent, run

BENCH = SOURCE_DIR / "bench"
sys.path.insert(0, str(BENCH))

import dud_screen_bench  # noqa: E402
import loto  # noqa: E402
import plddt_bench  # noqa: E402
import pocket_detection_bench  # noqa: E402
import site_choice  # noqa: E402
import site_null  # noqa: E402


def test_auc_and_ef1_of_known_rankings():
    labels = [1, 1, 0, 0, 0, 0, 0, 0]
    assert dud_screen_bench.roc_auc([8, 7, 6, 5, 4, 3, 2, 1], labels) == 1.0
    assert dud_screen_bench.roc_auc([1, 2, 3, 4, 5, 6, 7, 8], labels) == 0.0
    assert dud_screen_bench.roc_auc([1] * 8, labels) == 0.5
    # One active first, the other fourth of eight: it beats 4 of the 6 decoys.
    assert dud_screen_bench.roc_auc([8, 5, 7, 6, 4, 3, 2, 1], labels) == pytest.approx(10 / 12)
    # 200 molecules, 4 active: the top 1 % is two molecules; both active gives 2/2 over 4/200.
    scores = list(range(200, 0, -1))
    actives = [1, 1, 1, 1] + [0] * 196
    assert dud_screen_bench.enrichment_factor(scores, actives) == pytest.approx(50.0)
    # Every score tied: the top set holds the library's active share, EF 1.
    assert dud_screen_bench.enrichment_factor([0] * 200, actives) == pytest.approx(1.0)


def _site_pairs(path, sites, value):
    """A site_bench-like pair table over `sites` (name -> ligand type), every score column
    `value(a, b)`, all sites of one size."""
    columns = ["a", "b", "ligand_a", "ligand_b", "same", "imaged_a", "imaged_b",
               "site_vertices_a", "site_vertices_b", "overlay", "overlay_shape", "overlay_chem",
               "lining", "interactions", "fields"]
    names = list(sites)
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for i, a in enumerate(names):
            for b in names[i + 1:]:
                same = sites[a] == sites[b]
                scores = value(a, b, same)
                row = [a, b, sites[a], sites[b], str(int(same)), "10", "10", "100", "100"]
                row += [str(scores[c]) for c in columns[9:]]
                f.write(",".join(row) + "\n")


def test_site_choice_scores_a_rule_chosen_on_one_set_on_the_other(tmp_path, capsys, monkeypatch):
    assert site_choice.auc([3, 1, 2, 2], [True, False, True, False]) == pytest.approx(0.875)
    sites = {"s1": "X", "s2": "X", "s3": "Y", "s4": "Y"}
    # Set A: only the lining separates the types; set B: only the overlay does.
    _site_pairs(tmp_path / "a.csv", sites, lambda a, b, same: dict(
        overlay=0.5, overlay_shape=0.5, overlay_chem=0.5, lining=0.9 if same else 0.1,
        interactions=0.5, fields=0.5))
    _site_pairs(tmp_path / "b.csv", sites, lambda a, b, same: dict(
        overlay=0.9 if same else 0.2, overlay_shape=0.9 if same else 0.2, overlay_chem=0.5,
        lining=0.5, interactions=0.5, fields=0.5))
    rows = site_choice.read_pairs(tmp_path / "a.csv")
    default = site_choice.rules()["o30i0f0"]
    figures = site_choice.figures(rows, site_choice.rule_values(rows, default))
    assert figures["auc"] == 1.0 and figures["per_site_auc"] == 1.0 and figures["top1"] == 1.0
    assert figures["auc_size_matched"] == 1.0  # every pair is size-matched here
    monkeypatch.setattr(sys, "argv", [
        "site_choice.py", "--set", f"A={tmp_path / 'a.csv'}", "--set", f"B={tmp_path / 'b.csv'}",
        "--json", str(tmp_path / "choice.json")])
    site_choice.main()
    choice = json.loads((tmp_path / "choice.json").read_text())
    # Chosen on A, the least lining weight that separates the types, held out on B (where the
    # overlay still does); chosen on B, the overlay alone.
    assert choice["chosen_for"] == {"B": "o15i0f0", "A": "o0i0f0"}
    assert choice["figures"]["A"]["o0i0f0"]["auc"] == 0.5
    assert "held out on B" in capsys.readouterr().out


def test_pocket_ranking_terms_and_ligand_volume():
    # One ball: 4/3 pi r^3; two far apart: twice that.
    one = pocket_detection_bench.ligand_volume([(0.0, 0.0, 0.0)])
    assert one == pytest.approx(4.0 / 3.0 * math.pi * 1.7 ** 3, rel=0.03)
    assert pocket_detection_bench.ligand_volume([(0, 0, 0), (10, 0, 0)]) == pytest.approx(2 * one)
    big = {"buriedness": 0.7, "spheres": [0] * 100, "lining_residues": ["ASP1:A", "GLU2:A"]}
    small = {"buriedness": 0.9, "spheres": [0] * 25, "lining_residues": ["LEU3:A", "PHE4:A"]}
    # The program's score (size power 1) puts the big pocket first; without size, or with the
    # hydrophobic lining weighed, the small one (the site here) comes first.
    dca = [10.0, 1.0]
    assert pocket_detection_bench.rule_ranks([big, small], dca, 1.0, 0.0) == 2
    assert pocket_detection_bench.rule_ranks([big, small], dca, 0.0, 0.0) == 1
    assert pocket_detection_bench.rule_ranks([big, small], dca, 0.5, 2.0) == 1
    assert pocket_detection_bench.rule_value(small, 1.0, 0.0) == pytest.approx(0.9 * 25)


def test_site_null_fits_the_unrelated_pairs_mean_and_spread(tmp_path):
    # Unrelated pairs score 0.1 + 0.2 log10 n, +-0.05: the fitted mean is that line,
    # and their z is +-sqrt(2 / pi), the spread being the normal's from the mean absolute deviation.
    rows = ["a,b,same,site_vertices_a,site_vertices_b,site"]
    for k, n in enumerate([100, 200, 400, 800, 1600, 3200] * 2):
        noise = 0.05 if k >= 6 else -0.05  # each size once below the line, once above
        rows.append(f"s{k},t{k},0,{n},{2 * n},{0.1 + 0.2 * math.log10(n) + noise}")
    rows.append("u,v,1,1000,1000,0.9")
    (tmp_path / "pairs.csv").write_text("\n".join(rows) + "\n")
    table = site_null.rows(tmp_path / "pairs.csv", "site")
    (m0, m1), (s0, s1) = site_null.fit(table)
    assert (m0, m1) == (pytest.approx(0.1), pytest.approx(0.2))
    assert s0 == pytest.approx(0.05 * math.sqrt(math.pi / 2)) and s1 == pytest.approx(0.0, abs=1e-12)
    model = ((m0, m1), (s0, s1), 100, 3200)
    zs = [site_null.z_of(model, x, y) for x, y, same in table if not same]
    assert all(abs(abs(z) - math.sqrt(2 / math.pi)) < 1e-9 for z in zs)
    assert site_null.auc([0.9], [0.1, 0.2]) == 1.0


def test_plddt_models_mark_confidence_and_add_a_tail_off_the_surface(tmp_path):
    # A helix-like chain of 30 alanines (N, CA, C, O per residue) along x.
    lines = []
    for r in range(30):
        for k, (name, dx, dy) in enumerate(((" N  ", -1.2, 0.0), (" CA ", 0.0, 0.0),
                                            (" C  ", 1.2, 0.3), (" O  ", 1.6, 1.4))):
            x, y, z = 1.5 * r + dx, 2.3 * math.cos(r) + dy, 2.3 * math.sin(r)
            lines.append(f"ATOM  {4 * r + k + 1:5d} {name} ALA A{r + 1:4d}    "
                         f"{x:8.3f}{y:8.3f}{z:8.3f}  1.00 20.00           {name.strip()[0]}\n")
    (tmp_path / "chain.pdb").write_text("".join(lines) + "END\n")
    tail = plddt_bench.write_model(tmp_path / "chain.pdb", tmp_path / "model.pdb", "chain")
    model = [l for l in (tmp_path / "model.pdb").read_text().splitlines() if l.startswith("ATOM")]
    chain = [l for l in model if l[21] == "A"]
    values = {int(l[22:26]): float(l[60:66]) for l in chain}
    assert [values[r] for r in (1, 5, 26, 30)] == [40.0] * 4  # the chain's ends
    assert all(50.0 <= values[r] <= 95.0 for r in range(6, 26))
    assert len(tail) == 4 * plddt_bench.TAIL_RESIDUES
    assert all(float(l[60:66]) == plddt_bench.TAIL_PLDDT for l in model if l[21] == "Z")
    protein = [(float(l[30:38]), float(l[38:46]), float(l[46:54])) for l in chain]
    cas = tail[1::4]
    assert all(4.0 <= min(pocket_detection_bench.distance(c, p) for p in protein) <= 9.0
               for c in cas)
    # The same model on every run.
    again = plddt_bench.write_model(tmp_path / "chain.pdb", tmp_path / "again.pdb", "chain")
    assert again == tail


def test_loto_scores_each_target_with_the_choice_made_without_it(tmp_path):
    # Variant a wins on t1 and t2, b on t3 by a margin that makes b the mean's best overall:
    # without t3, a is chosen for t3; without t1 or t2, b is.
    figures = {"a": {"t1": 0.80, "t2": 0.80, "t3": 0.50},
               "b": {"t1": 0.75, "t2": 0.75, "t3": 0.90}}
    paths = {}
    for name, by_target in figures.items():
        report = {"config": {"set": "dud"},
                  "targets": {t: {"mean": {"surfcomp": {"auc": v, "ef1": 10 * v}}}
                              for t, v in by_target.items()}}
        paths[name] = tmp_path / f"{name}.json"
        paths[name].write_text(json.dumps(report))
    out = tmp_path / "loto.json"
    assert loto.main(["--variant", f"a={paths['a']}", "--variant", f"b={paths['b']}",
                      "--json", str(out)]) == 0
    rows = {r["target"]: r for r in json.loads(out.read_text())["rows"]}
    assert {t: r["chosen"] for t, r in rows.items()} == {"dud:t1": "b", "dud:t2": "b", "dud:t3": "a"}
    assert [rows[t]["held_out"]["auc"] for t in ("dud:t1", "dud:t2", "dud:t3")] == [0.75, 0.75, 0.50]


def test_muv_benchmark_skips_without_the_data(tmp_path):
    result = run([sys.executable, BENCH / "dud_screen_bench.py", "--set", "muv", "--skip-surfcomp",
                  "--datasets", tmp_path / "absent"])
    assert result.returncode == 0, result.stderr
    assert "muv not found; skipped" in result.stderr


@pytest.fixture(scope="module")
def muv_run(program, tmp_path_factory):
    """A small MUV screen with `--chemistry on`: one target, 2 queries, 30 molecules."""
    datasets = _shared_dir()
    if not (datasets / "muv").is_dir():
        absent(f"{datasets / 'muv'} is absent: the reference data sets are not beside the "
               "repository")
    work = tmp_path_factory.mktemp("muv")
    result = run([sys.executable, BENCH / "dud_screen_bench.py", "--surfcomp", program,
                  "--datasets", datasets, "--set", "muv", "--targets", "466", "--queries", "2",
                  "--conformers", "1", "--max-actives", "6", "--max-decoys", "24", "--skip-o3a",
                  "--threads", "2", "--screen-args", "--chemistry on --candidates 4",
                  "--work", work / "on", "--json", work / "on.json"], timeout=800)
    assert result.returncode == 0, result.stderr
    return work


def test_muv_run_reports_every_method(muv_run):
    report = json.loads((muv_run / "on.json").read_text())
    target = report["targets"]["466"]
    assert report["config"]["set"] == "muv"
    assert target["library_actives"] == 6 and target["library_decoys"] == 24
    for method in ("surfcomp", "usrcat"):
        figure = target["mean"][method]
        assert 0.0 <= figure["auc"] <= 1.0 and math.isfinite(figure["ef1"])


def test_rankings_recomputed_from_hits_equal_the_programs(program, muv_run):
    """ranking_variants' `on` and `auto` equal what `surfcomp screen` itself ranks, and the
    overlay weights it recomputes with equal the program's (6, 14)."""
    out = muv_run / "variants"
    result = run([sys.executable, BENCH / "ranking_variants.py", "--surfcomp", program,
                  "--work", f"muv={muv_run / 'on'}", "--out", out], timeout=600)
    assert result.returncode == 0, result.stderr  # it checks `on` against the run itself
    # The check below tells the rules apart only if a query has no ionic group (the mean).
    assert any(json.loads((out / "neutral_queries.json").read_text())["muv:466"])

    def auc(name):
        return json.loads((out / f"{name}.muv.json").read_text())["targets"]["466"]["mean"]["surfcomp"]

    assert auc("c6a14") == pytest.approx(auc("on"), abs=1e-9)
    auto = muv_run / "auto"
    shutil.copytree(muv_run / "on", auto)
    result = run([sys.executable, BENCH / "dud_screen_bench.py", "--surfcomp", program,
                  "--datasets", _shared_dir(), "--set", "muv", "--targets", "466", "--queries", "2",
                  "--conformers", "1", "--max-actives", "6", "--max-decoys", "24", "--skip-o3a",
                  "--threads", "2", "--rescreen", "--screen-args", "--chemistry auto --candidates 4",
                  "--work", auto, "--json", muv_run / "auto.json"], timeout=800)
    assert result.returncode == 0, result.stderr
    screened = json.loads((muv_run / "auto.json").read_text())["targets"]["466"]["mean"]["surfcomp"]
    assert auc("auto")["auc"] == pytest.approx(screened["auc"], abs=1e-9)
    assert auc("auto")["ef1"] == pytest.approx(screened["ef1"], abs=1e-9)


def test_absent_data_fails_only_when_data_is_required(monkeypatch):
    monkeypatch.setenv("SURFCOMP_REQUIRE_DATA", "1")
    with pytest.raises(pytest.fail.Exception, match="SURFCOMP_REQUIRE_DATA=1 requires it"):
        absent("x.pdb is absent")
    monkeypatch.delenv("SURFCOMP_REQUIRE_DATA")
    with pytest.raises(pytest.skip.Exception, match="x.pdb is absent"):
        absent("x.pdb is absent")
