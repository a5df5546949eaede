"""The Python module `surfcomp`: round trips, RDKit molecules against their files, a self-match,
errors, the GIL, the type stubs against the command line's options, and the example script."""
import ast
import os
import pathlib
import threading
import time

import numpy as np
import pytest

from conftest import SOURCE_DIR, run

surfcomp = pytest.importorskip("surfcomp", reason="the Python module is not built")
Chem = pytest.importorskip("rdkit.Chem")


@pytest.fixture(scope="module")
def ligands(cache, tmp_path_factory):
    """Two single-record SDF files (the first two benzodiazepine-receptor ligands of rdkit-data,
    written with hydrogens) and the two 1C9 ligands of PDB 4i23 and 4i24 (one frame)."""
    folder = tmp_path_factory.mktemp("ligands")
    supplier = Chem.SDMolSupplier(str(cache / "rdkit-data" / "bzr.sdf"), removeHs=False)
    paths = []
    for k in range(2):
        path = folder / f"bzr{k + 1}.sdf"
        Chem.MolToMolFile(supplier[k], str(path))
        paths.append(path)
    return paths + [cache / "rdkit-data" / "4i23_1C9.pdb", cache / "rdkit-data" / "4i24_1C9.pdb"]


def test_a_surface_holds_its_arrays_and_round_trips_through_ply(ligands, tmp_path):
    surface = surfcomp.build_surface(ligands[0], probe_radius=1.4)
    assert surface.vertices.shape == (surface.n_vertices, 3)
    assert surface.faces.shape == (surface.n_faces, 3)
    assert surface.normals.shape == surface.vertices.shape
    np.testing.assert_allclose(np.linalg.norm(surface.normals, axis=1), 1.0, atol=1e-9)
    assert {"esp", "lp", "cc1", "cc2", "shape_index", "curvedness"} <= set(surface.properties)
    measures = surface.measures()
    assert measures["euler_characteristic"] == 2 and measures["boundary_edges"] == 0
    # Euler's formula for a closed triangle mesh: F = 2 V - 4.
    assert surface.n_faces == 2 * surface.n_vertices - 4
    surface.save(tmp_path / "s.ply")
    again = surfcomp.build_surface(tmp_path / "s.ply")
    np.testing.assert_array_equal(again.vertices, surface.vertices)
    np.testing.assert_array_equal(again.faces, surface.faces)
    np.testing.assert_array_equal(again.properties["esp"], surface.properties["esp"])


def test_descriptors_round_trip_through_hsi(ligands, tmp_path):
    described = surfcomp.describe(ligands[0], image_rings=8, image_sectors=90)
    points = described.critical_points
    k = len(points["type"])
    assert k > 5 and described.images.shape == (k, 8, 90)
    assert set(points["type"]) <= {"peak", "valley"} and points["position"].shape == (k, 3)
    ok = points["status"] == "ok"
    assert ok.all()
    assert np.isfinite(described.images).any(axis=(1, 2)).all()
    assert described.options["image_sectors"] == 90
    described.save(tmp_path / "d.hsi")
    loaded = surfcomp.load_descriptors(tmp_path / "d.hsi")
    np.testing.assert_array_equal(loaded.images, described.images)
    np.testing.assert_array_equal(loaded.critical_points["position"], points["position"])
    assert loaded.options == described.options
    elements, positions = loaded.atoms
    assert len(elements) == positions.shape[0] > 10


def test_an_rdkit_molecule_gives_the_alignment_of_its_file(ligands):
    ref = Chem.MolFromMolFile(str(ligands[0]), removeHs=False)
    probe = Chem.MolFromMolFile(str(ligands[1]), removeHs=False)
    from_files = surfcomp.match(ligands[0], ligands[1])
    from_molecules = surfcomp.match(ref, probe)
    assert len(from_files) == len(from_molecules) > 0
    np.testing.assert_allclose(from_molecules[0].transform, from_files[0].transform, atol=1e-9)
    assert from_molecules[0].overlay_score == pytest.approx(from_files[0].overlay_score, abs=1e-12)


def test_a_self_match_gives_the_identity(ligands):
    result = surfcomp.match(ligands[2], ligands[2])
    best = result[0]
    # Measured: the identity to within 1e-6 (the overlay's refinement stops at 0.1 A steps).
    np.testing.assert_allclose(best.transform, np.eye(4), atol=1e-3)
    assert best.overlay_score == pytest.approx(1.0, abs=1e-6)
    assert result.trace[0]["stage"] == "critical points" and result.cliques_complete


def test_the_alignment_moves_an_rdkit_molecule_onto_its_crystal_pose(ligands):
    ref = Chem.MolFromPDBFile(str(ligands[2]))
    probe = Chem.MolFromPDBFile(str(ligands[3]))
    result = surfcomp.match(ligands[2], ligands[3])
    moved = result[0].apply(probe)
    assert moved is not probe
    before = probe.GetConformer().GetPositions()
    np.testing.assert_array_equal(probe.GetConformer().GetPositions(), before)  # a copy moved
    after = moved.GetConformer().GetPositions()
    np.testing.assert_allclose(after, result[0].apply_to(before), atol=1e-9)
    # Both ligands are in one frame: the probe should land on the reference,
    # over the atoms both structures resolve, matched by name.
    def by_name(mol, xyz):
        return {a.GetPDBResidueInfo().GetName().strip(): xyz[a.GetIdx()] for a in mol.GetAtoms()}
    at_ref = by_name(ref, ref.GetConformer().GetPositions())
    at_moved = by_name(probe, after)
    common = sorted(set(at_ref) & set(at_moved))
    assert len(common) == 22
    deviation = np.array([at_moved[n] - at_ref[n] for n in common])
    assert np.sqrt((deviation ** 2).sum(axis=1).mean()) < 0.5  # measured 0.16 A


def test_bad_input_raises_and_never_crashes(ligands, tmp_path):
    with pytest.raises(ValueError, match=r"--probe-radius: value -1 is outside \[0, 10\]"):
        surfcomp.build_surface(ligands[0], probe_radius=-1)
    with pytest.raises(ValueError, match="unrecognised option '--no-such-option'"):
        surfcomp.match(ligands[0], ligands[1], no_such_option=1)
    with pytest.raises(ValueError, match="--ranking"):
        surfcomp.match(ligands[0], ligands[1], ranking="best")
    with pytest.raises(OSError, match="missing.sdf"):
        surfcomp.build_surface(tmp_path / "missing.sdf")
    garbage = tmp_path / "garbage.sdf"
    garbage.write_text("not a molecule\n")
    with pytest.raises(ValueError, match="garbage.sdf"):
        surfcomp.describe(garbage)
    with pytest.raises(TypeError):
        surfcomp.build_surface(42)
    with pytest.raises(ValueError, match="no conformer"):
        surfcomp.build_surface(Chem.MolFromSmiles("CCO"))
    mol = Chem.MolFromMolFile(str(ligands[0]), removeHs=False)
    for atom in mol.GetAtoms():
        atom.SetDoubleProp("PartialCharge", float("nan"))
    with pytest.raises(ValueError, match="partial charge of atom 1 is not finite"):
        surfcomp.build_surface(mol)


def test_partial_charges_of_an_rdkit_molecule_are_used(ligands):
    mol = Chem.MolFromMolFile(str(ligands[0]), removeHs=False)
    plain = surfcomp.build_surface(mol).properties["esp"]
    for atom in mol.GetAtoms():
        atom.SetDoubleProp("PartialCharge", 0.0)
    neutral = surfcomp.build_surface(mol).properties["esp"]
    assert np.abs(plain).max() > 1.0
    np.testing.assert_array_equal(neutral, 0.0)


def test_the_work_runs_without_the_gil(ligands):
    ticks = 0
    done = threading.Event()

    def work():
        surfcomp.match(ligands[2], ligands[3], principal_axes_starts=24)
        done.set()

    thread = threading.Thread(target=work)
    start = time.perf_counter()
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    elapsed = time.perf_counter() - start
    # With the GIL held for the whole match this loop could not run; it ticks throughout (a
    # quarter of the 1 ms sleeps it could fit is a margin for a loaded machine).
    assert elapsed > 0.05
    assert ticks > 0.25 * elapsed / 0.001


def test_a_screen_finds_its_query_first(program, cache, tmp_path):
    library = tmp_path / "bzr.sclib"
    sdf = tmp_path / "ten.sdf"
    text = (cache / "rdkit-data" / "bzr.sdf").read_text().split("$$$$\n")[:10]
    sdf.write_text("$$$$\n".join(text) + "$$$$\n")
    result = run([program, "library", "build", sdf, "-o", library])
    assert result.returncode == 0, result.stderr
    info = surfcomp.library_info(library)
    assert len(info["entries"]) == 10
    query = Chem.SDMolSupplier(str(sdf), removeHs=False)[3]
    hits = surfcomp.screen(query, library, top=5, candidates=3)
    assert len(hits) == 5 and hits[0].entry == 4 and hits[0].stage == 3
    assert hits[0].score == pytest.approx(1.0, abs=1e-3)
    np.testing.assert_allclose(hits[0].transform, np.eye(4), atol=1e-2)


def test_the_stubs_list_every_option_with_the_command_lines_default():
    tree = ast.parse((SOURCE_DIR / "python" / "surfcomp" / "__init__.pyi").read_text())
    functions = {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}
    for name in ("build_surface", "describe", "match", "screen"):
        arguments = functions[name].args
        stub = {a.arg: ast.literal_eval(d) for a, d in zip(arguments.kwonlyargs,
                                                            arguments.kw_defaults)}
        stub.pop("report", None)
        cli = {k.replace("-", "_"): v for k, v in surfcomp.option_defaults(name).items()}
        assert set(stub) == set(cli), name
        for option, default in cli.items():
            if default == "":
                assert stub[option] in (None, False), (name, option)
            elif isinstance(stub[option], str):
                assert stub[option] == default, (name, option)
            else:
                assert stub[option] == float(default), (name, option)


def test_python_m_surfcomp_mirrors_the_program(program):
    env = dict(os.environ)
    for arguments in (["--help"], ["match", "--help"], ["match"]):
        python = run(["/usr/bin/python3", "-m", "surfcomp", *arguments], env=env)
        native = run([program, *arguments])
        assert python.returncode == native.returncode
        assert python.stdout == native.stdout
        assert python.stderr == native.stderr


def test_the_example_script_runs(cache, tmp_path):
    script = SOURCE_DIR / "examples" / "python_align_two_ligands.py"
    result = run(["/usr/bin/python3", script, cache / "rdkit-data" / "4i23_1C9.pdb",
                  cache / "rdkit-data" / "4i24_1C9.pdb", tmp_path], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "heavy-atom RMSD to the crystal pose" in result.stdout
    assert (tmp_path / "4i24_1C9_on_4i23.sdf").exists()
    assert (tmp_path / "report.html").exists()


def test_a_report_is_checked_before_the_work_and_never_lands_on_an_input(ligands, tmp_path):
    before = ligands[0].read_bytes()
    with pytest.raises(ValueError, match=r"use \.html"):
        surfcomp.match(ligands[0], ligands[1], report=ligands[0])
    assert ligands[0].read_bytes() == before
    with pytest.raises(OSError, match="missing"):
        surfcomp.match(ligands[0], ligands[1], report=tmp_path / "missing" / "r.html")
    result = surfcomp.match(ligands[0], ligands[1], report=tmp_path / "r.html", refine_top=2)
    page = (tmp_path / "r.html").read_text()
    assert page.startswith("<!DOCTYPE html>") and len(result) > 0
