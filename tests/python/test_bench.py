"""The screening benchmarks' own arithmetic and their run on MUV (bench/dud_screen_bench.py,
bench/ranking_variants.py, bench/loto.py), with the system Python (RDKit, numpy)."""
import json
import math
import shutil
import sys

import pytest

from conftest import SOURCE_DIR, _shared_dir, run

BENCH = SOURCE_DIR / "bench"
sys.path.insert(0, str(BENCH))

import dud_screen_bench  # noqa: E402
import loto  # noqa: E402


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
        pytest.skip(f"{datasets / 'muv'} is absent: the reference data sets are not beside the "
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
