"""Shapes made in code, no download: procedural surfaces and four-legged creatures in correspondence.

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_procedural": (
        "icosphere", "ellipsoid", "torus", "jittered_torus", "rectangle", "disk", "bumpy_sphere",
        "scan_like",
    ),
    "_creatures": (
        "creature", "creature_poses", "creature_parts", "joint_bands", "SPECIES", "POSES", "JOINTS",
        "PARTS",
    ),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
