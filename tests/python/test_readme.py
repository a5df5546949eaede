"""The README's steps for mesh researchers, run as a new user runs them: its shell block as
written, with `surfcomp` on the PATH and datasets/ where the block expects it, and its (V, F)
block on a mesh's arrays."""
import csv
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from conftest import SOURCE_DIR

surfcomp = pytest.importorskip("surfcomp", reason="the Python module is not built")


def _block(heading, language):
    """The first fenced block in `language` after the line `heading` of the README."""
    text = (SOURCE_DIR / "README.md").read_text()
    assert heading in text, f"the README has no {heading!r}"
    found = re.search(rf"```{language}\n(.*?)```", text.split(heading, 1)[1], re.S)
    assert found, f"no {language} block after {heading!r}"
    return found.group(1)


def _elephant(cache):
    sys.path.insert(0, str(SOURCE_DIR / "bench"))
    import mesh_cases  # reads OFF files without the module
    return mesh_cases.read_off(cache / "cgal" / "meshes" / "elephant.off")


def test_the_mesh_commands_run_as_written(program, cache, tmp_path):
    script = _block("### For mesh researchers", "sh")
    tools = tmp_path / "bin"
    tools.mkdir()
    (tools / "surfcomp").symlink_to(program)
    (tmp_path / "datasets").symlink_to(SOURCE_DIR / "datasets")
    env = dict(os.environ, PATH=f"{tools}{os.pathsep}{os.environ['PATH']}")
    done = subprocess.run(["bash", "-e", "-c", script], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr
    for written in ("cps.json", "cps.ply", "maps/patch_maps.json", "result.json", "meshes.sclib",
                    "hits.csv"):
        assert (tmp_path / written).is_file(), written
    # The critical points the first command wrote are the ones patch-map numbered.
    points = json.loads((tmp_path / "cps.json").read_text())["critical_points"]
    maps = json.loads((tmp_path / "maps" / "patch_maps.json").read_text())
    assert len(points) > 0 and json.dumps(maps).count('"harmonic"') >= 1
    # The mesh onto itself: the identity, and all of it on itself.
    result = json.loads((tmp_path / "result.json").read_text())
    best = result["alignments"][0]
    vertices, _ = _elephant(cache)
    diagonal = np.linalg.norm(np.ptp(vertices, axis=0))
    moved = vertices @ np.array(best["transform"])[:3, :3].T + np.array(best["transform"])[:3, 3]
    assert np.sqrt(((moved - vertices) ** 2).sum(1).mean()) < 1e-3 * diagonal
    assert best["coverage"]["score"] > 0.99
    # The elephant among three meshes: itself first, wholly on itself.
    with open(tmp_path / "hits.csv") as table:
        hits = list(csv.DictReader(table))
    assert [h["name"] for h in hits][0] == "elephant" and len(hits) == 3
    assert float(hits[0]["score"]) > 0.99


def test_the_mesh_arrays_example_runs_as_written(cache):
    code = _block("The same steps on arrays", "python")
    V, F = _elephant(cache)
    namespace = {"V": V, "F": F}
    exec(compile(code, "README.md", "exec"), namespace)
    assert namespace["described"].length_unit == pytest.approx(
        namespace["surface"].length_unit, rel=1e-12)
    assert len(namespace["described"].critical_points.vertex) > 0
