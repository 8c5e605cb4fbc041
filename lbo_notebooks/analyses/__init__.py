"""What the course computes from a spectrum or a mesh: the optimality theorem and min–max, competitor
bases, geodesics and MDS, regularized PCA, descriptors, functional maps and matching, and what a
computation costs.

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_optimality": (
        "representation_error", "error_bound", "dirichlet_energy", "kernel_basis", "worst_case_ratio",
        "witness_function",
    ),
    "_minmax": (
        "rayleigh_quotient", "min_rayleigh_quotient", "ConstrainedRayleigh", "random_subspace",
        "optimal_subspace", "complement_ratio",
    ),
    "_competitor_bases": (
        "lbo_basis", "random_smooth_basis", "random_smooth_functions", "sample_functions", "pca_basis",
        "umbrella_basis", "identity_mass_basis", "polynomial_basis", "metric_basis", "competitor_bases",
        "Metric",
    ),
    "_geodesics": (
        "GeodesicSolver", "geodesic_distances", "farthest_point_sampling", "distance_matrix_bytes",
    ),
    "_heat_method": ("HeatMethod",),
    "_mds": ("classical_mds", "landmark_mds", "spectral_mds", "SMDS_DEFAULTS", "SMDS_EIGEN_TOL"),
    "_fast_classical_scaling": ("fast_classical_scaling", "FCS_DEFAULTS"),
    "_embedding_error": ("gram_error", "procrustes_error"),
    "_distortion": ("pose_distortion", "vertex_strain"),
    "_shape_distribution": ("shape_distribution", "shape_distribution_distances"),
    "_rpca": ("RegularizedPCA", "RPCAResult", "regularized_pca", "mu_from_beta", "beta_from_mu"),
    "_descriptors": ("hks", "wks", "gps", "hks_times", "wks_energies"),
    "_functional_maps": ("map_from_points", "points_from_map", "estimate_map", "zoomout"),
    "_matching": ("match", "matching_error", "error_curve"),
    "_cost": ("growth_exponent", "measure_cost", "least_cost", "recorded_benchmark"),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
