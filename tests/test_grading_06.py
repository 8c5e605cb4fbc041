"""The graded tests of notebook 06 (the worst-case constant, and ties), with answers written as
students write them: the instructor's solution, correct answers written differently, typical wrong
ones, placeholders; and, as tests of the library, the claims the old hidden tests made about the
notebook's data. See lbo_notebooks/exercises/grading/nb06.py."""

from __future__ import annotations

import types
import warnings
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "06_optimality_ties.ipynb"


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def notebook():
    """What the solutions of 06-consistent and 06-worst use from the notebook's first cells: the dog,
    W, A, ``worst_case_ratio``, ``dirichlet_energy``, the polynomial competitor (the notebook's
    ``competitor_bases(dog, 100, ...)["polynomials"]`` is ``polynomial_basis(dog, 100)``) and a
    ``plotting`` that draws nothing."""
    from lbo_notebooks import mass_matrix, stiffness_matrix
    from lbo_notebooks.analyses import _competitor_bases as bases
    from lbo_notebooks.shapes import creature
    from lbo_notebooks.analyses import dirichlet_energy, worst_case_ratio

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dog = creature("dog", n_vertices=2000)
    return {"dog": dog, "W": stiffness_matrix(dog), "A": mass_matrix(dog),
            "competitors": {"polynomials": bases.polynomial_basis(dog, 100)},
            "worst_case_ratio": worst_case_ratio, "dirichlet_energy": dirichlet_energy,
            "plotting": types.SimpleNamespace(plot_mesh=lambda *args, **kwargs: None)}


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    exercises = ("06-shifted", "06-stationary", "06-consistent", "06-worst", "06-ties-recap")
    assert [full_points(e) for e in exercises] == [1, 1, 2, 2, 3]


# --- the two predictions --------------------------------------------------------------------------

@pytest.mark.parametrize("exercise, name, right, others", [
    ("06-shifted", "shifted_verdict", "infinite",
     {"below": "every n-dimensional", "one": "zero energy", "above": "worst function"}),
    ("06-stationary", "stationary_verdict", "quadruple",
     {"same": "grow", "double": "first order", "eightfold": "second-order"}),
])
def test_predictions(exercise, name, right, others):
    _full(exercise, **answers(solution(exercise), name))
    for spelling in (right.upper(), f"  {right.capitalize()} ", np.str_(right)):
        _full(exercise, **{name: spelling})
    for wrong, hint in others.items():
        _zero(exercise, hint, **{name: wrong})
    _zero(exercise, "one of", **{name: "no idea"})
    _zero(exercise, "one of", **{name: 4})
    _zero(exercise, status="not attempted", **answers(student_edition(exercise), name))
    assert verdict(exercise, **{name: "one"}) == verdict(exercise, **{name: "one"})


def test_a_patched_check_in_the_kernel_changes_no_grade(monkeypatch):
    """The graded run is a fresh process: an answer cell's `Feedback.correct = True` reaches nothing."""
    from lbo_notebooks import exercises

    monkeypatch.setattr(exercises.Feedback, "correct", property(lambda self: True))
    assert graded("06-stationary", stationary_verdict="double") == 0.0
    assert graded("06-stationary", stationary_verdict="Quadruple") == 1.0


# --- 06-consistent (compute) ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def consistent(notebook):
    import lbo_notebooks as lbo

    return lbo.eigenbasis(notebook["dog"], 51, mass_kind="consistent")


def test_consistent_solution_earns_full_points(notebook):
    given = answers(solution("06-consistent"), "consistent_ratio", **notebook)
    assert abs(given["consistent_ratio"] - 1) < 1e-8   # the old hidden test's claim on the instructor's answer
    _full("06-consistent", **given)


def test_consistent_written_differently_earns_full_points(notebook, consistent):
    from lbo_notebooks.analyses import worst_case_ratio

    code = """
        sc = lbo.eigenbasis(dog, 51, mass_kind="consistent")
        basis, lam = sc.vectors[:, :50], sc.values
        consistent_ratio = lam[50] * worst_case_ratio(basis, sc.stiffness, sc.mass, method="sparse")
    """
    _full("06-consistent", **answers(code, "consistent_ratio", **notebook))
    sc = consistent
    _full("06-consistent", consistent_ratio=[worst_case_ratio(sc.vectors[:, :50], sc.stiffness, sc.mass) * sc.values[50]])
    _full("06-consistent", consistent_ratio=1)
    _full("06-consistent", consistent_ratio="1.0")


def test_consistent_wrong_answers_earn_nothing(notebook, consistent):
    from lbo_notebooks.analyses import worst_case_ratio

    sc, W, A = consistent, notebook["W"], notebook["A"]
    C = worst_case_ratio(sc.vectors[:, :50], sc.stiffness, sc.mass)
    _zero("06-consistent", "own", consistent_ratio=worst_case_ratio(sc.vectors[:, :50], W, A) * sc.values[50])  # lumped W, A
    _zero("06-consistent", "values[n]", consistent_ratio=C * sc.values[49])     # off by one
    _zero("06-consistent", "normalise", consistent_ratio=C)                      # not multiplied by λ_50
    _zero("06-consistent", "number", consistent_ratio="one")
    _zero("06-consistent", "number", consistent_ratio={"ratio": 1.0})
    _zero("06-consistent", status="not attempted",
          **answers(student_edition("06-consistent"), "consistent_ratio", **notebook))


def test_a_competitor_stays_above_one_for_the_consistent_pair(notebook, consistent):
    """The old hidden test's claim about the notebook's data, kept as a test of the library: the
    umbrella basis (consistent mass) is not optimal for the consistent pair, the eigenbasis is."""
    from lbo_notebooks.analyses import _competitor_bases as bases
    from lbo_notebooks.analyses import worst_case_ratio

    sc = consistent
    assert abs(worst_case_ratio(sc.vectors[:, :50], sc.stiffness, sc.mass) * sc.values[50] - 1) < 1e-8
    umbrella = bases.umbrella_basis(notebook["dog"], 50, mass_kind="consistent")
    assert worst_case_ratio(umbrella, sc.stiffness, sc.mass) * sc.values[50] > 1


# --- 06-worst (explore) --------------------------------------------------------------------------

@pytest.fixture(scope="module")
def worst(notebook):
    from lbo_notebooks.analyses import worst_case_ratio

    P, W, A = notebook["competitors"]["polynomials"][:, :20], notebook["W"], notebook["A"]
    c, f = worst_case_ratio(P, W, A, return_vector=True)
    return c, f, P, W, A


def test_worst_solution_earns_full_points(notebook):
    _full("06-worst", **answers(solution("06-worst"), "worst_ratio", **notebook))


def test_worst_written_differently_earns_full_points(notebook, worst):
    code = """
        basis = competitors["polynomials"][:, :20]
        _, g = worst_case_ratio(basis, W, A, return_vector=True)
        coef = np.linalg.solve(basis.T @ (A @ basis), basis.T @ (A @ g))   # normal equations
        miss = g - basis @ coef
        worst_ratio = float(miss @ (A @ miss) / (g @ (W @ g)))
    """
    _full("06-worst", **answers(code, "worst_ratio", **notebook))
    code = """
        Ad, Wd = A.toarray(), W.toarray()   # dense, and the function scaled by 3: the ratio does not change
        V = competitors["polynomials"][:, :20]
        h = 3 * worst_case_ratio(V, W, A, return_vector=True)[1]
        e = h - V @ (V.T @ Ad @ h)
        worst_ratio = (e @ Ad @ e) / (h @ Wd @ h)
    """
    _full("06-worst", **answers(code, "worst_ratio", **notebook))
    c = worst[0]
    _full("06-worst", worst_ratio=float(f"{c:.9g}"))       # copied to nine digits
    _full("06-worst", worst_ratio=np.float32(c) * 1.0)      # single precision is still right to 1e-7


def test_worst_wrong_answers_earn_nothing(worst):
    c, f, P, W, A = worst
    energy = f @ (W @ f)
    r_euclid = f - P @ (P.T @ f)
    _zero("06-worst", "A inner product", worst_ratio=(r_euclid @ A @ r_euclid) / energy)
    _zero("06-worst", "misses", worst_ratio=(f @ A @ f) / energy)
    _zero("06-worst", "upside down", worst_ratio=1 / c)
    _zero("06-worst", "supremum", worst_ratio=2 * c)
    _zero("06-worst", "below", worst_ratio=c / 2)
    _zero("06-worst", "number", worst_ratio=(c, f))        # the pair worst_case_ratio returns
    _zero("06-worst", status="not attempted", worst_ratio=...)


def test_worst_hand_rounded_asks_for_digits(worst):
    c = worst[0]
    for typed in (float(f"{c:.3g}"), float(f"{c:.5g}"), np.trunc(c * 1e5) / 1e5):
        _zero("06-worst", "digits", worst_ratio=typed)


def test_worst_verdict_is_deterministic(worst):
    assert verdict("06-worst", worst_ratio=worst[0] / 2) == verdict("06-worst", worst_ratio=worst[0] / 2)


# --- 06-ties-recap (recap, partial credit) ------------------------------------------------------------

def test_recap_solution_and_other_spellings():
    _full("06-ties-recap", **answers(solution("06-ties-recap"), "q1", "q2", "q3"))
    _full("06-ties-recap", q1="No", q2="a lower bound", q3="2")
    _full("06-ties-recap", q1=False, q2="Lower", q3=2.0)
    _full("06-ties-recap", q1=" no ", q2="LOWER BOUND", q3="quadratic")
    _full("06-ties-recap", q1="no", q2="lower", q3=np.int64(2))


@pytest.mark.parametrize("given, points, hints", [
    (("yes", "lower", 2), 2.0, ["question 1", "tilted"]),
    (("no", "exactly", 2), 2.0, ["question 2", "cancel"]),
    (("no", "exact", 2), 2.0, ["question 2", "cancel"]),
    (("no", "upper", 1), 1.0, ["question 2", "overestimate", "question 3", "first-order"]),
    (("no", "lower", 4), 2.0, ["question 3", "doubles"]),
    (("no", ..., ...), 1.0, ["not answered"]),
])
def test_recap_partial_credit(given, points, hints):
    got, _, message = verdict("06-ties-recap", q1=given[0], q2=given[1], q3=given[2])
    assert got == points, message
    for hint in hints:
        assert hint in message.lower(), message
    assert '"lower"' not in message and "power 2" not in message   # never the right answers


def test_recap_all_wrong_and_placeholders():
    _zero("06-ties-recap", "0 of 3", q1="yes", q2="upper", q3=1)
    _zero("06-ties-recap", "one of", q1="maybe", q2=3, q3="θ")
    _zero("06-ties-recap", status="not attempted", **answers(student_edition("06-ties-recap"), "q1", "q2", "q3"))
    assert verdict("06-ties-recap", q1="yes", q2="lower", q3=2) == verdict("06-ties-recap", q1="yes", q2="lower", q3=2)


# --- 06-schur (build it yourself) -------------------------------------------------------------------
# Every answer is pickled now, at collection, as a student's kernel pickles it: before any graded
# run of this test process has made the library unavailable (a library function the answer refers
# to goes by reference, as from a notebook).

import textwrap  # noqa: E402

import cloudpickle  # noqa: E402


class Sent(bytes):
    """Answers pickled at import (see above)."""


def _judged(exercise, payload):
    from lbo_notebooks.exercises.grading.__main__ import _verdict

    result = _verdict(exercise, payload)
    assert "error" not in result, result["error"]
    return round(result["fraction"] * result["points"], 2), result["status"], result["message"]


SCHUR_HELPERS = """
import scipy.linalg
from scipy.sparse.csgraph import connected_components


def my_orthonormal(V, Ad):
    L = np.linalg.cholesky(V.T @ Ad @ V)
    return np.linalg.solve(L, V.T).T


def my_kernel_missed(W, Ad, Q):
    count, label = connected_components(W, directed=False)
    ones = np.eye(count)[label]
    miss = ones - Q @ (Q.T @ (Ad @ ones))
    return np.any(np.einsum("ij,ij->j", miss, Ad @ miss) > 1e-16 * np.einsum("ij,ij->j", ones, Ad @ ones))


def my_schur(Wd, Q):
    WQ = Wd @ Q
    return Wd - WQ @ np.linalg.pinv(Q.T @ WQ) @ WQ.T


def my_smallest(left, right):
    return scipy.linalg.eigh(left, right, eigvals_only=True, subset_by_index=[0, 0])[0]
"""

SCHUR = {
    "the pencil with one term per piece": """
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = lbo.a_orthonormalize(V, A)          # the library's orthonormaliser is allowed
            if my_kernel_missed(W, Ad, Q):
                return float("inf")
            count, label = connected_components(W, directed=False)
            ones = np.eye(count)[label]
            a = Ad @ ones
            right = Wd + (a / np.einsum("ij,ij->j", ones, a)) @ a.T
            left = Ad - (Ad @ Q) @ (Ad @ Q).T
            n = len(Wd)
            return float(scipy.linalg.eigh(left, right, eigvals_only=True, subset_by_index=[n - 1, n - 1])[0])
    """,
    "a threshold on mu, QR for the complement, lstsq for the Schur complement": """
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q, _ = np.linalg.qr(V)                  # Euclidean QR first, then A-orthonormal
            Q = my_orthonormal(Q, Ad)
            WQ = Wd @ Q
            S = Wd - WQ @ np.linalg.lstsq(Q.T @ WQ, WQ.T, rcond=1e-12)[0]
            full, _ = scipy.linalg.qr(Ad @ Q)       # the last columns are orthogonal to A Q
            Z = full[:, Q.shape[1]:]
            mus = scipy.linalg.eigh((Z.T @ S @ Z + (Z.T @ S @ Z).T) / 2, Z.T @ Ad @ Z, eigvals_only=True)
            return np.inf if mus[0] <= 1e-10 * mus[-1] else 1.0 / mus[0]
    """,
    "the library's kernel basis, a Cholesky whitening of the complement": """
        from lbo_notebooks.analyses import kernel_basis

        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(np.asarray(V, dtype=float), Ad)
            K = kernel_basis(W)
            gone = K - Q @ (Q.T @ Ad @ K)
            if (np.einsum("ij,ij->j", gone, Ad @ gone) > 1e-14 * np.einsum("ij,ij->j", K, Ad @ K)).any():
                return np.inf
            Z = scipy.linalg.null_space(Q.T @ Ad)
            Z = Z @ np.linalg.inv(np.linalg.cholesky(Z.T @ Ad @ Z)).T   # now Z^T A Z = I
            mu = np.linalg.eigvalsh(Z.T @ my_schur(Wd, Q) @ Z)[0]
            return np.float64(1 / mu)
    """,
}

SCHUR_SLIPS = {
    "the trap: W instead of S": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            if my_kernel_missed(W, Ad, Q):
                return np.inf
            Z = scipy.linalg.null_space((Ad @ Q).T)
            return 1 / my_smallest(Z.T @ Wd @ Z, Z.T @ Ad @ Z)
    """, "trap"),
    "a Euclidean complement": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            if my_kernel_missed(W, Ad, Q):
                return np.inf
            Z = scipy.linalg.null_space(Q.T)
            return 1 / my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Ad @ Z)
    """, "A-orthogonal to V"),
    "the Euclidean norm of r": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            if my_kernel_missed(W, Ad, Q):
                return np.inf
            Z = scipy.linalg.null_space((Ad @ Q).T)
            return 1 / my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Z)
    """, "A-norm"),
    "mu, not 1/mu": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            if my_kernel_missed(W, Ad, Q):
                return np.inf
            Z = scipy.linalg.null_space((Ad @ Q).T)
            return my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Ad @ Z)
    """, "upside down"),
    "no infinite case": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            Z = scipy.linalg.null_space((Ad @ Q).T)
            return 1 / my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Ad @ Z)
    """, "np.inf"),
    "only the global constant tested": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            one = np.ones(len(Wd))
            miss = one - Q @ (Q.T @ (Ad @ one))
            if miss @ Ad @ miss > 1e-16 * (one @ Ad @ one):
                return np.inf
            Z = scipy.linalg.null_space((Ad @ Q).T)
            mu = my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Ad @ Z)
            return 1 / max(mu, 1e-300)
    """, "each piece"),
    "a pair (C, mu)": ("""
        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            Z = scipy.linalg.null_space((Ad @ Q).T)
            mu = my_smallest(Z.T @ my_schur(Wd, Q) @ Z, Z.T @ Ad @ Z)
            return 1 / mu, mu
    """, "not a pair"),
}

SCHUR_LIBRARY = {
    "the library's worst-case ratio": ("my_worst_case = lambda W, A, V: worst_case_ratio(V, W, A)", "worst_case_ratio"),
    "its dense route": ("""
        from lbo_notebooks.analyses import _optimality as optimality

        def my_worst_case(W, A, V):
            Q = lbo.a_orthonormalize(V, A)
            return optimality._worst_case_dense(Q, W, A, optimality.kernel_basis(W))[0]
    """, "_worst_case_dense"),
    "the constrained minimum of S": ("""
        from lbo_notebooks.analyses import min_rayleigh_quotient

        def my_worst_case(W, A, V):
            Wd, Ad = W.toarray(), A.toarray()
            Q = my_orthonormal(V, Ad)
            if my_kernel_missed(W, Ad, Q):
                return np.inf
            return 1 / min_rayleigh_quotient(my_schur(Wd, Q), Ad, orthogonal_to=Q)
    """, "min_rayleigh_quotient"),
}


def _schur(code):
    given = answers("from lbo_notebooks.analyses._optimality import worst_case_ratio\n" + SCHUR_HELPERS + textwrap.dedent(code),
                    "my_worst_case")
    return Sent(cloudpickle.dumps(given))


SCHUR_ANSWERS = {name: _schur(code) for name, code in SCHUR.items()}
SCHUR_WRONG = {name: (_schur(code), hint) for name, (code, hint) in SCHUR_SLIPS.items()}
SCHUR_LIB = {name: (_schur(code), where) for name, (code, where) in SCHUR_LIBRARY.items()}
SOLUTION_SCHUR = _schur(solution("06-schur"))
STUB_SCHUR = _schur(student_edition("06-schur"))


def test_schur_points():
    assert full_points("06-schur") == 5


def test_schur_solution():
    points, status, message = _judged("06-schur", SOLUTION_SCHUR)
    assert points == 5 and "Right on seven bases" in message, message


@pytest.mark.parametrize("name", list(SCHUR))
def test_schur_written_differently(name):
    points, status, message = _judged("06-schur", SCHUR_ANSWERS[name])
    assert points == 5, message


@pytest.mark.parametrize("name", list(SCHUR_SLIPS))
def test_schur_slips(name):
    payload, hint = SCHUR_WRONG[name]
    points, status, message = _judged("06-schur", payload)
    assert points == 0 and status == "wrong" and hint.lower() in message.lower(), message
    assert "which the notebook does not show" in message


@pytest.mark.parametrize("name", list(SCHUR_LIBRARY))
def test_schur_library_calls(name):
    payload, where = SCHUR_LIB[name]
    points, status, message = _judged("06-schur", payload)
    assert points == 0 and "build it yourself" in message and where in message, message


def test_schur_placeholders_and_determinism():
    assert _judged("06-schur", STUB_SCHUR)[1] == "not attempted"
    _zero("06-schur", status="not attempted", my_worst_case=...)
    _zero("06-schur", "pass the function", my_worst_case=0.15)
    assert _judged("06-schur", SCHUR_WRONG["the trap: W instead of S"][0]) == _judged(
        "06-schur", SCHUR_WRONG["the trap: W instead of S"][0])


def test_schur_through_the_graded_run():
    assert graded("06-schur", **answers(solution("06-schur"), "my_worst_case")) == 5.0
    given = answers("from lbo_notebooks.analyses._optimality import worst_case_ratio\n"
                    "my_worst_case = lambda W, A, V: worst_case_ratio(V, W, A)", "my_worst_case")
    assert graded("06-schur", **given) == 0.0


def test_schur_graded_bases():
    """What the graded bases are: unseen by the visible check; the eigenbasis at the optimum, the
    others above it; the infinite cases where the kernel of W is missed (the global constant alone
    on two pieces among them); the instructor's solution within 1e-10 of the library on all."""
    import scipy.linalg

    from lbo_notebooks.exercises import theory
    from lbo_notebooks.exercises.grading import nb06
    from lbo_notebooks.analyses import worst_case_ratio

    graded_bases, visible = nb06._unseen_bases(), theory._worst_case_problems()
    assert not {W.shape[0] for W, *_ in graded_bases} & {W.shape[0] for W, *_ in visible}
    my_worst_case = answers(solution("06-schur"), "my_worst_case")["my_worst_case"]
    normalised = []
    for W, A, V, where in graded_bases:
        lam = scipy.linalg.eigh(W.toarray(), A.toarray(), eigvals_only=True)
        c = worst_case_ratio(V, W, A, method="dense")
        got = my_worst_case(W, A, V)
        assert (got == c == np.inf) or abs(got - c) < 1e-10 * c, where
        normalised.append(c * lam[V.shape[1]])
    assert abs(normalised[0] - 1) < 1e-9 and all(x > 1 + 1e-3 for x in normalised[1:3] + normalised[4:5])
    assert np.isinf(normalised[3]) and np.isinf(normalised[5]) and np.isfinite(normalised[6])
    trap = theory.worst_case_slips(graded_bases[1][2], *graded_bases[1][:2])[0][0]
    assert trap < 0.5 * worst_case_ratio(graded_bases[1][2], *graded_bases[1][:2])   # the trap is far off


def test_schur_visible_check():
    from lbo_notebooks.exercises import theory
    from lbo_notebooks.analyses import complement_ratio
    from lbo_notebooks.analyses import worst_case_ratio

    good = answers(solution("06-schur"), "my_worst_case")["my_worst_case"]
    assert theory.check_worst_case(good, show=False).correct
    trap = theory.check_worst_case(lambda W, A, V: complement_ratio(V, W, A), show=False)
    assert trap.status == "wrong" and "trap" in trap.message and "first seen on" in trap.message
    upside = theory.check_worst_case(lambda W, A, V: 1 / worst_case_ratio(V, W, A), show=False)
    assert "upside down" in upside.message.lower()
    finite = theory.check_worst_case(lambda W, A, V: min(worst_case_ratio(V, W, A), 1e3), show=False)
    assert "np.inf" in finite.message
    stub = answers(student_edition("06-schur"), "my_worst_case")["my_worst_case"]
    assert theory.check_worst_case(stub, show=False).status == "not attempted"
    assert theory.check_worst_case("schur", show=False).status == "wrong"   # never raises
    assert theory.check_worst_case(lambda W, A, V: "big", show=False).status == "wrong"
