"""Reading and writing mesh and point files (.off, .obj, .ply, .stl; points also .xyz, .pts, .txt).

:func:`load_mesh` returns a validated :class:`~lbo_notebooks.Mesh` whose vertices are exactly
the ones the file lists, in the file's order; :func:`save_mesh` writes one; :func:`load_points`
reads a :class:`~lbo_notebooks.PointCloud`. Repair lives in :mod:`lbo_notebooks.geometry._repair`
(:func:`~lbo_notebooks.geometry.clean_mesh`); ``load_mesh(path, clean=True)`` applies it.

How each format is read and written, and why (STL welding, polygons refused or split with
``clean=True``): see :mod:`lbo_notebooks.geometry._formats`.

Examples
--------
>>> import tempfile, pathlib
>>> from lbo_notebooks import shapes
>>> sphere = shapes.icosphere(2)
>>> path = pathlib.Path(tempfile.mkdtemp()) / "sphere.ply"
>>> _ = save_mesh(sphere, path)
>>> load_mesh(path) == sphere
True
"""


from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Union

import numpy as np
from numpy.typing import NDArray

from .._support.validation import Relation, Satisfies, validated
from .._support.warning import warn
from ._formats import (
    BINARY_FORMATS, FORMATS, POINT_FORMATS, RawMesh, mesh_text, read_point_text, read_raw, write_mesh_binary,
)
from ._mesh import Mesh, MeshError, unique_rows
from ._pointcloud import PointCloud
from ._repair import clean_arrays

__all__ = [
    "load_mesh", "save_mesh", "load_points", "read_mesh_arrays", "MeshRepairWarning",
]

PathLike = Union[str, "os.PathLike[str]"]


class MeshRepairWarning(UserWarning):
    """Issued by :func:`load_mesh` with ``clean=True`` when it changed the mesh; says what."""


def _extension_rule(formats: tuple[str, ...]) -> Satisfies:
    """The rule for a ``path`` argument: its extension (case-insensitive) is one of ``formats``.

    A value that is not a path gets the ``TypeError`` of :func:`os.fspath`, as before the table.
    """
    kind = "mesh" if formats == FORMATS else "point"

    def message(name: str, path: PathLike) -> str:
        p = Path(os.fspath(path))
        return f"unsupported {kind} file extension {p.suffix!r} in {str(p)!r}; supported: {', '.join(formats)}."

    return Satisfies(lambda path: Path(os.fspath(path)).suffix.lower() in formats, message=message)


_MESH_PATH, _POINT_PATH = _extension_rule(FORMATS), _extension_rule(POINT_FORMATS)


def _file(path: PathLike, formats: tuple[str, ...] = FORMATS) -> Path:
    """``path`` (its extension already checked) as a :class:`Path` to an existing, non-empty regular file."""
    p = Path(os.fspath(path))
    if not p.exists():
        raise FileNotFoundError(f"no such {'mesh' if formats == FORMATS else 'point'} file: {str(p)!r}")
    if not p.is_file():
        raise MeshError(f"{str(p)!r} is not a regular file; pass the path of a mesh file.")
    if p.stat().st_size == 0:
        raise MeshError(f"{str(p)!r} is empty (0 bytes); it holds no mesh. Re-export or re-download it.")
    return p


@validated(path=_MESH_PATH)
def read_mesh_arrays(path: PathLike) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Read a mesh file's vertices and triangles without any topology check.

    This is the raw material for :func:`clean_mesh` when :func:`load_mesh` refuses a file.
    Structural problems (truncated or junk files, absurd header counts) still raise. Polygons
    are split into fans of triangles.

    Parameters
    ----------
    path : str or os.PathLike
        A ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    Returns
    -------
    vertices : ndarray, shape (n, 3), float64
        As the file lists them (STL: welded corners, in order of first appearance).
    faces : ndarray, shape (m, 3), int64
        0-based triangles. OFF and OBJ indices are checked against ``n`` while reading (so
        that an error shows the index as the file writes it); PLY and STL ones are not.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "dup.off"
    >>> _ = path.write_text("OFF\\n3 2 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 2\\n3 0 1 2\\n")
    >>> v, f = read_mesh_arrays(path)
    >>> f.tolist()
    [[0, 1, 2], [0, 1, 2]]
    """
    raw = read_raw(_file(path))
    return raw.vertices, raw.triangles


# =============================================================================================

# Public API
# =============================================================================================
@validated(
    keep_largest_component=Relation(lambda clean, keep_largest_component, **_: clean or not keep_largest_component,
                                    "keep_largest_component=True only applies when cleaning; pass clean=True as well"),
    path=_MESH_PATH,
)
def load_mesh(path: PathLike, clean: bool = False, *, keep_largest_component: bool = False) -> Mesh:
    """Read a triangle mesh from an ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    The vertices come back exactly as the file lists them (same count, same order); STL corners
    are welded into shared vertices in order of first appearance. See the module docstring for
    how each format is read.

    Parameters
    ----------
    path : str or os.PathLike
        The file. The extension (case-insensitive) selects the format.
    clean : bool, default False
        Repair what can be repaired (see :func:`clean_mesh`) and issue a
        :class:`MeshRepairWarning` saying what changed. Without it, any defect raises. What no
        repair makes manifold (non-manifold edges, non-orientable pieces) is kept and reported;
        ``lbo.eigenbasis(lbo.load_mesh(path, clean=True), k)`` gives every such mesh a spectrum,
        through the robust Laplacian where the cotangent one cannot serve it. A mesh in ``c``
        pieces has ``c`` zero eigenvalues (the report says how many pieces).
    keep_largest_component : bool, default False
        With ``clean=True``, keep only the connected component with the most faces.

    Returns
    -------
    Mesh
        A validated mesh. Several connected components and boundaries are legal. With
        ``clean=True`` it may be non-manifold or non-orientable (built with ``check=False``).

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ValueError
        If the extension is not one of :data:`FORMATS`.
    MeshError
        If the file is unreadable, empty, truncated or junk, announces absurd counts, or holds
        a defect: non-finite coordinates, indices out of range, polygons, degenerate or
        duplicate faces, unreferenced vertices, non-manifold edges, inconsistent orientation (all
        accepted by ``clean=True``; corrupt data never is). The message names the file, the
        defect and the fix.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "quad.obj"
    >>> _ = path.write_text("v 0 0 0\\nv 1 0 0\\nv 1 1 0\\nv 0 1 0\\nf 1 2 3 4\\n")
    >>> load_mesh(path)
    Traceback (most recent call last):
    ...
    lbo_notebooks.geometry._mesh.MeshError: ...1 of its 1 faces have more than three corners...
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     load_mesh(path, clean=True).faces.tolist()
    [[0, 1, 2], [0, 2, 3]]
    """
    p = _file(path)
    raw = read_raw(p)
    if clean:
        try:
            mesh, report = clean_arrays(
                raw.vertices, raw.triangles, keep_largest_component=keep_largest_component, polygons_split=raw.n_polygons
            )
        except MeshError as exc:
            raise MeshError(f"{str(p)!r}: cannot be repaired: {exc}{_in_the_file(raw, str(exc), p)}") from None
        if report.noteworthy:
            warn(f"{str(p)!r} loaded with clean=True: {report}", MeshRepairWarning)
        return mesh
    if raw.n_polygons:
        raise MeshError(
            f"{str(p)!r}: {raw.n_polygons} of its {raw.n_file_faces} faces have more than three corners; the LBO "
            "needs triangles. Load with clean=True, which splits each polygon into a fan of triangles, or "
            "triangulate it in a mesh editor."
        )
    try:
        return Mesh(raw.vertices, raw.triangles)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}{_in_the_file(raw, str(exc), p)}") from None


_MENTION = re.compile(r"\b(face|vertex) (\d+)\b(?! (?:has|have|is|are)\b)")


def _in_the_file(raw: RawMesh, message: str, p: Path) -> str:
    """Where the faces and vertices a mesh error names (counted from 0) are in the file, for OFF and OBJ.

    An OBJ file numbers its vertices from 1, so ``face 12 = [8, 29, 9]`` is the line ``f 9 30 10``;
    the sentence returned shows that line (empty if the reader cannot point at lines).
    """
    if raw.locate is None:
        return ""
    places = []
    for kind, index in dict.fromkeys(_MENTION.findall(message)):
        where = raw.locate(kind, int(index))
        if where is not None:
            places.append(f"{kind} {index} is {where}")
    if not places:
        return ""
    counting = (" (which numbers its vertices from 1, where this message counts from 0)"
                if p.suffix.lower() == ".obj" else "")
    return f" In the file{counting}: {'; '.join(places)}."


@validated(
    mesh=Satisfies(lambda mesh: isinstance(mesh, Mesh), error=TypeError, message=(
        "save_mesh needs a Mesh, got {type}; build one with Mesh(vertices, faces).")),
    path=_MESH_PATH,
    binary=Relation(lambda path, binary, **_: not binary or Path(os.fspath(path)).suffix.lower() in BINARY_FORMATS,
                    lambda path, **_: f"{Path(os.fspath(path)).suffix.lower()} files are text only; pass binary=False "
                                      "(or None), or save as .ply or .stl"),
)
def save_mesh(mesh: Mesh, path: PathLike, *, binary: bool | None = None) -> Path:
    """Write ``mesh`` to an ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    Parameters
    ----------
    mesh : Mesh
        The mesh to write.
    path : str or os.PathLike
        Destination; the extension selects the format. An existing file is overwritten.
    binary : bool or None, default None
        PLY and STL: binary (default) or ASCII. OFF and OBJ are text only (``binary=True``
        raises). Binary PLY and text files store float64 exactly (text at 17 significant
        digits); STL stores float32 by definition of the format.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    TypeError
        If ``mesh`` is not a :class:`Mesh`.
    ValueError
        For an unsupported extension or ``binary=True`` with a text-only format.
    OSError
        If the file cannot be written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from lbo_notebooks import shapes
    >>> path = save_mesh(shapes.icosphere(1), pathlib.Path(tempfile.mkdtemp()) / "s.off")
    >>> path.read_text().splitlines()[1]
    '42 80 0'
    """
    p = Path(os.fspath(path))
    ext = p.suffix.lower()
    if binary is None:
        binary = ext in BINARY_FORMATS
    v, f = mesh.vertices, mesh.faces
    if binary:
        # Written with NumPy (formats.writers), not open3d: saving needs no system libraries.
        try:
            write_mesh_binary(v, f, p, ext)
        except OSError as exc:
            raise OSError(f"could not write {str(p)!r} ({exc.strerror or exc}); check that the folder exists "
                          "and is writable.") from exc
        return p
    with open(p, "w", encoding="ascii", newline="\n") as fh:
        fh.write(mesh_text(v, f, ext))
    return p



@validated(path=_POINT_PATH)
def load_points(path: PathLike, *, clean: bool = False) -> PointCloud:
    """Read a point cloud: a vertex-only PLY, a text list of points, or a mesh file's vertices.

    Parameters
    ----------
    path : str or os.PathLike
        ``.ply`` (the ``vertex`` element; faces, if any, are ignored), ``.xyz``, ``.pts``,
        ``.txt``, ``.csv`` (one point per line, numbers separated by spaces, tabs or commas; the
        first three columns are x y z, further columns such as normals or colours are ignored; a
        first line holding one integer is a ``.pts`` count and must match the number of points; a
        first line starting with a word (``x,y,z``) is a header and is skipped; ``#`` and ``//`` start comments),
        or ``.off``/``.obj``/``.stl`` (the mesh's vertices).
    clean : bool, default False
        Drop points with NaN/inf coordinates and repeated points (the first is kept), with a
        :class:`MeshRepairWarning` saying how many. Without it they raise.

    Returns
    -------
    PointCloud

    Raises
    ------
    FileNotFoundError, ValueError
        Missing file; unsupported extension.
    MeshError
        Corrupt or truncated file (see :mod:`lbo_notebooks.geometry._formats` for how truncation is
        detected), rows that are not at least three numbers, or (without ``clean``) bad points.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "scan.xyz"
    >>> _ = path.write_text("0 0 0 0 0 1\\n1 0 0 0 0 1\\n0 1 0 0 0 1\\n0 0 1 1 0 0\\n1 1 1 0 1 0\\n")
    >>> load_points(path).n_points
    5
    """
    p = _file(path, POINT_FORMATS)
    ext = p.suffix.lower()
    try:
        points = read_raw(p, need_faces=False).vertices if ext in FORMATS else read_point_text(p)
    except MeshError as exc:
        msg = str(exc)
        raise MeshError(msg if msg.startswith(repr(str(p))) else f"{str(p)!r}: {msg}") from None
    if clean:
        finite = np.isfinite(points).all(axis=1)
        first, _ = unique_rows(points[finite])
        keep = np.flatnonzero(finite)[np.sort(first)]
        dropped = len(points) - len(keep)
        if dropped:
            warn(
                f"{str(p)!r}: {int((~finite).sum())} non-finite and {dropped - int((~finite).sum())} repeated points "
                f"dropped ({len(points)} -> {len(keep)} points)", MeshRepairWarning,
            )
        points = points[keep]
    try:
        return PointCloud(points)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}") from None
