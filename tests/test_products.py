"""Every dataset the package returns names its product; ``ds.tippe.plot()`` draws its figure.

References: the product values are the table of docs/datasets.md (one per function that makes a
dataset); the figure drawn through the accessor is compared with the one drawn by calling the
registered plotting function directly, artist by artist (lines' data, labels, styles; the
collections' data; titles, axis labels, legends), never by pixels. The accessor adds nothing of
its own, so the two must be identical, not close. The plotting convention (data plus an optional
``ax``/``axes``, ``(Figure, Axes)`` back) is checked on the signatures of every public plotting
function.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

import continuation
import stability
import stability.plotting
from stability.errors import InputError
from stability.nonlinear.scene import INITIAL_CONDITIONS
from stability.plotting.accessor import PLOTS, plotting_function
from stability.products import PRODUCT_ATTR
from stability.recipes import critical_spin_dataset, load_recipe

DOCS = Path(__file__).resolve().parents[1] / "docs" / "datasets.md"


def _critical_spin(tmp_path: Path) -> xr.Dataset:
    p = tmp_path / "spin.toml"
    p.write_text('title = "x"\nkind = "critical_spin"\npreset = "table1"\nx = "q"\n[grid]\nq = [-0.3, -0.1]\n')
    return critical_spin_dataset(load_recipe(p))


#: product -> a small dataset of it, made by the package's own function
MAKERS = {
    "atlas": lambda tmp: stability.atlas(
        "sliding",
        q=np.linspace(-0.4, 0.4, 9),
        fr_inv=0.0,
        sigma=np.linspace(0.2, 1.8, 5),
        alpha_v=0.5,
        mask_unphysical=True,
    ),
    "neutral_curve": lambda tmp: stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5)),
    "fold_curve": lambda tmp: stability.fold_curve(
        "sliding", "q", "sigma", "fr_inv", fold_in="sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), z_range=(0.0, 0.3)
    ),
    "nonlinear_run": lambda tmp: stability.simulate(
        "sliding", t_end=5.0, omega=[0, 0, 1], k=[1e-3, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5
    ),
    "validation": lambda tmp: stability.validate(
        "sliding", q=[-0.1, 0.1], fr_inv=0.3, sigma=1.0, alpha_v=0.5, n_efold=1.0
    ),
    "coulomb_growth": lambda tmp: stability.coulomb_growth(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_k=0.2, t_end=60.0),
    "critical_spin": _critical_spin,
    "steady_states": lambda tmp: stability.steady_states(
        q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, jellett=-0.9001185873
    ),
    "steady_branch": lambda tmp: stability.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5),
    "final_state": lambda tmp: stability.final_state(
        q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3]
    ).to_dataset(),
    "top_classes": lambda tmp: stability.class_atlas(q=np.linspace(-0.6, 0.6, 25), sigma=np.linspace(0.05, 2.0, 20)),
    "contact_loss_map": lambda tmp: stability.contact_loss_boundary(
        stability.Top.table1(), x_range=(90.0, 110.0), y_range=(38.0, 46.0), grid=(2, 2), duration=0.3, max_points=3
    ),
    "flip_time_map": lambda tmp: __import__("stability.launches.estimate", fromlist=["x"]).flip_time_map(
        stability.Top.table1(), [8.0, 12.0], [5.0], t_max=3000.0
    ),
}


def _documented() -> dict[str, str]:
    """Product -> the function named for it, from the table of docs/datasets.md."""
    rows = re.findall(r"^\| `([a-z_]+)` \| (.+?) \|", DOCS.read_text(), flags=re.MULTILINE)
    return dict(rows)


def _bytes(values) -> bytes:
    return np.asarray(values, dtype=float).tobytes()


def _artists(fig: Figure) -> list:
    """What a figure draws, as comparable data (no pixels)."""
    out = [fig._suptitle.get_text() if fig._suptitle is not None else None]
    for ax in fig.axes:
        legend = ax.get_legend()
        out.append(
            {
                "titles": [ax.get_title(loc=loc) for loc in ("left", "center", "right")],
                "labels": (ax.get_xlabel(), ax.get_ylabel()),
                "scales": (ax.get_xscale(), ax.get_yscale()),
                "lines": [
                    (
                        ln.get_label(),
                        ln.get_linestyle(),
                        ln.get_marker(),
                        ln.get_color(),
                        ln.get_linewidth(),
                        _bytes(ln.get_xdata()),
                        _bytes(ln.get_ydata()),
                    )
                    for ln in ax.get_lines()
                ],
                "collections": [
                    (
                        type(c).__name__,
                        _bytes(c.get_offsets()),
                        None if c.get_array() is None else _bytes(c.get_array()),
                        [_bytes(p.vertices) for p in c.get_paths()],
                    )
                    for c in ax.collections
                ],
                "legend": None if legend is None else [t.get_text() for t in legend.get_texts()],
            }
        )
    return out


@pytest.mark.parametrize("product", sorted(MAKERS))
def test_every_product_carries_its_attribute_and_draws_as_its_function(product, tmp_path):
    """The dataset names its product; ``ds.tippe.plot()`` draws exactly what the registered
    function draws (checked artist by artist) and returns its ``(Figure, Axes)``."""
    ds = MAKERS[product](tmp_path)
    assert ds.attrs[PRODUCT_ATTR] == product and ds.tippe.product == product
    fig, axes = ds.tippe.plot()
    direct_fig, direct_axes = plotting_function(product)(ds)
    assert isinstance(fig, Figure) and type(axes) is type(direct_axes)
    assert _artists(fig) == _artists(direct_fig)
    assert len(fig.axes[0].get_lines()) + len(fig.axes[0].collections) > 0  # it drew something


def test_atlas_figure_follows_the_grid():
    """A 1-D atlas draws the growth rate against its dimension (plot_growth_rate), a 2-D one the
    stability map (plot_stability_map); more dimensions are refused with what to do; ``ax`` and
    the function's options pass through."""
    from stability.plotting import plot_growth_rate, plot_stability_map

    line = stability.atlas("sliding", q=np.linspace(-0.3, 0.3, 7), fr_inv=0.1, sigma=1.0, alpha_v=0.5)
    fig, ax = line.tippe.plot(quantity="frequency")
    assert _artists(fig) == _artists(plot_growth_rate(line, "q", quantity="frequency")[0])
    plane = MAKERS["atlas"](None)
    host = Figure().add_subplot()
    fig, ax = plane.tippe.plot(ax=host, colorbar=False)
    assert ax is host and fig is host.figure
    assert _artists(fig) == _artists(plot_stability_map(plane, "q", "sigma", colorbar=False)[0])
    cube = stability.atlas("sliding", q=[-0.1, 0.1], fr_inv=[0.1, 0.2], sigma=[0.9, 1.0], alpha_v=0.5)
    with pytest.raises(ValueError, match=r"3 grid dimensions \(q, fr_inv, sigma\).*select the others first"):
        cube.tippe.plot()


def test_product_survives_a_file_and_the_dense_output(tmp_path):
    """The attribute is a global attribute of the netCDF file; continuation.dense copies the
    curve's attributes, and its output (no special points) is drawn as the curve."""
    run = MAKERS["nonlinear_run"](tmp_path)
    stability.write_dataset(run, tmp_path / "run.nc")
    with xr.open_dataset(tmp_path / "run.nc") as f:
        assert f.tippe.product == "nonlinear_run"
    curve = MAKERS["neutral_curve"](tmp_path)
    dense = continuation.dense(curve, 4)
    assert dense.tippe.product == "neutral_curve"
    fig, ax = dense.tippe.plot()
    (line,) = ax.get_lines()  # one branch, no markers
    assert np.array_equal(line.get_xdata(), dense.q.values)


def test_missing_or_unknown_product_is_a_clear_error():
    ds = xr.Dataset({"x": ("t", np.arange(3.0))})
    assert ds.tippe.product is None
    with pytest.raises(InputError, match="this dataset has no global attribute 'tippe_stability_product'"):
        ds.tippe.plot()
    ds.attrs[PRODUCT_ATTR] = "pie_chart"
    with pytest.raises(
        InputError,
        match=r"tippe_stability_product = 'pie_chart': no figure is registered "
        r"for this product \(products with a figure: atlas, contact_loss_map, coulomb_growth",
    ):
        ds.tippe.plot()
    # a new Dataset from a product's variables has none of its attributes: the message says so
    with pytest.raises(InputError, match="attributes were dropped"):
        xr.Dataset(dict(MAKERS["nonlinear_run"](None).data_vars)).tippe.plot()


def test_friction_cases_has_a_product_and_no_figure():
    """scene.friction_cases names its product; no figure is registered for it, which the error says."""
    from stability.nonlinear.scene import friction_cases

    ds = friction_cases(t_end=20.0)
    assert ds.tippe.product == "friction_cases"
    with pytest.raises(InputError, match="'friction_cases': no figure is registered"):
        ds.tippe.plot()


def test_registry_and_documentation_agree():
    """Every product in docs/datasets.md is made by this test (or is friction_cases), every
    registered figure is documented and importable from stability.plotting, and a new entry
    is one line (a callable works as well as the name of a function of stability.plotting)."""
    documented = _documented()
    # launch has no figure yet; its attribute is checked in tests/test_launch.py
    assert set(documented) == set(MAKERS) | {"friction_cases", "launch"}
    assert set(PLOTS) <= set(documented)
    for product in PLOTS:
        fn = plotting_function(product)
        assert fn.__module__.startswith("stability.plotting.") and getattr(stability.plotting, fn.__name__) is fn
    ds = xr.Dataset({"x": ("t", np.arange(3.0))}, attrs={PRODUCT_ATTR: "test_product"})
    PLOTS["test_product"] = lambda d, **kw: ("drawn", kw)
    try:
        assert ds.tippe.plot(ax=1) == ("drawn", {"ax": 1})
    finally:
        del PLOTS["test_product"]


def _plotting_functions():
    """Every public function of stability.plotting that draws (not the helpers that save or style)."""
    for info in pkgutil.iter_modules(stability.plotting.__path__, "stability.plotting."):
        mod = importlib.import_module(info.name)
        for name in getattr(mod, "__all__", ()):
            if (name.startswith(("plot_", "fig")) or name.endswith("_figure")) and name != "save_figure":
                yield f"{info.name}.{name}", getattr(mod, name)


@pytest.mark.parametrize("name, fn", list(_plotting_functions()))
def test_plotting_functions_follow_the_convention(name, fn):
    """Data first, an optional keyword ``ax`` or ``axes`` (default None), ``(Figure, ...)`` back
    (stability/plotting/__init__.py)."""
    sig = inspect.signature(fn)
    where = [p for p in sig.parameters.values() if p.name in ("ax", "axes")]
    assert len(where) == 1 and where[0].kind is inspect.Parameter.KEYWORD_ONLY and where[0].default is None
    assert str(sig.return_annotation).startswith("tuple[Figure, "), sig.return_annotation


def test_import_stability_does_not_import_matplotlib():
    """The accessor is registered when the facade hands out a function that returns datasets
    (``import stability`` itself imports neither xarray nor matplotlib), without importing
    matplotlib (the plotting functions are imported when a figure is drawn)."""
    code = (
        "import sys, stability; assert 'xarray' not in sys.modules; stability.open_atlas; "
        "import xarray; assert 'matplotlib' not in sys.modules; "
        "assert hasattr(xarray.Dataset({}), 'tippe')"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
