"""The graded tests of notebook 09 (spectral MDS, canonical forms) on answers the instructor did not
write: correct ones written differently earn full points, typical wrong ones and library calls in
the build exercise earn none, placeholders count as not attempted, and verdicts are deterministic."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from tests.grading_support import answers, assert_full, assert_zero, full_points, graded, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "09_spectral_mds.ipynb"


def solution(exercise: str) -> str:
    """The instructor's answer cell of ``exercise`` as a student who wrote it would run it."""
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    (cell,) = [c for c in cells if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    lines = "".join(cell["source"]).splitlines()
    return "\n".join(line for line in lines if not re.match(r"\s*### (BEGIN|END) SOLUTION", line))


full = assert_full
zero = assert_zero


def test_points_follow_the_kinds():
    exercises = ("09-memory", "09-classical-mds", "09-landmarks", "09-scaling", "09-fmm", "09-recap")
    assert {e: full_points(e) for e in exercises} == {
        "09-memory": 2, "09-classical-mds": 5, "09-landmarks": 1, "09-scaling": 5, "09-fmm": 1, "09-recap": 3}


# --- 09-memory -----------------------------------------------------------------------------------

def test_memory_right_answers():
    full("09-memory", **answers(solution("09-memory"), "classical_gb"))
    full("09-memory", **answers("gb = 2 * (50_000 * 50_000) * 8 * 1e-9\nclassical_gb = gb", "classical_gb"))
    full("09-memory", classical_gb=40)                          # by hand
    full("09-memory", classical_gb=np.float32(40.0))
    full("09-memory", classical_gb=np.array([40.0]))
    full("09-memory", classical_gb="40")


def test_memory_the_librarys_count_is_the_answer():
    """The claim the hidden test used to make: the library's count of an n x n matrix gives the answer
    (0.8 GB per matrix at 10,000 vertices is asserted in the notebook itself)."""
    from lbo_notebooks.analyses import distance_matrix_bytes

    assert 2 * distance_matrix_bytes(50_000, 50_000) / 1e9 == pytest.approx(40.0, rel=1e-12)
    code = ("from lbo_notebooks.analyses._geodesics import distance_matrix_bytes\n"
            "classical_gb = 2 * distance_matrix_bytes(50_000, 50_000) / 1e9")
    full("09-memory", **answers(code, "classical_gb"))


@pytest.mark.parametrize("value, hint", [
    (20.0, "two"),                      # one matrix
    (37.25, "GiB"),                     # 2^30 bytes
    (40e9, "bytes"),                    # not divided
    (5.0, "8 bytes"),                   # entries, not bytes
    (2.5, "entries of one matrix"),
    (0.0008, "n²"),                     # n, not n^2
    (41.5, "10⁹"),
])
def test_memory_wrong_answers(value, hint):
    zero("09-memory", hint, classical_gb=value)


def test_memory_not_a_number_and_placeholders():
    zero("09-memory", "number of gigabytes", classical_gb="forty")
    zero("09-memory", "number of gigabytes", classical_gb={"gb": 40})
    zero("09-memory", classical_gb=..., status="not attempted")
    zero("09-memory", **answers("classical_gb = ...  # GB", "classical_gb"), status="not attempted")


# --- 09-landmarks, 09-fmm ------------------------------------------------------------------------

@pytest.mark.parametrize("exercise, name, right, wrong", [
    ("09-landmarks", "landmark_verdict", ["less", "Less", " LESS ", np.str_("less")],
     [("more", "triangulation"), ("as", "interpolates nothing"), ("fewer", "one of"), (2, "one of")]),
    ("09-fmm", "fmm_verdict", ["farther", "Farther ", "FARTHER"],
     [("closer", "reference"), ("same", "other numbers"), ("further away", "one of"), (True, "one of")]),
])
def test_predictions(exercise, name, right, wrong):
    full(exercise, **answers(solution(exercise), name))
    for answer in right:
        full(exercise, **{name: answer})
    for answer, hint in wrong:
        zero(exercise, hint, **{name: answer})
    zero(exercise, **{name: ...}, status="not attempted")
    zero(exercise, **{name: None}, status="not attempted")


# --- 09-classical-mds: build it yourself ---------------------------------------------------------

MDS_RIGHT = {
    "scipy eigh with subset_by_index, J as a matrix": """
import scipy.linalg

def my_classical_mds(D, dim):
    n = D.shape[0]
    J = np.eye(n) - 1.0 / n
    B = -0.5 * J @ np.square(D) @ J
    w, U = scipy.linalg.eigh(B, subset_by_index=[n - dim, n - 1])
    w, U = w[::-1], U[:, ::-1]
    return U * np.sqrt(np.clip(w, 0, None))
""",
    "centring by means, argsort, a loop over columns": """
def my_classical_mds(D, dim):
    D2 = D * D
    B = -(D2 - D2.mean(0)[None, :] - D2.mean(1)[:, None] + D2.mean()) / 2
    w, V = np.linalg.eigh(B)
    order = np.argsort(w)[::-1][:dim]
    X = np.zeros((len(D), dim))
    for j, i in enumerate(order):
        X[:, j] = V[:, i] * max(w[i], 0.0) ** 0.5
    return X
""",
    "Lanczos (eigsh, which='LA'), a list of lists, another sign of each column": """
import scipy.sparse.linalg as sla

def my_classical_mds(D, dim):
    n = len(D)
    J = np.identity(n) - np.full((n, n), 1 / n)
    B = -0.5 * (J @ (D ** 2) @ J)
    w, U = sla.eigsh(B, k=dim, which="LA", v0=np.ones(n))
    idx = np.argsort(-w)
    X = -U[:, idx] * np.sqrt(np.maximum(w[idx], 0))
    return X.tolist()
""",
    "an SVD of the double-centred matrix, then signs from B": """
def my_classical_mds(D, dim):
    n = len(D)
    J = np.eye(n) - np.ones((n, n)) / n
    B = -0.5 * J @ D**2 @ J
    w, U = np.linalg.eigh(B)
    w, U = w[::-1][:dim], U[:, ::-1][:, :dim]
    return U @ np.diag(np.sqrt(np.where(w > 0, w, 0.0))) + 7.0  # a translation is the same embedding
""",
}

_MDS_BASE = """
def my_top(B, dim):
    w, U = np.linalg.eigh(B)
    return w[::-1][:dim], U[:, ::-1][:, :dim]

def my_centre(M):
    n = len(M)
    J = np.eye(n) - 1 / n
    return J @ M @ J
"""

MDS_SLIPS = {
    "distances not squared": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D), dim)
    return U * np.sqrt(np.maximum(w, 0))
""", "squared"),
    "no ½": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-my_centre(D**2), dim)
    return U * np.sqrt(np.maximum(w, 0))
""", "√2"),
    "smallest eigenpairs": ("""
def my_classical_mds(D, dim):
    w, U = np.linalg.eigh(-0.5 * my_centre(D**2))
    return U[:, :dim] * np.sqrt(np.abs(w[:dim]))
""", "smallest"),
    "no double centring": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * D**2, dim)
    return U * np.sqrt(np.maximum(w, 0))
""", "double-centred"),
    "no square root": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D**2), dim)
    return U * np.maximum(w, 0)
""", "square-rooted"),
    "eigenvectors only": ("""
def my_classical_mds(D, dim):
    return my_top(-0.5 * my_centre(D**2), dim)[1]
""", "scaled by the square root"),
    "absolute values, not clipped": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D**2), dim)
    return U * np.sqrt(np.abs(w))
""", "absolute value"),
    "largest in magnitude": ("""
def my_classical_mds(D, dim):
    w, U = np.linalg.eigh(-0.5 * my_centre(D**2))
    idx = np.argsort(-np.abs(w))[:dim]
    return U[:, idx] * np.sqrt(np.maximum(w[idx], 0))
""", "magnitude"),
    "not clipped": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D**2), dim)
    return U * np.sqrt(w)
""", "clip"),
    "transposed": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D**2), dim)
    return (U * np.sqrt(np.maximum(w, 0))).T
""", "transposed"),
    "a fixed 3": ("""
def my_classical_mds(D, dim):
    w, U = my_top(-0.5 * my_centre(D**2), 3)
    return U * np.sqrt(np.maximum(w, 0))
""", "`dim` argument"),
}

MDS_LIBRARY = {
    "classical_mds itself": ("my_classical_mds = lbo.classical_mds", "classical_mds"),
    "a wrapper": ("""
from lbo_notebooks.analyses import classical_mds

def my_classical_mds(D, dim):
    return np.array(classical_mds(D, dim=dim))
""", "classical_mds"),
    "landmark MDS with every point a landmark": ("""
def my_classical_mds(D, dim):
    return lbo.analyses.landmark_mds(D, dim, landmarks=np.arange(len(D)))
""", "landmark_mds"),
    "the library's top eigenpairs": ("""
from lbo_notebooks.analyses._classical_scaling import top_eigenpairs

def my_classical_mds(D, dim):
    n = len(D)
    J = np.eye(n) - 1 / n
    w, U = top_eigenpairs(-0.5 * J @ D**2 @ J, dim)
    return U * np.sqrt(np.maximum(w, 0))
""", "top_eigenpairs"),
    "scaling in a span": ("""
from lbo_notebooks.analyses import _classical_scaling as scaling

def my_classical_mds(D, dim):
    n = len(D)
    J = np.eye(n) - 1 / n
    y, _ = scaling.scaling_in_span(J.T @ J, -0.5 * D**2, dim)
    return J @ y
""", "scaling_in_span"),
    "the visible check's reference": ("""
from lbo_notebooks.exercises import canonical_forms

my_classical_mds = lambda D, dim: canonical_forms.mds_slips(D, dim)[0]
""", "mds_slips"),
    "scikit-learn ClassicalMDS": ("""
from sklearn.manifold import ClassicalMDS

def my_classical_mds(D, dim):
    return ClassicalMDS(n_components=dim, metric="precomputed").fit_transform(D)
""", "ClassicalMDS"),
    "scikit-learn KernelPCA": ("""
from sklearn.decomposition import KernelPCA

def my_classical_mds(D, dim):
    n = len(D)
    J = np.eye(n) - 1 / n
    return KernelPCA(n_components=dim, kernel="precomputed").fit_transform(-0.5 * J @ D**2 @ J)
""", "KernelPCA"),
}


def test_classical_mds_solution():
    message = full("09-classical-mds", **answers(solution("09-classical-mds"), "my_classical_mds"))
    assert "does not show" in message


@pytest.mark.parametrize("name", list(MDS_RIGHT))
def test_classical_mds_written_differently(name):
    full("09-classical-mds", **answers(MDS_RIGHT[name], "my_classical_mds"))


@pytest.mark.parametrize("name", list(MDS_SLIPS))
def test_classical_mds_slips(name):
    code, hint = MDS_SLIPS[name]
    message = zero("09-classical-mds", hint, **answers(_MDS_BASE + code, "my_classical_mds"))
    assert "does not show" in message or name in ("transposed", "a fixed 3", "not clipped")


@pytest.mark.parametrize("name", list(MDS_LIBRARY))
def test_classical_mds_library_calls(name):
    code, where = MDS_LIBRARY[name]
    zero("09-classical-mds", "build it yourself", "not available", where, **answers(code, "my_classical_mds"))


def test_classical_mds_placeholders_and_odd_answers():
    stub = re.sub(r"(?ms)^([ \t]*)### BEGIN SOLUTION.*?### END SOLUTION[^\n]*", "",
                  "".join(json.loads(NOTEBOOK.read_text())["cells"][[
                      i for i, c in enumerate(json.loads(NOTEBOOK.read_text())["cells"])
                      if c["metadata"].get("nbgrader", {}).get("grade_id") == "09-classical-mds-answer"][0]]["source"]))
    zero("09-classical-mds", status="not attempted", **answers(stub, "my_classical_mds"))
    zero("09-classical-mds", status="not attempted", my_classical_mds=...)
    zero("09-classical-mds", "zeros", **answers("def my_classical_mds(D, dim):\n    return np.zeros((len(D), dim))",
                                                "my_classical_mds"))
    zero("09-classical-mds", "ZeroDivisionError", **answers("def my_classical_mds(D, dim):\n    return 1 / 0",
                                                            "my_classical_mds"))


def test_classical_mds_cases_are_determined_and_the_librarys():
    """Every graded case ends each dim below a gap (or among clipped eigenvalues), has the promised
    kinds (exactly embeddable, negative eigenvalues, repeated eigenvalues), and the reference is the
    library's classical MDS; every blocked function resolves."""
    from lbo_notebooks.analyses import gram_error
    from lbo_notebooks.exercises import canonical_forms
    from lbo_notebooks.exercises.grading import _registry, load_graders, nb09
    from lbo_notebooks.analyses import classical_mds

    negative = repeated = 0
    for D, dims, _ in nb09._mds_cases():
        G = np.linalg.eigvalsh(canonical_forms._double_centred(D**2))[::-1]
        negative += G[-1] < -1e-6 * G[0]
        repeated += np.any(np.abs(np.diff(G[:max(dims)])) < 1e-9 * G[0])
        for dim in dims:
            assert G[dim - 1] <= 1e-9 * G[0] or G[dim - 1] > 1.2 * G[dim], (dims, G[:dim + 1])
            ref, slips = canonical_forms.mds_slips(D, dim)
            assert gram_error(classical_mds(D, dim), ref) < 1e-10
            assert slips
    assert negative >= 3 and repeated >= 2
    for target in load_graders("09-classical-mds")["09-classical-mds"].replaces:
        assert _registry._resolve(target) is not None, target


def test_classical_mds_graded_run():
    given = answers(MDS_RIGHT["centring by means, argsort, a loop over columns"], "my_classical_mds")
    assert verdict("09-classical-mds", **given) == verdict("09-classical-mds", **given)
    assert graded("09-classical-mds", **given) == 5.0
    import lbo_notebooks as lbo

    assert graded("09-classical-mds", my_classical_mds=lbo.classical_mds) == 0.0


def test_classical_mds_visible_check():
    from lbo_notebooks.exercises import canonical_forms
    from lbo_notebooks.analyses import classical_mds

    right = answers(solution("09-classical-mds"), "my_classical_mds")["my_classical_mds"]
    assert canonical_forms.check_classical_mds(right, show=False).correct
    assert canonical_forms.check_classical_mds(lambda D, dim: classical_mds(D, dim), show=False).correct
    slip = answers(_MDS_BASE + MDS_SLIPS["no ½"][0], "my_classical_mds")["my_classical_mds"]
    feedback = canonical_forms.check_classical_mds(slip, show=False)
    assert feedback.status == "wrong" and "√2" in feedback.message
    assert canonical_forms.check_classical_mds(..., show=False).status == "not attempted"
    assert canonical_forms.check_classical_mds(42, show=False).status == "wrong"


# --- 09-scaling: build it yourself ---------------------------------------------------------------

SVD_ROUTE = """
import scipy.linalg

def my_scaling(phi, alpha, dim):
    centred = phi - phi.mean(axis=0, keepdims=True)
    left, s, right_t = np.linalg.svd(centred, full_matrices=False)     # J Phi = Q R with Q = left
    R = s[:, None] * right_t
    small = -0.5 * R @ alpha @ R.T
    k = small.shape[0]
    values, vectors = scipy.linalg.eigh(small, subset_by_index=[k - dim, k - 1])
    order = np.argsort(values)[::-1]
    return left @ vectors[:, order] * np.sqrt(values[order])
"""

GRAM_ROUTE = """
def top(matrix, m):
    w, v = np.linalg.eigh((matrix + matrix.T) / 2)
    idx = np.argsort(-w)[:m]
    return w[idx], v[:, idx]

def my_scaling(phi, alpha, dim):
    n = phi.shape[0]
    J = np.eye(n) - np.ones((n, n)) / n
    C = J @ phi
    s, V = np.linalg.eigh(C.T @ C)                 # R = S^(1/2) V^T, Q = C V S^(-1/2)
    keep = s > 1e-10 * s.max()
    s, V = s[keep], V[:, keep]
    R = np.sqrt(s)[:, None] * V.T
    Q = C @ V / np.sqrt(s)
    g, u = top(-0.5 * R @ alpha @ R.T, dim)
    X = np.zeros((n, dim))
    for j in range(dim):                           # one column at a time
        X[:, j] = np.sqrt(g[j]) * (Q @ u[:, j])
    return X
"""


def _slip(**change):
    """The solution with one typical slip, as answer-cell source."""
    centre = "phi - phi.mean(axis=0)" if change.get("centre", True) else "phi"
    factor = change.get("factor", "-0.5")
    small = "R.T @ alpha @ R" if change.get("transpose") else "R @ alpha @ R.T"
    order = "" if change.get("smallest") else "[::-1]"
    order_u = "" if change.get("smallest") else "[:, ::-1]"
    power = change.get("power", "np.sqrt(np.abs(G))")
    back = change.get("back", "Q")
    dim = change.get("dim", "dim")
    return f"""
def my_scaling(phi, alpha, dim):
    Q, R = np.linalg.qr({centre})
    G, U = np.linalg.eigh({factor} * ({small}))
    G, U = G{order}[:{dim}], U{order_u}[:, :{dim}]
    return {back} @ (U * {power})
"""


@pytest.fixture(scope="module")
def library_context():
    """The notebook's setting in small: the paper's form on a 1,000-vertex dog (phi, alpha, X_rows)."""
    from lbo_notebooks import eigenbasis
    from lbo_notebooks.shapes import _creatures as creatures
    from lbo_notebooks.analyses import spectral_mds

    dog = creatures.creature("dog", "walking", n_vertices=1000)
    spectrum = eigenbasis(dog, 40)
    X_rows, info = spectral_mds(dog, k=40, n_samples=60, sampled="rows", spectrum=spectrum, return_details=True)
    return spectrum.vectors[:, :40], info["alpha"], X_rows


def test_scaling_solution_is_the_librarys_embedding(library_context):
    """The claim the hidden test used to make (the solution reproduces the library's X_rows), and the
    grader's references are the library's embeddings on its unseen inputs."""
    from lbo_notebooks.analyses import gram_error
    from lbo_notebooks.exercises import canonical_forms
    from lbo_notebooks.exercises.grading import nb09
    from lbo_notebooks.analyses._classical_scaling import scaling_in_span

    phi, alpha, X_rows = library_context
    my_scaling = answers(solution("09-scaling"), "my_scaling")["my_scaling"]
    assert gram_error(my_scaling(phi, alpha, 3), X_rows) < 1e-8
    for _, phi, alpha, dims in nb09._scaling_cases():
        for dim in dims:
            m = phi.mean(axis=0)
            y, G = scaling_in_span(phi.T @ phi - len(phi) * np.outer(m, m), -0.5 * alpha, dim)
            assert G[dim - 1] > 1.15 * max(G[dim], 0.0) and G[dim - 1] > 0     # the top dim are well defined
            assert gram_error(canonical_forms.scaling_slips(phi, alpha, dim)[0], phi @ y) < 1e-10


def test_scaling_right_answers():
    full("09-scaling", **answers(solution("09-scaling"), "my_scaling"))
    full("09-scaling", **answers(SVD_ROUTE, "my_scaling"))
    full("09-scaling", **answers(GRAM_ROUTE, "my_scaling"))
    full("09-scaling", **answers(_slip(), "my_scaling"))          # |G|^(1/2): the same where G > 0


@pytest.mark.parametrize("slip, hint", [
    ({"centre": False}, "double-centred"),
    ({"factor": "-1.0"}, "factor √2"),
    ({"factor": "0.5"}, "wrong sign"),
    ({"smallest": True}, "smallest eigenpairs"),
    ({"power": "np.abs(G)"}, "square-rooted"),
    ({"power": "1 / np.sqrt(np.abs(G))"}, "G_m^(-½)"),
    ({"transpose": True}, "transpose"),
    ({"back": "(phi - phi.mean(axis=0))"}, "maps back with Q"),
    ({"dim": "3"}, "`dim` argument"),
])
def test_scaling_typical_slips(slip, hint):
    message = zero("09-scaling", hint, **answers(_slip(**slip), "my_scaling"))
    assert "notebook does not show" in message or "dim" in message


def test_scaling_other_wrong_answers():
    A = "def my_scaling(phi, alpha, dim):\n    "
    zero("09-scaling", "transposed", **answers(A + f"return ({_slip_expr()}).T", "my_scaling"))
    zero("09-scaling", "coefficients", **answers(A + "return np.ones((phi.shape[1], dim))", "my_scaling"))
    zero("09-scaling", "nan", **answers(A + "return np.full((len(phi), dim), np.nan)", "my_scaling"))
    zero("09-scaling", "zeros", **answers(A + "return np.zeros((len(phi), dim))", "my_scaling"))
    zero("09-scaling", "Q R, B̃", **answers(A + f"return 1.1 * ({_slip_expr()})", "my_scaling"))
    zero("09-scaling", "array", **answers(A + "return 'x'", "my_scaling"))
    zero("09-scaling", "ZeroDivisionError", **answers(A + "return 1 / 0", "my_scaling"))
    zero("09-scaling", "Pass the function", my_scaling=np.zeros((3, 3)))


def _slip_expr() -> str:
    return ("(lambda Q, R: Q @ (lambda G, U: U[:, ::-1][:, :dim] * np.sqrt(G[::-1][:dim]))"
            "(*np.linalg.eigh(-0.5 * R @ alpha @ R.T)))(*np.linalg.qr(phi - phi.mean(axis=0)))")


def test_scaling_placeholders():
    zero("09-scaling", my_scaling=..., status="not attempted")
    stub = 'def my_scaling(phi, alpha, dim):\n    """..."""\n    # YOUR CODE HERE\n    raise NotImplementedError()'
    zero("09-scaling", **answers(stub, "my_scaling"), status="not attempted")
    zero("09-scaling", **answers("def my_scaling(phi, alpha, dim):\n    pass", "my_scaling"), status="not attempted")


@pytest.mark.parametrize("code", [
    # the library's small eigenproblem, imported by name
    """
from lbo_notebooks.analyses._classical_scaling import scaling_in_span

def my_scaling(phi, alpha, dim):
    m = phi.mean(axis=0)
    y, _ = scaling_in_span(phi.T @ phi - len(phi) * np.outer(m, m), -0.5 * alpha, dim)
    return phi @ y
""",
    # the same through the package's attributes (as spectral_mds reaches it)
    """
def my_scaling(phi, alpha, dim):
    m = phi.mean(axis=0)
    y, _ = lbo.analyses._classical_scaling.scaling_in_span(phi.T @ phi - len(phi) * np.outer(m, m), -0.5 * alpha, dim)
    return phi @ y
""",
    # own QR, the library's top eigenpairs
    """
from lbo_notebooks.analyses import _classical_scaling as scaling

def my_scaling(phi, alpha, dim):
    Q, R = np.linalg.qr(phi - phi.mean(axis=0))
    G, U = scaling.top_eigenpairs(-0.5 * R @ alpha @ R.T, dim)
    return Q @ (U * np.sqrt(G))
""",
    # the visible check's reference
    """
from lbo_notebooks.exercises import canonical_forms

def my_scaling(phi, alpha, dim):
    return canonical_forms.scaling_slips(phi, alpha, dim)[0]
""",
    # classical MDS of the n x n matrix Phi alpha Phi^T
    """
from lbo_notebooks.analyses import classical_mds

def my_scaling(phi, alpha, dim):
    D2 = phi @ alpha @ phi.T
    return classical_mds(np.sqrt(np.maximum((D2 + D2.T) / 2, 0)), dim=dim)
""",
    # the library first, its own (right) code when that fails: still a library call
    """
from lbo_notebooks.analyses._classical_scaling import scaling_in_span

def my_scaling(phi, alpha, dim):
    try:
        m = phi.mean(axis=0)
        return phi @ scaling_in_span(phi.T @ phi - len(phi) * np.outer(m, m), -0.5 * alpha, dim)[0]
    except Exception:
        Q, R = np.linalg.qr(phi - phi.mean(axis=0))
        G, U = np.linalg.eigh(-0.5 * (R @ alpha @ R.T))
        return Q @ (U[:, ::-1][:, :dim] * np.sqrt(G[::-1][:dim]))
""",
    # scikit-learn's classical MDS of the n x n distances
    """
from sklearn.manifold import ClassicalMDS

def my_scaling(phi, alpha, dim):
    D2 = phi @ alpha @ phi.T
    D = np.sqrt(np.maximum((D2 + D2.T) / 2, 0))
    return ClassicalMDS(n_components=dim, metric="precomputed").fit_transform(D)
""",
    # scikit-learn's kernel PCA of B = -1/2 J Phi alpha Phi^T J
    """
from sklearn.decomposition import KernelPCA

def my_scaling(phi, alpha, dim):
    C = phi - phi.mean(axis=0)
    return KernelPCA(n_components=dim, kernel="precomputed").fit_transform(-0.5 * C @ alpha @ C.T)
""",
], ids=["scaling_in_span", "lbo.analyses._classical_scaling.scaling_in_span", "top_eigenpairs", "check's reference", "classical_mds",
        "caught", "sklearn ClassicalMDS", "sklearn KernelPCA"])
def test_scaling_library_calls_earn_nothing(code):
    zero("09-scaling", "build it yourself", "not available", **answers(code, "my_scaling"))


def test_scaling_blocked_functions_resolve():
    from lbo_notebooks.exercises.grading import _registry, load_graders

    for target in load_graders("09-scaling")["09-scaling"].replaces:
        assert _registry._resolve(target) is not None, target


def test_scaling_is_deterministic_and_graded_in_a_fresh_process():
    given = answers(SVD_ROUTE, "my_scaling")
    assert verdict("09-scaling", **given) == verdict("09-scaling", **given)
    assert graded("09-scaling", **given) == 5.0
    assert graded("09-scaling", **answers(_slip(factor="0.5"), "my_scaling")) == 0.0


# --- 09-recap ------------------------------------------------------------------------------------

def test_recap_prompt_matches_the_library():
    """The claim the hidden test used to make: the prompt's defaults (k = 200, q = 300, fields) are
    the library's, so the small eigenproblem has k + q rows (section 3's separation of the species
    is asserted in the notebook itself)."""
    from lbo_notebooks.analyses import SMDS_DEFAULTS

    assert (SMDS_DEFAULTS["k"], SMDS_DEFAULTS["n_samples"], SMDS_DEFAULTS["sampled"]) == (200, 300, "fields")


def test_recap_right_answers():
    full("09-recap", **answers(solution("09-recap"), "q1", "q2", "q3"))
    full("09-recap", q1=500.0, q2="Orthogonal Map", q3=" canonical  forms")
    full("09-recap", **answers("q1 = 200 + 300\nq2 = 'orthogonal map'\nq3 = 'Canonical forms'", "q1", "q2", "q3"))
    full("09-recap", q1=np.int64(500), q2=np.str_("orthogonal map"), q3="CANONICAL FORMS")


@pytest.mark.parametrize("given, expected, words", [
    ((200, "orthogonal map", "canonical forms"), 2.0, ["question 1", "projected rows"]),
    ((250_000, "orthogonal map", "canonical forms"), 2.0, ["question 1", "side"]),
    ((500, "rigid motion", "canonical forms"), 2.0, ["question 2", "mirror"]),
    ((500, "scaling", "both"), 1.0, ["question 2", "question 3"]),
    ((300, "nothing", "raw poses"), 0.0, ["0 of 3"]),
    ((500, ..., "canonical forms"), 2.0, ["question 2", "not answered"]),
    (("five hundred", "orthogonal map", "canonical forms"), 2.0, ["question 1", "expected"]),
])
def test_recap_partial_credit(given, expected, words):
    points, _, message = verdict("09-recap", **dict(zip(("q1", "q2", "q3"), given)))
    assert points == expected, (given, message)
    for word in words:
        assert word in message.lower(), (word, message)
    for answer, right in zip(given, ("500", "orthogonal map", "canonical forms")):
        if str(answer) != right:                                # hints of the wrong ones, never the right answers
            assert right not in message.lower(), (right, message)


def test_recap_placeholders_and_odd_values():
    zero("09-recap", q1=..., q2=..., q3=..., status="not attempted")
    zero("09-recap", **answers("q1 = ...\nq2 = ...\nq3 = ...", "q1", "q2", "q3"), status="not attempted")
    points, _, _ = verdict("09-recap", q1=[500], q2={"a": 1}, q3=object())
    assert points == 1.0                                        # a one-element list is a number; the rest wrong
