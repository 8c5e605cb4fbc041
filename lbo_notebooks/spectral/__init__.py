"""The eigenbasis of ``W phi = lam A phi`` and the A-inner-product algebra around it.

Everything public is importable from here (``__all__``); the modules with a leading underscore
are the implementation. Names load on first use.
"""

from __future__ import annotations

from .._support.lazy import front_door

# Public names by module, loaded on first use.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "_spectrum": ("Spectrum", "eigenbasis"),
    "_inner_product": (
        "a_norms", "a_orthonormalize", "fix_signs", "principal_angles", "reconstruct",
        "reconstruction_error",
    ),
    "_solvers": ("slice_eigsh", "count_below"),
}
__all__ = [name for names in _EXPORTS.values() for name in names]
__getattr__, __dir__ = front_door(__name__, _EXPORTS)
