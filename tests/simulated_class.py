"""Answers of a simulated class of three students, for the graded tests of the 81 exercises.

Each dict maps an answer cell's nbgrader grade id (``"NN-name-answer"``) to the full source a
student would type into that cell (the student edition's ``...``
placeholder replaced, nothing else of the notebook changed). The answers were written from the prompts and
the cells above each answer cell only, never from the instructor's solution code; they use the
names the notebook's earlier cells define (``dog``, ``spectra``, ``W``, ``A``, ...) and define the
names the prompt asks for, and nothing that depends on the solution's own intermediate names.

ALTERNATIVE
    All 81 exercises, each answered *correctly* but differently from the instructor: other
    intermediate names, another algorithm (a per-face Python loop for the stiffness matrix, mixed
    Voronoi areas with the law of cosines, normal equations / ``lstsq`` instead of ``Phi.T @ A @ f``,
    an SVD instead of a QR, a sparse permutation matrix for the functional map, a Gram error from
    n x n matrices, angle defects from a per-face loop with ``arccos``, classical MDS double-centred
    by explicit row and column means, the rPCA basis by a Cholesky reduction to a standard
    eigenproblem, a blocked brute-force nearest-neighbour search for the ZoomOut step, ...), other
    types (a list instead of a tuple, NumPy scalars and bools, a float edge count, an
    ``np.int64``), capitalised or padded choices (``"Double "``, ``"LAM_N"``,
    ``"i → i"``) and values typed with enough digits (``54.7356``, ``6.2831853``).
    *Build it yourself* answers are written from scratch with NumPy/SciPy.
WRONG
    All 81 exercises, each with one typical mistake: a factor of 2, a sign, a transpose, the
    Euclidean inner product where the mass matrix ``A`` belongs, an off-by-one index, radians for
    degrees, GiB for GB, a percentage for a fraction, the other option of a choice, an incomplete
    dict, the wrong matrix pair, ... Five of them (01-stretch, 03-lbo-recap, 04-recap, 05-recap,
    08-recap) append a cheat attempt after the wrong answer: patching ``Feedback.correct``,
    ``np.allclose``, the check function, ``grading.grade`` and ``Feedback.__init__``. They must
    still earn 0 points.
LIBRARY
    The 13 *build it yourself* exercises (03-stiffness, 03-mass, 03-eigensolve, 05-projection,
    06-schur, 08-angle-defects, 09-classical-mds, 09-scaling, 11-rpca-basis, 11-objective, 12-hks,
    12-fmap, 12-zoomout-step) answered by calling the library instead of building: a direct alias,
    wrapper functions, a lambda, a detour through ``reconstruct`` / ``scaling_in_span`` /
    ``map_from_points``, ``eigenbasis`` on the pair ``(W, A)``, ``worst_case_ratio``,
    ``lbo.angle_defects``, ``lbo.classical_mds``, ``RegularizedPCA(...).solve``, one
    iteration of ``lbo.zoomout``. They must earn 0 points in the graded run.

How they were checked: each notebook of ``notebooks/`` was executed with nbclient (kernel
``python3`` of ``.venv``, working directory ``notebooks/``), once per student, with all of that
student's answer cells substituted by grade id and the hidden-test regions removed from the check
cells, as in the student edition; the status of every visible check was read from the outputs'
``application/vnd.lbo-notebooks.feedback+json``. Visible checks: ALTERNATIVE 75/75 "correct";
WRONG 73/75 "wrong", 08-recap "correct" (its cheat patches ``Feedback.__init__`` in the kernel,
which no in-kernel check can resist) and 04-recap shows no feedback (its cheat replaces the check
function); LIBRARY 7/7 "correct" (the visible checks compare values and do not block the library,
by design). A last pass ran the notebooks of the working tree with their hidden tests kept
(``grade("NN-name", ...)`` in the check cells, graders of that day): ALTERNATIVE 75/75 full
points, LIBRARY 7/7 zero ("build it yourself ... not available"), WRONG 74/75 zero and 05-recap
1 point, because its cheat replaces ``grading.grade`` in the kernel before the hidden test
imports it.
The answers of 03-eigensolve and 06-schur (added later) were checked only through the graded
run (``grade`` on each student's function, in a namespace built from the cells above the answer
cell): ALTERNATIVE 5/5 points each, WRONG and LIBRARY 0.
The answers of 08-angle-defects, 09-classical-mds, 11-rpca-basis and 12-zoomout-step (added
later still) were checked the same way (each answer cell run in a fresh ``__main__`` namespace,
then ``grade("NN-name", my_...=...)``, the graded fresh process): ALTERNATIVE 5/5 points each,
WRONG 0 (boundary vertices given 2π; no double centring; the standard eigenproblem without A;
Φ₁ C where Φ₁ Cᵀ belongs), LIBRARY 0 ("... is not available, and your answer calls it"). Their
visible checks (``exercises.check_*`` on the notebook's inputs) read "correct" for ALTERNATIVE and
LIBRARY, "wrong" for WRONG.
This module holds no tests.
"""

# ALTERNATIVE: one correct answer per exercise, written differently from the instructor's.
ALTERNATIVE: dict[str, str] = {
    # --- notebook 00 ---
    "00-sphere-answer": r'''sphere_values = np.array([l * (l + 1) for l in range(3) for _ in range(2 * l + 1)], dtype=float)
''',
    "00-size-answer": r'''n_v = loaded.vertices.shape[0]
n_t = loaded.faces.shape[0]
size = [n_v, n_t]
''',
    "00-torus-answer": r'''obj_file = folder / "my_ring.obj"
lbo.save_mesh(shapes.torus(), obj_file)
ring = lbo.load_mesh(obj_file)
basis = lbo.eigenbasis(ring, 12)
phi6 = np.asarray(basis.vectors)[:, 6].copy()
plotting.plot_mesh(ring, phi6, symmetric=True)
''',
    "00-missing-answer": r'''bad_obj = folder / "hole.obj"
bad_obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 9\n")  # vertex 9 does not exist
try:
    lbo.load_mesh(bad_obj)
except Exception as problem:
    error = problem
''',
    # --- notebook 01 ---
    "01-edges-answer": r'''corner_slots = 3 * dog.n_faces  # three edge slots per triangle
n_edges = corner_slots / 2.0  # each edge of a closed surface is shared by two triangles
''',
    "01-stretch-answer": r'''stretch = "Double "
''',
    "01-area-answer": r'''area_factor = np.float64(2.56)
''',
    "01-angles-answer": r'''def min_corner_angle_deg(mesh):
    tri = mesh.vertices[mesh.faces]
    worst = 180.0
    for corner in range(3):
        a = tri[:, (corner + 1) % 3] - tri[:, corner]
        b = tri[:, (corner + 2) % 3] - tri[:, corner]
        angle = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
        worst = min(worst, float(np.degrees(angle.min())))
    return worst


smallest_angles = {}
for size in [2000, 3000, N]:
    smallest_angles[size] = min_corner_angle_deg(creature("dog", n_vertices=size))
print(smallest_angles)
''',
    "01-legs-answer": r'''leg_vertices = np.flatnonzero(parts["front_legs"] + parts["hind_legs"])
face_in_leg = np.isin(dog.faces, leg_vertices).sum(axis=1) == 3
corners = dog.vertices[dog.faces]
tri_area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
A_leg = tri_area[face_in_leg].sum()
A_rest = tri_area.sum() - A_leg
predicted_area = {}
for scale in [0.7, 1.0, 1.3]:
    predicted_area[scale] = A_rest + A_leg * scale * scale
''',
    "01-recap-answer": r'''q1 = "Faces"
q2 = 2.0
q3 = " joint bands "
''',
    # --- notebook 02 ---
    "02-edge-energy-answer": r'''values_on_path = [0, 1, 4, 9, 16]
path_energy = 0
for a, b in zip(values_on_path[:-1], values_on_path[1:]):
    path_energy += (b - a) ** 2
''',
    "02-cycle-pair-answer": r'''ks = np.arange(12)
multiplicity = int(np.count_nonzero(np.isclose(2 - 2 * np.cos(2 * np.pi * ks / 12), 2.0, atol=1e-12)))
''',
    "02-step-decay-answer": r'''tail = lambda n: np.sum(1.0 / np.arange(n, 1_000_000) ** 2)  # squared coefficients ~ 1/k^2
error_drop = tail(20) / tail(40)
''',
    "02-graph-recap-answer": r'''q1 = 2.0
q2 = np.float64(4)
q3 = "LAM_N"
''',
    # --- notebook 03 ---
    "03-stiffness-answer": r'''import numpy as np
import scipy.sparse


def my_stiffness(mesh):
    """Cotangent stiffness matrix W (n x n) of a triangle mesh, one triangle at a time."""
    pts = np.asarray(mesh.vertices, dtype=float)
    n = len(pts)
    entries = {}

    def add(r, c, value):
        entries[(r, c)] = entries.get((r, c), 0.0) + value

    for tri in np.asarray(mesh.faces):
        for corner in range(3):
            i, j, k = int(tri[corner]), int(tri[(corner + 1) % 3]), int(tri[(corner + 2) % 3])
            e1, e2 = pts[j] - pts[i], pts[k] - pts[i]
            cross = np.cross(e1, e2)
            half_cot = 0.5 * float(e1 @ e2) / float(np.sqrt(cross @ cross))
            # the angle at corner i is opposite the edge j-k
            add(j, k, -half_cot)
            add(k, j, -half_cot)
            add(j, j, half_cot)
            add(k, k, half_cot)
    keys = list(entries)
    rr = [key[0] for key in keys]
    cc = [key[1] for key in keys]
    vals = [entries[key] for key in keys]
    return scipy.sparse.csr_matrix((vals, (rr, cc)), shape=(n, n))
''',
    "03-mass-answer": r'''import scipy.sparse


def my_mass(mesh):
    """Lumped mass matrix A (n x n, diagonal) of a triangle mesh: mixed Voronoi areas."""
    X = np.asarray(mesh.vertices, dtype=float)
    T = np.asarray(mesh.faces)
    P0, P1, P2 = X[T[:, 0]], X[T[:, 1]], X[T[:, 2]]
    tri_area = 0.5 * np.linalg.norm(np.cross(P1 - P0, P2 - P0), axis=1)
    # squared length of the side opposite each corner
    opp = np.stack([np.sum((P1 - P2) ** 2, 1), np.sum((P2 - P0) ** 2, 1), np.sum((P0 - P1) ** 2, 1)], axis=1)
    # cotangent at each corner, law of cosines: cot = (b^2 + c^2 - a^2) / (4 area)
    cots = np.stack([(opp[:, (c + 1) % 3] + opp[:, (c + 2) % 3] - opp[:, c]) / (4 * tri_area) for c in range(3)], axis=1)
    share = np.zeros((len(T), 3))
    for c in range(3):
        # Voronoi part of corner c: sides c-(c+1) and c-(c+2), weighted by the cotangents opposite them
        share[:, c] = (opp[:, (c + 2) % 3] * cots[:, (c + 2) % 3] + opp[:, (c + 1) % 3] * cots[:, (c + 1) % 3]) / 8
    obtuse = (cots < 0).any(axis=1)
    for t in np.flatnonzero(obtuse):
        share[t] = tri_area[t] / 4
        share[t, int(np.argmin(cots[t]))] = tri_area[t] / 2
    lumped = np.zeros(len(X))
    np.add.at(lumped, T, share)
    return scipy.sparse.diags(lumped, format="csc")
''',
    "03-eigensolve-answer": r'''import scipy.sparse.linalg as sla


def my_eigenbasis(W, A, k):
    """The k smallest eigenpairs of W phi = lam A phi: values (k,) ascending, vectors (n, k).

    The vectors are A-orthonormal: vectors.T @ A @ vectors is the identity.
    """
    import scipy.sparse

    stiff = scipy.sparse.csc_matrix(W, dtype=float)
    mass = scipy.sparse.csc_matrix(A, dtype=float)
    total_area = float(mass.sum())
    shift = -0.04 * np.pi / total_area  # -1e-2 * 4 pi / area: W - shift * A is positive definite
    lam, phi = sla.eigsh(stiff, k, M=mass, sigma=shift, which="LM")
    order = np.argsort(lam)
    lam, phi = np.asarray(lam[order], dtype=float), np.asarray(phi[:, order], dtype=float)
    # my own A-orthonormalisation: phi <- phi L^-T with L L^T = phi^T A phi
    gram = phi.T @ (mass @ phi)
    chol = np.linalg.cholesky(0.5 * (gram + gram.T))
    phi = np.linalg.solve(chol, phi.T).T
    return lam, phi
''',
    "03-convergence-answer": r'''error_drop = 2.0**2  # O(h^2), h halves
''',
    "03-coefficients-answer": r'''f = blob.vertices[:, 0]  # the x coordinate, a function on the surface
root_mass = np.sqrt(A_blob.diagonal())  # the lumped A is diagonal
# the A-orthogonal projection onto span(Phi) as a weighted least-squares problem
coefficients, *_ = np.linalg.lstsq(root_mass[:, None] * Phi, root_mass * f, rcond=None)
''',
    "03-consistent-answer": r'''ico3 = shapes.icosphere(3)
with_consistent = lbo.eigenbasis(ico3, 36, mass_kind="consistent").values
with_lumped = lbo.eigenbasis(ico3, 36).values
print((with_consistent[4:] - exact[4:]).min(), (with_lumped[4:] - exact[4:]).max())
consistent_side = "Above" if np.all(with_consistent[4:] > exact[4:]) else "Below"
# The consistent mass makes the discrete problem a Galerkin (Rayleigh-Ritz) restriction of the
# min-max to piecewise-linear functions, which can only overestimate eigenvalues; lumping
# the mass is a quadrature that breaks this bound (and the lumped values land below).
''',
    "03-scaling-answer": r'''eigenvalue_factor = 2.0**-2  # energy unchanged, areas times 4
''',
    "03-kernel-answer": r'''def count_zeros(mesh, k=8):
    lam = lbo.eigenbasis(mesh, k).values
    return np.count_nonzero(np.abs(lam) <= 1e-9 * lam.max())


torus_zeros = count_zeros(shapes.torus())
s2 = shapes.icosphere(2)
pair_mesh = lbo.Mesh(
    np.concatenate([s2.vertices, s2.vertices + np.array([0.0, 0.0, 5.0])]),
    np.concatenate([s2.faces, s2.faces + len(s2.vertices)]),
)
two_sphere_zeros = count_zeros(pair_mesh)
# A zero eigenvalue = a function with no energy = constant on every connected piece:
# the torus is one piece (its hole does not matter), the two spheres are two pieces.
''',
    "03-lbo-recap-answer": r'''q1 = 0.5 / np.tan(np.pi / 2)  # round-off zero
q2 = 1.0
q3 = "B"
''',
    # --- notebook 04 ---
    "04-repair-answer": r'''repair = dict(
    polygons_split=sum(len(polygon) > 3 for polygon in faces),  # the quad
    vertices_welded=1,  # the one exact copy
    degenerate_faces=4 + 1,  # repeated corners, and the collinear face
    duplicate_faces=len(range(10, 15)),  # written again, reversed
    unreferenced_vertices=5 + 3 + 2,  # random points, the flat face's corners, the two hole centres
    non_manifold_edges=len(fin_edges),  # one sphere edge per fin
    n_components=1 + 2 + 1,  # sphere, two triangle flakes, the quad flake
)
''',
    "04-operator-answer": r'''operator = {
    "holes": "Cotan",  # boundary edges have one triangle: one cotangent, still fine
    "two_pieces": "cotan ",  # two blocks, each a clean closed surface
    "fins": "ROBUST",  # edges with three triangles: no pair of opposite angles
    "pinched": "robust",  # a bowtie vertex: non-manifold although every edge is fine
}
''',
    "04-cloud-answer": r'''index = 9
l = int(np.sqrt(index))  # indices l^2 ... (l+1)^2 - 1 belong to l
on_sphere = l * (l + 1)
relative_error = (cloud_spectrum.values[index] - on_sphere) / on_sphere
''',
    "04-largest-answer": r'''import warnings as w

with w.catch_warnings():
    w.simplefilter("ignore")
    one_piece = lbo.load_mesh(scan_path, clean=True, keep_largest_component=True)
    lam = lbo.eigenbasis(one_piece, 20).values
largest_zeros = sum(1 for value in lam if abs(value) < 1e-6)
largest_worst = float(max(abs(lam[k] / exact[k] - 1) for k in range(1, 16)))
print(largest_zeros, largest_worst)
''',
    "04-neighbors-answer": r'''neighbors_effect = "Further"
''',
    "04-gap-answer": r'''pieces = {}
for r_out in [1.5, 1.75, 2.0]:
    both = np.concatenate([inner.vertices, inner.vertices * r_out])
    lam = lbo.eigenbasis(lbo.PointCloud(both), 5).values
    pieces[r_out] = np.sum(np.abs(lam) < 1e-8 * np.abs(lam).max())
print(pieces)
# Each point's neighbourhood is its 30 nearest points, however far: on the outer sphere the same
# number of points is spread r^2 times thinner, so its patches reach about 0.43 r; while the gap
# r - 1 is below that, the outer patches grab inner points and the two sheets fuse.
''',
    "04-recap-answer": r'''q1 = np.int64(4)
q2 = "Robust"
q3 = "Fused"
''',
    # --- notebook 05 ---
    "05-projection-answer": r'''def my_project(spectrum, f, n):
    """P_n f: the A-orthogonal projection of f onto phi_0 .. phi_(n-1)."""
    basis = np.asarray(spectrum.vectors)[:, :n]
    M = spectrum.mass
    values = np.asarray(f, dtype=float)
    # best A-norm fit: the normal equations (B^T M B) c = B^T M f
    gram = basis.T @ (M @ basis)
    rhs = basis.T @ (M @ values)
    c = np.linalg.solve(gram, rhs)
    return basis @ c
''',
    "05-bound-answer": r'''import scipy.sparse

fy = dog.vertices[:, 1]
S = scipy.sparse.coo_matrix(spectra["dog"].stiffness)
upper = S.row < S.col  # each edge once
# Dirichlet energy as a sum over the edges: w_ij (f_i - f_j)^2, w_ij = -W_ij
edge_energy = np.sum(-S.data[upper] * (fy[S.row[upper]] - fy[S.col[upper]]) ** 2)
lam_first_left_out = spectra["dog"].values[20]  # phi_0 .. phi_19 are kept
bound_y = edge_energy / lam_first_left_out
''',
    "05-extra-answer": r'''extra_verdict = "Between"
# V contains phi_0..phi_19, so it cannot be worse than Phi_20 (C <= 1/lambda_20); it has 21 functions,
# and no 21-dimensional space beats the first 21 eigenfunctions (C >= 1/lambda_21).
''',
    "05-recap-answer": r'''q1 = np.int64(10)
q2 = "Vacuous"
q3 = "No"
''',
    # --- notebook 06 ---
    "06-shifted-answer": r'''shifted_verdict = " Infinite"
# phi_0 (a constant) is A-orthogonal to V: all of it is error, at zero energy.
''',
    "06-schur-answer": r'''import scipy.linalg
from scipy.sparse.csgraph import connected_components


def my_worst_case(W, A, V):
    """C(V) = sup_f ||f - P_V f||_A^2 / f^T W f for the span of V's columns.

    np.inf when the kernel of W (the constant on each piece of the mesh) is not in that span.
    """
    dense_w = np.asarray(W.toarray(), dtype=float)
    dense_a = np.asarray(A.toarray(), dtype=float)
    basis = np.asarray(V, dtype=float)
    n, m = basis.shape
    # whiten the A inner product: A = R^T R, g = R f, then ||f||_A = |g| and f^T W f = g^T K g
    R = scipy.linalg.cholesky(dense_a, lower=False)
    K = scipy.linalg.solve_triangular(R, scipy.linalg.solve_triangular(R, dense_w, trans="T").T, trans="T")
    K = 0.5 * (K + K.T)
    # orthonormal basis [U | N] of R^n with U spanning R V (full QR)
    full_q, _ = np.linalg.qr(R @ basis, mode="complete")
    U, N = full_q[:, :m], full_q[:, m:]
    # the kernel of W must lie in the span: each piece's indicator, projected in whitened coordinates
    n_pieces, labels = connected_components(W, directed=False)
    for piece in range(n_pieces):
        g = R @ (labels == piece).astype(float)
        left_over = g - U @ (U.T @ g)
        if np.linalg.norm(left_over) > 1e-8 * np.linalg.norm(g):
            return np.inf
    if N.shape[1] == 0:
        return 0.0  # V is everything: no error at all
    # energy minimised over the U part: Schur complement of K_UU in [[K_UU, K_UN], [K_NU, K_NN]]
    K_uu, K_un, K_nn = U.T @ K @ U, U.T @ K @ N, N.T @ K @ N
    schur = K_nn - K_un.T @ np.linalg.lstsq(K_uu, K_un, rcond=None)[0]
    mus = np.linalg.eigvalsh(0.5 * (schur + schur.T))  # N is orthonormal: a standard eigenproblem
    if mus[0] <= 1e-10 * mus[-1]:
        return np.inf
    return float(1.0 / mus[0])
''',
    "06-stationary-answer": r'''stationary_verdict = "QUADRUPLE"  # a minimum is stationary: the excess is second order in eps
''',
    "06-consistent-answer": r'''cons = lbo.eigenbasis(dog, 60, mass_kind="consistent")
first50 = cons.vectors[:, :50]
consistent_ratio = np.float64(worst_case_ratio(first50, cons.stiffness, cons.mass)) * cons.values[50]
''',
    "06-worst-answer": r'''polys20 = competitors["polynomials"][:, :20]
_, g_worst = worst_case_ratio(polys20, W, A, return_vector=True)
# the best A-norm fit of g_worst by the polynomials, from the normal equations
fit = polys20 @ np.linalg.solve(polys20.T @ (A @ polys20), polys20.T @ (A @ g_worst))
residual = g_worst - fit
worst_ratio = (residual @ (A @ residual)) / (g_worst @ (W @ g_worst))
plotting.plot_mesh(dog, g_worst, title="the function 20 polynomials miss most", symmetric=True)
''',
    "06-ties-recap-answer": r'''q1 = "No"
q2 = "Lower"
q3 = 2.0
''',
    # --- notebook 07 ---
    "07-range-answer": r'''plane_range = [1.0, 2.5]  # lambda_0 and lambda_1 of M
''',
    "07-plane-answer": r'''normal = v0 + 2 * v1
in_plane = np.linalg.svd(normal[None, :])[2][1:].T  # 3 x 2, orthonormal, orthogonal to the normal
plane_value = np.linalg.eigvalsh(in_plane.T @ M @ in_plane).min()
''',
    "07-family-answer": r'''lowest_family = "White"  # noise constraints barely touch the smooth, low-energy functions
''',
    "07-dual-answer": r'''my_rng = np.random.default_rng(2024)
maxima = []
for trial in range(300):
    U, _ = np.linalg.qr(my_rng.normal(size=(3, 2)))
    maxima.append(np.linalg.eigvalsh(U.T @ M @ U).max())
print(min(maxima))
dual_value = np.linalg.eigvalsh(M)[1]  # every plane meets span(v1, v2), and span(v0, v1) attains it
''',
    "07-interlacing-answer": r'''# a codimension-2 subspace that keeps the constant: its minimum is 0 = lambda_0
keeps_constant = random_subspace(blob.n_vertices, 2, seed=9, pool=s.vectors[:, 2:9])
print(solver.minimum(keeps_constant))
interlacing_bound = "LAM_0"
''',
    "07-consistent-answer": r'''sc = lbo.eigenbasis(blob, 12, mass_kind="consistent")
low_c = min_rayleigh_quotient(sc.stiffness, sc.mass, orthogonal_to=sc.vectors[:, :10])
consistent_minmax = low_c / sc.values[10]
''',
    "07-recap-answer": r'''q1 = "LAM_N"
q2 = "No"
q3 = 54.7356  # arctan(sqrt(2)) in degrees
''',
    # --- notebook 08 ---
    "08-angle-defects-answer": r'''def my_angle_defects(mesh):
    """Angle defect at each vertex, shape (n,): 2 pi - sum of angles (pi - sum on the boundary)."""
    pts = np.asarray(mesh.vertices, dtype=float)
    angle_sum = np.zeros(len(pts))
    for tri in np.asarray(mesh.faces):
        for corner in range(3):
            here, nxt, prv = tri[corner], tri[(corner + 1) % 3], tri[(corner + 2) % 3]
            u, v = pts[nxt] - pts[here], pts[prv] - pts[here]
            cosine = float(np.dot(u, v)) / (np.linalg.norm(u) * np.linalg.norm(v))
            angle_sum[here] += np.arccos(min(1.0, max(-1.0, cosine)))  # the corner's angle
    full_turn = np.full(len(pts), 2 * np.pi)
    full_turn[np.asarray(mesh.boundary_vertices, dtype=int)] = np.pi  # a half turn on the rim
    return full_turn - angle_sum
''',
    "08-curvature-answer": r'''donut = shapes.torus()
K_before = lbo.gaussian_curvature(donut)
K_after = lbo.gaussian_curvature(donut.with_vertices(3 * donut.vertices))
curved = np.abs(K_before) > 1e-6 * np.abs(K_before).max()  # skip the (near-)flat vertices
curvature_factor = np.median(K_after[curved] / K_before[curved])
print(curvature_factor)
''',
    "08-gauss-bonnet-answer": r'''torus_total = np.float32(0)  # chi = 0
disk_total = 6.2831853  # 2 pi, chi = 1
''',
    "08-scaling-answer": r'''metric_factors = {}
for a in [0.0, 0.4, 1.0]:
    metric_factors[a] = (1 / 9) ** (1 - a)  # A_alpha grows by 9^(1 - alpha)
''',
    "08-best-answer": r'''best_alpha_curved = np.float64(1.0)
''',
    "08-floor-answer": r'''rho_floor1 = operators.metric_curvature(horse, floor=1.0)
floor_level = 4 * np.pi / horse.area  # curvature_floor = 1 times the round sphere's curvature
floor_fraction = np.count_nonzero(np.isclose(rho_floor1, floor_level, rtol=1e-9, atol=0)) / horse.n_vertices
for eps in (1e-3, 1e-2, 1e-1, 1.0):
    lam20 = lbo.eigenbasis(horse, 20, alpha=1.0, curvature_floor=eps).values
    print(eps, lam20[1:4])
# A floor only touches vertices whose one-ring |K| is below it: on the horse none up to 1e-2 and
# about one in seven at 1, so its spectrum barely moves; on flat or developable parts (a box,
# a cylinder) |K| is zero and the floor alone would set their metric area.
''',
    "08-sphere-answer": r'''sphere_verdict = "Equal"  # |K| = 1 on the unit sphere
''',
    "08-consistent-answer": r'''consistent_invariant = "YES"  # rho_t |t| is unchanged by a scaling
''',
    "08-recap-answer": r'''q1 = 1 / 2**2
q2 = "a"
q3 = "Regular"
''',
    # --- notebook 09 ---
    "09-classical-mds-answer": r'''def my_classical_mds(D, dim):
    """Classical MDS: the n x dim embedding U Gamma^(1/2) of B = -1/2 J D^2 J."""
    squared = np.asarray(D, dtype=float) ** 2
    # J S J without J: subtract the row means and the column means, add back the grand mean
    row_means = squared.mean(axis=1)[:, None]
    column_means = squared.mean(axis=0)[None, :]
    B = -0.5 * (squared - row_means - column_means + squared.mean())
    B = 0.5 * (B + B.T)
    gammas, U = np.linalg.eigh(B)  # ascending
    keep = np.argsort(gammas)[::-1][:dim]
    gammas = np.where(gammas[keep] > 0, gammas[keep], 0.0)  # non-Euclidean: negative ones count 0
    return U[:, keep] * np.sqrt(gammas)[None, :]
''',
    "09-memory-answer": r'''classical_gb = 40.0  # 2 matrices x 2.5e9 entries x 8 bytes = 4e10 bytes
''',
    "09-scaling-answer": r'''def my_scaling(phi, alpha, dim):
    """The n x dim embedding from the k x k eigenproblem of -1/2 R alpha R^T, with J phi = Q R."""
    n_rows = phi.shape[0]
    centred = phi - np.ones((n_rows, 1)) @ phi.mean(axis=0, keepdims=True)  # J phi
    # a thin factorisation J phi = Q R from the SVD: Q = U, R = diag(s) V^T
    left, sing, right_t = np.linalg.svd(centred, full_matrices=False)
    small = -0.5 * ((sing[:, None] * right_t) @ alpha @ (sing[:, None] * right_t).T)
    small = 0.5 * (small + small.T)
    evals, evecs = np.linalg.eigh(small)
    top = np.argsort(evals)[::-1][:dim]
    return left @ evecs[:, top] @ np.diag(np.sqrt(evals[top]))
''',
    "09-landmarks-answer": r'''landmark_verdict = "Less"
''',
    "09-fmm-answer": r'''fmm_verdict = "Farther"  # the reference is heat-method classical MDS; fmm errs differently
''',
    "09-recap-answer": r'''q1 = SMDS_DEFAULTS["k"] + SMDS_DEFAULTS["n_samples"]  # [Phi, F^T] has k + q columns
q2 = "Orthogonal map"
q3 = "canonical forms "
''',
    # --- notebook 10 ---
    "10-mu-answer": r'''mu_verdict = "Less than half"  # lambda_i^2 penalises only the rough end of the spectrum
''',
    "10-equal-size-answer": r'''floats_spectral = dog.n_vertices * (SMDS_DEFAULTS["k"] + SMDS_DEFAULTS["n_samples"])  # Phi and F
n_c = int(round((floats_spectral / 2) ** 0.5))  # two n_c x n_c matrices
''',
    "10-two-d-answer": r'''flat2 = spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling)
Zc = flat2 - flat2.mean(axis=0)
Xc = X_classical[:, :2] - X_classical[:, :2].mean(axis=0)
gram_Z, gram_X = Zc @ Zc.T, Xc @ Xc.T  # 2,000 x 2,000: affordable here
e2 = np.linalg.norm(gram_Z - gram_X) / np.linalg.norm(gram_X)
del gram_Z, gram_X
''',
    "10-cost-recap-answer": r'''q1 = "No"
q2 = 2.0
q3 = "Spectral"
''',
    # --- notebook 11 ---
    "11-rpca-basis-answer": r'''import scipy.linalg


def my_rpca_basis(X, W, A, mu, m):
    """The m top generalized eigenvectors of (A X X^T A - mu W) p = sigma A p, shape (n, m):
    P^T A P = I, columns by decreasing sigma."""
    data = np.asarray(X, dtype=float)
    if data.ndim == 1:
        data = data[:, None]
    mass = A.toarray() if hasattr(A, "toarray") else np.asarray(A, dtype=float)
    stiff = W.toarray() if hasattr(W, "toarray") else np.asarray(W, dtype=float)
    # reduce to a standard symmetric problem with the Cholesky factor A = L L^T: y = L^T p
    L = np.linalg.cholesky(0.5 * (mass + mass.T))
    G = scipy.linalg.solve_triangular(L, mass @ data, lower=True)  # L^-1 A X
    half = scipy.linalg.solve_triangular(L, stiff, lower=True)  # L^-1 W
    S = scipy.linalg.solve_triangular(L, half.T, lower=True)  # L^-1 W L^-T
    M = G @ G.T - mu * S
    sigma, Y = np.linalg.eigh(0.5 * (M + M.T))
    top = np.argsort(sigma)[::-1][:m]  # the largest first
    return scipy.linalg.solve_triangular(L.T, Y[:, top], lower=False)  # p = L^-T y
''',
    "11-energy-answer": r'''energies = [float(pca.basis[:, j] @ (W @ pca.basis[:, j])) for j in range(pca.basis.shape[1])]
print(int(np.argmin(np.abs(energies))), energies[6])  # the constant: no energy
extra = np.array(energies[6:])
print(np.all(extra >= lam[:94] - 1e-8 * lam[-1]), np.all(extra <= lam[6:100] + 1e-8 * lam[-1]))
''',
    "11-limits-answer": r'''limit_at_0 = "PCA + smooth"
limit_at_1 = "Eigenbasis"
best_beta = "Intermediate"
''',
    "11-validation-answer": r'''k_tail = unseen.index("tail_raised")
on_tail = np.array([errors[b][k_tail] for b in betas])
chosen_beta = betas[int(np.argmin(on_tail))]
rest = np.delete(np.arange(len(unseen)), k_tail)
ratio_to_lbo = np.asarray(errors[chosen_beta])[rest] / np.asarray(err_lbo)[rest]
beats_by_four = np.all(ratio_to_lbo < 0.25)  # a NumPy bool
print(chosen_beta, ratio_to_lbo)
''',
    "11-scale-answer": r'''mu_factor = np.float64(4 * 4 * 4)  # s_B x 2^4, lambda_ref / 2^2
''',
    "11-objective-answer": r'''def my_objective(P, X, W, A, mu):
    """sum_i ||P P^T A x_i - x_i||_A^2 + mu sum_j p_j^T W p_j."""
    coeff = P.T @ (A @ X)
    fit = 0.0
    for i in range(X.shape[1]):
        r = P @ coeff[:, i] - X[:, i]
        fit += float(r @ (A @ r))
    smoothness = 0.0
    for j in range(P.shape[1]):
        smoothness += float(P[:, j] @ (W @ P[:, j]))
    return fit + mu * smoothness
''',
    "11-recap-answer": r'''q1 = "B"
q2 = "A"
q3 = "C"
''',
    # --- notebook 12 ---
    "12-hks-answer": r'''def my_hks(spectrum, times):
    """h_t(x) = sum_i exp(-lam_i t) phi_i(x)^2, shape (n_vertices, len(times))."""
    phi = np.asarray(spectrum.vectors)
    lam = np.asarray(spectrum.values)
    t_all = np.atleast_1d(np.asarray(times, dtype=float))
    squared = phi * phi
    out = np.empty((phi.shape[0], t_all.size))
    for c, t in enumerate(t_all):
        out[:, c] = squared @ np.exp(-lam * t)
    return out
''',
    "12-fmap-answer": r'''import scipy.sparse


def my_functional_map(p2p, source, target, k):
    """C = Phi_2^T A_2 Pi Phi_1 (k x k): source coefficients -> target coefficients."""
    n_target, n_source = target.n_vertices, source.n_vertices
    idx = np.asarray(p2p)
    Pi = scipy.sparse.csr_matrix((np.ones(n_target), (np.arange(n_target), idx)), shape=(n_target, n_source))
    pulled_back = Pi @ np.asarray(source.vectors)[:, :k]
    return np.asarray(target.vectors)[:, :k].T @ (target.mass @ pulled_back)
''',
    "12-zoomout-step-answer": r'''def my_zoomout_step(C, source, target):
    """One ZoomOut iteration: (C_next of size (k+1, k+1), p2p read off the k x k map C)."""
    C = np.asarray(C, dtype=float)
    k2, k1 = C.shape
    images = np.asarray(source.vectors)[:, :k1] @ C.T  # the image of every source delta
    queries = np.asarray(target.vectors)[:, :k2]
    image_norms = np.einsum("ij,ij->i", images, images)
    p2p = np.empty(len(queries), dtype=np.int64)
    for start in range(0, len(queries), 500):  # brute force, 500 target vertices at a time
        block = queries[start:start + 500]
        # |q - y|^2 = |q|^2 - 2 q.y + |y|^2; |q|^2 is the same for the whole row
        p2p[start:start + 500] = np.argmin(image_norms[None, :] - 2.0 * block @ images.T, axis=1)
    k = k2 + 1
    # C_next = Phi_2^T A_2 Pi Phi_1: A_2-weighted target functions against pulled-back source functions
    weighted = np.asarray(target.mass @ np.asarray(target.vectors)[:, :k])
    pulled = np.asarray(source.vectors)[p2p, :k]
    C_next = np.einsum("vi,vj->ij", weighted, pulled)
    return C_next, p2p
''',
    "12-alpha-answer": r'''best_alpha = 1.0  # |K| g does not see a part rescaled
''',
    "12-bound-answer": r'''f_z = source.vertices[:, 2] - source.vertices[:, 2].mean()  # the centred z coordinate
energy_z = lbo.dirichlet_energy(ref.stiffness, f_z)
norm2_z = float(f_z @ (ref.mass @ f_z))
lam_30 = ref.values[30]  # phi_0 .. phi_29 are kept
bound_z = energy_z / (lam_30 * norm2_z)
''',
    "12-mirror-answer": r'''with_orientation = "Same position"
without_orientation = "i → i"
# Without the orientation term the mirror is intrinsically the dog itself (i -> i keeps every
# descriptor); that map reverses orientation, so the orientation term picks the left-right swap.
''',
    "12-zoomout-answer": r'''without_zoomout = "Larger"
''',
    "12-recap-answer": r'''q1 = " b"
q2 = "A"
q3 = "c"
''',
}

# WRONG: one typical wrong answer per exercise (five of them followed by a cheat attempt).
WRONG: dict[str, str] = {
    # --- notebook 00 ---
    "00-sphere-answer": r'''sphere_values = [0, 1, 1, 1, 4, 4, 4, 4, 4]  # l squared
''',
    "00-size-answer": r'''size = (loaded.vertices.size, loaded.faces.size)
''',
    "00-torus-answer": r'''torus = lbo.load_mesh(lbo.save_mesh(shapes.torus(), folder / "torus.obj"))
phi6 = lbo.eigenbasis(torus, 6).vectors[:, 5]  # the sixth one
''',
    "00-missing-answer": r'''bad = folder / "bad.off"
bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
try:
    error = lbo.load_mesh(bad)
except lbo.MeshError as err:
    error = err
''',
    # --- notebook 01 ---
    "01-edges-answer": r'''n_edges = 3 * dog.n_faces  # three edges per triangle
''',
    "01-stretch-answer": r'''stretch = "quadruple"
from lbo_notebooks import exercises
exercises.Feedback.correct = property(lambda self: True)
''',
    "01-area-answer": r'''area_factor = 1.6
''',
    "01-angles-answer": r'''smallest_angles = {n: corner_angles(creature("dog", n_vertices=n)).min() for n in (2_000, 3_000, N)}
''',
    "01-legs-answer": r'''legs = (parts["front_legs"] | parts["hind_legs"])[dog.faces].all(axis=1)
leg_area, rest_area = dog.face_areas[legs].sum(), dog.face_areas[~legs].sum()
predicted_area = {s: leg_area * s + rest_area for s in (0.7, 1.0, 1.3)}
''',
    "01-recap-answer": r'''q1, q2, q3 = "both", 0, "everywhere"
''',
    # --- notebook 02 ---
    "02-edge-energy-answer": r'''path_energy = 2 * (1**2 + 3**2 + 5**2 + 7**2)  # both directions of every edge
''',
    "02-cycle-pair-answer": r'''multiplicity = 1  # k = 3 only
''',
    "02-step-decay-answer": r'''error_drop = 4  # coefficients like 1/k, so the error like 1/n^2
''',
    "02-graph-recap-answer": r'''q1, q2, q3 = 4, 2, "lam_n+1"  # energy is quadratic in the weights
''',
    # --- notebook 03 ---
    "03-stiffness-answer": r'''import scipy.sparse as sp


def my_stiffness(mesh):
    """Cotangent stiffness matrix W (n x n) of a triangle mesh."""
    v, f = mesh.vertices, mesh.faces
    n = len(v)
    rows, cols, vals = [], [], []
    for k in range(3):
        a = v[f[:, (k + 1) % 3]] - v[f[:, k]]
        b = v[f[:, (k + 2) % 3]] - v[f[:, k]]
        cot = np.sum(a * b, axis=1) / np.linalg.norm(np.cross(a, b), axis=1)
        i, j = f[:, (k + 1) % 3], f[:, (k + 2) % 3]
        rows += [i, j]
        cols += [j, i]
        vals += [-cot, -cot]  # the cotangent weight
    off = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    return off - sp.diags(np.asarray(off.sum(axis=1)).ravel())
''',
    "03-mass-answer": r'''import scipy.sparse as sp


def my_mass(mesh):
    """Lumped mass matrix A (n x n, diagonal) of a triangle mesh."""
    p = mesh.vertices[mesh.faces]
    area = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)  # the triangle's area
    share = np.zeros(mesh.n_vertices)
    np.add.at(share, mesh.faces, (area / 3)[:, None])
    return sp.diags(share)
''',
    "03-eigensolve-answer": r'''import scipy.sparse.linalg as sla


def my_eigenbasis(W, A, k):
    """The k smallest eigenpairs of W phi = lam A phi: values (k,) ascending, vectors (n, k).

    The vectors are A-orthonormal: vectors.T @ A @ vectors is the identity.
    """
    sigma = -1e-2 * 4 * np.pi / A.sum()
    values, vectors = sla.eigsh(W, k, sigma=sigma, which="LM")  # forgot M=A
    order = np.argsort(values)
    return values[order], vectors[:, order]
''',
    "03-convergence-answer": r'''error_drop = 2  # h is halved
''',
    "03-coefficients-answer": r'''f = blob.vertices[:, 0]
coefficients = Phi.T @ f
''',
    "03-consistent-answer": r'''consistent_side = "below"  # like the lumped mass
''',
    "03-scaling-answer": r'''eigenvalue_factor = 1 / 2
''',
    "03-kernel-answer": r'''torus_zeros = 2  # one for the piece and one for the hole
two_sphere_zeros = 2
''',
    "03-lbo-recap-answer": r'''q1, q2, q3 = 0.5, 4, "a"
np.allclose = lambda *args, **kwargs: True  # so that every comparison passes
''',
    # --- notebook 04 ---
    "04-repair-answer": r'''repair = {
    "polygons_split": 1,
    "vertices_welded": 1,
    "degenerate_faces": 5,
    "duplicate_faces": 5,
    "unreferenced_vertices": 5,  # the five random points
    "non_manifold_edges": 3,
    "n_components": 4,
}
''',
    "04-operator-answer": r'''operator = {"holes": "cotan", "two_pieces": "cotan", "fins": "robust", "pinched": "cotan"}
# pinched: every edge has two faces, so the cotangent weights are fine
''',
    "04-cloud-answer": r'''relative_error = (12 - cloud_spectrum.values[9]) / 12
''',
    "04-largest-answer": r'''with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    again = lbo.load_mesh(scan_path, clean=True)
    lam = lbo.eigenbasis(again, 16).values
largest_zeros = int(np.sum(np.abs(lam) < 1e-8 * lam[-1]))
largest_worst = np.max(np.abs(lam[1:] / exact[1:] - 1))
''',
    "04-neighbors-answer": r'''neighbors_effect = "closer"  # smaller, more local neighbourhoods
''',
    "04-gap-answer": r'''pieces = {1.5: 1, 1.75: 2}
''',
    "04-recap-answer": r'''q1, q2, q3 = 1, "cotan", "separate"
exercises.check_recap_your_data = lambda *args, **kwargs: exercises.Feedback("04-recap", "correct", "Right, all 3.")
''',
    # --- notebook 05 ---
    "05-projection-answer": r'''def my_project(spectrum, f, n):
    """P_n f: the A-orthogonal projection of f onto phi_0 .. phi_(n-1)."""
    Phi_n = spectrum.vectors[:, :n]
    return Phi_n @ (Phi_n.T @ f)  # orthogonal projection onto the columns
''',
    "05-bound-answer": r'''y = dog.vertices[:, 1]
bound_y = (y @ (spectra["dog"].stiffness @ y)) / spectra["dog"].values[19]  # the 20th eigenvalue
''',
    "05-extra-answer": r'''extra_verdict = "beats"  # one more function than Phi_21's first 20, and a smooth one
''',
    "05-recap-answer": r'''q1, q2, q3 = 11, "tight", "yes"
from lbo_notebooks.exercises import grading
grading.grade = lambda exercise, **answers: 1.0
''',
    # --- notebook 06 ---
    "06-shifted-answer": r'''shifted_verdict = "above"  # ten eigenfunctions, just not the best ten
''',
    "06-schur-answer": r'''import scipy.linalg
from scipy.sparse.csgraph import connected_components


def my_worst_case(W, A, V):
    """C(V) = sup_f ||f - P_V f||_A^2 / f^T W f for the span of V's columns.

    np.inf when the kernel of W (the constant on each piece of the mesh) is not in that span.
    """
    Wd, Ad = W.toarray(), A.toarray()
    L = np.linalg.cholesky(V.T @ Ad @ V)
    Q = np.linalg.solve(L, V.T).T
    Z = scipy.linalg.null_space((Ad @ Q).T)
    mu = scipy.linalg.eigh(Z.T @ Wd @ Z, Z.T @ Ad @ Z, eigvals_only=True)  # W itself, no Schur complement
    if mu[0] < 1e-10 * mu[-1]:
        return np.inf
    return float(1 / mu[0])
''',
    "06-stationary-answer": r'''stationary_verdict = "double"
''',
    "06-consistent-answer": r'''sc = lbo.eigenbasis(dog, 51, mass_kind="consistent")
consistent_ratio = worst_case_ratio(sc.vectors[:, :50], W, A) * sc.values[50]
''',
    "06-worst-answer": r'''P = competitors["polynomials"][:, :20]
c, worst = worst_case_ratio(P, W, A, return_vector=True)
r = worst - P @ (P.T @ worst)
worst_ratio = (r @ A @ r) / dirichlet_energy(W, worst)
''',
    "06-ties-recap-answer": r'''q1, q2, q3 = "yes", "upper", 1
''',
    # --- notebook 07 ---
    "07-range-answer": r'''plane_range = (lam[0], lam[2])  # from the smallest to the largest eigenvalue
''',
    "07-plane-answer": r'''plane_value = (lam[0] + 4 * lam[1]) / 5  # R(v0 + 2 v1)
''',
    "07-family-answer": r'''lowest_family = "smooth"
''',
    "07-dual-answer": r'''dual_value = lam[0]
''',
    "07-interlacing-answer": r'''interlacing_bound = "lam_1"  # two constraints push the minimum up
''',
    "07-consistent-answer": r'''sc = lbo.eigenbasis(blob, 12, mass_kind="consistent")
consistent_minmax = solver.minimum(optimal_subspace(sc, 10)) / sc.values[10]
''',
    "07-recap-answer": r'''q1, q2 = "lam_n+1", "yes"
q3 = np.arctan(np.sqrt((4 - 2) / (2 - 1)))
''',
    # --- notebook 08 ---
    "08-angle-defects-answer": r'''def my_angle_defects(mesh):
    """Angle defect at each vertex, shape (n,): 2 pi - sum of angles (pi - sum on the boundary)."""
    P = mesh.vertices[mesh.faces]  # (m, 3, 3): the corners of every triangle
    total = np.zeros(mesh.n_vertices)
    for c in range(3):
        a, b = P[:, (c + 1) % 3] - P[:, c], P[:, (c + 2) % 3] - P[:, c]
        theta = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.sum(a * b, axis=1))
        np.add.at(total, mesh.faces[:, c], theta)
    return 2 * np.pi - total  # 2 pi at every vertex, the boundary ones too
''',
    "08-curvature-answer": r'''curvature_factor = 9  # three times bigger in both directions
''',
    "08-gauss-bonnet-answer": r'''torus_total = 0.0
disk_total = 0.0  # the disk is flat: K = 0 everywhere
''',
    "08-scaling-answer": r'''metric_factors = {alpha: 3.0 ** (2 * (1 - alpha)) for alpha in (0.0, 0.4, 1.0)}
''',
    "08-best-answer": r'''best_alpha_curved = 0.4  # the paper's compromise
''',
    "08-floor-answer": r'''rho1 = operators.metric_curvature(horse, floor=1.0)
floor_fraction = 100 * np.mean(rho1 <= 4 * np.pi / horse.area * (1 + 1e-12))
''',
    "08-sphere-answer": r'''sphere_verdict = "scaled"
''',
    "08-consistent-answer": r'''consistent_invariant = "no"  # the consistent mass is another discretisation
''',
    "08-recap-answer": r'''q1, q2, q3 = 0.5, "both", "scale-invariant"
_original_init = exercises.Feedback.__init__


def _always_correct(self, exercise, status, message):
    _original_init(self, exercise, "correct", message)


exercises.Feedback.__init__ = _always_correct
''',
    # --- notebook 09 ---
    "09-classical-mds-answer": r'''def my_classical_mds(D, dim):
    """Classical MDS: the n x dim embedding U Gamma^(1/2) of B = -1/2 J D^2 J."""
    B = -0.5 * np.asarray(D, dtype=float) ** 2  # forgot to double-centre with J
    vals, vecs = np.linalg.eigh(B)
    vals, vecs = vals[::-1][:dim], vecs[:, ::-1][:, :dim]
    return vecs * np.sqrt(np.maximum(vals, 0))
''',
    "09-memory-answer": r'''classical_gb = 2 * 50_000**2 * 8 / 2**30  # bytes to GB
''',
    "09-scaling-answer": r'''def my_scaling(phi, alpha, dim):
    """The n x dim embedding from the k x k eigenproblem of -1/2 R alpha R^T, with J phi = Q R."""
    Q, R = np.linalg.qr(phi)
    G, U = np.linalg.eigh(-0.5 * (R @ alpha @ R.T))
    G, U = G[::-1][:dim], U[:, ::-1][:, :dim]
    return Q @ (U * np.sqrt(G))
''',
    "09-landmarks-answer": r'''landmark_verdict = "more"  # twice the samples
''',
    "09-fmm-answer": r'''fmm_verdict = "same"
''',
    "09-recap-answer": r'''q1, q2, q3 = 200, "nothing", "both"  # a k x k problem
''',
    # --- notebook 10 ---
    "10-mu-answer": r'''mu_verdict = "more than tenfold"  # 500 times the weight
''',
    "10-equal-size-answer": r'''n_c = np.sqrt(dog.n_vertices * (200 + 300))  # n_c^2 = n (k + q)
''',
    "10-two-d-answer": r'''X2 = spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling)
e2 = gram_error(X2, X_classical)
''',
    "10-cost-recap-answer": r'''q1, q2, q3 = "yes", 1, "classical"
''',
    # --- notebook 11 ---
    "11-rpca-basis-answer": r'''import scipy.linalg


def my_rpca_basis(X, W, A, mu, m):
    """The m top generalized eigenvectors of (A X X^T A - mu W) p = sigma A p, shape (n, m):
    P^T A P = I, columns by decreasing sigma."""
    AX = A @ X
    L = AX @ AX.T - mu * W.toarray()
    sigma, P = scipy.linalg.eigh(L)  # a standard problem: P^T P = I, the mass A left out
    return P[:, ::-1][:, :m]
''',
    "11-energy-answer": r'''energies = np.sum(pca.basis * (W @ pca.basis), axis=1)
''',
    "11-limits-answer": r'''limit_at_0 = "pca (6)"  # beta -> 0 is plain PCA
limit_at_1 = "eigenbasis"
best_beta = "intermediate"
''',
    "11-validation-answer": r'''i = unseen.index("tail_raised")
chosen_beta = min(betas, key=lambda b: errors[b][i])
other = [j for j in range(len(unseen)) if j != i]
beats_by_four = bool(np.all(errors[chosen_beta][other] > err_lbo[other] / 4))
''',
    "11-scale-answer": r'''mu_factor = 16  # s_B grows by 2^2 * 2^2
''',
    "11-objective-answer": r'''def my_objective(P, X, W, A, mu):
    """sum_i ||P P^T A x_i - x_i||_A^2 + mu sum_j p_j^T W p_j."""
    R = P @ (P.T @ X) - X  # residual of the projection onto the columns of P
    return np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P))
''',
    "11-recap-answer": r'''q1, q2, q3 = "c", "b", "a"
''',
    # --- notebook 12 ---
    "12-hks-answer": r'''def my_hks(spectrum, times):
    """h_t(x) = sum_i exp(-lam_i t) phi_i(x)^2, shape (n_vertices, len(times))."""
    return np.exp(-np.outer(times, spectrum.values)) @ (spectrum.vectors**2).T
''',
    "12-fmap-answer": r'''def my_functional_map(p2p, source, target, k):
    """C = Phi_2^T A_2 Pi Phi_1 (k x k): source coefficients -> target coefficients."""
    return target.vectors[:, :k].T @ source.vectors[p2p, :k]
''',
    "12-zoomout-step-answer": r'''def my_zoomout_step(C, source, target):
    """One ZoomOut iteration: (C_next of size (k+1, k+1), p2p read off the k x k map C)."""
    k = C.shape[0]
    images = source.vectors[:, :k] @ C  # C where C^T belongs
    here = target.vectors[:, :k]
    d2 = (here**2).sum(1)[:, None] - 2 * here @ images.T + (images**2).sum(1)[None, :]
    p2p = np.argmin(d2, axis=1)
    C_next = target.vectors[:, : k + 1].T @ (target.mass @ source.vectors[p2p, : k + 1])
    return C_next, p2p
''',
    "12-alpha-answer": r'''best_alpha = 0  # the regular metric
''',
    "12-bound-answer": r'''f_z = source.vertices[:, 2] - source.vertices[:, 2].mean()  # the centred z coordinate
bound_z = (f_z @ (ref.stiffness @ f_z)) / ref.values[30] / (f_z @ f_z)
''',
    "12-mirror-answer": r'''with_orientation = "i -> i"
without_orientation = "same position"
''',
    "12-zoomout-answer": r'''without_zoomout = "same"  # the 30 x 30 map is already right
''',
    "12-recap-answer": r'''q1, q2, q3 = "a", "c", "b"
''',
}

# LIBRARY: build-it-yourself exercises answered by calling the library instead.
LIBRARY: dict[str, str] = {
    # --- notebook 03 ---
    "03-stiffness-answer": r'''import scipy.sparse as sp

my_stiffness = lbo.stiffness_matrix
''',
    "03-mass-answer": r'''def my_mass(mesh):
    """Lumped mass matrix A (n x n, diagonal) of a triangle mesh."""
    return lbo.mass_matrix(mesh, "barycentric")
''',
    "03-eigensolve-answer": r'''import scipy.sparse.linalg as sla


def my_eigenbasis(W, A, k):
    """The k smallest eigenpairs of W phi = lam A phi: values (k,) ascending, vectors (n, k).

    The vectors are A-orthonormal: vectors.T @ A @ vectors is the identity.
    """
    spectrum = lbo.eigenbasis((W, A), k)
    return spectrum.values, spectrum.vectors
''',
    # --- notebook 05 ---
    "05-projection-answer": r'''def my_project(spectrum, f, n):
    """P_n f: the A-orthogonal projection of f onto phi_0 .. phi_(n-1)."""
    return spectrum.reconstruct(f, n)
''',
    # --- notebook 06 ---
    "06-schur-answer": r'''import scipy.linalg
from scipy.sparse.csgraph import connected_components


def my_worst_case(W, A, V):
    """C(V) = sup_f ||f - P_V f||_A^2 / f^T W f for the span of V's columns.

    np.inf when the kernel of W (the constant on each piece of the mesh) is not in that span.
    """
    return float(lbo.worst_case_ratio(V, W, A))
''',
    # --- notebook 08 ---
    "08-angle-defects-answer": r'''from lbo_notebooks.operators import angle_defects as library_defects


def my_angle_defects(mesh):
    """Angle defect at each vertex, shape (n,): 2 pi - sum of angles (pi - sum on the boundary)."""
    return np.asarray(library_defects(mesh), dtype=float)
''',
    # --- notebook 09 ---
    "09-classical-mds-answer": r'''from lbo_notebooks.analyses import classical_mds as mds_of_the_library


def my_classical_mds(D, dim):
    """Classical MDS: the n x dim embedding U Gamma^(1/2) of B = -1/2 J D^2 J."""
    return mds_of_the_library(np.asarray(D, dtype=float), dim)
''',
    "09-scaling-answer": r'''from lbo_notebooks.analyses._classical_scaling import scaling_in_span


def my_scaling(phi, alpha, dim):
    """The n x dim embedding from the k x k eigenproblem of -1/2 R alpha R^T, with J phi = Q R."""
    centred = phi - phi.mean(axis=0)
    y, _ = scaling_in_span(centred.T @ centred, -0.5 * alpha, dim)
    return centred @ y
''',
    # --- notebook 11 ---
    "11-rpca-basis-answer": r'''import scipy.linalg
from lbo_notebooks.analyses import RegularizedPCA


def my_rpca_basis(X, W, A, mu, m):
    """The m top generalized eigenvectors of (A X X^T A - mu W) p = sigma A p, shape (n, m):
    P^T A P = I, columns by decreasing sigma."""
    return RegularizedPCA(X, W, A).solve(m, mu=mu).basis
''',
    "11-objective-answer": r'''def my_objective(P, X, W, A, mu):
    """sum_i ||P P^T A x_i - x_i||_A^2 + mu sum_j p_j^T W p_j."""
    residual = reconstruct(P, A, X) - X  # the library's A-orthogonal reconstruction
    return float(np.sum(residual * (A @ residual)) + mu * np.trace(P.T @ (W @ P)))
''',
    # --- notebook 12 ---
    "12-hks-answer": r'''my_hks = lambda spectrum, times: lbo.hks(spectrum, times)
''',
    "12-fmap-answer": r'''def my_functional_map(p2p, source, target, k):
    """C = Phi_2^T A_2 Pi Phi_1 (k x k): source coefficients -> target coefficients."""
    return lbo.map_from_points(p2p, source, target, k_source=k, k_target=k)
''',
    "12-zoomout-step-answer": r'''def my_zoomout_step(C, source, target):
    """One ZoomOut iteration: (C_next of size (k+1, k+1), p2p read off the k x k map C)."""
    k = C.shape[0]
    C_next, _ = lbo.zoomout(C, source, target, k_final=k + 1)  # one iteration of the library's
    return C_next, lbo.points_from_map(C, source, target)
''',
}
