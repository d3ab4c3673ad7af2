"""Model names (issue 15 item 2): "rolling" is the rolling top from first principles, the
paper's eq. (8) as printed is "rolling_eq8"; the old name "rolling_first_principles" works for
one release with a DeprecationWarning, and a public lookup of "rolling" warns once per process
that its meaning changed, while the package's own lookups stay silent.

The numbers of the models are checked elsewhere against closed forms
(tests/test_spectra_reference.py: "rolling" against the first-principles quadratic and the
alpha_v -> infinity limit of eq. 11 in mpmath, "rolling_eq8" against eq. 8 as printed)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import stability
import stability.models as models
from stability.cli import main


@pytest.fixture
def fresh(monkeypatch):
    """As in a new process: the FutureWarning on "rolling" not given yet."""
    monkeypatch.setattr(models, "_ROLLING_WARNED", False)


def _caught(fn):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        out = fn()
    return out, [
        w
        for w in rec
        if issubclass(w.category, (FutureWarning, DeprecationWarning)) and str(w.message).startswith("model '")
    ]


def test_registry_names():
    assert set(models.MODELS) == {"fixed_pivot", "rolling", "rolling_eq8", "sliding"}
    assert models.MODELS["rolling"].equations == "(1), (2), (4), (5) linearised"
    assert "as printed" in models.MODELS["rolling_eq8"].description
    from stability.nonlinear import NONLINEAR_MODELS

    assert NONLINEAR_MODELS["rolling"].linear_model == "rolling"


def test_old_name_is_a_deprecated_alias(fresh):
    m, caught = _caught(lambda: models.get_model("rolling_first_principles"))
    assert m is models.MODELS["rolling"]
    assert len(caught) == 1 and caught[0].category is DeprecationWarning
    assert "it is now called 'rolling'" in str(caught[0].message)
    assert caught[0].filename == __file__  # attributed to the caller, not the package
    s, _ = _caught(lambda: stability.eigenvalues("rolling_first_principles", q=0.1, fr_inv=0.3, sigma=1.0))
    np.testing.assert_array_equal(s, stability.eigenvalues(models.MODELS["rolling"], q=0.1, fr_inv=0.3, sigma=1.0))


def test_rolling_warns_once_per_process(fresh):
    _, first = _caught(lambda: stability.eigenvalues("rolling", q=0.1, fr_inv=0.3, sigma=1.0))
    assert len(first) == 1 and first[0].category is FutureWarning
    assert "now the rolling top from first principles" in str(first[0].message)
    assert "'rolling_eq8'" in str(first[0].message) and first[0].filename == __file__
    _, second = _caught(lambda: stability.atlas("rolling", q=[0.1, 0.2], fr_inv=0.3, sigma=1.0))
    assert second == []
    _, other = _caught(lambda: stability.eigenvalues("rolling_eq8", q=0.1, fr_inv=0.3, sigma=1.0))
    assert other == []


@pytest.mark.filterwarnings("default:model 'rolling' is now:FutureWarning")  # Python's own default, not the suite's
def test_cli_prints_the_warning_on_one_line(fresh, capsys):
    assert main(["threshold", "sigma", "--model", "rolling", "--q", "0.1", "--fr-inv", "0.3"]) in (0, 2)
    err = capsys.readouterr().err
    assert "tippe threshold: warning: model 'rolling' is now the rolling top from first principles" in err


def test_the_package_own_lookups_are_silent(fresh, tmp_path, capsys):
    """simulate("rolling"), validate("rolling") (nonlinear names, unchanged) and `tippe figures`
    on a recipe drawing every linear model look "rolling" up without the FutureWarning."""
    _, caught = _caught(
        lambda: stability.simulate("rolling", t_end=1.0, omega=[0, 0, 1], k=[0.01, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.0)
    )
    assert caught == []
    ds, caught = _caught(lambda: stability.validate("rolling", q=0.2, fr_inv=1.5, sigma=1.0))
    assert caught == [] and ds.attrs["linear_model"] == "rolling"
    recipe = tmp_path / "m.toml"
    recipe.write_text(
        'title = "m"\nkind = "models"\nx = "q"\ny = "fr_inv"\nmask_unphysical = true\n\n'
        '[grid]\nq = "-0.3:0.3:7"\nfr_inv = "0:1:5"\nsigma = 1.0\nalpha_v = 0.5\n'
    )
    rc, caught = _caught(lambda: main(["figures", str(recipe)]))
    assert rc == 0 and caught == [] and "warning" not in capsys.readouterr().err
    assert models._ROLLING_WARNED is False


def test_an_old_rolling_atlas_says_what_it_holds(tmp_path):
    """A file written before the rename, model 'rolling' with eq. (8)-(9), is eq. (8) as printed."""
    ds = stability.atlas("rolling_eq8", q=[0.1, 0.2], fr_inv=0.3, sigma=1.0)
    ds.attrs.update(model="rolling", model_equations="(8)-(9)", source="tippe-stability 0.1.0")
    path = stability.write_dataset(ds, tmp_path / "old.nc")
    with pytest.warns(FutureWarning, match="eq. \\(8\\) as printed, which is now called 'rolling_eq8'"):
        stability.open_atlas(path)
