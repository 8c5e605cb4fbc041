"""The graded tests of notebook 03 (the Laplace–Beltrami operator), with answers written as students
write them: the instructor's solution, correct answers written differently (other loops, other
formulas, dense or sparse), typical wrong ones, library calls in the two builds, the placeholders;
see lbo_notebooks/exercises/grading/nb03.py. Also the notebook's claims that the hidden tests used
to assert (the sphere's spectrum with either mass, the kernels, W under scaling)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import cloudpickle
import numpy as np
import pytest

from .grading_support import answers, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "03_laplace_beltrami.ipynb"


class Sent(bytes):
    """Answers pickled when this module is imported (at collection, before any graded run of this
    test process has made the library unavailable), as a student's kernel pickles them: a library
    function the answer refers to goes by reference. Pickled after a block, it would go by value."""


def sent(**given) -> Sent:
    return Sent(cloudpickle.dumps(given))


def _judged(exercise, given):
    if isinstance(given.get("payload"), Sent):
        from lbo_notebooks.exercises.grading.__main__ import _verdict

        result = _verdict(exercise, given["payload"])
        assert "error" not in result, result["error"]
        return round(result["fraction"] * result["points"], 2), result["status"], result["message"]
    return verdict(exercise, **given)


def _full(exercise, **given):
    points, status, message = _judged(exercise, given)
    assert points == full_points(exercise), (status, message)
    return message


def _zero(exercise, *words, status="wrong", **given):
    points, got_status, message = _judged(exercise, given)
    assert points == 0 and got_status == status, (points, got_status, message)
    for word in words:
        assert word.lower() in message.lower(), (word, message)
    return message


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


def test_points_follow_the_kinds():
    exercises = ("03-stiffness", "03-mass", "03-eigensolve", "03-convergence", "03-coefficients", "03-consistent",
                 "03-scaling", "03-kernel", "03-lbo-recap")
    assert [full_points(e) for e in exercises] == [5, 5, 5, 1, 2, 2, 1, 2, 3]


# --- 03-stiffness (build it yourself) ------------------------------------------------------------
# Every answer is run now, at collection, as in a student's kernel: before any graded run of this
# test process has made the library unavailable (a blocked function imported by name afterwards
# would be pickled by value, which a student's kernel never does).

STIFFNESS = {
    "per-face loop, dense": """
        def my_stiffness(mesh):
            V, F = mesh.vertices, mesh.faces
            W = np.zeros((len(V), len(V)))
            for tri in F:
                for k in range(3):
                    o, i, j = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
                    u, w = V[i] - V[o], V[j] - V[o]
                    c = 0.5 * (u @ w) / np.linalg.norm(np.cross(u, w))
                    W[i, j] -= c
                    W[j, i] -= c
                    W[i, i] += c
                    W[j, j] += c
            return W
    """,
    "angles with arccos, csr from triplets": """
        def my_stiffness(m):
            p = m.vertices[m.faces]
            rows, cols, vals = [], [], []
            for k in range(3):
                e1 = p[:, (k + 1) % 3] - p[:, k]
                e2 = p[:, (k + 2) % 3] - p[:, k]
                cos = (e1 * e2).sum(1) / np.linalg.norm(e1, axis=1) / np.linalg.norm(e2, axis=1)
                half_cot = 0.5 / np.tan(np.arccos(cos))
                a, b = m.faces[:, (k + 1) % 3], m.faces[:, (k + 2) % 3]
                rows += [a, b, a, b]
                cols += [b, a, a, b]
                vals += [-half_cot, -half_cot, half_cot, half_cot]
            n = m.n_vertices
            return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    """,
    "an edge dictionary, lil_matrix": """
        from collections import defaultdict

        def my_stiffness(mesh):
            weight = defaultdict(float)
            v = mesh.vertices
            for f in mesh.faces.tolist():
                for k in range(3):
                    c, a, b = f[k], f[(k + 1) % 3], f[(k + 2) % 3]
                    x, y = v[a] - v[c], v[b] - v[c]
                    weight[min(a, b), max(a, b)] += np.dot(x, y) / np.linalg.norm(np.cross(x, y)) / 2
            W = sp.lil_matrix((len(v), len(v)))
            for (a, b), w in weight.items():
                W[a, b] = W[b, a] = -w
            W.setdiag(-np.asarray(W.sum(axis=1)).ravel())
            return W.tocsr()
    """,
}

STIFFNESS_SLIPS = {
    "no ½": ("""
        def my_stiffness(mesh):
            v, f = mesh.vertices, mesh.faces
            p = v[f]
            off = sp.csr_matrix((len(v), len(v)))
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                cot = np.einsum("ij,ij->i", a, b) / np.linalg.norm(np.cross(a, b), axis=1)
                i, j = f[:, (k + 1) % 3], f[:, (k + 2) % 3]
                off = off + sp.csr_matrix((-cot, (i, j)), shape=off.shape) + sp.csr_matrix((-cot, (j, i)), shape=off.shape)
            return off - sp.diags(np.asarray(off.sum(axis=1)).ravel())
    """, "twice"),
    "sign": ("W = lambda mesh: -my_ref(mesh)\nmy_stiffness = W", "sign"),
    "only W_ij, not W_ji": ("""
        def my_stiffness(mesh):
            W = my_ref(mesh).toarray()
            return np.triu(W, 1) + np.diag(np.diag(W))
    """, "(j, i)"),
    "no diagonal": ("""
        def my_stiffness(mesh):
            W = my_ref(mesh)
            return W - sp.diags(W.diagonal())
    """, "diagonal is missing"),
    "cosines, not cotangents": ("""
        def my_stiffness(mesh):
            v, f = mesh.vertices, mesh.faces
            n, p = len(v), v[f]
            W = np.zeros((n, n))
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                cos = np.einsum("ij,ij->i", a, b) / np.linalg.norm(a, axis=1) / np.linalg.norm(b, axis=1)
                i, j = f[:, (k + 1) % 3], f[:, (k + 2) % 3]
                np.add.at(W, (i, j), -cos / 2)
                np.add.at(W, (j, i), -cos / 2)
            return W - np.diag(W.sum(axis=1))
    """, "cotangent weights"),
    "angles at the corner, not opposite": ("""
        def my_stiffness(mesh):
            v, f = mesh.vertices, mesh.faces
            n, p = len(v), v[f]
            W = np.zeros((n, n))
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                cot = np.einsum("ij,ij->i", a, b) / np.linalg.norm(np.cross(a, b), axis=1)
                i, j = f[:, k], f[:, (k + 1) % 3]
                np.add.at(W, (i, j), -cot / 2)
                np.add.at(W, (j, i), -cot / 2)
            return W - np.diag(W.sum(axis=1))
    """, "opposite"),
    "one row too many": ("my_stiffness = lambda mesh: np.eye(mesh.n_vertices + 1)", "n × n"),
    "raises": ("def my_stiffness(mesh):\n    return mesh.cotangents\n", "AttributeError"),
}

STIFFNESS_LIBRARY = {
    "the function itself": ("my_stiffness = lbo.stiffness_matrix", "stiffness_matrix"),
    "a wrapper": ("def my_stiffness(mesh):\n    return lbo.stiffness_matrix(mesh).toarray()\n", "stiffness_matrix"),
    "the eigenbasis route": ("my_stiffness = lambda m: lbo.eigenbasis(m, 3).stiffness", "laplace_beltrami"),
    "the library's cotangents": ("""
        from lbo_notebooks.operators import face_cotangents

        def my_stiffness(mesh):
            f, n, cot = mesh.faces, mesh.n_vertices, face_cotangents(mesh)
            i = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
            j = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
            off = sp.coo_matrix((-0.5 * cot.T.ravel(), (i, j)), shape=(n, n))
            off = (off + off.T).tocsr()
            return off - sp.diags(np.asarray(off.sum(axis=1)).ravel())
    """, "face_cotangents"),
    "the library's angles": ("""
        from lbo_notebooks.operators import corner_angles

        def my_stiffness(mesh):
            return my_from_cotangents(mesh, 1 / np.tan(corner_angles(mesh)))
    """, "corner_angles"),
    "the gradient route": ("""
        from lbo_notebooks.analyses._heat_method import face_gradient_operator

        def my_stiffness(mesh):
            G, a = face_gradient_operator(mesh)
            return G.T @ sp.diags(np.tile(a, 3)) @ G
    """, "face_gradient_operator"),
    "laplace_beltrami": ("""
        from lbo_notebooks.operators import laplace_beltrami

        my_stiffness = lambda mesh: laplace_beltrami(mesh)[0]
    """, "laplace_beltrami"),
    "igl": ("import igl\n\ndef my_stiffness(mesh):\n    return -igl.cotmatrix(mesh.vertices, mesh.faces)\n", "igl.cotmatrix"),
    "gpytoolbox, imported by name": ("""
        from gpytoolbox import cotangent_laplacian

        def my_stiffness(mesh):
            return cotangent_laplacian(mesh.vertices, mesh.faces)
    """, "cotangent_laplacian"),
    "robust_laplacian": ("""
        import robust_laplacian

        def my_stiffness(mesh):
            return robust_laplacian.mesh_laplacian(np.asarray(mesh.vertices), np.asarray(mesh.faces))[0]
    """, "mesh_laplacian"),
    "potpourri3d": ("""
        import potpourri3d as pp3d

        my_stiffness = lambda mesh: pp3d.cotan_laplacian(mesh.vertices, mesh.faces)
    """, "cotan_laplacian"),
}

HELPERS = """
def my_ref(mesh):
    # a stiffness matrix built by hand, which the slips below get wrong on purpose
    v, f = mesh.vertices, mesh.faces
    n, p = len(v), v[f]
    rows, cols, weights = [], [], []
    for k in range(3):
        a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
        cot = np.einsum("ij,ij->i", a, b) / np.linalg.norm(np.cross(a, b), axis=1)
        i, j = f[:, (k + 1) % 3], f[:, (k + 2) % 3]
        rows += [i, j]
        cols += [j, i]
        weights += [-cot / 2, -cot / 2]
    off = sp.coo_matrix((np.concatenate(weights), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    return off.tocsr() - sp.diags(np.asarray(off.sum(axis=1)).ravel())


def my_from_cotangents(mesh, cot):
    f, n = mesh.faces, mesh.n_vertices
    i = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    j = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    off = sp.coo_matrix((-0.5 * cot.T.ravel(), (i, j)), shape=(n, n))
    off = (off + off.T).tocsr()
    return off - sp.diags(np.asarray(off.sum(axis=1)).ravel())


def my_bary(mesh):
    return sp.diags(np.bincount(mesh.faces.ravel(), np.repeat(mesh.face_areas / 3, 3), mesh.n_vertices))
"""


def _stiffness(code):
    return sent(**answers(HELPERS + textwrap.dedent(code), "my_stiffness"))


ANSWERS = {name: _stiffness(code) for name, code in STIFFNESS.items()}
SLIPS = {name: (_stiffness(code), hint) for name, (code, hint) in STIFFNESS_SLIPS.items()}
LIBRARY = {name: (_stiffness(code), where) for name, (code, where) in STIFFNESS_LIBRARY.items()}
SOLUTION_STIFFNESS = _stiffness(solution("03-stiffness"))
STUB_STIFFNESS = _stiffness(student_edition("03-stiffness"))


def test_stiffness_solution():
    assert "Right on three meshes" in _full("03-stiffness", payload=SOLUTION_STIFFNESS)


@pytest.mark.parametrize("name", list(STIFFNESS))
def test_stiffness_written_differently(name):
    _full("03-stiffness", payload=ANSWERS[name])


@pytest.mark.parametrize("name", list(STIFFNESS_SLIPS))
def test_stiffness_slips(name):
    function, hint = SLIPS[name]
    _zero("03-stiffness", hint, payload=function)


@pytest.mark.parametrize("name", list(STIFFNESS_LIBRARY))
def test_stiffness_library_calls(name):
    function, where = LIBRARY[name]
    _zero("03-stiffness", "build it yourself", "not available", where, payload=function)


def test_stiffness_placeholders():
    _zero("03-stiffness", status="not attempted", payload=STUB_STIFFNESS)
    _zero("03-stiffness", status="not attempted", my_stiffness=...)
    raises = answers("def my_stiffness(mesh):\n    raise NotImplementedError()\n", "my_stiffness")
    _zero("03-stiffness", status="not attempted", **raises)


def test_stiffness_library_call_through_the_graded_run():
    import lbo_notebooks as lbo

    assert graded("03-stiffness", my_stiffness=lbo.stiffness_matrix) == 0.0
    with pytest.raises(AssertionError, match="0 / 5 points: This exercise asks you to build it yourself"):
        from lbo_notebooks.exercises.grading import grade

        grade("03-stiffness", **answers(STIFFNESS_LIBRARY["a wrapper"][0], "my_stiffness"))


# --- 03-mass (build it yourself) -----------------------------------------------------------------

MASS = {
    "barycentric, loop over faces": """
        def my_mass(mesh):
            share = np.zeros(mesh.n_vertices)
            for tri in mesh.faces:
                p0, p1, p2 = mesh.vertices[tri]
                share[tri] += np.linalg.norm(np.cross(p1 - p0, p2 - p0)) / 6
            return sp.diags(share)
    """,
    "barycentric, incidence matrix, dense": """
        def my_mass(mesh):
            f = mesh.faces
            m = len(f)
            incidence = sp.csr_matrix((np.ones(3 * m), (f.ravel(), np.repeat(np.arange(m), 3))),
                                      shape=(mesh.n_vertices, m))
            return np.diag(incidence @ mesh.face_areas / 3)
    """,
    "mixed Voronoi, by hand": """
        def my_mass(mesh):
            v, f = mesh.vertices, mesh.faces
            p = v[f]
            area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
            cot = np.empty(f.shape)
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                cot[:, k] = (a * b).sum(1) / (2 * area)
            sq = np.stack([((p[:, (k + 1) % 3] - p[:, (k + 2) % 3]) ** 2).sum(1) for k in range(3)], axis=1)
            corner = np.empty(f.shape)
            for k in range(3):
                k1, k2 = (k + 1) % 3, (k + 2) % 3
                corner[:, k] = (sq[:, k2] * cot[:, k2] + sq[:, k1] * cot[:, k1]) / 8
            obtuse = cot < 0
            bad = obtuse.any(axis=1)
            corner[bad] = np.where(obtuse[bad], 0.5, 0.25) * area[bad, None]
            return sp.diags(np.bincount(f.ravel(), corner.ravel(), len(v)))
    """,
}

MASS_SLIPS = {
    "the identity": ("my_mass = lambda mesh: sp.identity(mesh.n_vertices)", "Euclidean"),
    "no ½": ("my_mass = lambda mesh: 2 * my_bary(mesh)", "twice too large"),
    "the whole area to every corner": ("my_mass = lambda mesh: 3 * my_bary(mesh)", "three corners"),
    "the consistent mass": ("""
        def my_mass(mesh):
            n, A = mesh.n_vertices, np.zeros((mesh.n_vertices, mesh.n_vertices))
            for tri, area in zip(mesh.faces, mesh.face_areas):
                A[np.ix_(tri, tri)] += area / 12 * (np.ones((3, 3)) + np.eye(3))
            return A
    """, "consistent"),
    "negative areas": ("my_mass = lambda mesh: -my_bary(mesh)", "negative"),
    "pure Voronoi": ("""
        def my_mass(mesh):
            v, f = mesh.vertices, mesh.faces
            p = v[f]
            twice = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
            corner = np.zeros(f.shape)
            for k in range(3):
                k1, k2 = (k + 1) % 3, (k + 2) % 3
                cot1 = ((p[:, k] - p[:, k1]) * (p[:, k2] - p[:, k1])).sum(1) / twice
                cot2 = ((p[:, k] - p[:, k2]) * (p[:, k1] - p[:, k2])).sum(1) / twice
                corner[:, k] = (((p[:, k] - p[:, k2]) ** 2).sum(1) * cot1 + ((p[:, k] - p[:, k1]) ** 2).sum(1) * cot2) / 8
            return sp.diags(np.bincount(f.ravel(), corner.ravel(), len(v)))
    """, "mixed rule"),
}

MASS_LIBRARY = {
    "the function itself": ("my_mass = lbo.mass_matrix", "mass_matrix"),
    "barycentric from the library": ("my_mass = lambda m: lbo.mass_matrix(m, 'barycentric')", "mass_matrix"),
    "the eigenbasis route": ("my_mass = lambda m: lbo.eigenbasis(m, 3).mass", "laplace_beltrami"),
    "the private helper": ("from lbo_notebooks.operators import _cotangent\nmy_mass = lambda m: _cotangent._mass(m, 'voronoi')",
                           "_mass"),
    "the curvature route": ("""
        from lbo_notebooks.operators import metric_mass_matrix

        my_mass = lambda m: metric_mass_matrix(m, 0.0)
    """, "metric_mass_matrix"),
    "igl": ("import igl\n\ndef my_mass(mesh):\n    return igl.massmatrix(mesh.vertices, mesh.faces)\n", "igl.massmatrix"),
    "gpytoolbox, imported by name": ("""
        from gpytoolbox import massmatrix

        my_mass = lambda m: massmatrix(m.vertices, m.faces)
    """, "massmatrix"),
    "robust_laplacian": ("""
        import robust_laplacian

        my_mass = lambda m: robust_laplacian.mesh_laplacian(m.vertices, m.faces)[1]
    """, "mesh_laplacian"),
}


def _mass(code):
    return sent(**answers(HELPERS + textwrap.dedent(code), "my_mass"))


MASS_ANSWERS = {name: _mass(code) for name, code in MASS.items()}
MASS_WRONG = {name: (_mass(code), hint) for name, (code, hint) in MASS_SLIPS.items()}
MASS_LIB = {name: (_mass(code), where) for name, (code, where) in MASS_LIBRARY.items()}
SOLUTION_MASS = _mass(solution("03-mass"))
STUB_MASS = _mass(student_edition("03-mass"))
VORONOI_WITH_LIBRARY_COTANGENTS = """
    from lbo_notebooks.operators import face_cotangents

    def my_mass(mesh):
        v, f = mesh.vertices, mesh.faces
        cot, area = face_cotangents(mesh), mesh.face_areas
        sq = np.stack([((v[f[:, (k + 1) % 3]] - v[f[:, (k + 2) % 3]]) ** 2).sum(1) for k in range(3)], axis=1)
        corner = np.stack([(sq[:, (k + 2) % 3] * cot[:, (k + 2) % 3] + sq[:, (k + 1) % 3] * cot[:, (k + 1) % 3]) / 8
                           for k in range(3)], axis=1)
        obtuse = cot < 0
        corner = np.where(obtuse.any(axis=1, keepdims=True), np.where(obtuse, 0.5, 0.25) * area[:, None], corner)
        return sp.diags(np.bincount(f.ravel(), corner.ravel(), len(v)))
"""


def test_mass_solution():
    assert "barycentric" in _full("03-mass", payload=SOLUTION_MASS)
    # The old hidden test's claim about the solution: the masses add up to the area.
    triangle = answers("t = lbo.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])", "t")["t"]
    my_mass = answers(solution("03-mass"), "my_mass")["my_mass"]
    assert np.isclose(my_mass(triangle).sum(), triangle.area)


@pytest.mark.parametrize("name", list(MASS))
def test_mass_written_differently(name):
    message = _full("03-mass", payload=MASS_ANSWERS[name])
    assert ("Voronoi" if "Voronoi" in name else "barycentric") in message


@pytest.mark.parametrize("name", list(MASS_SLIPS))
def test_mass_slips(name):
    function, hint = MASS_WRONG[name]
    _zero("03-mass", hint, payload=function)


@pytest.mark.parametrize("name", list(MASS_LIBRARY))
def test_mass_library_calls(name):
    function, where = MASS_LIB[name]
    _zero("03-mass", "build it yourself", "not available", where, payload=function)


def test_mass_placeholders():
    _zero("03-mass", status="not attempted", payload=STUB_MASS)
    _zero("03-mass", status="not attempted", my_mass=None)


def test_mass_may_use_the_cotangents_through_the_graded_run():
    """The mixed Voronoi rule needs cotangents: the library's are allowed in 03-mass (not in 03-stiffness)."""
    assert graded("03-mass", **answers(VORONOI_WITH_LIBRARY_COTANGENTS, "my_mass")) == 5.0


# --- 03-eigensolve (build it yourself) -----------------------------------------------------------
# Pickled at collection, like the builds above (library functions go by reference).

EIGEN_HELPERS = """
def my_sigma(A):
    return -1e-2 * 4 * np.pi / A.sum()


def my_right(W, A, k):
    # the k smallest eigenpairs, done right, for the slips below to spoil
    values, vectors = sla.eigsh(W, k, M=A, sigma=my_sigma(A), which="LM")
    order = np.argsort(values)
    return values[order], vectors[:, order]
"""

EIGEN = {
    "dense eigh of the pencil": """
        import scipy.linalg

        def my_eigenbasis(W, A, k):
            lam, phi = scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, k - 1])
            return lam, phi
    """,
    "Cholesky to a standard problem, a list, signs flipped": """
        def my_eigenbasis(W, A, k):
            L = np.linalg.cholesky(A.toarray())
            B = np.linalg.solve(L, np.linalg.solve(L, W.toarray()).T)   # L^-1 W L^-T (W symmetric)
            mu, Y = np.linalg.eigh((B + B.T) / 2)
            X = np.linalg.solve(L.T, Y[:, :k])
            return [list(mu[:k]), -X]
    """,
    "own shift-invert operator, every repeated eigenspace rotated": """
        def my_eigenbasis(W, A, k):
            n = W.shape[0]
            s = 0.05 * 4 * np.pi / A.sum()
            lu = sla.splu(sp.csc_matrix(W + s * A))
            op = sla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
            vals, vecs = sla.eigsh(W, k, M=A, sigma=-s, OPinv=op, v0=np.linspace(1.0, 2.0, n))
            idx = np.argsort(vals)
            vals, vecs = vals[idx], vecs[:, idx]
            rng = np.random.default_rng(5)
            start = 0
            while start < k:   # any A-orthonormal basis of a repeated eigenvalue is as good
                stop = start + 1
                while stop < k and vals[stop] - vals[start] < 1e-8 * vals[-1]:
                    stop += 1
                R = np.linalg.qr(rng.normal(size=(stop - start, stop - start)))[0]
                vecs[:, start:stop] = vecs[:, start:stop] @ R
                start = stop
            return vals, vecs
    """,
    "eig of A^-1 W, then Gram-Schmidt in the A inner product": """
        def my_eigenbasis(W, A, k):
            Wd, Ad = W.toarray(), A.toarray()
            lam, X = np.linalg.eig(np.linalg.solve(Ad, Wd))
            keep = np.argsort(lam.real)[:k]
            lam, X = lam.real[keep], X.real[:, keep]
            for j in range(k):
                for _ in range(2):   # twice is enough
                    for i in range(j):
                        X[:, j] -= (X[:, i] @ Ad @ X[:, j]) * X[:, i]
                X[:, j] /= np.sqrt(X[:, j] @ Ad @ X[:, j])
            return lam, X
    """,
}

EIGEN_SLIPS = {
    "the largest eigenvalues": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = sla.eigsh(W, k, M=A)
            order = np.argsort(values)
            return values[order], vectors[:, order]
    """, "largest"),
    "A left out": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = sla.eigsh(W, k, sigma=my_sigma(A))
            order = np.argsort(values)
            return values[order], vectors[:, order]
    """, "W alone"),
    "Euclidean normalisation": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = my_right(W, A, k)
            return values, vectors / np.linalg.norm(vectors, axis=0)
    """, "Euclidean"),
    "descending": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = my_right(W, A, k)
            return values[::-1], vectors[:, ::-1]
    """, "ascending"),
    "values sorted, vectors not": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = my_right(W, A, k)
            return np.sort(values[::-1]), vectors[:, ::-1]
    """, "reorder the vectors"),
    "transposed vectors": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = my_right(W, A, k)
            return values, vectors.T
    """, "columns"),
    "(vectors, values)": ("my_eigenbasis = lambda W, A, k: my_right(W, A, k)[::-1]", "swapped"),
    "the zero eigenvalue dropped": ("""
        def my_eigenbasis(W, A, k):
            values, vectors = my_right(W, A, k + 1)
            return values[1:], vectors[:, 1:]
    """, "λ₀ = 0"),
    "shift-inverted eigenvalues not turned back": ("""
        def my_eigenbasis(W, A, k):
            s = my_sigma(A)
            nu, vectors = sla.eigsh(A, k, M=W - s * A, which="LA")   # A x = nu (W - s A) x
            order = np.argsort(nu)
            return nu[order], vectors[:, order]
    """, "1/(λ − σ)"),
    "A-normalised, but a repeated eigenspace not orthogonalised": ("""
        def my_eigenbasis(W, A, k):
            lam, X = np.linalg.eig(np.linalg.solve(A.toarray(), W.toarray()))
            keep = np.argsort(lam.real)[:k]
            X = X.real[:, keep]
            return lam.real[keep], X / np.sqrt(np.einsum("ij,ij->j", X, A @ X))
    """, "not A-orthogonal"),
    "one pair short": ("my_eigenbasis = lambda W, A, k: my_right(W, A, k - 1)", "asked for k"),
    "a dict": ("my_eigenbasis = lambda W, A, k: dict(zip(('values', 'vectors'), my_right(W, A, k)))", "tuple"),
}

EIGEN_LIBRARY = {
    "the library's eigenbasis on the pencil": ("""
        def my_eigenbasis(W, A, k):
            spectrum = lbo.eigenbasis((W, A), k)
            return spectrum.values, spectrum.vectors
    """, "eigenbasis"),
    "spectrum slicing": ("""
        from lbo_notebooks.spectral._engine.eigensolver import slice_eigsh

        def my_eigenbasis(W, A, k):
            return slice_eigsh(W, A, k, v0=np.ones(W.shape[0]) + np.arange(W.shape[0]) % 3, shift=-my_sigma(A))[:2]
    """, "slice_eigsh"),
    "the block Lanczos underneath": ("""
        from lbo_notebooks.spectral._engine.krylov import nearest_eigenpairs

        def my_eigenbasis(W, A, k):
            s = my_sigma(A)
            lu = sla.splu(sp.csc_matrix(W - s * A))
            return nearest_eigenpairs(lu.solve, W, A, s, k, start=np.linspace(1, 2, W.shape[0]))
    """, "nearest_eigenpairs"),
    "deflation with the constrained minimum": ("""
        from lbo_notebooks.analyses import min_rayleigh_quotient

        def my_eigenbasis(W, A, k):
            values, vectors = [], []
            for _ in range(k):
                C = np.column_stack(vectors) if vectors else None
                lam, phi = min_rayleigh_quotient(W, A, C, return_vector=True)
                values.append(lam)
                vectors.append(phi)
            return np.array(values), np.column_stack(vectors)
    """, "min_rayleigh_quotient"),
    "pyFM": ("""
        from pyFM.mesh.laplacian import laplacian_spectrum

        my_eigenbasis = lambda W, A, k: laplacian_spectrum(W, A, spectrum_size=k)
    """, "laplacian_spectrum"),
}


def _eigen(code):
    return sent(**answers(EIGEN_HELPERS + textwrap.dedent(code), "my_eigenbasis"))


EIGEN_ANSWERS = {name: _eigen(code) for name, code in EIGEN.items()}
EIGEN_WRONG = {name: (_eigen(code), hint) for name, (code, hint) in EIGEN_SLIPS.items()}
EIGEN_LIB = {name: (_eigen(code), where) for name, (code, where) in EIGEN_LIBRARY.items()}
SOLUTION_EIGEN = _eigen(solution("03-eigensolve"))
STUB_EIGEN = _eigen(student_edition("03-eigensolve"))


def test_eigensolve_solution():
    assert "Right on four pencils" in _full("03-eigensolve", payload=SOLUTION_EIGEN)


@pytest.mark.parametrize("name", list(EIGEN))
def test_eigensolve_written_differently(name):
    _full("03-eigensolve", payload=EIGEN_ANSWERS[name])


@pytest.mark.parametrize("name", list(EIGEN_SLIPS))
def test_eigensolve_slips(name):
    function, hint = EIGEN_WRONG[name]
    message = _zero("03-eigensolve", hint, "graded on", payload=function)
    assert "notebook does not show" in message


@pytest.mark.parametrize("name", list(EIGEN_LIBRARY))
def test_eigensolve_library_calls(name):
    function, where = EIGEN_LIB[name]
    _zero("03-eigensolve", "build it yourself", "not available", where, payload=function)


def test_eigensolve_placeholders():
    _zero("03-eigensolve", status="not attempted", payload=STUB_EIGEN)
    _zero("03-eigensolve", status="not attempted", my_eigenbasis=...)
    _zero("03-eigensolve", "pass the function", my_eigenbasis=(np.zeros(3), np.eye(3)))


def test_eigensolve_through_the_graded_run():
    from lbo_notebooks.exercises.grading import grade

    assert graded("03-eigensolve", **answers(EIGEN_HELPERS + solution("03-eigensolve"), "my_eigenbasis")) == 5.0
    with pytest.raises(AssertionError, match="0 / 5 points: This exercise asks you to build it yourself"):
        grade("03-eigensolve", **answers(EIGEN_HELPERS + textwrap.dedent(EIGEN_LIBRARY["the library's eigenbasis on "
                                                                                      "the pencil"][0]), "my_eigenbasis"))


def test_eigensolve_verdict_is_deterministic():
    for payload in (SOLUTION_EIGEN, EIGEN_WRONG["Euclidean normalisation"][0]):
        assert _judged("03-eigensolve", {"payload": payload}) == _judged("03-eigensolve", {"payload": payload})


def test_eigensolve_graded_pencils():
    """The graded pencils: unseen by the visible check, each k below a gap (so the span is determined),
    an exactly repeated eigenvalue on the icosphere, two zero eigenvalues on the two pieces, a
    non-diagonal mass on the sheet; the instructor's solution within 1e-12 there."""
    from lbo_notebooks.exercises import laplace_beltrami as lb
    from lbo_notebooks.exercises.grading import nb03

    graded_problems, visible = nb03._unseen_eigenproblems(), lb._eigen_problems()
    sizes = {W.shape[0] for W, *_ in visible}
    assert all(W.shape[0] not in sizes for W, *_ in graded_problems)
    my_eigenbasis = answers(solution("03-eigensolve"), "my_eigenbasis")["my_eigenbasis"]
    zeros = []
    for W, A, k, where in [*graded_problems, *visible]:
        ref = lb.eigen_reference(W, A)[0]
        assert ref[k] - ref[k - 1] > 1e-2 * ref[k - 1], where
        values, vectors = my_eigenbasis(W, A, k)
        assert np.abs(values - ref[:k]).max() < 1e-12 * ref[k - 1], where
        zeros.append(int(np.sum(np.abs(ref) < 1e-10 * ref[-1])))
    ico = lb.eigen_reference(*graded_problems[0][:2])[0][:16]
    assert np.allclose(ico[1:4], ico[1]) and np.allclose(ico[4:9], ico[4]) and np.ptp(ico[1:4]) < 1e-12 * ico[-1]
    assert zeros[3] == 2 and zeros[:3] == [1, 1, 1]
    assert graded_problems[2][1].nnz > graded_problems[2][1].shape[0]  # the consistent mass: off-diagonal entries


def test_eigensolve_visible_check():
    from lbo_notebooks.exercises import laplace_beltrami as lb

    good = answers(EIGEN_HELPERS + solution("03-eigensolve"), "my_eigenbasis")["my_eigenbasis"]
    assert lb.check_eigensolve(good, show=False).correct
    for code, hint in (EIGEN_SLIPS["Euclidean normalisation"], EIGEN_SLIPS["descending"], EIGEN_SLIPS["A left out"]):
        function = answers(EIGEN_HELPERS + textwrap.dedent(code), "my_eigenbasis")["my_eigenbasis"]
        feedback = lb.check_eigensolve(function, show=False)
        assert feedback.status == "wrong" and hint.lower() in feedback.message.lower(), feedback.message
        assert "first seen on" in feedback.message
    stub = answers(student_edition("03-eigensolve"), "my_eigenbasis")["my_eigenbasis"]
    assert lb.check_eigensolve(stub, show=False).status == "not attempted"
    assert lb.check_eigensolve(..., show=False).status == "not attempted"
    assert lb.check_eigensolve("eigsh", show=False).status == "wrong"   # never raises
    assert lb.check_eigensolve(lambda W, A, k: 1 / 0, show=False).status == "wrong"


# --- 03-convergence and 03-scaling (predictions) -------------------------------------------------

def test_convergence():
    _full("03-convergence", **answers(solution("03-convergence"), "error_drop"))
    for right in (4.0, np.int64(4), 2**2, "4"):
        _full("03-convergence", error_drop=right)
    _zero("03-convergence", "first order", error_drop=2)
    _zero("03-convergence", "drops", error_drop=0.25)
    _zero("03-convergence", "higher order", error_drop=8)
    _zero("03-convergence", "h^p", error_drop=3)
    _zero("03-convergence", status="not attempted", **answers(student_edition("03-convergence"), "error_drop"))


def test_scaling():
    _full("03-scaling", **answers(solution("03-scaling"), "eigenvalue_factor"))
    for right in (0.25, 2.0**-2, np.float64(1) / 4, 0.2500001):
        _full("03-scaling", eigenvalue_factor=right)
    _zero("03-scaling", "upside down", eigenvalue_factor=4)
    _zero("03-scaling", "1/length²", eigenvalue_factor=0.5)
    _zero("03-scaling", "isometry", eigenvalue_factor=1)
    _zero("03-scaling", "more digits", eigenvalue_factor=0.3)
    _zero("03-scaling", status="not attempted", **answers(student_edition("03-scaling"), "eigenvalue_factor"))


# --- 03-coefficients (compute) -------------------------------------------------------------------

@pytest.fixture(scope="module")
def blob():
    """The notebook's section 4 and 5: the bumpy blob, its 50 eigenpairs, Phi and A_blob."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    mesh = shapes.bumpy_sphere(4)
    spectrum = lbo.eigenbasis(mesh, 50)
    return {"blob": mesh, "blob_spectrum": spectrum, "Phi": spectrum.vectors, "A_blob": spectrum.mass}


def test_coefficients_solution_and_other_right_answers(blob):
    _full("03-coefficients", **answers(solution("03-coefficients"), "coefficients", **blob))
    for code in ("coefficients = (A_blob @ Phi).T @ f",
                 "coefficients = np.einsum('vi,v,v->i', Phi, A_blob.diagonal(), f)",
                 "w = np.sqrt(A_blob.diagonal())\ncoefficients = np.linalg.lstsq(w[:, None] * Phi, w * f, rcond=None)[0]",
                 "coefficients = [phi @ (A_blob @ f) for phi in Phi.T]",
                 "coefficients = (f @ A_blob @ Phi)[:, None]"):
        _full("03-coefficients", **answers("f = blob.vertices[:, 0]\n" + code, "coefficients", **blob))


def test_coefficients_wrong_answers(blob):
    def given(code):
        return answers("f = blob.vertices[:, 0]\n" + code, "coefficients", **blob)

    _zero("03-coefficients", "Euclidean", **given("coefficients = Phi.T @ f"))
    _zero("03-coefficients", "transpose", **given("coefficients = Phi @ (Phi.T @ (A_blob @ f))"))
    _zero("03-coefficients", "sign", **given("coefficients = -Phi.T @ (A_blob @ f)"))
    _zero("03-coefficients", "factor of two", **given("coefficients = 2 * Phi.T @ (A_blob @ f)"))
    _zero("03-coefficients", "divided", **given("coefficients = Phi.T @ (f / A_blob.diagonal())"))
    _zero("03-coefficients", "shape", **given("coefficients = Phi[:, :40].T @ (A_blob @ f)"))
    _zero("03-coefficients", "φ_iᵀ A f", **given("coefficients = np.linalg.solve(Phi.T @ Phi, Phi.T @ f)"))
    _zero("03-coefficients", "φ_iᵀ A f", **given("coefficients = Phi.T @ (A_blob @ blob.vertices[:, 1])"))
    _zero("03-coefficients", "array", coefficients={"c": 1})


def test_coefficients_placeholder_and_the_kernels_f(blob):
    _zero("03-coefficients", status="not attempted",
          **answers(student_edition("03-coefficients"), "coefficients", **blob))
    # The graded run rebuilds f itself: a student who changed f in the kernel is graded on the x coordinate.
    assert np.allclose(blob["blob_spectrum"].project(blob["blob"].vertices[:, 0]),
                       answers(solution("03-coefficients"), "coefficients", **blob)["coefficients"])


# --- 03-consistent (compute; its explanation is graded by a person) ------------------------------

def test_consistent():
    _full("03-consistent", **answers(solution("03-consistent"), "consistent_side",
                                     exact=_exact_sphere()))
    for right in (" Above ", "ABOVE"):
        _full("03-consistent", consistent_side=right)
    _zero("03-consistent", "lumped", consistent_side="below")
    _zero("03-consistent", "neither", consistent_side="equal")
    _zero("03-consistent", "one of", consistent_side="higher")
    _zero("03-consistent", status="not attempted",
          **answers(student_edition("03-consistent"), "consistent_side"))


def _exact_sphere():
    ell = np.repeat(np.arange(6), 2 * np.arange(6) + 1)
    return ell * (ell + 1.0)


def test_consistent_claim_of_the_notebook():
    """What the old hidden test asserted: on icosphere(3) the lumped eigenvalues of l = 2..5 lie below
    l(l+1), the consistent-mass ones above."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    sphere3, exact = shapes.icosphere(3), _exact_sphere()
    assert np.all(lbo.eigenbasis(sphere3, 36).values[4:] < exact[4:])
    assert np.all(lbo.eigenbasis(sphere3, 36, mass_kind="consistent").values[4:] > exact[4:])


# --- 03-kernel (explore; its explanation is graded by a person) ----------------------------------

def test_kernel():
    _full("03-kernel", **answers(solution("03-kernel"), "torus_zeros", "two_sphere_zeros"))
    _full("03-kernel", torus_zeros=1.0, two_sphere_zeros=2.0)
    _full("03-kernel", torus_zeros=np.int64(1), two_sphere_zeros=np.sum([True, True]))
    _zero("03-kernel", "handle", torus_zeros=2, two_sphere_zeros=2)           # one per genus
    _zero("03-kernel", "handle", torus_zeros=0, two_sphere_zeros=2)
    _zero("03-kernel", "each sphere", torus_zeros=1, two_sphere_zeros=1)
    _zero("03-kernel", "whole number", torus_zeros=1, two_sphere_zeros="two")
    _zero("03-kernel", "every part", torus_zeros=1, two_sphere_zeros=...)
    _zero("03-kernel", status="not attempted",
          **answers(student_edition("03-kernel"), "torus_zeros", "two_sphere_zeros"))


def test_kernel_claims_of_the_notebook():
    """What the old hidden test asserted: two disjoint spheres, two zero eigenvalues with null vectors
    constant on each sphere; the torus, one."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    ball = shapes.icosphere(2)
    two_spheres = lbo.Mesh(np.vstack([ball.vertices, ball.vertices + [3.0, 0.0, 0.0]]),
                           np.vstack([ball.faces, ball.faces + ball.n_vertices]))
    pair = lbo.eigenbasis(two_spheres, 6)
    assert two_spheres.n_components == 2 and np.sum(np.abs(pair.values) < 1e-8 * pair.values[2]) == 2
    null = pair.vectors[:, :2]
    spread = max(np.ptp(null[: ball.n_vertices], axis=0).max(), np.ptp(null[ball.n_vertices:], axis=0).max())
    assert spread < 1e-6 * np.abs(null).max()
    torus_values = lbo.eigenbasis(shapes.torus(), 5).values
    assert np.sum(np.abs(torus_values) < 1e-8 * torus_values[1]) == 1


# --- 03-lbo-recap (partial credit) ---------------------------------------------------------------

def test_recap_solution_and_other_right_answers():
    _full("03-lbo-recap", **answers(solution("03-lbo-recap"), "q1", "q2", "q3"))
    _full("03-lbo-recap", q1=0.0, q2=1.0, q3="B")
    _full("03-lbo-recap", q1=1 / np.tan(np.pi / 2), q2=np.int64(1), q3=" b ")


def test_recap_partial_credit():
    points, _, message = verdict("03-lbo-recap", q1=0, q2=4, q3="b")
    assert points == 2 and "Question 2" in message and "angles" in message
    points, _, message = verdict("03-lbo-recap", q1=1, q2=1, q3="a")
    assert points == 1 and "Euclidean" in message and "Question 2" not in message
    _zero("03-lbo-recap", "0 of 3", q1=0.5, q2=0.25, q3="c")
    _zero("03-lbo-recap", status="not attempted", **answers(student_edition("03-lbo-recap"), "q1", "q2", "q3"))


def test_recap_claim_of_the_notebook():
    """What the old hidden test asserted: scaling a mesh leaves W unchanged."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    blob = shapes.bumpy_sphere(4)
    assert np.allclose(lbo.stiffness_matrix(blob.with_vertices(2 * blob.vertices)).toarray(),
                       lbo.stiffness_matrix(blob).toarray())


def test_the_same_answer_gets_the_same_verdict():
    for exercise, payload in (("03-stiffness", SLIPS["no ½"][0]), ("03-mass", MASS_ANSWERS["mixed Voronoi, by hand"]),
                              ("03-stiffness", LIBRARY["igl"][0])):
        assert _judged(exercise, {"payload": payload}) == _judged(exercise, {"payload": payload})


def test_every_blocked_function_exists():
    """Each function the builds must not call resolves: the package's always, another library's
    wherever that library is installed (a misspelt entry would block nothing)."""
    import importlib.util

    from lbo_notebooks.exercises.grading import _registry, load_graders

    graders = load_graders("03-stiffness")
    for exercise in ("03-stiffness", "03-mass", "03-eigensolve"):
        for target in graders[exercise].replaces:
            module = target.partition(":")[0]
            installed = importlib.util.find_spec(module.split(".")[0]) is not None
            assert (_registry._resolve(target) is not None) == installed, target
