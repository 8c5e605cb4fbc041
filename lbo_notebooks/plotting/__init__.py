"""Figures: interactive plotly 3D views of meshes and functions on them, a static matplotlib
fallback, sliders that drive a figure, and the few figures made for one lesson.

Two modules: :mod:`~lbo_notebooks.plotting.meshes` (any mesh, any function on it) and
:mod:`~lbo_notebooks.plotting.lessons` (the min–max sphere, the MDS benchmark plot, the
reconstruction sliders). Everything public is importable from ``lbo_notebooks.plotting``;
plotly, ipywidgets and open3d are imported inside the functions, so importing it is cheap.
"""

from __future__ import annotations

from .lessons import PlaneSlider, plane_slider, plot_mds_scaling, rayleigh_sphere_figure, reconstruction_sliders
from .meshes import (
    DEFAULT_MAX_FACES,
    MeshSlider,
    display_mesh,
    mesh_slider,
    plot_mesh,
    plot_mesh_static,
    plot_meshes,
    tidy_label,
)

__all__ = [
    "plot_mesh", "plot_meshes", "plot_mesh_static", "mesh_slider", "MeshSlider", "display_mesh", "tidy_label",
    "DEFAULT_MAX_FACES", "rayleigh_sphere_figure", "PlaneSlider", "plane_slider", "plot_mds_scaling",
    "reconstruction_sliders",
]
