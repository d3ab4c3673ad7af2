"""Packing of the physical parameters into the float vector the compiled kernels take.

Layout (indices are module constants): ``q, fr_inv, sigma, mu, alpha_v, alpha_k, epsilon,
law, normal`` with ``epsilon`` the Coulomb regularisation scale, ``law`` the friction-law code
and ``normal`` the normal-force code of :mod:`stability.nonlinear.friction`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterTypeError

__all__ = ["ALPHA_K", "ALPHA_V", "EPSILON", "FR_INV", "LAW", "MU", "NORMAL", "SIGMA", "Q", "pack"]

Q, FR_INV, SIGMA, MU, ALPHA_V, ALPHA_K, EPSILON, LAW, NORMAL = range(9)
#: the names of the vector's entries in their order, with their defaults (None: required)
_LAYOUT = dict(q=None, fr_inv=None, sigma=None, mu=None, alpha_v=0.0, alpha_k=0.0, epsilon=1e-4, law=0, normal=0)


def pack(**values: float) -> np.ndarray:
    """Return the parameter vector of the kernels (see module docstring) from the entries by name
    (``q, fr_inv, sigma, mu`` required, the others defaulting to 0, ``epsilon`` to 1e-4)."""
    wrong = ({n for n, d in _LAYOUT.items() if d is None} - set(values)) | (set(values) - set(_LAYOUT))
    if wrong:
        raise ParameterTypeError(f"pack: missing or unknown entries {sorted(wrong)} (layout: {', '.join(_LAYOUT)})")
    return np.array([values.get(n, d) for n, d in _LAYOUT.items()], dtype=np.float64)
