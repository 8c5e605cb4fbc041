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

from typing import Any, Mapping

import numpy as np
from numpy.typing import NDArray

from ..._support.validation import Integer, Options, Satisfies, validated
from ...geometry._mesh import Mesh
from .rig import JOINT_ORDER, deform, rotation_vector, template_for
from .tables import JOINTS, PARTS, POSES, SPECIES, part_joints

__all__ = [
    "creature", "creature_poses", "creature_parts", "joint_bands",
    "SPECIES", "POSES", "JOINTS", "PARTS",
]


_SPECIES = Options(*SPECIES, message=lambda name, value: f"unknown species {value!r}; choose one of {SPECIES}.")
_N_VERTICES = Integer(1_000, 200_000, what="an integer in 1000..200000 (honoured within 10% from 2000 to 50000)")


def _pose_message(name: str, value: Any) -> str:
    if isinstance(value, str):
        return f"unknown pose {value!r}; choose one of {tuple(POSES)} or pass a dict of joint angles."
    return f"{name} must be a pose name or a dict joint -> angles in degrees, got {type(value).__name__}."


# A pose name or a dict of joint angles; the angles of each joint are checked in _parse_pose.
_POSE = Satisfies(lambda pose: isinstance(pose, Mapping) or (isinstance(pose, str) and pose in POSES),
                  message=_pose_message)
# None or a dict part -> scale factor; the parts and factors are checked in _parse_parts.
_PARTS = Satisfies(lambda parts: isinstance(parts, Mapping), none=True,
                   message="{name} must be a dict part -> scale factor (e.g. {{'head': 1.6}}), got {type}.")


def _parse_pose(pose: Any) -> dict[str, NDArray[np.float64]]:
    """Rotation vectors of the joints (and of ``"body"``) named in a pose (a name or a dict, see ``_POSE``)."""
    angles: Mapping[str, Any] = POSES[pose] if isinstance(pose, str) else pose
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
            rotations[joint] = rotation_vector(tuple(a))
    return rotations


def _parse_parts(parts: Any) -> dict[str, float]:
    """Scale factors of the joints for the parts named in ``parts`` (None or a dict, see ``_PARTS``)."""
    if parts is None:
        return {}
    scales: dict[str, float] = {}
    for part, factor in parts.items():
        if part not in PARTS:
            raise ValueError(f"unknown part {part!r}; parts are {PARTS}.")
        if isinstance(factor, bool) or not np.isscalar(factor) or not np.isfinite(factor) or not 0.25 <= factor <= 4.0:
            raise ValueError(f"scale factor of part {part!r} must be a number in 0.25..4, got {factor!r}.")
        for joint, s in part_joints(part, float(factor)).items():
            scales[joint] = scales.get(joint, 1.0) * s
    return scales


@validated(species=_SPECIES, n_vertices=_N_VERTICES, pose=_POSE, parts=_PARTS)
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
    rotations = _parse_pose(pose)
    scales = _parse_parts(parts)
    template = template_for(species, n_vertices)
    if not rotations and not scales:
        return template.mesh
    return template.mesh.with_vertices(deform(template, rotations, scales))


@validated(species=_SPECIES, n_vertices=_N_VERTICES, parts=_PARTS)
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


@validated(species=_SPECIES, n_vertices=_N_VERTICES)
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
    template = template_for(species, n_vertices)
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
        mask = np.isin(template.owners, [JOINT_ORDER.index(j) for j in joints])
        mask.setflags(write=False)
        out[name] = mask
    return out


@validated(species=_SPECIES, n_vertices=_N_VERTICES)
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
    template = template_for(species, n_vertices)
    w = template.weights
    mask = np.any((w > 0.0) & (w < 1.0), axis=0)
    mask.setflags(write=False)
    return mask
