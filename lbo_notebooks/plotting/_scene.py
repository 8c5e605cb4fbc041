"""The camera and the plotly scene: which way is up, how far the camera stands so the whole shape
fits, and the plotly ``Mesh3d`` trace of a shape.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Satisfies
from ._display import POINT_SIZE, Display

__all__ = ["NOMINAL_WIDTH", "MARGIN", "ELEVATION", "AZIMUTH", "UP", "auto_up", "View", "scene_layout", "wrap",
           "trace"]


# --- the camera ------------------------------------------------------------------------------

_AXES = {"x": 0, "y": 1, "z": 2}
_FOV_Y = np.pi / 4             # plotly's perspective camera: 45 degree vertical field of view
NOMINAL_WIDTH = 800           # px; the figure is at least this wide in JupyterLab and on the site
MARGIN = 0.06                 # empty border around the bounding sphere, as a fraction of its radius
ELEVATION, AZIMUTH = np.radians(18.0), np.radians(28.0)


_RESTING = 0.02                # a shape whose lowest point is this close to a coordinate plane stands on it
_SAME_EXTENT = 1e-6            # relative difference below which two extents count as equal


def auto_up(vertices: NDArray[np.float64]) -> NDArray[np.float64]:
    """The axis drawn upwards when ``up="auto"``: +z or +y, the two conventions of mesh files.

    Files are authored axis-aligned and upright, either z-up (CAD, scanners, our creatures) or
    y-up (OBJ, glTF, most graphics tools); x is not used for up by either. Which of the two:

    1. a shape that stands on the coordinate plane z = 0 but not on y = 0 is z-up, and
       conversely (the built-in creatures stand on z = 0 in every pose; many scans stand on
       their floor);
    2. otherwise the taller of the two extents is up (an animal, a person, a bust or a bunny is
       taller than it is deep or wide, whatever its pose; a flat shape is then seen face on);
       equal extents (a sphere) give z.

    Principal axes or the axis of middle extent are not robust: a sitting dog is taller than it is
    long, and the mass of a head or of legs tilts principal axes.
    """
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    extent = hi - lo
    size = float(extent.max()) or 1.0
    stands = [bool(abs(lo[a]) <= _RESTING * size < extent[a]) for a in (1, 2)]
    if stands[0] != stands[1]:
        return np.eye(3)[1 if stands[0] else 2]
    y, z = extent[1], extent[2]
    return np.eye(3)[1 if y > z * (1 + _SAME_EXTENT) else 2]


def _is_up(up: str | ArrayLike) -> bool:
    if isinstance(up, str):
        key = up.strip().lower()
        return key == "auto" or key.lstrip("+-") in _AXES
    u = np.asarray(up, dtype=np.float64)
    return bool(u.shape == (3,) and np.all(np.isfinite(u)) and np.linalg.norm(u) != 0)


def _up_message(name: str, up: object) -> str:
    if isinstance(up, str):
        return f'{name}={up!r}: use "auto", "x", "y", "z" (optionally with a sign, e.g. "-y") or a 3-vector.'
    return f"{name} must be a finite non-zero 3-vector or one of 'auto', 'x', 'y', 'z'; got {up!r}."


#: The rule for ``up`` in every figure: "auto", an axis with an optional sign, or a finite non-zero 3-vector.
UP = Satisfies(_is_up, message=_up_message)


def _up_vector(up: str | ArrayLike, vertices: NDArray[np.float64]) -> NDArray[np.float64]:
    """The unit vector drawn upwards for an ``up`` that passed :data:`UP`."""
    if isinstance(up, str):
        key = up.strip().lower()
        if key == "auto":
            return auto_up(vertices)
        sign = -1.0 if key.startswith("-") else 1.0
        return sign * np.eye(3)[_AXES[key.lstrip("+-")]]
    u = np.asarray(up, dtype=np.float64)
    return u / np.linalg.norm(u)


class View:
    """Where the camera looks from: a unit ``up``, a unit ``toward`` (centre to eye), and the
    bounding sphere (``centre``, ``radius``) of the vertices."""

    def __init__(self, vertices: NDArray[np.float64], up: str | ArrayLike) -> None:
        v = np.asarray(vertices, dtype=np.float64)
        self.up = _up_vector(up, v)
        lo, hi = v.min(axis=0), v.max(axis=0)
        self.centre = (lo + hi) / 2
        self.radius = float(np.linalg.norm(v - self.centre, axis=1).max()) or 1.0
        # Look along the thinnest horizontal direction (a side view of an animal), from slightly
        # above and to one side so that depth reads.
        plane = np.eye(3) - np.outer(self.up, self.up)
        d = (v - self.centre) @ plane
        if np.count_nonzero(np.abs(self.up) > 1e-12) == 1:   # an axis: compare the other two axes
            others = [a for a in range(3) if abs(self.up[a]) <= 1e-12]
            extent = np.ptp(d[:, others], axis=0)
            thin = np.eye(3)[others[int(np.argmin(extent))]]
        else:                                                  # a general vector: principal axes in the plane
            w, vecs = np.linalg.eigh(d.T @ d)                  # one eigenvector is up itself (w = 0)
            in_plane = [i for i in range(3) if i != int(np.argmax(np.abs(vecs.T @ self.up)))]
            thin = vecs[:, in_plane[0]]                        # eigh sorts ascending
        # The eye is on the side of -thin (thin's largest component made positive): for a z-up
        # animal that is x to the right, as in a textbook front view.
        self.front = -thin * np.sign(thin[np.argmax(np.abs(thin))])       # horizontal, centre to eye
        self.right = np.cross(self.up, self.front)                           # screen right
        horizontal = np.cos(AZIMUTH) * self.front + np.sin(AZIMUTH) * self.right
        self.toward = np.cos(ELEVATION) * horizontal + np.sin(ELEVATION) * self.up
        # The light: from above, a little to the right and behind the shape, in the view's frame,
        # so that a y-up and a z-up file are shaded alike.
        self.light = 100 * self.right - 200 * self.front + 300 * self.up

    def ranges(self, radius: float) -> list[list[float]]:
        """Axis ranges: a cube of half-side ``radius`` around the centre (equal aspect ratio)."""
        return [[float(c - radius), float(c + radius)] for c in self.centre]

    def camera(self, radius: float, width_px: float, height_px: float) -> dict[str, Any]:
        """A plotly camera that shows the whole bounding sphere in a ``width_px`` x ``height_px`` scene.

        plotly maps the axis ranges to the cube [-0.5, 0.5]^3 and draws with a perspective
        camera of vertical field of view 45 degrees; the sphere of normalised radius
        ``rho`` is inside the view when ``rho / distance <= sin(half field of view)`` in both
        directions.
        """
        rho = 0.5 * self.radius / radius
        half_v = _FOV_Y / 2
        half_h = np.arctan(np.tan(half_v) * width_px / height_px)
        distance = rho * (1 + MARGIN) / np.sin(min(half_v, half_h))
        eye = distance * self.toward
        return dict(up=dict(zip("xyz", map(float, self.up))), eye=dict(zip("xyz", map(float, eye))),
                    center=dict(x=0.0, y=0.0, z=0.0), projection=dict(type="perspective"))


def scene_layout(view: View, radius: float, domain: dict[str, list[float]] | None, width_px: float,
           height_px: float) -> dict[str, Any]:
    axes = [dict(visible=False, range=r, autorange=False) for r in view.ranges(radius)]
    scene: dict[str, Any] = dict(xaxis=axes[0], yaxis=axes[1], zaxis=axes[2], aspectmode="manual",
                                 aspectratio=dict(x=1, y=1, z=1), camera=view.camera(radius, width_px, height_px))
    if domain is not None:
        scene["domain"] = domain
    return scene


def wrap(text: str, width_chars: int) -> str:
    """Break ``text`` at spaces into lines of at most ``width_chars`` characters (plotly ``<br>``)."""
    lines: list[str] = []
    for word in text.split():
        if lines and len(lines[-1]) + 1 + len(word) <= width_chars:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return "<br>".join(lines)


def trace(d: Display, s: NDArray[np.float64] | None, *, colorscale: str, cmin: float | None, cmax: float | None,
           showscale: bool, view: View, name: str | None = None, scene: str = "scene",
           colorbar: dict[str, Any] | None = None) -> Any:
    import plotly.graph_objects as go

    v, f = d.vertices, d.faces
    if f is None:  # a point cloud: markers coloured by the function
        marker: dict[str, Any] = dict(size=POINT_SIZE, color="#5b7a99")
        if s is not None:
            marker.update(color=d.values(s), colorscale=colorscale, cmin=cmin, cmax=cmax, showscale=showscale)
            if colorbar is not None:
                marker["colorbar"] = colorbar
        return go.Scatter3d(x=v[:, 0], y=v[:, 1], z=v[:, 2], mode="markers", marker=marker, name=name, scene=scene,
                            hoverinfo="skip")
    kwargs: dict[str, Any] = dict(
        x=v[:, 0], y=v[:, 1], z=v[:, 2], i=f[:, 0], j=f[:, 1], k=f[:, 2], name=name, scene=scene,
        flatshading=False, lighting=dict(ambient=0.45, diffuse=0.8, specular=0.15, roughness=0.6),
        lightposition=dict(zip("xyz", map(float, view.light))), hoverinfo="skip",
    )
    if s is None:
        kwargs["color"] = "#b9c7d6"
    else:
        kwargs.update(intensity=d.values(s), intensitymode="vertex", colorscale=colorscale, cmin=cmin, cmax=cmax,
                      showscale=showscale)
        if colorbar is not None:
            kwargs["colorbar"] = colorbar
    return go.Mesh3d(**kwargs)
