"""The creatures' data: skeleton, body plans of the species, named poses and scalable parts.

Pure tables and the small functions that expand them (left parts mirrored to the right); no
geometry is computed here.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Mapping

SPECIES: tuple[str, ...] = ("dog", "horse")


# ------------------------------------------------------------------------------------------
# Skeleton and body plan
# ------------------------------------------------------------------------------------------
# Joint tree shared by all species: name -> parent ("" for the root). Left ("_l") joints have
# y > 0; right ("_r") joints mirror them. The root ("pelvis") is not a rotating joint.
JOINT_PARENTS: dict[str, str] = {
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
JOINTS: tuple[str, ...] = tuple(j for j in JOINT_PARENTS if j != "pelvis")
"""Names of the joints a pose may rotate (the dict form of ``pose`` in :func:`creature`)."""

@dataclass(frozen=True)
class Primitive:
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
class Species:
    primitives: tuple[Primitive, ...]
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
) -> Species:
    """Assemble the primitives; left-side entries (ears, legs) are mirrored to the right."""
    prims: list[Primitive] = []
    index: dict[str, int] = {}
    for spec in body:
        spec = dict(spec)
        key = spec.pop("key")
        parent = spec.pop("parent", None)
        index[key] = len(prims)
        prims.append(Primitive(parent=-1 if parent is None else index[parent], **spec))
    for side in ("_l", "_r"):
        for spec in [dict(ear)] + [dict(s) for s in leg]:
            spec = dict(spec)
            key = spec.pop("key") + side
            parent = spec.pop("parent")
            parent = parent + side if parent + side in index else parent
            if spec["owner"] + side in JOINT_PARENTS:
                spec["owner"] = spec["owner"] + side
            if side == "_r":
                for f in ("a", "b"):
                    if f in spec:
                        spec[f] = _mirror(spec[f])
                if "tilt" in spec:
                    t = spec["tilt"]
                    spec["tilt"] = (-t[0], t[1], -t[2])
            index[key] = len(prims)
            prims.append(Primitive(parent=index[parent], **spec))
    full_bands = {}
    for name in JOINTS:
        base = name[:-2] if name.endswith(("_l", "_r")) else name
        full_bands[name] = bands[base]
    return Species(tuple(prims), full_bands, scale_band, spacing)


def _dog() -> Species:
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


def _horse() -> Species:
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
def species_plan(name: str) -> Species:
    if name == "dog":
        return _dog()
    if name == "horse":
        return _horse()
    raise ValueError(f"unknown species {name!r}; choose one of {SPECIES}.")


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


# ------------------------------------------------------------------------------------------
# Part scaling
# ------------------------------------------------------------------------------------------
def part_joints(part: str, factor: float) -> dict[str, float]:
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

