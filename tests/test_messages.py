"""Messages that name the parameter, its value and the allowed range (issue 13, item 13), and
the bound sigma <= 2 (1 - mu q^2) decided exactly.

References: exact rational arithmetic (fractions.Fraction: every double is a rational) for the
bound; the text of each message is the reference for the rest (it must name the parameter, the
value and the range, and the value must read differently from the bound).
"""

from __future__ import annotations

import math
import warnings
from fractions import Fraction

import numpy as np
import pytest

import stability
from stability.cli import main
from stability.errors import DomainError
from stability.parameters import check_domain, fmt_against, sigma_max

P = dict(fr_inv=0.3, alpha_v=0.5)


def test_integer_overflow_names_the_parameter():
    """q = 10**400 does not fit a double: a DomainError naming q, its size and the computable
    range (was: OverflowError from numpy), alone or in a list with floats, and a Fraction that
    overflows beside integers (its integer part named the same way)."""
    for q in (10**400, [0.1, 10**400], -(10**400), [Fraction(10**400), 1], [Fraction(-(10**401), 10), 0]):
        with pytest.raises(
            DomainError,
            match=r"^q = -?1e\+400 \(an integer of 401 digits\) is outside the "
            r"computable range: \|q\| <= 1e\+30",
        ):
            stability.spectrum("sliding", q=q, sigma=1.0, **P)


def test_scalar_where_a_scalar_is_meant_and_counts_bounded():
    with pytest.raises(TypeError, match=r"alpha_v must be a single number here, got an array of shape \(2,\)"):
        stability.critical_spin(stability.Top.table1(), alpha_v=[0.5, 1])
    with pytest.raises(DomainError, match=r"samples = 1000000000000 is outside the allowed range: 3 <= samples <= 1e6"):
        stability.threshold("sigma", q=-0.1, samples=10**12, **P)


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("inf:0:3", "--q = 'inf:0:3': 'inf' is not finite"),
        ("0,nan", "--q = '0,nan': 'nan' is not finite"),
        ("-1e308:1e308:3", r"--q = '-1e308:1e308:3': the step .* overflows"),
    ],
)
def test_parse_values_refuses_non_finite_ends_without_numpy_warnings(text, fragment, capsys, tmp_path):
    """Was: numpy's overflow/invalid warnings, then "q = nan". Exit 2, the flag named, no file."""
    out = tmp_path / "a.nc"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert main(["atlas", "--q", text, "--fr-inv", "0.3", "--sigma", "1", "--alpha-v", "0.5", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert pytest.importorskip("re").search(fragment, err) and "Warning" not in err
    assert not out.exists()


def test_one_ulp_outside_a_bound_reads_differently():
    """The value and the bound in a message differ in print (six digits where that suffices,
    the shortest round-trip form otherwise)."""
    up = math.nextafter(1.0, 2.0)
    assert fmt_against(up, 1.0) == ("1.0000000000000002", "1")
    assert fmt_against(0.5, 0.25) == ("0.5", "0.25")
    sm = float(sigma_max(0.3, 2.28))
    with pytest.raises(DomainError) as err:
        check_domain(scalar=True, q=0.3, mu=2.28, sigma=math.nextafter(sm, 3.0), **P)
    words = str(err.value).split()
    assert words[:2] == ["sigma", "="] and "sigma <= 2 (1 - mu q^2) = " in str(err.value)
    shown_value, shown_bound = words[2], words[words.index("q^2)") + 2]
    assert shown_value != shown_bound  # as many digits as it takes (here 17)
    assert float(shown_value) == math.nextafter(sm, 3.0) and float(shown_bound) == sm
    b = 1 / math.sqrt(2.28)
    q_out = math.nextafter(b, 1.0) if 1 - Fraction(2.28) * Fraction(math.nextafter(b, 1.0)) ** 2 <= 0 else None
    q_out = q_out or math.nextafter(math.nextafter(b, 1.0), 1.0)
    with pytest.raises(
        DomainError,
        match=r"^q = (\S+) is outside the physical domain: 1 - mu q\^2 > 0.*"
        r"the largest \|q\| allowed at mu = 2.28 is (\S+)\)",
    ) as err:
        check_domain(scalar=True, q=q_out, mu=2.28, sigma=0.1, **P)
    shown_q, shown_bound = str(err.value).split()[2], str(err.value).rstrip(")").split()[-1]
    assert shown_q != shown_bound and float(shown_q) == q_out


@pytest.mark.parametrize("seed", range(5))
def test_sigma_bound_is_exact(seed):
    """sigma <= 2 (1 - mu q^2) for the doubles given, in exact rational arithmetic: sigma_max is
    the largest double that satisfies it (the next double does not), the check accepts it and
    refuses the next one, and the kernel's fused test (spectrum, mask_unphysical) agrees. Also a
    bound that is exact in doubles (q = 0.5, mu = 2: sigma = 1) is accepted, one ulp more refused."""
    rng = np.random.default_rng(seed)
    cases = [(0.5, 2.0)] + [
        (float(q), float(mu))
        for q, mu in zip(rng.uniform(-0.6, 0.6, 40), rng.uniform(0.5, 2.7, 40))
        if mu * q * q < 0.999
    ]
    for q, mu in cases:
        exact = 2 * (1 - Fraction(mu) * Fraction(q) ** 2)
        sm = float(sigma_max(q, mu))
        nxt = math.nextafter(sm, math.inf)
        assert Fraction(sm) <= exact < Fraction(nxt)
        check_domain(scalar=True, q=q, mu=mu, sigma=sm, **P)
        with pytest.raises(DomainError, match="sigma <= 2"):
            check_domain(scalar=True, q=q, mu=mu, sigma=nxt, **P)
        sp = stability.spectrum("sliding", q=q, mu=mu, sigma=np.array([sm, nxt]), mask_unphysical=True, **P)
        assert list(sp.inside) == [True, False]
    assert float(sigma_max(0.5, 2.0)) == 1.0


def test_masked_arrays():
    """A masked array with masked entries is refused by name (the data under the mask is not the
    user's value; was: used silently); without masked entries it is its data."""
    m = np.ma.masked_array([0.1, 0.2], mask=[False, True])
    for f in (stability.spectrum, stability.atlas):
        with pytest.raises(DomainError, match=r"^q is a masked array with 1 masked entry \(the first at index 1\)"):
            f("sliding", q=m, sigma=1.0, **P)
    plain = stability.spectrum("sliding", q=np.array([0.1, 0.2]), sigma=1.0, **P)
    unmasked = stability.spectrum("sliding", q=np.ma.masked_array([0.1, 0.2], mask=False), sigma=1.0, **P)
    np.testing.assert_array_equal(plain.eigenvalues, unmasked.eigenvalues)


def test_plot_format_checked_before_computing_and_figure_before_netcdf(tmp_path, capsys, monkeypatch):
    """--plot x.xyz: refused before anything is computed or written (was: the netCDF file
    written, then a failure). A figure that fails to save leaves no netCDF file either."""
    out = tmp_path / "a.nc"
    argv = ["atlas", "--q", "-0.2:0.2:3", "--fr-inv", "0.3", "--sigma", "1", "--alpha-v", "0.5", "-o", str(out)]
    assert main(argv + ["--plot", str(tmp_path / "x.xyz")]) == 2
    err = capsys.readouterr().err
    assert "--plot = " in err and "the format .xyz is not known to matplotlib" in err and ".png" in err
    assert not out.exists()

    import stability.plotting as plotting

    def fail(*a, **k):
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(plotting, "save_figure", fail)
    assert main(argv + ["--plot", str(tmp_path / "x.png")]) != 0
    assert not out.exists() and not (tmp_path / "x.png").exists()
