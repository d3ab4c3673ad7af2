"""Bad input: each domain bound, NaN, wrong types, empty ranges; the message names the parameter.

Reference: the physical domain as stated in NOTES.md and the issue (1 - mu q^2 > 0,
0 < sigma <= 2 (1 - mu q^2), mu > 0, fr_inv >= 0, alpha_v >= 0, finite).
"""

from __future__ import annotations

import numpy as np
import pytest

import stability
from stability.errors import DomainError
from stability.parameters import check_domain

GOOD = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mu=2.28)


@pytest.mark.parametrize(
    "name,value,fragment",
    [
        ("mu", 0.0, "mu > 0"),
        ("mu", -1.0, "mu > 0"),
        ("fr_inv", -0.01, "fr_inv >= 0"),
        ("alpha_v", -1e-9, "alpha_v >= 0"),
        ("q", 0.7, "1 - mu q^2 > 0"),
        ("q", -0.7, "1 - mu q^2 > 0"),
        ("sigma", 0.0, "sigma > 0"),
        ("sigma", 1.96, "sigma <= 2 (1 - mu q^2)"),
    ],
)
def test_each_bound_names_parameter_value_and_bound(name, value, fragment):
    with pytest.raises(DomainError) as exc:
        stability.eigenvalues("sliding", **{**GOOD, name: value})
    msg = str(exc.value)
    assert msg.startswith(f"{name} = {value:.6g}")
    assert fragment in msg


def test_bound_is_numeric_in_message():
    # 2 (1 - mu q^2) at q = -0.1, mu = 2.28 is 1.9544: the number a user needs
    with pytest.raises(DomainError, match=r"= 1\.9544"):
        stability.eigenvalues("sliding", **{**GOOD, "sigma": 1.96})


def test_domain_edge_is_inclusive_for_sigma():
    # the triangle inequality allows equality (a flat disc about G)
    sg = 2 * (1 - 2.28 * 0.01)
    assert np.isfinite(stability.eigenvalues("sliding", **{**GOOD, "sigma": sg})).all()


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("name", ["q", "fr_inv", "sigma", "alpha_v", "mu"])
def test_non_finite(name, value):
    with pytest.raises(DomainError, match=rf"^{name} = .* is not finite"):
        stability.eigenvalues("sliding", **{**GOOD, name: value})


@pytest.mark.parametrize("value", ["0.3", True, 1 + 2j, [1j], None, object()])
def test_wrong_types(value):
    with pytest.raises(TypeError, match="fr_inv"):
        stability.eigenvalues("sliding", **{**GOOD, "fr_inv": value})


def test_empty_range():
    with pytest.raises(DomainError, match="q is empty"):
        stability.atlas("sliding", **{**GOOD, "q": []})


def test_missing_and_foreign_parameters():
    with pytest.raises(TypeError, match="alpha_v is required for model 'sliding'"):
        stability.eigenvalues("sliding", q=-0.1, fr_inv=0.3, sigma=1.0)
    with pytest.raises(TypeError, match="model 'rolling' takes no parameter alpha_v"):
        stability.eigenvalues("rolling", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    with pytest.raises(ValueError, match="model = 'spinning' is not a known model"):
        stability.eigenvalues("spinning", q=-0.1, fr_inv=0.3, sigma=1.0)


def test_grid_refused_whole_unless_masked():
    q = np.linspace(-0.6, 0.6, 13)
    with pytest.raises(DomainError, match=r"sigma = 1 .* \(4 of 13 grid points violate it"):
        stability.atlas("sliding", q=q, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    ds = stability.atlas("sliding", q=q, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mask_unphysical=True)
    outside = 2 * (1 - 2.28 * q**2) < 1.0
    assert np.array_equal(ds.physical.values == 0, outside)
    assert np.isnan(ds.growth_rate.values[outside]).all()
    assert np.isnan(ds.frequency.values[outside]).all()
    assert (ds.stability.values[outside] == -1).all()
    assert np.isfinite(ds.growth_rate.values[~outside]).all()


def test_shapes_that_do_not_broadcast():
    with pytest.raises(DomainError, match="do not broadcast"):
        check_domain(q=np.zeros(3), sigma=np.ones(4), mu=2.28)
