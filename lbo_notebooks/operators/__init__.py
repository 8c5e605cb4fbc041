"""Laplace–Beltrami operators ``(W, A)``: cotangent, robust (any soup, point clouds), and the
curvature metrics ``|K|^alpha g``.

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_cotangent": ("stiffness_matrix", "mass_matrix", "face_cotangents", "corner_angles", "MASS_KINDS"),
    "_laplace_beltrami": ("laplace_beltrami",),
    "_robust": (
        "robust_operators", "point_cloud_operators", "cotan_defects", "non_manifold_vertices",
        "LaplacianWarning", "LAPLACIANS",
    ),
    "_curvature": (
        "angle_defects", "gaussian_curvature", "metric_curvature", "conformal_factor", "metric_mass_matrix",
        "DEFAULT_FLOOR",
    ),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
