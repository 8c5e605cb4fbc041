"""How close one embedding is to another: Gram-matrix and Procrustes errors, without n x n matrices.

MDS determines an embedding only up to a translation and an orthogonal map (a rotation or a
reflection), so two embeddings of the same vertices are compared either by what those maps leave
unchanged (:func:`gram_error`, the relative error of the centred Gram matrices) or after the best
orthogonal alignment (:func:`procrustes_error`). Both cost O(n dim^2).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._support.validation import Array, Relation, validated

__all__ = ["gram_error", "procrustes_error"]

#: Each embedding: n points of any dimension, finite.
_EMBEDDING = Array(2, message="{name} must be an (n, dim) array of embedded points; got {shape}.")
_SAME_VERTICES = Relation(
    lambda Z, X, **_: Z.shape[0] == X.shape[0],
    lambda Z, X, **_: f"Z has {Z.shape[0]} points but X has {X.shape[0]}; compare embeddings of the same vertices.",
)
_SAME_DIMENSION = Relation(
    lambda Z, X, **_: Z.shape[1] == X.shape[1],
    lambda Z, X, **_: f"Z and X must have the same dimension for Procrustes, got {Z.shape[1]} and {X.shape[1]}.",
)


# --- accuracy ---------------------------------------------------------------------------------
@validated(Z=_EMBEDDING, X=(_EMBEDDING, _SAME_VERTICES))
def gram_error(Z: ArrayLike, X: ArrayLike) -> float:
    """Relative Gram-matrix error ``||Z Z.T - X X.T||_F / ||X X.T||_F`` of centred embeddings.

    ``X`` is the reference. No alignment is needed: Gram matrices do not change under rotations
    and reflections, and both point sets are centred first (so translations do not count either).
    Computed in O(n dim^2) without forming an n x n matrix (a thin QR of ``[Z X]``, so that the
    small errors of good embeddings do not drown in round-off);
    the two embeddings may have different dimensions.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> X = rng.normal(size=(100, 3))
    >>> Q = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    >>> bool(gram_error(X @ Q + 5.0, X) < 1e-12)
    True
    """
    Zc, Xc = Z - Z.mean(axis=0), X - X.mean(axis=0)
    # ZZ.T - XX.T = Y S Y.T with Y = [Z X], S = diag(I, -I). With the thin QR Y = Q R its Frobenius
    # norm is that of the small matrix R S R.T: no cancellation between ||Z.T Z|| and ||X.T X||.
    R = np.linalg.qr(np.hstack([Zc, Xc]), mode="r")
    p = Zc.shape[1]
    Rz, Rx = R[:, :p], R[:, p:]
    ref = np.linalg.norm(Rx @ Rx.T)
    if ref <= 0:
        raise ValueError("the reference embedding X is a single point (its Gram matrix is zero).")
    return float(np.linalg.norm(Rz @ Rz.T - Rx @ Rx.T) / ref)


@validated(Z=_EMBEDDING, X=(_EMBEDDING, _SAME_VERTICES, _SAME_DIMENSION))
def procrustes_error(Z: ArrayLike, X: ArrayLike) -> float:
    """Relative error ``min_R ||Z R - X||_F / ||X||_F`` over orthogonal ``R``, after centring.

    Reflections are allowed because MDS determines an embedding only up to an orthogonal map.
    O(n dim^2): one SVD of the dim x dim matrix ``Z.T X``. Both embeddings must have the same
    dimension.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> X = rng.normal(size=(50, 3))
    >>> bool(procrustes_error(-X[:, ::-1] + 1.0, X) < 1e-12)  # a reflection and a shift
    True
    """
    Zc, Xc = Z - Z.mean(axis=0), X - X.mean(axis=0)
    ref = np.sum(Xc * Xc)
    if ref <= 0:
        raise ValueError("the reference embedding X is a single point.")
    U, _, Vt = np.linalg.svd(Zc.T @ Xc)
    return float(np.linalg.norm(Zc @ (U @ Vt) - Xc) / np.sqrt(ref))
