"""The fast path of ``check_domain`` for one point of plain numbers against the general path.

Reference: the general (numpy) path of :func:`stability.parameters.check_domain`, a different
execution of the same :data:`DOMAIN` table, and the exact rational test of the sigma bound
(``fractions.Fraction``), which is independent of both. The two paths must agree exactly (same
accept/refuse decision, same doubles returned, the same message on refusal: the fast path never
refuses, it hands over), so there is no tolerance.
"""

from fractions import Fraction

import numpy as np
import pytest

from stability import parameters as P
from stability.errors import DomainError


def _general(**kw):
    """The general path: the same values as 0-d arrays (the fast path reads plain numbers only)."""
    return P.check_domain(scalar=True, **{k: np.asarray(v, dtype=float) for k, v in kw.items()})


def _points():
    rng = np.random.default_rng(20261123)
    mu = 2.28
    for _ in range(400):
        q = float(rng.uniform(-0.7, 0.7))
        sigma = float(rng.uniform(-0.2, 2.5))
        yield dict(q=q, sigma=sigma, fr_inv=float(rng.uniform(-0.1, 2)), alpha_v=float(rng.uniform(0, 5)), mu=mu)
    for q in (0.1, -0.3, 0.5, 1e-8):
        top = float(P.sigma_max(q, mu))
        for sigma in (top, np.nextafter(top, 3.0), np.nextafter(top, 0.0)):
            yield dict(q=q, sigma=float(sigma), fr_inv=0.3, alpha_v=0.5, mu=mu)
    yield dict(q=0, sigma=1, fr_inv=0, alpha_v=0)  # Python ints
    yield dict(q=10**400, sigma=1.0)  # overflowing int: general path
    yield dict(q=float("nan"), sigma=1.0)
    yield dict(q=0.1, sigma=1.0, fr_inv=1e31)  # outside the computable range


@pytest.mark.parametrize("kw", list(_points()))
def test_fast_path_agrees_with_the_general_path(kw):
    try:
        p_ref, inside_ref = _general(**kw)
        ref = None
    except (DomainError, TypeError, OverflowError, ValueError) as e:
        ref = (type(e), str(e))
    try:
        p, inside = P.check_domain(scalar=True, **kw)
        got = None
    except (DomainError, TypeError, OverflowError, ValueError) as e:
        got = (type(e), str(e))
    if isinstance(kw.get("q"), int) and abs(kw["q"]) > 2**53:
        assert got is not None and "q" in got[1]  # refused by name, whatever the path
        return
    assert got == ref
    if ref is None:
        assert bool(inside) and bool(inside_ref)
        assert {k: float(v) for k, v in p.items()} == {k: float(v) for k, v in p_ref.items()}


@pytest.mark.parametrize("q", [0.1, -0.3, 0.5, 1e-8])
def test_sigma_bound_exact_on_the_fast_path(q):
    """sigma <= 2 (1 - mu q^2) decided in exact rationals; the fast path accepts the largest
    double that satisfies it and refuses the next one up."""
    mu = 2.28
    exact = 2 * (1 - Fraction(mu) * Fraction(q) ** 2)
    top = float(P.sigma_max(q, mu))
    assert Fraction(top) <= exact < Fraction(float(np.nextafter(top, 3.0)))
    assert P._plain_point_inside(dict(q=q, sigma=top, mu=mu)) is not None
    assert P._plain_point_inside(dict(q=q, sigma=float(np.nextafter(top, 3.0)), mu=mu)) is None
    with pytest.raises(DomainError, match="sigma"):
        P.check_domain(scalar=True, q=q, sigma=float(np.nextafter(top, 3.0)), mu=mu)


@pytest.mark.parametrize(
    "value",
    [
        (0.0, 0.0, 5.0),
        [0.01, 0, 0.99995],
        (1, 2, 3),
        (1e30, -1e30, 0.0),
        (1e31, 0.0, 0.0),
        (0.0, float("nan"), 1.0),
        (10**400, 0, 0),
        (1.0, 2.0),
        (1.0, 2.0, 3.0, 4.0),
        [np.float64(0.1), 0.0, np.float64(1.0)],
        (np.float64(1e31), 0.0, 0.0),
        np.array([0.01, 0.0, 0.99995]),
        np.array([1e30, -1e30, 0.0]),
        np.array([0.0, np.inf, 1.0]),
        np.array([0.0, np.nan, 1.0]),
        np.array([1.0, 2.0]),
        np.zeros(4),
        np.zeros((1, 3)),
        np.array([1, 2, 3]),
        np.array([1.0, 2.0, 3.0], np.float32),
    ],
)
def test_state_vector_fast_path_agrees_with_the_general_path(value):
    """simulate's / final_state's state vectors given as a tuple or list of plain numbers (float,
    int, numpy.float64) or as a 1-D float64 array take a fast path; the reference is the same
    numbers in a tuple subclass, which the fast path does not take (the general path's checks and
    messages): the same vector, or the same refusal; and a returned array is never the caller's."""
    from stability.nonlinear.runs import _vector

    def outcome(v):
        try:
            return "ok", _vector("omega", v, (3,)).tolist()
        except (ValueError, TypeError) as e:
            return type(e).__name__, str(e).split(" = ")[0]

    class General(tuple):
        __slots__ = ()

    assert outcome(value) == outcome(General(value))
    if isinstance(value, np.ndarray) and outcome(value)[0] == "ok":
        assert not np.shares_memory(_vector("omega", value, (3,)), value)
