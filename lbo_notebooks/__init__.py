"""lbo_notebooks: spectral shape analysis with the Laplace–Beltrami operator.

The helper library behind the notebooks on *On the optimality of shape and data representation
in the spectral domain* (Aflalo, Brezis, Kimmel). The subpackages follow the layers, bottom to
top: ``geometry`` (meshes, point clouds, files), ``operators`` (``W`` and ``A``), ``spectral``
(the eigenbasis), ``analyses`` (what the paper computes with it), ``shapes`` and ``plotting``,
and ``exercises`` (the course). The names a reader meets first are importable from the top
level too; subpackages are loaded on first use so that ``import lbo_notebooks`` stays fast and
never pulls in open3d or plotly.

Examples
--------
>>> import lbo_notebooks as lbo
>>> sphere = lbo.shapes.icosphere(3)
>>> spectrum = lbo.eigenbasis(sphere, 9)
>>> spectrum.values[1:4].round(1).tolist()
[2.0, 2.0, 2.0]
"""

from __future__ import annotations

from ._support.lazy import front_door

__version__ = "0.1.0"

# Public names by subpackage: the names a reader meets first; each subpackage lists the rest.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "geometry": ("Mesh", "MeshError", "PointCloud", "load_mesh", "save_mesh", "load_points", "clean_mesh"),
    "operators": ("stiffness_matrix", "mass_matrix", "laplace_beltrami", "gaussian_curvature", "angle_defects"),
    "spectral": ("Spectrum", "eigenbasis", "a_orthonormalize", "principal_angles", "reconstruction_error"),
    "analyses": ("representation_error", "error_bound", "worst_case_ratio", "dirichlet_energy",
                 "geodesic_distances", "farthest_point_sampling", "GeodesicSolver",
                 "classical_mds", "landmark_mds", "spectral_mds", "fast_classical_scaling", "gram_error",
                 "procrustes_error", "regularized_pca", "RegularizedPCA", "hks", "wks",
                 "estimate_map", "map_from_points", "points_from_map", "zoomout",
                 "match", "matching_error", "error_curve", "pose_distortion"),
    "shapes": ("creature", "creature_poses", "creature_parts"),
    "plotting": ("plot_mesh",),
}
_SUBMODULES = frozenset({"geometry", "operators", "spectral", "analyses", "shapes", "plotting", "exercises"})
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}

__all__ = sorted(_WHERE) + sorted(_SUBMODULES)
__getattr__, __dir__ = front_door(__name__, _EXPORTS, modules=_SUBMODULES)
