"""The graded tests of notebook 12 (the spectral toolbox), with answers written as students write
them: the instructor's solution, correct answers written differently, typical wrong ones, library
calls (ours and pyFM's) in the build exercises, placeholders (the student edition); see
lbo_notebooks/exercises/grading/nb12.py. The claim that used to sit in 12-bound's hidden test (the
bound holds for f_z) is a test of the library here; the 12-mirror explanation is a written cell."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "12_spectral_toolbox.ipynb"
EXERCISES = {"12-hks": "build", "12-fmap": "build", "12-zoomout-step": "build", "12-alpha": "predict",
             "12-bound": "compute", "12-mirror": "predict", "12-zoomout": "predict", "12-recap": "recap"}
NAMES = {"12-hks": ["my_hks"], "12-fmap": ["my_functional_map"], "12-zoomout-step": ["my_zoomout_step"],
         "12-alpha": ["best_alpha"], "12-bound": ["bound_z"],
         "12-mirror": ["with_orientation", "without_orientation"], "12-zoomout": ["without_zoomout"],
         "12-recap": ["q1", "q2", "q3"]}


def _cells() -> list[dict]:
    return json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]


def _source(grade_id: str) -> str:
    (found,) = [c for c in _cells() if c["metadata"].get("nbgrader", {}).get("grade_id") == grade_id]
    return "".join(found["source"])


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def kernel():
    """What the notebook's kernel holds for 12-bound, restated from its cells: ``source`` (the standing
    dog) and ``ref``, its 60 eigenpairs."""
    import lbo_notebooks as lbo

    source = lbo.creature_poses("dog", n_vertices=3000)["standing"]
    return {"source": source, "ref": lbo.eigenbasis(source, 60)}


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    from lbo_notebooks.exercises.grading import POINTS

    assert {e: full_points(e) for e in EXERCISES} == {e: POINTS[k] for e, k in EXERCISES.items()}


def test_check_cells_grade_by_the_prompts_names():
    """Each check cell keeps its visible check, then grades with the names its grader takes (and the
    prompt names), as its last expression, for the points of its kind; no assert left in it."""
    from lbo_notebooks.exercises.grading import load_graders

    graders = load_graders("12-hks")
    cells = _cells()
    for exercise in EXERCISES:
        text = _source(f"{exercise}-check")
        assert text.startswith("feedback = exercises.check_"), exercise
        hidden = text.split("### BEGIN HIDDEN TESTS\n", 1)[1]
        names = graders[exercise].names
        assert list(names) == NAMES[exercise]
        call = f'grade("{exercise}", ' + ", ".join(f"{n}={n}" for n in names) + ")"
        assert hidden == f"from lbo_notebooks.exercises.grading import grade\n\n{call}\n### END HIDDEN TESTS", exercise
        (check,) = [c for c in cells if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-check"]
        assert check["metadata"]["nbgrader"]["points"] == graders[exercise].points
        (prompt,) = [c for c in cells if c["cell_type"] == "markdown" and f"**Exercise {exercise}**" in "".join(c["source"])]
        for name in names:
            assert f"`{name}" in "".join(prompt["source"]), (exercise, name)


def test_mirror_has_a_written_explanation_after_its_experiment():
    cells = _cells()
    ids = [c["metadata"].get("nbgrader", {}).get("grade_id") for c in cells]
    at = ids.index("12-mirror-explain")
    explain = cells[at]
    assert explain["cell_type"] == "markdown"
    assert explain["metadata"]["nbgrader"] == {"grade": True, "solution": True, "locked": False, "points": 2,
                                               "grade_id": "12-mirror-explain", "schema_version": 3}
    text = "".join(explain["source"])
    assert text.startswith("**Model answer.**") and "**Rubric (2 points).** 1 point:" in text
    assert ids.index("12-mirror-check") < at - 1 and "mirror_result" in "".join(cells[at - 1]["source"])
    prompt = next("".join(c["source"]) for c in cells if "**Exercise 12-mirror**" in "".join(c["source"]))
    assert "explain in two or three sentences" in prompt
    region = _source("12-mirror-answer").split("### BEGIN SOLUTION")[1].split("### END SOLUTION")[0]
    assert "#" not in region  # the explanation moved out of the solution's comments


def test_the_recorded_benchmark_is_read_through_the_package():
    text = "\n".join("".join(c["source"]) for c in _cells() if c["cell_type"] == "code")
    assert "../" not in text and 'lbo.analyses.recorded_benchmark("matching")' in text


@pytest.mark.parametrize("exercise", list(EXERCISES))
def test_the_student_edition_is_not_attempted(exercise, kernel):
    given = answers(student_edition(exercise), *NAMES[exercise], **kernel)
    _zero(exercise, "not attempted", status="not attempted", **given)


# --- 12-hks (build it yourself) ------------------------------------------------------------------------

RIGHT_HKS = {
    "a sum over the eigenpairs": """
        def my_hks(spectrum, times):
            out = np.zeros((spectrum.n_vertices, len(times)))
            for lam, phi in zip(spectrum.values, spectrum.vectors.T):
                out += np.outer(phi**2, np.exp(-lam * np.asarray(times)))
            return out
    """,
    "one column per time, raw eigenvalues": """
        def my_hks(s, t):
            return np.column_stack([(s.vectors**2) @ np.exp(-s.values * ti) for ti in t])
    """,
    "einsum": """
        def my_hks(spectrum, times):
            decay = np.exp(-np.clip(spectrum.values, 0, None)[:, None] * np.asarray(times)[None, :])
            return np.einsum("ni,ni,it->nt", spectrum.vectors, spectrum.vectors, decay)
    """,
}


def test_hks_solution_and_alternatives():
    message = _full("12-hks", **answers(solution("12-hks"), "my_hks"))
    assert "does not show" in message
    for name, code in RIGHT_HKS.items():
        _full("12-hks", **answers(code, "my_hks"))


@pytest.mark.parametrize("body, hint", [
    ("return s.vectors @ np.exp(-np.outer(s.values, t))", "square the eigenfunctions"),
    ("return (s.vectors**2) @ np.exp(np.outer(s.values, t))", "exp(+λ t)"),
    ("return (s.vectors[:, 1:] ** 2) @ np.exp(-np.outer(s.values[1:], t))", "starts at i = 0"),
    ("return ((s.vectors**2) @ np.exp(-np.outer(s.values, t))).T", "one row per vertex"),
    ("return s.mass @ ((s.vectors**2) @ np.exp(-np.outer(s.values, t)))", "no mass matrix"),
    ("return (s.vectors**2) @ np.exp(-np.outer(s.values, 2 * t))", "by hand"),
])
def test_hks_wrong_answers(body, hint):
    message = _zero("12-hks", hint, **answers(f"def my_hks(s, t):\n    {body}\n", "my_hks"))
    assert "notebook does not show" in message


@pytest.mark.parametrize("code, used", [
    ("my_hks = lbo.hks", "descriptors.hks"),
    ("from lbo_notebooks import analyses\ndef my_hks(spectrum, times):\n    return analyses.hks(spectrum, times)",
     "descriptors.hks"),
    ("import pyFM.signatures\ndef my_hks(s, t):\n    return pyFM.signatures.HKS(s.values, s.vectors, t)", "HKS"),
    ("from pyFM.signatures.HKS_functions import HKS\ndef my_hks(s, t):\n    return HKS(s.values, s.vectors, t)", "HKS"),
])
def test_hks_library_calls_earn_nothing(code, used):
    pytest.importorskip("pyFM") if "pyFM" in code else None
    _zero("12-hks", "not available", used, **answers(code, "my_hks"))


def test_hks_stubs_are_not_attempted():
    for code in ("my_hks = ...", "def my_hks(spectrum, times):\n    pass",
                 "def my_hks(spectrum, times):\n    raise NotImplementedError()"):
        _zero("12-hks", status="not attempted", **answers(code, "my_hks"))


# --- 12-fmap (build it yourself) ---------------------------------------------------------------------------

RIGHT_FMAPS = {
    "a sparse permutation matrix Π": """
        def my_functional_map(p2p, source, target, k):
            n2, n1 = target.n_vertices, source.n_vertices
            Pi = sp.csr_matrix((np.ones(n2), (np.arange(n2), p2p)), shape=(n2, n1))
            return target.vectors[:, :k].T @ (target.mass @ (Pi @ source.vectors[:, :k]))
    """,
    "the A-inner-product normal equations, np.linalg.solve": """
        def my_functional_map(p2p, source, target, k):
            phi2 = target.vectors[:, :k]
            gram = phi2.T @ (target.mass @ phi2)
            return np.linalg.solve(gram, phi2.T @ (target.mass @ source.vectors[p2p][:, :k]))
    """,
    "one entry at a time, a diagonal mass": """
        def my_functional_map(p2p, source, target, k):
            a = target.mass.diagonal()
            C = np.empty((k, k))
            for i in range(k):
                for j in range(k):
                    C[i, j] = np.sum(target.vectors[:, i] * a * source.vectors[p2p, j])
            return C
    """,
}


def test_fmap_solution_and_alternatives():
    message = _full("12-fmap", **answers(solution("12-fmap"), "my_functional_map"))
    assert "does not show" in message
    for name, code in RIGHT_FMAPS.items():
        _full("12-fmap", **answers(code, "my_functional_map"))


@pytest.mark.parametrize("body, hint", [
    ("return (t.vectors[:, :k].T @ (t.mass @ s.vectors[p, :k])).T", "transposed"),
    ("return t.vectors[:, :k].T @ s.vectors[p, :k]", "euclidean inner product"),
    ("return t.vectors[:, :k].T @ (t.mass @ s.vectors[np.argsort(p), :k])", "wrong way round"),
    ("return t.vectors[:, :k].T @ (s.mass @ s.vectors[p, :k])", "A₁"),
    ("return s.vectors[:, :k].T @ (s.mass @ t.vectors[p, :k])", "pull the first k"),  # source, target swapped
    ("return t.vectors[:, :k].T @ (t.mass @ s.vectors[p, : k - 1])", "k functions on each side"),
])
def test_fmap_wrong_answers(body, hint):
    _zero("12-fmap", hint, **answers(f"def my_functional_map(p, s, t, k):\n    {body}\n", "my_functional_map"))


@pytest.mark.parametrize("code, used", [
    ("from lbo_notebooks import analyses as fm\n"
     "def my_functional_map(p2p, source, target, k):\n"
     "    return fm.map_from_points(p2p, source, target, k_source=k, k_target=k)", "map_from_points"),
    ("def my_functional_map(p2p, source, target, k):\n"
     "    return lbo.map_from_points(p2p, source, target, k_source=k, k_target=k)", "map_from_points"),
    ("def my_functional_map(p2p, source, target, k):\n"
     "    return target.project(source.vectors[p2p, :k], k)", "Spectrum.project"),
    ("import pyFM.spectral\n"
     "def my_functional_map(p2p, source, target, k):\n"
     "    return pyFM.spectral.p2p_to_FM(p2p, source.vectors[:, :k], target.vectors[:, :k], A2=target.mass)",
     "p2p_to_FM"),
])
def test_fmap_library_calls_earn_nothing(code, used):
    pytest.importorskip("pyFM") if "pyFM" in code else None
    _zero("12-fmap", "not available", used, **answers(code, "my_functional_map"))


def test_fmap_is_judged_on_unseen_pairs():
    from lbo_notebooks.exercises.grading import nb12

    sizes = [(s.n_vertices, t.n_vertices) for _, _, s, t, _ in nb12._unseen_pairs()]
    assert any(a > b for a, b in sizes) and any(a < b for a, b in sizes) and any(a == b for a, b in sizes)
    assert all(3000 not in pair for pair in sizes)  # not the dog


# --- 12-zoomout-step (build it yourself) -------------------------------------------------------------------

RIGHT_ZOOMOUT_STEPS = {
    "brute force, one target vertex at a time": """
        def my_zoomout_step(C, source, target):
            k = len(C)
            images = source.vectors[:, :k] @ C.T
            p2p = np.array([np.argmin(((images - row) ** 2).sum(axis=1)) for row in target.vectors[:, :k]])
            phi2 = target.vectors[:, : k + 1]
            return phi2.T @ target.mass @ source.vectors[p2p][:, : k + 1], p2p
    """,
    "cKDTree, a sparse permutation matrix": """
        from scipy.spatial import cKDTree

        def my_zoomout_step(C, source, target):
            k = C.shape[1]
            _, p2p = cKDTree(source.vectors[:, :k] @ C.T).query(target.vectors[:, :k], k=1)
            n2, n1 = target.n_vertices, source.n_vertices
            Pi = sp.csr_matrix((np.ones(n2), (np.arange(n2), p2p)), shape=(n2, n1))
            C_next = target.vectors[:, : k + 1].T @ (target.mass @ (Pi @ source.vectors[:, : k + 1]))
            return C_next, p2p
    """,
    "sklearn NearestNeighbors, the A-weighted normal equations": """
        from sklearn.neighbors import NearestNeighbors

        def my_zoomout_step(C, source, target):
            k = C.shape[0]
            nn = NearestNeighbors(n_neighbors=1).fit(source.vectors[:, :k] @ C.T)
            p2p = nn.kneighbors(target.vectors[:, :k], return_distance=False)[:, 0]
            phi2 = target.vectors[:, : k + 1]
            gram = phi2.T @ (target.mass @ phi2)
            return np.linalg.solve(gram, phi2.T @ (target.mass @ source.vectors[p2p, : k + 1])), list(p2p)
    """,
    "single-precision scores, as the library's search": """
        def my_zoomout_step(C, source, target):
            k = len(C)
            images = (source.vectors[:, :k] @ C.T).astype(np.float32)
            rows = target.vectors[:, :k].astype(np.float32)
            score = rows @ images.T - 0.5 * (images**2).sum(axis=1)
            p2p = score.argmax(axis=1).astype(np.int32)
            a = target.mass.diagonal()
            return target.vectors[:, : k + 1].T @ (a[:, None] * source.vectors[p2p, : k + 1]), p2p
    """,
}


def test_zoomout_step_solution_and_alternatives():
    pytest.importorskip("sklearn")
    message = _full("12-zoomout-step", **answers(solution("12-zoomout-step"), "my_zoomout_step"))
    assert "does not show" in message
    for name, code in RIGHT_ZOOMOUT_STEPS.items():
        _full("12-zoomout-step", **answers(code, "my_zoomout_step"))


# The typical slips, each in a right answer's frame: ``nearest(queries, points)`` is a right brute force.
_STEP = """
from scipy.spatial import cKDTree

def nearest(queries, points):
    return cKDTree(points).query(queries)[1]

def pull(p2p, s, t, k):
    return t.vectors[:, :k].T @ (t.mass @ s.vectors[p2p, :k])

def my_zoomout_step(C, s, t):
    k = len(C)
    {body}
"""


@pytest.mark.parametrize("body, hint", [
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C)\n    return pull(p, s, t, k + 1), p", "transposed c"),
    ("p = nearest(t.vectors[:, :k] @ C, s.vectors[:, :k])\n    return pull(p, s, t, k + 1), p", "Φ₂ C with Φ₁"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k])\n    return pull(p, s, t, k + 1), p", "C is not used"),
    ("p = nearest(s.vectors[:, :k] @ C.T, t.vectors[:, :k])\n    return pull(p, s, t, k + 1), p", "wrong way"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, k), p", "not grown"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, None), p", "every computed"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n"
     "    return t.vectors[:, : k + 1].T @ s.vectors[p, : k + 1], p", "euclidean inner product"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n"
     "    return np.linalg.lstsq(t.vectors[:, : k + 1], s.vectors[p, : k + 1], rcond=None)[0], p", "least-squares"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, k + 1).T, p", "transposed"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return p, pull(p, s, t, k + 1)", "swapped"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, k + 1)", "the pair"),
    ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, k + 1), (p + 1) % s.n_vertices",
     "not the nearest"),
])
def test_zoomout_step_wrong_answers(body, hint):
    code = _STEP.replace("{body}", body)
    message = _zero("12-zoomout-step", hint, **answers(code, "my_zoomout_step"))
    assert "notebook does not show" in message


@pytest.mark.parametrize("code, used", [
    ("from lbo_notebooks import analyses as fm\n"
     "def my_zoomout_step(C, source, target):\n"
     "    k = len(C)\n"
     "    p2p = fm.points_from_map(C, source, target)\n"
     "    return fm.map_from_points(p2p, source, target, k_source=k + 1, k_target=k + 1), p2p", "points_from_map"),
    ("def my_zoomout_step(C, source, target):\n"
     "    C_next, _ = lbo.analyses.zoomout(C, source, target, k_final=len(C) + 1)\n"
     "    return C_next, lbo.points_from_map(C, source, target)", "zoomout"),
    ("from lbo_notebooks.analyses._functional_maps import _nearest_rows\n"
     "def my_zoomout_step(C, source, target):\n"
     "    k = len(C)\n"
     "    p2p = _nearest_rows(target.vectors[:, :k], source.vectors[:, :k] @ C.T)\n"
     "    return target.project(source.vectors[p2p, : k + 1], k + 1), p2p", "_nearest_rows"),
    ("import pyFM.spectral\n"
     "def my_zoomout_step(C, source, target):\n"
     "    k = len(C)\n"
     "    p2p = pyFM.spectral.FM_to_p2p(C, source.vectors[:, :k], target.vectors[:, :k])\n"
     "    return pyFM.spectral.p2p_to_FM(p2p, source.vectors[:, :k + 1], target.vectors[:, :k + 1], A2=target.mass), p2p",
     "FM_to_p2p"),
    ("from pyFM.refine.zoomout import zoomout_iteration\n"
     "from scipy.spatial import cKDTree\n"
     "def my_zoomout_step(C, source, target):\n"
     "    k = len(C)\n"
     "    p2p = cKDTree(source.vectors[:, :k] @ C.T).query(target.vectors[:, :k])[1]\n"
     "    return zoomout_iteration(C, source.vectors, target.vectors, A2=target.mass), p2p", "zoomout_iteration"),
])
def test_zoomout_step_library_calls_earn_nothing(code, used):
    pytest.importorskip("pyFM") if "pyFM" in code else None
    _zero("12-zoomout-step", "not available", used, **answers(code, "my_zoomout_step"))


def test_zoomout_step_stubs_are_not_attempted():
    for code in ("my_zoomout_step = ...", "def my_zoomout_step(C, source, target):\n    pass",
                 "def my_zoomout_step(C, source, target):\n    raise NotImplementedError()"):
        _zero("12-zoomout-step", status="not attempted", **answers(code, "my_zoomout_step"))


def test_zoomout_step_is_judged_on_unseen_maps():
    from lbo_notebooks.exercises.grading import nb12

    steps = nb12._unseen_steps()
    sizes = [(s.n_vertices, t.n_vertices) for _, _, s, t in steps]
    assert sizes[0][0] == sizes[0][1] and any(a > b for a, b in sizes) and any(a < b for a, b in sizes)
    assert all(3000 not in pair for pair in sizes)  # not the dog
    for _, C, source, target in steps:
        assert C.shape[0] < min(source.k, target.k)  # room for k + 1
        assert np.abs(C @ C.T - np.eye(len(C))).max() > 0.1  # not orthogonal: C^T is not C^-1


def test_zoomout_step_ties_accept_any_nearest_source_vertex():
    """With C = e_0 e_0^T every source vertex has the same image (φ_0 is constant): any point map is a
    nearest one, and C_next is judged as the map of the student's own point map."""
    from lbo_notebooks.exercises.grading import nb12
    from lbo_notebooks.exercises.toolbox import zoomout_step_hint

    _, _, source, target, _ = nb12._unseen_pairs()[1]
    k = 6
    C = np.zeros((k, k))
    C[0, 0] = 1.0
    for seed in (0, 1):
        p2p = np.random.default_rng(seed).integers(0, source.n_vertices, target.n_vertices)
        C_next = target.vectors[:, : k + 1].T @ (target.mass @ source.vectors[p2p, : k + 1])
        assert zoomout_step_hint((C_next, p2p), C, source, target) is None
        other = np.roll(p2p, 1)
        assert zoomout_step_hint((C_next, other), C, source, target) is not None  # another map's C_next


def test_zoomout_step_visible_check():
    """The visible check (exported from exercises as check_zoomout_step) on a small pair: the solution
    and the alternatives pass, the slips get their hints, a stub is not attempted."""
    from lbo_notebooks import shapes
    from lbo_notebooks.exercises.toolbox import check_zoomout_step
    from lbo_notebooks.spectral import eigenbasis

    mesh = shapes.bumpy_sphere(2, seed=3)
    one, two = eigenbasis(mesh, 14), eigenbasis(mesh.with_vertices(mesh.vertices * [1.0, 1.2, 0.9]), 14)
    pytest.importorskip("sklearn")
    for code in [solution("12-zoomout-step"), *RIGHT_ZOOMOUT_STEPS.values()]:
        assert check_zoomout_step(answers(code, "my_zoomout_step")["my_zoomout_step"], one, two, 10, show=False).correct
    for body, hint in [("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C)\n    return pull(p, s, t, k + 1), p",
                        "transposed c"),
                       ("p = nearest(s.vectors[:, :k] @ C.T, t.vectors[:, :k])\n    return pull(p, s, t, k + 1), p",
                        "wrong way"),
                       ("p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C.T)\n    return pull(p, s, t, k), p",
                        "not grown")]:
        step = answers(_STEP.replace("{body}", body), "my_zoomout_step")["my_zoomout_step"]
        feedback = check_zoomout_step(step, one, two, 10, show=False)
        assert feedback.status == "wrong" and hint in feedback.message.lower(), feedback.message
    stub = answers(student_edition("12-zoomout-step"), "my_zoomout_step")["my_zoomout_step"]
    assert check_zoomout_step(stub, one, two, 10, show=False).status == "not attempted"


def test_zoomout_step_same_answer_same_verdict():
    right = answers(solution("12-zoomout-step"), "my_zoomout_step")
    assert verdict("12-zoomout-step", **right) == verdict("12-zoomout-step", **right)
    wrong = answers(_STEP.replace("{body}", "p = nearest(t.vectors[:, :k], s.vectors[:, :k] @ C)\n"
                                            "    return pull(p, s, t, k + 1), p"), "my_zoomout_step")
    assert verdict("12-zoomout-step", **wrong) == verdict("12-zoomout-step", **wrong)


# --- 12-bound (compute) ------------------------------------------------------------------------------------------

def test_bound_solution_and_alternatives(kernel):
    given = answers(solution("12-bound"), "bound_z", **kernel)
    _full("12-bound", **given)
    exact = float(given["bound_z"])
    alternatives = {
        "the library's Dirichlet energy": """
            f = source.vertices[:, 2] - np.mean(source.vertices[:, 2])
            bound_z = lbo.dirichlet_energy(ref.stiffness, f) / ref.values[30] / (f @ ref.mass @ f)
        """,
        "a dense mass, the norm squared": """
            z = source.vertices[:, 2]
            z = z - z.mean()
            energy = z @ ref.stiffness.toarray() @ z
            bound_z = energy / (ref.values[30] * np.linalg.norm(np.sqrt(ref.mass.diagonal()) * z) ** 2)
        """,
    }
    for name, code in alternatives.items():
        _full("12-bound", **answers(code, "bound_z", **kernel))
    for right in (float(f"{exact:.6g}"), float(f"{exact:.5g}"), [exact], np.array(exact), str(exact)):
        _full("12-bound", bound_z=right)


def test_bound_wrong_answers(kernel):
    ref, v = kernel["ref"], kernel["source"].vertices
    f = v[:, 2] - v[:, 2].mean()
    energy, norm2, lam = f @ (ref.stiffness @ f), f @ (ref.mass @ f), ref.values
    exact = energy / lam[30] / norm2
    _zero("12-bound", "off by one", bound_z=energy / lam[29] / norm2)
    _zero("12-bound", "off by one", bound_z=energy / lam[31] / norm2)
    _zero("12-bound", "fraction", bound_z=energy / lam[30])
    _zero("12-bound", "A-norm", bound_z=energy / lam[30] / (f @ f))
    _zero("12-bound", "square root", bound_z=np.sqrt(exact))
    _zero("12-bound", "actually lost", bound_z=1 - np.sum(ref.project(f, 30) ** 2) / norm2)
    for digits in (1, 2, 3):                                # typed by hand, right to its digits
        _zero("12-bound", "more digits", bound_z=float(f"{exact:.{digits - 1}e}"))
    _zero("12-bound", "a number", bound_z=[exact, exact])
    _zero("12-bound", "a number", bound_z="small")


def test_the_bound_holds_for_f_z(kernel):
    """The claim that was in 12-bound's hidden test: the optimality bound holds for f_z at k = 30."""
    import lbo_notebooks as lbo

    ref, v = kernel["ref"], kernel["source"].vertices
    f = v[:, 2] - v[:, 2].mean()
    bound = (f @ (ref.stiffness @ f)) / ref.values[30]
    assert lbo.representation_error(ref, f, 30) <= bound * (1 + 1e-9)


# --- predictions ---------------------------------------------------------------------------------------------------

def test_alpha():
    _full("12-alpha", **answers(solution("12-alpha"), "best_alpha"))
    for right in (1, 1.0, np.int64(1), "1", np.float32(1.0)):
        _full("12-alpha", best_alpha=right)
    for wrong, hint in ((0, "regular metric"), (0.0, "regular metric"), (0.4, "in part"), (2, "0, 0.4 or 1"),
                        ("one", "one of"), (True, "a number")):
        _zero("12-alpha", hint, best_alpha=wrong)


def test_mirror():
    _full("12-mirror", **answers(solution("12-mirror"), "with_orientation", "without_orientation"))
    _full("12-mirror", with_orientation="Same Position", without_orientation="i->i")
    _full("12-mirror", with_orientation=" same  position", without_orientation="I -> I")
    _zero("12-mirror", "other way round", with_orientation="i -> i", without_orientation="same position")
    _zero("12-mirror", "reverses orientation", with_orientation="i -> i", without_orientation="i -> i")
    _zero("12-mirror", "intrinsic", with_orientation="same position", without_orientation="same position")
    _zero("12-mirror", "answer each", with_orientation="left-right swap", without_orientation="i -> i")


def test_zoomout():
    _full("12-zoomout", **answers(solution("12-zoomout"), "without_zoomout"))
    for right in ("Larger", " larger ", "LARGER"):
        _full("12-zoomout", without_zoomout=right)
    for wrong, hint in (("same", "50 more"), ("smaller", "sharpens"), ("bigger", "one of"), (1.5, "one of")):
        _zero("12-zoomout", hint, without_zoomout=wrong)


# --- 12-recap ----------------------------------------------------------------------------------------------------

def test_recap_partial_credit():
    assert verdict("12-recap", **answers(solution("12-recap"), "q1", "q2", "q3"))[0] == 3
    assert verdict("12-recap", q1=" B", q2="A", q3="c ")[0] == 3
    points, _, message = verdict("12-recap", q1="c", q2="a", q3="c")
    assert points == 2 and "Question 1" in message and "Question 2" not in message
    points, _, message = verdict("12-recap", q1="b", q2="b", q3="b")
    assert points == 1 and "1 of 3 right" in message and "Question 1" not in message
    assert verdict("12-recap", q1="a", q2="c", q3="a")[0] == 0
    assert verdict("12-recap", q1=["b"], q2=None, q3=3.0)[0] == 0       # any type: no error


# --- determinism, and the real graded run ----------------------------------------------------------------------

def test_the_same_answer_gets_the_same_grade(kernel):
    given = answers(solution("12-hks"), "my_hks")
    assert verdict("12-hks", **given) == verdict("12-hks", **given)
    wrong = {"bound_z": 0.05}
    assert verdict("12-bound", **wrong) == verdict("12-bound", **wrong)


def test_the_real_graded_run():
    """Through the real fresh process, as nbgrader runs it: the solution earns the points, a wrapper
    of the library none."""
    assert graded("12-fmap", **answers(solution("12-fmap"), "my_functional_map")) == 5.0
    assert graded("12-zoomout-step", **answers(solution("12-zoomout-step"), "my_zoomout_step")) == 5.0
    assert graded("12-hks", my_hks=lambda s, t: __import__("lbo_notebooks").hks(s, t)) == 0.0


KERNEL = """
import json, sys
import numpy as np
from lbo_notebooks.exercises.grading import grade

exec(sys.argv[1], globals())
points = {}
for exercise, name in (("12-hks", "my_hks"), ("12-fmap", "my_functional_map")):
    try:
        points[exercise] = grade(exercise, **{name: globals()[name]})
    except AssertionError as err:
        points[exercise] = str(err)
print(json.dumps(points))
"""


def test_names_imported_from_the_library_in_a_fresh_kernel_earn_nothing():
    """As in a real kernel (where nothing was ever blocked): functions imported by name from our
    package and from pyFM's package namespace, wrapped, are unavailable in the graded run."""
    import subprocess
    import sys

    pytest.importorskip("pyFM")
    code = ("from lbo_notebooks.analyses._descriptors import hks\n"
            "from pyFM.spectral import p2p_to_FM\n"
            "def my_hks(spectrum, times):\n"
            "    return hks(spectrum, times)\n"
            "def my_functional_map(p2p, source, target, k):\n"
            "    return p2p_to_FM(p2p, source.vectors[:, :k], target.vectors[:, :k], A2=target.mass)\n")
    run = subprocess.run([sys.executable, "-c", KERNEL, code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    points = json.loads(run.stdout.strip().splitlines()[-1])
    assert "0 / 5 points" in points["12-hks"] and "descriptors.hks` is not available" in points["12-hks"]
    assert "0 / 5 points" in points["12-fmap"] and "p2p_to_FM` is not available" in points["12-fmap"]
