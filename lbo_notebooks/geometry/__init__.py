"""Triangle meshes and point clouds: the value types, files in and out, repair.

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_mesh": ("Mesh", "MeshError"),
    "_pointcloud": ("PointCloud",),
    "_files": ("load_mesh", "save_mesh", "load_points", "MeshRepairWarning"),
    "_repair": ("clean_mesh", "CleanReport"),
    "_formats": ("FORMATS", "POINT_FORMATS"),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
