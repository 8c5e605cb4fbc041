"""Figures: interactive plotly 3D views of meshes and functions on them, a static matplotlib
fallback, sliders that drive a figure, and the few figures made for one lesson (the min–max
sphere, the MDS benchmark plot, the reconstruction sliders).

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use, and plotly, ipywidgets and open3d are imported
inside the functions, so importing the package is cheap.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_meshes": ("plot_mesh", "plot_meshes", "plot_mesh_static"),
    "_sliders": ("mesh_slider", "MeshSlider"),
    "_display": ("display_mesh", "tidy_label", "DEFAULT_MAX_FACES"),
    "_lessons": (
        "rayleigh_sphere_figure", "PlaneSlider", "plane_slider", "plot_mds_scaling",
        "reconstruction_sliders",
    ),
    "_rayleigh_plane": ("plane_normal",),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
