"""Procedural four-legged creatures in correspondence: poses and part scalings of one template.

A creature is the zero level set of an implicit function, a smooth union of round cones and
ellipsoids laid out along a skeleton (torso, neck, head with snout and ears, four legs, tail).
The surface is meshed once per ``(species, n_vertices)`` — marching cubes
(:func:`skimage.measure.marching_cubes`), isotropic remeshing (:func:`gpytoolbox.remesh_botsch`)
to the requested size, then Newton projection back onto the smooth implicit surface — and
cached in memory. That *template* is the standing pose.

Every other pose or part scaling moves the template's vertices and keeps its faces, so all the
meshes of one ``(species, n_vertices)`` share a triangulation: vertex ``i`` is the same point
of the body in each. Deformations are driven by named joints. Each joint ``j`` owns a smooth
weight ``phi_j`` on the surface: 1 on the body parts below the joint, 0 on the rest and
harmonic (cotangent Laplace equation) in a band around the junction. A joint rotation by angle
``theta`` turns vertex ``x`` by ``phi_j(x) * theta`` about the joint centre, deepest joints first
(forward kinematics with fractional angles); a part scaling by ``s`` maps
``x -> c + s**psi_j(x) (x - c)``, with a weight ``psi_j`` that blends on the parent side of the
seam only, so that the whole part scales by ``s``. Because the rotation is spread evenly over the band, an
outer fibre at distance ``r`` from the bone axis stretches by about ``r theta / L`` for a band
of length ``L``: joints sit where the body is thin and the poses keep their angles moderate, so
the deformations stay nearly isometric.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np
from numpy.typing import NDArray

from .mesh import Mesh

__all__ = [
    "creature", "creature_poses", "creature_parts", "pose_distortion", "vertex_strain", "joint_bands",
    "SPECIES", "POSES", "JOINTS", "PARTS",
]

SPECIES: tuple[str, ...] = ("dog", "horse")


# ------------------------------------------------------------------------------------------
# Skeleton and body plan
# ------------------------------------------------------------------------------------------
# Joint tree shared by all species: name -> parent ("" for the root). Left ("_l") joints have
# y > 0; right ("_r") joints mirror them. The root ("pelvis") is not a rotating joint.
_JOINT_PARENTS: dict[str, str] = {
    "pelvis": "",
    "spine": "pelvis",
    "neck": "spine",
    "head": "neck",
    "ear_l": "head",
    "ear_r": "head",
    "tail_base": "pelvis",
    "tail_mid": "tail_base",
    "shoulder_l": "spine",
    "elbow_l": "shoulder_l",
    "wrist_l": "elbow_l",
    "shoulder_r": "spine",
    "elbow_r": "shoulder_r",
    "wrist_r": "elbow_r",
    "hip_l": "pelvis",
    "knee_l": "hip_l",
    "hock_l": "knee_l",
    "hip_r": "pelvis",
    "knee_r": "hip_r",
    "hock_r": "knee_r",
}
JOINTS: tuple[str, ...] = tuple(j for j in _JOINT_PARENTS if j != "pelvis")
"""Names of the joints a pose may rotate (the dict form of ``pose`` in :func:`creature`)."""


@dataclass(frozen=True)
class _Primitive:
    """One implicit primitive: a round cone (two spheres' hull) or an ellipsoid.

    ``owner`` is the joint that moves it (its proximal joint); ``blend`` the smooth-union
    radius with which its subtree joins its parent primitive (``parent``, an index into the
    primitive list, -1 for the root).
    """

    kind: str  # "cone" or "ellipsoid"
    owner: str
    parent: int
    blend: float
    a: tuple[float, float, float] = (0.0, 0.0, 0.0)  # cone start / ellipsoid centre
    b: tuple[float, float, float] = (0.0, 0.0, 0.0)  # cone end
    ra: float = 0.0  # cone radius at a
    rb: float = 0.0  # cone radius at b
    radii: tuple[float, float, float] = (1.0, 1.0, 1.0)  # ellipsoid semi-axes (before rotation)
    tilt: tuple[float, float, float] = (0.0, 0.0, 0.0)  # ellipsoid rotation vector (radians)
    squash: float = 1.0  # cone: lateral (y) squash factor of the cross-section


@dataclass(frozen=True)
class _Species:
    primitives: tuple[_Primitive, ...]
    bands: dict[str, tuple[float, float]]  # (parent side, child side) band extents
    scale_band: float  # parent-side band extent of part scaling
    spacing: float  # marching-cubes grid spacing


def _mirror(p: tuple[float, float, float]) -> tuple[float, float, float]:
    return (p[0], -p[1], p[2])


def _build_species(
    body: list[dict[str, Any]],
    leg: list[dict[str, Any]],
    ear: dict[str, Any],
    bands: dict[str, tuple[float, float]],
    scale_band: float,
    spacing: float,
) -> _Species:
    """Assemble the primitives; left-side entries (ears, legs) are mirrored to the right."""
    prims: list[_Primitive] = []
    index: dict[str, int] = {}
    for spec in body:
        spec = dict(spec)
        key = spec.pop("key")
        parent = spec.pop("parent", None)
        index[key] = len(prims)
        prims.append(_Primitive(parent=-1 if parent is None else index[parent], **spec))
    for side in ("_l", "_r"):
        for spec in [dict(ear)] + [dict(s) for s in leg]:
            spec = dict(spec)
            key = spec.pop("key") + side
            parent = spec.pop("parent")
            parent = parent + side if parent + side in index else parent
            if spec["owner"] + side in _JOINT_PARENTS:
                spec["owner"] = spec["owner"] + side
            if side == "_r":
                for f in ("a", "b"):
                    if f in spec:
                        spec[f] = _mirror(spec[f])
                if "tilt" in spec:
                    t = spec["tilt"]
                    spec["tilt"] = (-t[0], t[1], -t[2])
            index[key] = len(prims)
            prims.append(_Primitive(parent=index[parent], **spec))
    full_bands = {}
    for name in JOINTS:
        base = name[:-2] if name.endswith(("_l", "_r")) else name
        full_bands[name] = bands[base]
    return _Species(tuple(prims), full_bands, scale_band, spacing)


def _dog() -> _Species:
    body = [
        dict(key="pelvis", kind="cone", owner="pelvis", blend=0.0, a=(-0.40, 0, 0.62), b=(-0.06, 0, 0.63),
             ra=0.14, rb=0.155, squash=0.85),
        dict(key="chest", parent="pelvis", kind="cone", owner="spine", blend=0.16, a=(0.04, 0, 0.62),
             b=(0.30, 0, 0.62), ra=0.165, rb=0.185, squash=0.8),
        dict(key="neck", parent="chest", kind="cone", owner="neck", blend=0.10, a=(0.34, 0, 0.70),
             b=(0.57, 0, 0.98), ra=0.09, rb=0.07),
        dict(key="head", parent="neck", kind="ellipsoid", owner="head", blend=0.06, a=(0.61, 0, 1.03),
             radii=(0.13, 0.09, 0.095)),
        dict(key="snout", parent="head", kind="cone", owner="head", blend=0.06, a=(0.67, 0, 1.01),
             b=(0.85, 0, 0.97), ra=0.066, rb=0.045),
        dict(key="tail1", parent="pelvis", kind="cone", owner="tail_base", blend=0.06, a=(-0.40, 0, 0.67),
             b=(-0.58, 0, 0.78), ra=0.05, rb=0.04),
        dict(key="tail2", parent="tail1", kind="cone", owner="tail_mid", blend=0.03, a=(-0.58, 0, 0.78),
             b=(-0.74, 0, 0.92), ra=0.04, rb=0.03),
    ]
    ear = dict(key="ear", parent="head", kind="ellipsoid", owner="ear", blend=0.035, a=(0.57, 0.062, 1.13),
               radii=(0.045, 0.022, 0.07), tilt=(-0.35, 0.0, 0.0))
    leg = [
        dict(key="upper_arm", parent="chest", kind="cone", owner="shoulder", blend=0.08, a=(0.28, 0.11, 0.56),
             b=(0.25, 0.11, 0.32), ra=0.07, rb=0.05),
        dict(key="forearm", parent="upper_arm", kind="cone", owner="elbow", blend=0.03, a=(0.25, 0.11, 0.32),
             b=(0.28, 0.11, 0.09), ra=0.05, rb=0.038),
        dict(key="front_paw", parent="forearm", kind="cone", owner="wrist", blend=0.03, a=(0.27, 0.11, 0.045),
             b=(0.34, 0.11, 0.04), ra=0.045, rb=0.04),
        dict(key="thigh", parent="pelvis", kind="cone", owner="hip", blend=0.08, a=(-0.30, 0.11, 0.58),
             b=(-0.22, 0.11, 0.33), ra=0.085, rb=0.05),
        dict(key="shin", parent="thigh", kind="cone", owner="knee", blend=0.03, a=(-0.22, 0.11, 0.33),
             b=(-0.34, 0.11, 0.14), ra=0.05, rb=0.038),
        dict(key="hind_foot", parent="shin", kind="cone", owner="hock", blend=0.03, a=(-0.34, 0.11, 0.14),
             b=(-0.30, 0.11, 0.06), ra=0.038, rb=0.037),
        dict(key="hind_paw", parent="hind_foot", kind="cone", owner="hock", blend=0.03, a=(-0.31, 0.11, 0.045),
             b=(-0.23, 0.11, 0.04), ra=0.045, rb=0.04),
    ]
    # (parent side, child side) extent of each joint's blending band along the surface.
    bands = {"spine": (0.3, 0.3), "neck": (0.03, 0.2), "head": (0.16, 0.04), "ear": (0.01, 0.06),
             "tail_base": (0.02, 0.16), "tail_mid": (0.1, 0.1), "shoulder": (0.03, 0.2),
             "elbow": (0.12, 0.12), "wrist": (0.1, 0.05), "hip": (0.03, 0.2), "knee": (0.12, 0.12),
             "hock": (0.08, 0.06)}
    return _build_species(body, leg, ear, bands, scale_band=0.12, spacing=0.01)


def _horse() -> _Species:
    body = [
        dict(key="pelvis", kind="cone", owner="pelvis", blend=0.0, a=(-0.50, 0, 1.06), b=(-0.10, 0, 1.07),
             ra=0.19, rb=0.21, squash=0.8),
        dict(key="chest", parent="pelvis", kind="cone", owner="spine", blend=0.2, a=(0.0, 0, 1.07),
             b=(0.36, 0, 1.06), ra=0.21, rb=0.23, squash=0.8),
        dict(key="neck", parent="chest", kind="cone", owner="neck", blend=0.14, a=(0.42, 0, 1.16),
             b=(0.70, 0, 1.50), ra=0.13, rb=0.085, squash=0.75),
        dict(key="head", parent="neck", kind="ellipsoid", owner="head", blend=0.08, a=(0.75, 0, 1.55),
             radii=(0.12, 0.075, 0.09), tilt=(0.0, 0.5, 0.0)),
        dict(key="snout", parent="head", kind="cone", owner="head", blend=0.08, a=(0.78, 0, 1.52),
             b=(0.97, 0, 1.36), ra=0.075, rb=0.06, squash=0.85),
        dict(key="tail1", parent="pelvis", kind="cone", owner="tail_base", blend=0.06, a=(-0.62, 0, 1.12),
             b=(-0.76, 0, 0.96), ra=0.06, rb=0.05),
        dict(key="tail2", parent="tail1", kind="cone", owner="tail_mid", blend=0.04, a=(-0.76, 0, 0.96),
             b=(-0.80, 0, 0.68), ra=0.05, rb=0.045),
    ]
    ear = dict(key="ear", parent="head", kind="ellipsoid", owner="ear", blend=0.035, a=(0.69, 0.05, 1.67),
               radii=(0.032, 0.022, 0.065), tilt=(-0.2, -0.2, 0.0))
    leg = [
        dict(key="upper_arm", parent="chest", kind="cone", owner="shoulder", blend=0.09, a=(0.33, 0.14, 0.98),
             b=(0.30, 0.14, 0.68), ra=0.095, rb=0.06),
        dict(key="forearm", parent="upper_arm", kind="cone", owner="elbow", blend=0.04, a=(0.30, 0.14, 0.68),
             b=(0.32, 0.14, 0.28), ra=0.06, rb=0.042),
        dict(key="front_paw", parent="forearm", kind="cone", owner="wrist", blend=0.04, a=(0.32, 0.14, 0.28),
             b=(0.34, 0.14, 0.055), ra=0.042, rb=0.055),
        dict(key="thigh", parent="pelvis", kind="cone", owner="hip", blend=0.09, a=(-0.42, 0.14, 0.98),
             b=(-0.30, 0.14, 0.68), ra=0.10, rb=0.065),
        dict(key="shin", parent="thigh", kind="cone", owner="knee", blend=0.04, a=(-0.30, 0.14, 0.68),
             b=(-0.48, 0.14, 0.40), ra=0.065, rb=0.045),
        dict(key="hind_foot", parent="shin", kind="cone", owner="hock", blend=0.04, a=(-0.48, 0.14, 0.40),
             b=(-0.46, 0.14, 0.055), ra=0.045, rb=0.055),
    ]
    bands = {"spine": (0.35, 0.35), "neck": (0.03, 0.3), "head": (0.2, 0.04), "ear": (0.01, 0.06),
             "tail_base": (0.02, 0.16), "tail_mid": (0.1, 0.1), "shoulder": (0.03, 0.22),
             "elbow": (0.14, 0.14), "wrist": (0.12, 0.06), "hip": (0.03, 0.22), "knee": (0.14, 0.14),
             "hock": (0.1, 0.06)}
    return _build_species(body, leg, ear, bands, scale_band=0.15, spacing=0.012)


@functools.lru_cache(maxsize=None)
def _species(name: str) -> _Species:
    if name == "dog":
        return _dog()
    if name == "horse":
        return _horse()
    raise ValueError(f"unknown species {name!r}; choose one of {SPECIES}.")


# ------------------------------------------------------------------------------------------
# Implicit surface
# ------------------------------------------------------------------------------------------
_FAR = 10.0  # distance value used where a primitive is too far away to matter


def _rotation_matrices(rotvec: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rodrigues' formula for rotation vectors of shape (..., 3) -> matrices (..., 3, 3)."""
    rotvec = np.asarray(rotvec, dtype=np.float64)
    theta = np.linalg.norm(rotvec, axis=-1)
    safe = np.where(theta > 0, theta, 1.0)
    k = rotvec / safe[..., None]
    K = np.zeros(rotvec.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -k[..., 2], k[..., 1]
    K[..., 1, 0], K[..., 1, 2] = k[..., 2], -k[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -k[..., 1], k[..., 0]
    s, c = np.sin(theta)[..., None, None], np.cos(theta)[..., None, None]
    return np.eye(3) + s * K + (1 - c) * (K @ K)


def _primitive_distance(prim: _Primitive, p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Signed distance (exact for round cones, first-order for ellipsoids) of points p (N, 3)."""
    if prim.kind == "ellipsoid":
        R = _rotation_matrices(np.array(prim.tilt))
        q = (p - np.array(prim.a)) @ R  # coordinates in the ellipsoid's frame
        r = np.array(prim.radii)
        k0 = np.linalg.norm(q / r, axis=1)
        k1 = np.maximum(np.linalg.norm(q / r**2, axis=1), 1e-12)
        return k0 * (k0 - 1.0) / k1
    squash = np.array([1.0, prim.squash, 1.0])
    a, b = np.array(prim.a) / squash, np.array(prim.b) / squash
    q = p / squash - a
    length = float(np.linalg.norm(b - a))
    u = (b - a) / length
    y = q @ u
    x = np.sqrt(np.maximum(np.einsum("ij,ij->i", q, q) - y * y, 0.0))
    s = (prim.ra - prim.rb) / length
    c = np.sqrt(1.0 - s * s)
    along = -x * s + y * c  # position along the tangent line of the cone's side
    d = x * c + y * s - prim.ra
    d = np.where(along < 0.0, np.sqrt(x * x + y * y) - prim.ra, d)
    d = np.where(along > length * c, np.sqrt(x * x + (y - length) ** 2) - prim.rb, d)
    return d * (0.5 * (1.0 + prim.squash))


def _primitive_box(prim: _Primitive, margin: float) -> NDArray[np.float64]:
    """Axis-aligned bounding box (2, 3) of a primitive, grown by ``margin``."""
    if prim.kind == "ellipsoid":
        r = max(prim.radii)
        lo, hi = np.array(prim.a) - r, np.array(prim.a) + r
    else:
        r = max(prim.ra, prim.rb)
        lo = np.minimum(prim.a, prim.b) - r
        hi = np.maximum(prim.a, prim.b) + r
    return np.stack([lo - margin, hi + margin])


def _smooth_min(a: NDArray[np.float64], b: NDArray[np.float64], k: float) -> NDArray[np.float64]:
    """C2 polynomial smooth minimum: equals min(a, b) where |a - b| >= k."""
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h**3 * (k / 6.0)


def _combine(spec: _Species, distances: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """Blend primitive distances bottom-up: a node joins each child subtree with its own radius."""
    prims = spec.primitives
    subtree: dict[int, NDArray[np.float64]] = {}
    for i in range(len(prims) - 1, -1, -1):
        own = distances[i]
        children = [c for c in range(i + 1, len(prims)) if prims[c].parent == i]
        value = own
        for c in children:
            value = np.minimum(value, _smooth_min(own, subtree.pop(c), prims[c].blend))
        subtree[i] = value
    return subtree[0]


def _field(spec: _Species, p: NDArray[np.float64]) -> NDArray[np.float64]:
    """The creature's implicit function at points p (N, 3): negative inside."""
    margin = max(pr.blend for pr in spec.primitives) + 0.02
    distances = []
    for prim in spec.primitives:
        lo, hi = _primitive_box(prim, margin)
        inside = np.all((p >= lo) & (p <= hi), axis=1)
        d = np.full(len(p), _FAR)
        d[inside] = _primitive_distance(prim, p[inside])
        distances.append(d)
    return _combine(spec, distances)


def _field_on_grid(spec: _Species) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Sample the implicit function on a regular grid; returns (values (nx, ny, nz), origin).

    The function is first sampled on a grid four times coarser; fine grid points whose nearest
    coarse value is far from zero only need the sign (the function grows at most about as fast
    as the distance), so the exact evaluation is limited to a shell around the surface.
    """
    h = spec.spacing
    boxes = np.array([_primitive_box(pr, 0.0) for pr in spec.primitives])
    origin = boxes[:, 0].min(axis=0) - 3 * h
    shape = np.ceil((boxes[:, 1].max(axis=0) + 3 * h - origin) / h).astype(int) + 1
    axes = [origin[k] + h * np.arange(shape[k]) for k in range(3)]
    step = 4
    coarse_axes = [a[::step] for a in axes]
    coarse_grid = np.meshgrid(*coarse_axes, indexing="ij")
    coarse = _field(spec, np.stack([g.ravel() for g in coarse_grid], axis=1)).reshape(coarse_grid[0].shape)
    nearest = [np.minimum(np.rint(np.arange(shape[k]) / step).astype(int), len(coarse_axes[k]) - 1) for k in range(3)]
    upsampled = coarse[np.ix_(*nearest)]
    values = np.where(upsampled > 0, _FAR, -_FAR)
    shell = np.abs(upsampled) < 2.0 * step * h
    index = np.nonzero(shell)
    points = np.stack([axes[k][index[k]] for k in range(3)], axis=1)
    values[index] = _field(spec, points)
    return values, origin


def _project_to_surface(spec: _Species, p: NDArray[np.float64], iterations: int = 3) -> NDArray[np.float64]:
    """Newton steps ``p -= F grad F / |grad F|^2`` onto the zero level set (finite-difference gradient)."""
    eps = 1e-5
    offsets = np.vstack([np.eye(3), -np.eye(3)]) * eps
    p = p.copy()
    for _ in range(iterations):
        stacked = np.concatenate([p] + [p + o for o in offsets])
        values = _field(spec, stacked).reshape(7, len(p))
        grad = (values[1:4] - values[4:7]).T / (2 * eps)
        g2 = np.maximum(np.einsum("ij,ij->i", grad, grad), 1e-12)
        step = (values[0] / g2)[:, None] * grad
        # Never move more than a fraction of the grid spacing (guards against creases).
        norm = np.linalg.norm(step, axis=1, keepdims=True)
        p -= step * np.minimum(1.0, spec.spacing / np.maximum(norm, 1e-300))
    return p


# ------------------------------------------------------------------------------------------
# Template: meshing and skinning weights (computed once per species and size, kept in memory)
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Template:
    mesh: Mesh  # the standing pose
    owners: NDArray[np.int64]  # per vertex: index into JOINT_ORDER of the joint that moves it
    weights: NDArray[np.float64]  # (len(JOINTS), n): phi_j per vertex
    centres: NDArray[np.float64]  # (len(JOINTS), 3): rotation centres
    scale_weights: NDArray[np.float64]  # (len(JOINTS), n): psi_j, the weights of part scaling
    scale_centres: NDArray[np.float64]  # (len(JOINTS), 3): centres of part scaling
    centre_weights: NDArray[np.float64]  # (len(JOINTS), len(JOINTS)): psi_j at rotation centre k


_JOINT_ORDER: tuple[str, ...] = tuple(_JOINT_PARENTS)  # parents before children (root first)


def _subtree(joint: str) -> set[str]:
    """The joint and every joint below it."""
    out = {joint}
    changed = True
    while changed:
        changed = False
        for j, parent in _JOINT_PARENTS.items():
            if parent in out and j not in out:
                out.add(j)
                changed = True
    return out


def _remesh(spec: _Species, n_vertices: int) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Marching cubes, then isotropic remeshing to about ``n_vertices``, then projection."""
    import warnings

    from skimage.measure import marching_cubes

    with warnings.catch_warnings():  # gpytoolbox's import touches deprecated numpy/scipy paths
        warnings.simplefilter("ignore", DeprecationWarning)
        import gpytoolbox

    values, origin = _field_on_grid(spec)
    v, f, _, _ = marching_cubes(values, 0.0, spacing=(spec.spacing,) * 3)
    v = v.astype(np.float64) + origin
    f = np.ascontiguousarray(f, dtype=np.int32)
    # A surface of equilateral triangles with edge h has 2 area / (sqrt(3) h^2) vertices. The
    # remesher lands about 4% below that at small sizes (measured), hence the factor 0.98;
    # a second pass corrects h when the count is more than 4% off.
    p = v[f]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum()
    h = 0.98 * np.sqrt(2.0 * area / (np.sqrt(3.0) * n_vertices))
    stage = 1.25 * spec.spacing
    if h < stage:
        # Refining far below the marching-cubes edge length in one go stalls the remesher
        # (measured: > 2 min at 45k vertices); an intermediate, projected mesh avoids it.
        v, f = gpytoolbox.remesh_botsch(v, f, 5, stage, True)
        v = _project_to_surface(spec, np.asarray(v, dtype=np.float64))
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
    return _project_to_surface(spec, best[0]), best[1]


def _is_sphere(v: NDArray[np.float64], f: NDArray[np.int64]) -> bool:
    """True for a closed, edge-manifold, connected triangle mesh with Euler characteristic 2."""
    from .mesh import MeshError

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

    from .operators import stiffness_matrix

    W = stiffness_matrix(mesh).tocsr()
    v, e, n = mesh.vertices, mesh.edges, mesh.n_vertices
    length = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    graph = sp.coo_matrix((length, (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    weights = np.zeros((len(JOINTS), n))
    centres = np.zeros((len(JOINTS), 3))
    for row, joint in enumerate(JOINTS):
        members = np.array([_JOINT_ORDER.index(j) for j in _subtree(joint)])
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
def _template(species: str, n_vertices: int) -> _Template:
    """The standing mesh with its skinning data; cached in memory (arrays are read-only)."""
    spec = _species(species)
    u, g = _remesh(spec, n_vertices)
    mesh = Mesh(u, g)
    d = np.stack([_primitive_distance(pr, u) for pr in spec.primitives])
    owner_names = [spec.primitives[i].owner for i in np.argmin(d, axis=0)]
    owners = np.array([_JOINT_ORDER.index(o) for o in owner_names], dtype=np.int64)
    weights, centres = _joint_weights(mesh, owners, spec.bands)
    # Part scaling blends on the parent side only, so that the whole part keeps its shape.
    scale_weights, scale_centres = _joint_weights(mesh, owners, {j: (spec.scale_band, 0.0) for j in JOINTS})
    from scipy.spatial import cKDTree

    _, near = cKDTree(u).query(centres, k=8)
    centre_weights = scale_weights[:, near].mean(axis=2)  # psi_j at each rotation centre
    out = _Template(mesh, owners, weights, centres, scale_weights, scale_centres, centre_weights)
    for a in (owners, weights, centres, scale_weights, scale_centres, centre_weights):
        a.setflags(write=False)
    return out


# ------------------------------------------------------------------------------------------
# Poses
# ------------------------------------------------------------------------------------------
Angles = tuple[float, float, float]


def _legs(front: tuple[float, float, float], hind: tuple[float, float, float], side: str) -> dict[str, Angles]:
    """Pitch angles (degrees) for one side's shoulder/elbow/wrist and hip/knee/hock."""
    names = ("shoulder", "elbow", "wrist", "hip", "knee", "hock")
    return {f"{n}_{side}": (a, 0.0, 0.0) for n, a in zip(names, front + hind)}


_POSES: dict[str, dict[str, Angles]] = {
    "standing": {},
    "walking": {
        **_legs((18.0, -8.0, 10.0), (-14.0, 16.0, -10.0), "l"),
        **_legs((-14.0, 20.0, -6.0), (14.0, -6.0, 8.0), "r"),
        "neck": (-4.0, 0.0, 0.0),
        "tail_base": (-6.0, 5.0, 0.0),
    },
    "galloping": {
        **_legs((24.0, -8.0, 16.0), (-22.0, 14.0, -10.0), "l"),
        **_legs((20.0, -10.0, 14.0), (-18.0, 12.0, -8.0), "r"),
        "spine": (4.0, 0.0, 0.0),
        "neck": (-10.0, 0.0, 0.0),
        "head": (8.0, 0.0, 0.0),
        "tail_base": (-12.0, 0.0, 0.0),
        "tail_mid": (-8.0, 0.0, 0.0),
        "ear_l": (-15.0, 0.0, 0.0),
        "ear_r": (-15.0, 0.0, 0.0),
    },
    "sitting": {
        "body": (27.0, 0.0, 0.0),
        **_legs((-18.0, 3.0, -10.0), (4.0, -26.0, 18.0), "l"),
        **_legs((-18.0, 3.0, -10.0), (4.0, -26.0, 18.0), "r"),
        "spine": (5.0, 0.0, 0.0),
        "neck": (-8.0, 0.0, 0.0),
        "head": (6.0, 0.0, 0.0),
        "tail_base": (12.0, 0.0, 0.0),
        "tail_mid": (10.0, 0.0, 0.0),
    },
    "head_turned": {
        "neck": (0.0, 12.0, 0.0),
        "head": (4.0, 16.0, 0.0),
        "ear_l": (0.0, 0.0, 10.0),
        "ear_r": (0.0, 0.0, -10.0),
    },
    "tail_raised": {
        "tail_base": (-26.0, 0.0, 0.0),
        "tail_mid": (-20.0, 0.0, 0.0),
        "ear_l": (10.0, 0.0, 0.0),
        "ear_r": (10.0, 0.0, 0.0),
    },
}
POSES: Mapping[str, Mapping[str, Angles]] = MappingProxyType({k: MappingProxyType(v) for k, v in _POSES.items()})
"""Named poses (read-only): joint -> (pitch, yaw, roll) in degrees, relative to standing.

Pitch > 0 turns the bone's forward direction upward (nose up, a hanging leg swings forward, a
backward-pointing tail goes down); yaw > 0 turns toward the animal's left; roll > 0 lifts its
left side. Joints not listed keep their rest angle. The key ``"body"`` turns the whole animal
rigidly (sitting pitches it nose-up). Every pose is then set on the ground plane z = 0 of the
standing pose by a vertical translation.
"""


def _rotation_vector(angles: Angles) -> NDArray[np.float64]:
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
# Part scaling
# ------------------------------------------------------------------------------------------
def _part_joints(part: str, factor: float) -> dict[str, float]:
    both = lambda base: {f"{base}_l": factor, f"{base}_r": factor}  # noqa: E731
    table: dict[str, dict[str, float]] = {
        "head": {"head": factor},
        "ears": both("ear"),
        "neck": {"neck": factor, "head": 1.0 / factor},
        "tail": {"tail_base": factor},
        "front_legs": both("shoulder"),
        "hind_legs": both("hip"),
        "legs": {**both("shoulder"), **both("hip")},
    }
    return table[part]


PARTS: tuple[str, ...] = ("head", "ears", "neck", "tail", "front_legs", "hind_legs", "legs")
"""Names accepted as keys of ``parts`` in :func:`creature`.

Each part (with everything attached below it) is scaled by its factor about the joint where it
meets the body; ``"neck"`` keeps the head's size and only carries it along.
"""


# ------------------------------------------------------------------------------------------
# Deformation and public API
# ------------------------------------------------------------------------------------------
def _deform(template: _Template, rotations: dict[str, NDArray[np.float64]], scales: dict[str, float]) -> NDArray[np.float64]:
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


def _check_n_vertices(n_vertices: Any) -> int:
    if isinstance(n_vertices, bool) or not isinstance(n_vertices, (int, np.integer)) or not 1_000 <= n_vertices <= 200_000:
        raise ValueError(
            f"n_vertices must be an integer in 1000..200000 (honoured within 10% from 2000 to 50000), got {n_vertices!r}."
        )
    return int(n_vertices)


def _check_species(species: Any) -> str:
    if species not in SPECIES:
        raise ValueError(f"unknown species {species!r}; choose one of {SPECIES}.")
    return str(species)


def _parse_pose(pose: Any) -> dict[str, NDArray[np.float64]]:
    """Rotation vectors of the joints (and of ``"body"``) named in a pose."""
    if isinstance(pose, str):
        if pose not in POSES:
            raise ValueError(f"unknown pose {pose!r}; choose one of {tuple(POSES)} or pass a dict of joint angles.")
        angles: Mapping[str, Any] = POSES[pose]
    elif isinstance(pose, Mapping):
        angles = pose
    else:
        raise ValueError(f"pose must be a pose name or a dict joint -> angles in degrees, got {type(pose).__name__}.")
    rotations = {}
    for joint, value in angles.items():
        if joint not in JOINTS and joint != "body":
            raise ValueError(f"unknown joint {joint!r} in pose; joints are {JOINTS} (and 'body' for the whole animal).")
        a = np.atleast_1d(np.asarray(value, dtype=np.float64))
        if a.shape == (1,):
            a = np.array([a[0], 0.0, 0.0])
        if a.shape != (3,) or not np.all(np.isfinite(a)):
            raise ValueError(
                f"angles of joint {joint!r} must be a finite pitch or a (pitch, yaw, roll) triple in degrees, got {value!r}."
            )
        if np.any(np.abs(a) > 90.0):
            raise ValueError(f"angles of joint {joint!r} must lie within +-90 degrees, got {a.tolist()}.")
        if np.any(a != 0.0):
            rotations[joint] = _rotation_vector(tuple(a))
    return rotations


def _parse_parts(parts: Any) -> dict[str, float]:
    if parts is None:
        return {}
    if not isinstance(parts, Mapping):
        raise ValueError(f"parts must be a dict part -> scale factor (e.g. {{'head': 1.6}}), got {type(parts).__name__}.")
    scales: dict[str, float] = {}
    for part, factor in parts.items():
        if part not in PARTS:
            raise ValueError(f"unknown part {part!r}; parts are {PARTS}.")
        if isinstance(factor, bool) or not np.isscalar(factor) or not np.isfinite(factor) or not 0.25 <= factor <= 4.0:
            raise ValueError(f"scale factor of part {part!r} must be a number in 0.25..4, got {factor!r}.")
        for joint, s in _part_joints(part, float(factor)).items():
            scales[joint] = scales.get(joint, 1.0) * s
    return scales


def creature(
    species: str = "dog",
    pose: str | Mapping[str, float | tuple[float, float, float]] = "standing",
    parts: Mapping[str, float] | None = None,
    n_vertices: int = 10_000,
) -> Mesh:
    """A four-legged animal as a closed, genus-0 triangle mesh, in a pose, with scaled parts.

    All meshes of one ``(species, n_vertices)`` share the faces of a standing template, so
    vertex ``i`` is the same point of the body in every pose and scaling.

    Parameters
    ----------
    species : {"dog", "horse"}
        Body proportions.
    pose : str or dict, default "standing"
        A name from :data:`POSES`, or a dict ``joint -> angles`` with joint names from
        :data:`JOINTS` (or ``"body"``, a rigid turn of the whole animal) and angles in degrees
        relative to the standing pose: a pitch, or a ``(pitch, yaw, roll)`` triple
        (conventions in :data:`POSES`), each within +-90. The named poses are tested to be
        nearly isometric and free of self-intersections; large custom angles stretch the
        joints (about ``r theta / L``, see the module notes) and can make parts collide.
    parts : dict, optional
        ``part -> factor`` with part names from :data:`PARTS`, e.g. ``{"head": 1.6}``. Each part
        is scaled about its joint, blending smoothly into the rest of the body.
    n_vertices : int, default 10000
        Target size, honoured within 10% from 2,000 to 50,000 vertices.

    Returns
    -------
    Mesh
        Closed, edge-manifold, outward oriented, one component, Euler characteristic 2. The
        standing dog is about 1.7 units long (the horse about 1.9), faces +x, has its left side
        at y > 0 and stands on the plane z = 0.

    Raises
    ------
    ValueError
        For an unknown species, pose, joint or part, or out-of-range numbers.

    Examples
    --------
    >>> dog = creature("dog", "sitting", n_vertices=3000)
    >>> dog.euler_characteristic, dog.n_components, abs(dog.n_vertices - 3000) < 300
    (2, 1, True)
    >>> big_head = creature("dog", parts={"head": 1.5}, n_vertices=3000)
    >>> bool((big_head.faces == dog.faces).all())
    True
    """
    species = _check_species(species)
    n_vertices = _check_n_vertices(n_vertices)
    rotations = _parse_pose(pose)
    scales = _parse_parts(parts)
    template = _template(species, n_vertices)
    if not rotations and not scales:
        return template.mesh
    return template.mesh.with_vertices(_deform(template, rotations, scales))


def creature_poses(
    species: str = "dog", n_vertices: int = 10_000, parts: Mapping[str, float] | None = None
) -> dict[str, Mesh]:
    """Every named pose of :data:`POSES` as meshes sharing one triangulation.

    Parameters
    ----------
    species, n_vertices, parts
        As in :func:`creature`; ``parts`` scales the same parts in every pose.

    Returns
    -------
    dict of str to Mesh
        Pose name -> mesh, in the order of :data:`POSES` (``"standing"`` first).

    Examples
    --------
    >>> poses = creature_poses("dog", n_vertices=3000)
    >>> sorted(poses)[:3]
    ['galloping', 'head_turned', 'sitting']
    >>> all((m.faces == poses["standing"].faces).all() for m in poses.values())
    True
    """
    return {name: creature(species, name, parts, n_vertices) for name in POSES}


def creature_parts(species: str = "dog", n_vertices: int = 10_000) -> dict[str, NDArray[np.bool_]]:
    """Vertex masks of the body parts of the template (same vertex order as :func:`creature`).

    Keys: ``"torso", "neck", "head"`` (with snout and ears), ``"tail", "front_legs", "hind_legs"``.
    The masks partition the vertices; each vertex belongs to the primitive nearest to it.

    Examples
    --------
    >>> masks = creature_parts("dog", n_vertices=3000)
    >>> int(sum(m.sum() for m in masks.values())) == creature("dog", n_vertices=3000).n_vertices
    True
    """
    species = _check_species(species)
    template = _template(species, _check_n_vertices(n_vertices))
    groups = {
        "torso": ("pelvis", "spine"),
        "neck": ("neck",),
        "head": ("head", "ear_l", "ear_r"),
        "tail": ("tail_base", "tail_mid"),
        "front_legs": tuple(f"{j}_{s}" for j in ("shoulder", "elbow", "wrist") for s in "lr"),
        "hind_legs": tuple(f"{j}_{s}" for j in ("hip", "knee", "hock") for s in "lr"),
    }
    out = {}
    for name, joints in groups.items():
        mask = np.isin(template.owners, [_JOINT_ORDER.index(j) for j in joints])
        mask.setflags(write=False)
        out[name] = mask
    return out


def pose_distortion(rest: Mesh, posed: Mesh, n_samples: int = 50) -> dict[str, float]:
    """How far ``posed`` is from an isometry of ``rest`` (two meshes with the same faces).

    Returns the median and 99th percentile of the relative edge-length change, and the mean
    relative change of the geodesic distances among ``n_samples`` farthest-point samples of
    ``rest`` (shortest paths on the edge graph, :func:`scipy.sparse.csgraph.dijkstra`).

    Examples
    --------
    >>> poses = creature_poses("dog", n_vertices=3000)
    >>> d = pose_distortion(poses["standing"], poses["walking"])
    >>> d["edge_median"] < 0.02 and d["edge_p99"] < 0.10 and d["geodesic_mean"] < 0.03
    True
    """
    import scipy.sparse as sp
    from scipy.sparse.csgraph import dijkstra

    if rest.n_vertices != posed.n_vertices or not np.array_equal(rest.faces, posed.faces):
        raise ValueError("rest and posed must share one triangulation (same faces); pass two poses of one creature.")
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) or not 2 <= n_samples <= rest.n_vertices:
        raise ValueError(f"n_samples must be an integer in 2..{rest.n_vertices}, got {n_samples!r}.")
    e, n = rest.edges, rest.n_vertices

    def lengths(m: Mesh) -> NDArray[np.float64]:
        return np.linalg.norm(m.vertices[e[:, 0]] - m.vertices[e[:, 1]], axis=1)

    def graph(w: NDArray[np.float64]) -> sp.csr_matrix:
        return sp.coo_matrix((w, (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()

    l0, l1 = lengths(rest), lengths(posed)
    g0 = graph(l0)
    d = dijkstra(g0, directed=False, indices=0)
    samples = [int(np.argmax(d))]
    d = dijkstra(g0, directed=False, indices=samples[0])
    for _ in range(n_samples - 1):
        samples.append(int(np.argmax(d)))
        d = np.minimum(d, dijkstra(g0, directed=False, indices=samples[-1]))
    d0 = dijkstra(g0, directed=False, indices=samples)[:, samples]
    d1 = dijkstra(graph(l1), directed=False, indices=samples)[:, samples]
    iu = np.triu_indices(n_samples, 1)
    rel = np.abs(l1 / l0 - 1.0)
    return {
        "edge_median": float(np.median(rel)),
        "edge_p99": float(np.percentile(rel, 99)),
        "geodesic_mean": float(np.mean(np.abs(d1[iu] / d0[iu] - 1.0))),
    }


def vertex_strain(rest: Mesh, posed: Mesh) -> NDArray[np.float64]:
    """Per vertex, the largest relative length change ``|l1 / l0 - 1|`` of the edges at it.

    ``rest`` and ``posed`` must share one triangulation (two poses of one creature). Zero for a
    rigid motion; a local picture of where a pose departs from an isometry
    (:func:`pose_distortion` gives the global statistics).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.icosphere(1)
    >>> float(vertex_strain(m, m.with_vertices(2 * m.vertices)).max().round(12))   # scaling by 2: +100%
    1.0
    """
    if not isinstance(rest, Mesh) or not isinstance(posed, Mesh):
        raise ValueError("rest and posed must be lbo_notebooks.Mesh objects.")
    if rest.n_vertices != posed.n_vertices or not np.array_equal(rest.faces, posed.faces):
        raise ValueError("rest and posed must share one triangulation (same faces); pass two poses of one creature.")
    e = rest.edges
    l0 = np.linalg.norm(rest.vertices[e[:, 0]] - rest.vertices[e[:, 1]], axis=1)
    l1 = np.linalg.norm(posed.vertices[e[:, 0]] - posed.vertices[e[:, 1]], axis=1)
    rel = np.abs(l1 / l0 - 1.0)
    out = np.zeros(rest.n_vertices)
    np.maximum.at(out, e[:, 0], rel)
    np.maximum.at(out, e[:, 1], rel)
    return out


def joint_bands(species: str = "dog", n_vertices: int = 10_000) -> NDArray[np.bool_]:
    """Vertex mask of the joint bands: where some joint weight ``phi_j`` is strictly between 0 and 1.

    Outside the bands every vertex moves rigidly with one bone in every pose; only inside them
    can a pose stretch the surface. Same vertex order as :func:`creature`.

    Examples
    --------
    >>> bands = joint_bands("dog", n_vertices=3000)
    >>> bool(0.05 < bands.mean() < 0.95)
    True
    """
    template = _template(_check_species(species), _check_n_vertices(n_vertices))
    w = template.weights
    mask = np.any((w > 0.0) & (w < 1.0), axis=0)
    mask.setflags(write=False)
    return mask
