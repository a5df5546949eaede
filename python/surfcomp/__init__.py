"""surfcomp: compare molecular surfaces from Python.

Finds where two molecules (two ligands, or two protein binding sites) look and feel alike on
their surfaces, and returns ranked rigid alignments that move the probe onto the reference:
solvent-excluded surfaces with ESP, lipophilic potential and curvature, shape critical points,
harmonic shape images, association-graph cliques and a Gaussian overlay refinement. The work is
done by the same C++ libraries as the ``surfcomp`` program, with the GIL released.

Inputs (``mol`` below) are a path (SDF, MOL, MOL2, PDB, PQR; a mesh: PLY, MSMS, OFF, OBJ; a
``.hsi`` file where a description is accepted), or an ``rdkit.Chem.Mol`` with a conformer (its
hydrogens as the molecule has them; its partial charges when every atom carries ``PartialCharge``,
``_TriposPartialCharge`` or ``_GasteigerCharge``, else computed as for a file), or a
:class:`Surface` or :class:`Descriptors` from this module.

Options are keyword arguments with the command line's names (``probe_radius`` for
``--probe-radius``), defaults, ranges and help, all from the library's one definition of each
option: ``help(surfcomp.match)`` and ``inspect.signature`` show them. Every error the library
raises derives from :class:`Error`: :class:`OptionError` (also a ``ValueError``) for a value
outside its range, :class:`InputError` (a ``ValueError``) for bad input, :class:`FileError`
(an ``OSError``) for a file that cannot be read or written. A keyword the function does not
take, or a value of the wrong type, raises ``TypeError``.

Example::

    import surfcomp
    from rdkit import Chem
    ref = Chem.MolFromMolFile("ref.sdf", removeHs=False)
    result = surfcomp.match(ref, "probe.sdf")
    best = result[0]
    print(best.rank, best.overlay_score, best.transform)
    moved = best.apply(Chem.MolFromMolFile("probe.sdf", removeHs=False))
"""

from __future__ import annotations

import inspect
import os
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _surfcomp
from ._surfcomp import Descriptors, Error, FileError, InputError, OptionError, Surface

__all__ = [
    "Alignment", "CoverageScore", "CriticalPointSet", "CriticalPoints", "Curvatures",
    "DescriptionParameters", "Descriptors", "DockPose", "DockResult", "Error", "FileError",
    "FusedHit", "GeodesicPatch",
    "Hit", "InputError", "LibraryEntry", "LibraryInfo", "MatchResult", "MatrixMember",
    "OptionError",
    "OverlayScore", "Patch", "Pocket", "ReceptorHit", "Screens", "ShapeHit",
    "SimilarityMatrix", "Surface",
    "SurfaceMeasures",
    "build_surface", "critical_points", "curvatures", "describe", "disk_map", "dock",
    "geodesic_distances",
    "library_info", "load_descriptors", "match", "matrix", "option_table", "patch", "pockets",
    "screen",
    "screen_queries", "screen_receptor", "screen_shapes", "shape_image",
]
__version__ = "0.1.0"

# Atom properties taken as partial charges, in this order of preference.
_CHARGE_PROPERTIES = ("PartialCharge", "_TriposPartialCharge", "_GasteigerCharge")


def _is_rdkit_molecule(obj: Any) -> bool:
    return hasattr(obj, "GetNumAtoms") and hasattr(obj, "GetConformer")


def _partial_charges(mol) -> Optional[List[float]]:
    atoms = list(mol.GetAtoms())
    for name in _CHARGE_PROPERTIES:
        if atoms and all(atom.HasProp(name) for atom in atoms):
            return [float(atom.GetProp(name)) for atom in atoms]
    return None


def _input(obj: Any):
    """A path, Surface or Descriptors as is; an RDKit molecule as its MDL block; a mesh given as
    ``(V, F)`` (NumPy-like, V (n, 3) positions, F (m, 3) 0-based triangles) as a tuple."""
    if isinstance(obj, (Surface, Descriptors)):
        return obj
    if isinstance(obj, (tuple, list)) and len(obj) == 2:
        return tuple(obj)
    if isinstance(obj, (str, os.PathLike)):
        return os.fspath(obj)
    if _is_rdkit_molecule(obj):
        from rdkit import Chem  # imported only when an RDKit molecule is given

        if obj.GetNumConformers() == 0:
            raise InputError("the RDKit molecule has no conformer: surfcomp needs 3D coordinates")
        name = obj.GetProp("_Name") if obj.HasProp("_Name") and obj.GetProp("_Name") else "mol"
        block = Chem.MolToMolBlock(obj, includeStereo=True, kekulize=True)
        return _surfcomp.MoleculeBlock(block, f"<rdkit Mol {name}>", _partial_charges(obj))
    raise TypeError(f"expected a path, an RDKit molecule, a Surface, a Descriptors or (V, F), "
                    f"got {type(obj).__name__}")


_ANNOTATIONS = {"real": float, "integer": int, "text": Optional[str], "choice": str,
                "flag": bool, "spheres": Sequence[Sequence[float]]}


def _keyword_options(function_name: str):
    """Gives the decorated function the keyword options of the library's option table for
    ``function_name``: its signature (names, defaults, types) and an Options section of its
    docstring. The function takes them as ``**options`` and hands them to the library, which
    checks each against the same definition."""
    table = _surfcomp.option_table(function_name)

    def decorate(function):
        signature = inspect.signature(function)
        fixed = [p for p in signature.parameters.values()
                 if p.kind is not inspect.Parameter.VAR_KEYWORD]
        options = [inspect.Parameter(o["name"], inspect.Parameter.KEYWORD_ONLY,
                                     default=o["default"],
                                     annotation=(Optional[_ANNOTATIONS[o["kind"]]]
                                                 if o["default"] is None
                                                 else _ANNOTATIONS[o["kind"]]))
                   for o in table]
        function.__signature__ = signature.replace(parameters=fixed + options)
        lines = [f"    {o['name']} (default {o['default']!r}): {o['help']}" for o in table]
        function.__doc__ = (function.__doc__ or "") + "\n\n    Options:\n\n" + "\n".join(lines)
        function._option_table = function_name  # scripts/python_stub.py writes the stubs from it
        return function

    return decorate


def _documented(cls, **docs):
    """Gives each field of the named tuple ``cls`` its docstring (``help()`` shows them); every
    field must have one."""
    if set(docs) != set(cls._fields):
        raise AssertionError(f"{cls.__name__}: fields {sorted(set(cls._fields) ^ set(docs))}")
    for name, doc in docs.items():
        getattr(cls, name).__doc__ = doc
    return cls


class OverlayScore(NamedTuple):
    """The Gaussian overlay score of an alignment and its terms (Tanimoto coefficients)."""

    score: float
    shape: float
    chem: float
    atoms: float


_documented(OverlayScore,
            score="(shape + w_chem chem + w_atoms atoms) / (1 + w_chem + w_atoms)",
            shape="shape Tanimoto of the two surfaces' Gaussian samples",
            chem="ESP/LP-weighted Tanimoto of the samples",
            atoms="same-element heteroatom Tanimoto (0 where either side has no atoms)")


class CoverageScore(NamedTuple):
    """How much of each surface lies on the other under an alignment (fractions of area)."""

    score: float
    reference: float
    probe: float


_documented(CoverageScore,
            score="the larger of reference and probe: the part's fraction in a partial match, "
                  "near 1 for a true one",
            reference="the fraction of the reference within coverage_distance of the moved probe",
            probe="the fraction of the moved probe within coverage_distance of the reference")


class Alignment(NamedTuple):
    """One rigid alignment of the probe onto the reference, best first by ``rank``."""

    rank: int
    source: str
    transform: np.ndarray
    rmsd: float
    n_points: int
    r_chem: float
    consensus: float
    refined: bool
    overlay: OverlayScore
    atom_fit: float
    coverage: CoverageScore
    icp: bool
    repeat_of: Optional[int]
    cp_pairs: np.ndarray
    parent: Optional[int]
    children: List[int]

    @property
    def overlay_score(self) -> float:
        """The overlay score (shape + chemistry + atoms Tanimoto, weighted) of ``transform``."""
        return self.overlay.score

    def apply_to(self, points: np.ndarray) -> np.ndarray:
        """``points`` (n, 3) moved by the alignment."""
        points = np.asarray(points, dtype=float)
        return points @ self.transform[:3, :3].T + self.transform[:3, 3]

    def apply(self, mol, conf_id: int = -1):
        """A copy of the RDKit molecule ``mol`` with conformer ``conf_id`` moved by the alignment."""
        from rdkit import Chem
        from rdkit.Chem import rdMolTransforms

        moved = Chem.Mol(mol)
        # RDKit reads the matrix's buffer in C order.
        rdMolTransforms.TransformConformer(moved.GetConformer(conf_id),
                                           np.ascontiguousarray(self.transform))
        return moved


_documented(
    Alignment,
    rank="1-based position, best first",
    source='"cliques" (critical-point correspondences) or "principal_axes" (a refined '
           "principal-axes start; then rmsd, n_points, r_chem and consensus are 0)",
    transform="(4, 4) moving probe coordinates into the reference's frame: "
              "x' = transform[:3, :3] @ x + transform[:3, 3]",
    rmsd="RMSD of the clique's least-squares fit, A",
    n_points="corresponding image points of the fit",
    r_chem="ESP correlation of the corresponding points",
    consensus="the consensus ranking's value",
    refined="whether the overlay refinement moved this pose",
    overlay="the overlay score of the pose and its terms (OverlayScore)",
    atom_fit="two molecules: the heavy-atom Tanimoto of the atom polish (like elements, "
             "Gaussians of atom_polish_sigma), 0-1; the scored alignments go by "
             "overlay.score + atom_polish_weight * atom_fit. 0 otherwise",
    coverage="how much of each surface lies on the other under the pose (CoverageScore); "
             "measured for the first refine_top distinct poses, 0 for the others",
    icp="whether the ICP polish (icp_top) moved this pose",
    repeat_of="rank of a better alignment whose pose this one repeats (no sampled probe point "
              "moved by more than 0.5 A), or None for a distinct pose",
    cp_pairs="(k, 2) (reference, probe) critical-point indices of the clique, rows of "
             "MatchResult.reference_critical_points and probe_critical_points",
    parent="rank of the alignment this one was merged into, or None",
    children="ranks of the alignments merged into this one")


class MatchResult(list):
    """The alignments of a match, best first (a list of :class:`Alignment`: every cluster of the
    merge tree, repeats marked by ``repeat_of``), with what the match did."""

    #: Each side's critical points, as the alignments' ``cp_pairs`` index them (in the inputs'
    #: coordinates).
    reference_critical_points: "CriticalPoints"
    probe_critical_points: "CriticalPoints"

    def distinct(self, top: Optional[int] = 10) -> List[Alignment]:
        """The first ``top`` distinct poses (``repeat_of`` None), best first; all with None."""
        poses = [a for a in self if a.repeat_of is None]
        return poses if top is None else poses[:top]

    #: The association graph after each filter: dicts of stage, nodes, edges, ms.
    trace: List[Dict[str, Any]]
    #: Milliseconds per step of the match.
    timing_ms: Dict[str, float]
    #: What the match cut, one line each (the clique search stopped early).
    warnings: List[str]
    #: What a reader may want to know, one line each.
    notes: List[str]
    #: True when ESP, LP and atoms were set aside (asked, or a side carries no ESP and LP).
    shape_only: bool
    #: Two sites on structures: {"lining": the lining residues' similarity, "lining_weight": w,
    #: "score": the site score, (top overlay score + w lining) / (1 + w), "z_score": how many
    #: spreads that lies above unrelated sites' of the same size (about 0 unrelated, 3 or more
    #: rare without a relation; None with other site settings), "interactions": the
    #: similarity of the sites' surface points' interaction classes, "fields": {"similarity",
    #: "coverage"}, those points compared under the top alignment (coverage: the smaller site's
    #: agreement, 1 when it lies class for class inside the other)}; None otherwise.
    site: Optional[Dict[str, Any]]
    #: The length unit the match ran at, in the inputs' coordinates (1 for molecules; see the
    #: ``scale`` and ``unit`` options). Transforms and RMSDs are in the inputs' coordinates.
    unit: float
    #: Cliques found.
    cliques: int
    #: Whether the clique search finished within its budget.
    cliques_complete: bool
    #: Milliseconds spent reading, building surfaces and describing.
    prepare_ms: float
    #: Milliseconds spent matching.
    match_ms: float


class Hit(NamedTuple):
    """One molecule of a screen, best first."""

    rank: int
    entry: int
    name: str
    source: str
    record: int
    conformer: int
    score: float
    stage: int
    shape: float
    chem: float
    atoms: float
    fast_score: float
    transform: np.ndarray
    molecule: Any = None


_documented(
    Hit,
    rank="1-based position, best first",
    entry="1-based library entry of the molecule's best conformer",
    name="the molecule's name",
    source="the file the molecule came from",
    record="1-based record of that file",
    conformer="the conformer's number (0: the record's own coordinates)",
    score="what ranks the hit (``chemistry``): the overlay score, its shape term, or their "
          "mean, of the full match (stage 3), the refined overlay (stage 2) or the fast one "
          "(stage 1)",
    stage="the stage whose score ``score`` is (3 for the full-match candidates)",
    shape="shape Tanimoto of the pose",
    chem="ESP/LP Tanimoto of the pose",
    atoms="same-element heteroatom Tanimoto of the pose",
    fast_score="the stage-1 score",
    transform="(4, 4) moving the hit into the query's frame",
    molecule="with screen(..., molecules=True): the hit as an RDKit molecule moved onto the "
             "query (a pocket hit: its structure), else None")


class ReceptorHit(NamedTuple):
    """One molecule of a screen into a receptor's pocket (:func:`screen_receptor`), best
    first."""

    rank: int
    entry: int
    name: str
    source: str
    record: int
    conformer: int
    score: float
    stage: int
    contact: float
    clash: float
    esp: float
    lp: float
    deepest: float
    area: float
    fast_score: float
    transform: np.ndarray


_documented(
    ReceptorHit,
    rank="1-based position, best first",
    entry="1-based library entry of the molecule's best conformer",
    name="the molecule's name",
    source="the file the molecule came from",
    record="1-based record of that file",
    conformer="the conformer's number (0: the record's own coordinates)",
    score="the complementarity score of the stage's best pose (DockPose.score)",
    stage="2: the full dock (the candidates, ranked first); 1: the fast dock",
    contact="the score's terms, as DockPose's",
    clash="A^2",
    esp="over the contact",
    lp="over the contact",
    deepest="A",
    area="A^2, of the ligand's surface the score is a mean over (``rank_by='total'``: score x "
         "area ranks)",
    fast_score="the stage-1 score of that conformer",
    transform="(4, 4) moving the entry's molecule into the receptor's frame")


class FusedHit(NamedTuple):
    """One molecule of a fused ranking of several queries, best first."""

    rank: int
    entry: int
    name: str
    source: str
    record: int
    conformer: int
    score: float
    query: int
    scores: Tuple[float, ...]


_documented(
    FusedHit,
    rank="1-based position, best first",
    entry="1-based library entry of the molecule's best conformer against its best query",
    name="the molecule's name",
    source="the file the molecule came from",
    record="1-based record of that file",
    conformer="that entry's conformer (0: the record's own coordinates)",
    score="the fused score: the maximum or the mean of `scores` (the fusion option)",
    query="1-based: the query that scores the molecule highest",
    scores="the molecule's score against each query, in query order")


class Screens(NamedTuple):
    """Several queries screened in one pass."""

    hits: List[List[Hit]]
    fused: List[FusedHit]


_documented(
    Screens,
    hits="per query, its hits as screen() gives them for that query alone",
    fused="every molecule ranked by its fused score (empty for one query)")


class CriticalPoints(NamedTuple):
    """The critical points of a description, one row per point."""

    position: np.ndarray
    normal: np.ndarray
    vertex: np.ndarray
    type: np.ndarray
    status: np.ndarray
    cc1: np.ndarray
    cc2: np.ndarray
    shape_index: np.ndarray
    curvedness: np.ndarray
    esp: np.ndarray
    lp: np.ndarray


_documented(
    CriticalPoints,
    position="(n, 3) positions, A",
    normal="(n, 3) unit outward normals",
    vertex="(n,) surface vertex indices",
    type='(n,) "peak" or "valley"',
    status='(n,) "ok" or why the point has no image',
    cc1="(n,) first principal curvature at the vertex, 1/A (convex < 0)",
    cc2="(n,) second principal curvature, 1/A",
    shape_index="(n,) shape index averaged over the property disc, [-1, 1]",
    curvedness="(n,) curvedness at the vertex, 1/A",
    esp="(n,) ESP averaged over the property disc, kcal/(mol e)",
    lp="(n,) lipophilic potential averaged over the property disc")


class Patch(NamedTuple):
    """A critical point's geodesic patch and its harmonic map onto the unit disk."""

    status: str
    center: int
    positions: np.ndarray
    faces: np.ndarray
    surface_vertex: List[int]
    distance: np.ndarray
    uv: np.ndarray
    outer_boundary: List[int]


_documented(
    Patch,
    status='"ok" or why the point has no patch or map',
    center="the patch vertex at the critical point",
    positions="(p, 3) patch vertex positions, A",
    faces="(f, 3) patch triangles",
    surface_vertex="the surface vertex of each patch vertex",
    distance="(p,) on-surface distance from the critical point, A",
    uv="(p, 2) harmonic map onto the unit disk",
    outer_boundary="patch vertices of the outer boundary, in order")


class SurfaceMeasures(NamedTuple):
    """Global measures of a surface."""

    area: float
    volume: float
    euler_characteristic: int
    boundary_edges: int


_documented(SurfaceMeasures, area="area, A^2", volume="enclosed volume, A^3 (closed surfaces)",
            euler_characteristic="V - E + F (2 for a sphere)",
            boundary_edges="edges with one triangle (0 for a closed surface)")


class DescriptionParameters(NamedTuple):
    """The parameters a description was built with."""

    critical_point_radius: float
    disc_radius: float
    patch_radius: float
    image_rings: int
    image_sectors: int
    weights: str
    image_property: str


_documented(DescriptionParameters, critical_point_radius="r_cp, A",
            disc_radius="radius of the disc the critical points' properties average over, A",
            patch_radius="patch radius, A",
            image_rings="rings of the image grid", image_sectors="sectors of the image grid",
            weights="spring weights of the harmonic maps",
            image_property="the vertex property the images resample")


class LibraryEntry(NamedTuple):
    """One entry (a conformer) of a screening library."""

    entry: int
    name: str
    source: str
    record: int
    conformer: int
    heavy_atoms: int
    site_spheres: int


_documented(LibraryEntry, entry="1-based entry number", name="the molecule's name",
            source="the file it came from", record="1-based record of that file",
            conformer="conformer number (0: the record's own coordinates)",
            heavy_atoms="heavy atoms of the molecule",
            site_spheres="spheres of a pocket entry's site (0 for a molecule)")


class DockPose(NamedTuple):
    """A pose of a ligand in a receptor's site (:func:`dock`), with its complementarity score
    and the score's terms, each a mean over the ligand's surface sample."""

    rank: int
    score: float
    contact: float
    clash: float
    esp: float
    lp: float
    deepest: float
    intersects: bool
    transform: np.ndarray
    start: int
    conformer: int
    cp_pairs: np.ndarray


_documented(DockPose, rank="1-based, best first",
            score="contact + w_esp esp + w_lp lp - w_clash clash - w_site outside^2",
            contact="the fraction of the ligand's surface in contact with the receptor, 0 to 1",
            clash="A^2, the mean squared depth beyond clash_tolerance inside the receptor's atoms",
            esp="over the contact, minus the product of the two sides' ESP z-scores",
            lp="over the contact, the product of the two sides' LP z-scores",
            deepest="A, the largest depth of a ligand surface point inside the receptor's atoms",
            intersects="deeper than twice clash_tolerance: ranked after every pose that is not",
            transform="4 x 4, moves the ligand as given (or its conformer) into the receptor's "
                      "frame",
            start="the clique alignment it started from (1-based), 0 for the Monte Carlo search",
            conformer="0: the ligand as given; k: DockResult.conformers[k - 1] (conformers=N)",
            cp_pairs="(k, 2) (receptor, ligand) critical-point indices of that clique")


class DockResult(list):
    """The distinct poses of a dock, best first (a list of :class:`DockPose`), with what the
    dock did."""

    #: With conformers=N: the docked conformers as MDL mol blocks (DockPose.conformer).
    conformers: List[str]
    #: Clique alignments of the complementary association graph.
    starts: int
    #: A^3: the free volume of the receptor's site, and the ligand's surface's volume.
    site_volume: float
    ligand_volume: float
    #: What a reader may want to know, one line each.
    notes: List[str]
    #: Milliseconds per step of the dock.
    timing_ms: Dict[str, float]


class Pocket(NamedTuple):
    """A pocket of a protein structure, found without a ligand (:func:`pockets`)."""

    rank: int
    score: float
    volume: float
    buriedness: float
    cavity: int
    center: Tuple[float, float, float]
    lining_residues: List[str]
    spheres: List[Tuple[float, float, float, float]]


_documented(Pocket, rank="1-based, by decreasing score",
            score="the sum of its alpha spheres' buriedness",
            volume="A^3, of its alpha spheres shrunk by 1.6 A",
            buriedness="its alpha spheres' mean buriedness, 0 to 1",
            cavity="the 1-based cavity it is part of (the parts of a cavity split by "
                   "pocket_max_volume share it)",
            center="the mean of its alpha sphere centres, A",
            lining_residues='the residues its alpha spheres touch, "HIS142:A"',
            spheres="its alpha spheres (x, y, z, r), A: a binding site's spheres")


class LibraryInfo(NamedTuple):
    """A screening library's index, as ``surfcomp library info`` reports it."""

    version: int
    settings: str
    bytes: int
    molecules: int
    largest_entry_bytes: int
    entries: List[LibraryEntry]


_documented(LibraryInfo, version="file format version", settings="how the library was built",
            bytes="size of the file", molecules="distinct molecules (source, record, name)",
            largest_entry_bytes="size of the largest entry",
            entries="the entries in library order (LibraryEntry)")


class Curvatures(NamedTuple):
    """Per-vertex curvature of a mesh (:func:`curvatures`), as :func:`build_surface` fits it."""

    cc1: np.ndarray
    cc2: np.ndarray
    shape_index: np.ndarray
    curvedness: np.ndarray
    length_unit: float


_documented(
    Curvatures,
    cc1="(n,) first principal curvature, per length of the mesh's coordinates; convex "
        "negative (a sphere of radius R: -1/R), |cc1| >= |cc2|",
    cc2="(n,) second principal curvature, same unit and sign",
    shape_index="(n,) Koenderink shape index in [-1, 1]: +1 on caps, -1 on cups, 0 on saddles",
    curvedness="(n,) Koenderink curvedness sqrt((k1^2 + k2^2) / 2), per length",
    length_unit="the length unit the curvature was fitted in, in the mesh's coordinates "
                "(the fit spans 3 units)")


class CriticalPointSet(NamedTuple):
    """The critical points of a mesh (:func:`critical_points`), as ``surfcomp cp-detect`` finds
    them: peaks first, then valleys, each by vertex."""

    vertex: np.ndarray
    type: np.ndarray
    position: np.ndarray
    normal: np.ndarray
    cc1: np.ndarray
    cc2: np.ndarray
    shape_index: np.ndarray
    curvedness: np.ndarray
    esp: np.ndarray
    lp: np.ndarray
    length_unit: float


_documented(
    CriticalPointSet,
    vertex="(k,) indices into V (rows of the mesh's vertices)",
    type='(k,) "peak" (convex, the largest |cc1| within critical_point_radius) or "valley" '
         "(concave, the largest cc1)",
    position="(k, 3) positions, the mesh's coordinates",
    normal="(k, 3) unit outward normals",
    cc1="(k,) first principal curvature at the vertex, per length (convex < 0)",
    cc2="(k,) second principal curvature, per length",
    shape_index="(k,) shape index averaged over the disc of disc_radius, [-1, 1]",
    curvedness="(k,) curvedness at the vertex, per length",
    esp="(k,) ESP averaged over the disc (NaN on a mesh without ESP)",
    lp="(k,) lipophilic potential averaged over the disc (NaN on a mesh without LP)",
    length_unit="the length unit the radii counted in, in the mesh's coordinates")


class GeodesicPatch(NamedTuple):
    """The geodesic patch around a vertex (:func:`patch`), as ``describe`` cuts it: a
    triangulated disk (possibly with holes) whose vertices are rows of V."""

    center: int
    surface_vertex: np.ndarray
    positions: np.ndarray
    faces: np.ndarray
    distance: np.ndarray
    outer_boundary: np.ndarray
    holes: List[np.ndarray]
    genus: int
    radius: float


_documented(
    GeodesicPatch,
    center="the patch vertex (local index) at the centre vertex",
    surface_vertex="(p,) index into V of each patch vertex, increasing",
    positions="(p, 3) the patch vertices' positions: V[surface_vertex]",
    faces="(f, 3) patch triangles, local indices, oriented as the mesh's",
    distance="(p,) on-surface (fast-marching) distance from the centre, the mesh's coordinates",
    outer_boundary="(b,) local indices of the outer border loop, counter-clockwise seen from "
                   "outside (the patch on its left), starting at its lowest index",
    holes="the other border loops, local indices, each with the patch on its left",
    genus="handles of the patch: 0 for a disk (with holes); a harmonic map needs 0",
    radius="the on-surface radius it was cut at, the mesh's coordinates")


def _critical_points(self) -> CriticalPoints:
    """The critical points, one row per point (:class:`CriticalPoints`)."""
    return CriticalPoints(**self._critical_points())


def _patch(self, index: int) -> Patch:
    """Critical point ``index``'s patch and harmonic map (:class:`Patch`); IndexError when out of
    range, empty arrays when the point has no patch."""
    return Patch(**self._patch(index))


def _parameters(self) -> DescriptionParameters:
    """The parameters the description was built with (:class:`DescriptionParameters`)."""
    return DescriptionParameters(**self._parameters())


def _measures(self) -> SurfaceMeasures:
    """Area, volume, Euler characteristic and boundary edges (:class:`SurfaceMeasures`)."""
    return SurfaceMeasures(**self._measures())


Descriptors.critical_points = property(_critical_points)
Descriptors.patch = _patch
Descriptors.options = property(_parameters)
Surface.measures = _measures


@_keyword_options("build_surface")
def build_surface(mol, **options) -> Surface:
    """The solvent-excluded surface of ``mol``, or a mesh (a file or ``(V, F)`` arrays) with its
    properties: per-vertex normals, ``esp``, ``lp``, ``cc1``, ``cc2``, ``shape_index`` and
    ``curvedness``, as ``surfcomp surf-build`` builds it. A general mesh (no ESP and LP) keeps
    its coordinates; its curvature is fitted in its length unit (``scale=``, ``unit=``;
    ``Surface.length_unit``)."""
    return _surfcomp.build_surface(_input(mol), options)


@_keyword_options("describe")
def describe(mol_or_surface, **options) -> Descriptors:
    """The critical points of a surface and, for each, its patch, harmonic map and harmonic shape
    image, as ``surfcomp hsi-build`` describes it. ``mol_or_surface`` is a molecule, a mesh (a
    file or ``(V, F)`` arrays), a ``.hsi`` file or a :class:`Surface`. A general mesh is
    described in its length unit (``scale=``, ``unit=``) and given back in its coordinates."""
    return _surfcomp.describe(_input(mol_or_surface), options)


def load_descriptors(path) -> Descriptors:
    """The description stored in a ``.hsi`` file (``Descriptors.save`` or ``surfcomp hsi-build``)."""
    return _surfcomp.load_descriptors(os.fspath(path))


@_keyword_options("match")
def match(ref, probe, *, report: Union[str, os.PathLike, None] = None, **options) -> MatchResult:
    """Aligns ``probe`` onto ``ref`` as ``surfcomp match`` does and returns the alignments, best
    first. With ``report``, also writes the HTML report of the match there. A site sphere is
    ``(x, y, z, r)`` or a list of them."""
    raw = _surfcomp.match(_input(ref), _input(probe), options,
                          os.fspath(report) if report is not None else "")
    result = MatchResult(Alignment(**dict(a, overlay=OverlayScore(**a["overlay"]),
                                          coverage=CoverageScore(**a["coverage"])))
                         for a in raw["alignments"])
    for key in ("trace", "timing_ms", "warnings", "notes", "shape_only", "site", "unit",
                "cliques", "cliques_complete", "prepare_ms", "match_ms"):
        setattr(result, key, raw[key])
    result.reference_critical_points = CriticalPoints(**raw["reference_critical_points"])
    result.probe_critical_points = CriticalPoints(**raw["probe_critical_points"])
    return result


def _hits(rows, molecules):
    """Hit tuples from the module's rows; with ``molecules``, their aligned texts as RDKit
    molecules."""
    if molecules:
        from rdkit import Chem

        for row in rows:
            block, kind = row.pop("aligned")
            row["molecule"] = (Chem.MolFromMolBlock(block, removeHs=False) if kind == "sdf"
                               else Chem.MolFromPDBBlock(block, removeHs=False))
    return [Hit(**row) for row in rows]


@_keyword_options("screen")
def screen(query, library, *, molecules: bool = False, **options) -> List[Hit]:
    """Ranks the molecules of a screening library (``surfcomp library build``) against ``query``
    (a molecule, a ``.hsi`` file or :class:`Descriptors`; with site_ligand or site_sphere, a
    binding site on a structure against a pocket library), as ``surfcomp screen`` does. With
    ``molecules``, each hit carries its molecule moved onto the query as an RDKit molecule
    (``Hit.molecule``; a pocket hit: the atoms of its site's neighbourhood that the entry keeps), written as ``screen --aligned-out``
    writes it. ``fusion`` applies to :func:`screen_queries`."""
    result = _surfcomp.screen([_input(query)], os.fspath(library), options, molecules)
    return _hits(result["hits"][0], molecules)


@_keyword_options("screen")
def screen_queries(queries, library, *, molecules: bool = False, **options) -> Screens:
    """Screens several queries against a library in one pass, as ``surfcomp screen Q1 Q2 ...
    LIB`` does: each query's hits (the rows :func:`screen` gives it alone) and, with more than
    one query, every molecule ranked by the ``fusion`` of its scores against the queries. With
    several actives, their fused ranking (``fused``, ``fusion="max"``) finds more actives than
    any one of them does alone (docs/benchmarks.md, dud_screen_bench)."""
    result = _surfcomp.screen([_input(q) for q in queries], os.fspath(library), options, molecules)
    return Screens(hits=[_hits(rows, molecules) for rows in result["hits"]],
                   fused=[FusedHit(**row) for row in result["fused"]])


class ShapeHit(NamedTuple):
    """One mesh of a library of meshes matched with a mesh query (:func:`screen_shapes`)."""
    rank: int
    entry: int
    name: str
    source: str
    score: float
    entry_coverage: float
    overlay: float
    unit: float
    transform: np.ndarray
    note: str


_documented(ShapeHit,
            rank="1-based rank", entry="1-based library entry",
            name="the mesh's name (its file's stem)", source="the mesh file it was built from",
            score="the fraction of the query's area within one unit of the query's own (or "
                  "``unit``) of the mesh, under the best of the pair's three best distinct poses",
            entry_coverage="the fraction of the mesh's area within that distance of the query",
            overlay="that pose's shape Tanimoto",
            unit="the pair's length unit, in the inputs' coordinates",
            transform="(4, 4) homogeneous transform moving the mesh into the query's frame",
            note="why the pair was not matched (score 0): the mesh is narrower than the query, "
                 "or the match failed; empty when it was")


def screen_shapes(query, library, *, top: int = 100, scale: str = "auto",
                  unit: Optional[float] = None, repair: bool = False,
                  threads: int = 0) -> List[ShapeHit]:
    """Ranks the meshes of a library of meshes (``surfcomp library build MESH...``) by how much
    of ``query`` (a mesh file, ``(V, F)`` or a :class:`Surface` of a mesh; a partial scan, say)
    lies on each, as ``surfcomp screen SCAN LIB`` does: each mesh is matched with the query as
    :func:`match` would match them (in the larger mesh's unit with ``scale="auto"``, or in
    ``unit``), best ``top`` first (0: every mesh). ``repair`` repairs a query file first."""
    mesh_options = {"scale": scale, "repair": repair}
    if unit is not None:
        mesh_options["unit"] = unit
    return [ShapeHit(**row) for row in
            _surfcomp.screen_shapes(_input(query), os.fspath(library),
                                    {"top": top, "threads": threads}, mesh_options)]


def library_info(path) -> LibraryInfo:
    """A library's format version, build settings, size and entries, read from its index."""
    raw = _surfcomp.library_info(os.fspath(path))
    return LibraryInfo(**dict(raw, entries=[LibraryEntry(**e) for e in raw["entries"]]))


@_keyword_options("pockets")
def pockets(structure, **options) -> List[Pocket]:
    """The pockets of a protein structure (a PDB or mmCIF path), found from its ATOM records
    alone as ``surfcomp pockets`` finds them, best first. A pocket's rank is what
    ``match(..., site_pocket=N)`` and ``screen(..., site_pocket=N)`` take."""
    return [Pocket(**p) for p in _surfcomp.pockets(os.fspath(structure), options)]


@_keyword_options("screen_receptor")
def screen_receptor(receptor, library, **options) -> List[ReceptorHit]:
    """Ranks the molecules of a screening library by how well they fit ``receptor``'s pocket
    (a protein structure path), as ``surfcomp screen --receptor`` does: a fast dock of every
    conformer, then the full dock of the ``candidates`` best molecules. The site is given as to
    :func:`dock`; none: pocket 1."""
    rows = _surfcomp.screen_receptor(_input(receptor), os.fspath(library), options)
    return [ReceptorHit(**row) for row in rows]


@_keyword_options("dock")
def dock(probe, receptor, *, output: Union[str, os.PathLike, None] = None,
         report: Union[str, os.PathLike, None] = None, **options) -> DockResult:
    """Places ``probe``, the ligand (a molecule file or RDKit molecule), into ``receptor``'s site
    (a protein structure path) as ``surfcomp dock`` does and returns the distinct poses, best
    first (the keywords ``ligand`` and ``molecule`` pick a residue or record of a file, as for
    :func:`match`). The site is given as to
    :func:`match`: site_ligand, site_sphere ``(x, y, z, r)`` or a list of them, site_pocket;
    none of them: pocket 1. ``conformers=N`` docks N RDKit conformers of a ligand file's record
    instead of its coordinates. With ``output``, the poses are also written there as SDF records
    of the ligand's file (or of their conformers) in the receptor's frame; with ``report``, the
    HTML report of the dock."""
    raw = _surfcomp.dock(_input(probe), _input(receptor), options,
                         os.fspath(output) if output is not None else "",
                         os.fspath(report) if report is not None else "")
    result = DockResult(DockPose(**p) for p in raw["poses"])
    for key in ("conformers", "starts", "site_volume", "ligand_volume", "notes", "timing_ms"):
        setattr(result, key, raw[key])
    return result


class MatrixMember(NamedTuple):
    """A molecule of a :func:`matrix`: a record of one of its files."""

    name: str
    source: str
    record: int


_documented(MatrixMember, name="the record's name (its title line; STEM:N when it has none)",
            source="the file it comes from", record="its 1-based position in the file")


class SimilarityMatrix(NamedTuple):
    """The molecules of one or two sets compared pair by pair (:func:`matrix`)."""

    scores: Any
    stage: Any
    neighbours: Any
    neighbour_scores: Any
    neighbour_stages: Any
    transforms: Any
    rows: List[MatrixMember]
    columns: List[MatrixMember]
    symmetric: bool
    left_out: List[str]
    warnings: List[str]
    describe_ms: float
    match_ms: float


_documented(
    SimilarityMatrix,
    scores="(rows, columns) float array: the overlay score (0-1) of columns[j] aligned onto "
           "rows[i], the best found at the stage ``stage`` gives; 0 without an alignment, NaN "
           "for a pair whose full match failed. None with ``neighbours``",
    stage="(rows, columns) uint8 array: the stage of each score: 1, the best principal-axes "
          "superposition; 2, its refinement (each molecule's ``refined_overlays`` best "
          "neighbours); 3, the full match's top alignment (each molecule's ``full_matches`` "
          "best, or every pair with ``exact=True``); 0, none. None with ``neighbours``",
    neighbours="with ``neighbours=K``, (rows, K) int array (K at most the other molecules): "
               "each row's K best columns, best first (not the row itself all against all), -1 "
               "past a row's last; else None",
    neighbour_scores="with ``neighbours=K``, (rows, K): their scores, as ``scores`` would "
                     "hold them (NaN past a row's last); else None",
    neighbour_stages="with ``neighbours=K``, (rows, K): their stages, as ``stage``; else None",
    transforms="with transforms=True, (rows, columns, 4, 4): the rigid transform that moves "
               "columns[j] onto rows[i] (with ``neighbours=K``, (rows, K, 4, 4), the k-th "
               "neighbour onto rows[i]); else None",
    rows="the molecules of the set, in file order, without those left out",
    columns="the molecules of ``against`` (the set's own when all against all)",
    symmetric="all against all: each pair matched once, the diagonal the self-matches",
    left_out="the records that could not be read or described, one line each: file, record, "
             "why",
    warnings="what the matching cut, one line each: a pair not matched (its score NaN), the "
             "pairs whose clique search stopped at its budget",
    describe_ms="milliseconds reading, surfacing and describing the molecules",
    match_ms="milliseconds matching the pairs")


@_keyword_options("matrix")
def matrix(set, against=None, *, transforms: bool = False,
           output: Union[str, os.PathLike, None] = None, **options) -> SimilarityMatrix:
    """Describes every molecule of the ``set`` files (a path or a list of paths: each record of
    an SDF or MOL2 file; a PDB, mmCIF or PQR file is one molecule) once and compares every pair,
    as ``surfcomp matrix`` does: all against all, or the set's molecules (rows) against those of
    the ``against`` files (columns). Every pair is overlaid at the principal-axes superpositions
    (a screen's stage 1); each molecule's ``refined_overlays`` best neighbours get the overlay
    refined (stage 2), and its ``full_matches`` best are then aligned as :func:`match` aligns two
    molecules (every pair with ``exact=True``). With ``neighbours=K`` only each molecule's K
    best neighbours are kept, for a set whose matrix would not fit in memory (``output`` then
    gets a line per neighbour, as ``surfcomp matrix --neighbours`` writes them). A
    record that cannot be read or described is left out and named in ``left_out``. With
    ``output``, the matrix is also written there as CSV."""
    def paths(files):
        if files is None:
            return []
        if isinstance(files, (str, os.PathLike)):
            return [os.fspath(files)]
        return [os.fspath(f) for f in files]

    raw = _surfcomp.matrix(paths(set), paths(against), options, transforms,
                           os.fspath(output) if output is not None else "")
    raw["rows"] = [MatrixMember(**m) for m in raw["rows"]]
    raw["columns"] = [MatrixMember(**m) for m in raw["columns"]]
    return SimilarityMatrix(**raw)


def option_table(function: str) -> List[Dict[str, Any]]:
    """The keyword options of ``build_surface``, ``describe``, ``match``, ``screen``,
    ``pockets``, ``dock``, ``matrix``, ``curvatures``, ``critical_points``, ``patch``,
    ``disk_map`` or ``shape_image``
    as the library defines them, in order: ``name`` (the keyword), ``option`` (the command
    line's), ``kind``, ``default``, ``help`` (with unit and range), ``unit``, ``range`` and
    ``choices``."""
    return _surfcomp.option_table(function)


# --- (V, F) functions: one step of the pipeline each, on a mesh's arrays ----------------------

_MESH_ARGUMENT = """``mesh`` is ``(V, F)``: V (n, 3) float positions and F (m, 3) int 0-based
    triangles, counter-clockwise seen from outside, a manifold mesh (else :class:`InputError`;
    ``build_surface((V, F), repair=True)`` repairs one, renumbering its vertices, and its
    :class:`Surface` goes here instead), or a :class:`Surface`. Vertex indices, in and out,
    are rows of V (``Surface.vertices``)."""

_UNIT_RULE = """Lengths are in the mesh's own coordinates. The radii that have defaults count in
    the mesh's length unit, chosen as :func:`build_surface` chooses it: 1/12 of the mesh's size
    (the area-weighted RMS distance of its triangles from their centre) with ``scale="auto"``,
    ``unit=`` when given, 1 with ``scale="none"``; a :class:`Surface` keeps its own
    (``Surface.length_unit``; 1 for a molecule's, in A). So one shape gives the same answers at
    any scale."""


def _mesh(mesh):
    """A mesh argument as the module takes it: a Surface as is, ``(V, F)`` as a tuple."""
    if isinstance(mesh, Surface):
        return mesh
    if isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        return tuple(mesh)
    raise TypeError(f"expected (V, F) arrays or a Surface, got {type(mesh).__name__}")


def _with_docs(function):
    function.__doc__ = (function.__doc__.replace("{mesh}", _MESH_ARGUMENT)
                        .replace("{units}", _UNIT_RULE))
    return function


@_keyword_options("curvatures")
@_with_docs
def curvatures(mesh, **options) -> Curvatures:
    """Per-vertex principal curvatures, shape index and curvedness of a mesh, as
    :func:`build_surface` (``surfcomp surf-build``) fits them: a local quadric over 3 length
    units around each vertex, in the project's sign (convex negative: a sphere of radius R has
    cc1 = cc2 = -1/R and shape index 1), per length of the mesh's coordinates.

    {mesh}

    {units} A :class:`Surface` without ``scale``/``unit`` gives back the curvature it holds.

    Returns a :class:`Curvatures` of (n,) arrays and the length unit."""
    return Curvatures(**_surfcomp.curvatures(_mesh(mesh), options))


@_keyword_options("critical_points")
@_with_docs
def critical_points(mesh, **options) -> CriticalPointSet:
    """The shape critical points of a mesh, as ``surfcomp cp-detect`` finds them: peaks, convex
    vertices whose |cc1| is the largest within ``critical_point_radius`` on the surface, and
    valleys, concave vertices whose cc1 is the largest within it; the curvature as
    :func:`curvatures` fits it.

    {mesh}

    {units} ``critical_point_radius`` and ``disc_radius`` count in that unit.

    Returns a :class:`CriticalPointSet`: vertex indices, types ("peak", "valley") and the
    points' positions, normals and curvature, peaks first."""
    return CriticalPointSet(**_surfcomp.critical_points(_mesh(mesh), options))


@_with_docs
def geodesic_distances(mesh, source_vertex: int, max_distance: Optional[float] = None, *,
                       method: str = "fast-marching") -> np.ndarray:
    """On-surface distances from ``source_vertex`` to every vertex: (n,) floats in the mesh's
    coordinates, ``inf`` beyond ``max_distance`` (None: no bound; a bounded run visits only the
    vertices within it and their neighbours) and in other connected components (never NaN).

    ``method``: ``"fast-marching"`` (default; the distances ``describe`` cuts its patches by,
    Dijkstra order with the Kimmel-Sethian triangle update: exact on a plane, within about 1 %
    of the great circle on a fine sphere) or ``"dijkstra"`` (shortest paths along the edges, as
    critical points are found; longer than the true geodesic).

    {mesh}"""
    return _surfcomp.geodesic_distances(
        _mesh(mesh), source_vertex, None if max_distance is None else float(max_distance), method)


@_keyword_options("patch")
@_with_docs
def patch(mesh, center_vertex: int, radius: Optional[float] = None, **options) -> GeodesicPatch:
    """The geodesic patch around ``center_vertex``, as ``describe`` (``surfcomp hsi-build``)
    cuts it around a critical point: the vertices within the on-surface (fast-marching)
    ``radius`` and those within 5 % more that share an edge with them, their triangles, cleaned
    until it is a disk with holes whose border loops pass each vertex once.

    {mesh}

    {units} ``radius`` is in the mesh's coordinates; None takes ``describe``'s patch radius,
    5 length units, which cuts the patch ``describe`` cuts.

    Returns a :class:`GeodesicPatch` (its vertices as rows of V, local triangles, the outer
    border loop); :func:`disk_map` maps it. :class:`InputError` when no triangle is left (a
    radius shorter than the vertex's edges)."""
    return GeodesicPatch(**_surfcomp.patch(_mesh(mesh), center_vertex,
                                           None if radius is None else float(radius), options))


@_keyword_options("disk_map")
def disk_map(patch_or_mesh, method: str = "harmonic", **options) -> np.ndarray:
    """A patch mapped onto the unit disk: (k, 2) uv, one row per patch vertex, by one of the
    seven methods ``surfcomp patch-map --methods`` compares:

    - ``"harmonic"`` (default): ``describe``'s harmonic map (spring weights ``weights``,
      the seed's 1 / edge length), the outer border on the unit circle by arc length;
    - ``"tutte"``, ``"mean-value"``, ``"discrete-conformal"``, ``"discrete-authalic"``: CGAL's
      fixed-border maps, the border on the unit circle as the harmonic map's;
    - ``"lscm"``, ``"arap"``: CGAL's free-border maps, moved and scaled (one factor) so that
      their bounding box is centred and its longer side spans [-1, 1], as patch-map writes
      them: inside the unit disk's square, not its circle.

    ``patch_or_mesh`` is a :class:`GeodesicPatch` (:func:`patch`) or a :class:`Patch`
    (``Descriptors.patch(i)``), mapped with its outer border; or ``(V, F)`` arrays of a
    disk-like mesh (one border loop, the longest; holes are free), mapped whole. Uv row i is
    patch vertex i (row i of V). :class:`InputError` for a mesh that is not a disk."""
    if all(hasattr(patch_or_mesh, a) for a in ("positions", "faces", "outer_boundary")):
        positions, faces = patch_or_mesh.positions, patch_or_mesh.faces
        boundary = [int(v) for v in patch_or_mesh.outer_boundary]
    elif isinstance(patch_or_mesh, (tuple, list)) and len(patch_or_mesh) == 2:
        (positions, faces), boundary = patch_or_mesh, None
    else:
        raise TypeError("expected a GeodesicPatch, a Patch or (V, F) arrays, got "
                        f"{type(patch_or_mesh).__name__}")
    return _surfcomp.disk_map(positions, faces, boundary, method, options)


@_keyword_options("shape_image")
@_with_docs
def shape_image(mesh, center_vertex: int, radius: Optional[float] = None,
                **options) -> np.ndarray:
    """The harmonic shape image of the patch around ``center_vertex``, as ``describe`` computes
    it for a critical point: the patch (:func:`patch`), its harmonic map (:func:`disk_map`) and
    the shape index (:func:`curvatures`) resampled on a polar grid over the disk: an
    (image_rings, image_sectors) array, ring k at radius (k + 0.5) / rings, sector j at
    j * 360 / sectors degrees counter-clockwise from the map's u axis; NaN where no triangle of
    the map lies under a grid point (a hole).

    {mesh}

    {units} ``radius`` is in the mesh's coordinates; None takes ``describe``'s 5 length units.

    :class:`InputError` when ``describe`` would give the vertex no image: its patch reaches the
    mesh's border, has a handle, or keeps no triangle."""
    return _surfcomp.shape_image(_mesh(mesh), center_vertex,
                                 None if radius is None else float(radius), options)
