"""Partial, noisy, moved copies of a mesh with their true motion: the cases of the mesh
registration benchmark (bench/mesh_registration_bench.py) and of the mesh match tests.

A case is made from a closed mesh in four steps, each from one seeded generator:
  1. crop: the faces whose centroids are nearest a random vertex, up to a fraction of the area,
     then the largest connected piece of them (a partial view);
  2. remesh: every triangle split into four at its edge midpoints, or with Open3D (when it is
     given) quadric decimation to half the triangles, so that the copy's vertices are not the
     original's;
  3. noise: Gaussian, per coordinate, a fraction of the original's bounding-box diagonal;
  4. a random rigid motion (uniform rotation, translation about 0.3 diagonal).
The truth is the copy's vertices before noise and motion (``truth``): a recovered motion T that
takes the copy into the original's frame is judged by ``motion_error``, the RMSE of
T(R x + t) - x over those vertices, as a fraction of the diagonal.
Needs NumPy only (Open3D for the decimation).
"""
import numpy as np


def read_off(path):
    """Vertices (n, 3) and triangles (m, 3) of an OFF file (polygons fanned into triangles)."""
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0]
            tokens.extend(line.split())
    if not tokens or not tokens[0].endswith("OFF"):
        raise ValueError(f"{path}: not an OFF file")
    n_vertices, n_faces = int(tokens[1]), int(tokens[2])
    at = 4
    vertices = np.array(tokens[at:at + 3 * n_vertices], float).reshape(n_vertices, 3)
    at += 3 * n_vertices
    faces = []
    for _ in range(n_faces):
        k = int(tokens[at])
        polygon = [int(x) for x in tokens[at + 1:at + 1 + k]]
        at += 1 + k
        faces.extend([polygon[0], polygon[i], polygon[i + 1]] for i in range(1, k - 1))
    return vertices, np.array(faces, dtype=np.int64).reshape(-1, 3)


def write_off(path, vertices, faces):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        np.savetxt(f, vertices, fmt="%.9g")
        np.savetxt(f, np.column_stack([np.full(len(faces), 3), faces]), fmt="%d")


def face_areas(vertices, faces):
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def diagonal(vertices):
    return float(np.linalg.norm(vertices.max(0) - vertices.min(0)))


def _largest_piece(faces):
    """The faces of the largest vertex-connected piece of ``faces``."""
    parent = np.arange(faces.max() + 1)

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b, c in faces:
        for u, v in ((a, b), (b, c)):
            ru, rv = find(u), find(v)
            if ru != rv:
                parent[max(ru, rv)] = min(ru, rv)
    roots = np.array([find(a) for a in faces[:, 0]])
    values, counts = np.unique(roots, return_counts=True)
    return faces[roots == values[np.argmax(counts)]]


def _compact(vertices, faces):
    used = np.unique(faces)
    index = -np.ones(len(vertices), dtype=np.int64)
    index[used] = np.arange(len(used))
    return vertices[used], index[faces]


def crop(vertices, faces, fraction, rng):
    """The largest piece of the faces nearest a random vertex, up to ``fraction`` of the area."""
    areas = face_areas(vertices, faces)
    centre = vertices[rng.integers(len(vertices))]
    order = np.argsort(np.linalg.norm(vertices[faces].mean(1) - centre, axis=1), kind="stable")
    count = int(np.searchsorted(np.cumsum(areas[order]), fraction * areas.sum())) + 1
    return _compact(vertices, _largest_piece(faces[np.sort(order[:count])]))


def subdivide(vertices, faces):
    """Every triangle split into four at its edge midpoints (new vertices on the surface)."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), 1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    mid = len(vertices) + inverse.reshape(3, -1).T  # midpoints of edges 01, 12, 20 per face
    out_vertices = np.vstack([vertices, vertices[unique].mean(1)])
    a, b, c = faces.T
    m01, m12, m20 = mid.T
    out_faces = np.concatenate([np.column_stack(t) for t in
                                ((a, m01, m20), (m01, b, m12), (m20, m12, c), (m01, m12, m20))])
    return out_vertices, out_faces


def decimate(vertices, faces, open3d):
    """Open3D's quadric decimation to half the triangles."""
    mesh = open3d.geometry.TriangleMesh(open3d.utility.Vector3dVector(vertices),
                                        open3d.utility.Vector3iVector(faces.astype(np.int32)))
    mesh = mesh.simplify_quadric_decimation(max(4, len(faces) // 2))
    mesh.remove_unreferenced_vertices()
    return np.asarray(mesh.vertices).copy(), np.asarray(mesh.triangles).astype(np.int64)


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


class Case:
    """A partial copy (``vertices``, ``faces``) of a mesh and its truth."""

    def __init__(self, vertices, faces, truth, rotation, translation, diag, area_fraction):
        self.vertices, self.faces = vertices, faces
        self.truth = truth  # (n, 3): the copy's vertices before noise and motion
        self.rotation, self.translation = rotation, translation
        self.diagonal = diag  # of the original mesh
        self.area_fraction = area_fraction


def make_case(vertices, faces, seed, fraction=None, noise=None, open3d=None):
    """A case from a closed mesh; fraction in [0.3, 0.7] and noise in [0.005, 0.01] drawn from
    the seed unless given."""
    rng = np.random.default_rng(seed)
    fraction = rng.uniform(0.3, 0.7) if fraction is None else fraction
    noise = rng.uniform(0.005, 0.01) if noise is None else noise
    diag = diagonal(vertices)
    part_v, part_f = crop(vertices, faces, fraction, rng)
    area_fraction = face_areas(part_v, part_f).sum() / face_areas(vertices, faces).sum()
    part_v, part_f = decimate(part_v, part_f, open3d) if open3d else subdivide(part_v, part_f)
    rotation = random_rotation(rng)
    translation = rng.normal(size=3) * 0.3 * diag
    noisy = part_v + rng.normal(size=part_v.shape) * noise * diag
    return Case(noisy @ rotation.T + translation, part_f, part_v, rotation, translation, diag,
                area_fraction)


def motion_error(case, transform):
    """RMSE, as a fraction of the diagonal, of transform(R x + t) - x over the truth x."""
    moved = case.truth @ case.rotation.T + case.translation
    back = moved @ transform[:3, :3].T + transform[:3, 3]
    return float(np.sqrt(((back - case.truth) ** 2).sum(1).mean()) / case.diagonal)
