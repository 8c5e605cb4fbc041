"""The graded tests of notebook 11 (regularized PCA), with answers written as students write them:
the instructor's solution, correct answers written differently, typical wrong ones, library calls
in the build exercise, placeholders (the student edition); see
lbo_notebooks/exercises/grading/nb11.py. The notebook claims that used to sit in the hidden tests
(the interlacing of the PCA limit's energies, the validation choice that moves by at most a decade)
are tests of the library here."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, cell, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "11_regularized_pca.ipynb"
EXERCISES = {"11-energy": "compute", "11-limits": "predict", "11-validation": "compute", "11-scale": "predict",
             "11-objective": "build", "11-rpca-basis": "build", "11-recap": "recap"}


def _cells() -> list[dict]:
    return json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def kernel():
    """The notebook's kernel after sections 2-4, restated from its cells (not the grader's rebuild)."""
    import lbo_notebooks as lbo
    from lbo_notebooks.spectral import reconstruction_error
    from lbo_notebooks.analyses import RegularizedPCA

    poses = lbo.creature_poses("dog", n_vertices=3000)
    reference = poses["standing"]
    W, A = lbo.stiffness_matrix(reference), lbo.mass_matrix(reference)
    train, validation = ["standing", "walking"], "galloping"
    unseen = [name for name in poses if name not in train + [validation]]
    X = np.hstack([poses[name].vertices for name in train])
    m = 100
    solver = RegularizedPCA(X, W, A, center=True)
    pca = solver.solve(m, 0.0)
    lbo_spectrum = lbo.eigenbasis((W, A), m)
    betas = [1e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 1e-2, 0.1, 0.9]
    results = dict(zip(betas, solver.sweep(m, betas=betas)))
    targets = [poses[name].vertices for name in unseen]
    val_error = {b: reconstruction_error(r.basis, A, poses[validation].vertices) for b, r in results.items()}
    errors = {b: reconstruction_error(r.basis, A, targets) for b, r in results.items()}
    return {"W": W, "A": A, "m": m, "pca": pca, "lam": lbo_spectrum.values, "lbo_basis": lbo_spectrum.vectors,
            "betas": betas, "results": results, "unseen": unseen, "errors": errors,
            "err_lbo": reconstruction_error(lbo_spectrum.vectors, A, targets), "best": min(betas, key=val_error.get),
            "solver": solver}


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    from lbo_notebooks.exercises.grading import POINTS

    assert {e: full_points(e) for e in EXERCISES} == {e: POINTS[k] for e, k in EXERCISES.items()}


def test_check_cells_grade_by_the_prompts_names():
    """Each check cell keeps its visible check, then grades with the names its grader takes (and the
    prompt names), as its last expression, for the points of its kind; no assert left in it."""
    from lbo_notebooks.exercises.grading import load_graders

    graders = load_graders("11-energy")
    cells = _cells()
    for exercise in EXERCISES:
        (check,) = [c for c in cells if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-check"]
        text = "".join(check["source"])
        assert text.startswith("feedback = exercises.check_"), exercise
        hidden = text.split("### BEGIN HIDDEN TESTS\n", 1)[1]
        names = graders[exercise].names
        call = f'grade("{exercise}", ' + ", ".join(f"{n}={n}" for n in names) + ")"
        assert hidden == f"from lbo_notebooks.exercises.grading import grade\n\n{call}\n### END HIDDEN TESTS", exercise
        assert check["metadata"]["nbgrader"]["points"] == graders[exercise].points
        (prompt,) = [c for c in cells if c["cell_type"] == "markdown" and f"**Exercise {exercise}**" in "".join(c["source"])]
        for name in names:
            assert f"`{name}" in "".join(prompt["source"]), (exercise, name)


@pytest.mark.parametrize("exercise", list(EXERCISES))
def test_the_student_edition_is_not_attempted(exercise, kernel):
    names = {"11-energy": ["energies"], "11-limits": ["limit_at_0", "limit_at_1", "best_beta"],
             "11-validation": ["chosen_beta", "beats_by_four"], "11-scale": ["mu_factor"],
             "11-objective": ["my_objective"], "11-rpca-basis": ["my_rpca_basis"], "11-recap": ["q1", "q2", "q3"]}[exercise]
    given = answers(student_edition(exercise), *names, **kernel)
    _zero(exercise, "not attempted", status="not attempted", **given)


# --- 11-energy (compute) -----------------------------------------------------------------------------

RIGHT_ENERGIES = {
    "the diagonal of Pᵀ W P": "energies = np.diag(pca.basis.T @ (W @ pca.basis))",
    "a list, one column at a time": "energies = [p @ (W @ p) for p in pca.basis.T]",
    "the library's Dirichlet energy, as a column": "energies = lbo.dirichlet_energy(W, pca.basis)[:, None]",
    "sparse times dense, summed": "WP = W @ pca.basis\nenergies = (pca.basis * WP).sum(axis=0)",
}


def test_energy_solution_and_alternatives(kernel):
    _full("11-energy", **answers(solution("11-energy"), "energies", **kernel))
    for name, code in RIGHT_ENERGIES.items():
        _full("11-energy", **answers(code, "energies", **kernel))


@pytest.mark.parametrize("code, hint", [
    ("energies = np.einsum('ij,ij->j', pca.basis, A @ pca.basis)", "A-norm"),
    ("energies = 0.5 * np.einsum('ij,ij->j', pca.basis, W @ pca.basis)", "factor of two"),
    ("energies = np.sqrt(np.abs(np.einsum('ij,ij->j', pca.basis, W @ pca.basis)))", "square root"),
    ("energies = pca.basis.T @ (W @ pca.basis)", "diagonal"),
    ("energies = np.einsum('ij,ij->j', lbo_basis, W @ lbo_basis)", "einsum"),      # another basis
    ("energies = np.einsum('ij,ij->j', pca.basis, W @ pca.basis)[:6]", "one energy per column"),
    ("energies = {'p0': 1.0}", "expected"),
])
def test_energy_wrong_answers(kernel, code, hint):
    _zero("11-energy", hint, **answers(code, "energies", **kernel))


def test_pca_limit_energies_interlace_with_the_eigenvalues(kernel):
    """The claim of section 3 (it was in 11-energy's hidden test): the 7th function is the constant,
    and the 94 extra energies interlace with the eigenvalues (Cauchy)."""
    pca, W, lam, m = kernel["pca"], kernel["W"], kernel["lam"], kernel["m"]
    energies = np.einsum("ij,ij->j", pca.basis, W @ pca.basis)
    tol = 1e-8 * lam[-1]
    assert abs(energies[6]) < tol
    j = np.arange(m - 6)
    assert np.all(lam[j] - tol <= energies[6 + j]) and np.all(energies[6 + j] <= lam[j + 6] + tol)


# --- 11-limits, 11-scale (predictions) ----------------------------------------------------------------

def test_limits():
    _full("11-limits", **answers(solution("11-limits"), "limit_at_0", "limit_at_1", "best_beta"))
    _full("11-limits", limit_at_0="PCA + Smooth", limit_at_1="EIGENBASIS", best_beta=" intermediate")
    _full("11-limits", limit_at_0="pca+smooth", limit_at_1="eigen basis", best_beta="Intermediate")
    _zero("11-limits", "94", limit_at_0="pca (6)", limit_at_1="eigenbasis", best_beta="intermediate")
    _zero("11-limits", "which end", limit_at_0="eigenbasis", limit_at_1="pca + smooth", best_beta="intermediate")
    _zero("11-limits", "each end", limit_at_0="pca + smooth", limit_at_1="eigenbasis", best_beta="small")
    _zero("11-limits", "μ → ∞", limit_at_0="pca + smooth", limit_at_1="pca (6)", best_beta="intermediate")
    _zero("11-limits", "one of", limit_at_0=0, limit_at_1=1, best_beta=0.5)
    _zero("11-limits", "every part", limit_at_0="pca + smooth", limit_at_1=..., best_beta="intermediate")


def test_scale():
    _full("11-scale", **answers(solution("11-scale"), "mu_factor"))
    for right in (64, 64.0, np.float64(64.0), 2.0**6, "64", np.array(64)):
        _full("11-scale", mu_factor=right)
    for wrong, hint in ((16, "s_B alone"), (1 / 64, "upside down"), (1, "dimensionless"), (32, "powers"),
                        (4, "both"), ("sixty-four", "a number")):
        _zero("11-scale", hint, mu_factor=wrong)


# --- 11-validation (compute) ---------------------------------------------------------------------------

RIGHT_VALIDATIONS = {
    "a loop and np.all": """
        i = unseen.index("tail_raised")
        best_err, chosen_beta = np.inf, None
        for b in betas:
            if errors[b][i] < best_err:
                best_err, chosen_beta = errors[b][i], b
        others = [0, 1, 2]
        others.remove(i)
        beats_by_four = all(errors[chosen_beta][j] * 4 < err_lbo[j] for j in others)
    """,
    "an argmin over an array, NumPy's bool": """
        col = unseen.index("tail_raised")
        table = np.array([errors[b] for b in betas])
        chosen_beta = betas[int(np.argmin(table[:, col]))]
        mask = np.arange(len(unseen)) != col
        beats_by_four = np.all(table[betas.index(chosen_beta), mask] < err_lbo[mask] / 4)
    """,
    "typed by hand": """
        chosen_beta = 0.001
        beats_by_four = "yes"
    """,
}


def test_validation_solution_and_alternatives(kernel):
    _full("11-validation", **answers(solution("11-validation"), "chosen_beta", "beats_by_four", **kernel))
    for name, code in RIGHT_VALIDATIONS.items():
        _full("11-validation", **answers(code, "chosen_beta", "beats_by_four", **kernel))


def test_validation_wrong_answers(kernel):
    errors, unseen, betas = kernel["errors"], kernel["unseen"], kernel["betas"]
    i = unseen.index("tail_raised")
    others = [j for j in range(3) if j != i]
    right = min(betas, key=lambda b: errors[b][i])
    on_others = min(betas, key=lambda b: np.mean([errors[b][j] for j in others]))
    assert on_others != right
    _zero("11-validation", "largest", chosen_beta=max(betas, key=lambda b: errors[b][i]), beats_by_four=True)
    _zero("11-validation", "alone", chosen_beta=on_others, beats_by_four=True)  # best elsewhere
    _zero("11-validation", "a quarter", chosen_beta=right, beats_by_four=False)
    _zero("11-validation", "swept", chosen_beta=5e-4, beats_by_four=True)
    _zero("11-validation", "not the β", chosen_beta=betas[betas.index(right) - 1], beats_by_four=True)  # a neighbour
    _zero("11-validation", "True or False", chosen_beta=right, beats_by_four="perhaps")
    _zero("11-validation", "one of the swept", chosen_beta={"beta": right}, beats_by_four=True)


def test_validation_choice_moves_by_at_most_a_decade(kernel):
    """The claim of 11-validation's solution (it was in its hidden test): chosen on tail_raised
    instead of galloping, β moves by at most a decade, and the factor of four survives."""
    errors, unseen, betas, err_lbo = kernel["errors"], kernel["unseen"], kernel["betas"], kernel["err_lbo"]
    i = unseen.index("tail_raised")
    chosen = min(betas, key=lambda b: errors[b][i])
    others = [j for j in range(3) if j != i]
    assert 0.1 <= chosen / kernel["best"] <= 10
    assert np.all(errors[chosen][others] < err_lbo[others] / 4)


# --- 11-objective (build it yourself) --------------------------------------------------------------------

RIGHT_OBJECTIVES = {
    "the closed form of section 1 (A-orthonormal P)": """
        def my_objective(P, X, W, A, mu):
            B = P.T @ (A @ X)
            return np.trace(X.T @ (A @ X)) - np.sum(B**2) + mu * np.trace(P.T @ (W @ P))
    """,
    "a loop over the data and the basis, dense matrices": """
        def my_objective(basis, data, stiff, mass, weight):
            Ad, Wd = mass.toarray(), stiff.toarray()
            total = 0.0
            for x in data.T:
                r = basis @ (basis.T @ (Ad @ x)) - x
                total += r @ Ad @ r
            for p in basis.T:
                total += weight * (p @ Wd @ p)
            return total
    """,
    "einsum, the library's Dirichlet energy": """
        def my_objective(P, X, W, A, mu):
            coefficients = np.einsum("ni,nc->ic", P, A @ X)
            residual = X - P @ coefficients
            return float(np.einsum("nc,nc->", residual, A @ residual) + mu * lbo.dirichlet_energy(W, P).sum())
    """,
}


def test_objective_solution_and_alternatives():
    message = _full("11-objective", **answers(solution("11-objective"), "my_objective"))
    assert "does not show" in message
    for name, code in RIGHT_OBJECTIVES.items():
        _full("11-objective", **answers(code, "my_objective"))


WRONG_OBJECTIVES = {
    "Euclidean norm": ("R = P @ (P.T @ (A @ X)) - X\n    return np.sum(R * R) + mu * np.sum(P * (W @ P))", "Euclidean norm"),
    "Euclidean projection": ("R = P @ (P.T @ X) - X\n    return np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P))", "P Pᵀ A x"),
    "energy with A": ("R = P @ (P.T @ (A @ X)) - X\n    return np.sum(R * (A @ R)) + mu * np.sum(P * (A @ P))", "uses A"),
    "penalty subtracted": ("R = P @ (P.T @ (A @ X)) - X\n    return np.sum(R * (A @ R)) - mu * np.sum(P * (W @ P))", "wrong sign"),
    "mu forgotten": ("R = P @ (P.T @ (A @ X)) - X\n    return np.sum(R * (A @ R)) + np.sum(P * (W @ P))", "μ is missing"),
    "twice the fit": ("R = P @ (P.T @ (A @ X)) - X\n    return 2 * np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P))", "each term"),
}


@pytest.mark.parametrize("name", list(WRONG_OBJECTIVES))
def test_objective_wrong_answers(name):
    body, hint = WRONG_OBJECTIVES[name]
    message = _zero("11-objective", hint, **answers(f"def my_objective(P, X, W, A, mu):\n    {body}\n", "my_objective"))
    assert "notebook does not show" in message


@pytest.mark.parametrize("code, used", [
    ("from lbo_notebooks.exercises import regularized_pca\nmy_objective = regularized_pca._rpca_objective", "_rpca_objective"),
    ("""
        from lbo_notebooks.spectral import reconstruct
        def my_objective(P, X, W, A, mu):
            R = reconstruct(P, A, X) - X
            return np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P))
     """, "inner_product.reconstruct"),
    ("""
        def my_objective(P, X, W, A, mu):   # the solver's eigenvalues: right only for the optimal P
            result = lbo.RegularizedPCA(X, W, A).solve(P.shape[1], mu)
            return np.sum(X * (A @ X)) - result.values.sum()
     """, "RegularizedPCA.solve"),
    ("""
        def my_objective(P, X, W, A, mu):
            s = lbo.Spectrum(np.zeros(P.shape[1]), P, W, A)
            return np.sum(s.error(X) ** 2) + mu * np.sum(P * (W @ P))
     """, "Spectrum.error"),
])
def test_objective_library_calls_earn_nothing(code, used):
    _zero("11-objective", "not available", used, **answers(code, "my_objective"))


def test_objective_stubs_are_not_attempted():
    for code in ("my_objective = ...", "def my_objective(P, X, W, A, mu):\n    pass",
                 "def my_objective(P, X, W, A, mu):\n    raise NotImplementedError"):
        _zero("11-objective", status="not attempted", **answers(code, "my_objective"))
    _zero("11-objective", "raised", **answers("def my_objective(P, X, W, A, mu):\n    return P @ X", "my_objective"))


# --- 11-rpca-basis (build) ----------------------------------------------------------------------------------

RIGHT_BASES = {
    "sparse shift-invert Lanczos with the mass on the right (eigsh, M=A)": """
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla
        def my_rpca_basis(X, W, A, mu, m):
            U = A @ X
            L = U @ U.T - mu * W.toarray()
            sigma, P = sla.eigsh(L, k=m, M=A.tocsc(), which="LA", tol=1e-13, v0=np.ones(L.shape[0]))
            order = np.argsort(sigma)[::-1]
            return P[:, order]
    """,
    "Cholesky reduction to a standard problem, numpy only": """
        def my_rpca_basis(X, W, A, mu, m):
            Ad = A.toarray()
            C = np.linalg.cholesky(Ad)                      # A = C Cᵀ
            Ci = np.linalg.inv(C)
            M = Ci @ ((Ad @ X) @ (Ad @ X).T - mu * W.toarray()) @ Ci.T
            sigma, Y = np.linalg.eigh((M + M.T) / 2)
            top = np.argsort(sigma)[::-1][:m]
            return Ci.T @ Y[:, top]                         # p = C⁻ᵀ y, so Pᵀ A P = I
    """,
    "scipy.linalg.eigh on the whole pencil, then the last m columns reversed": """
        import scipy.linalg
        def my_rpca_basis(X, W, A, mu, m):
            data = (A @ X) @ (A @ X).T
            _, vectors = scipy.linalg.eigh(data - mu * W.todense(), A.todense())
            return np.asarray(vectors)[:, ::-1][:, :m]
    """,
}


def test_rpca_basis_solution_and_alternatives():
    message = _full("11-rpca-basis", **answers(solution("11-rpca-basis"), "my_rpca_basis"))
    assert "does not show" in message
    for name, code in RIGHT_BASES.items():
        _full("11-rpca-basis", **answers(code, "my_rpca_basis"))


_DENSE = "    U = A @ X\n    L = U @ U.T - mu * W.toarray()\n"
WRONG_BASES = {
    "the standard problem (no A on the right)": (_DENSE + "    s, P = np.linalg.eigh(L)\n    return P[:, ::-1][:, :m]",
                                                 "standard problem"),
    "ascending order": (_DENSE + "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, -m:]", "ascending"),
    "the m smallest": (_DENSE + "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, :m]", "smallest"),
    "plus mu W": ("    U = A @ X\n    L = U @ U.T + mu * W.toarray()\n"
                  "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, ::-1][:, :m]", "wrong sign"),
    "X Xᵀ without the mass": ("    L = X @ X.T - mu * W.toarray()\n"
                              "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, ::-1][:, :m]", "lacks the mass"),
    "the data centred": ("    Xc = X - (A @ X).sum(axis=0) / A.sum()\n    U = A @ Xc\n    L = U @ U.T - mu * W.toarray()\n"
                         "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, ::-1][:, :m]", "centred"),
    "Euclidean normalisation": (_DENSE + "    s, P = scipy.linalg.eigh(L, A.toarray())\n    P = P[:, ::-1][:, :m]\n"
                                "    return P / np.linalg.norm(P, axis=0)", "not normalised in the A inner product"),
    "eigenvalues and basis": (_DENSE + "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return s[::-1][:m], P[:, ::-1][:, :m]",
                              "basis P alone"),
    "transposed": (_DENSE + "    s, P = scipy.linalg.eigh(L, A.toarray())\n    return P[:, ::-1][:, :m].T", "Transposed"),
}


@pytest.mark.parametrize("name", list(WRONG_BASES))
def test_rpca_basis_wrong_answers(name):
    body, hint = WRONG_BASES[name]
    code = f"import scipy.linalg\ndef my_rpca_basis(X, W, A, mu, m):\n{body}\n"
    message = _zero("11-rpca-basis", hint, **answers(code, "my_rpca_basis"))
    assert "notebook does not show" in message


@pytest.mark.parametrize("code, used", [
    ("""
        def my_rpca_basis(X, W, A, mu, m):
            return lbo.RegularizedPCA(X, W, A).solve(m, mu=mu).basis
     """, "RegularizedPCA.solve"),
    ("""
        def my_rpca_basis(X, W, A, mu, m):   # the pencil handed to the package's eigensolver
            U = A @ X
            return lbo.eigenbasis((mu * W - sp.csr_matrix(U @ U.T), A), m).vectors
     """, "eigenbasis"),
])
def test_rpca_basis_library_calls_earn_nothing(code, used):
    _zero("11-rpca-basis", "not available", used, **answers(code, "my_rpca_basis"))


def test_rpca_basis_stubs_are_not_attempted():
    for code in ("my_rpca_basis = ...", "def my_rpca_basis(X, W, A, mu, m):\n    pass",
                 "def my_rpca_basis(X, W, A, mu, m):\n    raise NotImplementedError"):
        _zero("11-rpca-basis", status="not attempted", **answers(code, "my_rpca_basis"))


def test_rpca_basis_is_judged_on_unseen_problems(kernel):
    """None of the graded problems is the notebook's (the dog, or the bumpy sphere of the visible
    check); one has data that are not centred, one repeated eigenvalues that m cuts."""
    from lbo_notebooks.exercises.grading import nb11

    problems = nb11._unseen_rpca_problems()
    sizes = {X.shape[0] for _, X, _, _, _, _ in problems}
    assert kernel["pca"].basis.shape[0] not in sizes and 642 not in sizes
    assert any(np.abs((A @ X).sum(axis=0)).max() > 1e-3 * np.abs(A @ X).sum() for _, X, _, A, _, _ in problems)
    assert verdict("11-rpca-basis", **answers(solution("11-rpca-basis"), "my_rpca_basis")) == \
        verdict("11-rpca-basis", **answers(solution("11-rpca-basis"), "my_rpca_basis"))


def test_the_visible_rpca_basis_check_says_right_and_wrong():
    import lbo_notebooks as lbo
    from lbo_notebooks import exercises
    from lbo_notebooks.analyses import RegularizedPCA

    small = lbo.shapes.bumpy_sphere(3)
    Ws, As = lbo.stiffness_matrix(small), lbo.mass_matrix(small)
    bent = small.vertices * [1.0, 1.2, 1.0]
    data = RegularizedPCA(np.hstack([small.vertices, bent]), Ws, As, center=True).data
    right = answers(solution("11-rpca-basis"), "my_rpca_basis")["my_rpca_basis"]
    assert exercises.check_rpca_basis(right, data, Ws, As, show=False).correct
    wrong = answers("import scipy.linalg\ndef my_rpca_basis(X, W, A, mu, m):\n" + WRONG_BASES["ascending order"][0],
                    "my_rpca_basis")["my_rpca_basis"]
    feedback = exercises.check_rpca_basis(wrong, data, Ws, As, show=False)
    assert feedback.status == "wrong" and "ascending" in feedback.message


# --- 11-recap ------------------------------------------------------------------------------------------------

def test_recap_partial_credit():
    assert verdict("11-recap", **answers(solution("11-recap"), "q1", "q2", "q3"))[0] == 3
    assert verdict("11-recap", q1="B", q2=" a", q3="C")[0] == 3
    assert verdict("11-recap", **answers("q1 = 'b'\nq2 = 'a'\nq3 = 'c'", "q1", "q2", "q3"))[0] == 3
    points, status, message = verdict("11-recap", q1="b", q2="b", q3="c")
    assert points == 2 and "2 of 3 right" in message and "Question 2" in message
    assert "Question 1" not in message and "Question 3" not in message
    points, _, message = verdict("11-recap", q1="c", q2="c", q3="c")
    assert points == 1 and "Question 1" in message and "Question 2" in message
    assert verdict("11-recap", q1="a", q2="b", q3="a")[0] == 0
    assert verdict("11-recap", q1="b", q2=..., q3="c")[0] == 2           # a question left out costs its point
    assert verdict("11-recap", q1="b", q2=2, q3={"c": 1})[0] == 1         # any type: no error


# --- the same answer, the same grade; the kernel cannot change it ----------------------------------------------

def test_the_same_answer_gets_the_same_grade(kernel):
    given = answers(solution("11-energy"), "energies", **kernel)
    assert verdict("11-energy", **given) == verdict("11-energy", **given)
    wrong = answers("def my_objective(P, X, W, A, mu):\n    return 1.0", "my_objective")
    assert verdict("11-objective", **wrong) == verdict("11-objective", **wrong)


def test_the_real_graded_run_ignores_a_patched_feedback_and_context():
    """Through the real fresh process (as nbgrader runs it): an answer cell that patches the checks'
    Feedback, or changes the notebook's variables, changes nothing."""
    from lbo_notebooks import exercises

    original = exercises.Feedback.correct
    try:
        wrong = cell("exercises.Feedback.correct = property(lambda s: True)\nq1, q2, q3 = 'a', 'b', 'a'",
                     exercises=exercises)
        assert exercises.check_recap_rpca("a", "b", "a", show=False).correct  # the visible check is fooled
        assert graded("11-recap", q1=wrong["q1"], q2=wrong["q2"], q3=wrong["q3"]) == 0.0
        assert graded("11-limits", limit_at_0="pca + smooth", limit_at_1="eigenbasis", best_beta="small") == 0.0
    finally:
        exercises.Feedback.correct = original
    assert graded("11-recap", q1="b", q2="b", q3="c") == 2.0                # partial credit
    assert graded("11-limits", limit_at_0="pca + smooth", limit_at_1="eigenbasis", best_beta="intermediate") == 1.0


def test_the_objective_is_judged_on_unseen_problems(kernel):
    """The graded problems are none of the notebook's (the dog's solver data and bases), and each
    basis is A-orthonormal but not the optimum for its weight."""
    from lbo_notebooks.exercises.grading import nb11

    for what, P, X, W, A, mu in nb11._unseen_problems():
        assert P.shape[0] != kernel["pca"].basis.shape[0], what
        assert np.allclose(P.T @ (A @ P), np.eye(P.shape[1]), atol=1e-8), what
