"""The file formats: raw readers and text and binary writers for .off, .obj, .ply, .stl and text point lists.

This layer turns bytes into arrays and arrays into text, with no topology checks; the public
entry points are in :mod:`lbo_notebooks.geometry._files` (``load_mesh``, ``save_mesh``, ``load_points``).

How each format is handled, and why
-----------------------------------
Every file is parsed here, with NumPy doing the bulk conversion, and NumPy writes the binary
formats too (binary PLY at float64, binary STL; :mod:`~lbo_notebooks.geometry._formats.writers`), so no
file operation needs open3d or its system libraries. Before any data is read, the counts a header
announces (OFF, PLY, binary STL) are checked against the file size, so a corrupt header fails at
once instead of allocating gigabytes. open3d's readers were tried first and rejected because a
broken file must raise :class:`MeshError`, not kill the Python process or Jupyter kernel
(tried with open3d 0.20):

- PLY: a five-line ASCII PLY whose quad has an out-of-range index crashes the interpreter
  (segmentation fault, in its ear-clipping triangulation); randomly corrupted binary PLY files
  did the same; a truncated file or a ``nan`` gives partial, uninitialised arrays and no error.
  PLY is read with the ``plyfile`` library instead, after the header has been checked here:
  scanners write headers ``plyfile`` alone refuses (the Stanford files' ``property ambient_red
  uchar { ambient color }`` puts the name before the type and a comment in braces), so each
  header line is normalised first. Every element is read (ASCII, binary little or big endian);
  only ``vertex`` (x, y, z) and ``face`` (``vertex_indices`` or ``vertex_index``) are used.
- OFF: a file with fewer vertices than its header announces crashes the interpreter; a ``nan``
  coordinate gives uninitialised memory.
- OBJ: open3d renumbers the vertices in order of first use, drops unreferenced ones, splits a
  vertex wherever its texture or normal index changes (cutting the surface open at every seam)
  and skips faces with more than three corners. Here the ``v`` and ``f`` lines are read directly,
  so vertex ``k`` of the mesh is the ``k``-th ``v`` line and ``vt``/``vn`` seams do not exist.
- STL: open3d reads ASCII STL through ASSIMP at single precision, and its binary reader is slow on
  large files; a binary STL is a header and fixed 50-byte records, read here
  with one ``numpy.fromfile`` call.
- open3d writes text formats with six significant digits, which is lossy; here they are written
  with 17, so that saving and loading gives back the same float64 coordinates.

Numbers are read as C and every mesh tool writes them: Python's ``1_000`` is not a number, and a
vertex index must be written as an integer (``2``, not ``2.0`` or ``2e0``) in every format; an
index too large for a 64-bit integer is reported as written. A truncated file is refused wherever
the format lets us tell: counts announced by a header (OFF, PLY, binary STL) are checked, an ASCII
STL must end with ``endsolid`` after complete facets, a ``.pts`` count line must match its points,
and the last line of a text file must end with a line break unless it ends in a comment, because a
file cut inside its last number (``3 0 1 12`` cut to ``3 0 1 1``) still parses. OBJ and the other
point lists announce no count: one cut exactly at a line break loses whole lines unseen.

STL stores three separate corners per triangle: corners with exactly equal coordinates are
welded back into shared vertices, numbered in order of first appearance, so a closed surface
stays closed.

Polygons (faces with more than three corners, in OFF, OBJ or PLY) are refused by default with a
:class:`MeshError`; with ``clean=True`` each is split into a fan of triangles from its first
corner (right for convex polygons, which is what exporters write) and the split is reported.

Examples
--------
>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "tri.off"
>>> _ = path.write_text(mesh_text([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], ".off"))
>>> raw = read_raw(path)
>>> raw.triangles.tolist(), raw.n_polygons
([[0, 1, 2]], 0)
"""

from __future__ import annotations

from pathlib import Path

from .._mesh import MeshError
from .common import BINARY_FORMATS, FORMATS, POINT_FORMATS, RawMesh
from .obj import read_obj
from .off import read_off
from .ply import read_ply
from .points import read_point_text
from .stl import read_stl
from .writers import mesh_bytes, mesh_text, write_mesh_binary

__all__ = [
    "FORMATS", "POINT_FORMATS", "BINARY_FORMATS", "RawMesh", "read_raw", "read_point_text", "mesh_text",
    "mesh_bytes", "write_mesh_binary",
]


def read_raw(p: Path, *, need_faces: bool = True) -> RawMesh:
    """Read the mesh file ``p`` (extension in :data:`FORMATS`, already checked to exist).

    Structural problems raise :class:`MeshError` naming the file; polygons are split into fans.
    With ``need_faces=False`` a file without faces (a point cloud) is not an error.
    """
    ext = p.suffix.lower()
    reader = {".off": read_off, ".obj": read_obj, ".ply": read_ply, ".stl": read_stl}[ext]
    try:
        return reader(p) if ext in (".off", ".stl") else reader(p, need_faces)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}") from None

