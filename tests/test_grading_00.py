"""The graded tests of notebook 00 (lbo_notebooks/exercises/grading/nb00.py), on answers written as
students write them: the instructor's, correct ones written differently, typical wrong ones and
placeholders; and notebook 00 released on its own, on a machine where open3d cannot be imported."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from lbo_notebooks import shapes
from lbo_notebooks.exercises.grading import load_graders

from .grading_support import answers, full_points, graded, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "00_start_here.ipynb"
_REGION = re.compile(r"### BEGIN SOLUTION\n(.*?)### END SOLUTION", re.S)


def _cells() -> list[dict]:
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    for cell in cells:
        cell["source"] = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
    return cells


def solution(exercise: str) -> str:
    """The instructor's answer cell of ``exercise``, between its solution markers."""
    (cell,) = [c for c in _cells() if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    return _REGION.search(cell["source"]).group(1)


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("answers")


@pytest.fixture(scope="module")
def loaded(folder):
    """The notebook's `loaded`: shapes.bumpy_sphere(3) written to binary PLY and read back."""
    import lbo_notebooks as lbo

    return lbo.load_mesh(lbo.save_mesh(shapes.bumpy_sphere(3), folder / "blob.ply"))


def _context(folder):
    from lbo_notebooks import plotting

    return {"folder": folder, "plotting": plotting}


def test_kinds_and_points():
    graders = load_graders("00-sphere")
    assert {e: (g.kind, g.points) for e, g in graders.items() if e.startswith("00-")} == {
        "00-sphere": ("predict", 1), "00-size": ("compute", 2), "00-torus": ("explore", 2), "00-missing": ("explore", 2)}


# --- 00-sphere ---------------------------------------------------------------------------------

SPHERE_RIGHT = [
    "sphere_values = np.repeat([0, 2, 6], [1, 3, 5])",
    "sphere_values = [l * (l + 1) for l in range(3) for _ in range(2 * l + 1)]",
    "sphere_values = (0.0, 2.0, 2.0, 2.0, 6.0, 6.0, 6.0, 6.0, 6.0)",
    "sphere_values = np.array([[0, 2, 2, 2, 6, 6, 6, 6, 6]])",
]
SPHERE_WRONG = [
    ("sphere_values = [l * l for l in range(3) for _ in range(2 * l + 1)]", "ℓ²"),
    ("sphere_values = [l * (l + 1) for l in range(9)]", "2ℓ+1 times"),
    ("sphere_values = [0, 2, 2, 6, 6, 6, 6, 6, 12]", "2ℓ+1"),
    ("sphere_values = [6, 6, 6, 6, 6, 2, 2, 2, 0]", "increasing"),
    ("sphere_values = [0, 2, 2, 2, 6, 6, 6, 6]", "nine"),
    ("sphere_values = lbo.eigenbasis(shapes.icosphere(3), 9).values", "measured"),
    ("sphere_values = {0: 0, 1: 2}", "nine"),
]


def test_sphere_solution_and_alternatives_earn_full_points():
    points = full_points("00-sphere")
    assert verdict("00-sphere", **answers(solution("00-sphere"), "sphere_values"))[0] == points
    for code in SPHERE_RIGHT:
        assert verdict("00-sphere", **answers(code, "sphere_values"))[0] == points, code


@pytest.mark.parametrize("code, hint", SPHERE_WRONG)
def test_sphere_wrong_answers_earn_nothing(code, hint):
    points, status, message = verdict("00-sphere", **answers(code, "sphere_values"))
    assert (points, status) == (0, "wrong") and hint in message, message
    assert "[0, 2, 2, 2" not in message


@pytest.mark.parametrize("placeholder", [..., None, [..., ...]])
def test_sphere_placeholder_is_not_attempted(placeholder):
    points, status, message = verdict("00-sphere", sphere_values=placeholder)
    assert (points, status) == (0, "not attempted") and message.startswith("Not attempted")


# --- 00-size -----------------------------------------------------------------------------------

SIZE_RIGHT = [
    "size = np.array([loaded.n_vertices, loaded.n_faces])",
    "size = [loaded.vertices.shape[0], loaded.faces.shape[0]]",
    "n_v, n_t = loaded.vertices.shape[0], float(len(loaded.faces))\nsize = (np.int64(n_v), n_t)",
]
SIZE_WRONG = [
    ("size = (len(loaded.faces), len(loaded.vertices))", "Swapped"),
    ("size = (loaded.vertices.size, loaded.faces.size)", "Three times"),
    ("size = loaded.vertices.shape", "coordinates"),
    ("size = (loaded.n_vertices, len(loaded.edges))", "edges"),
    ("size = (loaded.n_vertices + 1, loaded.n_faces)", "rows"),
    ("size = {'vertices': loaded.n_vertices, 'triangles': loaded.n_faces}", "two numbers"),
    ("size = (loaded.n_vertices + 0.5, loaded.n_faces)", "whole numbers"),
]


def test_size_solution_and_alternatives_earn_full_points(loaded):
    points = full_points("00-size")
    assert verdict("00-size", **answers(solution("00-size"), "size", loaded=loaded))[0] == points
    for code in SIZE_RIGHT:
        assert verdict("00-size", **answers(code, "size", loaded=loaded))[0] == points, code


@pytest.mark.parametrize("code, hint", SIZE_WRONG)
def test_size_wrong_answers_earn_nothing(code, hint, loaded):
    points, status, message = verdict("00-size", **answers(code, "size", loaded=loaded))
    assert (points, status) == (0, "wrong") and hint in message, message


def test_size_is_judged_on_the_blob_not_on_the_kernels_loaded():
    # A kernel whose `loaded` was changed while exploring: its counts are not the prompt's mesh's.
    other = shapes.torus()
    assert verdict("00-size", size=(other.n_vertices, other.n_faces))[0] == 0
    assert verdict("00-size", size=(..., ...))[1] == "not attempted"


# --- 00-torus ----------------------------------------------------------------------------------

TORUS_RIGHT = [
    # another name, another k, another sign and scale
    "ring = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'ring.obj'))\n"
    "phi6 = -2.5 * lbo.eigenbasis(ring, 12).vectors[:, 6]",
    # scipy on the library's W and A, shift-invert, a list of floats
    "ring = lbo.load_mesh(lbo.save_mesh(shapes.torus(), str(folder / 'ring2.obj')))\n"
    "W, A = lbo.stiffness_matrix(ring), lbo.mass_matrix(ring)\n"
    "vals, vecs = sla.eigsh(W, k=8, M=A, sigma=-0.01)\n"
    "phi6 = list(vecs[:, np.argsort(vals)[6]])",
    # a column kept as a column
    "mesh = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'col.obj'))\n"
    "phi6 = lbo.eigenbasis(mesh, 7).vectors[:, 6:7]",
]
TORUS_WRONG = [
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'a.obj'))\nphi6 = lbo.eigenbasis(t, 7).vectors[:, 5]",
     "indices start at 0"),
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'b.obj'))\nphi6 = lbo.eigenbasis(t, 6).vectors[:, -1]",
     "indices start at 0"),
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'c.obj'))\nphi6 = lbo.eigenbasis(t, 9).vectors[:, 7]",
     "larger eigenvalue"),
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'd.obj'))\nphi6 = lbo.eigenbasis(t, 7).vectors",
     "one column"),
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'e.obj'))\n"
     "s = lbo.eigenbasis(t, 7)\nphi6 = s.vectors[:, 5] + s.vectors[:, 6]", "Not an eigenfunction"),
    ("phi6 = lbo.eigenbasis(shapes.icosphere(3), 7).vectors[:, 6]", "one value per vertex"),
    ("t = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / 'f.obj'))\nphi6 = lbo.eigenbasis(t, 7).values[6]",
     "one value per vertex"),
]


def test_torus_solution_and_alternatives_earn_full_points(folder):
    points = full_points("00-torus")
    assert verdict("00-torus", **answers(solution("00-torus"), "phi6", **_context(folder)))[0] == points
    for code in TORUS_RIGHT:
        assert verdict("00-torus", **answers(code, "phi6", **_context(folder)))[0] == points, code


@pytest.mark.parametrize("code, hint", TORUS_WRONG)
def test_torus_wrong_answers_earn_nothing(code, hint, folder):
    points, status, message = verdict("00-torus", **answers(code, "phi6", **_context(folder)))
    assert (points, status) == (0, "wrong") and hint in message, message


def test_torus_placeholder_is_not_attempted():
    assert verdict("00-torus", phi6=...)[:2] == (0, "not attempted")


def test_an_obj_round_trip_keeps_the_torus_exactly(folder):
    """The claim the old hidden test asserted (on the solution's `torus`), as a test of the library:
    the grader may judge φ_6 on shapes.torus() because the .obj file gives back the same arrays."""
    import lbo_notebooks as lbo

    ring = shapes.torus()
    back = lbo.load_mesh(lbo.save_mesh(ring, folder / "claim.obj"))
    np.testing.assert_array_equal(back.faces, ring.faces)
    np.testing.assert_array_equal(back.vertices, ring.vertices)


# --- 00-missing --------------------------------------------------------------------------------

MISSING_RIGHT = [
    # the natural answer that passed the old hidden test only when the temporary path held a 7
    "p = folder / 'three.off'\np.write_text('OFF\\n3 1 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 3\\n')\n"
    "try:\n    lbo.load_mesh(p)\nexcept Exception as err:\n    error = err",
    # OBJ counts from 1: index 4 of three 'v' lines
    "p = folder / 'past.obj'\np.write_text('v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 4\\n')\n"
    "try:\n    lbo.load_mesh(str(p))\nexcept lbo.MeshError as e:\n    error = e",
    # PLY, and a face in the middle of the file
    "text = 'ply\\nformat ascii 1.0\\nelement vertex 4\\nproperty float x\\nproperty float y\\nproperty float z\\n'\n"
    "text += 'element face 2\\nproperty list uchar int vertex_indices\\nend_header\\n'\n"
    "text += '0 0 0\\n1 0 0\\n0 1 0\\n0 0 1\\n3 0 1 2\\n3 0 2 4\\n'\n"
    "(folder / 'p.ply').write_text(text)\n"
    "try:\n    lbo.load_mesh(folder / 'p.ply')\nexcept lbo.MeshError as e:\n    error = e",
    # OBJ's 0, which it refuses outright
    "(folder / 'zero.obj').write_text('v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 0 1 2\\n')\n"
    "try:\n    lbo.load_mesh(folder / 'zero.obj')\nexcept lbo.MeshError as e:\n    error = e",
]
MISSING_WRONG = [
    ("b = folder / 'twice.off'\nb.write_text('OFF\\n3 2 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 2\\n3 0 1 2\\n')\n"
     "try:\n    lbo.load_mesh(b)\nexcept lbo.MeshError as e:\n    error = e", "another defect"),
    ("try:\n    lbo.load_mesh(folder / 'nowhere.off')\nexcept Exception as e:\n    error = e", "FileNotFoundError"),
    ("b = folder / 'text.off'\nb.write_text('OFF\\n3 1 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 7\\n')\n"
     "try:\n    lbo.load_mesh(b)\nexcept lbo.MeshError as e:\n    error = str(e)", "not its text"),
    ("error = lbo.MeshError", "exception class"),
    ("error = 7", "exception object"),
]


def test_missing_solution_and_alternatives_earn_full_points(folder):
    points = full_points("00-missing")
    given = answers(solution("00-missing"), "error", **_context(folder))
    assert "vertex index 7," in str(given["error"])  # the old hidden test's claim: it names the index
    assert verdict("00-missing", **given)[0] == points
    for code in MISSING_RIGHT:
        assert verdict("00-missing", **answers(code, "error", **_context(folder)))[0] == points, code
    # A Mesh built from arrays says it as well.
    assert verdict("00-missing", **answers(
        "try:\n    lbo.Mesh(np.eye(3), [[0, 1, 3]])\nexcept lbo.MeshError as e:\n    error = e", "error"))[0] == points


@pytest.mark.parametrize("code, hint", MISSING_WRONG)
def test_missing_wrong_answers_earn_nothing(code, hint, folder):
    points, status, message = verdict("00-missing", **answers(code, "error", **_context(folder)))
    assert (points, status) == (0, "wrong") and hint in message, message


def test_missing_a_mesh_instead_of_an_error_earns_nothing(folder):
    # The file loaded: no face refers to a missing vertex. (A Mesh does not survive pickling today,
    # so the graded run says it could not read the answer back; in-process the check's hint.)
    code = ("b = folder / 'ok.off'\nb.write_text('OFF\\n3 1 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 2\\n')\n"
            "error = lbo.load_mesh(b)")
    points, status, message = verdict("00-missing", **answers(code, "error", **_context(folder)))
    assert (points, status) == (0, "wrong") and ("returned a mesh" in message or "could not be read back" in message)
    from lbo_notebooks.exercises.grading.nb00 import _missing
    from lbo_notebooks.exercises.feedback import Stop

    with pytest.raises(Stop, match="returned a mesh"):
        _missing(shapes.icosphere(0))


def test_missing_placeholder_is_not_attempted():
    assert verdict("00-missing", error=...)[:2] == (0, "not attempted")


@pytest.mark.parametrize("name", ["7", "plain", "uses vertex index 9, outside 0..2", "it's \"quoted\""])
def test_missing_does_not_depend_on_the_folders_name(tmp_path, name):
    """The grade reads what the message says about the file, never its path: the same files in
    folders with and without a 7 (or with the right words) in their name get the same points."""
    import lbo_notebooks as lbo

    where = tmp_path / name
    where.mkdir()
    results = []
    for file, text in [("i.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                       ("d.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n")]:
        (where / file).write_text(text)
        with pytest.raises(lbo.MeshError) as info:
            lbo.load_mesh(where / file)
        results.append(verdict("00-missing", error=info.value)[0])
    assert results == [full_points("00-missing"), 0]


def test_an_in_range_negative_obj_index_is_no_missing_vertex():
    from lbo_notebooks.exercises.grading.nb00 import _names_a_missing_vertex

    assert _names_a_missing_vertex("line 4 ('f 1 2 -4') uses vertex index -4, outside 1..3 (the file ...)")
    assert not _names_a_missing_vertex("line 4 ('f 1 2 -1') uses vertex index -1, outside 1..3 (the file ...)")
    assert not _names_a_missing_vertex("face 0 uses vertex index 2, outside 0..2")


# --- every exercise ----------------------------------------------------------------------------

def test_same_answers_same_verdicts(folder, loaded):
    cases = [("00-sphere", {"sphere_values": [0, 2, 2, 6, 6, 6, 6, 6, 12]}),
             ("00-size", answers(solution("00-size"), "size", loaded=loaded)),
             ("00-torus", answers(TORUS_WRONG[0][0], "phi6", **_context(folder))),
             ("00-missing", answers(MISSING_RIGHT[0], "error", **_context(folder)))]
    for exercise, given in cases:
        assert verdict(exercise, **given) == verdict(exercise, **given), exercise


def test_the_real_graded_run(folder):
    given = answers(solution("00-missing"), "error", **_context(folder))
    assert graded("00-missing", **given) == 2.0
    assert graded("00-sphere", sphere_values=[0, 1, 1, 1, 4, 4, 4, 4, 4]) == 0.0


# --- released alone, without open3d -----------------------------------------------------------

def _setup_cell() -> str:
    return _cells()[1]["source"]


def test_the_series_check_holds_in_the_checkout_and_skips_when_released_alone(tmp_path, monkeypatch):
    setup = _setup_cell()
    monkeypatch.chdir(NOTEBOOK.parent)  # the checkout: every notebook is there
    exec(compile(setup, "<00 setup>", "exec"), {})
    alone = tmp_path / "source" / "00_start_here"  # an nbgrader assignment folder
    alone.mkdir(parents=True)
    (alone / NOTEBOOK.name).write_bytes(NOTEBOOK.read_bytes())
    monkeypatch.chdir(alone)
    exec(compile(setup, "<00 setup>", "exec"), {})  # no error, a note
    # A checkout (the package installed from it) that lost a notebook still fails.
    import lbo_notebooks

    checkout = tmp_path / "repo"
    (checkout / "lbo_notebooks").mkdir(parents=True)
    (checkout / "notebooks").mkdir()
    (checkout / "notebooks" / NOTEBOOK.name).write_bytes(NOTEBOOK.read_bytes())
    monkeypatch.setattr(lbo_notebooks, "__file__", str(checkout / "lbo_notebooks" / "__init__.py"))
    monkeypatch.chdir(checkout / "notebooks")
    with pytest.raises(AssertionError, match="missing notebooks"):
        exec(compile(setup, "<00 setup>", "exec"), {})


def test_notebook_00_reads_nothing_outside_its_folder():
    assert not re.search(r"""["']\.\./""", "".join(c["source"] for c in _cells() if c["cell_type"] == "code"))


_RUN_ALONE = """
import sys
sys.modules["open3d"] = None  # `import open3d` fails, as where its system libraries are missing
import json, os
cells = json.load(open({notebook!r}, encoding="utf-8"))["cells"]
namespace = {{"__name__": "__main__"}}
for cell in cells:
    if cell["cell_type"] != "code":
        continue
    source = "".join(cell["source"])
    if "grade(" in source:  # the graded run is another process; judge in this one, open3d still blocked
        from lbo_notebooks.exercises.grading.__main__ import _verdict
        import cloudpickle, re
        exercise = re.search(r'grade\\("([\\w-]+)"', source).group(1)
        names = re.findall(r"(\\w+)=\\1", source)
        result = _verdict(exercise, cloudpickle.dumps({{n: namespace[n] for n in names}}))
        assert result.get("fraction") == 1.0, (exercise, result)
        source = source.split("### BEGIN HIDDEN TESTS")[0]
    exec(compile(source, "<cell>", "exec"), namespace)
assert sys.modules["open3d"] is None
print("ran", sorted(os.listdir(".")))
"""


def test_notebook_00_runs_alone_without_open3d(tmp_path):
    """Notebook 00 as one assignment (only itself in its folder), every code cell with the
    instructor's answers, on an interpreter where open3d cannot be imported; its graders too."""
    alone = tmp_path / "00_start_here"
    alone.mkdir()
    copy = alone / NOTEBOOK.name
    copy.write_bytes(NOTEBOOK.read_bytes())
    script = textwrap.dedent(_RUN_ALONE.format(notebook=str(copy)))
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-c", script], cwd=alone, capture_output=True, text=True, timeout=300,
                          env=env)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "handed out on its own" in done.stdout and "ran ['00_start_here.ipynb']" in done.stdout
