"""Datasets plotted with plain xarray read well (issue 15 item 7): short long_names and units
that xarray prints as axis labels ("long_name [units]"), and the leading growth rate stored in
atlases without the structural s = 0 mode. The labels are inspected, not pixels."""

from __future__ import annotations

import matplotlib as mpl

mpl.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from conftest import mp_sliding_eigenvalues

import stability

#: xarray labels an axis "long_name [units]" and wraps the label beyond 30 characters
#: (xarray.plot.utils.label_from_attrs)
LABEL_WIDTH = 30


@pytest.fixture(scope="module")
def atlas_fr0():
    return stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 17), fr_inv=0.0, sigma=1.0, alpha_v=0.5)


@pytest.fixture(scope="module")
def run():
    return stability.simulate(
        "sliding", t_end=5.0, omega=[0, 0, 1], k=[1e-3, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5
    )


def _too_long(ds):
    """Variables whose axis label would wrap."""
    out = {}
    for k, v in ds.variables.items():
        label = v.attrs.get("long_name", k) + (f" [{v.attrs['units']}]" if "units" in v.attrs else "")
        if len(label) > LABEL_WIDTH:
            out[k] = label
    return out


@pytest.mark.parametrize("which", ["atlas", "run"])
def test_long_names_are_short(which, atlas_fr0, run):
    ds = atlas_fr0 if which == "atlas" else run
    assert not _too_long(ds)


def test_plain_xarray_labels_of_an_atlas(atlas_fr0):
    fig, ax = plt.subplots()
    atlas_fr0.growth_rate.isel(mode=0).plot(ax=ax)
    assert ax.get_xlabel() == "centre-of-mass offset q [R]"
    assert ax.get_ylabel() == "growth rate Re s [Omega]"
    plt.close(fig)
    grid = stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 9), fr_inv=[0.0, 0.3], sigma=1.0, alpha_v=0.5)
    fig, ax = plt.subplots()
    grid.max_growth_rate.plot(ax=ax, x="q")
    assert ax.get_ylabel() == "inverse Froude number [1]"
    assert fig.axes[-1].get_ylabel() == "max growth rate [Omega]"  # the colour bar
    plt.close(fig)


def test_plain_xarray_labels_of_a_run(run):
    fig, ax = plt.subplots()
    run.polar_angle.plot(ax=ax)
    assert ax.get_xlabel() == "time [1/Omega]" and ax.get_ylabel() == "polar angle of k [degree]"
    plt.close(fig)
    fig, ax = plt.subplots()
    run.energy.plot(ax=ax)
    assert ax.get_ylabel() == "energy [A0 Omega^2]"
    plt.close(fig)


def test_leading_growth_rate_leaves_out_the_structural_zero_mode(atlas_fr0):
    """At Fr^-1 = 0 the sliding top has s = 0 exactly (c0 = -mu alpha_v q fr_inv = 0), so
    max_growth_rate is 0 on the whole stable side; leading_growth_rate is the largest real part
    of the other two modes. Reference: eq. (11) in mpmath (conftest.mp_sliding_eigenvalues),
    leaving out its root of modulus < 1e-30; 1e-12 absolute covers the double-precision roots."""
    ds = atlas_fr0
    lead = ds.leading_growth_rate
    assert lead.dims == ds.max_growth_rate.dims and lead.attrs["units"] == "Omega"
    assert (ds.max_growth_rate == 0).sum() > 3  # the flat part the issue complains about
    for j, q in enumerate(ds.q.values):
        ev = [complex(z) for z in mp_sliding_eigenvalues(q, 0.0, 1.0, 0.5, 2.28)]
        ref = max(z.real for z in ev if abs(z) > 1e-30)
        assert abs(float(lead[j]) - ref) < 1e-12, (q, float(lead[j]), ref)
    assert (lead < 0).sum() > 3  # not flat where the other modes decay


def test_leading_growth_rate_survives_files_and_chunks(atlas_fr0, tmp_path):
    """The stored variable passes open_atlas, and the chunked writer (which fills it from the
    chunks after deciding on the whole grid) writes the same numbers as the in-memory atlas."""
    grid = dict(q=np.linspace(-0.4, 0.4, 17), fr_inv=[0.0], sigma=[0.8, 1.0], alpha_v=0.5)
    ref = stability.atlas("sliding", **grid)
    lazy = stability.atlas("sliding", chunks=5, **grid)
    out = stability.grids.chunked.write_atlas(lazy, tmp_path / "c.nc")
    back = stability.open_atlas(out)
    np.testing.assert_array_equal(back.leading_growth_rate.values, ref.leading_growth_rate.values)
    np.testing.assert_array_equal(lazy.leading_growth_rate.values, ref.leading_growth_rate.values)
    assert (ref.leading_growth_rate != ref.max_growth_rate).any()


def test_validation_and_neutral_curve_long_names_are_short():
    import stability

    ds = stability.validate("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    assert not _too_long(ds)
    assert ds.duration.attrs["units"] == "1/Omega" and ds.measured_growth_rate.attrs["units"] == "Omega"
    curve = stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))
    assert not _too_long(curve)
    fig, ax = plt.subplots()
    curve.frequency.plot(ax=ax)
    assert ax.get_ylabel() == "neutral frequency [Omega]"
    plt.close(fig)


def test_steady_products_long_names_are_short():
    import stability
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    products = {
        "steady_states": stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5),
        "steady_branch": stability.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5),
        "final_state": stability.final_state(
            q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3]
        ).to_dataset(),
        "class_atlas": stability.class_atlas(q=np.linspace(-0.6, 0.6, 5), sigma=np.linspace(0.01, 2, 4)),
    }
    for name, ds in products.items():
        assert not _too_long(ds), name
    ds = products["steady_states"]
    assert ds.precession_rate.attrs["units"] == "Omega" and ds.energy.attrs["units"] == "A0 Omega^2"
