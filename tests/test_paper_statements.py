"""The paper's qualitative statements about Figs. 3-4, checked on atlas data.

Each test quotes the statement it holds the atlas to. Grids are those of the recipes
atlases/fig3ab.toml, fig3cd.toml, fig4.toml (coarser where it does not matter).
"""

from __future__ import annotations

import numpy as np

import stability

Q = np.linspace(-0.45, 0.45, 181)


def test_weak_spin_stabilises_below_destabilises_above_reversal_at_high_fr():
    """Sec. 3(i): "a weak spin relative to gravity (i.e., small Fr) is stabilizing if the center
    of mass is below O and destabilizing if it is above O. A reversal of this stability property
    occurs at high Fr." (sigma = 1, mu = 2.28, alpha_v = 0.5)"""
    ds = stability.atlas("sliding", q=Q, fr_inv=[0.0, 1.0], sigma=1.0, alpha_v=0.5)
    weak = ds.sel(fr_inv=1.0)  # small Fr: weak spin
    strong = ds.sel(fr_inv=0.0)  # high Fr
    below, above = Q < -0.01, Q > 0.01
    assert (weak.stability.values[below] == 0).all()  # stable below O
    assert (weak.stability.values[above] == 2).all()  # unstable above O
    assert (strong.stability.values[below & (Q > -0.43)] == 2).all()  # reversed at high Fr
    assert (strong.stability.values[above] != 2).all()


def test_sigma_above_1_14_stabilises_at_zero_gravity():
    """Sec. 3(i): "In the limit of very strong spin or very weak gravity, i.e., Fr^-1 = 0, the
    inertia ratio stabilizes the top above the value of sigma = 1.14." The closed form
    2 (mu - sqrt(mu (mu - 1))) = 1.14331 (docs/models.md) brackets it on a fine q grid."""
    q = np.linspace(-0.6, 0.6, 2401)
    ds = stability.atlas(
        "sliding", q=q, fr_inv=0.0, sigma=[1.13, 1.143, 1.1436, 1.15, 1.3], alpha_v=0.5, mask_unphysical=True
    )
    unstable_somewhere = (ds.stability == 2).any("q").values
    assert list(unstable_somewhere) == [True, True, False, False, False]


def test_growth_rises_with_alpha_v_then_falls():
    """Sec. 3(i), Fig. 4: "The solid curves rise with increasing alpha_v ... The family of curves
    has a maxima with respect to alpha_v, however, after which further increase in friction
    leads to a decrease in growth rate." (Fr^-1 = 0, sigma = 1)"""
    ds = stability.atlas("sliding", q=Q, fr_inv=0.0, sigma=1.0, alpha_v=[0.1, 0.2, 0.5, 1.0, 2.0, 5.0])
    peak = ds.max_growth_rate.max("q").values
    assert (np.diff(peak[:4]) > 0).all()  # rises up to alpha_v = 1
    assert (np.diff(peak[3:]) < 0).all()  # then falls for 2 and 5
