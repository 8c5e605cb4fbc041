"""Figures: interactive plotly 3D views of meshes and functions on them, a static matplotlib
fallback, sliders that drive a figure, and the few figures made for one lesson.

For any mesh and any function on it: :mod:`~lbo_notebooks.plotting.display` (what is shown:
decimation, colour range, labels), :mod:`~lbo_notebooks.plotting.scene` (the camera),
:mod:`~lbo_notebooks.plotting.meshes` (plotly and matplotlib figures) and
:mod:`~lbo_notebooks.plotting.sliders`; for one lesson each: :mod:`~lbo_notebooks.plotting.lessons`
(the min–max sphere, the MDS benchmark plot, the reconstruction sliders). Everything public is
importable from ``lbo_notebooks.plotting``;
plotly, ipywidgets and open3d are imported inside the functions, so importing it is cheap.
"""

from __future__ import annotations

from .display import DEFAULT_MAX_FACES, display_mesh, tidy_label
from .lessons import (
    PlaneSlider,
    plane_slider,
    plot_mds_scaling,
    rayleigh_sphere_figure,
    reconstruction_sliders,
)
from .meshes import plot_mesh, plot_mesh_static, plot_meshes
from .sliders import MeshSlider, mesh_slider

__all__ = [
    "plot_mesh", "plot_meshes", "plot_mesh_static", "mesh_slider", "MeshSlider", "display_mesh", "tidy_label",
    "DEFAULT_MAX_FACES", "rayleigh_sphere_figure", "PlaneSlider", "plane_slider", "plot_mds_scaling",
    "reconstruction_sliders",
]
