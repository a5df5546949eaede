"""Type stubs of the surfcomp package (see __init__.py for the documentation). The keyword
options of the functions made with the library's option tables are written from those tables by
scripts/python_stub.py; tests/python/test_module.py checks that they are current."""

import os
from typing import Any, Dict, Iterator, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, os.PathLike]
#: A molecule: a path, an ``rdkit.Chem.Mol`` with a conformer.
Molecule = Any
#: One site sphere (x, y, z, r), its text "x,y,z,r", or a list of them.
#: A general mesh: V (n, 3) positions and F (m, 3) 0-based triangles.
MeshArrays = Tuple[npt.ArrayLike, npt.ArrayLike]
SiteSpheres = Union[Sequence[float], str, List[Union[Sequence[float], str]]]

__version__: str

class Error(Exception):
    """Base of every error surfcomp raises."""

class InputError(Error, ValueError):
    """Bad input: a file's contents, a molecule, a mesh or an option."""

class OptionError(InputError):
    """An option outside its range or not one of its choices."""

class FileError(Error, OSError):
    """A file that cannot be opened, read or written."""

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
    @property
    def length_unit(self) -> float: ...  # a general mesh's length unit (scale=, unit=); 1 in A
    def measures(self) -> SurfaceMeasures: ...
    def save(self, path: PathLike, ascii: bool = ...) -> None: ...  # .ply, .off or .obj

class Descriptors:
    """A surface with its critical points, patches, harmonic maps and shape images."""
    @property
    def surface(self) -> Surface: ...
    @property
    def critical_points(self) -> CriticalPoints: ...
    def patch(self, index: int) -> Patch: ...
    @property
    def images(self) -> npt.NDArray[np.float64]: ...  # (k, rings, sectors); NaN where none
    @property
    def options(self) -> DescriptionParameters: ...
    @property
    def atoms(self) -> Tuple[List[str], npt.NDArray[np.float64]]: ...  # heavy atoms: elements, (a, 3)
    @property
    def length_unit(self) -> float: ...  # the unit its options' radii count in; 1 in A
    def save(self, path: PathLike) -> None: ...  # .hsi
    def write_critical_points(self, path: PathLike) -> None: ...  # .json, .pdb or .ply

class SurfaceMeasures(NamedTuple):
    area: float
    volume: float
    euler_characteristic: int
    boundary_edges: int

class CriticalPoints(NamedTuple):
    position: npt.NDArray[np.float64]  # (k, 3)
    normal: npt.NDArray[np.float64]  # (k, 3)
    vertex: npt.NDArray[np.int32]
    type: npt.NDArray[Any]  # "peak" or "valley"
    status: npt.NDArray[Any]  # "ok", "skipped", ...
    cc1: npt.NDArray[np.float64]
    cc2: npt.NDArray[np.float64]
    shape_index: npt.NDArray[np.float64]
    curvedness: npt.NDArray[np.float64]
    esp: npt.NDArray[np.float64]
    lp: npt.NDArray[np.float64]

class Patch(NamedTuple):
    status: str
    center: int
    positions: npt.NDArray[np.float64]  # (p, 3)
    faces: npt.NDArray[np.int32]  # (f, 3)
    surface_vertex: List[int]
    distance: npt.NDArray[np.float64]
    uv: npt.NDArray[np.float64]  # (p, 2)
    outer_boundary: List[int]

class Curvatures(NamedTuple):
    cc1: npt.NDArray[np.float64]  # (n,), per length of the mesh's coordinates; convex < 0
    cc2: npt.NDArray[np.float64]  # (n,)
    shape_index: npt.NDArray[np.float64]  # (n,), [-1, 1]; cap +1
    curvedness: npt.NDArray[np.float64]  # (n,)
    length_unit: float

class CriticalPointSet(NamedTuple):
    vertex: npt.NDArray[np.int32]  # (k,), rows of V
    type: npt.NDArray[Any]  # "peak" or "valley"
    position: npt.NDArray[np.float64]  # (k, 3)
    normal: npt.NDArray[np.float64]  # (k, 3)
    cc1: npt.NDArray[np.float64]
    cc2: npt.NDArray[np.float64]
    shape_index: npt.NDArray[np.float64]
    curvedness: npt.NDArray[np.float64]
    esp: npt.NDArray[np.float64]  # NaN without ESP
    lp: npt.NDArray[np.float64]  # NaN without LP
    length_unit: float

class GeodesicPatch(NamedTuple):
    center: int  # local index of the centre vertex
    surface_vertex: npt.NDArray[np.int32]  # (p,), rows of V
    positions: npt.NDArray[np.float64]  # (p, 3)
    faces: npt.NDArray[np.int32]  # (f, 3), local
    distance: npt.NDArray[np.float64]  # (p,), the mesh's coordinates
    outer_boundary: npt.NDArray[np.int32]  # (b,), local, counter-clockwise
    holes: List[npt.NDArray[np.int32]]
    genus: int
    radius: float  # the mesh's coordinates

class DescriptionParameters(NamedTuple):
    critical_point_radius: float
    disc_radius: float
    patch_radius: float
    image_rings: int
    image_sectors: int
    weights: str
    image_property: str

class OverlayScore(NamedTuple):
    score: float
    shape: float
    chem: float
    atoms: float

class CoverageScore(NamedTuple):
    score: float
    reference: float
    probe: float

class Alignment(NamedTuple):
    rank: int
    source: str
    transform: npt.NDArray[np.float64]  # (4, 4): probe coordinates -> reference frame
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
    shape_only: bool
    site: Optional[Dict[str, Any]]
    unit: float
    cliques: int
    cliques_complete: bool
    prepare_ms: float
    match_ms: float
    reference_critical_points: CriticalPoints
    probe_critical_points: CriticalPoints
    def distinct(self, top: Optional[int] = ...) -> List[Alignment]: ...

class Hit(NamedTuple):
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
    molecule: Any = None  # with screen(..., molecules=True): an RDKit molecule

class ShapeHit(NamedTuple):
    rank: int
    entry: int
    name: str
    source: str
    score: float
    entry_coverage: float
    overlay: float
    unit: float
    transform: npt.NDArray[np.float64]
    note: str

class FusedHit(NamedTuple):
    rank: int
    entry: int
    name: str
    source: str
    record: int
    conformer: int
    score: float
    query: int
    scores: Tuple[float, ...]

class Screens(NamedTuple):
    hits: List[List[Hit]]
    fused: List[FusedHit]

class LibraryEntry(NamedTuple):
    entry: int
    name: str
    source: str
    record: int
    conformer: int
    heavy_atoms: int
    site_spheres: int

class ReceptorHit(NamedTuple):
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
    transform: npt.NDArray[np.float64]

class DockPose(NamedTuple):
    rank: int
    score: float
    contact: float
    clash: float
    esp: float
    lp: float
    deepest: float
    intersects: bool
    transform: npt.NDArray[np.float64]
    start: int
    conformer: int
    cp_pairs: npt.NDArray[np.int32]

class DockResult(List[DockPose]):
    conformers: List[str]
    starts: int
    site_volume: float
    ligand_volume: float
    notes: List[str]
    timing_ms: Dict[str, float]

class Pocket(NamedTuple):
    rank: int
    score: float
    volume: float
    buriedness: float
    cavity: int
    center: Tuple[float, float, float]
    lining_residues: List[str]
    spheres: List[Tuple[float, float, float, float]]

class MatrixMember(NamedTuple):
    name: str
    source: str
    record: int

class SimilarityMatrix(NamedTuple):
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

class LibraryInfo(NamedTuple):
    version: int
    settings: str
    bytes: int
    molecules: int
    largest_entry_bytes: int
    entries: List[LibraryEntry]

def build_surface(
    mol: Union[PathLike, Molecule],
    *,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[PathLike] = None,
    record: Optional[int] = None,
    min_plddt: float = 0.0,
    molecule: Optional[PathLike] = None,
    repair: bool = False,
    scale: str = 'auto',
    unit: Optional[float] = None,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
) -> Surface: ...

def describe(
    mol_or_surface: Union[PathLike, Molecule, Surface, MeshArrays],
    *,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[PathLike] = None,
    record: Optional[int] = None,
    min_plddt: float = 0.0,
    molecule: Optional[PathLike] = None,
    repair: bool = False,
    scale: str = 'auto',
    unit: Optional[float] = None,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
    critical_point_radius: float = 2.5,
    disc_radius: float = 1.0,
    patch_radius: float = 5.0,
    image_rings: int = 16,
    image_sectors: int = 180,
    weights: str = 'inverse-length',
    max_image_bytes: int = 1073741824,
    threads: int = 0,
) -> Descriptors: ...

def load_descriptors(path: PathLike) -> Descriptors: ...

def match(
    ref: Union[PathLike, Molecule, Surface, Descriptors, MeshArrays],
    probe: Union[PathLike, Molecule, Surface, Descriptors, MeshArrays],
    *,
    report: Optional[PathLike] = None,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[PathLike] = None,
    record: Optional[int] = None,
    min_plddt: float = 0.0,
    molecule: Optional[PathLike] = None,
    repair: bool = False,
    scale: str = 'auto',
    unit: Optional[float] = None,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
    patch_radius: float = 5.0,
    max_image_bytes: int = 1073741824,
    shape_only: bool = False,
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
    fine_top: int = 2,
    overlay_sigma: float = 1.0,
    overlay_chem_weight: float = 6.0,
    overlay_atom_weight: float = 14.0,
    polish_top: int = 5,
    atom_polish_sigma: float = 0.5,
    atom_polish_weight: float = 1.0,
    overlay_tolerance: float = 0.1,
    coverage_distance: float = 1.0,
    icp_top: int = 0,
    icp_max_distance: float = 1.5,
    principal_axes_starts: int = 24,
    site_overlay_radius: float = 2.0,
    site_chem_weight: float = 0.25,
    site_lining_weight: float = 0.3,
    site_principal_axes_starts: int = 24,
    site_ligand: Optional[PathLike] = None,
    ref_site_ligand: Optional[PathLike] = None,
    probe_site_ligand: Optional[PathLike] = None,
    site_sphere: Optional[SiteSpheres] = None,
    ref_site_sphere: Optional[SiteSpheres] = None,
    probe_site_sphere: Optional[SiteSpheres] = None,
    site_pocket: Optional[int] = None,
    ref_site_pocket: Optional[int] = None,
    probe_site_pocket: Optional[int] = None,
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
    threads: int = 0,
) -> MatchResult: ...

def screen(
    query: Union[PathLike, Molecule, Descriptors],
    library: PathLike,
    *,
    molecules: bool = False,
    top: int = 100,
    refine: int = 5,
    refine_starts: int = 0,
    candidates: int = 50,
    fusion: str = 'max',
    chemistry: str = 'auto',
    site_ligand: Optional[PathLike] = None,
    site_sphere: Optional[SiteSpheres] = None,
    site_pocket: Optional[int] = None,
    record: Optional[int] = None,
    fine_top: int = 2,
    atom_polish_sigma: float = 0.5,
    atom_polish_weight: float = 1.0,
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
    threads: int = 0,
) -> List[Hit]: ...

def screen_queries(
    queries: Sequence[Union[PathLike, Molecule, Descriptors]],
    library: PathLike,
    *,
    molecules: bool = False,
    top: int = 100,
    refine: int = 5,
    refine_starts: int = 0,
    candidates: int = 50,
    fusion: str = 'max',
    chemistry: str = 'auto',
    site_ligand: Optional[PathLike] = None,
    site_sphere: Optional[SiteSpheres] = None,
    site_pocket: Optional[int] = None,
    record: Optional[int] = None,
    fine_top: int = 2,
    atom_polish_sigma: float = 0.5,
    atom_polish_weight: float = 1.0,
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
    threads: int = 0,
) -> Screens: ...

def screen_receptor(
    receptor: PathLike,
    library: PathLike,
    *,
    ligand: Optional[PathLike] = None,
    record: Optional[int] = None,
    molecule: Optional[PathLike] = None,
    repair: bool = False,
    scale: str = 'auto',
    unit: Optional[float] = None,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    min_plddt: float = 0.0,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
    patch_radius: float = 5.0,
    max_image_bytes: int = 1073741824,
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
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
    contact_gap: float = 0.5,
    contact_width: float = 0.5,
    clash_tolerance: float = 0.5,
    metal_allowance: float = 1.0,
    clash_weight: float = 100.0,
    esp_weight: float = 0.2,
    lp_weight: float = 0.2,
    site_weight: float = 1.0,
    grid_spacing: float = 0.4,
    grid_margin: float = 6.0,
    sample_spacing: float = 1.0,
    refine_top: int = 40,
    search_chains: int = 48,
    search_steps: int = 40,
    search_sample_spacing: float = 2.0,
    search_min_gain: float = 1e-05,
    search_temperature: float = 0.05,
    distinct_rmsd: float = 1.0,
    max_ligand_to_site: float = 3.0,
    site_ligand: Optional[PathLike] = None,
    site_sphere: Optional[SiteSpheres] = None,
    site_pocket: Optional[int] = None,
    threads: int = 0,
    fast_chains: int = 8,
    fast_steps: int = 10,
    candidates: int = 20,
    top: int = 0,
    rank_by: str = 'mean',
) -> List[ReceptorHit]: ...

def dock(
    probe: Union[PathLike, Molecule],
    receptor: PathLike,
    *,
    output: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[PathLike] = None,
    record: Optional[int] = None,
    min_plddt: float = 0.0,
    molecule: Optional[PathLike] = None,
    repair: bool = False,
    scale: str = 'auto',
    unit: Optional[float] = None,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
    patch_radius: float = 5.0,
    max_image_bytes: int = 1073741824,
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
    site_radius: float = 4.0,
    site_margin: float = 16.0,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
    contact_gap: float = 0.5,
    contact_width: float = 0.5,
    clash_tolerance: float = 0.5,
    metal_allowance: float = 1.0,
    clash_weight: float = 100.0,
    esp_weight: float = 0.2,
    lp_weight: float = 0.2,
    site_weight: float = 1.0,
    grid_spacing: float = 0.4,
    grid_margin: float = 6.0,
    sample_spacing: float = 1.0,
    poses: int = 9,
    refine_top: int = 40,
    search_chains: int = 48,
    search_steps: int = 40,
    search_sample_spacing: float = 2.0,
    search_min_gain: float = 1e-05,
    search_temperature: float = 0.05,
    conformers: int = 0,
    conformer_seed: int = 42,
    distinct_rmsd: float = 1.0,
    local_only: bool = False,
    score_only: bool = False,
    max_ligand_to_site: float = 3.0,
    site_ligand: Optional[PathLike] = None,
    site_sphere: Optional[SiteSpheres] = None,
    site_pocket: Optional[int] = None,
    threads: int = 0,
) -> DockResult: ...

def pockets(
    structure: PathLike,
    *,
    min_plddt: float = 0.0,
    max_atoms: int = 2000000,
    pocket_min_radius: float = 3.2,
    pocket_max_radius: float = 6.4,
    pocket_buriedness: float = 0.6,
    pocket_min_spheres: int = 12,
    pocket_max_volume: float = 0.0,
) -> List[Pocket]: ...

def screen_shapes(
    query: Union[PathLike, Surface, MeshArrays],
    library: PathLike,
    *,
    top: int = 100,
    scale: str = "auto",
    unit: Optional[float] = None,
    repair: bool = False,
    threads: int = 0,
) -> List[ShapeHit]: ...

def matrix(
    set: Union[PathLike, Sequence[PathLike]],
    against: Union[PathLike, Sequence[PathLike], None] = None,
    *,
    transforms: bool = False,
    output: Optional[PathLike] = None,
    probe_radius: float = 1.4,
    density: float = 2.5,
    voxel: float = 0.0,
    ses_method: str = 'exact',
    charges: str = 'file',
    eps: float = 1.0,
    eps_distance_dependent: bool = False,
    lp_kernel: str = 'fauchere',
    ligand: Optional[PathLike] = None,
    min_plddt: float = 0.0,
    max_atoms: int = 2000000,
    max_grid_cells: float = 200000000.0,
    max_vertices: int = 20000000,
    patch_radius: float = 5.0,
    max_image_bytes: int = 1073741824,
    shape_only: bool = False,
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
    fine_top: int = 2,
    overlay_sigma: float = 1.0,
    overlay_chem_weight: float = 6.0,
    overlay_atom_weight: float = 14.0,
    polish_top: int = 5,
    atom_polish_sigma: float = 0.5,
    atom_polish_weight: float = 1.0,
    overlay_tolerance: float = 0.1,
    coverage_distance: float = 1.0,
    icp_top: int = 0,
    icp_max_distance: float = 1.5,
    principal_axes_starts: int = 24,
    refined_overlays: int = 0,
    full_matches: int = 2,
    exact: bool = False,
    neighbours: int = 0,
    max_pairs: int = 10000000,
    threads: int = 0,
) -> SimilarityMatrix: ...

def library_info(path: PathLike) -> LibraryInfo: ...
def option_table(function: str) -> List[Dict[str, Any]]: ...

def curvatures(
    mesh: Union[MeshArrays, Surface],
    *,
    scale: str = 'auto',
    unit: Optional[float] = None,
) -> Curvatures: ...

def critical_points(
    mesh: Union[MeshArrays, Surface],
    *,
    scale: str = 'auto',
    unit: Optional[float] = None,
    critical_point_radius: float = 2.5,
    disc_radius: float = 1.0,
) -> CriticalPointSet: ...

def geodesic_distances(
    mesh: Union[MeshArrays, Surface],
    source_vertex: int,
    max_distance: Optional[float] = None,
    *,
    method: str = 'fast-marching',
) -> npt.NDArray[np.float64]: ...  # (n,); inf beyond max_distance

def patch(
    mesh: Union[MeshArrays, Surface],
    center_vertex: int,
    radius: Optional[float] = None,
    *,
    scale: str = 'auto',
    unit: Optional[float] = None,
) -> GeodesicPatch: ...

def disk_map(
    patch_or_mesh: Union[GeodesicPatch, Patch, MeshArrays],
    method: str = 'harmonic',
    *,
    weights: str = 'inverse-length',
) -> npt.NDArray[np.float64]: ...  # (k, 2)

def shape_image(
    mesh: Union[MeshArrays, Surface],
    center_vertex: int,
    radius: Optional[float] = None,
    *,
    scale: str = 'auto',
    unit: Optional[float] = None,
    image_rings: int = 16,
    image_sectors: int = 180,
    weights: str = 'inverse-length',
) -> npt.NDArray[np.float64]: ...  # (image_rings, image_sectors); NaN where no value
