"""The Python module `surfcomp`: round trips, RDKit molecules against their files, a self-match,
errors, the GIL, the type stubs against the command line's options, and the example script."""
import ast
import csv
import inspect
import json
import os
import re
import pathlib
import linecache
import sys
import threading

import numpy as np
import pytest

from conftest import SOURCE_DIR, absent, run

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


def test_the_distance_transform_surface_lies_near_the_exact_one(ligands):
    exact = surfcomp.build_surface(ligands[2]).measures()
    fast = surfcomp.build_surface(ligands[2], ses_method="edt").measures()
    assert fast.euler_characteristic == 2 and fast.boundary_edges == 0
    # Measured on 4i23's ligand: area -1.5 %, volume +2.5 % (crevices thinner than a voxel).
    assert abs(fast.area - exact.area) < 0.03 * exact.area
    assert abs(fast.volume - exact.volume) < 0.04 * exact.volume


def test_a_surface_holds_its_arrays_and_round_trips_through_ply(ligands, tmp_path):
    surface = surfcomp.build_surface(ligands[0], probe_radius=1.4)
    assert surface.vertices.shape == (surface.n_vertices, 3)
    assert surface.faces.shape == (surface.n_faces, 3)
    assert surface.normals.shape == surface.vertices.shape
    np.testing.assert_allclose(np.linalg.norm(surface.normals, axis=1), 1.0, atol=1e-9)
    assert {"esp", "lp", "cc1", "cc2", "shape_index", "curvedness"} <= set(surface.properties)
    measures = surface.measures()
    assert measures.euler_characteristic == 2 and measures.boundary_edges == 0
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
    k = len(points.type)
    assert k > 5 and described.images.shape == (k, 8, 90)
    assert set(points.type) <= {"peak", "valley"} and points.position.shape == (k, 3)
    ok = points.status == "ok"
    assert ok.all()
    assert np.isfinite(described.images).any(axis=(1, 2)).all()
    assert described.options.image_sectors == 90
    described.save(tmp_path / "d.hsi")
    loaded = surfcomp.load_descriptors(tmp_path / "d.hsi")
    np.testing.assert_array_equal(loaded.images, described.images)
    np.testing.assert_array_equal(loaded.critical_points.position, points.position)
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
    assert best.atom_fit == pytest.approx(1.0, abs=1e-9)  # the atom polish's fit on itself


def test_the_atom_polish_is_a_keyword_and_orders_the_poses(ligands):
    polished = surfcomp.match(ligands[2], ligands[3])
    unpolished = surfcomp.match(ligands[2], ligands[3], atom_polish_sigma=0)
    keys = [a.overlay_score + a.atom_fit for a in polished[:5]]
    assert keys == sorted(keys, reverse=True) and 0 < polished[0].atom_fit <= 1
    assert all(a.atom_fit == 0 for a in unpolished)


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
    with pytest.raises(surfcomp.OptionError, match=r"probe_radius: value -1 is outside \[0, 10\]"):
        surfcomp.build_surface(ligands[0], probe_radius=-1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'no_such_option'"):
        surfcomp.match(ligands[0], ligands[1], no_such_option=1)
    with pytest.raises(ValueError, match="ranking: 'best' is not one of rank|number|vote"):
        surfcomp.match(ligands[0], ligands[1], ranking="best")
    with pytest.raises(TypeError, match="refine_top: expected an integer"):
        surfcomp.match(ligands[0], ligands[1], refine_top=2.5)
    with pytest.raises(surfcomp.OptionError, match="site_sphere '1,2,3,-1'"):
        surfcomp.match(ligands[0], ligands[1], site_sphere=(1, 2, 3, -1))
    with pytest.raises(surfcomp.OptionError, match="site_sphere '1,2,3,-1'"):  # NumPy rows
        surfcomp.match(ligands[0], ligands[1], site_sphere=np.array([[1, 2, 3, 4], [1, 2, 3, -1]]))
    with pytest.raises(surfcomp.OptionError, match=r"max_cliques: value 1{30} is outside"):
        surfcomp.match(ligands[0], ligands[1], max_cliques=int("1" * 30))
    with pytest.raises(surfcomp.FileError, match="missing.sdf"):
        surfcomp.build_surface(tmp_path / "missing.sdf")
    garbage = tmp_path / "garbage.sdf"
    garbage.write_text("not a molecule\n")
    with pytest.raises(surfcomp.InputError, match="garbage.sdf"):
        surfcomp.describe(garbage)
    with pytest.raises(TypeError):
        surfcomp.build_surface(42)
    with pytest.raises(surfcomp.InputError, match="no conformer"):
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
    # The main thread watches the worker's Python frame: it can see the worker parked on the
    # line that calls into the C++ match only while that call has let the GIL go. With the GIL
    # held for the whole call it could see that line at most at the call's two edges.
    worker = threading.Thread(
        target=surfcomp.match, args=(ligands[2], ligands[3]), kwargs={"principal_axes_starts": 24})
    worker.start()
    inside = 0
    while worker.is_alive() and inside < 1000:
        frame = sys._current_frames().get(worker.ident)
        if (frame is not None and frame.f_code.co_name == "match"
                and frame.f_code.co_filename.endswith(os.path.join("surfcomp", "__init__.py"))
                and "_surfcomp.match" in linecache.getline(frame.f_code.co_filename,
                                                           frame.f_lineno)):
            inside += 1
    worker.join()
    assert inside >= 100


def test_a_screen_finds_its_query_first(program, cache, tmp_path):
    library = tmp_path / "bzr.sclib"
    sdf = tmp_path / "ten.sdf"
    text = (cache / "rdkit-data" / "bzr.sdf").read_text().split("$$$$\n")[:10]
    sdf.write_text("$$$$\n".join(text) + "$$$$\n")
    result = run([program, "library", "build", sdf, "-o", library])
    assert result.returncode == 0, result.stderr
    info = surfcomp.library_info(library)
    assert len(info.entries) == 10 and info.molecules == 10
    assert [e.entry for e in info.entries] == list(range(1, 11))
    query = Chem.SDMolSupplier(str(sdf), removeHs=False)[3]
    hits = surfcomp.screen(query, library, top=5, candidates=3)
    assert len(hits) == 5 and hits[0].entry == 4 and hits[0].stage == 3
    assert hits[0].score == pytest.approx(1.0, abs=1e-3)
    np.testing.assert_allclose(hits[0].transform, np.eye(4), atol=1e-2)
    assert hits[0].molecule is None
    # A query without an ionic group ranks by the mean of the score and the shape of its poses
    # unless told otherwise; the poses and the molecules given the full match are the same.
    chemical = surfcomp.screen(query, library, top=5, candidates=3, chemistry="on")
    assert chemical[0].entry == 4 and any(abs(h.score - h.shape) > 1e-3 for h in chemical)
    assert {h.entry for h in hits if h.stage == 3} == {h.entry for h in chemical if h.stage == 3}
    posed = {h.entry: h for h in chemical}
    assert len([h for h in hits if h.entry in posed]) >= 3
    for hit in (h for h in hits if h.entry in posed):
        assert hit.shape == posed[hit.entry].shape
        assert hit.score == pytest.approx(0.5 * (posed[hit.entry].score + hit.shape), abs=1e-12)
        np.testing.assert_array_equal(hit.transform, posed[hit.entry].transform)
    shaped = surfcomp.screen(query, library, top=5, candidates=3, chemistry="off")
    assert all(h.score == h.shape for h in shaped)
    # The atom polish is the full match's last step: without it the stage-3 poses of the other
    # molecules move, and the other rows do not.
    unpolished = {h.entry: h for h in surfcomp.screen(query, library, top=5, candidates=3,
                                                      atom_polish_sigma=0)}
    moved = [h for h in hits if h.stage == 3 and h.entry != 4
             and np.abs(h.transform - unpolished[h.entry].transform).max() > 1e-3]
    assert moved
    for hit in (h for h in hits if h.stage == 2 and h.entry in unpolished):
        np.testing.assert_array_equal(hit.transform, unpolished[hit.entry].transform)
    # molecules=True: each hit moved onto the query as the CLI's --aligned-out writes it.
    moved = surfcomp.screen(query, library, top=3, candidates=3, molecules=True)
    aligned = tmp_path / "hits.sdf"
    result = run([program, "screen", sdf, library, "--record", "4", "-o", tmp_path / "h.csv",
                  "--top", "3", "--candidates", "3", "--aligned-out", aligned, "--aligned-top", "3"])
    assert result.returncode == 0, result.stderr
    written = [m for m in Chem.SDMolSupplier(str(aligned), removeHs=False)]
    assert [h.entry for h in moved] == [int(m.GetProp("surfcomp_entry")) for m in written]
    for hit, mol in zip(moved, written):
        assert hit.molecule.GetNumAtoms() == mol.GetNumAtoms()
        np.testing.assert_allclose(hit.molecule.GetConformer().GetPositions(),
                                   mol.GetConformer().GetPositions(), atol=1e-3)
    # The best hit is the query itself: moved onto it, its atoms sit on the query's.
    np.testing.assert_allclose(moved[0].molecule.GetConformer().GetPositions(),
                               query.GetConformer().GetPositions(), atol=0.05)
    # Two queries in one pass: each query's hits are its own screen's; the fused ranking takes
    # each molecule's best score (fusion max) or their mean.
    other = Chem.SDMolSupplier(str(sdf), removeHs=False)[7]
    alone = [surfcomp.screen(q, library, top=0, candidates=2) for q in (query, other)]
    for fusion in ("max", "mean"):
        both = surfcomp.screen_queries([query, other], library, top=0, candidates=2, fusion=fusion)
        assert len(both.hits) == 2 and len(both.fused) == 10
        for own, joint in zip(alone, both.hits):
            assert [(h.entry, h.score, h.stage) for h in own] == [(h.entry, h.score, h.stage)
                                                                  for h in joint]
        by_name = [{h.name: h.score for h in own} for own in alone]
        for row in both.fused:
            assert row.scores == pytest.approx((by_name[0][row.name], by_name[1][row.name]))
            expected = max(row.scores) if fusion == "max" else sum(row.scores) / 2
            assert row.score == pytest.approx(expected)
            assert row.query == 1 + row.scores.index(max(row.scores))
        assert [r.score for r in both.fused] == sorted((r.score for r in both.fused), reverse=True)
        if fusion == "max":  # each query finds itself, at about 1
            assert {both.fused[0].entry, both.fused[1].entry} == {4, 8}


def _help_defaults(program, subcommand):
    """The options of ``surfcomp SUBCOMMAND --help`` with their defaults as text ("" for none)."""
    text = run([program, *subcommand.split(), "--help"]).stdout
    return {m.group(1).replace("-", "_"): m.group(3) or ""
            for m in re.finditer(r"^  --([a-z0-9-]+)( arg(?: \(=([^)]*)\))?)?", text, re.M)}


@pytest.mark.parametrize("function,subcommand,own", [
    ("build_surface", "surf-build", {"ascii", "output", "help"}),
    ("describe", "hsi-build", {"output", "help"}),
    ("match", "match", {"output", "aligned_out", "report", "top", "all_alignments", "trace",
                        "help"}),
    # screen's --repair --scale --unit are screen_shapes' (a mesh query).
    ("screen", "screen", {"output", "aligned_out", "aligned_top", "help", "repair", "scale",
                          "unit"}),
    ("pockets", "pockets", {"output", "pdb_out", "help"}),
])
def test_signatures_and_help_come_from_one_option_table(program, function, subcommand, own):
    signature = inspect.signature(getattr(surfcomp, function))
    keywords = {name: p.default for name, p in signature.parameters.items()
                if p.kind is inspect.Parameter.KEYWORD_ONLY and name not in ("report", "molecules")}
    cli = {k: v for k, v in _help_defaults(program, subcommand).items() if k not in own}
    assert set(keywords) == set(cli), function
    for name, default in keywords.items():
        if default is None or default is False:
            assert cli[name] == "", (function, name)
        elif isinstance(default, str):
            assert cli[name] == default, (function, name)
        else:
            assert float(cli[name]) == default, (function, name)
    documented = getattr(surfcomp, function).__doc__
    assert all(f"    {name} (default " in documented for name in keywords), function


def test_the_stubs_match_the_module():
    tree = ast.parse((SOURCE_DIR / "python" / "surfcomp" / "__init__.pyi").read_text())
    functions = {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}
    for name in ("build_surface", "describe", "match", "screen", "pockets", "curvatures",
                 "critical_points", "geodesic_distances", "patch", "disk_map", "shape_image"):
        arguments = functions[name].args
        stub = {a.arg: ast.literal_eval(d) for a, d in zip(arguments.kwonlyargs,
                                                            arguments.kw_defaults)}
        module = {n: p.default for n, p in inspect.signature(getattr(surfcomp, name)).parameters.items()
                  if p.kind is inspect.Parameter.KEYWORD_ONLY}
        assert stub == module, name
        # The positional parameters too: names and defaults.
        positional = [a.arg for a in arguments.args]
        assert positional == [n for n, p in inspect.signature(getattr(surfcomp, name)).parameters
                              .items() if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD], name
    exported = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    # Everything the stubs declare is exported, and everything exported is declared.
    assert set(surfcomp.__all__) == exported
    assert all(hasattr(surfcomp, name) for name in surfcomp.__all__)


def test_the_stubs_options_are_written_from_the_option_tables():
    sys.path.insert(0, str(SOURCE_DIR / "scripts"))
    import python_stub
    stub = (SOURCE_DIR / "python" / "surfcomp" / "__init__.pyi").read_text()
    assert python_stub.generated(stub) == stub, \
        "the stubs are not current: run scripts/python_stub.py with the built module"
    # The check can fail: a table's option missing from the stub is written back.
    dropped = stub.replace("    pocket_max_volume: float = 0.0,\n", "", 1)
    assert python_stub.generated(dropped) == stub


def test_every_field_of_every_result_class_is_documented():
    for cls in (surfcomp.Alignment, surfcomp.Hit, surfcomp.OverlayScore, surfcomp.CriticalPoints,
                surfcomp.Patch, surfcomp.SurfaceMeasures, surfcomp.DescriptionParameters,
                surfcomp.LibraryEntry, surfcomp.LibraryInfo, surfcomp.Pocket,
                surfcomp.Curvatures, surfcomp.CriticalPointSet, surfcomp.GeodesicPatch):
        for field in cls._fields:
            doc = getattr(cls, field).__doc__
            assert doc and not doc.startswith("Alias for field"), (cls.__name__, field)


def test_critical_points_are_written_as_cp_detect_writes_them(program, ligands, tmp_path):
    cli = run([program, "cp-detect", ligands[0], "-o", tmp_path / "cli.json",
               "--points-out", tmp_path / "cli.pdb"])
    assert cli.returncode == 0, cli.stderr
    described = surfcomp.describe(ligands[0])
    described.write_critical_points(tmp_path / "py.pdb")
    assert (tmp_path / "py.pdb").read_text() == (tmp_path / "cli.pdb").read_text()
    described.write_critical_points(tmp_path / "py.json")
    import json
    ours = json.loads((tmp_path / "py.json").read_text())
    theirs = json.loads((tmp_path / "cli.json").read_text())
    assert ours["critical_points"] == theirs["critical_points"]
    assert ours["parameters"] == theirs["parameters"]
    with pytest.raises(surfcomp.InputError, match=r"\.json, \.pdb or \.ply"):
        described.write_critical_points(tmp_path / "py.txt")


def test_errors_share_one_base():
    for error in (surfcomp.InputError, surfcomp.OptionError, surfcomp.FileError):
        assert issubclass(error, surfcomp.Error)
    assert issubclass(surfcomp.OptionError, ValueError)
    assert issubclass(surfcomp.FileError, OSError)


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


def _mesh_cases():
    sys.path.insert(0, str(SOURCE_DIR / "bench"))
    import mesh_cases  # the registration benchmark's cases
    return mesh_cases


@pytest.fixture(scope="module")
def elephant(cache):
    mesh_cases = _mesh_cases()
    path = cache / "cgal" / "meshes" / "elephant.off"
    if not path.exists():
        absent(f"{path} is not fetched (datasets/fetch.sh)")
    vertices, faces = mesh_cases.read_off(path)
    # A partial view (40 % of the area), remeshed (each triangle split in four), with noise of
    # 0.5 % of the diagonal and a random rigid motion: the benchmark's case, fixed seed.
    return path, vertices, faces, mesh_cases.make_case(vertices, faces, 2, fraction=0.4,
                                                       noise=0.005)


def test_numpy_meshes_are_matched_by_shape_alone(elephant):
    _, vertices, faces, case = elephant
    result = surfcomp.match((vertices, faces), (case.vertices, case.faces))
    assert result.shape_only
    assert result.notes == ["<(V, F) arrays> carries no ESP and LP: matched by shape alone"] * 2
    # The unit is 1/12 of the larger side's size: the original's.
    areas = _mesh_cases().face_areas(vertices, faces)
    centroids = vertices[faces].mean(1)
    centre = areas @ centroids / areas.sum()
    radius = np.sqrt(areas @ ((centroids - centre) ** 2).sum(1) / areas.sum())
    assert result.unit == pytest.approx(radius / 12, rel=1e-9)
    assert _mesh_cases().motion_error(case, result[0].transform) < 0.02
    assert result[0].overlay.chem == 0.0 and result[0].overlay.atoms == 0.0
    # The part lies on the whole: nearly all of the noisy copy (noise 0.5 % of the diagonal,
    # the distance 1 unit, about 3 % of it), and about its share of the original.
    assert result[0].repeat_of is None
    assert result[0].coverage.score == result[0].coverage.probe > 0.95
    assert result[0].coverage.reference == pytest.approx(case.area_fraction, abs=0.08)
    # Distinct poses only, best first; repeats point at a better distinct one.
    poses = result.distinct(None)
    assert poses[0] is result[0] and len(poses) < len(result)
    assert all(result[a.repeat_of - 1].repeat_of is None for a in result if a.repeat_of)
    assert len(result.distinct()) == min(10, len(poses))
    # The critical points the pairs index, in each input's coordinates, on its vertices.
    ref_cps, probe_cps = result.reference_critical_points, result.probe_critical_points
    for cps, points in ((ref_cps, vertices), (probe_cps, case.vertices)):
        assert np.allclose(cps.position, points[cps.vertex], atol=1e-9 * np.ptp(points))
    pairs = np.vstack([a.cp_pairs for a in result if len(a.cp_pairs)])
    assert pairs[:, 0].max() < len(ref_cps.vertex) and pairs[:, 1].max() < len(probe_cps.vertex)


def test_the_program_recovers_a_partial_copy_of_a_mesh(program, elephant, tmp_path):
    path, vertices, faces, case = elephant
    mesh_cases = _mesh_cases()
    partial = tmp_path / "elephant_partial.off"
    mesh_cases.write_off(partial, case.vertices, case.faces)
    out = tmp_path / "result.json"
    done = run([program, "match", partial, path, "-o", out])
    assert done.returncode == 0, done.stderr
    assert done.stderr == "".join(f"note: {side} carries no ESP and LP: matched by shape alone\n"
                                  for side in (partial, path))
    document = json.loads(out.read_text())
    assert document["shape_only"] and document["scale"]["from"] == "auto"
    # REF is the partial copy: the transform moves the original into the copy's frame.
    transform = np.linalg.inv(np.array(document["alignments"][0]["transform"]))
    assert mesh_cases.motion_error(case, transform) < 0.02


def test_a_partial_copy_finds_its_mesh_in_a_library_of_meshes(program, elephant, tmp_path):
    path, _, _, case = elephant
    others = [path.parent / f"{name}.off" for name in ("cow", "knot")]
    library = tmp_path / "meshes.sclib"
    done = run([program, "library", "build", path, *others, "-o", library])
    assert done.returncode == 0, done.stderr
    hits = surfcomp.screen_shapes((case.vertices, case.faces), library, top=0)
    assert [h.name for h in hits][0] == "elephant" and len(hits) == 3
    # The copy lies on its mesh (noise 0.5 % of the diagonal; the tolerance is the copy's own
    # unit, about 2 % of it) and covers its share of it; far less of it on the others.
    assert hits[0].score > 0.9 and hits[1].score < hits[0].score - 0.2
    assert hits[0].entry_coverage == pytest.approx(case.area_fraction, abs=0.1)
    # The transform moves the mesh into the copy's frame.
    assert _mesh_cases().motion_error(case, np.linalg.inv(hits[0].transform)) < 0.02
    # The program's table gives the same ranking and scores as the module's on the same file.
    # Through the file (9 digits) the copy is found alike; a wrong shape's coverage can move by
    # a few thousandths, where single-precision refinements of nearly tied starts part ways.
    scan = tmp_path / "scan.off"
    _mesh_cases().write_off(scan, case.vertices, case.faces)
    from_file = surfcomp.screen_shapes(scan, library, top=0)
    assert [h.name for h in from_file] == [h.name for h in hits]
    assert [h.score for h in from_file] == pytest.approx([h.score for h in hits], abs=5e-3)
    assert from_file[0].score == pytest.approx(hits[0].score, abs=1e-6)
    done = run([program, "screen", scan, library, "-o", tmp_path / "hits.csv", "--top", "0"])
    assert done.returncode == 0, done.stderr
    with open(tmp_path / "hits.csv") as table:
        rows = list(csv.DictReader(table))
    assert [r["name"] for r in rows] == [h.name for h in from_file]
    assert [float(r["score"]) for r in rows] == pytest.approx([h.score for h in from_file],
                                                             abs=1e-6)
    with pytest.raises(surfcomp.InputError, match="a shape screen's query is a mesh"):
        surfcomp.screen_shapes(SOURCE_DIR / "README.md", library)
    # The molecule screen points at the shape screen.
    with pytest.raises(surfcomp.InputError, match=r"a library of meshes.*screen_shapes"):
        surfcomp.screen((case.vertices, case.faces), library)


def test_pockets_are_the_programs_and_a_pocket_is_a_site(program, shared, tmp_path):
    pdb = shared / "thermolysin" / "1THL.pdb"
    if not pdb.exists():
        absent(f"{pdb} is absent")
    found = surfcomp.pockets(pdb)
    cli = run([program, "pockets", pdb, "-o", tmp_path / "p.json"])
    assert cli.returncode == 0, cli.stderr
    import json
    written = json.loads((tmp_path / "p.json").read_text())["pockets"]
    assert [p.rank for p in found] == [p["rank"] for p in written]
    assert [list(p.center) for p in found] == [p["center"] for p in written]
    assert [p.lining_residues for p in found] == [p["lining_residues"] for p in written]
    with pytest.raises(surfcomp.InputError,
                       match=f"has {len(found)} pockets; pocket {len(found) + 1} was asked for"):
        surfcomp.match(pdb, pdb, site_pocket=len(found) + 1)
    # A pocket onto itself: the same lining residues, and the site score weighs them as asked.
    itself = surfcomp.match(pdb, pdb, site_pocket=1, site_lining_weight=0.5)
    assert itself.site["lining"] == 1.0
    assert itself.site["lining_weight"] == 0.5
    assert itself.site["score"] == pytest.approx((itself[0].overlay.score + 0.5) / 1.5, abs=1e-12)
    assert itself.site["interactions"] == 1.0
    assert itself.site["z_score"] is None  # the null is the default weight's
    assert itself.site["fields"]["coverage"] == pytest.approx(1.0, abs=1e-9)


def test_dock_is_the_programs_and_writes_its_poses(program, shared, tmp_path):
    folder = shared / "thermolysin"
    pdb, ligand = folder / "1TMN.pdb", folder / "ligands-original" / "ligand1TMN.sdf"
    quick = {"site_ligand": "0ZN", "search_chains": 6, "search_steps": 10}
    poses = surfcomp.dock(ligand, pdb, output=tmp_path / "p.sdf", threads=1, **quick)
    cli = run([program, "dock", ligand, pdb, "--site-ligand", "0ZN", "--search-chains", "6",
               "--search-steps", "10", "--json", tmp_path / "d.json"])
    assert cli.returncode == 0, cli.stderr
    import json
    written = json.loads((tmp_path / "d.json").read_text())["poses"]
    # The same poses whatever the threads (the program used all).
    assert [p.score for p in poses] == pytest.approx([w["score"] for w in written], abs=1e-12)
    assert [p.rank for p in poses] == list(range(1, len(poses) + 1))
    # Each SDF record is the ligand moved by its pose's transform.
    crystal = Chem.MolFromMolFile(str(ligand), removeHs=False).GetConformer().GetPositions()
    records = list(Chem.SDMolSupplier(str(tmp_path / "p.sdf"), removeHs=False))
    assert len(records) == len(poses)
    for record, pose in zip(records, poses):
        moved = crystal @ pose.transform[:3, :3].T + pose.transform[:3, 3]
        assert np.abs(record.GetConformer().GetPositions() - moved).max() < 1e-3
        assert int(record.GetProp("surfcomp_rank")) == pose.rank
    assert poses.conformers == [] and {p.conformer for p in poses} == {0}
    # conformers=N docks RDKit's conformers of the record instead, each pose naming its own.
    flexible = surfcomp.dock(ligand, pdb, conformers=2, threads=1, **quick)
    assert 1 <= len(flexible.conformers) <= 2
    assert {p.conformer for p in flexible} <= set(range(1, len(flexible.conformers) + 1))
    with pytest.raises(surfcomp.OptionError, match="SDF or MOL2"):
        surfcomp.dock(folder / "ligand1TMN.pdb", pdb, conformers=2, **quick)
    with pytest.raises(surfcomp.OptionError, match="search_chains"):
        surfcomp.dock(ligand, pdb, site_ligand="0ZN", search_chains=-1)
    with pytest.raises(surfcomp.InputError, match="pocket 1000 was asked for"):
        surfcomp.dock(ligand, pdb, site_pocket=1000)
    # A mesh has no atoms to dock into.
    with pytest.raises(surfcomp.InputError, match="a receptor is a protein structure"):
        surfcomp.dock(ligand, _sphere_arrays(5.0, 1), site_sphere=(0, 0, 0, 5))


def test_matrix_is_the_programs_and_matchs(program, shared, tmp_path):
    folder = shared / "thermolysin" / "ligands-original"
    files = [folder / f"ligand{e}.sdf" for e in ("1THL", "1TMN")]
    computed = surfcomp.matrix(files, transforms=True, output=tmp_path / "m.csv", threads=1)
    assert computed.symmetric and computed.left_out == []
    assert [m.source for m in computed.rows] == [str(f) for f in files]
    assert computed.scores.shape == (2, 2) and computed.transforms.shape == (2, 2, 4, 4)
    # The pair, one of each row's best two, is match's top score and transform; the diagonal the
    # self-overlay (1 in single precision).
    pair = surfcomp.match(files[0], files[1], threads=1)
    assert computed.scores[0, 1] == pytest.approx(pair[0].overlay.score, abs=1e-12)
    assert computed.transforms[0, 1] == pytest.approx(pair[0].transform, abs=1e-12)
    assert computed.scores[1, 0] == computed.scores[0, 1]
    assert np.diag(computed.scores) == pytest.approx([1.0, 1.0], abs=1e-5)
    assert computed.stage.tolist() == [[2, 3], [3, 2]]
    # The program writes the same CSV.
    cli = run([program, "matrix", *files, "-o", tmp_path / "cli.csv"])
    assert cli.returncode == 0, cli.stderr
    assert (tmp_path / "cli.csv").read_text() == (tmp_path / "m.csv").read_text()
    # Each row's best neighbour: the other molecule, its cell of the matrix.
    best = surfcomp.matrix(files, neighbours=1, transforms=True, threads=1)
    assert best.scores is None and best.stage is None
    assert best.neighbours.tolist() == [[1], [0]]
    assert best.neighbour_scores[:, 0] == pytest.approx([computed.scores[0, 1]] * 2, abs=1e-12)
    assert best.neighbour_stages.tolist() == [[3], [3]]
    assert best.transforms[1, 0] == pytest.approx(computed.transforms[1, 0], abs=1e-12)
    against = surfcomp.matrix(files[0], against=files[1])
    assert against.scores.shape == (1, 1) and against.transforms is None
    assert against.scores[0, 0] == computed.scores[0, 1]
    with pytest.raises(surfcomp.InputError, match="a set of one molecule"):
        surfcomp.matrix(files[0])
    with pytest.raises(surfcomp.OptionError, match="max_pairs"):
        surfcomp.matrix(files, max_pairs=0)


def test_screen_receptor_is_the_programs(program, shared, tmp_path):
    folder = shared / "thermolysin"
    pdb = folder / "1TMN.pdb"
    (tmp_path / "set.smi").write_text("CC(=O)Nc1ccc(O)cc1 paracetamol\n"
                                      "OC(=O)c1ccccc1O salicylic_acid\n")
    built = run([program, "library", "build", tmp_path / "set.smi", "--conformers", "2", "-o",
                 tmp_path / "lib.sclib"])
    assert built.returncode == 0, built.stderr
    quick = {"site_ligand": "0ZN", "candidates": 1, "fast_chains": 2, "fast_steps": 3,
             "search_chains": 4, "search_steps": 5}
    hits = surfcomp.screen_receptor(pdb, tmp_path / "lib.sclib", **quick)
    cli = run([program, "screen", "--receptor", pdb, tmp_path / "lib.sclib", "-o",
               tmp_path / "hits.csv"] + [x for k, v in quick.items()
                                         for x in ("--" + k.replace("_", "-"), str(v))])
    assert cli.returncode == 0, cli.stderr
    import csv
    rows = list(csv.DictReader((tmp_path / "hits.csv").open()))
    assert [h.name for h in hits] == [r["name"] for r in rows] and len(hits) == 2
    assert [h.stage for h in hits] == [2, 1] and all(h.area > 50.0 for h in hits)
    assert [h.score for h in hits] == pytest.approx([float(r["score"]) for r in rows], abs=1e-6)
    with pytest.raises(surfcomp.OptionError, match="fast_chains"):
        surfcomp.screen_receptor(pdb, tmp_path / "lib.sclib", site_ligand="0ZN", fast_chains=0)


def _sphere_arrays(radius, levels):
    """An octahedron subdivided `levels` times onto the sphere of `radius`: (V, F)."""
    vertices = [np.array(v, float) for v in
                [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(levels):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                point = vertices[a] + vertices[b]
                vertices.append(point / np.linalg.norm(point))
                middle[key] = len(vertices) - 1
            return middle[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            split += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        faces = split
    return radius * np.array(vertices), np.array(faces, dtype=np.int32)


@pytest.mark.parametrize("radius", [0.01, 1.0, 100.0])
def test_numpy_arrays_are_a_mesh_at_its_own_scale(radius):
    vertices, faces = _sphere_arrays(radius, 5)
    surface = surfcomp.build_surface((vertices, faces))
    # A sphere's curvature, per length of its own coordinates (convex negative), at any scale.
    assert surface.length_unit == pytest.approx(radius / 12, rel=2e-3)
    assert np.allclose(surface.properties["cc1"], -1 / radius, rtol=1e-3)
    assert np.allclose(surface.properties["shape_index"], 1.0, atol=1e-6)
    described = surfcomp.describe((vertices, faces))
    assert described.length_unit == pytest.approx(surface.length_unit, rel=1e-12)
    assert np.allclose(described.surface.vertices, vertices, rtol=1e-12, atol=1e-15 * radius)
    # Errors name the keyword arguments, not the command line's options.
    with pytest.raises(surfcomp.OptionError, match=r"^unit: value nan is outside") as refused:
        surfcomp.build_surface((vertices, faces), unit=float("nan"))
    with pytest.raises(surfcomp.InputError, match=r"more than max_vertices 10$"):
        surfcomp.describe((vertices, faces), max_vertices=10)
    assert "--" not in str(refused.value)
    # The Surface carries its unit into describe.
    chosen = surfcomp.build_surface((vertices, faces), unit=radius / 5)
    assert chosen.length_unit == pytest.approx(radius / 5)
    assert surfcomp.describe(chosen).length_unit == pytest.approx(radius / 5)


# --- (V, F) functions -----------------------------------------------------------------------


def _flat_disk(rings):
    """A flat disk of radius 1 in the z = 0 plane: a centre vertex and rings k = 1..rings of 6k
    vertices at radius k / rings, the first of each at angle 0, joined ring to ring by angle;
    counter-clockwise seen from +z. (V, F)."""
    vertices, ring_start = [(0.0, 0.0, 0.0)], [0]
    for k in range(1, rings + 1):
        ring_start.append(len(vertices))
        vertices += [(k / rings * np.cos(a), k / rings * np.sin(a), 0.0)
                     for a in 2 * np.pi * np.arange(6 * k) / (6 * k)]
    faces = []
    for k in range(1, rings + 1):
        inner = [0] if k == 1 else list(range(ring_start[k - 1], ring_start[k - 1] + 6 * (k - 1)))
        outer = list(range(ring_start[k], ring_start[k] + 6 * k))
        i = j = 0
        while i < len(inner) or j < len(outer):  # advance the ring whose next angle is nearer
            next_inner = (i + 1) / len(inner) if i < len(inner) else 2.0
            next_outer = (j + 1) / len(outer) if j < len(outer) else 2.0
            if len(inner) > 1 and next_inner <= next_outer:
                faces.append((inner[i % len(inner)], outer[j % len(outer)],
                              inner[(i + 1) % len(inner)]))
                i += 1
            else:
                faces.append((inner[i % len(inner)], outer[j % len(outer)],
                              outer[(j + 1) % len(outer)]))
                j += 1
                if len(inner) == 1 and j == len(outer):
                    i = 1
    return np.array(vertices), np.array(faces, dtype=np.int32)


def _bumpy_sphere(radius):
    """A sphere of `radius` with smooth bumps (up to 36 % of the radius), no mirror symmetry
    (whose ties rounding would break): peaks and valleys."""
    vertices, faces = _sphere_arrays(1.0, 4)
    x, y, z = vertices.T
    bumps = 1 + 0.2 * np.sin(3 * x + 1) * np.cos(2 * y + 0.3) + 0.16 * np.sin(4 * z - 0.5)
    return radius * vertices * bumps[:, None], faces


def _signed_areas(uv, faces):
    a, b, c = uv[faces[:, 0]], uv[faces[:, 1]], uv[faces[:, 2]]
    return 0.5 * ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])


@pytest.mark.parametrize("radius", [0.01, 100.0])
def test_a_spheres_curvature_is_minus_one_over_its_radius_at_any_scale(radius):
    vertices, faces = _sphere_arrays(radius, 5)
    k = surfcomp.curvatures((vertices, faces))
    # Convex negative, per length of the mesh's own coordinates (measured at both scales:
    # relative error 2e-8, shape index within 1e-8 of 1).
    assert k.length_unit == pytest.approx(radius / 12, rel=2e-3)
    for cc in (k.cc1, k.cc2):
        assert cc.shape == (len(vertices),) and np.allclose(cc, -1 / radius, rtol=1e-7, atol=0)
    assert np.allclose(k.shape_index, 1.0, rtol=0, atol=1e-7)
    assert np.allclose(k.curvedness, 1 / radius, rtol=1e-7, atol=0)
    # A Surface gives the curvature build_surface fitted; unit= fits it again.
    surface = surfcomp.build_surface((vertices, faces))
    assert np.array_equal(surfcomp.curvatures(surface).cc1, surface.properties["cc1"])
    refit = surfcomp.curvatures(surface, unit=radius / 6)
    assert refit.length_unit == radius / 6
    assert np.allclose(refit.cc1, -1 / radius, rtol=1e-6, atol=0)


def test_geodesic_distances_on_a_sphere_are_radius_times_angle():
    radius = 3.0
    vertices, faces = _sphere_arrays(radius, 5)
    angle = np.arccos(np.clip(vertices @ vertices[0] / radius ** 2, -1, 1))
    d = surfcomp.geodesic_distances((vertices, faces), 0)
    assert d.shape == (len(vertices),) and d[0] == 0.0
    # Fast marching: within 2 % of the great circle (measured: 1.4 % at most).
    assert np.all(np.abs(d - radius * angle) <= 0.02 * radius * angle + 1e-12)
    # Dijkstra along the edges is never shorter than fast marching (which also crosses
    # triangles), and zig-zags: 7.6 % longer on average here.
    edges = surfcomp.geodesic_distances((vertices, faces), 0, method="dijkstra")
    assert np.all(edges >= d - 1e-12) and edges.mean() > 1.05 * d.mean()
    # A bound: the same distances within it, inf beyond it (never NaN).
    bounded = surfcomp.geodesic_distances((vertices, faces), 0, max_distance=2.0)
    inside = d <= 2.0
    assert np.array_equal(bounded[inside], d[inside])
    assert np.all(np.isinf(bounded[d > 2.0 + 1e-9])) and not np.isnan(bounded).any()
    with pytest.raises(surfcomp.InputError, match=r"source_vertex 99999 is outside 0\.\."):
        surfcomp.geodesic_distances((vertices, faces), 99999)
    with pytest.raises(surfcomp.OptionError, match="max_distance: -1.0"):
        surfcomp.geodesic_distances((vertices, faces), 0, max_distance=-1)
    with pytest.raises(surfcomp.OptionError, match="'heat' is not one of dijkstra, fast-marching"):
        surfcomp.geodesic_distances((vertices, faces), 0, method="heat")


def test_a_flat_disks_harmonic_map_is_near_the_identity():
    vertices, faces = _flat_disk(12)
    # The whole disk: its border on the unit circle, the first border vertex (angle 0) at (1, 0).
    uv = surfcomp.disk_map((vertices, faces))
    assert uv.shape == (len(vertices), 2)
    r = np.linalg.norm(vertices[:, :2], axis=1)
    assert np.allclose(np.linalg.norm(uv, axis=1)[r > 0.999], 1.0, atol=1e-12)
    # The seed's weights, 1 / edge length, do not reproduce linear maps: measured 0.052.
    assert np.abs(uv - vertices[:, :2]).max() < 0.08
    # A patch of it: |uv| against r / R_patch, up to a rotation.
    piece = surfcomp.patch((vertices, faces), 0, radius=0.6)
    assert piece.surface_vertex[piece.center] == 0 and piece.genus == 0 and not piece.holes
    # Cut in the mesh's length unit and given back: its positions to rounding.
    assert np.allclose(piece.positions, vertices[piece.surface_vertex], rtol=0, atol=1e-15)
    assert np.allclose(piece.distance, np.linalg.norm(piece.positions, axis=1), atol=1e-12)
    assert piece.radius == 0.6 and piece.distance.max() <= 0.6 * 1.05 + 1e-12
    uv = surfcomp.disk_map(piece)
    r = np.linalg.norm(piece.positions[:, :2], axis=1)
    r_patch = r[piece.outer_boundary].mean()
    assert np.abs(np.linalg.norm(uv, axis=1) - r / r_patch).max() < 0.08  # measured 0.051
    assert (_signed_areas(uv, piece.faces) > 0).all()


def test_every_method_maps_a_flat_disk_without_flips():
    vertices, faces = _flat_disk(8)
    for method in ("harmonic", "tutte", "mean-value", "discrete-conformal",
                   "discrete-authalic", "lscm", "arap"):
        uv = surfcomp.disk_map((vertices, faces), method)
        assert uv.shape == (len(vertices), 2) and np.isfinite(uv).all(), method
        if method in ("lscm", "arap"):  # free border: within the unit disk's square
            assert np.abs(uv).max() == pytest.approx(1.0, abs=1e-12), method
        else:
            assert np.linalg.norm(uv, axis=1).max() <= 1 + 1e-12, method
        assert (_signed_areas(uv, faces) > 0).all(), method
    # Weights that reproduce linear maps give a flat disk with a circular border the identity.
    for method in ("mean-value", "discrete-conformal"):
        assert np.abs(surfcomp.disk_map((vertices, faces), method)
                      - vertices[:, :2]).max() < 1e-9, method
    with pytest.raises(surfcomp.OptionError, match="'mean_value' is not one of harmonic, tutte"):
        surfcomp.disk_map((vertices, faces), "mean_value")
    closed = _sphere_arrays(1.0, 2)
    with pytest.raises(surfcomp.InputError, match="no border"):
        surfcomp.disk_map(closed)


@pytest.mark.parametrize("radius", [0.01, 100.0])
def test_critical_points_are_cp_detects_as_vertex_indices(program, tmp_path, radius):
    vertices, faces = _bumpy_sphere(radius)
    found = surfcomp.critical_points((vertices, faces))
    assert len(found.vertex) > 2 and set(found.type) == {"peak", "valley"}
    assert np.allclose(found.position, vertices[found.vertex], rtol=1e-14, atol=0)
    assert found.length_unit == surfcomp.curvatures((vertices, faces)).length_unit
    mesh = tmp_path / "bumpy.off"
    with open(mesh, "w") as out:
        out.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        out.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in vertices)
        out.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
    cli = run([program, "cp-detect", mesh, "-o", tmp_path / "cps.json"])
    assert cli.returncode == 0, cli.stderr
    theirs = json.loads((tmp_path / "cps.json").read_text())["critical_points"]
    assert [p["vertex"] for p in theirs] == found.vertex.tolist()
    assert [p["type"] for p in theirs] == found.type.tolist()
    # The same points describe finds, with their patches and images.
    described = surfcomp.describe((vertices, faces))
    assert np.array_equal(described.critical_points.vertex, found.vertex)
    assert list(described.critical_points.type) == list(found.type)
    imaged = [i for i, s in enumerate(described.critical_points.status) if s == "ok"]
    assert imaged
    for i in imaged[:3]:
        vertex = int(found.vertex[i])
        stored = described.patch(i)
        piece = surfcomp.patch((vertices, faces), vertex)
        assert piece.surface_vertex.tolist() == stored.surface_vertex
        assert np.array_equal(piece.faces, stored.faces)
        assert np.allclose(surfcomp.disk_map(piece), stored.uv, atol=1e-9)
        image = surfcomp.shape_image((vertices, faces), vertex)
        assert image.shape == described.images[i].shape
        assert np.allclose(image, described.images[i], atol=1e-9, equal_nan=True)


def test_a_shape_image_has_its_grid_and_a_spheres_is_a_cap():
    vertices, faces = _sphere_arrays(7.0, 4)
    image = surfcomp.shape_image((vertices, faces), 0, image_rings=8, image_sectors=90)
    assert image.shape == (8, 90)
    assert np.allclose(image, 1.0, atol=1e-6)  # the shape index of a sphere, everywhere
    default = surfcomp.shape_image((vertices, faces), 0)
    assert default.shape == (16, 180)
    # A radius in the mesh's coordinates: a quarter of the sphere's.
    assert surfcomp.shape_image((vertices, faces), 0, radius=1.75).shape == (16, 180)
    flat, flat_faces = _flat_disk(8)
    assert surfcomp.shape_image((flat, flat_faces), 0).shape == (16, 180)
    with pytest.raises(surfcomp.InputError, match="center_vertex 216: its patch reaches the mesh's"):
        surfcomp.shape_image((flat, flat_faces), len(flat) - 1)  # on the disk's border


def test_the_array_functions_refuse_bad_arrays_with_one_message():
    vertices, faces = _sphere_arrays(1.0, 2)
    with pytest.raises(surfcomp.InputError, match=r"V of shape \(n, 3\).*got V \(\d+, 2\)"):
        surfcomp.curvatures((vertices[:, :2], faces))
    with pytest.raises(surfcomp.InputError, match="center_vertex -1 is outside"):
        surfcomp.patch((vertices, faces), -1)
    with pytest.raises(surfcomp.InputError, match="center_vertex 1000 is outside"):
        surfcomp.shape_image((vertices, faces), 1000)
    with pytest.raises(surfcomp.OptionError, match="radius: 0.0"):
        surfcomp.patch((vertices, faces), 0, radius=0)
    with pytest.raises(surfcomp.InputError, match="center_vertex 0: no triangle of its patch"):
        surfcomp.patch((vertices, faces), 0, radius=1e-6)
    with pytest.raises(surfcomp.InputError, match="no triangle \\(F is empty\\)"):
        surfcomp.curvatures((vertices, np.zeros((0, 3), int)))
    # Three triangles on one edge: not a manifold mesh.
    fan = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1.0]]),
           np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]]))
    with pytest.raises(surfcomp.InputError, match="non-manifold.*repair=True"):
        surfcomp.geodesic_distances(fan, 0)
    with pytest.raises(TypeError, match=r"expected \(V, F\) arrays or a Surface"):
        surfcomp.curvatures("mesh.off")
    with pytest.raises(surfcomp.OptionError):
        surfcomp.critical_points((vertices, faces), critical_point_radius=-1)
