"""Graded tests of notebook 04 (your own data): see :mod:`lbo_notebooks.exercises.grading`.

Every exercise of notebook 04 is about data the notebook writes and reads back (the messy scan's
OBJ file, the point cloud's XYZ file, the candidate meshes of section 3). A grader trusts none of
the kernel's objects or paths: it rebuilds that data here, with the notebook's constructors and
its seed (``np.random.default_rng(14)``, drawn in the notebook's order), writes the files into a
temporary folder of its own, and judges the answers against what the library makes of them. The
visible checks (:mod:`lbo_notebooks.exercises.your_data`) give the hints; ``tests/test_grading_04.py``
checks that the rebuilt data is the notebook's, array for array.
"""

from __future__ import annotations

import functools
import tempfile
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from .. import your_data
from ._registry import Verdict, from_feedback, grader, recap_verdict

# --- the notebook's data, rebuilt -----------------------------------------------------------------


def messy_scan() -> tuple[np.ndarray, list[list[int]], np.random.Generator]:
    """The arrays of section 1's messy scan, ``(v, faces)``, as the notebook's first cells build
    them, and the notebook's generator in the state they leave it (section 4 draws on from there)."""
    from ... import shapes

    rng = np.random.default_rng(14)
    sphere = shapes.icosphere(4)
    v = sphere.vertices * (1 + 1e-3 * rng.standard_normal((sphere.n_vertices, 1)))  # noise
    centres = sphere.vertices[rng.choice(sphere.n_vertices, 2, replace=False)]
    in_hole = (np.linalg.norm(sphere.vertices[sphere.faces].mean(axis=1)[:, None] - centres, axis=2) < 0.08).any(axis=1)
    faces = [list(t) for t in sphere.faces[~in_hole]]  # holes
    n = len(v)
    fin_edges = sphere.edges[rng.choice(len(sphere.edges), 3, replace=False)]
    tips = 1.05 * v[fin_edges].mean(axis=1)
    v = np.vstack([v, tips])
    faces += [[a, b, n + k] for k, (a, b) in enumerate(fin_edges)]  # non-manifold seam
    faces += [[t[0], t[1], t[1]] for t in faces[:4]]  # repeated corner
    v = np.vstack([v, [[0, 0, 1.1], [0, 0, 1.2], [0, 0, 1.3]]])
    faces += [[len(v) - 3, len(v) - 2, len(v) - 1]]  # flat (collinear) face
    faces += [faces[k][::-1] for k in range(10, 15)]  # duplicates, reversed
    for k in range(20, 40):
        faces[k] = faces[k][::-1]  # flipped orientation
    v = np.vstack([v, v[faces[50][0]]])
    faces[50] = [len(v) - 1, *faces[50][1:]]  # a split vertex (exact copy)
    v = np.vstack([v, rng.normal(size=(5, 3))])  # unreferenced vertices
    for centre in ([2.0, 0, 0], [0, 2.0, 0]):  # dust: small triangles
        base = len(v)
        v = np.vstack([v, np.asarray(centre) + 0.02 * np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]])])
        faces.append([base, base + 1, base + 2])
    base = len(v)
    v = np.vstack([v, [2, 2, 0] + 0.02 * np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])])
    faces.append([base, base + 1, base + 2, base + 3])  # a quad
    return v, faces, rng


def write_scan(folder: Path, v: np.ndarray, faces: list[list[int]]) -> Path:
    """``messy_scan.obj`` in ``folder``, written as the notebook writes it (17 significant digits)."""
    path = Path(folder) / "messy_scan.obj"
    lines = [f"v {x:.17g} {y:.17g} {z:.17g}" for x, y, z in v] + [
        "f " + " ".join(str(i + 1) for i in face) for face in faces]
    path.write_text("# a messy scan\n" + "\n".join(lines) + "\n")
    return path


def load_scan(path: Path) -> Any:
    """The scan as the notebook loads it, ``load_mesh(path, clean=True)``, its repair report silenced."""
    from ...geometry._files import load_mesh

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_mesh(path, clean=True)


def candidates(scan: Any) -> dict[str, Any]:
    """The four meshes of exercise 04-operator, built as in section 3 (``scan`` is the loaded scan)."""
    from ... import shapes
    from ...geometry._mesh import Mesh

    ball = shapes.icosphere(2)
    holes = Mesh(ball.vertices, ball.faces[2:])
    two_pieces = Mesh(np.vstack([ball.vertices, ball.vertices + [3.0, 0, 0]]),
                      np.vstack([ball.faces, ball.faces + ball.n_vertices]))
    top = int(np.argmax(ball.vertices[:, 2]))
    mirror = 2 * ball.vertices[top] - ball.vertices
    others = np.arange(ball.n_vertices) != top
    index = np.where(others, ball.n_vertices + np.cumsum(others) - 1, top)
    pinched = Mesh(np.vstack([ball.vertices, mirror[others]]), np.vstack([ball.faces, index[ball.faces]]))
    return {"holes": holes, "two_pieces": two_pieces, "fins": scan, "pinched": pinched}


def cloud_values(folder: Path, rng: np.random.Generator) -> np.ndarray:
    """``cloud_spectrum.values`` of section 4: 4,000 points drawn on from ``rng`` (as :func:`messy_scan`
    leaves it), written to ``scan.xyz`` with their normals at 9 decimals, read back, 16 eigenvalues."""
    from ...geometry._files import load_points
    from ...spectral._spectrum import eigenbasis

    points = rng.standard_normal((4000, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    path = Path(folder) / "scan.xyz"
    np.savetxt(path, np.hstack([points, points]), fmt="%.9f")  # x y z nx ny nz
    return eigenbasis(load_points(path), 16, progress=False).values


# --- the graders ----------------------------------------------------------------------------------


@grader("04-repair", kind="predict")
def _repair(repair: Any) -> Verdict:
    v, faces, _ = messy_scan()
    return from_feedback(your_data.check_repair_counts(repair, (v, faces), show=False))


@grader("04-operator", kind="choice")
def _operator(operator: Any) -> Verdict:
    v, faces, _ = messy_scan()
    with tempfile.TemporaryDirectory(prefix="lbo-grade-04-") as folder:
        scan = load_scan(write_scan(Path(folder), v, faces))
    return from_feedback(your_data.check_operator_choice(operator, candidates(scan), show=False))


@functools.lru_cache(maxsize=1)
def _cloud_reference() -> np.ndarray:
    """The cloud's eigenvalues, rebuilt once per process (the graded run grades one answer; the
    tests grade many), read-only."""
    _, _, rng = messy_scan()
    with tempfile.TemporaryDirectory(prefix="lbo-grade-04-") as folder:
        values = cloud_values(Path(folder), rng)
    values.flags.writeable = False
    return values


@grader("04-cloud", kind="compute")
def _cloud(relative_error: Any) -> Verdict:
    return from_feedback(your_data.check_cloud_eigenvalue(relative_error, _cloud_reference(), 9, show=False))


@grader("04-largest", kind="compute")
def _largest(largest_zeros: Any, largest_worst: Any) -> Verdict:
    v, faces, _ = messy_scan()
    with tempfile.TemporaryDirectory(prefix="lbo-grade-04-") as folder:
        path = write_scan(Path(folder), v, faces)
        return from_feedback(your_data.check_largest_component(largest_zeros, largest_worst, path, show=False))


@grader("04-neighbors", kind="predict")
def _neighbors(neighbors_effect: Any) -> Verdict:
    return from_feedback(your_data.check_neighbors_effect(neighbors_effect, show=False))


@grader("04-gap", kind="explore")
def _gap(pieces: Any) -> Verdict:
    # The check rebuilds the two spheres itself (shapes.icosphere(3), 30 neighbours) and requires
    # exactly the three radii the prompt asks for.
    return from_feedback(your_data.check_cloud_pieces(pieces, 30, (1.5, 1.75, 2.0), show=False))


@grader("04-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], your_data.recap_judges())
