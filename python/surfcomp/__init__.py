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
``--probe-radius``) and defaults; ``surfcomp match --help`` lists them. A value outside its
range raises ``ValueError`` with the command line's message, an unreadable file ``OSError``.

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

import dataclasses
import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _surfcomp
from ._surfcomp import Descriptors, Surface

__all__ = [
    "Alignment", "Descriptors", "Hit", "MatchResult", "Surface", "build_surface", "describe",
    "library_info", "load_descriptors", "match", "option_defaults", "screen",
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
    """A path, Surface or Descriptors as is; an RDKit molecule as its MDL block."""
    if isinstance(obj, (Surface, Descriptors)):
        return obj
    if isinstance(obj, (str, os.PathLike)):
        return os.fspath(obj)
    if _is_rdkit_molecule(obj):
        from rdkit import Chem  # imported only when an RDKit molecule is given

        if obj.GetNumConformers() == 0:
            raise ValueError("the RDKit molecule has no conformer: surfcomp needs 3D coordinates")
        name = obj.GetProp("_Name") if obj.HasProp("_Name") and obj.GetProp("_Name") else "mol"
        block = Chem.MolToMolBlock(obj, includeStereo=True, kekulize=True)
        return _surfcomp.MoleculeBlock(block, f"<rdkit Mol {name}>", _partial_charges(obj))
    raise TypeError(f"expected a path, an RDKit molecule, a Surface or a Descriptors, "
                    f"got {type(obj).__name__}")


def _arguments(options: Dict[str, Any]) -> List[str]:
    """Keyword options as command-line words: probe_radius=1.2 -> ['--probe-radius', '1.2'];
    True switches a flag on; a list or tuple of lists repeats the option; None is left out; a
    site sphere may be given as four numbers."""
    words: List[str] = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            words.append(flag)
            continue
        values = value if isinstance(value, list) else [value]
        for v in values:
            if isinstance(v, (tuple, np.ndarray)):
                v = ",".join(repr(float(x)) for x in v)
            words += [flag, str(v)]
    return words


@dataclasses.dataclass
class Alignment:
    """One rigid alignment of the probe onto the reference, best first by ``rank``.

    ``transform`` (4, 4) moves probe coordinates into the reference's frame:
    ``x' = transform[:3, :3] @ x + transform[:3, 3]``. ``source`` is ``"cliques"`` (critical-point
    correspondences) or ``"principal_axes"`` (a refined principal-axes start; then ``rmsd``,
    ``n_points``, ``r_chem`` and ``consensus`` are 0 and ``cp_pairs`` is empty). ``cp_pairs``
    (k, 2) holds (reference, probe) critical-point indices.
    """

    rank: int
    source: str
    transform: np.ndarray
    rmsd: float
    n_points: int
    r_chem: float
    consensus: float
    refined: bool
    overlay: Dict[str, float]
    cp_pairs: np.ndarray
    parent: Optional[int]
    children: List[int]

    @property
    def overlay_score(self) -> float:
        """The overlay score (shape + chemistry + atoms Tanimoto, weighted) of ``transform``."""
        return self.overlay["score"]

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


class MatchResult(list):
    """The alignments of a match, best first (a list of :class:`Alignment`), with what the match
    did: ``trace`` (the association graph after each filter: stage, nodes, edges, ms),
    ``timing_ms``, ``warnings`` (what the match cut), ``notes``, ``cliques`` and
    ``cliques_complete``, ``prepare_ms`` (surfaces and descriptors) and ``match_ms``."""

    trace: List[Dict[str, Any]]
    timing_ms: Dict[str, float]
    warnings: List[str]
    notes: List[str]
    cliques: int
    cliques_complete: bool
    prepare_ms: float
    match_ms: float


@dataclasses.dataclass
class Hit:
    """One molecule of a screen, best first: its best conformer's ``entry`` (1-based) in the
    library, its ``score`` (stage 3: the full match's overlay score; stage 2: the refined
    overlay score; stage 1: the fast score)
    and terms, and ``transform`` (4, 4) moving it into the query's frame."""

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


def build_surface(mol, **options) -> Surface:
    """The solvent-excluded surface of ``mol`` (or a mesh file with its properties) with per-vertex
    normals, ``esp``, ``lp``, ``cc1``, ``cc2``, ``shape_index`` and ``curvedness``.

    Options (``surfcomp surf-build --help``): probe_radius=1.4, density=2.5, voxel=0,
    charges="file", eps=1, eps_distance_dependent=False, lp_kernel="fauchere", ligand=None,
    record=None, molecule=None, max_atoms, max_grid_cells, max_vertices.
    """
    return _surfcomp.build_surface(_input(mol), _arguments(options))


def describe(mol_or_surface, **options) -> Descriptors:
    """The critical points of a surface and, for each, its patch, harmonic map and harmonic shape
    image. ``mol_or_surface`` is a molecule, a mesh, a ``.hsi`` file or a :class:`Surface`.

    Options: the surface options of :func:`build_surface`, and critical_point_radius=2.5,
    patch_radius=5, image_rings=16, image_sectors=180, weights="inverse-length", threads=0,
    max_image_bytes.
    """
    return _surfcomp.describe(_input(mol_or_surface), _arguments(options))


def load_descriptors(path) -> Descriptors:
    """The description stored in a ``.hsi`` file (``Descriptors.save`` or ``surfcomp hsi-build``)."""
    return _surfcomp.load_descriptors(os.fspath(path))


def match(ref, probe, *, report: Union[str, os.PathLike, None] = None, **options) -> MatchResult:
    """Aligns ``probe`` onto ``ref`` as ``surfcomp match`` does and returns the alignments, best
    first. With ``report``, also writes the HTML report of the match there.

    Options: every option of ``surfcomp match --help`` (fuzzy_threshold=0.3,
    image_threshold=0.5, ..., site_ligand, site_sphere=(x, y, z, r) or a list of them,
    patch_radius=5, and the surface options), and threads=0.
    """
    raw = _surfcomp.match(_input(ref), _input(probe), _arguments(options),
                          os.fspath(report) if report is not None else "")
    result = MatchResult(Alignment(**a) for a in raw["alignments"])
    for key in ("trace", "timing_ms", "warnings", "notes", "cliques", "cliques_complete",
                "prepare_ms", "match_ms"):
        setattr(result, key, raw[key])
    return result


def screen(query, library, **options) -> List[Hit]:
    """Ranks the molecules of a screening library (``surfcomp library build``) against ``query``
    (a molecule, a ``.hsi`` file or :class:`Descriptors`; with site_ligand or site_sphere, a
    binding site on a structure against a pocket library), as ``surfcomp screen`` does.

    Options: top=100 (0: every molecule), refine=5, refine_starts=0 (all), candidates=50, record,
    site_ligand, site_sphere, site_radius=4, site_margin=16, threads=0.
    """
    return [Hit(**h) for h in _surfcomp.screen(_input(query), os.fspath(library),
                                               _arguments(options))]


def library_info(path) -> Dict[str, Any]:
    """A library's format version, build settings, size in bytes and entries (entry, name,
    source, record, conformer, heavy_atoms, site_spheres), read from its index."""
    return _surfcomp.library_info(os.fspath(path))


def option_defaults(function: str) -> Dict[str, str]:
    """The options of ``build_surface``, ``describe``, ``match`` or ``screen`` with their
    defaults as the command line shows them (command-line names)."""
    return _surfcomp.option_defaults(function)
