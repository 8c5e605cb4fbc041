"""Meshing and skinning of the creatures: the template mesh, joint weights, and deformation.

The template (standing pose) is meshed once per ``(species, n_vertices)`` and cached; every pose
or part scaling moves its vertices with smooth per-joint weights (forward kinematics with
fractional angles, see :mod:`lbo_notebooks.shapes._creatures`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Mapping

import numpy as np
from numpy.typing import NDArray

from ...geometry._mesh import Mesh
from .implicit import field_on_grid, primitive_distance, project_to_surface
from .tables import JOINT_PARENTS, JOINTS, Angles, Species, species_plan

# ------------------------------------------------------------------------------------------
# Template: meshing and skinning weights (computed once per species and size, kept in memory)
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Template:
    mesh: Mesh  # the standing pose
    owners: NDArray[np.int64]  # per vertex: index into JOINT_ORDER of the joint that moves it
    weights: NDArray[np.float64]  # (len(JOINTS), n): phi_j per vertex
    centres: NDArray[np.float64]  # (len(JOINTS), 3): rotation centres
    scale_weights: NDArray[np.float64]  # (len(JOINTS), n): psi_j, the weights of part scaling
    scale_centres: NDArray[np.float64]  # (len(JOINTS), 3): centres of part scaling
    centre_weights: NDArray[np.float64]  # (len(JOINTS), len(JOINTS)): psi_j at rotation centre k


JOINT_ORDER: tuple[str, ...] = tuple(JOINT_PARENTS)  # parents before children (root first)


def _subtree(joint: str) -> set[str]:
    """The joint and every joint below it."""
    out = {joint}
    changed = True
    while changed:
        changed = False
        for j, parent in JOINT_PARENTS.items():
            if parent in out and j not in out:
                out.add(j)
                changed = True
    return out


def _remesh(spec: Species, n_vertices: int) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Marching cubes, then isotropic remeshing to about ``n_vertices``, then projection."""
    import warnings

    from skimage.measure import marching_cubes

    with warnings.catch_warnings():  # gpytoolbox's import touches deprecated numpy/scipy paths
        warnings.simplefilter("ignore", DeprecationWarning)
        import gpytoolbox

    values, origin = field_on_grid(spec)
    v, f, _, _ = marching_cubes(values, 0.0, spacing=(spec.spacing,) * 3)
    v = v.astype(np.float64) + origin
    f = np.ascontiguousarray(f, dtype=np.int32)
    # A surface of equilateral triangles with edge h has 2 area / (sqrt(3) h^2) vertices. The
    # remesher lands a little below that at small sizes, hence the factor 0.98;
    # a second pass corrects h when the count is more than 4% off.
    p = v[f]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum()
    h = 0.98 * np.sqrt(2.0 * area / (np.sqrt(3.0) * n_vertices))
    stage = 1.25 * spec.spacing
    if h < stage:
        # Refining far below the marching-cubes edge length in one go stalls the remesher
        # (for minutes on large meshes); an intermediate, projected mesh avoids it.
        v, f = gpytoolbox.remesh_botsch(v, f, 5, stage, True)
        v = project_to_surface(spec, np.asarray(v, dtype=np.float64))
        f = np.ascontiguousarray(f, dtype=np.int32)
    best = None
    for _ in range(4):
        u, g = gpytoolbox.remesh_botsch(v, f, 10, h, True)
        u, g = np.asarray(u, dtype=np.float64), np.asarray(g, dtype=np.int64)
        ratio = len(u) / n_vertices
        # The remesher should keep the topology; a sphere it must stay (else try another h).
        if _is_sphere(u, g) and (best is None or abs(ratio - 1.0) < abs(len(best[0]) / n_vertices - 1.0)):
            best = (u, g)
        if best is not None and abs(len(best[0]) / n_vertices - 1.0) < 0.04:
            break
        h *= np.sqrt(ratio) if abs(ratio - 1.0) >= 0.04 else 1.03
    if best is None:
        raise RuntimeError(f"remeshing did not give a closed genus-0 surface for n_vertices={n_vertices}; try another size.")
    return project_to_surface(spec, best[0]), best[1]


def _is_sphere(v: NDArray[np.float64], f: NDArray[np.int64]) -> bool:
    """True for a closed, edge-manifold, connected triangle mesh with Euler characteristic 2."""
    from ...geometry._mesh import MeshError

    try:
        m = Mesh(v, f)
    except MeshError:
        return False
    return m.is_closed and m.n_components == 1 and m.euler_characteristic == 2


def _joint_weights(
    mesh: Mesh, owners: NDArray[np.int64], bands: Mapping[str, tuple[float, float]]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """phi_j for every joint and its centre.

    phi_j is 1 on the body parts below joint j and 0 on the rest, except in a band around the
    seam between the two, measured along the surface (shortest paths on the edge graph), where
    it solves the cotangent Laplace equation; it rises from 0 to 1 almost linearly across the
    band, which spreads a rotation evenly. The joint's centre is the centroid of the ring
    ``phi ~ 1/2`` (weights ``(phi (1 - phi))**2``): on the bone's axis, mid-band.
    """
    import scipy.sparse as sp
    from scipy.sparse.csgraph import dijkstra
    from scipy.sparse.linalg import spsolve

    from ...operators._cotangent import stiffness_matrix

    W = stiffness_matrix(mesh).tocsr()
    v, e, n = mesh.vertices, mesh.edges, mesh.n_vertices
    length = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    graph = sp.coo_matrix((length, (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    weights = np.zeros((len(JOINTS), n))
    centres = np.zeros((len(JOINTS), 3))
    for row, joint in enumerate(JOINTS):
        members = np.array([JOINT_ORDER.index(j) for j in _subtree(joint)])
        inside = np.isin(owners, members)
        cut = e[inside[e[:, 0]] != inside[e[:, 1]]]
        if len(cut) == 0:
            raise RuntimeError(f"joint {joint!r} has no seam on the surface (internal error).")
        parent_side, child_side = bands[joint]
        dist = dijkstra(graph, directed=False, indices=np.unique(cut), min_only=True,
                        limit=max(parent_side, child_side))
        if child_side == 0.0:  # the seam's inner vertices join the band too
            inner = np.unique(cut[inside[cut]])
            dist[inner] = 0.0
            child_side = 1e-12
        band = np.where(inside, dist < child_side, dist < parent_side)
        phi = inside.astype(np.float64)
        free = np.flatnonzero(band)
        fixed = np.flatnonzero(~band)
        Wf = W[free]
        phi[free] = spsolve(sp.csc_matrix(Wf[:, free]), -(Wf[:, fixed] @ phi[fixed]))
        phi = np.clip(phi, 0.0, 1.0)
        weights[row] = phi
        # Centroid of the band weighted towards phi = 1/2 (the seam itself if the band is empty).
        w = (phi * (1.0 - phi)) ** 2
        centres[row] = w @ v / w.sum() if w.sum() > 0 else 0.5 * (v[cut[:, 0]] + v[cut[:, 1]]).mean(axis=0)
    return weights, centres


@functools.lru_cache(maxsize=16)
def template_for(species: str, n_vertices: int) -> Template:
    """The standing mesh with its skinning data; cached in memory (arrays are read-only)."""
    spec = species_plan(species)
    u, g = _remesh(spec, n_vertices)
    mesh = Mesh(u, g)
    d = np.stack([primitive_distance(pr, u) for pr in spec.primitives])
    owner_names = [spec.primitives[i].owner for i in np.argmin(d, axis=0)]
    owners = np.array([JOINT_ORDER.index(o) for o in owner_names], dtype=np.int64)
    weights, centres = _joint_weights(mesh, owners, spec.bands)
    # Part scaling blends on the parent side only, so that the whole part keeps its shape.
    scale_weights, scale_centres = _joint_weights(mesh, owners, {j: (spec.scale_band, 0.0) for j in JOINTS})
    from scipy.spatial import cKDTree

    _, near = cKDTree(u).query(centres, k=8)
    centre_weights = scale_weights[:, near].mean(axis=2)  # psi_j at each rotation centre
    out = Template(mesh, owners, weights, centres, scale_weights, scale_centres, centre_weights)
    for a in (owners, weights, centres, scale_weights, scale_centres, centre_weights):
        a.setflags(write=False)
    return out


def rotation_vector(angles: Angles) -> NDArray[np.float64]:
    """Rotation vector of R = R_yaw @ R_pitch @ R_roll (angles in degrees, conventions above)."""
    from scipy.spatial.transform import Rotation

    pitch, yaw, roll = np.radians(np.asarray(angles, dtype=np.float64))
    r = Rotation.from_rotvec([0.0, 0.0, yaw]) * Rotation.from_rotvec([0.0, -pitch, 0.0]) * Rotation.from_rotvec([roll, 0.0, 0.0])
    return r.as_rotvec()


def _rotate(points: NDArray[np.float64], centre: NDArray[np.float64], rotvec: NDArray[np.float64], fraction: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotate each point about ``centre`` by ``fraction`` times the rotation ``rotvec`` (Rodrigues)."""
    theta = float(np.linalg.norm(rotvec))
    if theta == 0.0:
        return points
    k = rotvec / theta
    q = points - centre
    ang = fraction * theta
    c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]
    return centre + q * c + np.cross(k, q) * s + np.outer(q @ k, k) * (1.0 - c)


# ------------------------------------------------------------------------------------------
# Deformation and public API
# ------------------------------------------------------------------------------------------
def deform(template: Template, rotations: dict[str, NDArray[np.float64]], scales: dict[str, float]) -> NDArray[np.float64]:
    """Part scalings, then joint rotations (deepest first), then the rigid ``"body"`` turn."""
    x = np.array(template.mesh.vertices, dtype=np.float64)
    centres = np.array(template.centres)
    for row in range(len(JOINTS) - 1, -1, -1):  # deepest joints first
        joint = JOINTS[row]
        s = scales.get(joint, 1.0)
        if s == 1.0:
            continue
        c = template.scale_centres[row]
        x = c + np.power(s, template.scale_weights[row])[:, None] * (x - c)
        centres = c + np.power(s, template.centre_weights[row])[:, None] * (centres - c)
    for row in range(len(JOINTS) - 1, -1, -1):
        rotvec = rotations.get(JOINTS[row])
        if rotvec is not None:
            x = _rotate(x, centres[row], rotvec, template.weights[row])
    if "body" in rotations:
        x = _rotate(x, x.mean(axis=0), rotations["body"], np.ones(len(x)))
    # Rest on the same ground plane as the standing pose (a rigid translation).
    x[:, 2] += template.mesh.vertices[:, 2].min() - x[:, 2].min()
    return x

