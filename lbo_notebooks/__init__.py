"""lbo_notebooks: spectral shape analysis with the Laplace–Beltrami operator.

The helper library behind the notebooks on *On the optimality of shape and data representation
in the spectral domain* (Aflalo, Brezis, Kimmel). Everything public is importable from the top
level; modules are loaded on first use so that ``import lbo_notebooks`` stays fast and never
pulls in open3d or plotly.

Examples
--------
>>> import lbo_notebooks as lbo
>>> sphere = lbo.shapes.icosphere(3)
>>> spectrum = lbo.eigenbasis(sphere, 9)
>>> spectrum.values[1:4].round(1).tolist()
[2.0, 2.0, 2.0]
"""

from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

# Public names by module: one line per module, one concept per module.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "mesh": ("Mesh", "MeshError"),
    "io": ("load_mesh", "save_mesh", "load_points"),
    "repair": ("clean_mesh",),
    "pointcloud": ("PointCloud",),
    "operators": ("stiffness_matrix", "mass_matrix"),
    "laplacians": ("laplace_beltrami",),
    "spectrum": ("Spectrum", "eigenbasis"),
    "inner_product": ("a_orthonormalize", "fix_signs", "principal_angles", "reconstruction_error"),
    "solvers": ("slice_eigsh", "count_below"),
    "plotting": ("plot_mesh",),
    "creatures": ("creature", "creature_poses", "creature_parts", "joint_bands"),
    "distortion": ("pose_distortion", "vertex_strain"),
    "optimality": ("representation_error", "error_bound", "worst_case_ratio", "dirichlet_energy", "witness_function"),
    "curvature": ("gaussian_curvature", "angle_defects", "metric_curvature", "conformal_factor", "metric_mass_matrix"),
    "geodesics": ("geodesic_distances", "farthest_point_sampling", "GeodesicSolver"),
    "mds": ("classical_mds", "landmark_mds", "spectral_mds"),
    "fast_scaling": ("fast_classical_scaling",),
    "embedding_error": ("gram_error", "procrustes_error"),
    "rpca": ("regularized_pca", "RegularizedPCA", "mu_from_beta"),
    "descriptors": ("hks", "wks", "gps"),
    "functional_maps": ("estimate_map", "map_from_points", "points_from_map", "zoomout"),
    "matching": ("match", "matching_error", "error_curve"),
}
_SUBMODULES = frozenset(_EXPORTS) | {"shapes", "creatures", "bases", "minmax", "robust", "formats", "cost", "shape_distribution",
                                     "teaching", "exercises"}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}

__all__ = sorted(_WHERE) + sorted(_SUBMODULES)


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'lbo_notebooks' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
