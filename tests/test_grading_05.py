"""The graded tests of notebook 05 (the optimality theorem), with answers written as students write
them: the instructor's solution, correct answers written differently, typical wrong ones, library
calls in the build exercise, placeholders; see lbo_notebooks/exercises/grading/nb05.py."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "05_optimality_theorem.ipynb"


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def notebook():
    """The notebook's dog and its spectrum (section 2), for the solutions that use them."""
    import lbo_notebooks as lbo
    from lbo_notebooks.shapes import creature

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dog = creature("dog", n_vertices=2000)
    return {"dog": dog, "spectra": {"dog": lbo.eigenbasis(dog, 101)}}


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    assert [full_points(e) for e in ("05-projection", "05-bound", "05-extra", "05-recap")] == [5, 2, 1, 3]


# --- 05-projection (build it yourself) -----------------------------------------------------------

def _project(code: str):
    return answers(code, "my_project")


RIGHT_PROJECTIONS = {
    "diagonal mass, vectorised": """
        def my_project(spec, g, k):
            basis = spec.vectors[:, :k]
            weights = spec.mass.diagonal()
            return basis @ (basis.T @ (weights * g))
    """,
    "normal equations, np.linalg.solve": """
        def my_project(spectrum, f, n):
            B = np.asarray(spectrum.vectors)[:, :n]
            A = spectrum.mass
            gram = B.T @ (A @ B)
            return B @ np.linalg.solve(gram, B.T @ (A @ f))
    """,
    "one eigenfunction at a time": """
        def my_project(spectrum, f, n):
            out = np.zeros(spectrum.vectors.shape[0])
            Af = spectrum.mass @ f
            for k in range(n):
                phi = spectrum.vectors[:, k]
                out += (phi @ Af) * phi
            return out
    """,
    "weighted least squares": """
        def my_project(spectrum, f, n):
            w = np.sqrt(spectrum.mass.diagonal())
            Phi = spectrum.vectors[:, :n]
            c, *_ = np.linalg.lstsq(w[:, None] * Phi, w * f, rcond=None)
            return Phi @ c
    """,
    "re-orthonormalised first, a column out": """
        def my_project(spectrum, f, n):
            Q = lbo.a_orthonormalize(spectrum.vectors[:, :n], spectrum.mass)
            return (Q @ (Q.T @ (spectrum.mass @ f)))[:, None]
    """,
}


def test_projection_solution_earns_full_points():
    _full("05-projection", **_project(solution("05-projection")))


def test_projection_solution_satisfies_the_old_hidden_claims(notebook):
    """The claims the old hidden test made of the instructor's answer, on the notebook's dog: the
    error is A-orthogonal to φ_0..φ_9, and its squared norm is `representation_error`."""
    from lbo_notebooks.analyses import representation_error

    my_project = _project(solution("05-projection"))["my_project"]
    s, x = notebook["spectra"]["dog"], notebook["dog"].vertices[:, 0]
    r = x - my_project(s, x, 10)
    assert np.abs(s.vectors[:, :10].T @ (s.mass @ r)).max() < 1e-10 * np.sqrt(x @ (s.mass @ x))
    assert abs(r @ (s.mass @ r) / representation_error(s, x, 10) - 1) < 1e-10


@pytest.mark.parametrize("name", sorted(RIGHT_PROJECTIONS))
def test_projection_written_differently_earns_full_points(name):
    _full("05-projection", **_project(RIGHT_PROJECTIONS[name]))


WRONG_PROJECTIONS = [
    ("Euclidean", "def my_project(s, f, n):\n    P = s.vectors[:, :n]\n    return P @ (P.T @ f)"),
    ("coefficients", "def my_project(s, f, n):\n    return s.vectors[:, :n].T @ (s.mass @ f)"),
    ("off by one", "def my_project(s, f, n):\n    P = s.vectors[:, :n + 1]\n    return P @ (P.T @ (s.mass @ f))"),
    ("φ_0", "def my_project(s, f, n):\n    P = s.vectors[:, 1:n + 1]\n    return P @ (P.T @ (s.mass @ f))"),
    ("error f − P_n f", "def my_project(s, f, n):\n    P = s.vectors[:, :n]\n    return f - P @ (P.T @ (s.mass @ f))"),
    ("wrong place", "def my_project(s, f, n):\n    P = s.vectors[:, :n]\n    return s.mass @ (P @ (P.T @ f))"),
    ("Φ_nᵀ A f", "def my_project(s, f, n):\n    P = s.vectors[:, :n]\n    return 2 * P @ (P.T @ (s.mass @ f))"),
    ("transposes", "def my_project(s, f, n):\n    P = s.vectors[:, :n]\n    return P.T @ (P @ (s.mass @ f))"),
]


@pytest.mark.parametrize("hint, code", WRONG_PROJECTIONS, ids=[h for h, _ in WRONG_PROJECTIONS])
def test_projection_wrong_answers_earn_nothing(hint, code):
    _zero("05-projection", hint, **_project(code))


def test_projection_on_the_notebooks_spectrum_is_not_an_answer(notebook):
    """A function that ignores its argument and projects with the notebook's dog is right only there."""
    code = """
        def my_project(spectrum, f, n):
            s = spectra["dog"]
            P = s.vectors[:, :n]
            return P @ (P.T @ (s.mass @ f))
    """
    _zero("05-projection", "raised", "does not show", **answers(code, "my_project", spectra=notebook["spectra"]))


LIBRARY_PROJECTIONS = {
    "reconstruct": "def my_project(s, f, n):\n    return s.reconstruct(f, n)",
    "project": "def my_project(s, f, n):\n    return s.vectors[:, :n] @ s.project(f, n)",
    "the class's method": "def my_project(s, f, n):\n    return lbo.Spectrum.reconstruct(s, f, n)",
    "a wrapper": "def helper(s, f, n):\n    return s.reconstruct(f, n)\n\ndef my_project(s, f, n):\n    return helper(s, f, n)",
    "inner_product.reconstruct": ("from lbo_notebooks.spectral._inner_product import reconstruct\n\n"
                                  "def my_project(s, f, n):\n    return reconstruct(s.vectors[:, :n], s.mass, f)"),
    "the error, caught": ("def my_project(s, f, n):\n    try:\n        s.error(f, n)\n    except Exception:\n        pass\n"
                          "    P = s.vectors[:, :n]\n    return P @ (P.T @ (s.mass @ f))"),
    "krylov": ("from lbo_notebooks.spectral._engine import krylov\n\ndef my_project(s, f, n):\n    y = np.array(f, dtype=float)[:, None]\n"
               "    c = krylov._project_out(s.vectors[:, :n], y, s.mass)\n    return (s.vectors[:, :n] @ c).ravel()"),
}


@pytest.mark.parametrize("name", sorted(LIBRARY_PROJECTIONS))
def test_projection_library_calls_earn_nothing(name):
    _zero("05-projection", "build it yourself", "not available", **_project(LIBRARY_PROJECTIONS[name]))


def test_projection_placeholders_are_not_attempted():
    _zero("05-projection", status="not attempted", **_project(student_edition("05-projection")))
    _zero("05-projection", status="not attempted", my_project=...)
    _zero("05-projection", status="not attempted",
          **_project("def my_project(s, f, n):\n    raise NotImplementedError()"))


def test_projection_a_crash_is_wrong_not_an_error():
    _zero("05-projection", "raised", **_project("def my_project(s, f, n):\n    return s.vectors[:, :n] @ f"))
    _zero("05-projection", "array", **_project("def my_project(s, f, n):\n    return {'p': 1}"))


def test_projection_verdict_is_deterministic():
    given = _project(WRONG_PROJECTIONS[0][1])
    assert verdict("05-projection", **given) == verdict("05-projection", **given)


def test_projection_through_the_real_graded_run():
    assert graded("05-projection", **_project(RIGHT_PROJECTIONS["one eigenfunction at a time"])) == 5.0
    assert graded("05-projection", **_project(LIBRARY_PROJECTIONS["reconstruct"])) == 0.0


# --- 05-bound (compute) ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def bound(notebook):
    s, y = notebook["spectra"]["dog"], notebook["dog"].vertices[:, 1]
    return float(y @ (s.stiffness @ y)), s.values, float(y @ (s.mass @ y))


def test_bound_solution_earns_full_points(notebook):
    _full("05-bound", **answers(solution("05-bound"), "bound_y", **notebook))


def test_bound_written_differently_earns_full_points(notebook, bound):
    energy, lam, _ = bound
    ref = energy / lam[20]
    code = """
        from lbo_notebooks.analyses import dirichlet_energy
        bound_y = dirichlet_energy(lbo.stiffness_matrix(dog), dog.vertices[:, 1]) / spectra["dog"].values[20]
    """
    _full("05-bound", **answers(code, "bound_y", **notebook))
    code = """
        yy = dog.vertices[:, 1][:, None]
        bound_y = (yy.T @ spectra["dog"].stiffness @ yy) / spectra["dog"].values[20]   # a 1 x 1 array
    """
    _full("05-bound", **answers(code, "bound_y", **notebook))
    _full("05-bound", bound_y=float(f"{ref:.9g}"))            # copied to nine digits
    _full("05-bound", bound_y=np.array([ref]))
    _full("05-bound", bound_y=str(ref))


def test_bound_wrong_answers_earn_nothing(bound):
    energy, lam, norm2 = bound
    _zero("05-bound", "off by one", bound_y=energy / lam[19])
    _zero("05-bound", "off by one", bound_y=energy / lam[21])
    _zero("05-bound", "divides", bound_y=energy)
    _zero("05-bound", "squared norm", bound_y=norm2 / lam[20])
    _zero("05-bound", "square root", bound_y=np.sqrt(energy / lam[20]))
    _zero("05-bound", "number", bound_y="about 0.01")
    _zero("05-bound", "number", bound_y={"y": energy / lam[20]})


def test_bound_hand_rounded_asks_for_digits(bound):
    energy, lam, _ = bound
    ref = energy / lam[20]
    for typed in (float(f"{ref:.3g}"), float(f"{ref:.5g}"), np.trunc(ref * 1e4) / 1e4):
        message = _zero("05-bound", "digits", bound_y=typed)
        assert "off by one" not in message.lower()
    _zero("05-bound", "Dirichlet energy", bound_y=float(f"{1.3 * ref:.3g}"))  # coarse and wrong: the method


def test_bound_placeholders_are_not_attempted(notebook):
    _zero("05-bound", status="not attempted", **answers(student_edition("05-bound"), "bound_y", **notebook))
    _zero("05-bound", status="not attempted", bound_y=None)


def test_bound_verdict_is_deterministic(bound):
    energy, lam, _ = bound
    assert verdict("05-bound", bound_y=energy / lam[20]) == verdict("05-bound", bound_y=energy / lam[20])


# --- 05-extra (predict) -----------------------------------------------------------------------------

def test_extra():
    _full("05-extra", **answers(solution("05-extra"), "extra_verdict"))
    for right in ("Between", "  between ", "BETWEEN", np.str_("between")):
        _full("05-extra", extra_verdict=right)
    _zero("05-extra", "n + 1", extra_verdict="beats")
    _zero("05-extra", "contains", extra_verdict="worse")
    _zero("05-extra", "one of", extra_verdict="in between, probably")
    _zero("05-extra", "one of", extra_verdict=2)
    _zero("05-extra", status="not attempted", **answers(student_edition("05-extra"), "extra_verdict"))
    assert verdict("05-extra", extra_verdict="worse") == verdict("05-extra", extra_verdict="worse")


# --- 05-recap (recap, partial credit) -------------------------------------------------------------------

def test_recap_solution_and_other_spellings():
    _full("05-recap", **answers(solution("05-recap"), "q1", "q2", "q3"))
    _full("05-recap", q1="10", q2="Vacuous", q3="No")
    _full("05-recap", q1=np.int64(10), q2=" vacuous ", q3=False)
    _full("05-recap", q1=10.0, q2="VACUOUS", q3="no")


@pytest.mark.parametrize("given, points, hints", [
    ((9, "vacuous", "no"), 2.0, ["question 1", "left out"]),
    ((11, "vacuous", "no"), 2.0, ["question 1", "count again"]),
    ((10, "tight", "yes"), 1.0, ["question 2", "huge", "question 3", "conditions"]),
    ((10, "violated", "no"), 2.0, ["question 2", "every function"]),
    ((10, ..., ...), 1.0, ["not answered"]),
])
def test_recap_partial_credit(given, points, hints):
    got, _, message = verdict("05-recap", q1=given[0], q2=given[1], q3=given[2])
    assert got == points, message
    for hint in hints:
        assert hint in message.lower(), message
    assert "vacuous" not in message.lower() and "values[10]" not in message  # never the right answers


def test_recap_all_wrong_and_placeholders():
    _zero("05-recap", "0 of 3", q1=9, q2="violated", q3="yes")
    _zero("05-recap", "one of", q1="ten", q2="maybe", q3={"no": 1})
    _zero("05-recap", status="not attempted", **answers(student_edition("05-recap"), "q1", "q2", "q3"))
    assert verdict("05-recap", q1=9, q2="vacuous", q3="no") == verdict("05-recap", q1=9, q2="vacuous", q3="no")
