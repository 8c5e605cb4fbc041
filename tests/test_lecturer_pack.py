"""The lecturer pack (docs/lecturers/, scripts/slides.py, scripts/booklet.py): the three documents
have their sections, the plan's minutes are the notebooks', the exam's numeric answers hold in the
library, and slides and booklet build offline with every exercise and no solution in the slides."""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import nbformat
import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks import shapes

REPO = Path(__file__).resolve().parent.parent
DOCS = REPO / "docs" / "lecturers"
NOTEBOOKS = sorted((REPO / "notebooks").glob("[0-9][0-9]_*.ipynb"))


def _load(name: str):
    if name not in sys.modules:
        sys.path.insert(0, str(REPO / "scripts"))
        spec = importlib.util.spec_from_file_location(name, REPO / "scripts" / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


@pytest.fixture(scope="module")
def booklet():
    return _load("booklet")


@pytest.fixture(scope="module")
def slides():
    return _load("slides")


def _core() -> list[str]:
    plan = (DOCS / "plan.md").read_text()
    return re.findall(r"^\| (\d\d) \|[^|]*\| core \|", plan, re.M)


# --- the documents -------------------------------------------------------------------------------

def test_plan_minutes_are_the_notebooks_stated_minutes(booklet):
    plan = (DOCS / "plan.md").read_text()
    stated = booklet.notebook_minutes()
    assert booklet.plan_minutes(plan) == stated, (
        "docs/lecturers/plan.md and the notebooks' headers differ: run python scripts/booklet.py --sync-plan")
    assert booklet.sync_plan(plan, stated) == plan            # totals and weekly sums too
    assert f"**{sum(stated.values())} minutes**" in plan


def test_plan_sync_follows_a_changed_header(booklet):
    plan = (DOCS / "plan.md").read_text()
    changed = dict(booklet.notebook_minutes(), **{"05": 95})
    synced = booklet.sync_plan(plan, changed)
    assert booklet.plan_minutes(synced)["05"] == 95 and f"**{sum(changed.values())} minutes**" in synced
    assert re.search(r"^\| 5 \| 05 \| 95 \|", synced, re.M)     # the week of notebook 05


def test_plan_has_every_notebook_with_role_prerequisites_and_a_schedule():
    plan = (DOCS / "plan.md").read_text()
    rows = re.findall(r"^\| (\d\d) \|([^\n]*)$", plan.split("## Weekly schedule")[0], re.M)
    assert [nb for nb, _ in rows] == [p.name[:2] for p in NOTEBOOKS]
    assert all(re.search(r"\| (core|optional) \|", rest) and rest.count("|") >= 5 for _, rest in rows)
    weeks = re.findall(r"^\| (\d+) \| ([\d, ]+) \| (\d+) \|", plan.split("## Weekly schedule")[1], re.M)
    assert len(weeks) >= 10 and {"00", "05", "11"} <= {n for _, nbs, _ in weeks for n in re.findall(r"\d\d", nbs)}
    assert set(_core()) >= {"00", "02", "03", "05", "07", "08", "09", "11"}


def test_project_has_milestones_deliverables_and_a_rubric_table():
    project = (DOCS / "project.md").read_text()
    assert "notebook 04" in project.lower()
    milestones = re.split(r"^### Milestone \d", project, flags=re.M)[1:]
    assert len(milestones) >= 3 and all("**Deliverables.**" in m for m in milestones)
    rubric = project.split("## Rubric")[1]
    header = re.search(r"^\| Criterion \|(.*)\|$", rubric, re.M)
    levels = [c.strip() for c in header.group(1).split("|")]
    rows = [r for r in re.findall(r"^\|(.*)\|$", rubric, re.M)[2:]]
    assert len(levels) >= 3 and len(rows) >= 4
    points = [[int(c) for c in r.split("|")[1:]] for r in rows]
    assert all(len(p) == len(levels) and p == sorted(p, reverse=True) for p in points)
    assert sum(p[0] for p in points) == 100


def test_exam_has_two_worked_questions_per_core_notebook():
    exam = (DOCS / "exam.md").read_text()
    questions = re.split(r"^### ", exam, flags=re.M)[1:]
    by_notebook: dict[str, int] = {}
    for q in questions:
        assert "**Worked answer.**" in q and len(q.split("**Worked answer.**")[1].strip()) > 100, q[:40]
        by_notebook[q[1:3]] = by_notebook.get(q[1:3], 0) + 1
    assert all(by_notebook.get(nb, 0) >= 2 for nb in _core()), by_notebook


# --- the exam's numbers, again with the library ----------------------------------------------------

@pytest.fixture(scope="module")
def sphere():
    return lbo.eigenbasis(shapes.icosphere(4), 26)


def test_q00_1_twenty_five_eigenvalues_up_to_twenty(sphere):
    exact = np.concatenate([[l * (l + 1)] * (2 * l + 1) for l in range(6)])
    assert np.sum(exact <= 20) == 25 and exact[25] == 30
    assert sphere.values[24] < 20 < sphere.values[25]
    assert abs(sphere.values[24] / 20 - 1) < 0.02 and abs(sphere.values[25] / 30 - 1) < 0.02


def test_q00_2_the_height_attains_the_bound(sphere):
    z = shapes.icosphere(4).vertices[:, 2]
    error, bound = lbo.representation_error(sphere, z, 1), lbo.error_bound(sphere, z, 1)
    assert error == pytest.approx(bound, rel=1e-6) and error == pytest.approx(4 * np.pi / 3, rel=0.01)
    assert lbo.dirichlet_energy(sphere.stiffness, z) == pytest.approx(8 * np.pi / 3, rel=0.01)
    assert lbo.representation_error(sphere, z, 4) < 1e-6 * error


def _path(n: int) -> np.ndarray:
    return np.diag(np.r_[1.0, 2 * np.ones(n - 2), 1.0]) - np.eye(n, k=1) - np.eye(n, k=-1)


def test_q02_1_the_ring_of_eight():
    L = 2 * np.eye(8) - np.roll(np.eye(8), 1, axis=1) - np.roll(np.eye(8), -1, axis=1)
    expected = [0, 2 - np.sqrt(2), 2 - np.sqrt(2), 2, 2, 2 + np.sqrt(2), 2 + np.sqrt(2), 4]
    np.testing.assert_allclose(np.linalg.eigvalsh(L), expected, atol=1e-12 * 4)
    j = np.arange(8)
    for k in range(8):
        for wave in (np.cos(2 * np.pi * k * j / 8), np.sin(2 * np.pi * k * j / 8)):
            np.testing.assert_allclose(L @ wave, (2 - 2 * np.cos(2 * np.pi * k / 8)) * wave, atol=1e-12 * 4)


def test_q02_2_a_step_on_a_string():
    L = _path(200)
    lam, Phi = np.linalg.eigh(L)
    np.testing.assert_allclose(lam, 2 - 2 * np.cos(np.pi * np.arange(200) / 200), atol=1e-12 * 4)
    f = (np.arange(200) >= 100).astype(float)
    c = Phi.T @ f
    assert f @ L @ f == pytest.approx(1.0)
    assert 1 / lam[10] == pytest.approx(40.6, rel=1e-3)
    assert np.sum(c[10:] ** 2) == pytest.approx(2.0, rel=0.02) and np.sum(c[1:] ** 2) == pytest.approx(50)


def test_q03_1_one_right_triangle():
    tri = lbo.Mesh(np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]]))
    W = lbo.stiffness_matrix(tri).toarray()
    np.testing.assert_allclose(W, [[1, -0.5, -0.5], [-0.5, 0.5, 0], [-0.5, 0, 0.5]], atol=1e-14)
    x = tri.vertices[:, 0]
    assert x @ W @ x == pytest.approx(0.5)
    np.testing.assert_allclose(lbo.mass_matrix(tri, mass_kind="barycentric").toarray(), np.eye(3) / 6, atol=1e-15)
    np.testing.assert_allclose(lbo.mass_matrix(tri, mass_kind="consistent").toarray(),
                               (np.ones((3, 3)) + np.eye(3)) / 24, atol=1e-15)


def test_q03_2_and_q03_3_scaling_and_coefficients():
    ball = shapes.icosphere(2)
    one, three = lbo.eigenbasis(ball, 10), lbo.eigenbasis(ball.with_vertices(3 * ball.vertices), 10)
    np.testing.assert_allclose(three.values[1:], one.values[1:] / 9, rtol=1e-8)
    np.testing.assert_allclose(np.abs(three.vectors[:, 0]), np.abs(one.vectors[:, 0]) / 3, rtol=1e-8)
    c = np.random.default_rng(0).normal(size=10)
    f = one.vectors @ c
    np.testing.assert_allclose(one.vectors.T @ (one.mass @ f), c, atol=1e-10 * np.abs(c).max())
    assert np.linalg.norm(one.vectors.T @ f - c) > 0.5 * np.linalg.norm(c)


def test_q04_1_three_pieces_three_zero_eigenvalues():
    ball = shapes.icosphere(2)
    n = ball.n_vertices
    three = lbo.Mesh(np.vstack([ball.vertices + [3.0 * i, 0, 0] for i in range(3)]),
                     np.vstack([ball.faces + i * n for i in range(3)]))
    spectrum = lbo.eigenbasis(three, 5)
    assert np.sum(np.abs(spectrum.values) < 1e-8 * spectrum.values[-1]) == 3
    null = spectrum.vectors[:, :3]
    assert all(np.ptp(null[i * n:(i + 1) * n], axis=0).max() < 1e-8 * np.abs(null).max() for i in range(3))


def test_q04_2_two_sheets_fuse_below_r_176():
    reach = np.sqrt(4 * 30 / 642)
    assert reach == pytest.approx(0.432, abs=1e-3) and 1 / (1 - reach) == pytest.approx(1.76, abs=0.005)
    inner = shapes.icosphere(3).vertices
    assert len(inner) == 642
    zeros = {}
    for r in (1.5, 2.0):
        values = lbo.eigenbasis(lbo.PointCloud(np.vstack([inner, r * inner])), 3).values
        zeros[r] = int(np.sum(np.abs(values) < 1e-8 * values[-1]))
    assert zeros == {1.5: 1, 2.0: 2}


@pytest.fixture(scope="module")
def blob():
    return lbo.eigenbasis(shapes.icosphere(3), 22)


def test_q05_1_the_eigenbasis_and_the_basis_without_the_constant(blob):
    W, A = blob.stiffness, blob.mass
    assert lbo.worst_case_ratio(blob.vectors[:, :20], W, A) * blob.values[20] == pytest.approx(1, rel=1e-8)
    assert lbo.worst_case_ratio(blob.vectors[:, 1:21], W, A) == np.inf


def test_q05_2_the_witness_in_the_span_of_n_plus_one(blob):
    n = 10
    rng = np.random.default_rng(1)
    V = np.column_stack([np.ones(blob.vectors.shape[0]), rng.normal(size=(blob.vectors.shape[0], n - 1))])
    constraints = V.T @ (blob.mass @ blob.vectors[:, : n + 1])          # n x (n + 1)
    a = np.linalg.svd(constraints)[2][-1]
    f = blob.vectors[:, : n + 1] @ a
    assert np.abs(V.T @ (blob.mass @ f)).max() < 1e-10 * np.abs(V.T @ (blob.mass @ blob.vectors[:, :n + 1])).max()
    assert (f @ (blob.mass @ f)) / (f @ (blob.stiffness @ f)) >= (1 - 1e-9) / blob.values[n]
    assert lbo.worst_case_ratio(V, blob.stiffness, blob.mass) >= (1 - 1e-9) / blob.values[n]


def test_q05_3_one_more_function(blob):
    g = np.random.default_rng(2).normal(size=blob.vectors.shape[0])
    C = lbo.worst_case_ratio(np.column_stack([blob.vectors[:, :20], g]), blob.stiffness, blob.mass)
    assert (1 - 1e-9) / blob.values[21] <= C <= (1 + 1e-9) / blob.values[20]


def _plane_min(M: np.ndarray, u: np.ndarray) -> float:
    u = u / np.linalg.norm(u)
    Q = np.linalg.svd(np.eye(3) - np.outer(u, u))[0][:, :2]
    return np.linalg.eigvalsh(Q.T @ M @ Q)[0]


def test_q07_1_and_q07_2_planes_through_diag_1_2_5():
    M = np.diag([1.0, 2.0, 5.0])
    assert _plane_min(M, np.ones(3)) == pytest.approx((16 - np.sqrt(52)) / 6, rel=1e-12)
    assert (16 - np.sqrt(52)) / 6 == pytest.approx(1.465, abs=1e-3) and (16 + np.sqrt(52)) / 6 == pytest.approx(3.869, abs=1e-3)
    for degrees in (0, 30, 50, 60, 70, 85):
        t = np.radians(degrees)
        expected = min(2.0, 1 + 4 * np.cos(t) ** 2)
        assert _plane_min(M, np.array([np.cos(t), 0, np.sin(t)])) == pytest.approx(expected, rel=1e-9)
    assert 1 + 4 * np.cos(np.radians(70)) ** 2 == pytest.approx(1.468, abs=1e-3)


def test_q08_1_gauss_bonnet():
    torus = lbo.angle_defects(shapes.torus())
    assert abs(torus.sum()) < 1e-12 * np.abs(torus).sum()
    assert lbo.angle_defects(shapes.icosphere(3)).sum() == pytest.approx(4 * np.pi, rel=1e-12)
    assert lbo.angle_defects(shapes.disk()).sum() == pytest.approx(2 * np.pi, rel=1e-12)


def test_q08_2_eigenvalues_scale_as_s_to_the_minus_2_1_minus_alpha():
    ellipsoid = shapes.ellipsoid(subdivisions=3)
    doubled = ellipsoid.with_vertices(2 * ellipsoid.vertices)
    for alpha, factor in ((0.0, 0.25), (0.4, 0.435), (1.0, 1.0)):
        ratio = lbo.eigenbasis(doubled, 6, alpha=alpha).values[1:] / lbo.eigenbasis(ellipsoid, 6, alpha=alpha).values[1:]
        np.testing.assert_allclose(ratio, 2 ** (-2 * (1 - alpha)), rtol=1e-8)
        assert 2 ** (-2 * (1 - alpha)) == pytest.approx(factor, abs=1e-3)


def test_q09_1_to_q09_3_classical_mds_memory_and_interpolation(blob):
    from scipy.spatial.distance import cdist

    P = np.random.default_rng(3).normal(size=(40, 3))
    P -= P.mean(axis=0)
    X = lbo.classical_mds(cdist(P, P), dim=3)
    assert lbo.gram_error(X, P) < 1e-10
    n, k = 10_000, 200
    assert 8 * n * n == 0.8e9 and 8 * n * k == 16e6 and np.sqrt(16e9 / 16) == pytest.approx(31_623, abs=1)
    Phi, lam = blob.vectors[:, :20], blob.values[:20]
    samples = np.random.default_rng(4).choice(Phi.shape[0], 60, replace=False)
    Phi_s = Phi[samples]
    M = np.linalg.solve(Phi_s.T @ Phi_s, Phi_s.T)                   # mu = 0
    np.testing.assert_allclose(M @ Phi_s, np.eye(20), atol=1e-10)
    M_mu = np.linalg.solve(Phi_s.T @ Phi_s + 1e-3 * np.diag(lam**2), Phi_s.T)
    shrink = np.diag(M_mu @ Phi_s)
    assert shrink[1] > shrink[-1] and shrink[-1] < 1                 # the rough ones shrink most


def test_q11_1_and_q11_2_regularized_pca_trace_and_rank(blob):
    W, A = blob.stiffness, blob.mass
    rng = np.random.default_rng(5)
    base = shapes.icosphere(3).vertices
    X = np.hstack([base * [1.0, 0.8, 1.2], base + 0.05 * rng.normal(size=base.shape)])   # two "poses"
    P = lbo.a_orthonormalize(rng.normal(size=(base.shape[0], 8)), A)
    lhs = sum(float((P @ (P.T @ (A @ x)) - x) @ (A @ (P @ (P.T @ (A @ x)) - x))) for x in X.T)
    rhs = sum(float(x @ (A @ x)) for x in X.T) - np.trace(P.T @ (A @ X) @ (X.T @ A) @ P)
    assert lhs == pytest.approx(rhs, rel=1e-9)
    import scipy.linalg

    Ad = A.toarray()
    AX = Ad @ X
    sigma = scipy.linalg.eigh(AX @ AX.T - 1e-2 * W.toarray(), Ad, eigvals_only=True)
    assert np.sum(sigma > 1e-12 * np.abs(sigma).max()) <= 6
    # mu -> infinity: the first eigenvectors (4 of them: the sphere's l = 0, 1 clusters, complete)
    far = lbo.regularized_pca(X, W, A, 4, mu=1e9)
    overlap = np.linalg.norm(blob.vectors[:, :4].T @ (A @ far)) ** 2       # = 4 when the spans agree
    assert overlap == pytest.approx(4, rel=1e-3)


# --- slides and booklet, built for two notebooks ---------------------------------------------------

TWO = [REPO / "notebooks" / "03_laplace_beltrami.ipynb", REPO / "notebooks" / "08_scale_invariant.ipynb"]


def _loads(page: str) -> list[str]:
    tags = re.findall(r'<(?:script|link|img)\b[^>]*?\b(?:src|href)="([^"]+)"', page)
    return tags + re.findall(r"@import\s+(?:url\()?[\"']?([^\"')\s;]+)", page)


@pytest.fixture(scope="module")
def built_slides(slides, tmp_path_factory):
    try:
        slides.reveal_source(fetch=True)
    except RuntimeError as exc:
        pytest.skip(str(exc))
    out = tmp_path_factory.mktemp("slides")
    slides.build(TWO, out)
    return out


def test_slides_are_offline_and_hold_no_solution(built_slides):
    for nb in TWO:
        page = (built_slides / f"{nb.stem}.slides.html").read_text()
        loads = _loads(page)
        assert loads and not [u for u in loads if re.match(r"(https?:)?//", u)], loads
        for url in loads:
            assert (built_slides / url.split("?")[0]).is_file(), url
        assert "require.js" not in page and "mermaid" not in page.lower().split("</style>")[-1]
        for secret in ("BEGIN SOLUTION", "HIDDEN TESTS", "Model answer", "grade(\""):
            assert secret not in page, secret
        assert page.count('<section') > 10 and "Reveal.initialize" in page
    assert (built_slides / "index.html").is_file()


def test_slide_types_follow_the_structure_and_keep_explicit_ones(slides):
    nb = nbformat.read(TWO[0], as_version=4)
    nb.cells[1].metadata["slideshow"] = {"slide_type": "notes"}
    before = nbformat.writes(nb)
    deck = slides.slide_cells(nb)
    assert nbformat.writes(nb) == before                                 # the notebook is not changed
    types = [(c.metadata["slideshow"]["slide_type"], c) for c in deck.cells]
    assert types[0][0] == "slide"
    assert any(t == "notes" for t, _ in types)
    for kind, cell in types:
        if cell.cell_type == "markdown" and re.match(r"##? ", cell.source) and kind != "notes":
            assert kind == "slide"
        if cell.cell_type == "code" and "hide-input" in cell.metadata.get("tags", []):
            assert kind == "skip"
        if cell.metadata.get("nbgrader", {}).get("solution") and cell.cell_type == "markdown":
            assert kind == "skip"
        assert "BEGIN SOLUTION" not in cell.source and "BEGIN HIDDEN TESTS" not in cell.source


@pytest.fixture(scope="module")
def built_booklet(booklet, tmp_path_factory):
    out = tmp_path_factory.mktemp("booklet")
    return out, booklet.build(TWO, out)


def test_booklet_has_every_exercise_with_its_solution(built_booklet):
    out, by_notebook = built_booklet
    index = (out / "index.html").read_text()
    for nb in TWO:
        page = (out / f"{nb.stem}.html").read_text()
        loads = _loads(page)
        assert loads and not [u for u in loads if re.match(r"(https?:)?//", u)], loads
        ids = {c.metadata["nbgrader"]["grade_id"] for c in nbformat.read(nb, as_version=4).cells
               if c.metadata.get("nbgrader", {}).get("grade_id", "").endswith(("-answer", "-explain"))}
        shown = {e.id + ("" if e.kind == "written" else "-answer") for e in by_notebook[nb.stem]}
        assert ids == shown
        for e in by_notebook[nb.stem]:
            assert f'id="{e.id}"' in page and e.id in index and e.solution.strip() and e.question.startswith("**Exercise")
            assert e.points and (e.kind == "written") == e.id.endswith("-explain")
            if e.kind == "written":
                assert e.rubric.startswith("**Rubric")
            assert "BEGIN SOLUTION" not in e.solution
        assert "HIDDEN TESTS" not in page


def test_booklet_reflows_wrapped_comments(booklet):
    nb = nbformat.read(REPO / "notebooks" / "07_min_max.ipynb", as_version=4)
    family = next(e for e in booklet.exercises_of(nb) if e.id == "07-family")
    assert "almost none of them: the subspace keeps" in family.solution
    assert "# Step 1\n# Step 2" == booklet.reflow_comments("# Step 1\n# Step 2")


def test_every_exercise_of_the_series_is_in_the_booklet(booklet):
    kinds = booklet._kinds()
    for path in NOTEBOOKS:
        nb = nbformat.read(path, as_version=4)
        exercises = booklet.exercises_of(nb, kinds)
        ids = [c.metadata["nbgrader"]["grade_id"] for c in nb.cells
               if c.metadata.get("nbgrader", {}).get("grade_id", "").endswith(("-answer", "-explain"))]
        assert len(exercises) == len(ids) and all(e.solution.strip() and e.kind != "?" for e in exercises), path.name
