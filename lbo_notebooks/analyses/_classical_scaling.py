"""Classical scaling's shared steps: the checks, the top eigenpairs, and scaling in a span.

Every MDS variant of the package (:mod:`lbo_notebooks.analyses._mds`, :mod:`lbo_notebooks.analyses._fast_classical_scaling`)
ends with classical scaling: the top ``dim`` eigenpairs of ``B = -1/2 J D2 J``. Classical and
landmark MDS form ``B`` (n x n or q x q) and call :func:`top_eigenpairs`; spectral MDS and fast
classical scaling know ``B`` only as ``C middle C.T`` for a thin ``C`` and call
:func:`scaling_in_span`, which needs only small matrices (docs/maths.md, "Multidimensional
scaling", scaling in a span).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.linalg
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from .._support.validation import Constraint, Integer, Number, Relation, Satisfies
from ..spectral._solvers import start_vector, use_dense

__all__ = [
    "dim_below", "sample_count", "check_dim", "check_samples", "sampling_pair", "top_eigenpairs", "scaling_in_span",
]

#: The table entry of ``dim`` when its limit is known only from the data (then :func:`check_dim`).
DIM = Integer(1, what="a positive integer (the embedding dimension)")


def _smaller_than(limit: Any, what: str) -> tuple[Constraint, ...]:
    # Number for the strict bound, so that the message can name the limit itself; then back to int.
    return (Number(high=limit, open_high=True, message=f"dim={{value}} must be smaller than {what} ({{high}})."),
            Satisfies(lambda value: True, convert=int))


def dim_below(limit: Any, what: str) -> tuple[Constraint, ...]:
    """The table entry of ``dim``: a positive integer smaller than ``limit`` (``what`` names it in the message).

    ``limit`` is a number or a callable of the function's arguments (``lambda k, **_: k``).
    """
    return (DIM, *_smaller_than(limit, what))


def check_dim(dim: int, limit: int, what: str) -> int:
    """``dim``, already checked by :data:`DIM`, checked to be smaller than ``limit``, a size of the data."""
    for rule in _smaller_than(limit, what):
        dim = rule.check(dim, "dim", {})
    return dim


def sample_count(n_vertices: Any, *, none: bool = False) -> tuple[Constraint, ...]:
    """The table entry of a number of samples: an integer in ``2..n_vertices`` (a callable of the arguments).

    ``none=True`` lets ``None`` (a default chosen later) through.
    """
    return (
        Integer(2, none=none),
        Integer(high=n_vertices, none=none, message=(
            "{name}={value} is more than the mesh's {high} vertices; samples are distinct vertices, "
            "so use at most {high} (a few hundred are plenty).")),
    )


def check_samples(count: Any, n: int, name: str = "n_samples") -> int:
    """A number of samples checked to be an integer in ``2..n``, where the table cannot (a mesh-only argument)."""
    for rule in sample_count(n):
        count = rule.check(count, name, {})
    return int(count)


def sampling_pair(count: Callable[..., int], letter: str = "count") -> Relation:
    """The table entry of ``sampling``: ``None``, or ``(samples, distances)`` with at least ``count`` samples.

    ``count`` is a callable of the arguments (``lambda n_samples, **_: n_samples``); ``distances``
    holds one row of ``mesh.n_vertices`` values per sample, as
    ``farthest_point_sampling(mesh, count, return_distances=True)`` returns them. ``letter`` names
    the count in the message.
    """

    def parts(sampling: Any) -> tuple[Any, Any] | None:
        try:
            samples, fields = (np.asarray(a) for a in sampling)
        except (TypeError, ValueError):  # not a pair of arrays
            return None
        return samples, fields

    def holds(mesh: Any, sampling: Any, **arguments: Any) -> bool:
        if sampling is None:
            return True
        pair, n = parts(sampling), mesh.n_vertices
        if pair is None:
            return False
        samples, fields = pair
        indices = samples.dtype != bool and np.issubdtype(samples.dtype, np.integer) and (
            samples.size == 0 or (samples.min() >= 0 and samples.max() < n))
        return samples.ndim == 1 and bool(indices) and fields.shape == (samples.size, n) and (
            samples.size >= count(mesh=mesh, sampling=sampling, **arguments))

    def message(mesh: Any, sampling: Any, **arguments: Any) -> str:
        q, n = count(mesh=mesh, sampling=sampling, **arguments), mesh.n_vertices
        pair = parts(sampling)
        got = ("something that is not a pair of arrays" if pair is None else
               f"dtype {pair[0].dtype} and shape {pair[0].shape}, and shape {pair[1].shape}")
        return (f"sampling must be (samples, distances) from farthest_point_sampling(mesh, {letter} >= {q}, "
                f"return_distances=True): integer vertex indices in 0..{n - 1} of shape ({letter},), and "
                f"distances of shape ({letter}, {n}); got {got}.")

    return Relation(holds, message)


def top_eigenpairs(B: NDArray[np.float64], dim: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Largest ``dim`` eigenpairs of a symmetric matrix, descending (dense ``eigh`` or Lanczos)."""
    n = B.shape[0]
    if use_dense(n) or dim + 1 >= n // 2:
        vals, vecs = scipy.linalg.eigh(B, subset_by_index=[n - dim, n - 1])
    else:
        vals, vecs = spla.eigsh(B, k=dim, which="LA", v0=start_vector(n))
    order = np.argsort(vals)[::-1]
    return vals[order], vecs[:, order]


def scaling_in_span(gram: NDArray[np.float64], middle: NDArray[np.float64], dim: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Top ``dim`` eigenpairs of ``B = C middle C.T`` (n x n) from k x k matrices only.

    ``gram = C.T C``. Any factorisation ``C = Q R`` with Q orthonormal will do: from
    ``gram = V S V.T``, ``R = S^(1/2) V.T`` and ``Q = C V S^(-1/2)``, so ``B = Q (R middle R.T) Q.T``
    and only the small matrix is eigendecomposed. Directions that C does not span (S at round-off
    level) are dropped. Returns ``y`` (k x dim) with ``X = C y`` and the eigenvalues G, descending.
    Costs one k x k Gram product instead of a Householder QR and never forms Q.
    """
    S, V = np.linalg.eigh(0.5 * (gram + gram.T))
    keep = S > S.max() * len(S) * np.finfo(float).eps
    S, V = S[keep], V[:, keep]
    R = np.sqrt(S)[:, None] * V.T
    small = R @ middle @ R.T
    G, U = np.linalg.eigh(0.5 * (small + small.T))
    G, U = G[::-1], U[:, ::-1]
    y = V @ (U[:, :dim] * (np.sqrt(np.maximum(G[:dim], 0.0)) / np.sqrt(S)[:, None]))
    return y, G
