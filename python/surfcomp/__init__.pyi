"""Type stubs of the surfcomp package (see __init__.py for the documentation). The keyword
options and their defaults are the command line's (tests/python/test_module.py checks them
against the option sets the C++ side parses)."""

import os
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, os.PathLike]
#: A molecule: a path, an ``rdkit.Chem.Mol`` with a conformer.
Molecule = Any
#: One site sphere (x, y, z, r), its text "x,y,z,r", or a list of them.
SiteSpheres = Union[Sequence[float], str, List[Union[Sequence[float], str]]]

__version__: str

class Surface:
    """A closed triangle surface with per-vertex properties (built or read; not constructed)."""
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...  # (n, 3), A
    @property
    def normals(self) -> npt.NDArray[np.float64]: ...  # (n, 3), unit, outward
    @property
    def faces(self) -> npt.NDArray[np.int32]: ...  # (m, 3), counter-clockwise from outside
    @property
    def properties(self) -> Dict[str, npt.NDArray[np.float64]]: ...  # name -> (n,)
    @property
    def source(self) -> str: ...
    @property
    def n_vertices(self) -> int: ...
    @property
    def n_faces(self) -> int: ...
    @property
    def has_molecule(self) -> bool: ...
    def measures(self) -> Dict[str, float]: ...  # area, volume, euler_characteristic, boundary_edges
    def save(self, path: PathLike, ascii: bool = ...) -> None: ...  # .ply, .off or .obj

class Descriptors:
    """A surface with its critical points, patches, harmonic maps and shape images."""
    @property
    def surface(self) -> Surface: ...
    @property
    def critical_points(self) -> Dict[str, np.ndarray]: ...
    # position (k, 3), normal (k, 3), vertex, type ("peak"/"valley"), status ("ok", "skipped",
    # ...), cc1, cc2, shape_index, curvedness, esp, lp: one row per critical point
    @property
    def images(self) -> npt.NDArray[np.float64]: ...  # (k, rings, sectors); NaN where none
    @property
    def options(self) -> Dict[str, Any]: ...
    @property
    def atoms(self) -> Tuple[List[str], npt.NDArray[np.float64]]: ...  # heavy atoms: elements, (a, 3)
    def save(self, path: PathLike) -> None: ...  # .hsi

class Alignment:
    rank: int
    source: str
    transform: npt.NDArray[np.float64]  # (4, 4): probe coordinates -> reference frame
    rmsd: float
    n_points: int
    r_chem: float
    consensus: float
    refined: bool
    overlay: Dict[str, float]  # score, shape, chem, atoms
    cp_pairs: npt.NDArray[np.int32]  # (k, 2): reference, probe critical-point indices
    parent: Optional[int]
    children: List[int]
    @property
    def overlay_score(self) -> float: ...
    def apply_to(self, points: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def apply(self, mol: Any, conf_id: int = ...) -> Any: ...

class MatchResult(List[Alignment]):
    trace: List[Dict[str, Any]]
    timing_ms: Dict[str, float]
    warnings: List[str]
    notes: List[str]
    cliques: int
    cliques_complete: bool
    prepare_ms: float
    match_ms: float

class Hit:
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
    transform: npt.NDArray[np.float64]

def build_surface(
    mol: Union[PathLike, Molecule],
    *,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[str] = None,
    record: Optional[int] = None,
    molecule: Optional[PathLike] = None,
    max_atoms: int = 2000000,
    max_grid_cells: int = 200000000,
    max_vertices: int = 20000000,
) -> Surface: ...

def describe(
    mol_or_surface: Union[PathLike, Molecule, Surface],
    *,
    critical_point_radius: float = 2.5,
    patch_radius: float = 5.0,
    image_rings: int = 16,
    image_sectors: int = 180,
    weights: str = 'inverse-length',
    threads: int = 0,
    max_image_bytes: int = 1073741824,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[str] = None,
    record: Optional[int] = None,
    molecule: Optional[PathLike] = None,
    max_atoms: int = 2000000,
    max_grid_cells: int = 200000000,
    max_vertices: int = 20000000,
) -> Descriptors: ...

def load_descriptors(path: PathLike) -> Descriptors: ...

def match(
    ref: Union[PathLike, Molecule, Surface, Descriptors],
    probe: Union[PathLike, Molecule, Surface, Descriptors],
    *,
    report: Optional[PathLike] = None,
    site_ligand: Optional[str] = None,
    ref_site_ligand: Optional[str] = None,
    probe_site_ligand: Optional[str] = None,
    site_radius: float = 4.0,
    site_sphere: Optional[SiteSpheres] = None,
    site_margin: float = 16.0,
    ref_site_sphere: Optional[SiteSpheres] = None,
    probe_site_sphere: Optional[SiteSpheres] = None,
    fuzzy_threshold: float = 0.3,
    image_threshold: float = 0.5,
    distance_tolerance: float = 1.5,
    min_distance: float = 2.0,
    overlap_tolerance: float = 30.0,
    max_graph_nodes: int = 20000,
    max_clique_work: int = 100000000,
    max_cliques: int = 1000,
    rmsd_cut: float = 4.0,
    ranking: str = 'rank',
    refine_top: int = 10,
    overlay_sigma: float = 1.0,
    overlay_chem_weight: float = 6.0,
    overlay_atom_weight: float = 14.0,
    polish_top: int = 5,
    overlay_tolerance: float = 0.1,
    principal_axes_starts: int = 24,
    site_overlay_radius: float = 2.0,
    site_chem_weight: float = 0.25,
    site_principal_axes_starts: int = 24,
    patch_radius: float = 5.0,
    max_image_bytes: int = 1073741824,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[str] = None,
    record: Optional[int] = None,
    molecule: Optional[PathLike] = None,
    max_atoms: int = 2000000,
    max_grid_cells: int = 200000000,
    max_vertices: int = 20000000,
    threads: int = 0,
) -> MatchResult: ...

def screen(
    query: Union[PathLike, Molecule, Descriptors],
    library: PathLike,
    *,
    top: int = 100,
    refine: int = 5,
    refine_starts: int = 0,
    candidates: int = 50,
    record: Optional[int] = None,
    site_ligand: Optional[str] = None,
    site_sphere: Optional[SiteSpheres] = None,
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    threads: int = 0,
) -> List[Hit]: ...

def library_info(path: PathLike) -> Dict[str, Any]: ...
def option_defaults(function: str) -> Dict[str, str]: ...
