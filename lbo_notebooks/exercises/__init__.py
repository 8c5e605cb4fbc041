"""Self-checks for the notebooks' exercises: feedback on an attempt, never the answer.

Each exercise in the notebooks ends with a call such as ``exercises.check_stiffness(my_stiffness)``.
The check compares the student's answer with the library (or with the exact value), and says one of

- **correct**, sometimes with a remark (e.g. which of two valid mass matrices was built);
- **wrong**, with a hint aimed at the typical mistake: a factor of two, a wrong sign, a transpose,
  the Euclidean inner product where the ``A`` inner product belongs, a missing diagonal, ...;
- **not attempted**, when the answer is still the placeholder the student edition leaves
  (``...``, ``None``, ``NotImplemented``, a function that raises ``NotImplementedError`` or
  returns nothing). This never raises, so the student edition runs top to bottom unanswered.

Messages never contain the reference value. In Jupyter the feedback is shown as one coloured
line (IPython's display machinery; plain text elsewhere), and the check returns a
:class:`Feedback` whose ``correct`` attribute the autograder asserts (the hidden tests of the
notebooks, see docs/exercises.md). :func:`solution` shows the instructor's solution of an
exercise on purpose, read from the instructor edition (``notebooks/``) when it is available.

This module needs neither the grader nor IPython; the checks import the heavier parts of the
library (creatures, spectra) only when an attempt has to be compared with them.

Examples
--------
>>> from lbo_notebooks import exercises
>>> exercises.check_area_factor(..., scale=1.6, show=False).status
'not attempted'
>>> exercises.check_area_factor(1.6, scale=1.6, show=False).status
'wrong'
>>> exercises.check_area_factor(1.6**2, scale=1.6, show=False).correct
True
"""

from .feedback import CORRECT, MIME_TYPE, NOT_ATTEMPTED, WRONG, Feedback, solution
from .basics import check_recap_shapes, check_edge_count, check_area_factor, check_stretch_growth, check_smallest_angles, check_leg_area
from .laplace_beltrami import check_stiffness, check_mass, check_convergence_factor, check_coefficients, check_consistent_mass, check_eigenvalue_scaling, check_zero_eigenvalues, check_recap_lbo, check_eigensolve
from .warm_up import check_edge_energy, check_cycle_multiplicity, check_step_decay, check_recap_graph
from .your_data import check_repair_counts, check_operator_choice, check_cloud_eigenvalue, check_largest_component, check_neighbors_effect, check_cloud_pieces, check_recap_your_data
from .theory import check_projection, check_energy_bound, check_shifted_basis, check_consistent_optimality, check_extra_function, check_worst_ratio, check_recap_optimality, check_stationary_frame, check_recap_ties, check_worst_case
from .minmax_and_metrics import check_plane_minimum, check_plane_range, check_lowest_family, check_dual_value, check_interlacing, check_consistent_minmax, check_recap_min_max, check_gauss_bonnet, check_curvature_scaling, check_metric_scaling, check_best_alpha, check_floor_fraction, check_sphere_alpha, check_consistent_invariance, check_recap_scale_invariant, check_angle_defects
from .canonical_forms import check_classical_memory, check_small_scaling, check_fmm_gap, check_gram_2d, check_landmark_samples, check_recap_canonical_forms, check_mu_range, check_equal_size, check_recap_mds_at_scale, check_classical_mds
from .start_here import check_sphere_eigenvalues, check_mesh_size, check_eigenfunction, check_load_error
from .regularized_pca import check_rpca_limits, check_dirichlet_energies, check_validation_choice, check_mu_scaling, check_rpca_objective, check_recap_rpca, check_rpca_basis
from .toolbox import check_hks, check_functional_map, check_truncation_bound, check_alpha_choice, check_mirror_maps, check_zoomout, check_recap_toolbox, check_zoomout_step



def _reading_plain(check):  # type: ignore[no-untyped-def]
    """``check`` with its answers read as :func:`~lbo_notebooks.exercises.feedback.plain` data first,
    so that no method of an answer's own class (a ``str`` subclass's ``lower``) runs inside it."""
    import functools

    @functools.wraps(check)
    def reading_plain(*args, **kwargs):  # type: ignore[no-untyped-def]
        try:
            args = tuple(_plain(a) for a in args)
            kwargs = {k: _plain(v) for k, v in kwargs.items()}
        except _Stop as stop:
            return _result(check.__name__, stop.status, stop.message, kwargs.get("show", True))
        return check(*args, **kwargs)
    del reading_plain.__wrapped__  # the check's own globals stay out of reach of an answer
    return reading_plain


from .feedback import Stop as _Stop, plain as _plain, result as _result  # noqa: E402

for _name in [n for n in dir() if n.startswith("check_")]:
    globals()[_name] = _reading_plain(globals()[_name])
del _name

__all__ = [
    "Feedback", "CORRECT", "WRONG", "NOT_ATTEMPTED", "MIME_TYPE", "solution", "check_edge_count",
    "check_area_factor", "check_stretch_growth", "check_smallest_angles", "check_leg_area",
    "check_stiffness", "check_mass", "check_convergence_factor", "check_coefficients",
    "check_consistent_mass", "check_eigenvalue_scaling", "check_zero_eigenvalues", "check_recap_shapes",
    "check_recap_lbo", "check_edge_energy", "check_cycle_multiplicity", "check_step_decay",
    "check_recap_graph",
    "check_repair_counts", "check_operator_choice", "check_cloud_eigenvalue",
    "check_largest_component", "check_neighbors_effect", "check_cloud_pieces", "check_recap_your_data",
    "check_projection",
    "check_energy_bound", "check_shifted_basis", "check_consistent_optimality",
    "check_extra_function", "check_worst_ratio", "check_recap_optimality", "check_stationary_frame",
    "check_recap_ties", "check_plane_minimum",
    "check_plane_range", "check_lowest_family", "check_dual_value", "check_interlacing",
    "check_consistent_minmax", "check_recap_min_max", "check_gauss_bonnet", "check_curvature_scaling",
    "check_metric_scaling", "check_best_alpha", "check_floor_fraction", "check_sphere_alpha",
    "check_consistent_invariance", "check_recap_scale_invariant", "check_sphere_eigenvalues",
    "check_mesh_size",
    "check_eigenfunction", "check_load_error", "check_rpca_limits", "check_dirichlet_energies",
    "check_validation_choice", "check_mu_scaling", "check_rpca_objective", "check_recap_rpca",
    "check_hks", "check_functional_map", "check_truncation_bound", "check_alpha_choice",
    "check_mirror_maps", "check_zoomout", "check_recap_toolbox", "check_classical_memory",
    "check_small_scaling", "check_fmm_gap", "check_gram_2d", "check_landmark_samples",
    "check_recap_canonical_forms",
    "check_mu_range", "check_equal_size", "check_recap_mds_at_scale", "check_eigensolve", "check_worst_case",
    "check_angle_defects", "check_classical_mds", "check_rpca_basis", "check_zoomout_step",
]
